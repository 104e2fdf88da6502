"""How sure the asymmetry is: subsampling intervals, estimated rate, for ``C_diff``, ``T_diff``.

A resample keeps a fraction of the window's states, chosen as whole blocks of consecutive
states without replacement, and repeats on them every data-dependent step of the network: it
normalizes the kept states again (``parameters.normalize``: min-max or z-score of the kept
samples), recomputes the thresholds by rate (``A_X``, ``A_Y``, ``CR_XY``) and the measures
``C^XY``, ``C^YX``, ``T^XY``, ``T^YX`` (Eq. 6-10). Resamples are drawn at two sizes, about
two fifths and about three quarters of the states (``FRACTIONS``), and the spread of the
full-window value is extrapolated from them with an **estimated convergence rate** (Bertail,
Politis and Romano 1999). Why this design:

* **no duplicates**: a bootstrap with replacement repeats states, and a repeated state is
  recurrent with its copy and cross-recurrent with the same states, which inflates the
  clustering of exactly the repeated nodes; subsampling without replacement has no copies (a
  full-size block bootstrap that never links copies was measured too: it was too narrow for
  white noise and Lorenz copies, docs/validation/evidence.md section 2);
* **blocks** keep the serial dependence inside each block (block length ``ceil(sqrt(M))`` by
  default);
* **an estimated rate**: the spread of ``C_diff`` over independent realizations does not
  shrink like ``N**-0.5``: measured over 200 realizations it falls like ``N**-0.3`` for white
  noise (min-max normalization: the extremes set the relative scale of X and Y) and like
  ``N**-1`` for Henon and Rossler maps/flows between 140 and 600 samples. A fixed half-sample
  (the delete-half jackknife, exact for rate 1/2) was therefore too narrow for noise and too
  wide for maps. For a kept fraction ``f``, the spread of the resampled values around their
  centre is modelled as ``v(f) = s**2 ((1/f)**(2 beta) - 1)`` (the finite-population form of
  ``var(theta_b) - var(theta_N)`` with ``var(theta_n) ~ n**(-2 beta)``); two fractions give
  ``beta`` (clipped to ``[BETA_MIN, BETA_MAX]`` = ``[0.1, 0.75]``) and the full window's spread
  ``s``. The spreads that give ``beta`` are the same ``level``-quantiles of the absolute
  deviations that scale the interval (Bertail, Politis and Romano estimate the rate from
  quantile ranges too). The fractions 0.4 / 0.75 (the first version: 0.5 / 0.75 and the central
  68 % range for ``beta``) were chosen on seeds 5000-5199 and validated on seeds 2000-2199
  (docs/validation/evidence.md sections 2, 3): between 0.5 and 0.75 the model's spread ratio only
  moves from 1.58 (``beta = 0.1``) to 1.96 (``beta = 1``), within the noise of two spreads of 100
  resamples; going further down than 0.4 fails at 140 samples (11 blocks of 12 states), where a
  subsample of three blocks (0.3: 36 states) no longer shrinks the spread of ``C_diff``;
* **normalization and thresholds again**: under min-max most of the scatter of ``C_diff`` for
  noise comes from the samples' extremes; a resample that kept the window's normalization
  could not see that (a first version covered 0 in 17 % of noise pairs at N = 1000).

The interval is ``d +- sqrt(k_1 q_1 k_2 q_2)`` for the observed difference ``d``, the
``level``-quantiles ``q_i`` of the absolute deviations of the resamples of size ``i`` from their
median, and the rate factors ``k_i = 1 / sqrt((1/f_i)**(2 beta) - 1)`` (``k = 1`` for an exact
half and ``beta = 1/2``): each size extrapolated to the full window, and the two extrapolations
averaged geometrically. Measuring deviations from the resamples' median and not from ``d``
removes the shift a smaller network has; the interval contains ``d`` always. It is
symmetric (Hall 1988): the reflected interval ``[d - k (q_hi - med), d + k (med - q_lo)]`` of
the previous version covered 0 in 85 % of 100 noise pairs (seeds 5000-5099, N = 140 and 300)
where the symmetric one covered 90-93 %: under min-max half of a noise window's resamples lose
an extreme sample and fall back towards 0, and the reflection turns that tail away from 0. The
fraction of the smaller resamples with the sign of ``d`` is a stability figure, not a
probability. Calibration: docs/validation/evidence.md, section 3 (``benchmarks/bench_interval.py``).

Length: over 600 lines because the module notes carry the method's calibration history.

References
----------
P. Bertail, D. N. Politis, J. P. Romano, "On subsampling estimators with unknown rate of
convergence", J. Am. Stat. Assoc. 94, 569-579 (1999).
D. N. Politis, J. P. Romano, M. Wolf, *Subsampling*, Springer (1999), chapters 2-3, 8.
J. Shao, C. F. J. Wu, "A general theory for jackknife variance estimation", Ann. Stat. 17,
1176-1197 (1989) (delete-d jackknife, d = n/2).
H. R. Kuensch, "The jackknife and the bootstrap for general stationary observations", Ann.
Stat. 17, 1217-1241 (1989) (blocks).
P. Hall, "On symmetric bootstrap confidence intervals", J. R. Stat. Soc. B 50, 35-45 (1988).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numba
import numpy as np

from funcnet.core.batch import stacked_measures, windows_per_block
from funcnet.core.embedding import MIN_STATES
from funcnet.core.measures import isrn_measures
from funcnet.core.recurrence import auto_recurrence, cross_recurrence
from funcnet.core.thresholds import signal_thresholds
from funcnet.errors import ParameterError
from funcnet.parameters import NetworkParameters

__all__ = ["AsymmetryInterval", "half_samples", "subsamples", "resampled_differences",
           "rate_factor", "interval_from", "asymmetry_interval", "asymmetry_intervals",
           "interval_kind", "FRACTIONS", "BETA_MIN", "BETA_MAX", "EDGE_RULES",
           "RESAMPLE_MAX_STATES"]

#: Edge rules: the paper's (``mu`` only, the default) and ``mu`` with the interval.
EDGE_RULES: tuple[str, ...] = ("paper", "interval")

#: Kept fractions of the two resample sizes (of the blocks; the exact fraction of states is
#: used in the formulas). Chosen on seeds 5000-5199 among 0.3-0.9 (module notes); the first
#: version used (0.5, 0.75).
FRACTIONS: tuple[float, float] = (0.4, 0.75)
#: Smallest convergence exponent accepted: at ``beta -> 0`` the extrapolated spread diverges;
#: 0.1 caps the widening (``k`` 2.2 at a kept fraction of 0.4, 2.6 at a half; white noise
#: under min-max measured about 0.3 over 140-2000 samples).
BETA_MIN = 0.1
#: Largest exponent accepted. One pair's estimate is noisy (two spreads of 100 resamples);
#: an estimate of 1 where the truth is 0.3 (noise) halves the interval and misses. Chosen on
#: seeds 5000-5099 (100 pairs per process at 140 and 300 samples) over 0.65, 0.75, 0.85, 1:
#: with 1 noise covered 0.89-0.93 and Lorenz 0.80-0.94, with 0.75 0.91-0.95 and 0.83-0.94;
#: validated on seeds 1000-1199; kept for the fractions (0.4, 0.75) after comparing 0.65-0.85
#: on seeds 5000-5199 (benchmarks/bench_interval.py, docs/validation/evidence.md section 3).
BETA_MAX = 0.75
#: Largest resample (kept states) computed by the batched engine's kernel, all resamples and
#: pairs of a network in one compiled pass. Above :data:`~funcnet.core.batch.DIRECT_MAX_STATES`
#: (the limit for plain windows) the kernel still beats the per-resample path here, where each
#: of many pairs shares its signals' recurrences: measured on 18 nodes (153 pairs) of a 26 s
#: UR5 run, one thread each, 1.8x at 855 kept states, 1.4x at 1,254, 1.1x at 1,596, 1.0x at
#: 1,881 and 0.95x at 2,394 (benchmarks/HISTORY.md, "Whole robots with evidence"). The
#: numbers are the same either way.
RESAMPLE_MAX_STATES = 1600


@dataclass(frozen=True)
class AsymmetryInterval:
    """Resampling intervals of ``C_diff`` and ``T_diff`` of one pair.

    Attributes
    ----------
    c_diff, t_diff : float
        The observed differences (Eq. 10).
    c_diff_low, c_diff_high, t_diff_low, t_diff_high : float
        The interval bounds; ``low <= diff <= high`` always.
    c_sign_fraction, t_sign_fraction : float
        Fraction of resamples whose difference has the observed sign (a stability figure).
    level : float
        Nominal coverage.
    resamples : int
        Resamples drawn in all (both sizes).
    c_rate, t_rate : float
        Estimated convergence exponents ``beta`` of the two differences (module notes); 0.5
        when no second resample size was given.
    """

    c_diff: float
    t_diff: float
    c_diff_low: float
    c_diff_high: float
    t_diff_low: float
    t_diff_high: float
    c_sign_fraction: float
    t_sign_fraction: float
    level: float
    resamples: int
    c_rate: float = 0.5
    t_rate: float = 0.5

    @classmethod
    def without_resamples(cls, c_diff: float, t_diff: float,
                          level: float = 0.95) -> AsymmetryInterval:
        """The differences alone (``resamples=0``): bounds and sign fractions NaN.

        Examples
        --------
        >>> iv = AsymmetryInterval.without_resamples(0.1, -0.2)
        >>> iv.c_diff, iv.resamples, bool(np.isnan(iv.c_diff_low))
        (0.1, 0, True)
        """
        nan = float("nan")
        return cls(c_diff=float(c_diff), t_diff=float(t_diff), c_diff_low=nan, c_diff_high=nan,
                   t_diff_low=nan, t_diff_high=nan, c_sign_fraction=nan, t_sign_fraction=nan,
                   level=level, resamples=0)


def half_samples(n_states: int, resamples: int, *, block: int | None = None,
                 seed: int = 0) -> np.ndarray:
    """States kept by each resample: half of the blocks, without replacement, sorted.

    Parameters
    ----------
    n_states : int
        ``M``.
    resamples : int
        Number of resamples ``R``.
    block : int, optional
        Block length (default ``ceil(sqrt(M))``); the last block takes the remainder.
    seed : int

    Returns
    -------
    ndarray of int64, shape (R, n_kept)
        Every row holds the same number of states (blocks of equal length are drawn; the
        remainder block is never drawn when it is shorter).

    Raises
    ------
    ParameterError
        ``resamples < 1`` or fewer than two blocks.

    Examples
    --------
    >>> half_samples(20, 2, block=5, seed=0).shape
    (2, 10)
    """
    return subsamples(n_states, resamples, 0.5, block=block, seed=seed)


def subsamples(n_states: int, resamples: int, fraction: float, *, block: int | None = None,
               seed: int | Sequence[int] = 0) -> np.ndarray:
    """States kept by each resample: ``floor(fraction * n_blocks)`` blocks, without replacement.

    ``fraction=0.5`` with an integer seed gives exactly :func:`half_samples`.

    Parameters
    ----------
    n_states : int
        ``M``.
    resamples : int
        Number of resamples ``R``.
    fraction : float in (0, 1)
        Fraction of the blocks kept.
    block : int, optional
        Block length (default ``ceil(sqrt(M))``).
    seed : int or sequence of int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    ndarray of int64, shape (R, n_kept)

    Raises
    ------
    ParameterError
        ``resamples < 1``, ``fraction`` outside (0, 1), or a fraction that keeps no block or
        every block.

    Examples
    --------
    >>> subsamples(40, 3, 0.75, block=5, seed=0).shape
    (3, 30)
    """
    if isinstance(resamples, bool) or not isinstance(resamples, (int, np.integer)) or \
            resamples < 1:
        raise ParameterError.of("resamples", f"must be an integer >= 1, got {resamples!r}")
    if not 0.0 < fraction < 1.0:
        raise ParameterError.of("fraction", f"must be in (0, 1), got {fraction}")
    length = math.ceil(math.sqrt(n_states)) if block is None else int(block)
    n_blocks = n_states // max(1, length)
    keep = int(fraction * n_blocks)
    if n_blocks < 2 or not 1 <= keep < n_blocks:
        raise ParameterError.of(
            "block", f"gives {n_blocks} block(s) of {length} states in {n_states}; a fraction "
            f"{fraction} of them must keep at least one block and leave one out"
        )
    rng = np.random.default_rng(seed)
    # Blocks start at a random phase, so the remainder is not always the same tail.
    phase = rng.integers(0, n_states - n_blocks * length + 1, size=resamples)
    blocks = np.sort(np.argsort(rng.random((resamples, n_blocks)), axis=1)[:, :keep], axis=1)
    starts = phase[:, None] + blocks * length
    return (starts[:, :, None] + np.arange(length)).reshape(resamples, keep * length)


def _renormalized(states: np.ndarray, method: str | None, dim: int) -> np.ndarray:
    """The kept states normalized again, per channel (``dim`` columns each), as the network
    normalizes a window's samples (every coordinate of a state is a sample of its channel)."""
    if method is None:
        return np.ascontiguousarray(states)
    out = np.empty_like(states)
    for start in range(0, states.shape[1], dim):
        block = states[:, start:start + dim]
        if method == "minmax":
            low, span = block.min(), block.max() - block.min()
        else:
            low, span = block.mean(), block.std()
        out[:, start:start + dim] = (block - low) / span if span > 0 else block
    return out


