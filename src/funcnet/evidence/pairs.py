"""Evidence for every pair of a set of signals: coupling test, intervals, direction, reading.

:func:`pairwise_evidence` embeds each signal and computes its recurrence matrix once (the
thresholds of :func:`funcnet.core.measures.pairwise_cross_measures`, so ``c_diff``/``t_diff`` are
the
network's own numbers), then per pair runs the dependence test
(:mod:`funcnet.evidence.dependence`) and the half-sampling intervals
(:mod:`funcnet.evidence.interval`), and adjusts the coupling and direction p-values across the
pairs with Benjamini-Hochberg.

The reading of a pair (:func:`evidence_label`):

=====================  ===================================================================
``coupled-directed``   the dependence test rejects independence (BH-adjusted, at ``alpha``),
                       the direction index is significant (BH-adjusted, ``direction``) and
                       the network's ``kind`` points the same way
``coupled``            dependence found, no direction supported
``untestable``         the test could not have rejected at ``alpha`` whatever the data (too
                       few surrogates, :func:`funcnet.evidence.reading.untestable`)
``asymmetry-only``     tested, no dependence found, yet the network's rule draws an arrow:
                       the arrow rests on a difference of character only
``not-coupled``        tested, no dependence found, no arrow
=====================  ===================================================================

"not-coupled" means the test found nothing, not that the signals are independent: smooth
(long-memory) signals leave the test few surrogates and little power (docs/validation/evidence.md).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Unpack

import numpy as np

from funcnet.core.embedding import signal_states, thinned
from funcnet.core.measures import isrn_measures
from funcnet.core.recurrence import PackedRecurrence, auto_recurrence, cross_recurrence
from funcnet.core.thresholds import signal_thresholds
from funcnet.errors import ParameterError, SignalError
from funcnet.evidence.dependence import (
    DependenceResult,
    benjamini_hochberg,
    check_surrogate_method,
    decorrelation_time,
    default_surrogates,
    dependence_test,
    planned_surrogates,
    shift_bits,
    shift_plan,
    shift_test,
    surrogate_plan,
)
from funcnet.evidence.interval import AsymmetryInterval, asymmetry_intervals
from funcnet.parameters import PAIR_FIELDS, NetworkParameters, ParameterOverrides, resolve

__all__ = ["EVIDENCE_LABELS", "INTERVAL_SCOPES", "PairEvidence", "pairwise_evidence",
           "evidence_label", "check_evidence_arguments"]

#: The readings of a pair (the ``evidence`` column).
EVIDENCE_LABELS: tuple[str, ...] = ("coupled-directed", "coupled", "not-coupled",
                                    "asymmetry-only", "untestable")
#: The pairs whose asymmetry intervals are drawn: those whose coupling test rejects
#: (``"coupled"``, the default: an interval says how precisely a coupled pair's asymmetry is
#: known; a pair without coupling has no influence to qualify), those whose test can reach the
#: level (``"testable"``), or every pair.
INTERVAL_SCOPES: tuple[str, ...] = ("coupled", "testable", "all")


@dataclass(frozen=True)
class PairEvidence:
    """The evidence of one pair (X, Y).

    Attributes
    ----------
    coupling_statistic : float
        Observed joint-recurrence correlation ``phi`` (NaN when the pair could not be tested).
    coupling_p : float
        Its surrogate p-value, Benjamini-Hochberg adjusted across the pairs (NaN: not tested).
    coupled : bool
        ``coupling_p <= alpha``.
    surrogates : int
        ``K`` used (0: not tested: too few states for one offset).
    c_diff, t_diff : float
        The network's differences (Eq. 10).
    c_diff_low, c_diff_high, t_diff_low, t_diff_high : float
        Half-sampling intervals (always containing the difference); NaN with ``resamples=0``.
    c_sign_fraction, t_sign_fraction : float
        Fraction of resamples with the observed sign; NaN with ``resamples=0``.
    direction_index : float
        ``MCR(X|Y) - MCR(Y|X)`` minus its surrogate mean; positive reads X -> Y.
    direction_p : float
        Its two-sided surrogate p-value, BH-adjusted across the pairs.
    direction : str
        ``"x->y"``, ``"y->x"`` when coupled and ``direction_p <= alpha``; else ``""``.
    """

    coupling_statistic: float
    coupling_p: float
    coupled: bool
    surrogates: int
    c_diff: float
    t_diff: float
    c_diff_low: float
    c_diff_high: float
    t_diff_low: float
    t_diff_high: float
    c_sign_fraction: float
    t_sign_fraction: float
    direction_index: float
    direction_p: float
    direction: str


def evidence_label(coupled: bool, direction: str, kind: str, *,
                   untestable: bool = False) -> str:
    """The reading of a pair from its test result and the network's kind (module notes).

    Parameters
    ----------
    coupled : bool
    direction : str
        ``"x->y"``, ``"y->x"`` or ``""`` (the conditional-recurrence direction).
    kind : str
        The network's pair kind (``"x->y"``, ``"y->x"``, ``"bidirectional"``, ``"conflict"``).
    untestable : bool
        The test could not have rejected (:func:`funcnet.evidence.reading.untestable`): read
        ``"untestable"`` rather than ``"asymmetry-only"`` or ``"not-coupled"``.

    Returns
    -------
    str
        One of :data:`EVIDENCE_LABELS`.

    Examples
    --------
    >>> evidence_label(False, "", "x->y"), evidence_label(True, "y->x", "y->x")
    ('asymmetry-only', 'coupled-directed')
    >>> evidence_label(True, "y->x", "x->y")  # the readings disagree
    'coupled'
    >>> evidence_label(False, "", "x->y", untestable=True)
    'untestable'
    """
    if coupled:
        # Two independent readings must agree: the conditional-recurrence direction alone named
        # a direction for 55 % of common-driver pairs (docs/validation/evidence.md).
        return "coupled-directed" if direction and direction == kind else "coupled"
    if untestable:
        return "untestable"
    return "asymmetry-only" if kind in ("x->y", "y->x") else "not-coupled"


def _check_surrogates(surrogates: Any) -> None:
    if surrogates is not None and (isinstance(surrogates, bool) or not isinstance(
            surrogates, (int, np.integer)) or surrogates < 1):
        raise ParameterError.of("surrogates", f"must be an integer >= 1 (or None), got "
                                f"{surrogates!r}")


def _check_alpha(alpha: Any) -> float:
    if isinstance(alpha, bool) or not isinstance(alpha, (int, float)) or not 0 < alpha < 1:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha!r}")
    return float(alpha)


def check_evidence_arguments(surrogates: Any, alpha: Any, resamples: Any,
                             surrogate_method: Any = "shift", intervals: Any = "coupled") -> None:
    """Raise a :class:`ParameterError` naming the first bad evidence argument.

    ``resamples=0`` is allowed (no intervals); ``surrogate_method`` is ``"shift"`` or
    ``"twin"``; ``intervals`` one of :data:`INTERVAL_SCOPES`.

    Examples
    --------
    >>> check_evidence_arguments(None, 0.05, 200)
    >>> check_evidence_arguments(None, 0.05, 0, "twin")
    >>> check_evidence_arguments(0, 0.05, 200)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: surrogates must be an integer >= 1 (or None), got 0
    """
    _check_surrogates(surrogates)
    _check_alpha(alpha)
    if isinstance(resamples, bool) or not isinstance(resamples, (int, np.integer)) or \
            resamples < 0:
        raise ParameterError.of("resamples", f"must be an integer >= 0, got {resamples!r}")
    check_surrogate_method(surrogate_method)
    if intervals not in INTERVAL_SCOPES:
        raise ParameterError.of("intervals", f"must be one of {list(INTERVAL_SCOPES)}, got "
                                f"{intervals!r}")


def pairwise_evidence(
    signals: Sequence[Any],
    *,
    names: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    surrogates: int | None = None,
    alpha: float = 0.05,
    seed: int = 0,
    resamples: int = 200,
    level: float = 0.95,
    surrogate_method: str = "shift",
    intervals: str = "coupled",
    observed: Mapping[tuple[Any, Any], tuple[float, float]] | None = None,
    tests: Mapping[tuple[Any, Any], DependenceResult | None] | None = None,
    step: int = 1,
    auto_eps: Sequence[float] | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> dict[tuple[Any, Any], PairEvidence]:
    """Coupling test, intervals and direction of every pair ``i < j`` of equally long signals.

    Parameters
    ----------
    signals : sequence of array_like (N,) or (N, c)
        The signals as the measures use them (already normalized: this function does not
        normalize).
    names : sequence of str, optional
        Keys of the result (default positions).
    parameters : NetworkParameters, optional
        Embedding and thresholds (``dim``, ``delay``, ``rr``, ``cr``, ``eps``, ``metric``,
        ``rule``, ``theiler``), as :func:`funcnet.core.measures.pairwise_cross_measures`.
    surrogates : int, optional
        ``K`` asked per pair; default :func:`default_surrogates` of the number of pairs.
    alpha : float
        Level of the coupling and direction decisions (after Benjamini-Hochberg).
    seed : int
        Seeds the subsamples and the twin surrogates (the shift surrogates are a fixed
        lattice).
    resamples : int
        Resamples for the intervals (subsamples of two sizes, one set per network); 0 skips
        the intervals (their columns and the sign fractions are NaN) for callers that want only
        the coupling test.
    level : float
        Nominal coverage of the intervals.
    surrogate_method : {"shift", "twin"}
        Surrogates of the dependence test: the non-circular time-shift lattice (default) or
        twin surrogates of the second signal of each pair (Thiel et al. 2006;
        :mod:`funcnet.evidence.surrogates`; where each is valid: docs/validation/evidence.md).
    intervals : {"coupled", "testable", "all"}
        Whose intervals are drawn (:data:`INTERVAL_SCOPES`); the others' are NaN as with
        ``resamples=0``. ``"coupled"`` (default): the pairs whose coupling test rejects at
        ``alpha`` (known after the test, before any interval). ``"testable"``: the pairs
        whose coupling test can reach ``alpha``, decided from the window's size before any
        measure (:func:`~funcnet.evidence.dependence.planned_surrogates`,
        :func:`~funcnet.evidence.reading.untestable`). ``"all"``: every pair's. A drawn
        pair's interval is the same number under each choice (the network's resamples do not
        depend on which pairs are drawn).
    observed : mapping, optional
        ``{(name_i, name_j): (c_diff, t_diff)}``: the pairs' differences already computed on
        these signals with these parameters (a network's pairs table); default computed here.
        Given, no cross recurrence is computed but for the intervals.
    tests : mapping, optional
        ``{(name_i, name_j): DependenceResult or None}``: every pair's dependence test already
        run (over a longer span holding these signals: the whole segment of a recording cut
        into parts, :func:`funcnet.evidence.segment.segment_tests`; None: not testable).
        Given, no test and no dense recurrence is computed here; the adjustment across the
        pairs, the readings and the intervals are as without it.
    step : int
        Every ``step``-th state, as the network's measures took them
        (:func:`funcnet.core.measures.pairwise_cross_measures`): the test, its shift lattice
        (spaced by the decorrelation time in thinned states, as
        :func:`funcnet.evidence.segment.segment_tests`) and the intervals read those states.
    auto_eps : sequence of float, optional
        Each signal's recurrence threshold as the network's measures found it (its pairs
        table's ``eps_x``, ``eps_y``): its recurrence is built at that threshold, the same
        matrix as the rate gives, without searching for it again. The intervals' resamples
        still threshold by rate.
    **overrides
        Fields of ``parameters`` (pair fields only).

    Returns
    -------
    dict
        ``{(name_i, name_j): PairEvidence}``, the keys of
        :func:`funcnet.core.measures.pairwise_cross_measures`.

    Raises
    ------
    ParameterError
        Bad ``alpha``, ``surrogates``, ``resamples``, ``level`` or parameter.
    SignalError
        Fewer than two signals, or unequal lengths.

    References
    ----------
    Romano et al. (2004, 2007), Benjamini and Hochberg (1995), Politis et al. (1999): see
    :mod:`funcnet.evidence.dependence` and :mod:`funcnet.evidence.interval`.

    Examples
    --------
    >>> from funcnet.validation.systems import henon_pair
    >>> data = henon_pair(400, 0.6, seed=0)
    >>> result = pairwise_evidence([data[:, 0], data[:, 1]], names=["x", "y"], delay=1,
    ...                            resamples=50)
    >>> pair = result[("x", "y")]
    >>> pair.coupled, pair.surrogates, pair.c_diff_low <= pair.c_diff <= pair.c_diff_high
    (True, 100, True)
    >>> twin = pairwise_evidence([data[:, 0], data[:, 1]], names=["x", "y"], delay=1,
    ...                          resamples=0, surrogate_method="twin")[("x", "y")]
    >>> twin.coupled, twin.surrogates, bool(np.isnan(twin.c_diff_low))
    (True, 99, True)

    Nine surrogates cannot reach 0.05 (``1 / 10``): no interval unless asked for.

    >>> few = pairwise_evidence([data[:, 0], data[:, 1]], names=["x", "y"], delay=1,
    ...                         resamples=20, surrogates=9)[("x", "y")]
    >>> few.surrogates, bool(np.isnan(few.c_diff_low))
    (10, True)
    >>> every = pairwise_evidence([data[:, 0], data[:, 1]], names=["x", "y"], delay=1,
    ...                           resamples=20, surrogates=9, intervals="all")[("x", "y")]
    >>> bool(every.c_diff_low <= every.c_diff <= every.c_diff_high)
    True
    """
    check_evidence_arguments(surrogates, alpha, resamples, surrogate_method, intervals)
    alpha = float(alpha)
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    signals = list(signals)
    keys, called = _signal_names(signals, names)
    n = len(signals)
    n_pairs = n * (n - 1) // 2
    k = default_surrogates(n_pairs, alpha) if surrogates is None else surrogates
    prepared = _prepare(signals, p, called, surrogate_method, test=tests is None,
                        autos=observed is None, step=step, auto_eps=auto_eps)
    p = thinned(p, step)
    raw = [_test_pair(prepared, p, i, j, k, keys=keys, seed=seed,
                      surrogate_method=surrogate_method, observed=observed, tests=tests)
           for i in range(n) for j in range(i + 1, n)]
    can_reach = (_can_reach(prepared, surrogate_method, k, alpha, intervals) if tests is None
                 else _reachable([e["k"] for e in raw], alpha, intervals))
    for e in raw:
        c_diff, t_diff = e["observed"]
        e["interval"] = AsymmetryInterval.without_resamples(c_diff, t_diff, level=level)
    coupling_p = benjamini_hochberg([e["p"] for e in raw])
    drawn = can_reach & (coupling_p <= alpha) if intervals == "coupled" else can_reach
    chosen = [e for e, draw in zip(raw, drawn, strict=True) if draw]
    if resamples and chosen:
        # One set of subsamples for the network: each signal is re-thresholded once per
        # resample.
        found = asymmetry_intervals(prepared.states, [e["pair"] for e in chosen],
                                    [e["observed"] for e in chosen], parameters=p,
                                    resamples=resamples, level=level, seed=seed)
        for e, interval in zip(chosen, found, strict=True):
            e["interval"] = interval
    direction_p = benjamini_hochberg([e["index_p"] for e in raw])
    return {e["key"]: _pair_evidence(e, cp, dp, alpha)
            for e, cp, dp in zip(raw, coupling_p, direction_p, strict=True)}


@dataclass(frozen=True)
class _Prepared:
    """Each signal's states and recurrence, computed once for all the pairs it is in."""

    called: list[str]
    states: list[np.ndarray]
    autos: list[PackedRecurrence]
    dense: list[np.ndarray]
    # each signal's recurrence as bits, for all its pairs' shift tests (None for twins)
    bits: list[np.ndarray] | None
    decorrelation: list[int]
    span: int
    cr: float
    cross_eps: float | None
    step: int = 1

    def min_shift(self, i: int, j: int) -> int:
        """``s0`` of the pair's shift lattice, in (thinned) states."""
        return -(-max(self.decorrelation[i], self.decorrelation[j], self.span) // self.step)


def _signal_names(signals: list[Any], names: Sequence[str] | None) -> tuple[list[Any], list[str]]:
    """The result's keys and the names errors use; raise on too few or unequal signals."""
    n = len(signals)
    if n < 2:
        raise SignalError(f"pairwise_evidence needs at least two signals, got {n}")
    keys: list[Any] = list(range(n)) if names is None else list(names)
    if len(keys) != n:
        raise ParameterError.of("names", f"has {len(keys)} entries for {n} signals")
    lengths = {np.shape(s)[0] for s in signals}
    if len(lengths) != 1:
        raise SignalError(f"signals must have equal lengths, got {sorted(lengths)}")
    called = [f"signals[{i}]" if names is None else repr(str(keys[i])) for i in range(n)]
    return keys, called


def _prepare(signals: list[Any], p: NetworkParameters, called: list[str],
             surrogate_method: str, *, test: bool = True, autos: bool = True,
             step: int = 1, auto_eps: Sequence[float] | None = None) -> _Prepared:
    """Embed each signal and compute its recurrence once, at the network's thresholds (its
    rates, or ``auto_eps`` found by them), on every ``step``-th state.

    Without ``test`` (the tests given) no dense matrix is made, and without ``autos`` (the
    differences given too) no recurrence: the states are what the intervals read.
    """
    thresholds, (cr, cross_eps) = signal_thresholds(p, len(signals))
    if auto_eps is not None:
        thresholds = [(rate, float(eps))  # an eps overrides the rate
                      for (rate, _), eps in zip(thresholds, auto_eps, strict=True)]
    states = [signal_states(s, parameters=p, name=c, step=step)
              for s, c in zip(signals, called, strict=True)]
    p = thinned(p, step)
    packed = [
        auto_recurrence(s, rr=rate, eps=eps, parameters=p, name=c)
        for s, (rate, eps), c in zip(states, thresholds, called, strict=True)
    ] if test or autos else []
    shift = test and surrogate_method == "shift"
    # twins read the dense matrices (their bytes as uint8: 0 and 1, as a copy to uint8 would
    # hold them); the shift lattice the packed rows, made into bits once per signal
    dense = [a.to_dense().view(np.uint8) for a in packed] if test and not shift else []
    bits = [shift_bits(a.rows) for a in packed] if shift else None
    decorrelation = [decorrelation_time(s) for s in signals] if test else []
    return _Prepared(called=called, states=states, autos=packed, dense=dense,
                     bits=bits, decorrelation=decorrelation,
                     span=(p.dim - 1) * p.delay + 1, cr=cr, cross_eps=cross_eps, step=step)


def _can_reach(prepared: _Prepared, surrogate_method: str, k: int, alpha: float,
               intervals: str) -> np.ndarray:
    """Per pair, whether its intervals may be drawn, before any measure.

    Whether each pair can reach alpha is known from the sizes: the intervals of those that
    cannot are not drawn (unless ``intervals="all"``).
    """
    n = len(prepared.states)
    n_states = int(np.shape(prepared.states[0])[0])
    planned = [planned_surrogates(surrogate_method, n_states, k,
                                  min_shift=prepared.min_shift(i, j))
               for i in range(n) for j in range(i + 1, n)]
    # the least p-value each can reach, BH-adjusted (funcnet.evidence.reading.untestable)
    return _reachable(planned, alpha, intervals)


def _reachable(planned: Sequence[int], alpha: float, intervals: str) -> np.ndarray:
    """Per pair of ``K`` surrogates, whether it can reach ``alpha`` after the adjustment."""
    k_planned = np.asarray(planned, dtype=np.float64)
    with np.errstate(divide="ignore"):
        least = benjamini_hochberg(np.where(k_planned > 0, 1.0 / (k_planned + 1.0), np.nan))
    return least <= alpha if intervals != "all" else np.ones(len(planned), bool)


def _test_pair(prepared: _Prepared, p: NetworkParameters, i: int, j: int, k: int, *,
               keys: list[Any], seed: int, surrogate_method: str,
               observed: Mapping[tuple[Any, Any], tuple[float, float]] | None,
               tests: Mapping[tuple[Any, Any], DependenceResult | None] | None = None,
               ) -> dict[str, Any]:
    """One pair's differences and dependence test (run, or given), before the adjustment
    across pairs."""
    if observed is None:
        cr_ij = cross_recurrence(prepared.states[i], prepared.states[j], cr=prepared.cr,
                                 eps=prepared.cross_eps, parameters=p,
                                 names=(prepared.called[i], prepared.called[j]))
        measures = isrn_measures(prepared.autos[i], prepared.autos[j], cr_ij,
                                 parameters=p.for_pair(i, j))
        differences = (measures.c_diff, measures.t_diff)
    else:
        c_diff, t_diff = observed[(keys[i], keys[j])]
        differences = (float(c_diff), float(t_diff))
    entry: dict[str, Any] = {"key": (keys[i], keys[j])}
    test = (_run_test(prepared, p, i, j, k, seed, surrogate_method) if tests is None
            else tests[(keys[i], keys[j])])
    if test is None:
        entry.update(statistic=np.nan, p=np.nan, k=0, index=np.nan, index_p=np.nan)
    else:
        entry.update(statistic=test.statistic, p=test.p_value, k=test.surrogates,
                     index=test.direction_index, index_p=test.direction_p)
    entry["observed"] = differences
    entry["pair"] = (i, j)
    return entry


def _run_test(prepared: _Prepared, p: NetworkParameters, i: int, j: int, k: int, seed: int,
              surrogate_method: str) -> DependenceResult | None:
    """The dependence test of one pair on the prepared recurrences (None: too short)."""
    bits = prepared.bits
    if bits is not None:  # the shift lattice, as surrogate_plan makes it
        try:
            shifts = shift_plan(bits[j].shape[0], k, min_shift=prepared.min_shift(i, j))
        except ParameterError:
            return None
        return shift_test(bits[i], bits[j], shifts, theiler=p.theiler)
    try:
        plan = surrogate_plan(surrogate_method, prepared.dense[j], k,
                              min_shift=prepared.min_shift(i, j), seed=[int(seed), i, j])
    except ParameterError:
        return None
    return dependence_test(prepared.dense[i], prepared.dense[j], plan, theiler=p.theiler)


def _pair_evidence(e: Mapping[str, Any], cp: float, dp: float, alpha: float) -> PairEvidence:
    """One pair's evidence from its test, its interval and its adjusted p-values."""
    coupled = bool(cp <= alpha)  # NaN compares False
    direction = ""
    if coupled and dp <= alpha and e["index"] != 0:
        direction = "x->y" if e["index"] > 0 else "y->x"
    iv = e["interval"]
    return PairEvidence(
        coupling_statistic=float(e["statistic"]), coupling_p=float(cp), coupled=coupled,
        surrogates=int(e["k"]), c_diff=iv.c_diff, t_diff=iv.t_diff,
        c_diff_low=iv.c_diff_low, c_diff_high=iv.c_diff_high,
        t_diff_low=iv.t_diff_low, t_diff_high=iv.t_diff_high,
        c_sign_fraction=iv.c_sign_fraction, t_sign_fraction=iv.t_sign_fraction,
        direction_index=float(e["index"]), direction_p=float(dp), direction=direction,
    )
