"""A direction for each pair that survives what a recording fixes: prediction from the past.

The paper's ``kind`` (:mod:`funcnet.network.rule`) reads the ISRN asymmetry, which never uses
the timing of the two signals: circularly shifting Y leaves ``C_diff`` and ``T_diff`` unchanged
(docs/validation/evidence.md, 'What the asymmetry measures'), so tested against a null that
keeps each signal's structure and breaks their timing it never differs from that null. On real
robot recordings its arrows point into the position set-point -- which nothing in a robot drives
-- more often than out of it (:mod:`funcnet.network.setpoint`). The ``direction`` column reads
something else: whether one signal's **past** improves the prediction of the other beyond the
other's own past.

The test (one pair, both ways)
    For ``X -> Y``: the least-squares prediction of ``y[t]`` from ``1, y[t-1], ..., y[t-p]``
    (restricted) and from those and X's past after a gap of ``g`` samples,
    ``x[t-1-g], ..., x[t-p-g]`` (full); the F statistic of the residual sums of squares,
    ``((RSS_r - RSS_f) / p) / (RSS_f / (n - 2p - 1))``, ``n = N - p - g`` predicted samples,
    and its upper tail p-value on ``(p, n - 2p - 1)`` degrees of freedom (a Granger test).
    ``p`` is the embedding span of the network, ``(dim - 1) * delay + 1`` samples: the past a
    state of the network already holds (21 samples with the defaults). ``g`` is
    :data:`DIRECTION_GAP` (1): channels of one controller are logged up to a sample apart (a
    measured position logged before the set-point it follows, encoders read milliseconds
    apart), which turns a simultaneous relation into a lag-1 one; a simultaneous relation has
    no direction (Granger's instantaneous causality), so the other signal's lag 1 is left out.
    A coupling that acts within one sample reads ``none``.

The reading (abstaining where the data cannot tell)
    ``x->y`` when X's past improves Y's prediction at ``alpha / 2`` and Y's does not improve
    X's (or X is predicted within its logged step, below); ``y->x`` the reverse; ``none``
    otherwise, with the reason: both ways (feedback, a shared command, or a logging offset
    between the two channels), neither way, a window too short for ``p`` lags, a constant
    signal, both predicted within their logged steps, a degenerate pair, a multichannel node.
    ``alpha / 2``: the two directions of a pair are two tests (Bonferroni); pairs are not
    adjusted against each other (a pair's reading does not depend on how many other signals
    the network has).

The log's precision
    A signal its own past predicts to within the precision it is logged with -- root mean
    square error at most one step of its grid (:func:`logged_step`), its own past explaining
    all but 1 % of its variance over the window -- has nothing left that the log can show:
    whatever improves its prediction further does so below one step, as a signal following
    its true value would by undoing the rounding of the past the prediction rests on, without
    acting on it. No improvement of it is shown: an arrow into it is never read; its own past
    may still improve another's. The same holds for a signal its own past predicts exactly (to
    the rounding of the arithmetic). This holds for any signal, whatever its role. A coarse
    signal its own past does not predict (a few levels of noise) stays testable: a drive of it
    below one step still reads. On the recordings it is what the stored precision makes of a
    planned set-point: the KUKA files keep it in single precision, and every arrow into a
    set-point there claimed an improvement of one its own past predicts to 0.2-0.9 of a step.

The computation
    :mod:`funcnet.network._prediction`: each signal's lags are replaced by differences that
    span the same columns exactly (every residual is the same number; the rounding is that of
    the differences, not of the levels of a smooth position), one QR factorization of a
    window's design serves every pair of it, and every window of a call is read in one stacked
    pass. Numerically rank-deficient designs drop the singular directions least squares drops.
    Windows cut one row apart from a recording (a sliding timeline) share their factors along
    the run (:mod:`funcnet.network._sliding`).
    The p-values agree across OpenBLAS kernels to a relative 1e-6 and with exact rational
    arithmetic to 1e-7 (tests/test_direction_kernels.py); with the previous implementation
    (the levels factored as they stand) the decisions are equal.

Why this test (measured, docs/validation/direction.md)
    A set-point computed ahead by a planner is predicted by its own past; a measured signal of
    the axis is not, and the set-point's past improves it. Over the SINUMERIK trace, both
    KUKA runs and five UR5 runs (every axis and phase, and the whole robot) the reading points
    into a set-point for 0-7.8 % of the set-point pairs (<= 5 % on 14 of the 15 groups, 0 on
    the SINUMERIK and KUKA recordings); on the simulated plan (the 36 trials of the paper,
    moving phases) 0 % into and 51 % out.
    Before the precision rule: without the gap the UR5 axes read 5.3-9.5 % into (mostly
    ``RC -> RP``: RC's lag 1 carries the set-point's next sample), and the time-reversal check
    (Haufe et al. 2013) removed nearly every arrow, those out of the set-point too (0.8 % out
    on the simulated plan). Timing is no
    shortcut: the lead of one signal's cross-map skill over the other's points from the
    current into the position (an acceleration leads the position it produces), and the
    conditional-recurrence index and convergent cross mapping need surrogates a smooth window
    does not hold. Linear prediction assumes the relation is near linear over ``p`` samples; a
    nonlinear coupling the linear past misses reads ``none``, not a wrong arrow.

References
----------
C. W. J. Granger, "Investigating causal relations by econometric models and cross-spectral
methods", Econometrica 37, 424-438 (1969).
S. Haufe, V. V. Nikulin, K.-R. Mueller, G. Nolte, "A critical assessment of connectivity
measures for EEG data: a simulation study", NeuroImage 64, 120-133 (2013).
I. Winkler, D. Panknin, D. Bartz, K.-R. Mueller, S. Haufe, "Validity of time reversal for
testing Granger causality", IEEE Trans. Signal Process. 64, 2746-2760 (2016).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError
from funcnet.network._prediction import pair_p_values
from funcnet.network._sliding import sliding_p_values
from funcnet.network.precision import checked_steps, logged_step
from funcnet.parameters import NetworkParameters

__all__ = ["DIRECTIONS", "DIRECTION_ALPHA", "DIRECTION_GAP", "direction_lags", "prediction_p",
           "read_direction", "direction_columns", "window_directions", "window_p_values"]

#: Values of the ``direction`` column.
DIRECTIONS: tuple[str, ...] = ("x->y", "y->x", "none")

#: Level of a pair's two tests together (each at half of it).
DIRECTION_ALPHA = 0.05

#: Samples of the other signal's past left out before its lags begin: a logging offset of one
#: sample between two channels makes their lag-1 relation a simultaneous one, which has no
#: direction.
DIRECTION_GAP = 1


def direction_lags(parameters: NetworkParameters) -> int:
    """The lags ``p`` of the test: the embedding span ``(dim - 1) * delay + 1``.

    Examples
    --------
    >>> direction_lags(NetworkParameters()), direction_lags(NetworkParameters(delay=1))
    (21, 3)
    """
    return (parameters.dim - 1) * parameters.delay + 1


def _p_matrix(columns: np.ndarray, lags: int, gap: int,
              steps: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """p-values of every ordered pair of columns of one window: ``P[i, j]`` that column j's
    past (lags ``gap + 1 .. gap + p``) improves the prediction of column i beyond i's own past
    (lags ``1 .. p``); NaN: too short, constant, or exact. With them ``W[i, j]``: column i's
    own past predicts it to within its logged step (``steps[i]`` in the columns' unit; default
    :func:`logged_step` of each column), or to the rounding of the arithmetic
    (:func:`funcnet.network._prediction.pair_p_values`, one window).
    """
    if steps is None:
        steps = np.array([logged_step(column) for column in columns.T])
    values = np.asarray(columns, dtype=np.float64)
    if values.ndim != 2 or values.shape[1] == 0:
        k = values.shape[1] if values.ndim == 2 else 0
        return np.full((k, k), np.nan), np.zeros((k, k), dtype=bool)
    found, within = pair_p_values(values[np.newaxis], lags, gap,
                                  np.asarray(steps, dtype=np.float64)[np.newaxis])
    return found[0], within[0]


def prediction_p(x: Any, y: Any, lags: int, *, gap: int = DIRECTION_GAP) -> float:
    """p-value that X's past improves the linear prediction of Y beyond Y's own past.

    Parameters
    ----------
    x, y : array_like, shape (N,)
        Equally long signals (standardized here: any affine scaling gives the same p-value).
    lags : int
        ``p``, samples of each past.
    gap : int
        Samples of X's past left out: X's lags are ``gap + 1 .. gap + p`` (Y's own ``1 .. p``).

    Returns
    -------
    float
        The F test's upper-tail p-value; NaN when ``N - 3 p - 1 - gap < 1`` (too short), a
        signal is constant, or Y's own past predicts it to the rounding of the arithmetic.

    Raises
    ------
    ParameterError
        ``lags < 1``, ``gap < 0`` or signals of unequal length.

    References
    ----------
    Granger (1969).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(400)
    >>> y = np.concatenate([[0.0, 0.0], 0.8 * x[:-2]]) + 0.3 * rng.standard_normal(400)
    >>> prediction_p(x, y, 2) < 1e-6, prediction_p(y, x, 2) > 0.05
    (True, True)
    >>> prediction_p(x[:-1], y[1:], 2) > 0.05, prediction_p(x[:-1], y[1:], 2, gap=0) < 1e-6
    (True, True)
    """
    if isinstance(lags, bool) or not isinstance(lags, (int, np.integer)) or lags < 1:
        raise ParameterError.of("lags", f"must be an integer >= 1, got {lags!r}")
    xs = np.asarray(x, dtype=np.float64).ravel()
    ys = np.asarray(y, dtype=np.float64).ravel()
    if xs.size != ys.size:
        raise ParameterError.of("y", f"has {ys.size} samples, x has {xs.size}")
    return float(_p_matrix(np.column_stack([xs, ys]), int(lags), _gap(gap), np.zeros(2))[0][1, 0])


def _g(value: float) -> str:
    return f"{value:.2g}"


def read_direction(x: Any, y: Any, lags: int, *, gap: int = DIRECTION_GAP,
                   alpha: float = DIRECTION_ALPHA, names: tuple[str, str] = ("X", "Y"),
                   steps: tuple[float, float] | None = None) -> tuple[str, str]:
    """The direction of one pair and why (module notes).

    Parameters
    ----------
    x, y : array_like, shape (N,)
    lags : int
        ``p`` (:func:`direction_lags`).
    gap : int
        As :func:`prediction_p` (:data:`DIRECTION_GAP`).
    alpha : float in (0, 1)
        Level of the pair's two tests together; each is decided at ``alpha / 2``.
    names : (str, str)
        The signals' names, for the reason.
    steps : (float, float), optional
        The precision X and Y are logged with, in their units; default :func:`logged_step`
        of each (0: none).

    Returns
    -------
    (str, str)
        One of :data:`DIRECTIONS` and one sentence saying why.

    Raises
    ------
    ParameterError
        ``alpha`` outside (0, 1), ``lags < 1``, ``gap < 0``, signals of unequal length, or
        ``steps`` not two finite steps >= 0.

    References
    ----------
    Granger (1969).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(400)
    >>> y = np.concatenate([[0.0, 0.0], 0.8 * x[:-2]]) + 0.3 * rng.standard_normal(400)
    >>> read_direction(x, y, 2, names=("RP", "AC"))
    ('x->y', "RP's past improves AC's prediction (p 1.2e-175), AC's does not improve RP's (p 0.8)")
    >>> read_direction(x, rng.standard_normal(400), 2)[0]
    'none'
    """
    if not 0.0 < alpha < 1.0:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha!r}")
    xs, ys = (np.asarray(v, dtype=np.float64).ravel() for v in (x, y))
    if xs.size != ys.size:
        raise ParameterError.of("y", f"has {ys.size} samples, x has {xs.size}")
    if isinstance(lags, bool) or not isinstance(lags, (int, np.integer)) or lags < 1:
        raise ParameterError.of("lags", f"must be an integer >= 1, got {lags!r}")
    if steps is not None:
        if len(steps) != 2:
            raise ParameterError.of("steps", f"must hold the steps of X and Y, got {steps!r}")
        checked_steps(dict(zip(names, steps, strict=True)), names)
    found, within = _p_matrix(np.column_stack([xs, ys]), int(lags), _gap(gap),
                              None if steps is None else np.asarray(steps, dtype=np.float64))
    return _reading((found[1, 0], found[0, 1]), (within[1, 0], within[0, 1]), xs.size,
                    int(lags), int(gap), alpha, names)


def _gap(gap: int) -> int:
    if isinstance(gap, bool) or not isinstance(gap, (int, np.integer)) or gap < 0:
        raise ParameterError.of("gap", f"must be an integer >= 0, got {gap!r}")
    return int(gap)


def _reading(p_values: tuple[float, float], within: tuple[bool, bool], n: int, lags: int,
             gap: int, alpha: float, names: tuple[str, str]) -> tuple[str, str]:
    """:func:`read_direction` of a pair's two p-values (X's past for Y, Y's for X) and whether
    each target's own past predicts it to within its logged step (Y, then X)."""
    (forward, backward), (a, b) = p_values, names
    if n < 3 * lags + 2 + gap:
        return "none", (f"window too short: {n} samples for {lags} lags (needs at least "
                        f"{3 * lags + 2 + gap})")
    if np.isnan(forward) and not within[0] or np.isnan(backward) and not within[1]:
        return "none", ("a constant signal, or one the other's past predicts exactly: nothing "
                        "to test")
    if within[0] and within[1]:
        return "none", ("each is predicted by its own past exactly or to within its logged "
                        "step: no improvement of either can be shown")
    level = alpha / 2
    fwd, bwd = not within[0] and forward <= level, not within[1] and backward <= level

    def improves(source: str, target: str, p: float, found: bool, logged: bool) -> str:
        if logged:
            return (f"{target} is predicted by its own past exactly or to within its logged "
                    f"step, so no improvement of it can be shown")
        if found:
            return f"{source}'s past improves {target}'s prediction (p {_g(p)})"
        return f"{source}'s does not improve {target}'s (p {_g(p)})"

    one = improves(a, b, forward, fwd, within[0])
    other = improves(b, a, backward, bwd, within[1])
    if fwd and not bwd:
        return "x->y", f"{one}; {other}" if within[1] else f"{one}, {other}"
    if bwd and not fwd:
        return "y->x", f"{other}; {one}" if within[0] else f"{other}, {one}"
    if fwd and bwd:
        return "none", (f"each past improves the other's prediction (p {_g(forward)}, "
                        f"{_g(backward)}): feedback, a shared command or a logging offset")
    if within[0] or within[1]:
        return "none", f"{one}; {other}"
    return "none", (f"neither past improves the other's prediction (p {_g(forward)}, "
                    f"{_g(backward)})")


def direction_columns(pairs: pd.DataFrame, signals: Mapping[str, Any],
                      parameters: NetworkParameters, alpha: float = DIRECTION_ALPHA, *,
                      steps: Mapping[str, float] | None = None) -> dict[str, list[str]]:
    """``direction`` and ``direction_reason`` of every row of a pairs table.

    Parameters
    ----------
    pairs : pandas.DataFrame
        At least ``x``, ``y`` and ``degenerate``.
    signals : mapping of str to array_like
        Each node's samples, shape (N,) or (N, c) (a multichannel node reads ``none``).
    parameters : NetworkParameters
        Its ``dim`` and ``delay`` set the lags (:func:`direction_lags`).
    alpha : float
        As :func:`read_direction`.
    steps : mapping of str to float, optional
        The precision each node is logged with, in its signal's unit (a normalized signal's
        step is its channel's scaled alike); a node not named: :func:`logged_step` of its
        signal.

    Returns
    -------
    dict
        ``{"direction": [...], "direction_reason": [...]}``, in the rows' order.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> x = rng.standard_normal(300)
    >>> y = np.concatenate([[0.0, 0.0], x[:-2]]) + 0.5 * rng.standard_normal(300)
    >>> pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "degenerate": [False]})
    >>> direction_columns(pairs, {"A": x, "B": y}, NetworkParameters(delay=1))["direction"]
    ['x->y']
    """
    # plain lists: fast to walk
    return _direction_rows(pairs["x"].tolist(), pairs["y"].tolist(),
                           [bool(flagged) for flagged in pairs["degenerate"].tolist()],
                           signals, parameters, alpha, steps=steps)


def _direction_rows(first: Sequence[Any], second: Sequence[Any], tested: list[bool],
                    signals: Mapping[str, Any], parameters: NetworkParameters,
                    alpha: float = DIRECTION_ALPHA, *,
                    steps: Mapping[str, float] | None = None) -> dict[str, list[str]]:
    """:func:`direction_columns` of the table whose columns ``x``, ``y`` and ``degenerate``
    are ``first``, ``second`` and ``tested`` (plain lists, as a caller building the table has
    them), without making the table."""
    lags = direction_lags(parameters)
    if not 0.0 < alpha < 1.0:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha!r}")
    out: dict[str, list[str]] = {"direction": [], "direction_reason": []}
    # every node of the table, tested or not (a degenerate pair's where given): the same
    # columns whichever pairs a window flags, as in :func:`window_directions`
    names = list(dict.fromkeys(name for x, y, flagged in zip(first, second, tested,
                                                             strict=True)
                               for name in (x, y) if not flagged or name in signals))
    arrays = {name: np.asarray(signals[name], dtype=np.float64) for name in names}
    single = [name for name in names if arrays[name].ndim < 2 or arrays[name].shape[1] == 1]
    sizes = {arrays[name].shape[0] for name in single}
    if len(sizes) > 1:
        raise ParameterError.of("signals", f"have unequal lengths {sorted(sizes)}")
    column = {name: k for k, name in enumerate(single)}
    n = sizes.pop() if sizes else 0
    # every pair of the window at once
    known = checked_steps(steps, list(signals))
    found, within = _p_matrix(
        np.column_stack([arrays[name].ravel() for name in single]) if single
        else np.empty((0, 0)), lags, DIRECTION_GAP,
        np.array([known[name] if name in known else logged_step(arrays[name])
                  for name in single]))
    index = [(column.get(x, -1), column.get(y, -1), str(x), str(y))
             for x, y in zip(first, second, strict=True)]
    _read_rows(found.tolist(), within.tolist(), index, tested, n, lags, alpha, out)
    return out


