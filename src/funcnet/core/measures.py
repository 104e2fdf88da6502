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

Direction convention (docs/guide/direction.md, as in the code the paper used): a **negative**
difference reads as X -> Y, a positive one as Y -> X. It holds for systems of similar character
only: the asymmetry also follows the relative complexity of the two signals (a smooth response of
a rough driver can look like the driver), and near-zero differences mean "bidirectional or
uncoupled".

The triangle counts use bit-packed rows: ``tri_v = sum_{p in N(v)} popcount(A_Y[p] & CR_XY[v])``
over the words between v's first and last cross-neighbour, each unordered pair once, in a
compiled parallel kernel (about ``M_X * k * M_Y / 128`` word operations for mean cross-degree
``k``). For long windows (auto matrices beyond 32 MiB, M > ~16,400) a blocked kernel counts
both directions in one pass, reading each auto row once per block of 256 cross rows; the
integer counts, and so every value, are the same. Thresholds follow the rule of
:mod:`funcnet.core.recurrence` (exact k-th order statistic of the candidate distances,
``k = max(1, ceil(rate * P))`` for the rate as written in decimal, ``d <= eps``; or
``rule="pyunicorn"``). Parameters come as a :class:`funcnet.parameters.NetworkParameters`
(``parameters=``) and keyword overrides; the
defaults are the paper's ``RR = CR = 0.05`` (section 3.4).

A pair is **degenerate** when one of its blocks says nothing: a threshold of 0 or an achieved
rate more than twice its target (too few distinct states, e.g. a signal that barely moves), or
a constant signal. Its numbers are computed as for any pair, but ``degenerate`` is True and
``degenerate_reason`` names the block; such a pair says nothing about direction.

Signals are used as given: nothing in this module normalizes them, so a common threshold
``eps_xy`` compares raw amplitudes. :func:`funcnet.network.functional_network` normalizes each
signal of the data it receives (one analysis window) first, by default min-max (section 3.3).

Length: over 600 lines because of the numpydoc of seven public names; the code is about 330.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Unpack

import numba
import numpy as np

from funcnet.core import _batch_kernels
from funcnet.core._isrn_kernels import (
    _METRIC_CODE,
    _cross_triangles,
    _cross_triangles_both,
    _transpose_packed,
)
from funcnet.core.embedding import MIN_STATES, signal_states, thinned
from funcnet.core.recurrence import (
    PackedRecurrence,
    _check_channels,
    _check_states,
    _cross_block,
    _isrn_blocks,
    _state_range,
    auto_recurrence,
)
from funcnet.core.thresholds import (
    _auto_candidates,
    _auto_rank,
    _cross_rank,
    _unordered_rank,
    block_threshold,
    signal_thresholds,
)
from funcnet.errors import (
    DegenerateWarning,
    FuncnetWarning,
    ParameterError,
    SignalError,
    ThresholdWarning,
    caller_stacklevel,
)
from funcnet.parameters import PAIR_FIELDS, NetworkParameters, ParameterOverrides, resolve

__all__ = [
    "CrossMeasures",
    "isrn_measures",
    "cross_measures",
    "pairwise_cross_measures",
    "threshold_warnings",
    "local_cross_clustering",
    "cross_degree",
]


# The triangle kernel: row-wise while the auto matrices fit in the last-level cache (32 MiB
# here), blocked above (each auto row read once per block of 64 * _BLOCK_WORDS cross rows).
# Measured on the real trace (benchmarks/bench_long.py, CPU time): the blocked kernel is
# 0.5-0.9x the row-wise one up to M = 10,000, 0.93-1.17x at 15,000 and 1.4-2.6x at 22,686;
# b = 4 was the fastest block.
_BLOCKED_BYTES = 32 * 2**20
_BLOCK_WORDS = 4