def resampled_differences(states: Sequence[np.ndarray], pairs: Sequence[tuple[int, int]],
                          chosen: np.ndarray, *,
                          parameters: NetworkParameters | None = None) -> np.ndarray:
    """``C_diff`` and ``T_diff`` of every pair on every resample: shape (pairs, R, 2).

    Each signal's kept states are normalized again and its recurrence thresholded again once
    per resample, and reused in all its pairs (module notes). Resamples of at most
    :data:`RESAMPLE_MAX_STATES` states with thresholds by rate go through
    the batched engine's compiled kernel, all resamples and pairs in one pass (the same
    numbers as one resample at a time, bit for bit).

    Parameters
    ----------
    states : sequence of ndarray (M, c * dim)
        Embedded states of every signal (:func:`funcnet.core.embedding.signal_states`).
    pairs : sequence of (i, j)
        The pairs, as positions in ``states``.
    chosen : ndarray of int, shape (R, n_kept)
        Kept states of each resample (:func:`subsamples`).
    parameters : NetworkParameters, optional
        ``normalize``, ``dim``, ``rr`` (one or one per signal), ``cr``, ``eps``, ``metric``,
        ``theiler``, ``rule``.

    Returns
    -------
    ndarray of float64, shape (len(pairs), R, 2)

    Examples
    --------
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.validation.systems import white_noise
    >>> data = white_noise(200, seed=0)
    >>> states = [embed(data[:, k], 3, 1) for k in (0, 1)]
    >>> resampled_differences(states, [(0, 1)], half_samples(198, 5)).shape
    (1, 5, 2)
    """
    p = parameters if parameters is not None else NetworkParameters()
    thresholds, (cr, cross_eps) = signal_thresholds(p, len(states))
    batched = _batched(states, pairs, chosen, p)
    if batched is not None:
        return batched
    out = np.empty((len(pairs), chosen.shape[0], 2), dtype=np.float64)
    # Thousands of small blocks: a parallel region per call costs more than it saves (17 s
    # instead of 1.4 s for 6 signals x 200 resamples on 2 busy cores). numba's thread count
    # is per calling thread, and restored below.
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        _fill(out, states, pairs, chosen, p, thresholds, cr, cross_eps)
    finally:
        numba.set_num_threads(threads)
    return out


