"""The recurrence thresholds: a block's threshold from its rate, and each signal's of a network.

Every threshold search of the core lives here. :func:`signal_thresholds` gives each signal's
(rate, explicit eps) and the cross block's from the parameters; :func:`block_threshold` one
block's; :func:`threshold_rows` finds the threshold of a rate and packs the block's rows with it.
The threshold of a rate is an exact order statistic of pairwise distances without the distance
matrix: the ``rank``-th smallest candidate distance,
with the rank computed exactly from the rate as written in decimal
(:func:`_rank_from_rate`), or pyunicorn 1.0.0's float index (:func:`_pyunicorn_rank`).

Selection (:func:`_rate_rows`): a random sample of distances brackets the order statistic; one
pass over the pairs packs those below the bracket, counts, and keeps only the few pairs inside it
(a few per cent), whose partial sort gives the exact value. If the sample misses (probability
far below 1e-9) a wider bracket is tried, and last a bisection of the key range by counting
passes (memory one row of keys per thread).

Heavy ties (a signal that rests: a third of its pairs at distance 0) put millions of pairs on
one key. The band is then never collected: counting passes find the tied order statistic
directly (:func:`_narrow`), and one more pass packs the rows, so memory stays O(M) per thread
plus the packed rows.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from fractions import Fraction
from typing import Any, TypeVar

import numpy as np

from funcnet.core._isrn_kernels import (
    _add_band_bits,
    _collect_band,
    _compact_band,
    _count_keys,
    _merge_into,
    _pack_rows,
    _sample_keys,
    _scan_rows,
    _transpose_packed,
)
from funcnet.core._keys import key_bound as _key_bound, key_distance as _key_distance
from funcnet.errors import ParameterError
from funcnet.parameters import NetworkParameters, check_eps_value, check_rate

Array = np.ndarray
_Rank = TypeVar("_Rank", int, np.ndarray)

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


def _draw(rng: np.random.Generator, n_rows: int, n_cols: int) -> tuple[Array, Array]:
    """Rows and columns of twice the sample's pairs (the auto block drops its Theiler band)."""
    # About one pair in a thousand: the bracket then holds about 2 % of the pairs at M = 2000
    # and 0.7 % at M = 20000 (its width shrinks as 1 / sqrt(sample size)).
    size = min(1 << 18, max(1 << 14, n_rows * n_cols >> 10))
    return rng.integers(0, n_rows, size=2 * size), rng.integers(0, n_cols, size=2 * size)


@functools.lru_cache(maxsize=8)
def _first_draw(n_rows: int, n_cols: int, rank: int) -> tuple[Array, Array, Mapping[str, Any]]:
    """The first :func:`_draw` of the generator seeded ``[n_rows, n_cols, rank]``, and the
    generator's state after it. The blocks of a network share their size and rank: the cross
    blocks of all its pairs draw the same sample positions, made once."""
    rng = np.random.default_rng([n_rows, n_cols, rank])
    rows, cols = _draw(rng, n_rows, n_cols)
    rows.flags.writeable = cols.flags.writeable = False  # shared by every caller
    return rows, cols, rng.bit_generator.state


def _sample_bracket(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, quantile: float, width: float,
    draw: tuple[Array, Array],
) -> tuple[float, float, float]:
    """Keys [lo, hi] that bracket the ``quantile`` of all candidate keys w.h.p., and the share
    of the sample inside (what the band is expected to hold), from a :func:`_draw`."""
    rows, cols = draw
    size = rows.size // 2
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


def _key_bits(key: float) -> int:
    """Keys are >= 0: their float64 bit patterns, read as integers, are in the same order."""
    return int(np.float64(key).view(np.int64)) if key >= 0 else -1


def _bits_key(bits: int) -> float:
    return float(np.int64(bits).view(np.float64))


