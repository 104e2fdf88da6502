"""Compiled kernels of the batched engine (:mod:`funcnet.core.batch`).

Many short windows, each with a few signals: per window every signal is normalized and its
recurrence adjacency ``A`` built once; then every pair gets its cross-recurrence ``CR`` (both
orientations packed) and the triangle counts of both directions. The parallel loops run over
flat task lists -- (window, signal), then (window, pair) -- so that one call spreads thousands
of windows, or the pairs of one window, over the cores; nothing runs in Python per window or per
pair.

Every float is computed with the operations, and in the order, of the per-window path
(:func:`funcnet.network.functional_network`): the same keys (squared distances accumulated
coordinate by coordinate), the same exact order statistic, the same key bound (one compiled
copy for both, :func:`funcnet.core._keys.key_bound`), the same integer counts, and NumPy's
pairwise summation for the means (:func:`_pairwise_sum` reproduces ``np.add.reduce`` on a
contiguous float64 array).

Thresholds (small M: all candidate keys fit in cache). Below :data:`DIRECT_PAIRS` candidates,
every key is written to a buffer and the k-th is selected (:func:`_select`, a quickselect with
branch-free partitions). Above, 512 pseudo-random candidate keys give a bracket around the
quantile; one pass computes every key, packs the bits below the bracket and collects the few
keys inside it, among which the k-th is selected. A bracket that misses falls back to the
direct selection: the value never depends on the sample.

Length: over 600 lines because NumPy's reductions, the selection, the threshold passes and the
kernel that calls them compile together (one parallel function, serial helpers); under 900.

References
----------
Eq. 1-10 of the paper (embedding, thresholds, cross-clustering and -transitivity).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit, prange

from funcnet.core._isrn_kernels import (
    Int,
    _lowest_bit,
    _popcount,
    add_coordinate_keys,
    below_and_upto_words,
    dim3_squared_keys,
    first_candidate,
)
from funcnet.core._keys import key_bound, key_distance, next_up

Array = np.ndarray

# normalize codes
NORMALIZE_CODE = {None: 0, "minmax": 1, "zscore": 2}
# Thresholds over fewer candidate pairs are selected directly among all their keys; above, a
# sample of _SAMPLE keys brackets the order statistic first (the bracket holds it unless the
# sample is off by more than _BRACKET_SIGMAS binomial standard deviations; a miss costs a
# direct selection, never a wrong value).
DIRECT_PAIRS = 6144
#: Largest number of embedded states M for which a window, or one pair of
#: :func:`funcnet.core.measures.cross_measures`, is computed by these kernels (thresholds selected
#: among candidate distances that fit in cache); larger ones go through the per-window path,
#: whose kernels for the whole matrix are faster there. Chosen by measurement
#: (benchmarks/HISTORY.md, "Many short windows").
DIRECT_MAX_STATES = 800
_SAMPLE = 512
# From this many candidates on, the sample is _LARGE_SAMPLE keys: four times the sample, a
# bracket half as wide (a share of the keys), half the keys to select from (at M = 532,
# 0.24 ms instead of 0.33 ms per cross-recurrence); the value never depends on the sample.
_LARGE_CANDIDATES = 65536
_LARGE_SAMPLE = 2048
_BRACKET_SIGMAS = 4.0


# --------------------------------------------------------------------------------------------
# NumPy's reductions, bit for bit


@njit(cache=True)
def _block_sum(a: Array, lo: int, n: int) -> float:
    """NumPy's sum of at most 128 contiguous float64: eight interleaved accumulators."""
    if n < 8:
        res = -0.0
        for i in range(n):
            res += a[lo + i]
        return res
    r0 = a[lo]
    r1 = a[lo + 1]
    r2 = a[lo + 2]
    r3 = a[lo + 3]
    r4 = a[lo + 4]
    r5 = a[lo + 5]
    r6 = a[lo + 6]
    r7 = a[lo + 7]
    i = 8
    whole = n - n % 8
    while i < whole:
        r0 += a[lo + i]
        r1 += a[lo + i + 1]
        r2 += a[lo + i + 2]
        r3 += a[lo + i + 3]
        r4 += a[lo + i + 4]
        r5 += a[lo + i + 5]
        r6 += a[lo + i + 6]
        r7 += a[lo + i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@njit(cache=True)
def _pairwise_sum(a: Array, lo: int, n: int) -> float:
    """``np.add.reduce(a[lo:lo + n])`` for contiguous float64: NumPy's pairwise summation.

    Blocks of at most 128 elements are summed by :func:`_block_sum`; a larger range is split in
    two halves (the first a multiple of 8 long) whose sums are added. The recursion runs on an
    explicit stack: Numba's on-disk cache cannot load a recursive function.
    """
    if n <= 128:
        return _block_sum(a, lo, n)
    stack_lo = np.empty(64, dtype=np.int64)
    stack_n = np.empty(64, dtype=np.int64)
    stack_state = np.zeros(64, dtype=np.int64)  # 0 new, 1 left pending, 2 right pending
    stack_left = np.empty(64, dtype=np.float64)
    top = 0
    stack_lo[0] = lo
    stack_n[0] = n
    value = 0.0
    have_value = False
    while True:
        if have_value:
            if top < 0:
                return value
            if stack_state[top] == 1:
                stack_left[top] = value
                stack_state[top] = 2
                half = stack_n[top] // 2
                half -= half % 8
                top += 1
                stack_lo[top] = stack_lo[top - 1] + half
                stack_n[top] = stack_n[top - 1] - half
                stack_state[top] = 0
                have_value = False
            else:
                value = stack_left[top] + value
                top -= 1
            continue
        if stack_n[top] <= 128:
            value = _block_sum(a, stack_lo[top], stack_n[top])
            top -= 1
            have_value = True
        else:
            half = stack_n[top] // 2
            half -= half % 8
            stack_state[top] = 1
            top += 1
            stack_lo[top] = stack_lo[top - 1]
            stack_n[top] = half
            stack_state[top] = 0


@njit(cache=True)
def _mean(a: Array) -> float:
    """``a.mean()`` of a contiguous float64 array, as NumPy computes it."""
    return (0.0 + _pairwise_sum(a, 0, a.size)) / a.size


# --------------------------------------------------------------------------------------------
# thresholds


@njit(cache=True)
def _partition(a: Array, lo: int, hi: int, pivot: float, or_equal: bool) -> int:
    """Move the keys of a[lo:hi] below ``pivot`` (or equal to it, if ``or_equal``) to the front,
    without branches (Lomuto, swap always, advance by the comparison); return their end."""
    store = lo
    for i in range(lo, hi):
        value = a[i]
        smaller = value <= pivot if or_equal else value < pivot
        a[i] = a[store]
        a[store] = value
        store += int(smaller)
    return store


@njit(cache=True)
def _select(a: Array, n: int, k: int) -> float:
    """The ``k``-th smallest (0-based) of ``a[:n]``, reordering ``a[:n]`` (quickselect).

    Median-of-three pivots and branch-free partitions (random keys make the branches of a
    classic partition unpredictable). When ``k`` falls above the keys below the pivot, a second
    partition separates the keys equal to it, so that ties (quantized signals) end a round
    instead of costing one round each. Small ranges, or too many rounds, are sorted.
    """
    lo = 0
    hi = n
    rounds = 0
    limit = 16 + 4 * int(math.log2(n + 1))
    while hi - lo > 24:
        rounds += 1
        if rounds > limit:
            break
        mid = lo + ((hi - lo) >> 1)
        first = a[lo]
        middle = a[mid]
        last = a[hi - 1]
        if first > middle:
            first, middle = middle, first
        if middle > last:
            middle = last
            if first > middle:
                middle = first
        pivot = middle
        below = _partition(a, lo, hi, pivot, False)
        if k < below:
            hi = below
            continue
        upto = _partition(a, below, hi, pivot, True)
        if k < upto:
            return pivot
        lo = upto
    a[lo:hi].sort()
    return a[k]


# --------------------------------------------------------------------------------------------
# keys


@njit(cache=True)
def _row_keys(
    x: Array, i: int, y: Array, start: int, n: int, dim: int, delay: int, metric: int,
    keys: Array,
) -> None:
    """keys[t] = key of state i of x and state start + t of y, t < n (1-D signals, delay
    embedding read in place); accumulated coordinate by coordinate as the per-window path does.
    """
    if metric == 0 and dim == 3:
        dim3_squared_keys(x[i], x[i + delay], x[i + 2 * delay], y[start : start + n],
                          y[start + delay : start + delay + n],
                          y[start + 2 * delay : start + 2 * delay + n], n, keys)
        return
    for c in range(dim):
        column = y[start + c * delay : start + c * delay + n]
        add_coordinate_keys(x[i + c * delay], column, n, c == 0, metric, keys)


# --------------------------------------------------------------------------------------------
# one signal, one pair


@njit(cache=True)
def _pair_key(x: Array, i: Int, y: Array, j: Int, dim: int, delay: int, metric: int) -> float:
    """Key of state i of x and state j of y (the sample of the bracket)."""
    acc = 0.0
    for c in range(dim):
        diff = x[i + c * delay] - y[j + c * delay]
        if metric == 0:
            acc = diff * diff if c == 0 else acc + diff * diff
        elif metric == 1:
            acc = max(acc, abs(diff))
        else:
            acc += abs(diff)
    return acc


@njit(cache=True)
def _mix(state: Any) -> tuple[Any, Any]:
    """One step of splitmix64: (new state, pseudo-random 64-bit word)."""
    state = state + np.uint64(0x9E3779B97F4A7C15)
    z = state
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return state, z ^ (z >> np.uint64(31))


@njit(cache=True)
def _bracket(
    x: Array, y: Array, m: int, auto: bool, theiler: int, dim: int, delay: int, metric: int,
    rank: int, n_candidates: int, sample: Array,
) -> tuple[float, float, float]:
    """Keys ``(lo, hi)`` that bracket the rank-th smallest candidate key with high probability,
    from a pseudo-random sample of candidate pairs (deterministic: seeded by m and rank), and
    the share of the sample inside."""
    size = sample.size
    state = np.uint64(m * 1000003 + rank)
    got = 0
    tries = 0
    while got < size and tries < 64 * size:
        tries += 1
        state, h = _mix(state)
        i = np.int64(h % np.uint64(m))
        j = np.int64((h >> np.uint64(32)) % np.uint64(m))
        if auto and abs(i - j) <= theiler:
            continue
        sample[got] = _pair_key(x, i, y, j, dim, delay, metric)
        got += 1
    if got < size:
        return -np.inf, np.inf, 1.0
    quantile = rank / n_candidates
    spread = _BRACKET_SIGMAS * math.sqrt(size * quantile * (1.0 - quantile)) + 2.0
    lo_rank = math.floor(quantile * size - spread)
    hi_rank = math.ceil(quantile * size + spread)
    lo = -np.inf if lo_rank < 0 else _select(sample, size, lo_rank)
    hi = np.inf if hi_rank >= size else _select(sample, size, hi_rank)
    return lo, hi, (min(hi_rank, size) - max(lo_rank, 0) + 1) / size


@njit(cache=True)
def _scan(
    x: Array, y: Array, m: int, auto: bool, theiler: int, dim: int, delay: int, metric: int,
    lo: float, hi: float, rowbuf: Array, rows: Array, band_keys: Array, band_index: Array,
) -> tuple[int, int]:
    """One pass over the candidate pairs (j > i + theiler for an auto-recurrence, all pairs
    otherwise): rows[i] = bits of key < lo; the pairs lo <= key <= hi (key and flat index
    (i << 32) | j) appended to the band buffers while they have room.

    Returns ``(number of keys < lo, number of band pairs)`` (more than the buffers hold if they
    overflowed).
    """
    n_words = (m + 63) // 64
    rowbuf[m:] = np.inf
    below = 0
    position = 0
    for i in range(m):
        start = first_candidate(i, auto, theiler)
        if start >= m:
            continue
        first_word = start // 64
        rowbuf[first_word * 64 : start] = np.inf
        _row_keys(x, i, y, start, m - start, dim, delay, metric, rowbuf[start:])
        base = i << 32
        for w in range(first_word, n_words):
            below_word, upto_word = below_and_upto_words(rowbuf[w * 64 : w * 64 + 64], lo, hi)
            rows[i, w] = below_word
            below += int(_popcount(below_word))
            band = upto_word & ~below_word
            while band:
                j = w * 64 + np.int64(_lowest_bit(band))
                band &= band - np.uint64(1)
                if position < band_keys.size:
                    band_keys[position] = rowbuf[j]
                    band_index[position] = base + j
                position += 1
    return below, position


@njit(cache=True)
def _threshold(
    x: Array, y: Array, m: int, auto: bool, theiler: int, dim: int, delay: int, metric: int,
    rank: int, n_candidates: int, strict: bool, direct: bool, rowbuf: Array, rows: Array,
) -> tuple[float, int]:
    """Exact threshold at the rank-th smallest candidate key and the packed rows of key <= bound
    (for an auto-recurrence only the pairs j > i + theiler: the caller mirrors them).

    Unless ``direct``, a sampled bracket is tried first: one pass packs the pairs below it and
    collects the few inside, whose selection gives the exact value. If the bracket misses (or
    its buffer overflows, or ``direct``), every candidate key is collected and selected
    directly. Returns ``(eps, number of candidate pairs set)``.
    """
    if not direct:
        sample = np.empty(_LARGE_SAMPLE if n_candidates >= _LARGE_CANDIDATES else _SAMPLE,
                          dtype=np.float64)
        lo, hi, share = _bracket(
            x, y, m, auto, theiler, dim, delay, metric, rank, n_candidates, sample
        )
        capacity = min(n_candidates, int(2.0 * share * n_candidates) + 2 * m + 64)
        band_keys = np.empty(capacity, dtype=np.float64)
        band_index = np.empty(capacity, dtype=np.int64)
        below, inside = _scan(
            x,
            y,
            m,
            auto,
            theiler,
            dim,
            delay,
            metric,
            lo,
            hi,
            rowbuf,
            rows,
            band_keys,
            band_index,
        )
        if inside <= capacity and below < rank <= below + inside:
            work = band_keys[:inside].copy()
            eps = key_distance(_select(work, inside, rank - below - 1), metric)
            bound = key_bound(eps, strict, metric)
            if lo <= bound <= hi:
                count = below
                for t in range(inside):  # without branches: half of them are taken
                    within = band_keys[t] <= bound
                    i = band_index[t] >> 32
                    j = band_index[t] & 0xFFFFFFFF
                    rows[i, j >> 6] |= np.uint64(within) << np.uint64(j & 63)
                    count += int(within)
                return eps, count
    cand = np.empty(n_candidates, dtype=np.float64)
    n = 0
    for i in range(m):
        start = first_candidate(i, auto, theiler)
        if start < m:
            _row_keys(x, i, y, start, m - start, dim, delay, metric, cand[n:])
            n += m - start
    eps = key_distance(_select(cand, n, rank - 1), metric)
    bound = key_bound(eps, strict, metric)
    # Pack key <= bound as key < the next key up; an empty band.
    lo = -np.inf if bound == -np.inf else next_up(bound)
    no_keys = np.empty(0, dtype=np.float64)
    no_index = np.empty(0, dtype=np.int64)
    count, _ = _scan(
        x, y, m, auto, theiler, dim, delay, metric, lo, -np.inf, rowbuf, rows, no_keys, no_index
    )
    return eps, count


@njit(cache=True)
def _transpose_into(rows: Array, out: Array, m: int, upper_only: bool) -> None:
    """out[j] |= bit i for every bit j of rows[i] (j > i only if ``upper_only``)."""
    for i in range(m):
        word_i = i >> 6
        bit_i = np.uint64(1) << np.uint64(i & 63)
        for w in range(rows.shape[1]):
            word = rows[i, w]
            while word:
                j = w * 64 + np.int64(_lowest_bit(word))
                word &= word - np.uint64(1)
                if not upper_only or j > i:
                    out[j, word_i] |= bit_i


@njit(cache=True)
def _recurrence(
    x: Array, y: Array, m: int, auto: bool, theiler: int, dim: int, delay: int, metric: int,
    rank: int, n_candidates: int, strict: bool, direct: bool, rows: Array, rows_t: Array,
) -> tuple[float, int]:
    """Threshold and packed rows of one block (zeroed on entry) and its transpose into
    ``rows_t`` (for an auto-recurrence ``rows`` itself: the mirrored triangle); returns
    ``(eps, candidate pairs set)``."""
    rowbuf = np.empty(((m + 63) // 64) * 64, dtype=np.float64)
    eps, count = _threshold(
        x, y, m, auto, theiler, dim, delay, metric, rank, n_candidates, strict, direct, rowbuf,
        rows,
    )
    _transpose_into(rows, rows_t, m, auto)
    return eps, count


@njit(cache=True)
def _auto(
    x: Array, m: int, dim: int, delay: int, metric: int, theiler: int, rank: int,
    n_candidates: int, strict: bool, direct: bool, rows: Array,
) -> tuple[float, int]:
    """Threshold and packed rows (zeroed on entry) of A_X; returns (eps, recurrent ordered pairs).

    ``rank`` is the rank among the ``n_candidates`` unordered pairs ``j > i + theiler``; 0 means
    nothing is recurrent (threshold 0).
    """
    if rank == 0:
        return 0.0, 0
    eps, count = _recurrence(x, x, m, True, theiler, dim, delay, metric, rank, n_candidates,
                             strict, direct, rows, rows)
    return eps, 2 * count


@njit(cache=True)
def _cross(
    x: Array, y: Array, m: int, dim: int, delay: int, metric: int, rank: int, strict: bool,
    direct: bool, rows: Array, rows_t: Array,
) -> tuple[float, int]:
    """Threshold and packed rows of CR_XY and CR_YX (zeroed on entry); (eps, recurrent pairs)."""
    return _recurrence(x, y, m, False, 0, dim, delay, metric, rank, m * m, strict, direct, rows,
                       rows_t)


@njit(cache=True)
def _clustering_transitivity(
    cross_rows: Array, auto_rows: Array, m: int, n_words: int, local: Array
) -> tuple[float, float]:
    """Global cross-clustering and cross-transitivity of one direction (Eq. 6-9)."""
    total_triangles = 0
    total_triples = 0
    # The words of a row that hold a neighbour: a state's cross-recurrences lie close in
    # time, in one or two words of the row, so the triangle counts skip the empty ones.
    occupied = np.empty(n_words, dtype=np.int64)
    for v in range(m):
        degree = 0
        n_occupied = 0
        for w in range(n_words):
            if cross_rows[v, w]:
                degree += int(_popcount(cross_rows[v, w]))
                occupied[n_occupied] = w
                n_occupied += 1
        triangles = 0
        for k in range(n_occupied):
            w = occupied[k]
            word = cross_rows[v, w]
            while word:
                p = w * 64 + np.int64(_lowest_bit(word))
                word &= word - np.uint64(1)
                for q in range(n_occupied):
                    u = occupied[q]
                    triangles += int(_popcount(auto_rows[p, u] & cross_rows[v, u]))
        triples = degree * (degree - 1)
        local[v] = triangles / triples if triples > 0 else 0.0
        total_triangles += triangles
        total_triples += triples
    clustering = _mean(local[:m])
    transitivity = total_triangles / total_triples if total_triples else 0.0
    return clustering, transitivity


# --------------------------------------------------------------------------------------------
# the batch


@njit(cache=True)
def _normalize(
    values: Array, start: int, n: int, s: int, mode: int, cast32: bool, target: Array
) -> None:
    """target[t] = normalized sample t of signal s in the window of rows start:start + n."""
    column = np.empty(n, dtype=np.float64)
    for t in range(n):
        column[t] = values[start + t, s]
    if mode == 1:
        low = column.min()
        span = column.max() - low
        for t in range(n):
            target[t] = (column[t] - low) / span
    elif mode == 2:
        mean = (0.0 + _pairwise_sum(column, 0, n)) / n
        squares = np.empty(n, dtype=np.float64)
        for t in range(n):
            deviation = column[t] - mean
            squares[t] = deviation * deviation
        std = math.sqrt((0.0 + _pairwise_sum(squares, 0, n)) / n)
        for t in range(n):
            target[t] = (column[t] - mean) / std
    else:
        target[:] = column
    if cast32:
        for t in range(n):
            target[t] = np.float64(np.float32(target[t]))


def _batch_kernel(
    values: Array, starts: Array, stops: Array, norm_offsets: Array, mode: int, cast32: bool,
    dim: int, delay: int, metric: int, theiler: int, strict: bool, auto_rank: Array,
    cross_rank: Array, pair_x: Array, pair_y: Array, max_states: int, direct_pairs: int,
) -> tuple[Array, Array, Array, Array, Array, Array]:
    """All pairs of all windows.

    ``auto_rank`` is per (window, signal): the rank among the unordered candidates of A (0:
    nothing recurrent); ``cross_rank`` per window. Returns ``(auto_eps, auto_count, cross_eps,
    cross_count, measures, constant)``: per (window, signal) the threshold and recurrent ordered
    pairs of A; per (window, pair) those of CR and the measures ``c_xy, c_yx, t_xy, t_yx``; per
    (window, signal) whether the signal (as embedded: normalized, cast) is constant, i.e. every
    state is the same (the per-window path's ``PackedRecurrence.constant``).
    """
    n_windows = starts.size
    n_signals = values.shape[1]
    n_pairs = pair_x.size
    n_words = (max_states + 63) // 64
    # A parallel function calling another parallel function does not survive Numba's cache:
    # every parallel loop is here, the helpers are serial.
    norm = np.empty((n_signals, norm_offsets[n_windows]), dtype=np.float64)
    for task in prange(n_windows * n_signals):
        w = task // n_signals
        s = task - w * n_signals
        n = stops[w] - starts[w]
        _normalize(
            values, starts[w], n, s, mode, cast32, norm[s, norm_offsets[w] : norm_offsets[w] + n]
        )

    constant = np.zeros((n_windows, n_signals), dtype=np.bool_)
    for task in prange(n_windows * n_signals):
        w = task // n_signals
        s = task - w * n_signals
        n = stops[w] - starts[w]
        first = norm[s, norm_offsets[w]]
        same = True
        for t in range(1, n):
            same = same and norm[s, norm_offsets[w] + t] == first
        constant[w, s] = same

    auto_rows = np.zeros((n_windows, n_signals, max_states, n_words), dtype=np.uint64)
    auto_eps = np.zeros((n_windows, n_signals), dtype=np.float64)
    auto_count = np.zeros((n_windows, n_signals), dtype=np.int64)
    for task in prange(n_windows * n_signals):
        w = task // n_signals
        s = task - w * n_signals
        n = stops[w] - starts[w]
        m = n - (dim - 1) * delay
        n_candidates = (m - theiler) * (m - theiler - 1) // 2
        x = np.ascontiguousarray(norm[s, norm_offsets[w] : norm_offsets[w] + n])
        auto_eps[w, s], auto_count[w, s] = _auto(
            x,
            m,
            dim,
            delay,
            metric,
            theiler,
            auto_rank[w, s],
            n_candidates,
            strict,
            n_candidates < direct_pairs,
            auto_rows[w, s],
        )

    cross_eps = np.zeros((n_windows, n_pairs), dtype=np.float64)
    cross_count = np.zeros((n_windows, n_pairs), dtype=np.int64)
    measures = np.zeros((n_windows, n_pairs, 4), dtype=np.float64)
    for task in prange(n_windows * n_pairs):
        w = task // n_pairs
        q = task - w * n_pairs
        n = stops[w] - starts[w]
        m = n - (dim - 1) * delay
        words = (m + 63) // 64
        local = np.empty(m, dtype=np.float64)
        rows = np.zeros((m, words), dtype=np.uint64)
        rows_t = np.zeros((m, words), dtype=np.uint64)
        # Contiguous copies: the key loops vectorize only on unit-stride arrays.
        x = np.ascontiguousarray(norm[pair_x[q], norm_offsets[w] : norm_offsets[w] + n])
        y = np.ascontiguousarray(norm[pair_y[q], norm_offsets[w] : norm_offsets[w] + n])
        cross_eps[w, q], cross_count[w, q] = _cross(
            x, y, m, dim, delay, metric, cross_rank[w], strict, m * m < direct_pairs, rows, rows_t
        )
        a_x = auto_rows[w, pair_x[q]]
        a_y = auto_rows[w, pair_y[q]]
        c_xy, t_xy = _clustering_transitivity(rows, a_y, m, words, local)
        c_yx, t_yx = _clustering_transitivity(rows_t, a_x, m, words, local)
        measures[w, q, 0] = c_xy
        measures[w, q, 1] = c_yx
        measures[w, q, 2] = t_xy
        measures[w, q, 3] = t_yx
    return auto_eps, auto_count, cross_eps, cross_count, measures, constant


#: The kernel with its loops over the cores, and the same loops in the calling thread: a parallel
#: region costs a wake-up of the other threads, which on a busy machine outweighs a small batch.
#: Both release the interpreter: a caller's other threads go on meanwhile.
batch_kernel = njit(cache=True, parallel=True, nogil=True)(_batch_kernel)
batch_kernel_serial = njit(cache=True, nogil=True)(_batch_kernel)


@njit(cache=True)
def pair_kernel(
    x: Array, y: Array, cast32: bool, dim: int, delay: int, metric: int, theiler: int,
    strict: bool, rank_x: int, rank_y: int, rank_xy: int,
) -> tuple[bool, float, int, float, int, float, int, float, float, float, float, bool, bool]:
    """One pair of equally long signals, used as given (no normalization): the batch kernel on
    one window of two signals, in the calling thread.

    ``rank_x``, ``rank_y`` are ranks among the unordered candidates of A (0: nothing
    recurrent), ``rank_xy`` that of CR. Returns ``(plain, eps_x, count_x, eps_y, count_y,
    eps_xy, count_xy, c_xy, c_yx, t_xy, t_yx, constant_x, constant_y)``; ``plain`` is False,
    and nothing computed, unless every value is finite and below 1e38 in magnitude (then the
    float32 cast of ``cast32`` and every distance stay finite).
    """
    n = x.size
    values = np.empty((n, 2), dtype=np.float64)
    for t in range(n):
        if not (abs(x[t]) < 1e38 and abs(y[t]) < 1e38):
            return False, 0.0, 0, 0.0, 0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, False, False
        values[t, 0] = x[t]
        values[t, 1] = y[t]
    bounds = np.zeros(2, dtype=np.int64)
    bounds[1] = n
    pair_x = np.zeros(1, dtype=np.int64)
    pair_y = np.ones(1, dtype=np.int64)
    auto_rank = np.empty((1, 2), dtype=np.int64)
    auto_rank[0, 0] = rank_x
    auto_rank[0, 1] = rank_y
    cross_rank = np.full(1, rank_xy, dtype=np.int64)
    m = n - (dim - 1) * delay
    auto_eps, auto_count, cross_eps, cross_count, measures, constant = batch_kernel_serial(
        values, bounds[:1], bounds[1:], bounds, 0, cast32, dim, delay, metric, theiler, strict,
        auto_rank, cross_rank, pair_x, pair_y, m, DIRECT_PAIRS,
    )
    return (
        True, auto_eps[0, 0], auto_count[0, 0], auto_eps[0, 1], auto_count[0, 1],
        cross_eps[0, 0], cross_count[0, 0], measures[0, 0, 0], measures[0, 0, 1],
        measures[0, 0, 2], measures[0, 0, 3], constant[0, 0], constant[0, 1],
    )