def _read_rows(p_values: list[list[float]], within: list[list[bool]],
               index: list[tuple[int, int, str, str]], flags: list[bool], n: int, lags: int,
               alpha: float, out: dict[str, list[str]]) -> None:
    """Append the readings of one window's rows to ``out``: each row's columns ``(i, j)`` in
    the window's p-values (-1: a multichannel node), its names, and whether it is degenerate
    (plain lists: this loop runs once per row of every window)."""
    directions, reasons = out["direction"], out["direction_reason"]
    for (i, j, x, y), flagged in zip(index, flags, strict=True):
        if flagged:
            reading = ("none", "degenerate pair: too few distinct states")
        elif i < 0 or j < 0:
            reading = ("none", "a multichannel node: the test reads one channel per node")
        else:
            reading = _reading((p_values[j][i], p_values[i][j]), (within[j][i], within[i][j]),
                               n, lags, DIRECTION_GAP, alpha, (x, y))
        directions.append(reading[0])
        reasons.append(reading[1])


def window_p_values(windows: Sequence[np.ndarray], parameters: NetworkParameters,
                    steps: np.ndarray, *, origin: tuple[np.ndarray, np.ndarray] | None = None
                    ) -> list[tuple[list[list[float]], list[list[bool]]]]:
    """The p-values that :func:`window_directions` reads, each window's, computed apart: a
    caller may compute them while it computes the windows' degenerate flags.

    Parameters
    ----------
    windows, parameters, steps, origin
        As :func:`window_directions`.

    Returns
    -------
    list
        Per window ``(p_values, within)``, plain nested lists ``k x k``: at ``[j][i]`` the
        p-value of column ``i``'s past for column ``j``, and whether ``j``'s own past predicts
        it to within its logged step; pass it as ``window_directions(..., p_values=...)``.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> x = rng.standard_normal(600)
    >>> y = np.concatenate([[0.0, 0.0], x[:-2]]) + 0.5 * rng.standard_normal(600)
    >>> found = window_p_values([np.column_stack([x, y])], NetworkParameters(delay=1),
    ...                         np.zeros((1, 2)))
    >>> bool(found[0][0][1][0] < 1e-6), found[0][1][1][0]
    (True, False)
    """
    lags = direction_lags(parameters)
    by_length: dict[int, list[int]] = {}
    for w, part in enumerate(windows):
        by_length.setdefault(part.shape[0], []).append(w)
    found: list[Any] = [None] * len(windows)
    all_steps = np.asarray(steps, dtype=np.float64)
    for members in by_length.values():  # windows of one length: one stack
        stack = np.stack([windows[w] for w in members])
        if origin is None:
            values, within = pair_p_values(stack, lags, DIRECTION_GAP, all_steps[members])
        else:
            values, within = sliding_p_values(stack, origin[0], np.asarray(origin[1])[members],
                                              lags, DIRECTION_GAP, all_steps[members])
        for slot, w in enumerate(members):  # plain lists: fast to walk
            found[w] = (values[slot].tolist(), within[slot].tolist())
    return found