def _fill(out: np.ndarray, states: Sequence[np.ndarray], pairs: Sequence[tuple[int, int]],
          chosen: np.ndarray, p: NetworkParameters, thresholds: list[tuple[float, float | None]],
          cr: float, cross_eps: float | None) -> None:
    for r, kept in enumerate(chosen):
        subsets = [_renormalized(s[kept], p.normalize, p.dim) for s in states]
        autos = {
            i: auto_recurrence(subsets[i], rr=thresholds[i][0], eps=thresholds[i][1],
                               parameters=p)
            for i in sorted({i for pair in pairs for i in pair})
        }
        for k, (i, j) in enumerate(pairs):
            cross = cross_recurrence(subsets[i], subsets[j], cr=cr, eps=cross_eps, parameters=p)
            measures = isrn_measures(autos[i], autos[j], cross)
            out[k, r, 0] = measures.c_diff
            out[k, r, 1] = measures.t_diff


def _batched(states: Sequence[np.ndarray], pairs: Sequence[tuple[int, int]],
             chosen: np.ndarray, p: NetworkParameters) -> np.ndarray | None:
    """:func:`resampled_differences` through the batched engine's kernel, or None.

    A resample's states ``S`` (``n`` kept states of ``D`` coordinates) are laid out column by
    column, ``z[c n + t] = S[t, c]``: the kernel reads state ``t`` of a 1-D signal embedded
    with ``dim = D`` and ``delay = n`` as ``z[t + c n] = S[t, c]``, so each resample is one
    window of the batched engine, already normalized, and the kernel computes its thresholds,
    recurrences and measures with the operations, and in the order, of the per-window path
    (:func:`funcnet.core.batch.stacked_measures`): the same numbers, bit for bit. Applies to
    thresholds by
    rate, nodes of equally many channels, ``MIN_STATES <= n <= RESAMPLE_MAX_STATES`` and finite
    values below 1e38; everything else returns None (the per-resample path, which also raises
    what it raises).
    """
    if p.eps is not None or not pairs:
        return None
    n_resamples, n = chosen.shape
    widths = {int(np.shape(s)[1]) for s in states}
    if len(widths) != 1 or not MIN_STATES <= n <= RESAMPLE_MAX_STATES or p.theiler >= n - 1:
        return None
    (width,) = widths
    # Only the signals of the pairs (the testable pairs may leave some out): each signal's
    # recurrence depends on itself alone, and its rate goes with it.
    used = sorted({i for pair in pairs for i in pair})
    column = {signal: k for k, signal in enumerate(used)}
    if isinstance(p.rr, tuple):
        p = p.replace(rr=tuple(p.rr[i] for i in used))
    states = [states[i] for i in used]
    n_signals = len(states)
    pair_x = np.array([column[i] for i, _ in pairs], dtype=np.int64)
    pair_y = np.array([column[j] for _, j in pairs], dtype=np.int64)
    rows = n * width
    out = np.empty((len(pairs), n_resamples, 2), dtype=np.float64)
    block = windows_per_block(n_signals, n)
    for first in range(0, n_resamples, block):
        kept = chosen[first:first + block]
        table = np.empty((kept.shape[0] * rows, n_signals), dtype=np.float64)
        for r, index in enumerate(kept):
            for s, signal in enumerate(states):
                table[r * rows:(r + 1) * rows, s] = _renormalized(
                    signal[index], p.normalize, p.dim).T.ravel()
        if not (np.abs(table) < 1e38).all():  # NaN compares False too
            return None
        measures = stacked_measures(table, kept.shape[0], width, n, p, pair_x, pair_y)
        out[:, first:first + kept.shape[0], 0] = (measures[:, :, 0] - measures[:, :, 1]).T
        out[:, first:first + kept.shape[0], 1] = (measures[:, :, 2] - measures[:, :, 3]).T
    return out


