"""A direction for each pair that survives what a recording fixes: prediction from the past.

The paper's ``kind`` (:mod:`funcnet.network.rule`) reads the ISRN asymmetry, which never uses
the timing of the two signals: circularly shifting Y leaves ``C_diff`` and ``T_diff`` unchanged
(DESIGN section 1.6), so tested against a null that keeps each signal's structure and breaks
their timing it never differs from that null. On real robot recordings its arrows point into
the position set-point -- which nothing in a robot drives -- more often than out of it
(:mod:`funcnet.network.setpoint`). The ``direction`` column reads something else: whether one
signal's **past** improves the prediction of the other beyond the other's own past.

The test (one pair, both ways)
    For ``X -> Y``: the least-squares prediction of ``y[t]`` from ``1, y[t-1], ..., y[t-p]``
    (restricted) and from those and ``x[t-1], ..., x[t-p]`` (full); the F statistic of the
    residual sums of squares, ``((RSS_r - RSS_f) / p) / (RSS_f / (n - 2p - 1))``, ``n = N - p``
    predicted samples, and its upper tail p-value on ``(p, n - 2p - 1)`` degrees of freedom
    (a Granger test). ``p`` is the embedding span of the network, ``(dim - 1) * delay + 1``
    samples: the past a state of the network already holds (21 samples with the defaults).

The reading (abstaining where the data cannot tell)
    ``x->y`` when X's past improves Y's prediction at ``alpha / 2`` and Y's does not improve
    X's; ``y->x`` the reverse; ``none`` otherwise, with the reason: both ways (feedback, a
    shared command, or a logging offset between the two channels), neither way, a window too
    short for ``p`` lags, a degenerate pair, a multichannel node. ``alpha / 2``: the two
    directions of a pair are two tests (Bonferroni); pairs are not adjusted against each
    other (a pair's reading does not depend on how many other signals the network has).

Why this test (measured, docs/guide/direction.md)
    A set-point computed ahead by a planner is predicted by its own past; a measured signal of
    the axis is not, and the set-point's past improves it. Over the SINUMERIK trace and both
    KUKA runs (every axis and phase, and the whole robot) the reading points into a set-point
    for 0.4-4.8 % of the set-point pairs and out of it for 10-58 %; on the simulated plan (the
    36 trials of the paper, moving phases) 1.8 % into and 57 % out. On the UR5 runs, read after
    the method was fixed, 5-14 %: their current set-point RC carries the planner's
    feed-forward. Timing is no shortcut: the lead of one signal's cross-map skill over the
    other's points from the current into the position (an acceleration leads the position it
    produces), and the conditional-recurrence index and convergent cross mapping need
    surrogates a smooth window does not hold.
    Linear prediction assumes the relation is near linear over ``p`` samples; a nonlinear
    coupling the linear past misses reads ``none``, not a wrong arrow.

References
----------
C. W. J. Granger, "Investigating causal relations by econometric models and cross-spectral
methods", Econometrica 37, 424-438 (1969).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd
from scipy import special

from funcnet.errors import ParameterError
from funcnet.parameters import NetworkParameters

__all__ = ["DIRECTIONS", "DIRECTION_ALPHA", "direction_lags", "prediction_p", "read_direction",
           "direction_columns"]

#: Values of the ``direction`` column.
DIRECTIONS: tuple[str, ...] = ("x->y", "y->x", "none")

#: Level of a pair's two tests together (each at half of it).
DIRECTION_ALPHA = 0.05


def direction_lags(parameters: NetworkParameters) -> int:
    """The lags ``p`` of the test: the embedding span ``(dim - 1) * delay + 1``.

    Examples
    --------
    >>> direction_lags(NetworkParameters()), direction_lags(NetworkParameters(delay=1))
    (21, 3)
    """
    return (parameters.dim - 1) * parameters.delay + 1


def _lagged(v: np.ndarray, p: int) -> np.ndarray:
    n = v.size
    return np.column_stack([v[p - k - 1 : n - k - 1] for k in range(p)])


def prediction_p(x: Any, y: Any, lags: int) -> float:
    """p-value that X's past improves the linear prediction of Y beyond Y's own past.

    Parameters
    ----------
    x, y : array_like, shape (N,)
        Equally long signals (standardized here: any affine scaling gives the same p-value).
    lags : int
        ``p``, samples of each past.

    Returns
    -------
    float
        The F test's upper-tail p-value; NaN when ``N - 3 p - 1 < 1`` (too short), a signal
        is constant or the full prediction is exact.

    Raises
    ------
    ParameterError
        ``lags < 1`` or signals of unequal length.

    References
    ----------
    Granger (1969).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(400)
    >>> y = np.concatenate([[0.0], 0.8 * x[:-1]]) + 0.3 * rng.standard_normal(400)
    >>> prediction_p(x, y, 2) < 1e-6, prediction_p(y, x, 2) > 0.05
    (True, True)
    """
    if isinstance(lags, bool) or not isinstance(lags, (int, np.integer)) or lags < 1:
        raise ParameterError.of("lags", f"must be an integer >= 1, got {lags!r}")
    xs = np.asarray(x, dtype=np.float64).ravel()
    ys = np.asarray(y, dtype=np.float64).ravel()
    if xs.size != ys.size:
        raise ParameterError.of("y", f"has {ys.size} samples, x has {xs.size}")
    past_x, past_y = _Past.of(xs, int(lags)), _Past.of(ys, int(lags))
    return _p_value(past_x, past_y)


class _Past:
    """A signal standardized, its lagged design ``1, v[t-1..t-p]``, and the residual sum of
    squares of its prediction from its own past (shared by every pair it is the target of)."""

    def __init__(self, values: np.ndarray | None, lags: int) -> None:
        self.lags = lags
        self.values = values
        self.size = 0 if values is None else values.size
        if values is None:
            return
        self.target = values[lags:]
        self.own = np.column_stack([np.ones(self.target.size), _lagged(values, lags)])
        self.rss = _rss(self.own, self.target)

    @classmethod
    def of(cls, v: np.ndarray, lags: int) -> _Past:
        # too short (N - 3p - 1 < 1) or constant: nothing to test (values None)
        if v.size - 3 * lags - 1 < 1 or np.ptp(v) == 0:
            empty = cls(None, lags)
            empty.size = v.size
            return empty
        return cls((v - v.mean()) / v.std(), lags)


def _rss(design: np.ndarray, target: np.ndarray) -> float:
    residual = target - design @ np.linalg.lstsq(design, target, rcond=None)[0]
    return float(residual @ residual)


def _p_value(x: _Past, y: _Past) -> float:
    """p-value that X's past improves Y's prediction beyond Y's own (both prepared)."""
    if x.values is None or y.values is None:
        return float("nan")
    p = y.lags
    dfd = y.values.size - p - (2 * p + 1)
    full = _rss(np.column_stack([y.own, x.own[:, 1:]]), y.target)
    if full <= 0.0:
        return float("nan")
    f = max(y.rss - full, 0.0) / p / (full / dfd)
    return float(special.fdtrc(p, dfd, f))  # the F distribution's upper tail (f.sf)


