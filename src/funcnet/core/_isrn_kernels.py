"""Compiled kernels of the recurrence structures and the cross measures (private).

Distances are compared through a monotone *key*: the sum of squares for "euclidean" (no square
root in the hot loops), the distance itself otherwise. A threshold eps becomes the largest key
whose distance is <= eps (or < eps), computed exactly with the same correctly rounded square
root (:func:`funcnet.core._keys.key_bound`), so every comparison equals the one on
distances. Keys are accumulated coordinate by coordinate in the order pyunicorn's kernels use,
so both give the same bits. One row of keys at a time is held, never the distance matrix.

Recurrence rows are bit-packed: bit ``j`` of row ``i`` is word ``j // 64``, bit ``j % 64``.
The cross-triangle kernel of Eq. 6-9 counts with popcounts over those words.

Every kernel called from Python releases the GIL, so that threads compute side by side: the
parallel ones while their region runs, the serial ones compiled ``nogil``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from llvmlite import ir
from numba import njit, prange, types
from numba.extending import intrinsic

Array = np.ndarray
# Numba hands kernels NumPy integer scalars as well as ints.
Int = int | np.integer[Any]

_METRIC_CODE = {"euclidean": 0, "supremum": 1, "manhattan": 2}


if TYPE_CHECKING:  # what the intrinsics compute, as mypy should see them

    def _popcount(word: Any) -> int: ...

    def _lowest_bit(word: Any) -> int: ...

else:

    @intrinsic
    def _popcount(typingctx: Any, word: Any) -> Any:
        """Number of set bits of a uint64 (LLVM ``ctpop``, one instruction on x86-64)."""
        signature = types.uint64(types.uint64)

        def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
            return builder.ctpop(args[0])

        return signature, codegen


    @intrinsic
    def _lowest_bit(typingctx: Any, word: Any) -> Any:
        """Index of the lowest set bit of a non-zero uint64 (LLVM ``cttz``)."""
        signature = types.uint64(types.uint64)

        def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
            return builder.cttz(args[0], ir.Constant(ir.IntType(1), 1))

        return signature, codegen


@njit(cache=True, inline="always")
def add_coordinate_keys(value: float, column: Array, n: int, first: bool, metric: int,
                        keys: Array) -> None:
    """Fold one coordinate into ``keys[:n]``: the keys of one state against ``n`` others, built
    coordinate by coordinate (squared sum, maximum or sum); shared by the per-window and the
    batched kernels, so that both give the same bits."""
    if metric == 0:
        if first:
            for t in range(n):
                diff = value - column[t]
                keys[t] = diff * diff
        else:
            for t in range(n):
                diff = value - column[t]
                keys[t] += diff * diff
    elif metric == 1:
        if first:
            for t in range(n):
                keys[t] = abs(value - column[t])
        else:
            for t in range(n):
                keys[t] = max(keys[t], abs(value - column[t]))
    else:
        if first:
            for t in range(n):
                keys[t] = abs(value - column[t])
        else:
            for t in range(n):
                keys[t] += abs(value - column[t])


@njit(cache=True, inline="always")
def dim3_squared_keys(a0: float, a1: float, a2: float, b0: Array, b1: Array, b2: Array, n: int,
                      keys: Array) -> None:
    """``keys[:n]`` of the state ``(a0, a1, a2)`` against the states of the columns ``b0``,
    ``b1``, ``b2``: the default embedding (dim 3, Euclidean) in one pass, the same sum in the
    same order as three folds of :func:`add_coordinate_keys` (``(d0^2 + d1^2) + d2^2``, no fused
    multiply-add) with a third of the loads and stores of keys (about twice as fast); shared
    by the per-window and the batched kernels."""
    for t in range(n):
        d0 = a0 - b0[t]
        d1 = a1 - b1[t]
        d2 = a2 - b2[t]
        keys[t] = d0 * d0 + d1 * d1 + d2 * d2


@njit(cache=True, inline="always")
def below_and_upto_words(block: Array, lo: float, hi: float) -> tuple[Any, Any]:
    """The two uint64 words of 64 keys: bits of key < lo, bits of key <= hi."""
    below_word = np.uint64(0)
    upto_word = np.uint64(0)
    for b in range(64):
        below_word |= np.uint64(block[b] < lo) << np.uint64(b)
        upto_word |= np.uint64(block[b] <= hi) << np.uint64(b)
    return below_word, upto_word


@njit(cache=True, inline="always")
def first_candidate(i: Int, auto: bool, theiler: int) -> int:
    """The first column of row i among the candidate pairs: j > i + theiler of an
    auto-recurrence (its upper triangle), every column otherwise."""
    return int(i + theiler + 1) if auto else 0


@njit(cache=True)
def _row_keys(a: Array, i: Int, bt: Array, start: int, metric: int, keys: Array) -> int:
    """keys[j - start] = key of (a[i], b[j]) for j >= start; ``bt`` is b transposed, (dim, n)."""
    # Loops run over views from 0 so that the compiler sees non-negative indices and
    # vectorizes (a runtime start index costs a wrap-around check per element).
    n = bt.shape[1] - start
    if metric == 0 and bt.shape[0] == 3:
        dim3_squared_keys(a[i, 0], a[i, 1], a[i, 2], bt[0, start:], bt[1, start:],
                          bt[2, start:], n, keys)
        return n
    for c in range(bt.shape[0]):
        add_coordinate_keys(a[i, c], bt[c, start:], n, c == 0, metric, keys)
    return n


@njit(cache=True)
def _n_iterations(n_rows: int, auto: bool) -> int:
    # A conditional expression written inside prange(...) keeps Numba from parallelizing the
    # loop (silently, when other parts of the function are parallel): call this instead.
    return (n_rows + 1) // 2 if auto else n_rows


@njit(cache=True)
def _row_of(r: Int, side: int, n_rows: int, auto: bool) -> Int:
    # For the triangle j > i of an auto-recurrence, iteration r handles rows r and n - 1 - r, so
    # that every iteration does the same work; -1 marks "no row".
    if not auto:
        return r if side == 0 else -1
    i = r if side == 0 else n_rows - 1 - r
    return -1 if side == 1 and i == r else i


@njit(cache=True, parallel=True)
def _sample_keys(a: Array, bt: Array, rows: Array, cols: Array, metric: int) -> Array:
    out = np.empty(rows.size, dtype=np.float64)
    for t in prange(rows.size):
        acc = 0.0
        for c in range(bt.shape[0]):
            diff = abs(a[rows[t], c] - bt[c, cols[t]])
            if metric == 0:
                acc += diff * diff
            elif metric == 1:
                acc = max(acc, diff)
            else:
                acc += diff
        out[t] = acc
    return out


# The parallel loops only call row functions: Numba optimizes (vectorizes) loops in a plain
# function far better than the same loops written inside a prange body.


@njit(cache=True)
def _padded_row_keys(a: Array, i: Int, bt: Array, start: int, metric: int, keys: Array) -> None:
    """Keys of row i indexed by column, NaN (false in every comparison) before start and after
    the end. ``keys`` holds whole words: each word is assembled by a fixed loop of 64 compares.
    """
    _row_keys(a, i, bt, start, metric, keys[start:])
    keys[(start // 64) * 64 : start] = np.nan
    keys[bt.shape[1] :] = np.nan


@njit(cache=True)
def _pack_keys(keys: Array, first_word: int, bound: float, packed_row: Array) -> Int:
    """packed_row[w] = bits of keys <= bound for the words from first_word on; bits set."""
    count: Int = 0
    for w in range(first_word, packed_row.size):
        block = keys[w * 64 : w * 64 + 64]
        word = np.uint64(0)
        for b in range(64):
            word |= np.uint64(block[b] <= bound) << np.uint64(b)
        packed_row[w] = word
        count += np.int64(_popcount(word))
    return count


@njit(cache=True)
def _pack_row(
    a: Array, i: Int, bt: Array, start: int, metric: int, bound: float, keys: Array,
    packed: Array,
) -> Int:
    _padded_row_keys(a, i, bt, start, metric, keys)
    return _pack_keys(keys, start // 64, bound, packed[i])


@njit(cache=True)
def _scan_row(
    a: Array, i: Int, bt: Array, start: int, metric: int, lo: float, hi: float, keys: Array,
    counts: Array, packed: Array, band_keys: Array, band_index: Array, at: int,
) -> int:
    """Pack key < lo of row i, count #key < lo and #key <= hi, and append the band pairs
    lo <= key <= hi (key, and position ``(i << 32) | j``) to the band buffers from ``at`` on
    while they have room. Returns the new band position (beyond the buffer size on overflow)."""
    _padded_row_keys(a, i, bt, start, metric, keys)
    below: Int = 0
    upto: Int = 0
    for w in range(start // 64, packed.shape[1]):
        below_word, upto_word = below_and_upto_words(keys[w * 64 : w * 64 + 64], lo, hi)
        packed[i, w] = below_word
        below += np.int64(_popcount(below_word))
        upto += np.int64(_popcount(upto_word))
        band = upto_word & ~below_word
        while band:
            if at < band_keys.size:
                j = w * 64 + np.int64(_lowest_bit(band))
                band_keys[at] = keys[j]
                band_index[at] = (i << 32) | j
            at += 1
            band &= band - np.uint64(1)
    counts[i, 0] = below
    counts[i, 1] = upto
    return at


@njit(cache=True)
def _collect_row(
    a: Array, i: Int, bt: Array, start: int, metric: int, lo: float, hi: float, keys: Array,
    position: int, band_keys: Array, band_index: Array,
) -> None:
    """Write key and position ``(i << 32) | j`` of every lo <= key <= hi of row i from
    ``position`` on."""
    n = _row_keys(a, i, bt, start, metric, keys)
    for t in range(n):
        if lo <= keys[t] <= hi:
            band_keys[position] = keys[t]
            band_index[position] = (i << 32) | (start + t)
            position += 1


@njit(cache=True, parallel=True)
def _scan_rows(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, lo: float, hi: float,
    n_chunks: int, capacity: int,
) -> tuple[Array, Array, Array, Array, Array]:
    """One pass (see _rate_rows): packed rows of key < lo, per-row counts of key < lo and
    key <= hi, and the band lo <= key <= hi in ``n_chunks`` buffers of ``capacity``
    (``filled[c] > capacity`` means chunk c overflowed). Chunk c takes every n_chunks-th row
    pair from c on: a recording's band gathers in stretches of time (a robot at rest), which a
    block of consecutive rows would collect in one chunk and overflow it."""
    n_rows = a.shape[0]
    n_iterations = _n_iterations(n_rows, auto)
    counts = np.zeros((n_rows, 2), dtype=np.int64)
    packed = np.zeros((n_rows, (bt.shape[1] + 63) // 64), dtype=np.uint64)
    band_keys = np.empty((n_chunks, capacity), dtype=np.float64)
    band_index = np.empty((n_chunks, capacity), dtype=np.int64)
    filled = np.zeros(n_chunks, dtype=np.int64)
    for chunk in prange(n_chunks):
        keys = np.empty(packed.shape[1] * 64, dtype=np.float64)
        position = 0
        for r in range(chunk, n_iterations, n_chunks):
            for side in range(2):
                i = _row_of(np.int64(r), side, n_rows, auto)
                if i >= 0:
                    start = first_candidate(i, auto, theiler)
                    position = _scan_row(
                        a,
                        i,
                        bt,
                        start,
                        metric,
                        lo,
                        hi,
                        keys,
                        counts,
                        packed,
                        band_keys[chunk],
                        band_index[chunk],
                        position,
                    )
        filled[chunk] = position
    return counts, packed, band_keys, band_index, filled


@njit(cache=True, parallel=True)
def _collect_band(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, lo: float, hi: float,
    offsets: Array, band_keys: Array, band_index: Array,
) -> None:
    """Pass 2 when a band buffer overflowed: keys and positions of lo <= key <= hi, row i
    from offsets[i] on."""
    n_rows = a.shape[0]
    for r in prange(_n_iterations(n_rows, auto)):
        keys = np.empty(bt.shape[1], dtype=np.float64)
        for side in range(2):
            i = _row_of(np.int64(r), side, n_rows, auto)
            if i >= 0:
                start = first_candidate(i, auto, theiler)
                _collect_row(
                    a, i, bt, start, metric, lo, hi, keys, offsets[i], band_keys, band_index
                )


@njit(cache=True, nogil=True)
def _compact_band(chunk_keys: Array, chunk_index: Array, filled: Array) -> int:
    """Move the filled part of every chunk to the front of the buffers (flattened), in chunk
    order, without a new array; return the number of band pairs."""
    keys = chunk_keys.reshape(-1)
    index = chunk_index.reshape(-1)
    capacity = chunk_keys.shape[1]
    at = 0
    for c in range(filled.size):
        for t in range(c * capacity, c * capacity + filled[c]):  # never behind ``at``
            keys[at] = keys[t]
            index[at] = index[t]
            at += 1
    return at


@njit(cache=True)
def _count_row(a: Array, i: Int, bt: Array, start: int, metric: int, value: float,
               keys: Array) -> tuple[int, int]:
    n = _row_keys(a, i, bt, start, metric, keys)
    below = 0
    upto = 0
    for t in range(n):
        below += keys[t] < value
        upto += keys[t] <= value
    return below, upto


@njit(cache=True, parallel=True)
def _count_keys(a: Array, bt: Array, auto: bool, theiler: int, metric: int,
                value: float) -> Array:
    """Numbers of candidate keys < value and <= value; memory one row of keys per thread."""
    n_rows = a.shape[0]
    counts = np.zeros((n_rows, 2), dtype=np.int64)
    for r in prange(_n_iterations(n_rows, auto)):
        keys = np.empty(bt.shape[1], dtype=np.float64)
        for side in range(2):
            i = _row_of(np.int64(r), side, n_rows, auto)
            if i >= 0:
                start = first_candidate(i, auto, theiler)
                counts[i, 0], counts[i, 1] = _count_row(a, i, bt, start, metric, value, keys)
    return counts.sum(axis=0)


@njit(cache=True, nogil=True)
def _add_band_bits(packed: Array, band_keys: Array, band_index: Array, bound: float) -> int:
    """Set the bits of the band pairs with key <= bound; return how many were set."""
    count = 0
    for t in range(band_keys.size):
        if band_keys[t] <= bound:
            i = band_index[t] >> 32
            j = band_index[t] & 0xFFFFFFFF
            packed[i, j >> 6] |= np.uint64(1) << np.uint64(j & 63)
            count += 1
    return count


@njit(cache=True, parallel=True)
def _pack_rows(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, bound: float
) -> tuple[Array, int]:
    """Bit-packed rows of key <= bound, and the number of bits set.

    For an auto-recurrence only the triangle j > i + theiler is filled (see threshold_rows).
    """
    n_rows = a.shape[0]
    packed = np.zeros((n_rows, (bt.shape[1] + 63) // 64), dtype=np.uint64)
    degree = np.zeros(n_rows, dtype=np.int64)
    for r in prange(_n_iterations(n_rows, auto)):
        keys = np.empty(packed.shape[1] * 64, dtype=np.float64)
        for side in range(2):
            i = _row_of(np.int64(r), side, n_rows, auto)
            if i >= 0:
                start = first_candidate(i, auto, theiler)
                degree[i] = _pack_row(a, i, bt, start, metric, bound, keys, packed)
    return packed, int(degree.sum())


@njit(cache=True, inline="always")
def _transpose_block(packed: Array, w: int, r: int, block: Array) -> bool:
    """``block[j]`` bit ``k`` = bit ``j`` of ``packed[64 r + k, w]``: the 64 x 64 bit block
    transposed in place by swapping ever smaller off-diagonal halves (Hacker's Delight 7-3);
    False (and the block left as read) when it holds no bit."""
    any_bit = np.uint64(0)
    for k in range(64):
        v = 64 * r + k
        block[k] = packed[v, w] if v < packed.shape[0] else np.uint64(0)
        any_bit |= block[k]
    if not any_bit:  # most blocks of a recurrence are empty: their transpose too
        return False
    j = 32
    mask = np.uint64(0xFFFFFFFF)
    while j:
        shift = np.uint64(j)
        for k in range(64):
            if k & j == 0:
                t = ((block[k] >> shift) ^ block[k + j]) & mask
                block[k] ^= t << shift
                block[k + j] ^= t
        j >>= 1
        mask ^= mask << np.uint64(j)
    return True


@njit(cache=True, parallel=True)
def _transpose_packed(packed: Array, n_cols: int) -> Array:
    n_rows, n_words = packed.shape
    out = np.zeros((n_cols, (n_rows + 63) // 64), dtype=np.uint64)
    # Each iteration owns the 64 output rows of one input word column: no write conflicts.
    for w in prange(n_words):
        block = np.empty(64, dtype=np.uint64)
        for r in range(out.shape[1]):
            if not _transpose_block(packed, w, r, block):
                continue
            for j in range(min(64, n_cols - 64 * w)):
                out[64 * w + j, r] = block[j]
    return out


@njit(cache=True, parallel=True)
def _merge_into(packed: Array, other: Array) -> None:
    for i in prange(packed.shape[0]):
        for w in range(packed.shape[1]):
            packed[i, w] |= other[i, w]


@njit(cache=True, parallel=True)
def _row_popcounts(packed: Array) -> Array:
    sums = np.zeros(packed.shape[0], dtype=np.int64)
    for i in prange(packed.shape[0]):
        count: Int = 0
        for w in range(packed.shape[1]):
            count += np.int64(_popcount(packed[i, w]))
        sums[i] = count
    return sums


@njit(cache=True, nogil=True)
def _unpack(packed: Array, n_cols: int) -> Array:
    dense = np.zeros((packed.shape[0], n_cols), dtype=np.bool_)
    for i in range(packed.shape[0]):
        for j in range(n_cols):
            dense[i, j] = (packed[i, j >> 6] >> np.uint64(j & 63)) & np.uint64(1)
    return dense




@njit(cache=True)
def _row_triangles(row: Array, auto_rows: Array) -> tuple[Int, Int]:
    """``(k_v, tri_v)`` of one packed cross-recurrence row against the packed ``auto_rows``."""
    first = -1
    last = -1
    degree: Int = 0
    for w in range(row.size):
        if row[w]:
            if first < 0:
                first = w
            last = w
            degree += np.int64(_popcount(row[w]))
    # Each unordered neighbour pair p < q is counted once: for neighbour p, the AND runs over
    # the neighbours above p only (the rest of p's word, then the words up to v's last one).
    # Contiguous word ranges let the compiler vectorize the popcounts.
    pairs: Int = 0
    for w in range(max(first, 0), last + 1):
        word = row[w]
        row_tail = row[w + 1 : last + 1]
        while word:
            p = w * 64 + np.int64(_lowest_bit(word))
            word &= word - np.uint64(1)
            neighbours = auto_rows[p]
            pairs += np.int64(_popcount(neighbours[w] & word))
            neighbours_tail = neighbours[w + 1 : last + 1]
            for s in range(row_tail.size):
                pairs += np.int64(_popcount(neighbours_tail[s] & row_tail[s]))
    return degree, 2 * pairs


@njit(cache=True, parallel=True)
def _cross_triangles(cross_rows: Array, auto_rows: Array) -> tuple[Array, Array]:
    """Per row v of ``cross_rows``: cross-degree k_v and ordered cross-triangles tri_v (Eq. 6-7)."""
    n_rows = cross_rows.shape[0]
    degree = np.zeros(n_rows, dtype=np.int64)
    triangles = np.zeros(n_rows, dtype=np.int64)
    for v in prange(n_rows):
        degree[v], triangles[v] = _row_triangles(cross_rows[v], auto_rows)
    return degree, triangles


# --------------------------------------------------------------------------------------------
# blocked triangle counts: both directions, each auto row read once per block of cross rows


@njit(cache=True)
def _word_spans(rows: Array) -> Array:
    """First and last non-zero word of each row (``(0, -1)`` for an empty row)."""
    spans = np.zeros((rows.shape[0], 2), dtype=np.int64)
    for v in range(rows.shape[0]):
        spans[v, 1] = -1
        for w in range(rows.shape[1]):
            if rows[v, w]:
                spans[v, 0] = w
                break
        for w in range(rows.shape[1] - 1, -1, -1):
            if rows[v, w]:
                spans[v, 1] = w
                break
    return spans


@njit(cache=True)
def _block_pairs(
    rows: Array, columns: Array, auto_rows: Array, row_spans: Array, auto_spans: Array,
    first_word: int, n_block_words: int, pairs: Array,
) -> None:
    """Unordered neighbour pairs of the rows ``v`` of one block (the rows of ``columns`` words
    ``first_word ..``): for each neighbour ``p`` (a row of ``columns``, the transposed
    ``rows``), the auto row ``p`` is read once and ANDed with every block row that holds it,
    over the words where both rows have bits. The same bits are counted as by _row_triangles,
    in another order: the integer sums agree."""
    end_word = min(first_word + n_block_words, columns.shape[1])
    for p in range(columns.shape[0]):
        neighbours = auto_rows[p]
        wp = p >> 6
        # Bits above p in its own word; 2 << 63 wraps to 0, leaving no bit above bit 63.
        above = ~((np.uint64(2) << np.uint64(p & 63)) - np.uint64(1))
        start = max(wp + 1, auto_spans[p, 0])
        for mw in range(first_word, end_word):
            holders = columns[p, mw]
            while holders:
                v = mw * 64 + np.int64(_lowest_bit(holders))
                holders &= holders - np.uint64(1)
                row = rows[v]
                count: Int = np.int64(_popcount(neighbours[wp] & row[wp] & above))
                stop = min(row_spans[v, 1], auto_spans[p, 1]) + 1
                if stop > start:
                    row_tail = row[start:stop]
                    neighbours_tail = neighbours[start:stop]
                    for s in range(row_tail.size):
                        count += np.int64(_popcount(neighbours_tail[s] & row_tail[s]))
                pairs[v] += count


@njit(cache=True, parallel=True)
def _cross_triangles_both(
    cross_rows: Array, cross_columns: Array, auto_x: Array, auto_y: Array, block_words: int,
    n_threads: int,
) -> tuple[Array, Array, Array, Array]:
    """``(k_xy, tri_xy, k_yx, tri_yx)`` of Eq. 6-7 in one parallel pass over blocks of
    ``64 * block_words`` rows of ``CR_XY`` (``cross_rows``) and of ``CR_YX``
    (``cross_columns``, its transpose). Blocks of both directions are dealt to the
    ``n_threads`` workers in turn, so that uneven blocks even out."""
    spans_xy = _word_spans(cross_rows)
    spans_yx = _word_spans(cross_columns)
    spans_x = _word_spans(auto_x)
    spans_y = _word_spans(auto_y)
    pairs_xy = np.zeros(cross_rows.shape[0], dtype=np.int64)
    pairs_yx = np.zeros(cross_columns.shape[0], dtype=np.int64)
    n_xy = (cross_columns.shape[1] + block_words - 1) // block_words
    n_yx = (cross_rows.shape[1] + block_words - 1) // block_words
    for thread in prange(n_threads):
        for task in range(thread, n_xy + n_yx, n_threads):
            if task < n_xy:
                _block_pairs(cross_rows, cross_columns, auto_y, spans_xy, spans_y,
                             task * block_words, block_words, pairs_xy)
            else:
                _block_pairs(cross_columns, cross_rows, auto_x, spans_yx, spans_x,
                             (task - n_xy) * block_words, block_words, pairs_yx)
    return (_row_popcounts(cross_rows), 2 * pairs_xy, _row_popcounts(cross_columns),
            2 * pairs_yx)