def _narrow(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, rank: int, lo_bits: int,
    n_lo: int, hi_bits: int, n_hi: int, probes: tuple[float, ...] = (),
) -> tuple[float, float, bool]:
    """Shrink a bracket of the rank-th key by counting passes (memory one row per thread).

    The bracket is (lo, hi] as bit patterns (:func:`_key_bits`; -1 is below every key) with
    ``n_lo = #key <= lo < rank <= n_hi = #key <= hi``. Each pass counts the keys below and up
    to one value: first the ``probes``, then the middle bit pattern, so a value tied millions of
    times is recognized as the order statistic when probed. Returns ``(lo, hi, exact)``:
    ``exact`` when the rank-th key is ``hi`` (then ``lo == hi``), else a band [lo, hi] (lo the
    smallest key above the bracket's lower end) of at most ``_BAND_LIMIT`` keys.
    """
    queue = [_key_bits(value) for value in probes]
    while True:
        if hi_bits - lo_bits <= 1:  # (lo, hi] holds the single value hi
            return _bits_key(hi_bits), _bits_key(hi_bits), True
        if not queue and n_hi - n_lo <= _BAND_LIMIT:
            return _bits_key(lo_bits + 1), _bits_key(hi_bits), False
        if queue:
            middle = queue.pop(0)
            if not lo_bits < middle <= hi_bits:
                continue
        else:
            middle = lo_bits + (hi_bits - lo_bits) // 2
        below, upto = (int(c) for c in _count_keys(a, bt, auto, theiler, metric,
                                                   _bits_key(middle)))
        if below < rank <= upto:
            return _bits_key(middle), _bits_key(middle), True
        if upto < rank:
            lo_bits, n_lo = middle, upto
        else:  # #key <= (middle - 1 ulp) is #key < middle
            hi_bits, n_hi = middle - 1, below


def _bisect_bracket(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, rank: int
) -> tuple[float, float, float]:
    """A bracket [lo, hi] of keys holding the rank-th key and, unless ties forbid, at most
    _BAND_LIMIT pairs; slow (a counting pass per halving) but with memory O(M) per thread.
    ``lo == hi`` when the passes met the rank-th key itself."""
    hi = 1.0
    n_hi = int(_count_keys(a, bt, auto, theiler, metric, hi)[1])
    while n_hi < rank:
        hi *= 2.0
        n_hi = int(_count_keys(a, bt, auto, theiler, metric, hi)[1])
    lo, hi, exact = _narrow(a, bt, auto, theiler, metric, rank, -1, 0, _key_bits(hi), n_hi)
    n_pairs = max(1, a.shape[0] * bt.shape[1])
    return lo, hi, 1.0 / n_pairs if exact else min(1.0, _BAND_LIMIT / n_pairs)


def _exact_rows(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, key: float, strict: bool
) -> tuple[float, Array, int]:
    """Threshold and packed rows when the order statistic's key is known: one packing pass."""
    eps = _key_distance(key, metric)
    packed, n_recurrent = _pack_rows(a, bt, auto, theiler, metric, _key_bound(eps, strict, metric))
    return eps, packed, n_recurrent


