"""Cross-clustering and cross-transitivity of inter-system recurrence networks (section 2.3-2.4).

For an ISRN with blocks ``A_X``, ``A_Y``, ``CR_XY`` (Eq. 4) and a node ``v`` of X:

* cross-degree ``k_v = sum_q CR_XY[v, q]`` (Eq. 7);
* cross-triangles ``tri_v = sum_{p, q} CR_XY[v, p] A_Y[p, q] CR_XY[v, q]`` (ordered ``p != q``,
  since ``A_Y`` has no self-loops);
* local cross-clustering ``C^XY(v) = tri_v / (k_v (k_v - 1))``, and 0 where ``k_v < 2`` (Eq. 6);
* global cross-clustering ``C^XY`` = mean of ``C^XY(v)`` over **all** ``v`` of X (Eq. 8);
* cross-transitivity ``T^XY = sum_v tri_v / sum_v k_v (k_v - 1)``, 0 without any triple (Eq. 9);
* ``C^YX``, ``T^YX``: the same with the roles of X and Y swapped (``CR_XY^T`` and ``A_X``);
* ``C_diff = C^XY - C^YX``, ``T_diff = T^XY - T^YX`` (Eq. 10).

Direction convention (README "Direction", as in the code the paper used): a **negative**
difference reads as X -> Y, a positive one as Y -> X. It holds for systems of similar character
only: the asymmetry also follows the relative complexity of the two signals (a smooth response of
a rough driver can look like the driver), and near-zero differences mean "bidirectional or
uncoupled".

The triangle counts use bit-packed rows: ``tri_v = sum_{p in N(v)} popcount(A_Y[p] & CR_XY[v])``
over the words between v's first and last cross-neighbour, each unordered pair once, in a
compiled parallel kernel (about ``M_X * k * M_Y / 128`` word operations for mean cross-degree
``k``). Thresholds follow the rule of :mod:`funcnet.recurrence` (exact k-th order statistic of
the candidate distances, ``k = max(1, ceil(rate * P - 1e-9))``, ``d <= eps``; or
``rule="pyunicorn"``). Rates default to the paper's ``RR = CR = 0.05`` (section 3.4).

Signals are used as given: nothing in this module normalizes them, so a common threshold
``eps_xy`` compares raw amplitudes. :func:`funcnet.network.functional_network` normalizes each
signal of the data it receives (one analysis window) first, by default min-max (section 3.3).
"""

from __future__ import annotations

import numbers
import os
import sys
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numba import njit, prange

from funcnet.errors import ParameterError, SignalError, ThresholdWarning
from funcnet.recurrence import (
    PackedRecurrence,
    _check_eps,
    _check_options,
    _check_rate,
    _isrn_blocks,
    _lowest_bit,
    _popcount,
    auto_recurrence,
    cross_recurrence,
    signal_states,
)

__all__ = [
    "CrossMeasures",
    "isrn_measures",
    "cross_measures",
    "pairwise_cross_measures",
    "local_cross_clustering",
    "cross_degree",
]


@njit(cache=True)
def _row_triangles(row, auto_rows):
    """``(k_v, tri_v)`` of one packed cross-recurrence row against the packed ``auto_rows``."""
    first = -1
    last = -1
    degree = 0
    for w in range(row.size):
        if row[w]:
            if first < 0:
                first = w
            last = w
            degree += np.int64(_popcount(row[w]))
    # Each unordered neighbour pair p < q is counted once: for neighbour p, the AND runs over
    # the neighbours above p only (the rest of p's word, then the words up to v's last one).
    # Contiguous word ranges let the compiler vectorize the popcounts.
    pairs = 0
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
def _cross_triangles(cross_rows, auto_rows):
    """Per row v of ``cross_rows``: cross-degree k_v and ordered cross-triangles tri_v (Eq. 6-7)."""
    n_rows = cross_rows.shape[0]
    degree = np.zeros(n_rows, dtype=np.int64)
    triangles = np.zeros(n_rows, dtype=np.int64)
    for v in prange(n_rows):
        degree[v], triangles[v] = _row_triangles(cross_rows[v], auto_rows)
    return degree, triangles