def _spread(values: np.ndarray, level: float = 0.95) -> float:
    """The ``level``-quantile of the absolute deviations from the median: the spread the
    interval is built from (module notes)."""
    return float(np.quantile(np.abs(values - np.median(values)), level))


def rate_factor(small: np.ndarray, large: np.ndarray, fractions: tuple[float, float], *,
                level: float = 0.95) -> tuple[float, float]:
    """The rate exponent ``beta`` and the factor ``k`` that scales the smaller resamples'
    spread to the full window's (module notes).

    With ``a_i = 1 / f_i`` and spreads ``s_i`` (the ``level``-quantile of the absolute
    deviations from the median) of the resampled values at the kept fractions ``f_1 < f_2``,
    ``beta`` solves
    ``(s_1 / s_2)**2 = (a_1**(2 beta) - 1) / (a_2**(2 beta) - 1)`` (clipped to
    ``[BETA_MIN, BETA_MAX]``) and ``k = 1 / sqrt(a_1**(2 beta) - 1)``.

    Parameters
    ----------
    small, large : ndarray, shape (R,)
        Resampled values at the smaller and the larger fraction.
    fractions : (float, float)
        The exact kept fractions of states, smaller first.
    level : float in (0, 1)
        Quantile of the absolute deviations used as the spread.

    Returns
    -------
    (float, float)
        ``beta`` and ``k``; NaN for both when a spread is NaN (a resample without a value).

    Raises
    ------
    ParameterError
        Fractions not in ``0 < f_1 < f_2 < 1``.

    References
    ----------
    Bertail, Politis and Romano (1999), section 2 (rate from quantile ranges at two subsample
    sizes), with the finite-population form of the spread of subsamples without replacement.

    Examples
    --------
    Spreads of the model with ``beta = 1/2`` (variances ``1/f - 1``: 1.5 and 1/3); the
    quantile of 40,000 values still carries about 1 % error, and ``beta`` amplifies it:

    >>> rng = np.random.default_rng(0)
    >>> beta, k = rate_factor(rng.normal(0, 1.5 ** 0.5, 40_000),
    ...                       rng.normal(0, 1 / 3 ** 0.5, 40_000), (0.4, 0.75))
    >>> round(beta, 1), round(k, 1)
    (0.5, 0.8)
    """
    return _rate(_spread(small, level), _spread(large, level), fractions)