def _rate_rows(
    a: Array, bt: Array, auto: bool, theiler: int, metric: int, rank: int, n_pairs: int,
    strict: bool,
) -> tuple[float, Array, int]:
    """Threshold at the ``rank``-th smallest candidate distance, exactly, and the packed rows.

    Candidates are the pairs ``j > i + theiler`` when ``auto``, else all ``(i, j)``. A random
    sample gives a bracket [lo, hi] of keys that holds the order statistic with overwhelming
    probability. One pass over the pairs packs those with key < lo, counts the keys below and
    up to the bracket, and keeps key and position of the few inside [lo, hi]; a partial sort of
    these picks the exact value, and their bits are added. Memory: O(M + pairs inside the
    bracket), a few per cent of the pairs; never the distance matrix. (If a band buffer
    overflows, a second pass collects the band, narrowed first by counting passes when it is
    large -- heavy ties; if the sample missed, a wider bracket is tried.)

    Returns ``(eps, packed rows, number of bits set)``.
    """
    n_cols = bt.shape[1]
    # the generator seeded [rows, cols, rank]: its first draw made once per size and rank, its
    # state after it resumed for a wider bracket's draw
    state: Mapping[str, Any] | None = None
    for width in _BRACKET_WIDTHS:
        if n_pairs <= _DIRECT_PAIRS:
            lo, hi, share = -math.inf, math.inf, 1.0
        elif math.isfinite(width):
            if state is None:
                rows, cols, state = _first_draw(a.shape[0], n_cols, rank)
            else:
                rng = np.random.default_rng()
                rng.bit_generator.state = state
                rows, cols = _draw(rng, a.shape[0], n_cols)
                state = rng.bit_generator.state
            lo, hi, share = _sample_bracket(
                a, bt, auto, theiler, metric, rank / n_pairs, width, (rows, cols)
            )
        else:
            lo, hi, share = _bisect_bracket(a, bt, auto, theiler, metric, rank)
            if lo == hi:
                return _exact_rows(a, bt, auto, theiler, metric, hi, strict)
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

    overflow = not (filled <= capacity).all()
    if overflow and (lo == hi or upto_hi - below_lo > _BAND_LIMIT):
        # Too many pairs in the band to hold (ties): count instead of collecting.
        del packed, chunk_keys, chunk_index
        if lo == hi:
            return _exact_rows(a, bt, auto, theiler, metric, hi, strict)
        lo, hi, exact = _narrow(
            a, bt, auto, theiler, metric, rank, _key_bits(lo) - 1 if lo >= 0 else -1, below_lo,
            _key_bits(hi), upto_hi, probes=(lo, hi),
        )
        if exact:
            return _exact_rows(a, bt, auto, theiler, metric, hi, strict)
        n_chunks, capacity = 16, int(_BAND_SLACK * (_BAND_LIMIT / 16 + n_cols))
        counts, packed, chunk_keys, chunk_index, filled = _scan_rows(
            a, bt, auto, theiler, metric, lo, hi, n_chunks, capacity
        )
        below_lo, upto_hi = (int(c) for c in counts.sum(axis=0))
        overflow = not (filled <= capacity).all()
    if not overflow:
        # The band in place, at the front of the chunk buffers (a copy would cost a page
        # fault per 4 KiB of it).
        n_band = _compact_band(chunk_keys, chunk_index, filled)
        band_keys = chunk_keys.reshape(-1)[:n_band]
        band_index = chunk_index.reshape(-1)[:n_band]
    else:
        del chunk_keys, chunk_index
        inside = counts[:, 1] - counts[:, 0]
        offsets = np.zeros(inside.size, dtype=np.int64)
        np.cumsum(inside[:-1], out=offsets[1:])
        band_keys = np.empty(int(inside.sum()), dtype=np.float64)
        band_index = np.empty(band_keys.size, dtype=np.int64)
        _collect_band(a, bt, auto, theiler, metric, lo, hi, offsets, band_keys, band_index)
    position = rank - below_lo - 1
    eps = _key_distance(float(np.partition(band_keys, position)[position]), metric)
    bound = _key_bound(eps, strict, metric)
    if lo <= bound <= hi:
        return eps, packed, below_lo + _add_band_bits(packed, band_keys, band_index, bound)
    # Strict comparison at lo, or distinct keys with the same square root across a bracket end.
    del packed
    packed, n_recurrent = _pack_rows(a, bt, auto, theiler, metric, bound)
    return eps, packed, n_recurrent


# --------------------------------------------------------------------------------------------
# ranks


def _rank_from_rate(rate: float, n_candidates: int) -> int:
    """``k = max(1, ceil(rate * P))`` for the rate as written in decimal, exactly.

    ``repr`` gives the shortest decimal that reads back as the same float (``0.07``, not
    ``0.070000000000000007``); the product is a rational, so no float rounding can add a pair.

    Examples
    --------
    >>> 0.07 * 399_980_000  # float64 lands above the integer
    27998600.000000004
    >>> _rank_from_rate(0.07, 399_980_000)
    27998600
    >>> _rank_from_rate(0.05, 10)
    1
    """
    return max(1, math.ceil(Fraction(repr(float(rate))) * n_candidates))


def _pyunicorn_rank(rate: float, n_states: int | None, n_candidates: int) -> int:
    """pyunicorn 1.0.0's rank: index ``int(rate * (P - 1))`` of the sorted full matrix, in float.

    For an auto-recurrence (``n_states`` given) the full matrix holds the ``M`` zeros of the
    diagonal first, and ``n_candidates`` is ``M**2``; an index among them gives rank 0
    (threshold 0, nothing recurrent with ``d < 0``). Otherwise (cross) the rank is index + 1.

    Examples
    --------
    >>> _pyunicorn_rank(0.05, None, 231 * 231), _pyunicorn_rank(0.05, 231, 231 * 231)
    (2669, 2438)
    """
    index = int(rate * (n_candidates - 1))
    if n_states is None:
        return index + 1
    return max(0, index + 1 - n_states)