def _cross_counts(
    a_x: PackedRecurrence,
    a_y: PackedRecurrence,
    cr_xy: PackedRecurrence,
    cr_yx: PackedRecurrence | None = None,
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """``(k_v, tri_v)`` of every node of X towards Y, then of every node of Y towards X."""
    if cr_yx is None:
        cr_yx = cr_xy.transposed()
    return _cross_triangles(cr_xy.rows, a_y.rows), _cross_triangles(cr_yx.rows, a_x.rows)


def _local_clustering(degree: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    pairs = degree * (degree - 1)
    local = np.zeros(degree.size, dtype=np.float64)
    np.divide(triangles, pairs, out=local, where=pairs > 0)
    return local


def _transitivity(degree: np.ndarray, triangles: np.ndarray) -> float:
    triples = int((degree * (degree - 1)).sum())
    return int(triangles.sum()) / triples if triples else 0.0


@dataclass(frozen=True)
class CrossMeasures:
    """Global cross measures of one pair of signals (X, Y), with the thresholds that made them.

    Attributes
    ----------
    c_xy, c_yx : float
        Global cross-clustering ``C^XY``, ``C^YX`` (Eq. 6-8).
    t_xy, t_yx : float
        Cross-transitivity ``T^XY``, ``T^YX`` (Eq. 9).
    c_diff, t_diff : float
        ``C^XY - C^YX`` and ``T^XY - T^YX`` (Eq. 10); negative reads as X -> Y.
    eps_x, eps_y, eps_xy : float
        Thresholds of ``A_X``, ``A_Y``, ``CR_XY`` (float64).
    rr_x, rr_y, cr : float
        Achieved rates (recurrent / candidate pairs).
    eps_ordered : bool
        ``eps_xy < min(eps_x, eps_y)``, as section 2.2 of the paper asks for a modular ISRN.
    rate_exceeded : bool
        Ties at a threshold made an achieved rate exceed its target.
    m_x, m_y : int
        Numbers of embedded states.
    parameters : dict
        The parameters that produced the values (dim, delay, rr, cr, eps, metric, rule, theiler).
    degenerate : tuple of str
        The blocks whose recurrence structure is degenerate -- ``"x"`` (``A_X``), ``"y"``
        (``A_Y``), ``"xy"`` (``CR_XY``): threshold 0, or an achieved rate more than twice its
        target. Too few distinct states (a signal that barely moves) cause it; the measures of
        such a pair say nothing about direction.
    """

    c_xy: float
    c_yx: float
    t_xy: float
    t_yx: float
    c_diff: float
    t_diff: float
    eps_x: float
    eps_y: float
    eps_xy: float
    rr_x: float
    rr_y: float
    cr: float
    eps_ordered: bool
    rate_exceeded: bool
    m_x: int
    m_y: int
    parameters: dict[str, Any] = field(default_factory=dict)
    degenerate: tuple[str, ...] = ()


def _is_degenerate(block: PackedRecurrence) -> bool:
    """Threshold 0, or an achieved rate more than twice its target: too few distinct states."""
    return block.eps == 0.0 or (block.target is not None and block.rate > 2 * block.target)


def isrn_measures(
    a_x: PackedRecurrence,
    a_y: PackedRecurrence,
    cr_xy: PackedRecurrence,
    *,
    cr_yx: PackedRecurrence | None = None,
    parameters: Mapping[str, Any] | None = None,
) -> CrossMeasures:
    """Cross measures of an ISRN given as precomputed packed blocks (Eq. 6-10).

    This is the kernel behind :func:`cross_measures`; call it directly to reuse ``A_X`` and
    ``A_Y`` across many cross-recurrences (functional networks, surrogate tests). It neither
    validates signals nor warns.

    Parameters
    ----------
    a_x, a_y : PackedRecurrence
        Recurrence adjacencies of X and Y (no self-loops), from
        :func:`funcnet.recurrence.auto_recurrence`.
    cr_xy : PackedRecurrence
        Cross-recurrence of X (rows) and Y (columns), from
        :func:`funcnet.recurrence.cross_recurrence`.
    cr_yx : PackedRecurrence, optional
        ``cr_xy.transposed()``, if already at hand.
    parameters : mapping, optional
        Stored in the result's ``parameters``.

    Returns
    -------
    CrossMeasures

    Raises
    ------
    ParameterError
        ``cr_xy`` is not ``M_X x M_Y``.

    References
    ----------
    Eq. 4 and 6-10 (section 2.2-2.4).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.recurrence import auto_recurrence, cross_recurrence, embed
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> xs, ys = embed(np.sin(t), 3, 10), embed(np.sin(1.5 * t) + 0.3 * np.sin(t), 3, 10)
    >>> a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    >>> result = isrn_measures(a_x, a_y, cross_recurrence(xs, ys, cr=0.01))
    >>> round(result.c_xy, 4), round(result.c_yx, 4)
    (0.2573, 0.1166)
    """
    if cr_xy.shape != (a_x.shape[0], a_y.shape[0]):
        raise ParameterError(
            f"cr_xy has shape {cr_xy.shape}, expected (M_x, M_y) = ({a_x.shape[0]}, {a_y.shape[0]})"
        )
    xy, yx = _cross_counts(a_x, a_y, cr_xy, cr_yx)
    c_xy = float(_local_clustering(*xy).mean())
    c_yx = float(_local_clustering(*yx).mean())
    t_xy = _transitivity(*xy)
    t_yx = _transitivity(*yx)
    return CrossMeasures(
        c_xy=c_xy,
        c_yx=c_yx,
        t_xy=t_xy,
        t_yx=t_yx,
        c_diff=c_xy - c_yx,
        t_diff=t_xy - t_yx,
        eps_x=a_x.eps,
        eps_y=a_y.eps,
        eps_xy=cr_xy.eps,
        rr_x=a_x.rate,
        rr_y=a_y.rate,
        cr=cr_xy.rate,
        eps_ordered=cr_xy.eps < min(a_x.eps, a_y.eps),
        rate_exceeded=a_x.rate_exceeded or a_y.rate_exceeded or cr_xy.rate_exceeded,
        m_x=a_x.shape[0],
        m_y=a_y.shape[0],
        parameters=dict(parameters or {}),
        degenerate=tuple(
            name for name, block in (("x", a_x), ("y", a_y), ("xy", cr_xy)) if _is_degenerate(block)
        ),
    )


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _caller_stacklevel() -> int:
    """``stacklevel`` of the first frame outside funcnet, seen from this function's caller.

    A warning then points at the user's call, whether it reached the measures directly or
    through :func:`funcnet.network.functional_network` or a study.
    """
    frame, level = sys._getframe(1), 1
    while frame.f_back is not None and frame.f_code.co_filename.startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    return level


def _degenerate_message(results: Mapping[tuple[str, str], CrossMeasures]) -> str | None:
    """The warning for pairs with a degenerate block, naming the signals behind it; or None."""
    causes: dict[str, str] = {}  # signal or pair -> its achieved rate and threshold
    pairs = []
    for (x, y), r in results.items():
        if not r.degenerate:
            continue
        pairs.append(f"({x}, {y})")
        if "x" in r.degenerate:
            causes.setdefault(f"signal {x}", f"rr {r.rr_x:.3g}, eps {r.eps_x:.3g}")
        if "y" in r.degenerate:
            causes.setdefault(f"signal {y}", f"rr {r.rr_y:.3g}, eps {r.eps_y:.3g}")
        if "xy" in r.degenerate:
            causes.setdefault(
                f"cross-recurrence of ({x}, {y})", f"cr {r.cr:.3g}, eps {r.eps_xy:.3g}"
            )
    if not pairs:
        return None
    return (
        "degenerate recurrence structure of "
        + "; ".join(f"{cause} ({numbers})" for cause, numbers in causes.items())
        + ": threshold 0 or an achieved rate more than twice its target, i.e. too few distinct "
        "states (e.g. a signal that barely moves); the arrows of "
        f"{len(pairs)} pair(s) are meaningless: {', '.join(pairs)}"
    )


def _warn_thresholds(results: Mapping[tuple[str, str], CrossMeasures]) -> None:
    """At most one ThresholdWarning per kind of problem, naming the pairs (and signals) with it.

    A degenerate block (:attr:`CrossMeasures.degenerate`) gets its own warning; the generic one
    about ties covers only the pairs whose rates overshoot slightly.
    """
    labels = {pair: f"({pair[0]}, {pair[1]})" for pair in results}
    problems = (
        (
            [labels[pair] for pair, r in results.items() if not r.eps_ordered],
            "eps_xy is not below eps_x and eps_y",
            "section 2.2 of the paper asks eps_xy < eps_x, eps_y for a modular ISRN "
            "(eps_ordered is False)",
        ),
        (
            [labels[pair] for pair, r in results.items() if r.rate_exceeded and not r.degenerate],
            "ties at a threshold pushed an achieved rate above its target",
            "see rr_x, rr_y, cr (rate_exceeded is True)",
        ),
    )
    messages = [
        f"{problem} for {len(pairs)} pair(s): {', '.join(pairs)}; {advice}"
        for pairs, problem, advice in problems
        if pairs
    ]
    degenerate = _degenerate_message(results)
    if degenerate is not None:
        messages.append(degenerate)
    for message in messages:
        warnings.warn(message, ThresholdWarning, stacklevel=_caller_stacklevel())


def cross_measures(
    x: Any,
    y: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    eps: Any = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
    theiler: int = 0,
) -> CrossMeasures:
    """Global cross-clustering and cross-transitivity of two signals, both directions.

    ``x`` and ``y`` are used as given: no normalization. Scale them yourself if they have
    different units; :func:`funcnet.network.functional_network` normalizes each signal of the
    data (window) it is given, min-max by default, before it calls the measures.

    Builds the ISRN of Eq. 4 (thresholds by rate: ``eps`` is the k-th smallest candidate distance,
    ``k = max(1, ceil(rate * P - 1e-9))``, with ``P = (M - w)(M - w - 1)`` ordered pairs
    ``|i - j| > w`` (``w = theiler``) for ``A_X``, ``A_Y`` and ``P = M_X M_Y`` for ``CR_XY``) and
    returns ``C^XY``, ``C^YX``, ``T^XY``, ``T^YX`` and their differences (Eq. 6-10).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,)
        The signals, used as given (no normalization); their lengths may differ.
    dim, delay : int
        Embedding dimension and delay in samples (Eq. 1); the paper's illustration uses 3, 10.
    rr : float in (0, 1)
        Recurrence rate of ``A_X`` and ``A_Y`` (default 0.05, section 3.4).
    cr : float in (0, 1)
        Cross-recurrence rate of ``CR_XY`` (default 0.05).
    eps : (eps_x, eps_y, eps_xy), optional
        Explicit thresholds; each overrides its rate (a None entry keeps the rate).
    metric : {"euclidean", "supremum", "manhattan"}
        Distance in phase space (Eq. 2-3 use Euclidean).
    rule : {"funcnet", "pyunicorn"}
        ``"funcnet"``: the exact rule above with ``d <= eps``; ``"pyunicorn"``: pyunicorn 1.0.0's
        (float32 input, index ``int(rate (P - 1))`` of the sorted full matrix, ``d < eps``).
    theiler : int
        Pairs with ``|i - j| <= theiler`` are left out of ``A_X``, ``A_Y`` and their rates.

    Returns
    -------
    CrossMeasures
        Negative ``c_diff``/``t_diff`` read as X -> Y (module notes).

    Raises
    ------
    ParameterError
        ``rr``/``cr`` outside (0, 1), non-positive ``eps``, unknown ``metric``/``rule``, bad
        ``dim``/``delay``/``theiler``.
    SignalError
        ``x`` or ``y`` holds NaN/inf or is too short for the embedding; the message names it.

    Warns
    -----
    ThresholdWarning
        ``eps_xy`` is not below ``eps_x`` and ``eps_y``, or ties pushed a rate above target; a
        separate one when a structure is degenerate (:attr:`CrossMeasures.degenerate`).

    References
    ----------
    Eq. 1-10 (section 2); README "The method, exactly", steps 4-7.

    Examples
    --------
    The coupled sine pair of Fig. 2:

    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x = np.sin(t)
    >>> y = np.sin(1.5 * t) + 0.3 * x
    >>> result = cross_measures(x, y, dim=3, delay=10, eps=(0.2, 0.4, 0.15))
    >>> round(result.c_xy, 4), round(result.c_yx, 4), result.eps_ordered
    (0.0866, 0.0519, True)
    """
    parameters: dict[str, Any] = {
        "dim": dim,
        "delay": delay,
        "rr": rr,
        "cr": cr,
        "eps": eps,
        "metric": metric,
        "rule": rule,
        "theiler": theiler,
    }
    a_x, a_y, cr_xy = _isrn_blocks(x, y, **parameters)
    parameters["eps"] = None if eps is None else tuple(eps)
    result = isrn_measures(a_x, a_y, cr_xy, parameters=parameters)
    _warn_thresholds({("x", "y"): result})
    return result


def _pairwise_eps(eps: Any, n_signals: int) -> tuple[list[float | None], float | None]:
    """Split pairwise ``eps`` (None or {"auto": float | sequence, "cross": float})."""
    if eps is None:
        return [None] * n_signals, None
    if not isinstance(eps, Mapping) or not set(eps) <= {"auto", "cross"}:
        raise ParameterError(
            f"eps must be None or a dict with keys 'auto' and/or 'cross', got {eps!r}"
        )
    auto = eps.get("auto")
    if auto is None or isinstance(auto, numbers.Real):
        per_signal = [auto] * n_signals
    else:
        per_signal = list(auto)
        if len(per_signal) != n_signals:
            raise ParameterError(
                f"eps['auto'] must be one number or one per signal ({n_signals}), got "
                f"{len(per_signal)}"
            )
    checked = [
        None if e is None else _check_eps(e, f"eps['auto'][{i}]") for i, e in enumerate(per_signal)
    ]
    cross = eps.get("cross")
    return checked, None if cross is None else _check_eps(cross, "eps['cross']")


def pairwise_cross_measures(
    signals: Sequence[Any] | np.ndarray,
    *,
    names: Sequence[str] | None = None,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    eps: Mapping[str, Any] | None = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
    theiler: int = 0,
) -> dict[tuple[int, int], CrossMeasures]:
    """Cross measures of every pair ``i < j`` of equally long signals (a functional network).

    Each signal is embedded and its recurrence adjacency computed once, then reused in all its
    pairs; only ``CR`` is computed per pair. Thresholds follow the same rule as
    :func:`cross_measures` (k-th order statistic, ``k = max(1, ceil(rate * P - 1e-9))``).

    Parameters
    ----------
    signals : sequence of array_like (N,), or 2-D array_like (N, n_signals)
        At least two signals of the same length, used as given (no normalization); a 2-D array
        (or DataFrame) holds one signal per column, time on axis 0.
    names : sequence of str, optional
        How error messages (``signal 'AP' ...``) and warnings (``(RP, AP)``) call the signals;
        by default by position (``signal signals[1] ...``, ``(0, 1)``).
    dim, delay, rr, cr, metric, rule, theiler
        As in :func:`cross_measures`.
    eps : dict, optional
        ``{"auto": float or one per signal, "cross": float}``; a missing key keeps its rate.

    Returns
    -------
    dict
        ``{(i, j): CrossMeasures}`` for ``i < j``, in lexicographic order; X is signal ``i``.

    Raises
    ------
    ParameterError, SignalError
        As :func:`cross_measures`; also fewer than two signals, unequal lengths, or ``names`` of
        the wrong length.

    Warns
    -----
    ThresholdWarning
        One warning listing the pairs whose ``eps_xy`` is not below ``eps_x``, ``eps_y``, one
        for those where ties pushed a rate slightly above target, and one naming the signals
        whose structure is degenerate (:attr:`CrossMeasures.degenerate`) and their pairs.

    References
    ----------
    Eq. 1-10 (section 2), section 2.4 (functional network over all pairs).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> signals = [np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t), np.cos(2 * t)]
    >>> results = pairwise_cross_measures(signals, eps={"cross": 0.1})
    >>> sorted(results)
    [(0, 1), (0, 2), (1, 2)]
    >>> round(results[(0, 1)].c_diff, 4)
    0.0173
    """
    if getattr(signals, "ndim", 1) == 2:  # an array or DataFrame, one signal per column
        table = np.asarray(signals)
        signals = [table[:, column] for column in range(table.shape[1])]
    signals = list(signals)
    if len(signals) < 2:
        raise SignalError(f"pairwise_cross_measures needs at least two signals, got {len(signals)}")
    if names is None:
        called = [f"signals[{i}]" for i in range(len(signals))]  # in messages
        labels = [str(i) for i in range(len(signals))]  # in pair labels
    else:
        labels = [str(name) for name in names]
        if len(labels) != len(signals):
            raise ParameterError(f"names has {len(labels)} entries for {len(signals)} signals")
        called = [repr(name) for name in labels]
    metric, rule, theiler = _check_options(metric, rule, theiler)
    auto_eps, cross_eps = _pairwise_eps(eps, len(signals))
    if any(e is None for e in auto_eps):
        rr = _check_rate(rr, "rr")
    if cross_eps is None:
        cr = _check_rate(cr, "cr")
    states = [
        signal_states(s, dim=dim, delay=delay, rule=rule, name=name)
        for s, name in zip(signals, called, strict=True)
    ]
    for i, s in enumerate(states[1:], start=1):
        if s.shape[0] != states[0].shape[0]:
            raise SignalError(
                f"signals must have equal lengths: {called[i]} differs from {called[0]} "
                f"({len(signals[i])} vs {len(signals[0])} samples)"
            )
    autos = [
        auto_recurrence(s, rr=rr, eps=e, metric=metric, theiler=theiler, rule=rule, name=name)
        for s, e, name in zip(states, auto_eps, called, strict=True)
    ]
    parameters: dict[str, Any] = {
        "dim": dim,
        "delay": delay,
        "rr": rr,
        "cr": cr,
        "eps": None if eps is None else dict(eps),
        "metric": metric,
        "rule": rule,
        "theiler": theiler,
    }
    results = {}
    for i in range(len(signals)):
        for j in range(i + 1, len(signals)):
            cr_ij = cross_recurrence(
                states[i], states[j], cr=cr, eps=cross_eps, metric=metric, rule=rule
            )
            results[(i, j)] = isrn_measures(autos[i], autos[j], cr_ij, parameters=parameters)
    _warn_thresholds({(labels[i], labels[j]): r for (i, j), r in results.items()})
    return results


def local_cross_clustering(
    x: Any,
    y: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    eps: Any = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
    theiler: int = 0,
) -> tuple[np.ndarray, np.ndarray]:
    """Local cross-clustering of every node, both directions (Eq. 6).

    ``C^XY(v) = tri_v / (k_v (k_v - 1))`` for ``v`` in X (0 where ``k_v < 2``), and ``C^YX(u)``
    for ``u`` in Y. Their means are ``C^XY`` and ``C^YX`` (Eq. 8).

    Parameters
    ----------
    x, y, dim, delay, rr, cr, eps, metric, rule, theiler
        As in :func:`cross_measures`.

    Returns
    -------
    c_xy_local : ndarray, shape (M_X,)
    c_yx_local : ndarray, shape (M_Y,)

    Raises
    ------
    ParameterError, SignalError
        As :func:`cross_measures`.

    References
    ----------
    Eq. 6-8 (section 2.3).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> c_xy, c_yx = local_cross_clustering(np.sin(t), np.sin(1.5 * t), eps=(0.15, 0.15, 0.05))
    >>> c_xy.shape, float(c_xy.max()) <= 1.0
    ((231,), True)
    """
    a_x, a_y, cr_xy = _isrn_blocks(
        x, y, dim=dim, delay=delay, rr=rr, cr=cr, eps=eps, metric=metric, theiler=theiler, rule=rule
    )
    xy, yx = _cross_counts(a_x, a_y, cr_xy)
    return _local_clustering(*xy), _local_clustering(*yx)


def cross_degree(
    x: Any,
    y: Any,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float = 0.05,
    cr: float = 0.05,
    eps: Any = None,
    metric: str = "euclidean",
    rule: str = "funcnet",
    theiler: int = 0,
) -> tuple[np.ndarray, np.ndarray]:
    """Cross-degree of every node, both directions (Eq. 7).

    ``k_v^XY`` = number of Y states within ``eps_xy`` of ``x_v``; ``k_u^YX`` likewise for Y.

    Parameters
    ----------
    x, y, dim, delay, rr, cr, eps, metric, rule, theiler
        As in :func:`cross_measures`.

    Returns
    -------
    k_xy : ndarray of int64, shape (M_X,)
    k_yx : ndarray of int64, shape (M_Y,)

    Raises
    ------
    ParameterError, SignalError
        As :func:`cross_measures`.

    References
    ----------
    Eq. 7 (section 2.3).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> k_xy, k_yx = cross_degree(np.sin(t), np.cos(t), cr=0.05)
    >>> int(k_xy.sum()) == int(k_yx.sum())
    True
    """
    _, _, cr_xy = _isrn_blocks(
        x, y, dim=dim, delay=delay, rr=rr, cr=cr, eps=eps, metric=metric, theiler=theiler, rule=rule
    )
    return cr_xy.row_sums(), cr_xy.transposed().row_sums()