def window_directions(windows: Sequence[np.ndarray], names: Sequence[str],
                      pairs: Sequence[tuple[str, str]], degenerate: np.ndarray,
                      parameters: NetworkParameters, steps: np.ndarray,
                      alpha: float = DIRECTION_ALPHA, *,
                      origin: tuple[np.ndarray, np.ndarray] | None = None,
                      p_values: list[tuple[list[list[float]], list[list[bool]]]] | None = None,
                      ) -> dict[str, list[str]]:
    """:func:`direction_columns` of many windows' pairs tables at once, one stacked pass.

    Parameters
    ----------
    windows : sequence of ndarray, shape (N_w, k)
        Each window's nodes (single-channel, in the order of ``names``), normalized as the
        networks' are.
    names : sequence of str
        The ``k`` nodes.
    pairs : sequence of (str, str)
        The rows of each window's table, the same for every window.
    degenerate : ndarray of bool, shape (W, len(pairs))
        Each window's degenerate rows.
    parameters : NetworkParameters
        Its ``dim`` and ``delay`` set the lags.
    steps : ndarray, shape (W, k)
        Each node's logged step in its window's unit.
    alpha : float
        As :func:`read_direction`.
    origin : (ndarray, ndarray), optional
        ``(values, firsts)``: the recording's rows ``(T, k)`` and each window's first row, the
        window being an affine map of each column of ``values[firsts[w] : firsts[w] + N_w]``.
        Windows one row apart are then read by factors shared along their run
        (:mod:`funcnet.network._sliding`: the same p-values to a relative 1e-6 but where the
        inputs' rounding sets them).
    p_values : list, optional
        :func:`window_p_values` of the same windows, steps and origin, computed already.

    Returns
    -------
    dict
        ``{"direction": [...], "direction_reason": [...]}``: every window's rows, in order;
        each window's equal to :func:`direction_columns` of its table (without ``origin``).

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> x = rng.standard_normal(600)
    >>> y = np.concatenate([[0.0, 0.0], x[:-2]]) + 0.5 * rng.standard_normal(600)
    >>> parts = [np.column_stack([x, y])[:300], np.column_stack([y, x])[300:]]
    >>> window_directions(parts, ["A", "B"], [("A", "B")], np.zeros((2, 1), bool),
    ...                   NetworkParameters(delay=1), np.zeros((2, 2)))["direction"]
    ['x->y', 'y->x']
    """
    lags = direction_lags(parameters)
    if not 0.0 < alpha < 1.0:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha!r}")
    found = (window_p_values(windows, parameters, steps, origin=origin) if p_values is None
             else p_values)
    column = {name: k for k, name in enumerate(names)}
    index = [(column[x], column[y], str(x), str(y)) for x, y in pairs]
    out: dict[str, list[str]] = {"direction": [], "direction_reason": []}
    for w, flags in enumerate(np.asarray(degenerate, dtype=bool).tolist()):
        values, within = found[w]
        _read_rows(values, within, index, flags, windows[w].shape[0], lags, alpha, out)
    return out
