"""Whether two signals are coupled at all: a joint-recurrence test with time-shift surrogates.

The ISRN asymmetry never uses time alignment (shifting Y leaves ``C_diff`` unchanged), so it
cannot say whether X and Y are coupled. This test does: it pairs the state ``x_t`` with
``y_t``.

Statistic
    ``phi``: the correlation, over the pairs of times ``i < j`` of a window of ``L`` states
    (``|i - j| > theiler``), of the recurrence indicators ``A_X[i, j]`` and ``A_Y[i, j]`` --
    the excess of joint recurrences (Romano et al. 2004) over what the two recurrence rates
    of the window give by chance, scaled to [-1, 1]. ``A_X`` and ``A_Y`` are each signal's
    recurrence matrix over the whole window (thresholds by rate, :mod:`funcnet.core.recurrence`),
    computed once.

Surrogates: a lattice of non-circular time shifts on equal-length windows
    A surrogate pairs ``x[a + i]`` with ``y[a + o + i]``, ``i < L``, for the offsets
    ``o = +-s0, +-2 s0, ..., +-k s0``; the observed window is the lattice's point ``o = 0``, on
    the same length ``L = M - k s0``; every window is centred in the data. Nothing wraps
    around: a circular shift joins the end of Y to its start, so the pairs of times that
    straddle the wrap get a different lag in Y than in X; two independent copies of the same
    oscillator recur at the same lags, the wrap destroys exactly that, and the circular test
    rejected independence in about 20 % of such pairs. With equal-length windows and
    no wrap, every surrogate is, when X and Y are independent and each is stationary, a draw
    of the same law as the observed window, whatever the signals' periods.

    ``s0`` is the larger decorrelation time of the two signals (first lag where the
    autocorrelation falls below 1/e), at least the embedding span ``(dim - 1) * delay + 1``.
    Offsets closer than that give nearly equal statistics: a prototype that used every offset
    beyond ``s0`` had clumps of near-copies among its surrogates, and the observed window, alone
    at offset 0, fell outside them too often (8.5 % false positives for AR(1) at N = 140). On
    the lattice the observed window has neighbours at ``+-s0`` like every surrogate. At most
    half the window is shifted (``k s0 <= M / 2``), which caps ``K`` at ``2 floor(M / (2 s0))``
    in short windows (the result reports the ``K`` used).

p-value
    ``(1 + #{surrogate phi >= observed phi}) / (K + 1)`` (one-sided: coupling adds joint
    recurrences). No p-value is below ``1 / (K + 1)``: with ``m`` pairs a lone discovery under
    Benjamini-Hochberg at level ``alpha`` needs ``K >= m / alpha - 1``
    (:func:`default_surrogates`).

Direction (tested, kept as a secondary reading; see docs/validation/evidence.md for its error rates)
    The mean conditional probabilities of recurrence ``MCR(X|Y) = <sum_j JR_ij / sum_j
    A_Y[i, j]>_i`` and ``MCR(Y|X)`` (Romano et al. 2007): if X drives Y, Y's recurrences imply
    X's more than the reverse, ``MCR(X|Y) > MCR(Y|X)``. Two signals of different character
    show an asymmetry without any coupling, so the index reported is the observed
    ``MCR(X|Y) - MCR(Y|X)`` minus its mean over the surrogates (which keep each signal's
    character and lose the coupling), with a two-sided surrogate p-value.

Twin surrogates (``method="twin"``, :mod:`funcnet.evidence.surrogates`)
    An option: Y is replaced by twin surrogates (Thiel et al. 2006), index sequences that jump
    between states with identical neighbourhoods; the observed window and every surrogate hold
    all ``M`` states, so ``K`` is never limited by the window. Where they are valid and where
    not is measured in docs/validation/evidence.md.

Validity needs stationarity inside the window: a ramp or a spin-up makes every time offset a
different part of the trend (docs/validation/evidence.md, "Robot windows").

References
----------
M. C. Romano, M. Thiel, J. Kurths, W. von Bloh, "Multivariate recurrence plots", Phys. Lett. A
330, 214-223 (2004) (joint recurrences).
M. C. Romano, M. Thiel, J. Kurths, C. Grebogi, "Estimation of the direction of the coupling by
conditional probabilities of recurrence", Phys. Rev. E 76, 036211 (2007).
N. Marwan, M. C. Romano, M. Thiel, J. Kurths, "Recurrence plots for the analysis of complex
systems", Phys. Rep. 438, 237-329 (2007), section 3.7 (surrogates).
Y. Benjamini, Y. Hochberg, "Controlling the false discovery rate", J. R. Stat. Soc. B 57,
289-300 (1995).
M. Thiel, M. C. Romano, J. Kurths, M. Rolfs, R. Kliegl, "Twin surrogates to test for complex
synchronisation", Europhys. Lett. 75, 535-541 (2006).

Length: over 600 lines because the test reads its recurrences in two forms that belong
together, dense matrices and each signal's packed rows made into bits once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from funcnet.errors import ParameterError
from funcnet.evidence._kernels import _bit_windows, _index_windows, _upper_pairs, _windows
from funcnet.evidence.surrogates import TwinPlan, twin_plan

__all__ = [
    "SURROGATE_METHODS",
    "ShiftPlan",
    "DependenceResult",
    "decorrelation_time",
    "shift_plan",
    "surrogate_plan",
    "planned_surrogates",
    "check_surrogate_method",
    "dependence_test",
    "recurrent_pairs",
    "shift_bits",
    "shift_test",
    "default_surrogates",
    "benjamini_hochberg",
]

#: The fewest states a test window may hold.
MIN_WINDOW = 20

#: Surrogates of the dependence test: the non-circular shift lattice (default) or twins.
SURROGATE_METHODS: tuple[str, ...] = ("shift", "twin")


def decorrelation_time(x: Any) -> int:
    """First lag at which the autocorrelation of ``x`` falls below 1/e (of any channel: the max).

    Parameters
    ----------
    x : array_like, shape (N,) or (N, c)

    Returns
    -------
    int
        At least 1; ``N - 1`` when it never falls below 1/e (a trend).

    Examples
    --------
    >>> decorrelation_time(np.random.default_rng(0).standard_normal(500))
    1
    >>> decorrelation_time(np.sin(np.linspace(0, 20 * np.pi, 1000)))
    20
    """
    array = np.asarray(x, dtype=np.float64)
    if array.ndim == 1:
        array = array[:, None]
    n = array.shape[0]
    longest = 1
    for column in array.T:
        centred = column - column.mean()
        size = 1 << (2 * n - 1).bit_length()
        spectrum = np.fft.rfft(centred, size)
        acf = np.fft.irfft(spectrum * np.conj(spectrum), size)[:n]
        if acf[0] <= 0:
            continue
        below = np.flatnonzero(acf / acf[0] < 1.0 / math.e)
        longest = max(longest, int(below[0]) if below.size else n - 1)
    return longest


@dataclass(frozen=True)
class ShiftPlan:
    """The windows of one dependence test: the observed one and the surrogates.

    Attributes
    ----------
    n_states : int
        ``M``, states per signal.
    length : int
        ``L``, states per window.
    min_shift, max_shift : int
        ``s0`` and ``S``: the surrogates' offsets are the multiples of ``s0`` up to ``S``.
    observed : int
        Start of the observed window (the same in X and Y).
    starts_x, starts_y : ndarray of int64
        Starts of the surrogate windows in X and in Y.
    """

    n_states: int
    length: int
    min_shift: int
    max_shift: int
    observed: int
    starts_x: np.ndarray
    starts_y: np.ndarray

    @property
    def surrogates(self) -> int:
        """``K``, the number of surrogate windows."""
        return int(self.starts_x.size)


def shift_plan(n_states: int, surrogates: int, *, min_shift: int = 1,
               max_fraction: float = 0.5) -> ShiftPlan:
    """Observed and surrogate windows for ``M = n_states`` states (module notes).

    The offsets form a lattice ``o = +-s0, +-2 s0, ..., +-k s0`` with ``k = ceil(K / 2)``
    (fewer when ``k s0`` would exceed ``max_fraction * M``); the observed window is the
    lattice's point 0. Each window is centred in the data.

    Parameters
    ----------
    n_states : int
        ``M``.
    surrogates : int
        ``K`` asked for; the plan holds ``2 k``, fewer than asked when the window is short.
    min_shift : int
        ``s0``, the lattice spacing, at least 1.
    max_fraction : float in (0, 1)
        The largest offset as a fraction of ``M``; the windows hold ``M - k s0`` states.

    Returns
    -------
    ShiftPlan

    Raises
    ------
    ParameterError
        ``surrogates < 1``, or ``M`` too small for a window of :data:`MIN_WINDOW` states and
        one offset.

    Examples
    --------
    >>> plan = shift_plan(498, 99, min_shift=3)
    >>> plan.length, plan.max_shift, plan.surrogates
    (348, 150, 100)
    >>> shift_plan(138, 99, min_shift=3).surrogates  # a short window: fewer surrogates
    46
    """
    if isinstance(surrogates, bool) or not isinstance(surrogates, (int, np.integer)) or \
            surrogates < 1:
        raise ParameterError.of("surrogates", f"must be an integer >= 1, got {surrogates!r}")
    if not 0.0 < max_fraction < 1.0:
        raise ParameterError.of("max_fraction", f"must be in (0, 1), got {max_fraction}")
    s0 = max(1, int(min_shift))
    steps = min(math.ceil(int(surrogates) / 2), int(max_fraction * n_states) // s0)
    max_shift = steps * s0
    length = n_states - max_shift
    if steps < 1 or length < MIN_WINDOW:
        raise ParameterError.of(
            "surrogates",
            f"{n_states} states leave no window of {MIN_WINDOW} states with offsets of "
            f"{s0} (the decorrelation time): the signals are too short to test",
        )
    offsets = s0 * np.concatenate([np.arange(1, steps + 1), -np.arange(1, steps + 1)])
    # Centred windows: x starts at (S - o) // 2, y at that + o.
    starts_x = ((max_shift - offsets) // 2).astype(np.int64)
    starts_y = (starts_x + offsets).astype(np.int64)
    return ShiftPlan(
        n_states=int(n_states), length=int(length), min_shift=s0, max_shift=int(max_shift),
        observed=max_shift // 2, starts_x=starts_x, starts_y=starts_y,
    )


def check_surrogate_method(method: Any) -> str:
    """``method`` if it is one of :data:`SURROGATE_METHODS`, else a :class:`ParameterError`.

    Examples
    --------
    >>> check_surrogate_method("twin")
    'twin'
    """
    if method not in SURROGATE_METHODS:
        raise ParameterError.of("surrogate_method",
                                f"must be one of {list(SURROGATE_METHODS)}, got {method!r}")
    return str(method)


def surrogate_plan(method: str, a_y: np.ndarray, surrogates: int, *, min_shift: int = 1,
                   seed: Any = 0) -> ShiftPlan | TwinPlan:
    """The surrogates of one test: the shift lattice or twins (:mod:`~funcnet.evidence.surrogates`).

    Parameters
    ----------
    method : {"shift", "twin"}
    a_y : ndarray, shape (M, M)
        Y's recurrence matrix (its shape gives ``M``; the twins are read from it).
    surrogates : int
        ``K`` asked.
    min_shift : int
        ``s0`` of the shift lattice (ignored by twins).
    seed : int or sequence of int
        Seeds the twin surrogates (the shift lattice is deterministic).

    Returns
    -------
    ShiftPlan or TwinPlan

    Raises
    ------
    ParameterError
        Unknown ``method``; see :func:`shift_plan` and
        :func:`~funcnet.evidence.surrogates.twin_plan`.

    Examples
    --------
    >>> a = np.zeros((140, 140), dtype=np.uint8)
    >>> surrogate_plan("shift", a, 99, min_shift=20).surrogates  # the lattice is short
    6
    >>> surrogate_plan("twin", a, 99).surrogates
    99
    """
    method = check_surrogate_method(method)
    m = int(np.shape(a_y)[0])
    if method == "twin":
        if m < MIN_WINDOW:
            raise ParameterError.of("surrogates", f"{m} states are fewer than {MIN_WINDOW}: "
                                    "the signals are too short to test")
        return twin_plan(a_y, surrogates, seed=seed)
    return shift_plan(m, surrogates, min_shift=min_shift)


def planned_surrogates(method: str, n_states: int, surrogates: int, *,
                       min_shift: int = 1) -> int:
    """``K``, the surrogates a test of ``n_states`` states will hold, before any recurrence.

    What :func:`surrogate_plan` gives, from the sizes alone: the shift lattice's ``2 k``
    (:func:`shift_plan`), or ``surrogates`` twins; 0 where the window is too short to test.
    Whether a pair can reach a level is thus known before anything is computed
    (:func:`funcnet.evidence.reading.untestable`).

    Parameters
    ----------
    method : {"shift", "twin"}
    n_states : int
        ``M``, states per signal.
    surrogates : int
        ``K`` asked.
    min_shift : int
        ``s0`` of the shift lattice (ignored by twins).

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        Unknown ``method`` or ``surrogates < 1``.

    Examples
    --------
    >>> planned_surrogates("shift", 140, 99, min_shift=20), planned_surrogates("twin", 140, 99)
    (6, 99)
    >>> planned_surrogates("shift", 30, 99, min_shift=20)  # no window of 20 states is left
    0
    """
    method = check_surrogate_method(method)
    if isinstance(surrogates, bool) or not isinstance(surrogates, (int, np.integer)) or \
            surrogates < 1:
        raise ParameterError.of("surrogates", f"must be an integer >= 1, got {surrogates!r}")
    if method == "twin":
        return int(surrogates) if n_states >= MIN_WINDOW else 0
    try:
        return shift_plan(int(n_states), int(surrogates), min_shift=min_shift).surrogates
    except ParameterError:
        return 0


@dataclass(frozen=True)
class DependenceResult:
    """The dependence test of one pair, and the direction reading of the same surrogates.

    Attributes
    ----------
    statistic : float
        Observed ``phi`` (joint-recurrence correlation).
    p_value : float
        Unadjusted surrogate p-value, in ``[1 / (K + 1), 1]``.
    surrogates : int
        ``K`` used.
    direction_index : float
        ``MCR(X|Y) - MCR(Y|X)`` observed minus its surrogate mean; positive reads X -> Y.
    direction_p : float
        Two-sided surrogate p-value of ``direction_index`` (unadjusted).
    null_statistics : ndarray
        The surrogates' ``phi``.
    """

    statistic: float
    p_value: float
    surrogates: int
    direction_index: float
    direction_p: float
    null_statistics: np.ndarray


def recurrent_pairs(a: np.ndarray) -> np.ndarray:
    """The recurrent pairs ``i < j`` of a dense recurrence matrix, shape (pairs, 2), in row
    order: what :func:`dependence_test` reads of each matrix for the shift lattice.

    Examples
    --------
    >>> recurrent_pairs(np.array([[0, 1, 1], [1, 0, 0], [1, 0, 0]], dtype=np.uint8)).tolist()
    [[0, 1], [0, 2]]
    """
    # np.argwhere(np.triu(a, 1)), without copying a uint8 matrix (other types: their
    # non-zero cells as uint8, one compiled kernel)
    a = np.asarray(a)
    cells = a if a.dtype == np.uint8 else (a != 0).view(np.uint8)
    return _upper_pairs(np.ascontiguousarray(cells))


def dependence_test(a_x: np.ndarray, a_y: np.ndarray, plan: ShiftPlan | TwinPlan, *,
                    theiler: int = 0,
                    recurrent: tuple[np.ndarray, np.ndarray] | None = None) -> DependenceResult:
    """Joint-recurrence dependence test of X and Y on precomputed recurrence matrices.

    Parameters
    ----------
    a_x, a_y : ndarray of uint8, shape (M, M)
        Dense recurrence matrices (no self-loops), e.g. ``PackedRecurrence.to_dense()``.
    plan : ShiftPlan or TwinPlan
        From :func:`shift_plan` for this ``M``, or twin surrogates of Y
        (:func:`surrogate_plan`).
    theiler : int
        Pairs of times with ``|i - j| <= theiler`` are not counted.
    recurrent : (ndarray, ndarray), optional
        :func:`recurrent_pairs` of ``a_x`` and ``a_y`` when the caller has them (a signal in
        many pairs); computed here otherwise.

    Returns
    -------
    DependenceResult

    Raises
    ------
    ParameterError
        Matrices of another shape than ``(M, M)``.

    References
    ----------
    Romano et al. (2004, 2007); Thiel et al. (2006) for twin surrogates; module notes.

    Examples
    --------
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.core.recurrence import auto_recurrence
    >>> from funcnet.validation.systems import henon_pair
    >>> data = henon_pair(300, 0.6, seed=0)
    >>> a_x, a_y = (auto_recurrence(embed(data[:, k], 2, 1), rr=0.05).to_dense().astype(np.uint8)
    ...             for k in (0, 1))
    >>> result = dependence_test(a_x, a_y, shift_plan(299, 99, min_shift=2))
    >>> round(result.p_value, 4), result.surrogates  # the smallest p-value 1 / (K + 1)
    (0.0099, 100)
    >>> twins = dependence_test(a_x, a_y, surrogate_plan("twin", a_y, 99, seed=0))
    >>> round(twins.p_value, 4), twins.surrogates
    (0.01, 99)
    """
    m = plan.n_states
    for name, matrix in (("a_x", a_x), ("a_y", a_y)):
        if np.shape(matrix) != (m, m):
            raise ParameterError.of(name, f"must have shape ({m}, {m}), got {np.shape(matrix)}")
    a_x = np.ascontiguousarray(a_x, dtype=np.uint8)
    a_y = np.ascontiguousarray(a_y, dtype=np.uint8)
    if isinstance(plan, TwinPlan):
        # The observed window is the identity sequence of Y's states, on the same kernel.
        indices = np.vstack([np.arange(m, dtype=np.int64)[None, :], plan.indices])
        return _result(_index_windows(a_x, a_y, indices, int(theiler)), plan.surrogates)
    starts_x, starts_y = _starts(plan)
    pairs_x, pairs_y = ((recurrent_pairs(a_x), recurrent_pairs(a_y)) if recurrent is None
                        else recurrent)
    values = _windows(a_y, pairs_x, pairs_y, starts_x, starts_y, plan.length, int(theiler))
    return _result(values, plan.surrogates)


def _starts(plan: ShiftPlan) -> tuple[np.ndarray, np.ndarray]:
    """The windows' starts in X and in Y: the observed one first, then the surrogates'."""
    return (np.concatenate([[plan.observed], plan.starts_x]).astype(np.int64),
            np.concatenate([[plan.observed], plan.starts_y]).astype(np.int64))


def shift_bits(rows: np.ndarray) -> np.ndarray:
    """A recurrence's packed rows as the shift lattice reads them.

    The bits :func:`dependence_test` makes of a matrix's :func:`recurrent_pairs`, without the
    dense matrix and the list: a signal in many pairs is made into bits once
    (:func:`shift_test`).

    Parameters
    ----------
    rows : ndarray of uint64, shape (M, words)
        ``PackedRecurrence.rows`` of an auto-recurrence (symmetric, no self-loops).

    Returns
    -------
    ndarray of uint64, shape (M, words + 1)
        The rows with one spare zero word each (a read of 64 bits at any offset inside a row
        has the word after it).

    Examples
    --------
    >>> rows = np.array([[0b110], [0b001], [0b001]], dtype=np.uint64)  # pairs (0, 1), (0, 2)
    >>> shift_bits(rows).tolist()
    [[6, 0], [1, 0], [1, 0]]
    """
    return np.pad(np.asarray(rows, dtype=np.uint64), ((0, 0), (0, 1)))


def shift_test(bits_x: np.ndarray, bits_y: np.ndarray, plan: ShiftPlan, *,
               theiler: int = 0) -> DependenceResult:
    """:func:`dependence_test` on a shift lattice, of two recurrences as :func:`shift_bits`.

    Parameters
    ----------
    bits_x, bits_y : ndarray of uint64, shape (M, words + 1)
        :func:`shift_bits` of X's and Y's recurrences.
    plan : ShiftPlan
        From :func:`shift_plan` for this ``M``.
    theiler : int
        Pairs of times with ``|i - j| <= theiler`` are not counted.

    Returns
    -------
    DependenceResult
        The same as :func:`dependence_test` of the dense matrices, bit for bit.

    Raises
    ------
    ParameterError
        Bits of another shape than ``(M, words + 1)``.

    Examples
    --------
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.core.recurrence import auto_recurrence
    >>> from funcnet.validation.systems import henon_pair
    >>> data = henon_pair(300, 0.6, seed=0)
    >>> a_x, a_y = (auto_recurrence(embed(data[:, k], 2, 1), rr=0.05) for k in (0, 1))
    >>> plan = shift_plan(299, 99, min_shift=2)
    >>> bits = shift_test(shift_bits(a_x.rows), shift_bits(a_y.rows), plan)
    >>> dense = dependence_test(a_x.to_dense().view(np.uint8), a_y.to_dense().view(np.uint8),
    ...                         plan)
    >>> bits.p_value == dense.p_value, bits.statistic == dense.statistic
    (True, True)
    """
    m = plan.n_states
    for name, bits in (("bits_x", bits_x), ("bits_y", bits_y)):
        if np.shape(bits) != (m, (m + 63) // 64 + 1):
            raise ParameterError.of(name, f"must have shape ({m}, {(m + 63) // 64 + 1}), got "
                                    f"{np.shape(bits)}")
    starts_x, starts_y = _starts(plan)
    values = _bit_windows(np.ascontiguousarray(bits_x, dtype=np.uint64),
                          np.ascontiguousarray(bits_y, dtype=np.uint64), starts_x, starts_y,
                          plan.length, int(theiler))
    return _result(values, plan.surrogates)


def _result(values: np.ndarray, k: int) -> DependenceResult:
    """p-values and direction index from the statistics of the observed window (row 0) and
    the ``k`` surrogates."""
    phi = values[:, 0]
    index = values[:, 1] - values[:, 2]
    observed, null = float(phi[0]), phi[1:]
    p_value = (1 + int(np.count_nonzero(null >= observed))) / (k + 1)
    centre = float(index[1:].mean())
    excess = float(index[0]) - centre
    spread = np.abs(index[1:] - centre)
    direction_p = (1 + int(np.count_nonzero(spread >= abs(excess)))) / (k + 1)
    return DependenceResult(
        statistic=observed, p_value=p_value, surrogates=k, direction_index=excess,
        direction_p=direction_p, null_statistics=null.copy(),
    )


def default_surrogates(n_pairs: int, alpha: float = 0.05) -> int:
    """``K`` such that a lone discovery among ``n_pairs`` survives Benjamini-Hochberg at ``alpha``.

    ``K = max(99, ceil(n_pairs / alpha) - 1)``: the smallest p-value is ``1 / (K + 1)``, and
    BH's smallest threshold is ``alpha / n_pairs``.

    Parameters
    ----------
    n_pairs : int
    alpha : float in (0, 1)

    Returns
    -------
    int

    Examples
    --------
    >>> default_surrogates(1), default_surrogates(15), default_surrogates(15, 0.01)
    (99, 299, 1499)
    """
    if not 0.0 < alpha < 1.0:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha}")
    return max(99, math.ceil(round(n_pairs / alpha, 9)) - 1)


def benjamini_hochberg(p_values: Any) -> np.ndarray:
    """Benjamini-Hochberg adjusted p-values (step-up; reject where adjusted <= alpha).

    The arithmetic of :func:`scipy.stats.false_discovery_control` (``method="bh"``), on the
    p-values that are not NaN, equal to it bit for bit (tested): importing :mod:`scipy.stats`
    costs about a second per command, which every page would pay for these few lines.

    Parameters
    ----------
    p_values : array_like of float
        NaN entries are left NaN and not counted.

    Returns
    -------
    ndarray
        ``min_{j >= i} (m / j) p_(j)``, capped at 1, in the input order.

    References
    ----------
    Benjamini and Hochberg (1995).

    Examples
    --------
    >>> benjamini_hochberg([0.01, 0.04, 0.03, 0.5]).round(3).tolist()
    [0.04, 0.053, 0.053, 0.5]
    """
    p = np.asarray(p_values, dtype=np.float64)
    out = np.full(p.shape, np.nan)
    valid = ~np.isnan(p)
    kept = p[valid]
    if kept.size <= 1:  # nothing to adjust (scipy returns it as it is, unclipped)
        out[valid] = kept
        return out
    order = np.argsort(kept)
    ranked = kept[order] * (kept.size / np.arange(1, kept.size + 1, dtype=np.float64))
    np.minimum.accumulate(ranked[::-1], out=ranked[::-1])
    adjusted = np.empty_like(ranked)
    adjusted[order] = ranked
    out[valid] = np.clip(adjusted, 0.0, 1.0)
    return out