def _g(value: float) -> str:
    return f"{value:.2g}"


def read_direction(x: Any, y: Any, lags: int, *, alpha: float = DIRECTION_ALPHA,
                   names: tuple[str, str] = ("X", "Y")) -> tuple[str, str]:
    """The direction of one pair and why (module notes).

    Parameters
    ----------
    x, y : array_like, shape (N,)
    lags : int
        ``p`` (:func:`direction_lags`).
    alpha : float in (0, 1)
        Level of the pair's two tests together; each is decided at ``alpha / 2``.
    names : (str, str)
        The signals' names, for the reason.

    Returns
    -------
    (str, str)
        One of :data:`DIRECTIONS` and one sentence saying why.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(400)
    >>> y = np.concatenate([[0.0], 0.8 * x[:-1]]) + 0.3 * rng.standard_normal(400)
    >>> read_direction(x, y, 2, names=("RP", "AC"))
    ('x->y', "RP's past improves AC's prediction (p 3.8e-181), AC's does not improve RP's (p 0.6)")
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
    return _reading(_Past.of(xs, int(lags)), _Past.of(ys, int(lags)), alpha, names)


def _reading(px: _Past, py: _Past, alpha: float, names: tuple[str, str]) -> tuple[str, str]:
    """:func:`read_direction` of two prepared pasts."""
    lags = px.lags
    a, b = names
    forward = _p_value(px, py)
    backward = _p_value(py, px)
    if np.isnan(forward) or np.isnan(backward):
        n = px.size
        if n < 3 * lags + 2:
            return "none", (f"window too short: {n} samples for {lags} lags (needs at least "
                            f"{3 * lags + 2})")
        return "none", "a signal constant or predicted exactly by its own past: nothing to test"
    level = alpha / 2
    fwd, bwd = forward <= level, backward <= level
    if fwd and not bwd:
        return "x->y", (f"{a}'s past improves {b}'s prediction (p {_g(forward)}), {b}'s does "
                        f"not improve {a}'s (p {_g(backward)})")
    if bwd and not fwd:
        return "y->x", (f"{b}'s past improves {a}'s prediction (p {_g(backward)}), {a}'s does "
                        f"not improve {b}'s (p {_g(forward)})")
    if fwd and bwd:
        return "none", (f"each past improves the other's prediction (p {_g(forward)}, "
                        f"{_g(backward)}): feedback, a shared command or a logging offset")
    return "none", (f"neither past improves the other's prediction (p {_g(forward)}, "
                    f"{_g(backward)})")


def direction_columns(pairs: pd.DataFrame, signals: Mapping[str, Any],
                      parameters: NetworkParameters,
                      alpha: float = DIRECTION_ALPHA) -> dict[str, list[str]]:
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

    Returns
    -------
    dict
        ``{"direction": [...], "direction_reason": [...]}``, in the rows' order.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> x = rng.standard_normal(300)
    >>> y = np.concatenate([[0.0], x[:-1]]) + 0.5 * rng.standard_normal(300)
    >>> pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "degenerate": [False]})
    >>> direction_columns(pairs, {"A": x, "B": y}, NetworkParameters(delay=1))["direction"]
    ['x->y']
    """
    lags = direction_lags(parameters)
    if not 0.0 < alpha < 1.0:
        raise ParameterError.of("alpha", f"must be in (0, 1), got {alpha!r}")
    out: dict[str, list[str]] = {"direction": [], "direction_reason": []}
    pasts: dict[Any, _Past | None] = {}  # each node prepared once for all its pairs

    def past(name: Any) -> _Past | None:
        if name not in pasts:
            v = np.asarray(signals[name], dtype=np.float64)
            pasts[name] = (None if v.ndim > 1 and v.shape[1] > 1
                           else _Past.of(v.ravel(), lags))
        return pasts[name]

    for x, y, flagged in zip(pairs["x"], pairs["y"], pairs["degenerate"], strict=True):
        if bool(flagged):
            reading = ("none", "degenerate pair: too few distinct states")
            out["direction"].append(reading[0])
            out["direction_reason"].append(reading[1])
            continue
        px, py = past(x), past(y)
        if px is None or py is None:
            reading = ("none", "a multichannel node: the test reads one channel per node")
        else:
            reading = _reading(px, py, alpha, (str(x), str(y)))
        out["direction"].append(reading[0])
        out["direction_reason"].append(reading[1])
    return out


def check_directions(values: Sequence[str]) -> None:
    """Raise a :class:`ParameterError` for a value outside :data:`DIRECTIONS`.

    Examples
    --------
    >>> check_directions(["none", "x->y"])
    """
    bad = sorted(set(values) - set(DIRECTIONS))
    if bad:
        raise ParameterError.of("direction", f"holds {bad}; values are {list(DIRECTIONS)}")