def _rate(s1: float, s2: float, fractions: tuple[float, float]) -> tuple[float, float]:
    """:func:`rate_factor` from the two spreads."""
    f1, f2 = fractions
    if not 0.0 < f1 < f2 < 1.0:
        raise ParameterError.of("fractions", f"must satisfy 0 < f1 < f2 < 1, got {fractions}")
    a1, a2 = 1.0 / f1, 1.0 / f2
    if not (math.isfinite(s1) and math.isfinite(s2)):
        return math.nan, math.nan  # a resample without a value: no rate to report
    if s1 <= 0.0:
        # No spread at the smaller size: nothing to extrapolate, keep the standard rate.
        beta = 0.5
    elif s2 <= 0.0:
        beta = BETA_MAX
    else:
        ratio = (s1 / s2) ** 2

        def g(b: float) -> float:  # increasing in b
            return float((a1 ** (2 * b) - 1) / (a2 ** (2 * b) - 1))

        if ratio <= g(BETA_MIN):
            beta = BETA_MIN
        elif ratio >= g(BETA_MAX):
            beta = BETA_MAX
        else:
            low, high = BETA_MIN, BETA_MAX
            for _ in range(50):
                mid = 0.5 * (low + high)
                low, high = (mid, high) if g(mid) < ratio else (low, mid)
            beta = 0.5 * (low + high)
    return beta, 1.0 / math.sqrt(a1 ** (2 * beta) - 1.0)


