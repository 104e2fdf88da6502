"""Delay embedding, thresholds and (cross-)recurrence structures (paper section 2.1-2.2).

A signal ``x`` of ``N`` samples becomes ``M = N - (dim - 1) * delay`` states (Eq. 1). Two states are
recurrent when their distance is within a threshold ``eps`` (Eq. 2, 3, 5). The thresholds are
usually fixed by a *rate*: the fraction of candidate pairs that must be recurrent.

Threshold rule (``rule="funcnet"``, the default)
    * auto-recurrence of X (Eq. 5): the candidates are the ``P = (M - w)(M - w - 1)`` ordered pairs
      ``(i, j)`` with ``|i - j| > w`` (``w = theiler``; ``w = 0`` excludes only the diagonal, as the
      paper does). ``eps_X`` is the ``k``-th smallest of their distances,
      ``k = max(1, ceil(rr * P - 1e-9))`` evaluated in float64; ``A_X[i, j] = 1`` iff
      ``|i - j| > w`` and ``d(x_i, x_j) <= eps_X``;
    * cross-recurrence (Eq. 3): the candidates are all ``P = M_X * M_Y`` pairs,
      ``k = max(1, ceil(cr * P - 1e-9))``; ``CR_XY[i, j] = 1`` iff ``d(x_i, y_j) <= eps_XY``.

    The order statistic is exact (not estimated from a sample) and reported in float64. Ties at the
    threshold can make more than ``k`` pairs recurrent; the achieved rate is reported next to each
    ``eps``, and the measures issue a :class:`~funcnet.errors.ThresholdWarning` when it exceeds
    its target.

Compatibility rule (``rule="pyunicorn"``)
    Reproduces pyunicorn 1.0.0's ``InterSystemRecurrenceNetwork``: the input series are cast to
    float32 (then embedded, and distances measured, in float64 from those values); ``eps`` is the
    element at index ``int(rate * (P - 1))`` of the sorted full distance matrix (diagonal included,
    ``P = M**2`` for auto-, ``M_X * M_Y`` for cross-recurrence); recurrence means ``d < eps``
    (strict); the diagonal of ``A_X``, ``A_Y`` is zeroed, the cross block keeps its diagonal. An
    explicit ``eps`` is also compared strictly. ``theiler`` must be 0 in this mode. pyunicorn's own
    default metric is ``"supremum"``; here the metric is whatever the caller passes.

Achieved rates are reported as the fraction of candidate pairs that are recurrent (diagonal and
Theiler-excluded pairs are not candidates, under both rules).

Memory and speed: the ``M x M`` distance matrix is never stored, in any precision. Recurrence
structures are bit-packed rows (:class:`PackedRecurrence`, ``M^2 / 8`` bytes) built by compiled,
parallel kernels that compute one row of distances at a time. The exact order statistic costs
one pass over the pairs: a random sample of distances brackets it, the pass packs the pairs below
the bracket, counts, and keeps only the few pairs inside it (a few per cent), whose partial sort
gives the exact value. At M = 20000 one pair of signals needs about 0.4 GB.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from llvmlite import ir
from numba import njit, prange, types
from numba.extending import intrinsic

from funcnet.errors import ParameterError, SignalError

# The kernels run many short parallel loops. OpenMP's default lets idle threads spin between
# them, which on a shared or busy machine takes the cores the work needs; sleeping threads cost
# microseconds instead. Numba starts its OpenMP runtime at the first parallel call, after this
# line; a user's own setting wins.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

__all__ = [
    "METRICS",
    "RULES",
    "PackedRecurrence",
    "embed",
    "signal_states",
    "auto_recurrence",
    "cross_recurrence",
    "recurrence_matrix",
    "cross_recurrence_matrix",
    "isrn_adjacency",
    "estimate_delay",
    "estimate_dimension",
]

METRICS = ("euclidean", "supremum", "manhattan")
RULES = ("funcnet", "pyunicorn")

_WORD = 64


# --------------------------------------------------------------------------------------------
# validation


def _check_int(value: Any, name: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ParameterError(f"{name} must be an integer, got {value!r}")
    if value < minimum:
        raise ParameterError(f"{name} must be >= {minimum}, got {value}")
    return int(value)


def _check_metric(metric: Any) -> str:
    if metric not in METRICS:
        raise ParameterError(f"metric must be one of {', '.join(METRICS)}; got {metric!r}")
    return str(metric)


def _check_rule(rule: Any) -> str:
    if rule not in RULES:
        raise ParameterError(f"rule must be one of {', '.join(RULES)}; got {rule!r}")
    return str(rule)


def _check_theiler(theiler: Any, rule: str) -> int:
    theiler = _check_int(theiler, "theiler", 0)
    if rule == "pyunicorn" and theiler != 0:
        raise ParameterError(
            f"theiler must be 0 with rule='pyunicorn' (pyunicorn has no Theiler window); "
            f"got {theiler}"
        )
    return theiler


def _check_options(metric: Any, rule: Any, theiler: Any) -> tuple[str, str, int]:
    """Validated ``(metric, rule, theiler)``, shared by every function that takes them."""
    rule = _check_rule(rule)
    return _check_metric(metric), rule, _check_theiler(theiler, rule)


def _check_rate(rate: Any, name: str) -> float:
    if isinstance(rate, bool) or not isinstance(rate, numbers.Real):
        raise ParameterError(f"{name} must be a number in (0, 1), got {rate!r}")
    rate = float(rate)
    if not 0.0 < rate < 1.0:
        raise ParameterError(f"{name} must be in (0, 1), got {rate}")
    return rate


def _check_eps(eps: Any, name: str) -> float:
    if isinstance(eps, bool) or not isinstance(eps, numbers.Real):
        raise ParameterError(f"{name} must be a positive number, got {eps!r}")
    eps = float(eps)
    if not (eps > 0.0 and math.isfinite(eps)):
        raise ParameterError(f"{name} must be positive and finite, got {eps}")
    return eps


def _check_signal(x: Any, name: str) -> np.ndarray:
    """Return ``x`` as a 1-D float64 array of finite values, or raise naming it."""
    array = np.asarray(x)
    if array.ndim == 2 and array.shape[1] == 1:
        array = array[:, 0]
    if array.ndim != 1:
        raise SignalError(f"signal {name} must be one-dimensional, got shape {array.shape}")
    if array.dtype.kind not in "biuf":
        raise SignalError(f"signal {name} must be real-valued, got dtype {array.dtype}")
    array = array.astype(np.float64, copy=False)
    bad = ~np.isfinite(array)
    if bad.any():
        first = int(np.flatnonzero(bad)[0])
        raise SignalError(
            f"signal {name} has {int(bad.sum())} NaN or infinite value(s), the first at index "
            f"{first}"
        )
    return array


def _n_states(n_samples: int, dim: int, delay: int, name: str, minimum: int) -> int:
    n_states = n_samples - (dim - 1) * delay
    if n_states < minimum:
        raise SignalError(
            f"signal {name} is too short for the embedding: {n_samples} samples with dim={dim}, "
            f"delay={delay} give {max(n_states, 0)} state(s), at least {minimum} needed "
            f"(N >= {(dim - 1) * delay + minimum})"
        )
    return n_states


# --------------------------------------------------------------------------------------------
# embedding


def _delay_rows(signal: np.ndarray, dim: int, delay: int, n_states: int) -> np.ndarray:
    states = np.empty((n_states, dim), dtype=np.float64)
    for column in range(dim):
        states[:, column] = signal[column * delay : column * delay + n_states]
    return states


def embed(x: Any, dim: int, delay: int) -> np.ndarray:
    """Delay embedding of a scalar signal (Eq. 1).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal, finite real values, time on axis 0.
    dim : int
        Embedding dimension ``m >= 1``.
    delay : int
        Delay ``tau >= 1`` in samples.

    Returns
    -------
    ndarray, shape (N - (dim - 1) * delay, dim), float64
        Row ``i`` is ``[x[i], x[i + delay], ..., x[i + (dim - 1) * delay]]``.

    Raises
    ------
    ParameterError
        ``dim`` or ``delay`` is not a positive integer.
    SignalError
        ``x`` is not 1-D, holds NaN or inf, or is too short to give one state.

    References
    ----------
    Eq. 1 of El Dabett, Hansen & Geier (section 2.1).

    Examples
    --------
    >>> from funcnet import embed
    >>> embed([0, 1, 2, 3, 4, 5], dim=3, delay=2)
    array([[0., 2., 4.],
           [1., 3., 5.]])
    """
    dim = _check_int(dim, "dim", 1)
    delay = _check_int(delay, "delay", 1)
    signal = _check_signal(x, "x")
    return _delay_rows(signal, dim, delay, _n_states(signal.size, dim, delay, "x", 1))


def signal_states(
    x: Any, *, dim: int = 3, delay: int = 10, rule: str = "funcnet", name: str = "x"
) -> np.ndarray:
    """Validated embedded states of ``x`` as the measures use them.

    Under ``rule="pyunicorn"`` the series is cast to float32 first (then embedded in float64), as
    pyunicorn 1.0.0 does; otherwise this is :func:`embed` with at least two states required.

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal.
    dim, delay : int
        Embedding dimension and delay (Eq. 1).
    rule : {"funcnet", "pyunicorn"}
        Threshold rule (see the module notes).
    name : str
        How error messages call the signal.

    Returns
    -------
    ndarray, shape (M, dim), float64, C-contiguous

    Raises
    ------
    ParameterError, SignalError
        Bad ``dim``, ``delay`` or ``rule``; a signal that is not finite or too short (M < 2).

    References
    ----------
    Eq. 1 (section 2.1); README "pyunicorn compatibility" for the cast.

    Examples
    --------
    >>> float(signal_states([0.1, 0.2, 0.3, 0.4], dim=2, delay=1, rule="pyunicorn")[0, 0])
    0.10000000149011612
    """
    dim = _check_int(dim, "dim", 1)
    delay = _check_int(delay, "delay", 1)
    rule = _check_rule(rule)
    signal = _check_signal(x, name)
    if rule == "pyunicorn":
        signal = signal.astype(np.float32).astype(np.float64)
    return _delay_rows(signal, dim, delay, _n_states(signal.size, dim, delay, name, 2))


# --------------------------------------------------------------------------------------------
# compiled kernels
#
# Distances are compared through a monotone *key*: the sum of squares for "euclidean" (no
# square root in the hot loops), the distance itself otherwise. A threshold eps becomes the
# largest key whose distance is <= eps (or < eps), computed exactly with the same correctly
# rounded square root (see _key_bound), so every comparison equals the one on distances. Keys are
# accumulated coordinate by coordinate in the order pyunicorn's kernels use, so both give the
# same bits. One row of keys at a time is held, never the distance matrix.

_METRIC_CODE = {"euclidean": 0, "supremum": 1, "manhattan": 2}


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


@njit(cache=True)
def _row_keys(a, i, bt, start, metric, keys):
    """keys[j - start] = key of (a[i], b[j]) for j >= start; ``bt`` is b transposed, (dim, n)."""
    # Loops run over views from 0 so that the compiler sees non-negative indices and
    # vectorizes (a runtime start index costs a wrap-around check per element).
    n = bt.shape[1] - start
    for c in range(bt.shape[0]):
        value = a[i, c]
        column = bt[c, start:]
        if metric == 0:
            if c == 0:
                for t in range(n):
                    diff = value - column[t]
                    keys[t] = diff * diff
            else:
                for t in range(n):
                    diff = value - column[t]
                    keys[t] += diff * diff
        elif metric == 1:
            if c == 0:
                for t in range(n):
                    keys[t] = abs(value - column[t])
            else:
                for t in range(n):
                    keys[t] = max(keys[t], abs(value - column[t]))
        else:
            if c == 0:
                for t in range(n):
                    keys[t] = abs(value - column[t])
            else:
                for t in range(n):
                    keys[t] += abs(value - column[t])
    return n


@njit(cache=True)
def _n_iterations(n_rows, auto):
    # A conditional expression written inside prange(...) keeps Numba from parallelizing the
    # loop (silently, when other parts of the function are parallel): call this instead.
    return (n_rows + 1) // 2 if auto else n_rows


@njit(cache=True)
def _row_of(r, side, n_rows, auto):
    # For the triangle j > i of an auto-recurrence, iteration r handles rows r and n - 1 - r, so
    # that every iteration does the same work; -1 marks "no row".
    if not auto:
        return r if side == 0 else -1
    i = r if side == 0 else n_rows - 1 - r
    return -1 if side == 1 and i == r else i


@njit(cache=True, parallel=True)
def _sample_keys(a, bt, rows, cols, metric):
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
def _padded_row_keys(a, i, bt, start, metric, keys):
    """Keys of row i indexed by column, NaN (false in every comparison) before start and after
    the end. ``keys`` holds whole words: each word is assembled by a fixed loop of 64 compares.
    """
    _row_keys(a, i, bt, start, metric, keys[start:])
    keys[(start // 64) * 64 : start] = np.nan
    keys[bt.shape[1] :] = np.nan


@njit(cache=True)
def _pack_keys(keys, first_word, bound, packed_row):
    """packed_row[w] = bits of keys <= bound for the words from first_word on; bits set."""
    count = 0
    for w in range(first_word, packed_row.size):
        block = keys[w * 64 : w * 64 + 64]
        word = np.uint64(0)
        for b in range(64):
            word |= np.uint64(block[b] <= bound) << np.uint64(b)
        packed_row[w] = word
        count += np.int64(_popcount(word))
    return count


@njit(cache=True)
def _pack_row(a, i, bt, start, metric, bound, keys, packed):
    _padded_row_keys(a, i, bt, start, metric, keys)
    return _pack_keys(keys, start // 64, bound, packed[i])


@njit(cache=True)
def _scan_row(a, i, bt, start, metric, lo, hi, keys, counts, packed, band_keys, band_index, at):
    """Pack key < lo of row i, count #key < lo and #key <= hi, and append the band pairs
    lo <= key <= hi (key, flat index i * n + j) to the band buffers from ``at`` on while they
    have room. Returns the new band position (beyond the buffer size on overflow)."""
    _padded_row_keys(a, i, bt, start, metric, keys)
    n_cols = bt.shape[1]
    below = 0
    upto = 0
    for w in range(start // 64, packed.shape[1]):
        block = keys[w * 64 : w * 64 + 64]
        below_word = np.uint64(0)
        upto_word = np.uint64(0)
        for b in range(64):
            below_word |= np.uint64(block[b] < lo) << np.uint64(b)
            upto_word |= np.uint64(block[b] <= hi) << np.uint64(b)
        packed[i, w] = below_word
        below += np.int64(_popcount(below_word))
        upto += np.int64(_popcount(upto_word))
        band = upto_word & ~below_word
        while band:
            if at < band_keys.size:
                j = w * 64 + np.int64(_lowest_bit(band))
                band_keys[at] = keys[j]
                band_index[at] = i * n_cols + j
            at += 1
            band &= band - np.uint64(1)
    counts[i, 0] = below
    counts[i, 1] = upto
    return at


@njit(cache=True)
def _collect_row(a, i, bt, start, metric, lo, hi, keys, position, band_keys, band_index):
    """Write key and flat index of every lo <= key <= hi of row i from ``position`` on."""
    n = _row_keys(a, i, bt, start, metric, keys)
    for t in range(n):
        if lo <= keys[t] <= hi:
            band_keys[position] = keys[t]
            band_index[position] = i * bt.shape[1] + start + t
            position += 1


@njit(cache=True, parallel=True)
def _scan_rows(a, bt, auto, theiler, metric, lo, hi, n_chunks, capacity):
    """One pass (see _rate_rows): packed rows of key < lo, per-row counts of key < lo and
    key <= hi, and the band lo <= key <= hi in ``n_chunks`` buffers of ``capacity`` (each
    chunk is a block of rows; ``filled[c] > capacity`` means chunk c overflowed)."""
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
        first = chunk * n_iterations // n_chunks
        for r in range(first, (chunk + 1) * n_iterations // n_chunks):
            for side in range(2):
                i = _row_of(np.int64(r), side, n_rows, auto)
                if i >= 0:
                    start = i + theiler + 1 if auto else 0
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
def _collect_band(a, bt, auto, theiler, metric, lo, hi, offsets, band_keys, band_index):
    """Pass 2 when a band buffer overflowed: keys and flat indices of lo <= key <= hi, row i
    from offsets[i] on."""
    n_rows = a.shape[0]
    for r in prange(_n_iterations(n_rows, auto)):
        keys = np.empty(bt.shape[1], dtype=np.float64)
        for side in range(2):
            i = _row_of(np.int64(r), side, n_rows, auto)
            if i >= 0:
                start = i + theiler + 1 if auto else 0
                _collect_row(
                    a, i, bt, start, metric, lo, hi, keys, offsets[i], band_keys, band_index
                )


@njit(cache=True)
def _add_band_bits(packed, n_cols, band_keys, band_index, bound):
    """Set the bits of the band pairs with key <= bound; return how many were set."""
    count = 0
    for t in range(band_keys.size):
        if band_keys[t] <= bound:
            i = band_index[t] // n_cols
            j = band_index[t] - i * n_cols
            packed[i, j >> 6] |= np.uint64(1) << np.uint64(j & 63)
            count += 1
    return count


@njit(cache=True, parallel=True)
def _pack_rows(a, bt, auto, theiler, metric, bound):
    """Bit-packed rows of key <= bound, and the number of bits set.

    For an auto-recurrence only the triangle j > i + theiler is filled (see _threshold_rows).
    """
    n_rows = a.shape[0]
    packed = np.zeros((n_rows, (bt.shape[1] + 63) // 64), dtype=np.uint64)
    degree = np.zeros(n_rows, dtype=np.int64)
    for r in prange(_n_iterations(n_rows, auto)):
        keys = np.empty(packed.shape[1] * 64, dtype=np.float64)
        for side in range(2):
            i = _row_of(np.int64(r), side, n_rows, auto)
            if i >= 0:
                start = i + theiler + 1 if auto else 0
                degree[i] = _pack_row(a, i, bt, start, metric, bound, keys, packed)
    return packed, int(degree.sum())


@njit(cache=True, parallel=True)
def _transpose_packed(packed, n_cols):
    n_rows, n_words = packed.shape
    out = np.zeros((n_cols, (n_rows + 63) // 64), dtype=np.uint64)
    # Each iteration owns the 64 output rows of one input word column: no write conflicts.
    for w in prange(n_words):
        for v in range(n_rows):
            word = packed[v, w]
            bit = np.uint64(1) << np.uint64(v & 63)
            while word:
                u = w * 64 + np.int64(_lowest_bit(word))
                out[u, v >> 6] |= bit
                word &= word - np.uint64(1)
    return out


@njit(cache=True, parallel=True)
def _merge_into(packed, other):
    for i in prange(packed.shape[0]):
        for w in range(packed.shape[1]):
            packed[i, w] |= other[i, w]


@njit(cache=True, parallel=True)
def _row_popcounts(packed):
    sums = np.zeros(packed.shape[0], dtype=np.int64)
    for i in prange(packed.shape[0]):
        count = 0
        for w in range(packed.shape[1]):
            count += np.int64(_popcount(packed[i, w]))
        sums[i] = count
    return sums


@njit(cache=True)
def _unpack(packed, n_cols):
    dense = np.zeros((packed.shape[0], n_cols), dtype=np.bool_)
    for i in range(packed.shape[0]):
        for j in range(n_cols):
            dense[i, j] = (packed[i, j >> 6] >> np.uint64(j & 63)) & np.uint64(1)
    return dense


# --------------------------------------------------------------------------------------------
# exact thresholds without the distance matrix

# Below this many candidate pairs every key is collected directly (at most 2 MB); above, a
# random sample of pairs brackets the order statistic.
_DIRECT_PAIRS = 1 << 18
# Half-widths of the bracket around the sampled quantile, in binomial standard deviations; the
# last, unbounded one always succeeds (it is needed with a probability far below 1e-9): it is
# found by bisection of the key range with counting passes, down to at most _BAND_LIMIT pairs.
_BRACKET_WIDTHS = (8.0, 64.0, math.inf)
_BAND_LIMIT = 1 << 22
# Band buffers hold this many times the pairs the sample expects inside the bracket (plus two
# rows); a buffer that overflows costs one more pass, not a wrong result.
_BAND_SLACK = 2.0


def _key_bound(eps: float, strict: bool, metric: int) -> float:
    """The largest key whose distance is <= eps (< eps if strict); -inf when there is none."""
    if metric != 0:
        return math.nextafter(eps, -math.inf) if strict else eps
    if math.isinf(eps):
        return eps

    def within(key: float) -> bool:
        distance = math.sqrt(key)
        return distance < eps if strict else distance <= eps

    key = eps * eps if eps > 0 else 0.0
    while key > 0 and not within(key):
        key = math.nextafter(key, -math.inf)
    if not within(key):
        return -math.inf
    while within(math.nextafter(key, math.inf)):
        key = math.nextafter(key, math.inf)
    return key


def _key_distance(key: float, metric: int) -> float:
    return math.sqrt(key) if metric == 0 else key


def _sample_bracket(a, bt, auto, theiler, metric, quantile, width, rng):
    """Keys [lo, hi] that bracket the ``quantile`` of all candidate keys w.h.p., and the share
    of the sample inside (what the band is expected to hold)."""
    # About one pair in a thousand: the bracket then holds about 2 % of the pairs at M = 2000
    # and 0.7 % at M = 20000 (its width shrinks as 1 / sqrt(sample size)).
    size = min(1 << 18, max(1 << 14, a.shape[0] * bt.shape[1] >> 10))
    rows = rng.integers(0, a.shape[0], size=2 * size)
    cols = rng.integers(0, bt.shape[1], size=2 * size)
    if auto:
        keep = np.abs(rows - cols) > theiler
        rows, cols = rows[keep], cols[keep]
    sample = _sample_keys(a, bt, rows[:size], cols[:size], metric)
    n = sample.size
    spread = width * (math.sqrt(n * quantile * (1.0 - quantile)) + 1.0)
    lo_index = math.floor(quantile * n - spread)
    hi_index = math.ceil(quantile * n + spread)
    inside = [index for index in (lo_index, hi_index) if 0 <= index < n]
    sample = np.partition(sample, inside) if inside else sample
    lo = sample[lo_index] if lo_index >= 0 else -math.inf
    hi = sample[hi_index] if hi_index < n else math.inf
    return float(lo), float(hi), (min(hi_index, n) - max(lo_index, 0)) / n


def _bisect_bracket(a, bt, auto, theiler, metric, rank):
    """A bracket [lo, hi] of keys holding the rank-th key and, unless ties forbid, at most
    _BAND_LIMIT pairs; slow (a counting pass per halving) but with memory O(M)."""

    def count_upto(key):
        return int(_scan_rows(a, bt, auto, theiler, metric, key, key, 1, 0)[0][:, 1].sum())

    lo, hi, n_lo = -1.0, 1.0, 0  # every key is >= 0
    n_hi = count_upto(hi)
    while n_hi < rank:
        hi *= 2.0
        n_hi = count_upto(hi)
    while n_hi - n_lo > _BAND_LIMIT:
        middle = lo + (hi - lo) / 2
        if middle in (lo, hi):  # the band is one value, tied
            break
        n_middle = count_upto(middle)
        if n_middle >= rank:
            hi, n_hi = middle, n_middle
        else:
            lo, n_lo = middle, n_middle
    return lo, hi, (n_hi - n_lo) / max(1, a.shape[0] * bt.shape[1])


def _rate_rows(a, bt, auto, theiler, metric, rank, n_pairs, strict):
    """Threshold at the ``rank``-th smallest candidate distance, exactly, and the packed rows.

    Candidates are the pairs ``j > i + theiler`` when ``auto``, else all ``(i, j)``. A random
    sample gives a bracket [lo, hi] of keys that holds the order statistic with overwhelming
    probability. One pass over the pairs packs those with key < lo, counts the keys below and
    up to the bracket, and keeps key and position of the few inside [lo, hi]; a partial sort of
    these picks the exact value, and their bits are added. Memory: O(M + pairs inside the
    bracket), a few per cent of the pairs; never the distance matrix. (If a band buffer
    overflows, a second pass collects the band; if the sample missed, a wider bracket is tried.)

    Returns ``(eps, packed rows, number of bits set)``.
    """
    rng = np.random.default_rng([a.shape[0], bt.shape[1], rank])
    n_cols = bt.shape[1]
    for width in _BRACKET_WIDTHS:
        if n_pairs <= _DIRECT_PAIRS:
            lo, hi, share = -math.inf, math.inf, 1.0
        elif math.isfinite(width):
            lo, hi, share = _sample_bracket(
                a, bt, auto, theiler, metric, rank / n_pairs, width, rng
            )
        else:
            lo, hi, share = _bisect_bracket(a, bt, auto, theiler, metric, rank)
        n_chunks = 1 if share >= 1.0 or n_pairs <= _DIRECT_PAIRS else 16
        capacity = int(_BAND_SLACK * (min(n_pairs, share * n_pairs) / n_chunks + n_cols))
        counts, packed, chunk_keys, chunk_index, filled = _scan_rows(
            a, bt, auto, theiler, metric, lo, hi, n_chunks, capacity
        )
        below_lo, upto_hi = (int(c) for c in counts.sum(axis=0))
        if below_lo < rank <= upto_hi:
            break
    else:  # unreachable: the last bracket is unbounded
        raise AssertionError("unreachable: the unbounded bracket holds every key")

    if (filled <= capacity).all():
        band_keys = np.concatenate([chunk_keys[c, : filled[c]] for c in range(n_chunks)])
        band_index = np.concatenate([chunk_index[c, : filled[c]] for c in range(n_chunks)])
    else:
        inside = counts[:, 1] - counts[:, 0]
        offsets = np.zeros(inside.size, dtype=np.int64)
        np.cumsum(inside[:-1], out=offsets[1:])
        band_keys = np.empty(int(inside.sum()), dtype=np.float64)
        band_index = np.empty(band_keys.size, dtype=np.int64)
        _collect_band(a, bt, auto, theiler, metric, lo, hi, offsets, band_keys, band_index)
    del chunk_keys, chunk_index
    position = rank - below_lo - 1
    eps = _key_distance(float(np.partition(band_keys, position)[position]), metric)
    bound = _key_bound(eps, strict, metric)
    if lo <= bound <= hi:
        return eps, packed, below_lo + _add_band_bits(packed, n_cols, band_keys, band_index, bound)
    # Strict comparison at lo, or distinct keys with the same square root across a bracket end.
    packed, n_recurrent = _pack_rows(a, bt, auto, theiler, metric, bound)
    return eps, packed, n_recurrent


def _threshold_rows(a, b, *, auto, theiler, metric, rank, n_pairs, eps, strict):
    """``(eps, packed rows, number of recurrent ordered pairs)`` of one recurrence block.

    With ``rank`` the threshold is the rank-th smallest candidate distance, else ``eps``.
    """
    bt = np.ascontiguousarray(b.T)
    if rank is None:
        rows, n_recurrent = _pack_rows(
            a, bt, auto, theiler, metric, _key_bound(eps, strict, metric)
        )
    else:
        eps, rows, n_recurrent = _rate_rows(a, bt, auto, theiler, metric, rank, n_pairs, strict)
    if auto:
        # Only j > i was filled: A = U | U^T.
        _merge_into(rows, _transpose_packed(rows, a.shape[0]))
        n_recurrent *= 2
    return float(eps), rows, n_recurrent


# --------------------------------------------------------------------------------------------
# packed recurrence structures


@dataclass(frozen=True, eq=False)
class PackedRecurrence:
    """A binary (cross-)recurrence matrix stored as bit-packed rows, with its threshold.

    Bit ``j`` of row ``i`` is word ``j // 64``, bit ``j % 64`` of ``rows[i]`` (little-endian
    bit order). Build it with :func:`auto_recurrence` or :func:`cross_recurrence`.

    Attributes
    ----------
    rows : ndarray of uint64, shape (n_rows, ceil(n_cols / 64))
        The packed rows.
    n_cols : int
        Number of columns.
    eps : float
        The threshold used (float64).
    rate : float
        Achieved rate: recurrent pairs / candidate pairs.
    target : float or None
        The requested rate, None when ``eps`` was given explicitly.
    n_recurrent : int
        Number of recurrent (ordered) pairs, i.e. of set bits.
    n_candidates : int
        Number of candidate (ordered) pairs the rate refers to.
    rank : int or None
        ``k``, the number of pairs the rule asked for (None with explicit ``eps``).
    rate_exceeded : bool
        True when ties at ``eps`` made more than ``k`` pairs recurrent (for an auto-recurrence,
        more than ``k`` rounded up to even: its pairs come in symmetric twins).
    """

    rows: np.ndarray
    n_cols: int
    eps: float
    rate: float
    target: float | None
    n_recurrent: int
    n_candidates: int
    rank: int | None
    rate_exceeded: bool

    @property
    def shape(self) -> tuple[int, int]:
        """``(n_rows, n_cols)`` of the unpacked matrix."""
        return (self.rows.shape[0], self.n_cols)

    def to_dense(self) -> np.ndarray:
        """The matrix as a dense boolean array (for small sizes and figures)."""
        return _unpack(self.rows, self.n_cols)

    def row_sums(self) -> np.ndarray:
        """Number of recurrences of each row (the cross-degree of Eq. 7 for ``CR_XY``)."""
        return _row_popcounts(self.rows)

    def transposed(self) -> PackedRecurrence:
        """The transposed matrix (``CR_YX = CR_XY^T``), with the same threshold and counts."""
        return replace(
            self, rows=_transpose_packed(self.rows, self.n_cols), n_cols=self.rows.shape[0]
        )


def _check_states(states: Any, name: str) -> np.ndarray:
    array = np.ascontiguousarray(states, dtype=np.float64)
    if array.ndim != 2 or array.shape[0] < 2 or array.shape[1] < 1:
        raise SignalError(
            f"states of {name} must be a 2-D array (M >= 2 states, dim >= 1), got shape "
            f"{array.shape}"
        )
    if not np.isfinite(array).all():
        raise SignalError(f"states of {name} hold NaN or infinite values")
    return array


def _rank_from_rate(rate: float, n_candidates: int) -> int:
    # README method step 4: ceil in float64, minus 1e-9 so that rate * P a hair above an integer
    # does not take one element too many.
    return max(1, math.ceil(rate * n_candidates - 1e-9))


def auto_recurrence(
    states: Any,
    *,
    rr: float | None = 0.05,
    eps: float | None = None,
    metric: str = "euclidean",
    theiler: int = 0,
    rule: str = "funcnet",
    name: str = "x",
) -> PackedRecurrence:
    """Bit-packed recurrence adjacency ``A_X`` of embedded states (Eq. 2, 5).

    Parameters
    ----------
    states : array_like, shape (M, dim)
        Embedded states (:func:`embed`, or :func:`signal_states` for the rule's input cast).
    rr : float in (0, 1), optional
        Target recurrence rate (default 0.05, the paper's); ignored when ``eps`` is given.
    eps : float, optional
        Explicit threshold, overrides ``rr``.
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in phase space.
    theiler : int
        Pairs with ``|i - j| <= theiler`` are neither recurrent nor candidates of the rate.
    rule : {"funcnet", "pyunicorn"}
        Threshold rule, see the module notes.
    name : str
        How error messages call the signal.

    Returns
    -------
    PackedRecurrence
        ``A_X`` without self-loops; ``rate`` is recurrent pairs over candidate pairs.

    Raises
    ------
    ParameterError
        Bad ``rr``, ``eps``, ``metric``, ``theiler`` (also: too large for M) or ``rule``.
    SignalError
        ``states`` not a finite 2-D array with at least two rows.

    References
    ----------
    Eq. 2 and 5 (section 2.1-2.2).

    Examples
    --------
    >>> import numpy as np
    >>> states = embed(np.sin(np.linspace(0, 8 * np.pi, 251)), dim=3, delay=10)
    >>> a_x = auto_recurrence(states, rr=0.05)
    >>> a_x.rank, a_x.n_recurrent, a_x.n_candidates
    (2657, 2658, 53130)
    >>> round(a_x.eps, 6)
    0.188357
    """
    metric, rule, theiler = _check_options(metric, rule, theiler)
    states = _check_states(states, name)
    n_states = states.shape[0]
    if theiler >= n_states - 1:
        raise ParameterError(
            f"theiler={theiler} excludes every pair of the {n_states} states of {name}"
        )
    pyunicorn = rule == "pyunicorn"
    n_candidates = (n_states - theiler) * (n_states - theiler - 1)
    rank: int | None = None
    if eps is not None:
        eps = _check_eps(eps, "eps" if name == "x" else f"eps of {name}")
        target = None
    else:
        target = _check_rate(rr, "rr")
        if pyunicorn:
            # Index into the sorted full M x M matrix, whose first M entries are the diagonal's
            # zeros; an index among them gives eps = 0 (rank 0): nothing is recurrent (d < 0).
            rank = max(0, int(target * (n_states * n_states - 1)) + 1 - n_states)
        else:
            rank = _rank_from_rate(target, n_candidates)
    threshold, rows, n_recurrent = _threshold_rows(
        states,
        states,
        auto=True,
        theiler=theiler,
        metric=_METRIC_CODE[metric],
        # Each unordered pair appears twice among the ordered candidates.
        rank=None if not rank else (rank + 1) // 2,
        n_pairs=n_candidates // 2,
        eps=0.0 if eps is None else eps,
        strict=pyunicorn,
    )
    return PackedRecurrence(
        rows=rows,
        n_cols=n_states,
        eps=threshold,
        rate=n_recurrent / n_candidates,
        target=target,
        n_recurrent=n_recurrent,
        n_candidates=n_candidates,
        rank=rank,
        # Recurrences come in symmetric pairs: an odd k always gives k + 1 without any tie.
        rate_exceeded=rank is not None and n_recurrent > 2 * ((rank + 1) // 2),
    )


def cross_recurrence(
    x_states: Any,
    y_states: Any,
    *,
    cr: float | None = 0.05,
    eps: float | None = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
) -> PackedRecurrence:
    """Bit-packed cross-recurrence matrix ``CR_XY`` of two sets of embedded states (Eq. 3).

    Parameters
    ----------
    x_states, y_states : array_like, shapes (M_X, dim) and (M_Y, dim)
        Embedded states of X and Y (same ``dim``; ``M_X`` and ``M_Y`` may differ).
    cr : float in (0, 1), optional
        Target cross-recurrence rate over all ``M_X * M_Y`` pairs (default 0.05); ignored when
        ``eps`` is given.
    eps : float, optional
        Explicit threshold ``eps_XY``, overrides ``cr``.
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in the common phase space.
    rule : {"funcnet", "pyunicorn"}
        Threshold rule, see the module notes. The diagonal is kept under both rules.

    Returns
    -------
    PackedRecurrence
        ``CR_XY`` with ``M_X`` rows and ``M_Y`` columns.

    Raises
    ------
    ParameterError
        Bad ``cr``, ``eps``, ``metric`` or ``rule``.
    SignalError
        States not finite 2-D arrays, or of different ``dim``.

    References
    ----------
    Eq. 3 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> cr_xy = cross_recurrence(embed(np.sin(t), 3, 10), embed(np.cos(t), 3, 10), cr=0.05)
    >>> cr_xy.shape, cr_xy.n_recurrent, cr_xy.rank
    ((231, 231), 2669, 2669)
    """
    metric = _check_metric(metric)
    rule = _check_rule(rule)
    x_states = _check_states(x_states, "x")
    y_states = _check_states(y_states, "y")
    if x_states.shape[1] != y_states.shape[1]:
        raise SignalError(
            f"states of x and y must have the same dim, got {x_states.shape[1]} and "
            f"{y_states.shape[1]}"
        )
    n_candidates = x_states.shape[0] * y_states.shape[0]
    pyunicorn = rule == "pyunicorn"
    rank: int | None = None
    if eps is not None:
        eps = _check_eps(eps, "eps_xy")
        target = None
    else:
        target = _check_rate(cr, "cr")
        if pyunicorn:
            rank = int(target * (n_candidates - 1)) + 1
        else:
            rank = _rank_from_rate(target, n_candidates)
    threshold, rows, n_recurrent = _threshold_rows(
        x_states,
        y_states,
        auto=False,
        theiler=0,
        metric=_METRIC_CODE[metric],
        rank=rank,
        n_pairs=n_candidates,
        eps=eps,
        strict=pyunicorn,
    )
    return PackedRecurrence(
        rows=rows,
        n_cols=y_states.shape[0],
        eps=threshold,
        rate=n_recurrent / n_candidates,
        target=target,
        n_recurrent=n_recurrent,
        n_candidates=n_candidates,
        rank=rank,
        rate_exceeded=rank is not None and n_recurrent > rank,
    )


# --------------------------------------------------------------------------------------------
# signals -> ISRN blocks, and dense matrices for small N and figures


def _eps_triple(eps: Any) -> tuple[float | None, float | None, float | None]:
    """``eps=None`` or ``(eps_x, eps_y, eps_xy)``; a None entry falls back to its rate."""
    if eps is None:
        return (None, None, None)
    if isinstance(eps, (str, bytes)) or not hasattr(eps, "__len__") or len(eps) != 3:
        raise ParameterError(f"eps must be None or a triple (eps_x, eps_y, eps_xy), got {eps!r}")
    names = ("eps_x", "eps_y", "eps_xy")
    return tuple(  # type: ignore[return-value]
        None if value is None else _check_eps(value, name)
        for value, name in zip(eps, names, strict=True)
    )


def _isrn_blocks(x, y, *, dim, delay, rr, cr, eps, metric, theiler, rule):
    """Validated ``(A_X, A_Y, CR_XY)`` of two signals (Eq. 4 blocks, packed)."""
    metric, rule, theiler = _check_options(metric, rule, theiler)
    eps_x, eps_y, eps_xy = _eps_triple(eps)
    if eps_x is None or eps_y is None:
        rr = _check_rate(rr, "rr")
    if eps_xy is None:
        cr = _check_rate(cr, "cr")
    x_states = signal_states(x, dim=dim, delay=delay, rule=rule, name="x")
    y_states = signal_states(y, dim=dim, delay=delay, rule=rule, name="y")
    common = {"metric": metric, "rule": rule}
    a_x = auto_recurrence(x_states, rr=rr, eps=eps_x, theiler=theiler, name="x", **common)
    a_y = auto_recurrence(y_states, rr=rr, eps=eps_y, theiler=theiler, name="y", **common)
    cr_xy = cross_recurrence(x_states, y_states, cr=cr, eps=eps_xy, **common)
    return a_x, a_y, cr_xy


def recurrence_matrix(
    x: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float | None = None,
    eps: float | None = None,
    metric: str = "euclidean",
    theiler: int = 0,
    rule: str = "funcnet",
) -> np.ndarray:
    """Dense recurrence adjacency ``A_X`` of a signal (Eq. 2, 5), for small N and figures.

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal, used as given.
    dim, delay : int
        Embedding (Eq. 1).
    rr : float in (0, 1), optional
        Target recurrence rate over the ``(M - w)(M - w - 1)`` candidate pairs; 0.05 when
        neither ``rr`` nor ``eps`` is given.
    eps : float, optional
        Explicit threshold; overrides ``rr``.
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in phase space.
    theiler : int
        ``w``: pairs with ``|i - j| <= w`` are excluded (0 excludes the diagonal only).
    rule : {"funcnet", "pyunicorn"}
        Threshold rule (module notes): k-th order statistic and ``d <= eps``, or pyunicorn's.

    Returns
    -------
    ndarray of bool, shape (M, M)
        ``A_X``: symmetric, no self-loops (Eq. 5). Add ``np.eye(M, dtype=bool)`` for the
        recurrence plot ``R`` of Eq. 2.

    Raises
    ------
    ParameterError, SignalError
        See :func:`auto_recurrence` and :func:`embed`.

    References
    ----------
    Eq. 1, 2 and 5 (section 2.1-2.2).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.sin(np.linspace(0, 8 * np.pi, 251))
    >>> a_x = recurrence_matrix(x, dim=3, delay=10, eps=0.15)
    >>> a_x.shape, int(a_x.sum()), bool((a_x == a_x.T).all())
    ((231, 231), 1944, True)
    """
    states = signal_states(x, dim=dim, delay=delay, rule=rule, name="x")
    rate = 0.05 if rr is None and eps is None else rr
    return auto_recurrence(
        states, rr=rate, eps=eps, metric=metric, theiler=theiler, rule=rule
    ).to_dense()


def cross_recurrence_matrix(
    x: Any,
    y: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    cr: float | None = None,
    eps: float | None = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
    theiler: int = 0,
) -> np.ndarray:
    """Dense cross-recurrence matrix ``CR_XY`` of two signals (Eq. 3).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,)
        The signals, used as given (no normalization); their lengths may differ.
    dim, delay : int
        Embedding (Eq. 1), the same for both.
    cr : float in (0, 1), optional
        Target cross-recurrence rate over the ``M_X * M_Y`` pairs; 0.05 when neither ``cr`` nor
        ``eps`` is given.
    eps : float, optional
        Explicit threshold ``eps_XY``; overrides ``cr``.
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in the common phase space.
    rule : {"funcnet", "pyunicorn"}
        Threshold rule (module notes).
    theiler : int, optional
        Accepted, and validated, like every call of this module takes it; it changes nothing
        here: a Theiler window excludes temporally close states of *one* system from ``A_X``
        and ``A_Y``, while ``CR_XY`` compares states of two systems and keeps its diagonal.

    Returns
    -------
    ndarray of bool, shape (M_X, M_Y)

    Raises
    ------
    ParameterError, SignalError
        See :func:`cross_recurrence` and :func:`embed`.

    References
    ----------
    Eq. 3 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x = np.sin(t)
    >>> cr_xy = cross_recurrence_matrix(x, np.sin(1.5 * t) + 0.3 * x, eps=0.15)
    >>> cr_xy.shape, int(cr_xy.sum())
    ((231, 231), 64)
    """
    _check_options(metric, rule, theiler)
    x_states = signal_states(x, dim=dim, delay=delay, rule=rule, name="x")
    y_states = signal_states(y, dim=dim, delay=delay, rule=rule, name="y")
    rate = 0.05 if cr is None and eps is None else cr
    return cross_recurrence(
        x_states, y_states, cr=rate, eps=eps, metric=metric, rule=rule
    ).to_dense()


def isrn_adjacency(
    x: Any,
    y: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    eps: Any = None,
    metric: str = "euclidean",
    theiler: int = 0,
    rule: str = "funcnet",
) -> np.ndarray:
    """Dense adjacency matrix of the inter-system recurrence network (Eq. 4).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,)
        The signals, used as given.
    dim, delay : int
        Embedding (Eq. 1).
    rr : float in (0, 1)
        Recurrence rate of ``A_X`` and ``A_Y`` (default 0.05).
    cr : float in (0, 1)
        Cross-recurrence rate of ``CR_XY`` (default 0.05).
    eps : (eps_x, eps_y, eps_xy), optional
        Explicit thresholds; each one overrides its rate (a None entry keeps the rate).
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in phase space.
    theiler : int
        Theiler window of ``A_X`` and ``A_Y`` (the cross block has none).
    rule : {"funcnet", "pyunicorn"}
        Threshold rule (module notes).

    Returns
    -------
    ndarray of bool, shape (M_X + M_Y, M_X + M_Y)
        ``[[A_X, CR_XY], [CR_XY^T, A_Y]]``; X's states first.

    Raises
    ------
    ParameterError, SignalError
        Bad parameters, or a signal that is not finite or too short; the message names it.

    References
    ----------
    Eq. 4 and 5 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x, y = np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)
    >>> adjacency = isrn_adjacency(x, y, eps=(0.15, 0.15, 0.05))
    >>> adjacency.shape, bool((adjacency == adjacency.T).all())
    ((462, 462), True)
    """
    blocks = {"dim": dim, "delay": delay, "rr": rr, "cr": cr, "eps": eps, "metric": metric}
    a_x, a_y, cr_xy = _isrn_blocks(x, y, theiler=theiler, rule=rule, **blocks)
    cross = cr_xy.to_dense()
    return np.block([[a_x.to_dense(), cross], [cross.T, a_y.to_dense()]])


# --------------------------------------------------------------------------------------------
# embedding parameters from the data


def _mutual_information(a: np.ndarray, b: np.ndarray, edges: np.ndarray, smoothing: float) -> float:
    from scipy.ndimage import gaussian_filter

    joint, _, _ = np.histogram2d(a, b, bins=(edges, edges))
    if smoothing > 0:
        joint = gaussian_filter(joint, smoothing, mode="constant")
    joint /= joint.sum()
    expected = np.outer(joint.sum(axis=1), joint.sum(axis=0))
    nonzero = joint > 0
    return float((joint[nonzero] * np.log(joint[nonzero] / expected[nonzero])).sum())


def estimate_delay(
    x: Any, *, max_delay: int | None = None, bins: int = 64, smoothing: float = 4.0
) -> int:
    """Embedding delay: the first local minimum of the auto mutual information (Fraser-Swinney).

    ``I(tau)`` between ``x[t]`` and ``x[t + tau]`` is estimated from a 2-D histogram with
    ``bins`` equal-width bins over the range of ``x``, smoothed with a Gaussian kernel of
    ``smoothing`` bins (a kernel density estimate: a plain histogram makes ``I(tau)`` jagged, and
    its first "minimum" an artefact of the binning, on smooth or periodic signals).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal.
    max_delay : int, optional
        Largest delay tried (default ``N // 4``).
    bins : int
        Histogram bins per axis (default 64).
    smoothing : float
        Standard deviation of the smoothing kernel, in bins (default 4; 0 for none).

    Returns
    -------
    int
        The smallest ``tau >= 1`` with ``I(tau - 1) > I(tau) <= I(tau + 1)``.

    Raises
    ------
    ParameterError
        Bad ``max_delay``, ``bins`` or ``smoothing``.
    SignalError
        ``x`` not finite, constant, too short, or without a minimum up to ``max_delay``.

    References
    ----------
    Eq. 1 (the embedding the delay is for); A. M. Fraser and H. L. Swinney, Phys. Rev. A 33,
    1134 (1986).

    Examples
    --------
    A sine of period 100 samples: a quarter period.

    >>> import numpy as np
    >>> estimate_delay(np.sin(2 * np.pi * np.arange(2000) / 100))
    25
    """
    signal = _check_signal(x, "x")
    bins = _check_int(bins, "bins", 2)
    if isinstance(smoothing, bool) or not isinstance(smoothing, numbers.Real) or smoothing < 0:
        raise ParameterError(f"smoothing must be a number >= 0, got {smoothing!r}")
    if max_delay is None:
        max_delay = signal.size // 4
    max_delay = _check_int(max_delay, "max_delay", 1)
    if signal.size < max_delay + 3:
        raise SignalError(
            f"signal x is too short ({signal.size} samples) for max_delay={max_delay}"
        )
    if signal.min() == signal.max():
        raise SignalError("signal x is constant: its mutual information has no minimum")
    edges = np.linspace(signal.min(), signal.max(), bins + 1)

    def information(tau: int) -> float:
        return _mutual_information(signal[: signal.size - tau], signal[tau:], edges, smoothing)

    previous, current = information(0), information(1)
    for tau in range(1, max_delay + 1):
        following = information(tau + 1)
        if previous > current <= following:
            return tau
        previous, current = current, following
    raise SignalError(
        f"the auto mutual information of x has no minimum up to max_delay={max_delay}"
    )


def _nearest_neighbours(states: np.ndarray, p: float) -> tuple[np.ndarray, np.ndarray]:
    # Nearest other state of every state (p-norm); states at distance 0 are skipped by asking
    # for a few neighbours and taking the first at a positive distance.
    from scipy.spatial import cKDTree

    distances, indices = cKDTree(states).query(states, k=min(8, states.shape[0]), p=p)
    positive = distances > 0
    first = np.argmax(positive, axis=1)
    rows = np.arange(states.shape[0])
    found = positive[rows, first]
    return np.where(found, indices[rows, first], -1), np.where(found, distances[rows, first], 0.0)


def estimate_dimension(
    x: Any,
    *,
    delay: int,
    max_dim: int = 10,
    method: str = "fnn",
    rtol: float = 15.0,
    atol: float = 2.0,
    fraction: float = 0.01,
    saturation: float = 0.9,
) -> int:
    """Embedding dimension by false nearest neighbours (Kennel) or Cao's method.

    ``"fnn"``: the nearest neighbour of each state in dimension ``d`` is *false* when adding the
    coordinate ``d + 1`` stretches their distance ``R_d`` by more than ``rtol * R_d`` or makes it
    exceed ``atol`` times the signal's standard deviation; the answer is the first ``d`` whose
    fraction of false neighbours is below ``fraction``.
    ``"cao"``: ``E1(d) = E(d + 1) / E(d)`` with ``E(d)`` the mean stretch of supremum-norm nearest
    neighbour distances from ``d`` to ``d + 1``; the answer is the first ``d`` with
    ``E1(d) >= saturation`` (``E1`` approaching 1 means an added coordinate stops unfolding).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal.
    delay : int
        Embedding delay (e.g. from :func:`estimate_delay`).
    max_dim : int
        Largest dimension tried (default 10); returned when no smaller one qualifies.
    method : {"fnn", "cao"}
        The criterion.
    rtol, atol, fraction : float
        FNN thresholds (Kennel et al.'s 15 and 2, and the accepted fraction 1 %).
    saturation : float
        Cao threshold on ``E1``.

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        Bad ``delay``, ``max_dim``, ``method`` or thresholds.
    SignalError
        ``x`` not finite, constant or too short for ``max_dim + 1`` coordinates.

    References
    ----------
    Eq. 1; M. B. Kennel, R. Brown, H. D. I. Abarbanel, Phys. Rev. A 45, 3403 (1992);
    L. Cao, Physica D 110, 43 (1997).

    Examples
    --------
    The Henon map needs two dimensions:

    >>> import numpy as np
    >>> u, v = 0.1, 0.1
    >>> series = []
    >>> for _ in range(3000):
    ...     u, v = 1 - 1.4 * u * u + v, 0.3 * u
    ...     series.append(u)
    >>> estimate_dimension(series[100:], delay=1)
    2
    """
    signal = _check_signal(x, "x")
    delay = _check_int(delay, "delay", 1)
    max_dim = _check_int(max_dim, "max_dim", 1)
    if method not in ("fnn", "cao"):
        raise ParameterError(f"method must be 'fnn' or 'cao', got {method!r}")
    for value, name in (
        (rtol, "rtol"),
        (atol, "atol"),
        (fraction, "fraction"),
        (saturation, "saturation"),
    ):
        _check_eps(value, name)
    std = float(signal.std())
    if std == 0.0:
        raise SignalError("signal x is constant: no embedding dimension can be estimated")
    n_states = _n_states(signal.size, max_dim + 2, delay, "x", 10)
    stretch = []
    # Cao's E1(d) needs E(d + 1): one dimension more than the FNN test.
    for d in range(1, max_dim + (2 if method == "cao" else 1)):
        states = _delay_rows(signal, d, delay, n_states)
        following = signal[d * delay : d * delay + n_states]
        neighbour, distance = _nearest_neighbours(states, 2.0 if method == "fnn" else np.inf)
        valid = neighbour >= 0
        gap = np.abs(following[valid] - following[neighbour[valid]])
        if method == "fnn":
            false = (gap > rtol * distance[valid]) | (np.hypot(distance[valid], gap) > atol * std)
            if false.mean() < fraction:
                return d
        else:
            stretched = np.maximum(distance[valid], gap)
            stretch.append(float((stretched / distance[valid]).mean()))
            if len(stretch) >= 2 and stretch[-1] / stretch[-2] >= saturation:
                return d - 1
    return max_dim