def _cross_counts(
    a_x: PackedRecurrence, a_y: PackedRecurrence, cr_xy: PackedRecurrence
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """``(k_v, tri_v)`` of every node of X towards Y, then of every node of Y towards X."""
    cr_yx = _transpose_packed(cr_xy.rows, cr_xy.n_cols)
    if max(a_x.rows.nbytes, a_y.rows.nbytes) < _BLOCKED_BYTES:
        return _cross_triangles(cr_xy.rows, a_y.rows), _cross_triangles(cr_yx, a_x.rows)
    k_xy, tri_xy, k_yx, tri_yx = _cross_triangles_both(
        cr_xy.rows, cr_yx, a_x.rows, a_y.rows, _BLOCK_WORDS, numba.get_num_threads()
    )
    return (k_xy, tri_xy), (k_yx, tri_yx)


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
    achieved_rr_x, achieved_rr_y, achieved_cr : float
        Achieved rates (recurrent / candidate pairs); the targets are ``parameters.rr`` and
        ``parameters.cr``.
    eps_ordered : bool
        ``eps_xy < min(eps_x, eps_y)``, as section 2.2 of the paper asks for a modular ISRN.
    rate_exceeded : bool
        Ties at a threshold made an achieved rate exceed its target.
    degenerate : bool
        A block's recurrence structure is degenerate: threshold 0, an achieved rate more than
        twice its target (too few distinct states), or a constant signal. The measures of such
        a pair say nothing about direction.
    degenerate_reason : str
        ``""`` unless degenerate; else each degenerate block and why, e.g. ``"signal x:
        threshold 0 (too few distinct states)"``, joined by ``"; "``.
    m_x, m_y : int
        Numbers of embedded states.
    parameters : NetworkParameters or None
        The parameters that produced the values (for a pair of a larger set, restricted to the
        pair: per-signal ``rr`` and ``eps`` become ``(x's, y's)``); None only from
        :func:`isrn_measures` called without them.
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
    achieved_rr_x: float
    achieved_rr_y: float
    achieved_cr: float
    eps_ordered: bool
    rate_exceeded: bool
    degenerate: bool
    degenerate_reason: str
    m_x: int
    m_y: int
    parameters: NetworkParameters | None


def _degenerate_reason(
    label: str, constant: bool, eps: float, rate: float, target: float | None
) -> str:
    """Why a block is degenerate (``""`` when it is not), from its threshold, achieved rate and
    target rate (None: an explicit threshold)."""
    if constant:
        return f"{label}: constant (a single distinct state)"
    if eps == 0.0:
        return f"{label}: threshold 0 (too few distinct states)"
    if target is not None and rate > 2 * target:
        return (
            f"{label}: achieved rate {rate:.3g} over twice its target {target:.3g} "
            "(too few distinct states)"
        )
    return ""


# (constant, eps, achieved rate, target rate or None) of a block: what its reason is made of.
_Block = tuple[bool, float, float, float | None]


def _block_labels(x: str, y: str) -> tuple[str, str, str]:
    """How ``degenerate_reason`` calls the blocks ``A_X``, ``A_Y``, ``CR_XY`` of signals x, y."""
    return f"signal {x}", f"signal {y}", f"cross-recurrence ({x}, {y})"


_XY_LABELS = _block_labels("x", "y")


def _pair_measures(
    measures: tuple[float, float, float, float],
    blocks: tuple[_Block, _Block, _Block],
    rate_exceeded: bool,
    labels: tuple[str, str, str],
    n_states: tuple[int, int],
    parameters: NetworkParameters | None,
) -> CrossMeasures:
    """The result of a pair from ``(c_xy, c_yx, t_xy, t_yx)`` and the numbers of its blocks
    ``A_X``, ``A_Y``, ``CR_XY`` (:func:`_block_labels` names them): the differences,
    ``eps_ordered`` and the reasons."""
    c_xy, c_yx, t_xy, t_yx = measures
    (constant_x, eps_x, rate_x, target_x), (constant_y, eps_y, rate_y, target_y), (
        constant_xy, eps_xy, rate_xy, target_xy) = blocks
    label_x, label_y, label_xy = labels
    reasons = [
        reason
        for reason in (
            _degenerate_reason(label_x, constant_x, eps_x, rate_x, target_x),
            _degenerate_reason(label_y, constant_y, eps_y, rate_y, target_y),
            _degenerate_reason(label_xy, constant_xy, eps_xy, rate_xy, target_xy),
        )
        if reason
    ]
    return CrossMeasures(
        c_xy=c_xy,
        c_yx=c_yx,
        t_xy=t_xy,
        t_yx=t_yx,
        c_diff=c_xy - c_yx,
        t_diff=t_xy - t_yx,
        eps_x=eps_x,
        eps_y=eps_y,
        eps_xy=eps_xy,
        achieved_rr_x=rate_x,
        achieved_rr_y=rate_y,
        achieved_cr=rate_xy,
        eps_ordered=eps_xy < min(eps_x, eps_y),
        rate_exceeded=rate_exceeded,
        degenerate=bool(reasons),
        degenerate_reason="; ".join(reasons),
        m_x=n_states[0],
        m_y=n_states[1],
        parameters=parameters,
    )


def isrn_measures(
    a_x: PackedRecurrence,
    a_y: PackedRecurrence,
    cr_xy: PackedRecurrence,
    *,
    parameters: NetworkParameters | None = None,
    names: tuple[str, str] = ("x", "y"),
) -> CrossMeasures:
    """Cross measures of an ISRN given as precomputed packed blocks (Eq. 6-10).

    This is the kernel behind :func:`cross_measures`; call it directly to reuse ``A_X`` and
    ``A_Y`` across many cross-recurrences (functional networks, surrogate tests). It neither
    validates signals nor warns. ``CR_YX`` is computed as the transpose of ``cr_xy`` (cheap
    next to the triangle counts), so that it cannot disagree with it.

    Parameters
    ----------
    a_x, a_y : PackedRecurrence
        Recurrence adjacencies of X and Y (no self-loops), from
        :func:`funcnet.core.recurrence.auto_recurrence`.
    cr_xy : PackedRecurrence
        Cross-recurrence of X (rows) and Y (columns), from
        :func:`funcnet.core.recurrence.cross_recurrence`.
    parameters : NetworkParameters, optional
        Stored in the result's ``parameters``.
    names : (str, str)
        How ``degenerate_reason`` calls X and Y.

    Returns
    -------
    CrossMeasures

    Raises
    ------
    ParameterError
        ``a_x`` or ``a_y`` is not square, or ``cr_xy`` is not ``M_X x M_Y``.

    References
    ----------
    Eq. 4 and 6-10 (section 2.2-2.4).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.core.embedding import embed
    >>> from funcnet.core.recurrence import auto_recurrence, cross_recurrence
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> xs, ys = embed(np.sin(t), 3, 10), embed(np.sin(1.5 * t) + 0.3 * np.sin(t), 3, 10)
    >>> a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    >>> result = isrn_measures(a_x, a_y, cross_recurrence(xs, ys, cr=0.01))
    >>> round(result.c_xy, 4), round(result.c_yx, 4), result.degenerate
    (0.2573, 0.1166, False)
    """
    for label, block in (("a_x", a_x), ("a_y", a_y)):
        if block.shape[0] != block.shape[1]:
            raise ParameterError.of(label, f"must be square, got shape {block.shape}")
    if cr_xy.shape != (a_x.shape[0], a_y.shape[0]):
        raise ParameterError.of(
            "cr_xy",
            f"has shape {cr_xy.shape}, expected (M_x, M_y) = ({a_x.shape[0]}, {a_y.shape[0]})",
        )
    xy, yx = _cross_counts(a_x, a_y, cr_xy)
    return _pair_measures(
        (float(_local_clustering(*xy).mean()), float(_local_clustering(*yx).mean()),
         _transitivity(*xy), _transitivity(*yx)),
        ((a_x.constant, a_x.eps, a_x.rate, a_x.target), (a_y.constant, a_y.eps, a_y.rate,
         a_y.target), (cr_xy.constant, cr_xy.eps, cr_xy.rate, cr_xy.target)),
        a_x.rate_exceeded or a_y.rate_exceeded or cr_xy.rate_exceeded,
        _block_labels(*names), (a_x.shape[0], a_y.shape[0]), parameters,
    )


# --------------------------------------------------------------------------------------------
# warnings, built from the results' flags


def _targets(result: CrossMeasures) -> tuple[float | None, float | None, float | None]:
    """Target rates of (A_X, A_Y, CR_XY); None where an explicit threshold was used or the
    parameters do not say (none stored, or per-signal values of more than the pair)."""
    p = result.parameters
    if p is None:
        return None, None, None
    auto, cross = p.eps if p.eps is not None else (None, None)
    targets: list[float | None] = []
    for side in (0, 1):
        rate: Any = p.rr[side] if isinstance(p.rr, tuple) and len(p.rr) == 2 else p.rr
        eps = auto[side] if isinstance(auto, tuple) and len(auto) == 2 else auto
        known = not isinstance(rate, tuple) and not isinstance(eps, tuple)
        targets.append(float(rate) if known and eps is None else None)
    return targets[0], targets[1], None if cross is not None else p.cr


def _degenerate_blocks(result: CrossMeasures) -> tuple[bool, bool, bool]:
    """Which blocks of a degenerate pair are degenerate, from its numbers and parameters."""
    targets = _targets(result)
    blocks = []
    for eps, rate, target, auto in (
        (result.eps_x, result.achieved_rr_x, targets[0], True),
        (result.eps_y, result.achieved_rr_y, targets[1], True),
        (result.eps_xy, result.achieved_cr, targets[2], False),
    ):
        # A constant signal at an explicit threshold shows as a complete A_X (rate 1).
        blocks.append(
            eps == 0.0
            or (target is not None and rate > 2 * target)
            or (auto and target is None and rate == 1.0)
        )
    return blocks[0], blocks[1], blocks[2]


def threshold_warnings(
    results: Mapping[tuple[Any, Any], CrossMeasures],
) -> list[FuncnetWarning]:
    """The warnings the flags of ``results`` call for: at most one per problem.

    Pure: nothing is emitted (``warnings.warn(w)`` each to emit them, as
    :func:`pairwise_cross_measures` does with ``warn=True``). Signal names come from the keys.

    Parameters
    ----------
    results : mapping
        ``{(x, y): CrossMeasures}``, e.g. from :func:`pairwise_cross_measures`.

    Returns
    -------
    list of FuncnetWarning
        In this order, each only if some pair has the problem:
        :class:`~funcnet.errors.ThresholdWarning` ``problem="eps_order"`` (``eps_xy`` not below
        ``eps_x`` and ``eps_y``), ``problem="rate_exceeded"`` (ties pushed a rate slightly above
        its target; degenerate pairs are not listed again), and
        :class:`~funcnet.errors.DegenerateWarning` ``problem="degenerate"`` naming the signals
        whose structure is degenerate in ``signals``. ``pairs`` lists the pairs concerned.

    References
    ----------
    Section 2.2 (``eps_xy < eps_x, eps_y`` for a modular ISRN).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> result = cross_measures(np.sin(t), np.cos(t), eps=(0.1, 0.2), warn=False)
    >>> [(w.problem, w.pairs) for w in threshold_warnings({("RP", "AP"): result})]
    [('eps_order', (('RP', 'AP'),))]
    """
    named = {(str(x), str(y)): r for (x, y), r in results.items()}
    label = {pair: f"({pair[0]}, {pair[1]})" for pair in named}
    found: list[FuncnetWarning] = []
    unordered = [pair for pair, r in named.items() if not r.eps_ordered]
    if unordered:
        found.append(
            ThresholdWarning(
                f"eps_xy is not below eps_x and eps_y for {len(unordered)} pair(s): "
                f"{', '.join(label[p] for p in unordered)}; section 2.2 of the paper asks "
                "eps_xy < eps_x, eps_y for a modular ISRN (eps_ordered is False)",
                problem="eps_order",
                pairs=tuple(unordered),
            )
        )
    exceeded = [pair for pair, r in named.items() if r.rate_exceeded and not r.degenerate]
    if exceeded:
        found.append(
            ThresholdWarning(
                "ties at a threshold pushed an achieved rate above its target for "
                f"{len(exceeded)} pair(s): {', '.join(label[p] for p in exceeded)}; see "
                "achieved_rr_x, achieved_rr_y, achieved_cr (rate_exceeded is True)",
                problem="rate_exceeded",
                pairs=tuple(exceeded),
            )
        )
    degenerate = [pair for pair, r in named.items() if r.degenerate]
    if degenerate:
        causes: dict[str, str] = {}  # signal or pair -> its achieved rate and threshold
        signals: list[str] = []
        for pair in degenerate:
            r = named[pair]
            x, y = pair
            in_x, in_y, in_xy = _degenerate_blocks(r)
            for flagged, name, rate, eps in (
                (in_x, x, r.achieved_rr_x, r.eps_x),
                (in_y, y, r.achieved_rr_y, r.eps_y),
            ):
                if flagged and name not in signals:
                    signals.append(name)
                    causes[f"signal {name}"] = f"rr {rate:.3g}, eps {eps:.3g}"
            if in_xy:
                causes.setdefault(
                    f"cross-recurrence of ({x}, {y})",
                    f"cr {r.achieved_cr:.3g}, eps {r.eps_xy:.3g}",
                )
        found.append(
            DegenerateWarning(
                "degenerate recurrence structure"
                + (" of " if causes else "")
                + "; ".join(f"{cause} ({numbers})" for cause, numbers in causes.items())
                + ": threshold 0, an achieved rate more than twice its target or a constant "
                "signal, i.e. too few distinct states (e.g. a signal that barely moves); the "
                f"arrows of {len(degenerate)} pair(s) are meaningless: "
                f"{', '.join(label[p] for p in degenerate)}",
                problem="degenerate",
                signals=tuple(signals),
                pairs=tuple(degenerate),
            )
        )
    return found


def _warn(results: Mapping[tuple[Any, Any], CrossMeasures]) -> None:
    for warning in threshold_warnings(results):
        warnings.warn(warning, stacklevel=caller_stacklevel())


# --------------------------------------------------------------------------------------------
# signals -> measures


def cross_measures(
    x: Any,
    y: Any,
    *,
    parameters: NetworkParameters | None = None,
    warn: bool = True,
    **overrides: Unpack[ParameterOverrides],
) -> CrossMeasures:
    """Global cross-clustering and cross-transitivity of two signals, both directions.

    ``x`` and ``y`` are used as given: no normalization. Scale them yourself if they have
    different units; :func:`funcnet.network.functional_network` normalizes each signal of the
    data (window) it is given, min-max by default, before it calls the measures.

    Builds the ISRN of Eq. 4 (thresholds by rate: ``eps`` is the k-th smallest candidate distance,
    ``k = max(1, ceil(rate * P))`` exactly for the decimal rate, with ``P = (M - w)(M - w - 1)``
    ordered pairs ``|i - j| > w`` (``w = theiler``) for ``A_X``, ``A_Y`` and ``P = M_X M_Y`` for
    ``CR_XY``) and returns ``C^XY``, ``C^YX``, ``T^XY``, ``T^YX`` and their differences
    (Eq. 6-10).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,), or (N, c) multichannel nodes
        The signals, used as given (no normalization); their lengths may differ. A 2-D signal
        is one node: each channel is embedded and the states concatenated.
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay`` (Eq. 1), ``rr`` (one rate, or ``(rr_x, rr_y)``), ``cr``,
        ``eps`` (``(auto, cross)``: ``auto`` one threshold or ``(eps_x, eps_y)``; a None entry
        keeps its rate), ``metric``, ``rule`` (``"funcnet"``: the exact rule above with
        ``d <= eps``; ``"pyunicorn"``: pyunicorn 1.0.0's), ``theiler`` (pairs with
        ``|i - j| <= theiler`` are left out of ``A_X``, ``A_Y`` and their rates). Defaults: the
        paper's (:class:`~funcnet.parameters.NetworkParameters`).
    warn : bool
        Emit :func:`threshold_warnings` of the result (default True).
    **overrides
        Any of those fields (``rr=0.1``, ``eps=(0.2, 0.15)``...).

    Returns
    -------
    CrossMeasures
        Negative ``c_diff``/``t_diff`` read as X -> Y (module notes). A constant signal, or one
        with too few distinct states, gives a ``degenerate`` result, not an error.

    Raises
    ------
    ParameterError
        A bad parameter (named), a parameter that is not a pair's (``mu``...), ``eps`` not
        ``(auto, cross)``.
    SignalError
        ``x`` or ``y`` holds NaN/inf, is too short (fewer than 7 states), or has amplitudes
        whose distances overflow float64; the message names it.

    Warns
    -----
    ThresholdWarning
        ``eps_xy`` is not below ``eps_x`` and ``eps_y``, or ties pushed a rate above target.
    DegenerateWarning
        The pair is degenerate (:attr:`CrossMeasures.degenerate`).

    References
    ----------
    Eq. 1-10 (section 2); docs/guide/method.md, steps 4-7.

    Examples
    --------
    The coupled sine pair of Fig. 2:

    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x = np.sin(t)
    >>> y = np.sin(1.5 * t) + 0.3 * x
    >>> result = cross_measures(x, y, dim=3, delay=10, eps=((0.2, 0.4), 0.15))
    >>> round(result.c_xy, 4), round(result.c_yx, 4), result.eps_ordered
    (0.0866, 0.0519, True)
    """
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    result = _short_pair(x, y, p)
    if result is None:
        a_x, a_y, cr_xy = _isrn_blocks(x, y, p)
        result = isrn_measures(a_x, a_y, cr_xy, parameters=p)
    if warn and (not result.eps_ordered or result.rate_exceeded or result.degenerate):
        if result.degenerate:  # its message names the rates and thresholds
            _warn({("x", "y"): result})
        else:
            # The pair's other warnings depend on its two flags only: built once each.
            flags = (result.eps_ordered, result.rate_exceeded)
            if flags not in _PAIR_WARNINGS:
                _PAIR_WARNINGS[flags] = threshold_warnings({("x", "y"): result})
            for warning in _PAIR_WARNINGS[flags]:
                warnings.warn(warning, stacklevel=caller_stacklevel())
    return result


_PAIR_WARNINGS: dict[tuple[bool, bool], list[FuncnetWarning]] = {}


def _short_pair(x: Any, y: Any, p: NetworkParameters) -> CrossMeasures | None:
    """The measures of a short pair through the batched engine's kernel, or None.

    Applies to equally long 1-D real signals of at most
    :data:`funcnet.core._batch_kernels.DIRECT_MAX_STATES` states, thresholds by rate, values finite
    and below 1e38 in magnitude; the kernel gives the general path's numbers bit for bit
    (:mod:`funcnet.core._batch_kernels`) without its validation and packed blocks, which cost most
    of a short pair's time. Everything else (including every input the
    general path rejects) returns None and takes the general path.
    """
    if p.eps is not None:
        return None
    x, y = np.asarray(x), np.asarray(y)
    if x.ndim != 1 or y.shape != x.shape or x.dtype.kind not in "biuf" or (
        y.dtype.kind not in "biuf"
    ):
        return None
    m = x.shape[0] - (p.dim - 1) * p.delay
    if not MIN_STATES <= m <= _batch_kernels.DIRECT_MAX_STATES or p.theiler >= m - 1:
        return None
    rates = p.rr if isinstance(p.rr, tuple) else (p.rr, p.rr)
    if len(rates) != 2:
        return None
    pyunicorn = p.rule == "pyunicorn"
    rank_x = _unordered_rank(_auto_rank(rates[0], m, p.theiler, pyunicorn))
    rank_y = _unordered_rank(_auto_rank(rates[1], m, p.theiler, pyunicorn))
    rank_xy = _cross_rank(p.cr, m * m, pyunicorn)
    (plain, eps_x, count_x, eps_y, count_y, eps_xy, count_xy, c_xy, c_yx, t_xy, t_yx,
     constant_x, constant_y) = _batch_kernels.pair_kernel(
        np.ascontiguousarray(x, dtype=np.float64), np.ascontiguousarray(y, dtype=np.float64),
        pyunicorn, p.dim, p.delay, _METRIC_CODE[p.metric], p.theiler, pyunicorn,
        rank_x, rank_y, rank_xy,
    )
    if not plain:
        return None
    n_candidates = _auto_candidates(m, p.theiler)
    return _pair_measures(
        (c_xy, c_yx, t_xy, t_yx),
        ((constant_x, eps_x, count_x / n_candidates, rates[0]),
         (constant_y, eps_y, count_y / n_candidates, rates[1]),
         (False, eps_xy, count_xy / (m * m), p.cr)),
        count_x > 2 * rank_x or count_y > 2 * rank_y or count_xy > rank_xy,
        _XY_LABELS, (m, m), p,
    )


def pairwise_cross_measures(
    signals: Sequence[Any] | np.ndarray,
    *,
    names: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    warn: bool = True,
    step: int = 1,
    **overrides: Unpack[ParameterOverrides],
) -> dict[tuple[Any, Any], CrossMeasures]:
    """Cross measures of every pair ``i < j`` of equally long signals (a functional network).

    Each signal is embedded and its recurrence adjacency computed once, then reused in all its
    pairs; only ``CR`` is computed per pair, reduced to counts and freed before the next, so
    memory is ``n_signals + 2`` packed ``M x M`` bit matrices (about 64 MB each at
    M = 22,700) plus one threshold's candidate band. Thresholds follow the same rule as
    :func:`cross_measures`. :func:`funcnet.core.recurrence.estimate_cost` forecasts time and
    memory from the length.

    Parameters
    ----------
    signals : sequence of array_like (N,) or (N, c), or 2-D array_like (N, n_signals)
        At least two signals of the same length ``N``, used as given (no normalization). A 2-D
        array (or DataFrame) holds one signal per column, time on axis 0; in a sequence, a 2-D
        entry ``(N, c)`` is one multichannel node (its channels embedded jointly).
    names : sequence of str, optional
        The signals' names: the keys of the result, and how error messages (``signal 'AP'
        ...``), ``degenerate_reason`` and warnings (``(RP, AP)``) call them. By default the
        keys are positions and messages say ``signals[1]``.
    parameters : NetworkParameters, optional
        As in :func:`cross_measures`; ``rr`` and the auto part of ``eps`` may hold one entry
        per signal.
    warn : bool
        Emit :func:`threshold_warnings` of the results (default True); with False nothing is
        emitted (collect them from the results, e.g. in threads).
    step : int
        Every ``step``-th state of each signal (:func:`~funcnet.core.embedding.signal_states`):
        a long window's network on a bounded number of states, each embedded at the full rate;
        the Theiler window, in samples, becomes ``ceil(theiler / step)`` thinned states.
    **overrides
        Fields of ``parameters``, as in :func:`cross_measures`.

    Returns
    -------
    dict
        ``{(name_i, name_j): CrossMeasures}`` (``(i, j)`` without ``names``) for ``i < j``, in
        lexicographic order of positions; X is signal ``i``.

    Raises
    ------
    ParameterError, SignalError
        As :func:`cross_measures`; also fewer than two signals, unequal lengths, ``names`` of
        the wrong length, per-signal ``rr``/``eps`` of the wrong length.

    Warns
    -----
    ThresholdWarning, DegenerateWarning
        With ``warn=True``: at most one per problem, listing its pairs
        (:func:`threshold_warnings`).

    References
    ----------
    Eq. 1-10 (section 2), section 2.4 (functional network over all pairs).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> signals = [np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t), np.cos(2 * t)]
    >>> results = pairwise_cross_measures(signals, names=["a", "b", "c"], eps=(None, 0.1))
    >>> sorted(results)
    [('a', 'b'), ('a', 'c'), ('b', 'c')]
    >>> round(results[("a", "b")].c_diff, 4)
    0.0173
    """
    if getattr(signals, "ndim", 1) == 2:  # an array or DataFrame, one signal per column
        table = np.asarray(signals)
        signals = [table[:, column] for column in range(table.shape[1])]
    signals = list(signals)
    n = len(signals)
    if n < 2:
        raise SignalError(f"pairwise_cross_measures needs at least two signals, got {n}")
    keys: list[Any]
    if names is None:
        called = [f"signals[{i}]" for i in range(n)]  # in messages
        labels = [str(i) for i in range(n)]  # in reasons
        keys = list(range(n))
    else:
        labels = [str(name) for name in names]
        if len(labels) != n:
            raise ParameterError.of("names", f"has {len(labels)} entries for {n} signals")
        called = [repr(name) for name in labels]
        keys = labels
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    thresholds, (cr, cross_eps) = signal_thresholds(p, n)
    states = [signal_states(s, parameters=p, name=name, step=step)
              for s, name in zip(signals, called, strict=True)]
    p = thinned(p, step)
    _check_channels(states, called, p.dim)
    for i in range(1, n):
        if np.shape(signals[i])[0] != np.shape(signals[0])[0]:
            raise SignalError(
                f"signals must have equal lengths: {called[i]} differs from {called[0]} "
                f"({np.shape(signals[i])[0]} vs {np.shape(signals[0])[0]} samples)"
            )
    autos = [
        auto_recurrence(s, rr=rate, eps=eps, parameters=p, name=name)
        for s, (rate, eps), name in zip(states, thresholds, called, strict=True)
    ]
    # each signal's states checked, and their ranges taken, once for all its pairs
    checked = [_check_states(s, name) for s, name in zip(states, called, strict=True)]
    ranges = [_state_range(s) for s in checked]
    target, eps_xy = block_threshold(p, cr, cross_eps, auto=False)
    results = {}
    labelled = {}  # the same results keyed by names, for the warnings
    for i in range(n):
        for j in range(i + 1, n):
            cr_ij = _cross_block(checked[i], checked[j], target, eps_xy, p,
                                 (called[i], called[j]), (ranges[i], ranges[j]))
            result = isrn_measures(
                autos[i], autos[j], cr_ij, parameters=p.for_pair(i, j),
                names=(labels[i], labels[j]),
            )
            # One pair's cross structure at a time (M^2 / 8 bytes each): free it before the
            # next pair's is built.
            del cr_ij
            results[(keys[i], keys[j])] = labelled[(labels[i], labels[j])] = result
    if warn:
        _warn(labelled)
    return results


def local_cross_clustering(
    x: Any,
    y: Any,
    *,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> tuple[np.ndarray, np.ndarray]:
    """Local cross-clustering of every node, both directions (Eq. 6).

    ``C^XY(v) = tri_v / (k_v (k_v - 1))`` for ``v`` in X (0 where ``k_v < 2``), and ``C^YX(u)``
    for ``u`` in Y. Their means are ``C^XY`` and ``C^YX`` (Eq. 8).

    Parameters
    ----------
    x, y, parameters, **overrides
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
    >>> c_xy, c_yx = local_cross_clustering(np.sin(t), np.sin(1.5 * t), eps=(0.15, 0.05))
    >>> c_xy.shape, float(c_xy.max()) <= 1.0
    ((231,), True)
    """
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    a_x, a_y, cr_xy = _isrn_blocks(x, y, p)
    xy, yx = _cross_counts(a_x, a_y, cr_xy)
    return _local_clustering(*xy), _local_clustering(*yx)


def cross_degree(
    x: Any,
    y: Any,
    *,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> tuple[np.ndarray, np.ndarray]:
    """Cross-degree of every node, both directions (Eq. 7).

    ``k_v^XY`` = number of Y states within ``eps_xy`` of ``x_v``; ``k_u^YX`` likewise for Y.

    Parameters
    ----------
    x, y, parameters, **overrides
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
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    _, _, cr_xy = _isrn_blocks(x, y, p)
    return cr_xy.row_sums(), cr_xy.transposed().row_sums()