def _bounds(observed: float, values: np.ndarray, half: float) -> tuple[float, float, float]:
    # Symmetric: d +- half, half from the level-quantiles of the resamples' absolute
    # deviations from their median. Under min-max the resamples of noise are often bimodal
    # (half of them lose an extreme sample and fall back towards 0); a reflected interval then
    # barely extends towards 0.
    sign = np.sign(observed)
    same = float(np.mean(np.sign(values) == sign)) if sign != 0 else float(np.mean(values == 0))
    return observed - half, observed + half, same


def _extrapolated(small: np.ndarray, large: np.ndarray, fractions: tuple[float, float],
                  level: float) -> tuple[float, float]:
    """``beta`` and the half-width ``sqrt(k_1 q_1 k_2 q_2)``: both sizes' spreads scaled to the
    full window with the estimated rate, averaged geometrically (module notes)."""
    q_small, q_large = _spread(small, level), _spread(large, level)
    beta, k_small = _rate(q_small, q_large, fractions)
    k_large = 1.0 / math.sqrt((1.0 / fractions[1]) ** (2 * beta) - 1.0)
    small_half, large_half = k_small * q_small, k_large * q_large
    if small_half > 0.0 and large_half > 0.0:
        return beta, math.sqrt(small_half * large_half)
    # one size without spread (a few distinct values): the other size's extrapolation alone,
    # not a zero-width interval
    return beta, max(small_half, large_half)