def _auto_candidates(n_states: int, theiler: int) -> int:
    """Ordered candidate pairs ``|i - j| > theiler`` of an auto-recurrence of ``n_states``."""
    return (n_states - theiler) * (n_states - theiler - 1)


def _auto_rank(rate: float, n_states: int, theiler: int, pyunicorn: bool) -> int:
    """Rank of an auto-recurrence's threshold among its ordered candidates, by the exact rule
    or pyunicorn's (0: nothing recurrent, threshold 0).

    Examples
    --------
    >>> _auto_rank(0.05, 231, 0, False), _auto_rank(0.05, 231, 0, True)
    (2657, 2438)
    """
    if pyunicorn:
        return _pyunicorn_rank(rate, n_states, n_states * n_states)
    return _rank_from_rate(rate, _auto_candidates(n_states, theiler))


def _unordered_rank(rank: _Rank) -> _Rank:
    """An auto-recurrence's rank among its unordered candidates ``j > i + theiler`` from its
    rank among the ordered ones, each unordered pair being two (0 stays 0: nothing recurrent).

    Recurrences come in symmetric pairs: an odd rank ``k`` always gives ``k + 1`` recurrences
    without any tie, so only a count beyond ``2 * _unordered_rank(k)`` means that ties pushed
    the rate above its target.

    Examples
    --------
    >>> _unordered_rank(2657), _unordered_rank(2438), _unordered_rank(0)
    (1329, 1219, 0)
    """
    return (rank + 1) // 2


def _cross_rank(rate: float, n_candidates: int, pyunicorn: bool) -> int:
    """Rank of a cross-recurrence's threshold among its ``n_candidates`` pairs, by the exact
    rule or pyunicorn's.

    Examples
    --------
    >>> _cross_rank(0.05, 231 * 231, False), _cross_rank(0.05, 231 * 231, True)
    (2669, 2669)
    """
    if pyunicorn:
        return _pyunicorn_rank(rate, None, n_candidates)
    return _rank_from_rate(rate, n_candidates)


# --------------------------------------------------------------------------------------------
# the thresholds of a recurrence block and of a network's signals


def _single(value: Any, name: str, what: str) -> Any:
    """A parameter that must be one value for one block (not one per signal)."""
    if isinstance(value, tuple):
        raise ParameterError.of(
            name, f"must be one {what} for one recurrence block, got {value!r}; pass it explicitly"
        )
    return value


def block_threshold(
    p: NetworkParameters, rate: float | None, eps: float | None, *, auto: bool
) -> tuple[float | None, float | None]:
    """``(target rate, explicit eps)`` of one block: explicit arguments, else the parameters."""
    if eps is not None:
        return None, check_eps_value(eps, "eps")
    if rate is not None:
        return check_rate(rate, "rr" if auto else "cr"), None
    auto_eps, cross_eps = p.eps if p.eps is not None else (None, None)
    given = _single(auto_eps, "eps", "threshold") if auto else cross_eps
    if given is not None:
        return None, float(given)
    return (float(_single(p.rr, "rr", "rate")) if auto else p.cr), None


def threshold_rows(
    a: np.ndarray, b: np.ndarray, *, auto: bool, theiler: int, metric: int, rank: int | None,
    n_pairs: int, eps: float, strict: bool,
) -> tuple[float, np.ndarray, int]:
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
    return float(eps), rows, int(n_recurrent)


def _per_signal(value: Any, n_signals: int, name: str, what: str) -> list[Any]:
    """One entry per signal from one value or a tuple of one per signal."""
    if isinstance(value, tuple):
        if len(value) != n_signals:
            raise ParameterError.of(
                name,
                f"must be one {what} or one per signal ({n_signals}), got {len(value)}: "
                f"{value!r}",
            )
        return list(value)
    return [value] * n_signals


def signal_thresholds(
    p: NetworkParameters, n_signals: int
) -> tuple[list[tuple[float, float | None]], tuple[float, float | None]]:
    """``([(rr_i, eps_i) per signal], (cr, eps_cross))``; an eps of None keeps the rate."""
    auto_eps, cross_eps = p.eps if p.eps is not None else (None, None)
    rates = _per_signal(p.rr, n_signals, "rr", "rate")
    thresholds = _per_signal(auto_eps, n_signals, "eps", "auto threshold")
    return list(zip(rates, thresholds, strict=True)), (p.cr, cross_eps)