def interval_from(c_diff: float, t_diff: float, values: np.ndarray, *,
                  level: float = 0.95, rate_values: np.ndarray | None = None,
                  fractions: tuple[float, float] | None = None) -> AsymmetryInterval:
    """The intervals of one pair from its resampled differences (module notes).

    Parameters
    ----------
    c_diff, t_diff : float
        Observed differences.
    values : ndarray, shape (R, 2)
        Resampled ``(C_diff, T_diff)`` at the smaller fraction (a row of
        :func:`resampled_differences`).
    level : float in (0, 1)
    rate_values : ndarray, shape (R2, 2), optional
        The same at the larger fraction. Without it the spread of ``values`` is used as it is
        (``k = 1``: the plain subsample interval, rate 1/2 for an exact half).
    fractions : (float, float), optional
        The exact kept fractions of states of ``values`` and ``rate_values``; needed with
        ``rate_values``.

    Returns
    -------
    AsymmetryInterval

    Raises
    ------
    ParameterError
        ``level`` outside (0, 1), or ``rate_values`` without valid ``fractions``.

    Examples
    --------
    >>> values = np.column_stack([np.linspace(-0.1, 0.1, 201), np.zeros(201)])
    >>> iv = interval_from(0.05, 0.0, values)
    >>> round(iv.c_diff_low, 3), round(iv.c_diff_high, 3), iv.t_diff_low
    (-0.045, 0.145, 0.0)
    """
    if not 0.0 < level < 1.0:
        raise ParameterError.of("level", f"must be in (0, 1), got {level}")
    total = int(values.shape[0])
    if rate_values is None:
        c_rate = t_rate = 0.5
        c_half, t_half = _spread(values[:, 0], level), _spread(values[:, 1], level)
    else:
        if fractions is None:
            raise ParameterError.of("fractions", "must be given with rate_values")
        c_rate, c_half = _extrapolated(values[:, 0], rate_values[:, 0], fractions, level)
        t_rate, t_half = _extrapolated(values[:, 1], rate_values[:, 1], fractions, level)
        total += int(rate_values.shape[0])
    c_low, c_high, c_same = _bounds(c_diff, values[:, 0], c_half)
    t_low, t_high, t_same = _bounds(t_diff, values[:, 1], t_half)
    return AsymmetryInterval(
        c_diff=float(c_diff), t_diff=float(t_diff),
        c_diff_low=float(c_low), c_diff_high=float(c_high),
        t_diff_low=float(t_low), t_diff_high=float(t_high),
        c_sign_fraction=c_same, t_sign_fraction=t_same,
        level=float(level), resamples=total, c_rate=float(c_rate), t_rate=float(t_rate),
    )


def asymmetry_intervals(states: Sequence[np.ndarray], pairs: Sequence[tuple[int, int]],
                        observed: Sequence[tuple[float, float]], *,
                        parameters: NetworkParameters | None = None, resamples: int = 200,
                        level: float = 0.95, block: int | None = None,
                        seed: int = 0) -> list[AsymmetryInterval]:
    """Intervals of every pair of a network from one set of resamples (module notes).

    ``resamples - resamples // 2`` resamples keep ``FRACTIONS[0]`` of the blocks
    (:func:`subsamples` with ``seed``) and ``resamples // 2`` keep ``FRACTIONS[1]`` (a
    separate stream);
    each signal is normalized and thresholded again once per resample, for all its pairs.

    Parameters
    ----------
    states : sequence of ndarray (M, c * dim)
        Embedded states of every signal.
    pairs : sequence of (i, j)
        Positions in ``states``.
    observed : sequence of (c_diff, t_diff)
        The observed differences of each pair.
    parameters : NetworkParameters, optional
    resamples : int
        In all; with 1 the plain subsample interval of the smaller size (no rate).
    level : float in (0, 1)
    block : int, optional
        Block length, default ``ceil(sqrt(M))``.
    seed : int

    Returns
    -------
    list of AsymmetryInterval
        One per pair, in order.

    Raises
    ------
    ParameterError
        Bad ``resamples``, ``level`` or ``block``; a window too short for the two sizes.

    Examples
    --------
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.validation.systems import white_noise
    >>> data = white_noise(200, seed=0)
    >>> states = [embed(data[:, k], 3, 1) for k in (0, 1)]
    >>> [iv] = asymmetry_intervals(states, [(0, 1)], [(0.0, 0.0)], resamples=10)
    >>> iv.c_diff_low <= 0.0 <= iv.c_diff_high, iv.resamples
    (True, 10)
    """
    if isinstance(resamples, bool) or not isinstance(resamples, (int, np.integer)) or \
            resamples < 1:
        raise ParameterError.of("resamples", f"must be an integer >= 1, got {resamples!r}")
    if not 0.0 < level < 1.0:
        raise ParameterError.of("level", f"must be in (0, 1), got {level}")
    n_states = int(np.shape(states[0])[0])
    small = subsamples(n_states, resamples - resamples // 2, FRACTIONS[0], block=block,
                       seed=seed)
    values = resampled_differences(states, pairs, small, parameters=parameters)
    if resamples < 2:
        # One resample cannot give a rate: the plain subsample interval (k = 1).
        return [interval_from(c, t, values[k], level=level) for k, (c, t) in enumerate(observed)]
    # A separate stream for the larger size: the smaller resamples do not depend on it.
    large = subsamples(n_states, resamples // 2, FRACTIONS[1], block=block, seed=(seed, 1))
    fractions = (small.shape[1] / n_states, large.shape[1] / n_states)
    larger = resampled_differences(states, pairs, large, parameters=parameters)
    return [
        interval_from(c_diff, t_diff, values[k], level=level, rate_values=larger[k],
                      fractions=fractions)
        for k, (c_diff, t_diff) in enumerate(observed)
    ]


def asymmetry_interval(x_states: np.ndarray, y_states: np.ndarray, *, c_diff: float,
                       t_diff: float, parameters: NetworkParameters | None = None,
                       resamples: int = 200, level: float = 0.95, block: int | None = None,
                       seed: int = 0) -> AsymmetryInterval:
    """Subsampling interval with an estimated rate of ``C_diff`` and ``T_diff`` of one pair.

    :func:`asymmetry_intervals` for a single pair (module notes).

    Parameters
    ----------
    x_states, y_states : ndarray, shape (M, c * dim)
        The pair's embedded states, built from the normalized signals.
    c_diff, t_diff : float
        The observed differences (:func:`funcnet.core.measures.cross_measures` on the same states).
    parameters : NetworkParameters, optional
        Normalization, embedding dimension (for the channels), thresholds, metric.
    resamples : int
        In all (both sizes).
    level : float in (0, 1)
    block : int, optional
        Block length, default ``ceil(sqrt(M))``.
    seed : int

    Returns
    -------
    AsymmetryInterval

    Raises
    ------
    ParameterError
        Bad ``level``, ``resamples``, ``block``, or states of different lengths.

    References
    ----------
    Bertail, Politis and Romano (1999); Politis, Romano and Wolf (1999); Kuensch (1989).

    Examples
    --------
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.core.measures import cross_measures
    >>> from funcnet.validation.systems import logistic_pair
    >>> data = logistic_pair(300, 3.7, 4.0, seed=0)
    >>> x = (data[:, 0] - data[:, 0].min()) / np.ptp(data[:, 0])
    >>> y = (data[:, 1] - data[:, 1].min()) / np.ptp(data[:, 1])
    >>> m = cross_measures(x, y, delay=1, warn=False)
    >>> iv = asymmetry_interval(embed(x, 3, 1), embed(y, 3, 1), c_diff=m.c_diff,
    ...                         t_diff=m.t_diff, resamples=50,
    ...                         parameters=m.parameters)
    >>> bool(0 < iv.c_diff_low <= m.c_diff <= iv.c_diff_high), iv.c_sign_fraction
    (True, 1.0)
    """
    if np.shape(x_states)[0] != np.shape(y_states)[0]:
        raise ParameterError.of("y_states", "must have as many states as x_states")
    return asymmetry_intervals(
        [np.asarray(x_states, dtype=np.float64), np.asarray(y_states, dtype=np.float64)],
        [(0, 1)], [(c_diff, t_diff)], parameters=parameters, resamples=resamples, level=level,
        block=block, seed=seed,
    )[0]


def interval_kind(diff: float, low: float, high: float, mu: float) -> str:
    """The interval edge rule for one measure: directed only if the interval excludes 0 and
    ``|diff| >= mu``.

    Negative reads X -> Y, as the paper's rule (:func:`funcnet.network.rule.edge_kind`).

    Parameters
    ----------
    diff, low, high : float
        Observed difference and its interval.
    mu : float

    Returns
    -------
    str
        ``"x->y"``, ``"y->x"`` or ``"bidirectional"``.

    Examples
    --------
    >>> interval_kind(-0.08, -0.12, -0.03, 0.05), interval_kind(-0.08, -0.15, 0.01, 0.05)
    ('x->y', 'bidirectional')
    """
    if high < 0 and diff <= -mu:
        return "x->y"
    if low > 0 and diff >= mu:
        return "y->x"
    return "bidirectional"
