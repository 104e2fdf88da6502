"""The direction reading's least squares: every ordered pair of every window of a call at once.

For a target ``y`` and a source ``x`` the models are ``y[t]`` on ``1, y[t-1..t-p]``
(restricted) and on those and ``x[t-1-g..t-p-g]`` (full); :mod:`funcnet.network.direction`
reads them.

Conditioning (an exact reparametrisation)
    The lags of a smooth signal are nearly the same column, and a signal its own past predicts
    well leaves a residual many orders under its own size: factored as they stand, the
    residual sums of squares are whatever the BLAS kernel's rounding makes of them (the
    computed residual errs by about ``eps cond(design) |y|``). Each node's lags are therefore
    replaced by differences that span the same columns exactly: with ``d`` the node's
    difference order, lags ``1..p`` of ``v`` span the same space as ``Δ^q v[t-1]`` for
    ``q < d`` and ``Δ^d v[t-1-m]`` for ``m = 0..p-1-d`` (and likewise from ``t-1-g`` for a
    source), and the target ``y[t]`` differs from ``Δ^d y[t]`` by a combination of its own
    lags 1..d: every residual, hence every p-value, is the same number. Differences of the
    recorded values are exact to a rounding of their own size, where the factorization of the
    levels rounds at the size of the levels. ``d`` is the order (at most ``min(p, 8)``) whose
    differences vary least over the window (the variate-difference choice): a smooth signal is
    differenced down to its noise, white noise not at all. Columns are centred (the intercept
    takes their means) and scaled to unit norm (least squares does not depend on a column's
    scale; the rank decisions below then compare like with like).

The factorization
    One QR factorization of a window's design (every column of every node) serves every pair
    of it: a pair's design and target are a column subset ``W S = Q (R_W S)``, factored small
    (at most ``1 + k (p + g + 1 + d)`` rows however long the window). In the triangular factor
    ``R`` of a pair (target column ``c = 2 p + 1``) the full model's residual sum of squares is
    ``R[c, c]^2`` and the improvement ``sum R[p+1..2p, c]^2``: orthogonal throughout, never a
    difference of nearly equal numbers. Where ``R``'s diagonal spans more than ``1 / _SCREEN``
    (a numerically rank-deficient design) singular values decide as least squares does:
    directions at most ``eps max(n, columns) s_max`` are dropped. Windows of one length whose
    nodes vary and take the same orders are stacked: one call factors them all.
"""

from __future__ import annotations

import functools
from collections import defaultdict
from typing import Any

import numpy as np
from scipy import special
from threadpoolctl import ThreadpoolController

_EPS = float(np.finfo(np.float64).eps)
#: Designs whose triangular diagonal spans less than ``1 / _SCREEN`` are read from ``R`` alone.
#: The diagonal only bounds the condition number from below; least squares drops directions
#: below ``eps max(n, columns)`` (1e-14 to 1e-12 here), four orders under the screen.
_SCREEN = 1e-8
#: The precision rule needs the own past to explain all but this share of a signal's variance:
#: rounding the past matters only where the past carries the prediction (a coarse signal that
#: its own past does not predict, a few levels of noise, stays testable).
_EXPLAINED = 0.01
#: Elements of one batch of triangular factors (bounds the memory of a long window).
_CHUNK = 2_000_000
#: Highest difference order: past it the recorded values' rounding, amplified ``2^d`` times,
#: is what the differences hold.
_MAX_ORDER = 8


@functools.cache
def _blas() -> ThreadpoolController:
    """The BLAS thread pools: one thread for the small factorizations of a window (several
    threads spin on matrices of this size, and compete with the rule's compiled kernels: ten
    times slower on two busy cores)."""
    return ThreadpoolController()


def pair_p_values(windows: np.ndarray, lags: int, gap: int,
                  steps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """p-values of every ordered pair of columns of every window.

    Parameters
    ----------
    windows : ndarray, shape (W, N, k)
        ``W`` windows of ``N`` samples of ``k`` signals.
    lags, gap : int
        ``p`` and ``g``.
    steps : ndarray, shape (W, k)
        Each column's logged step in its unit (0: none).

    Returns
    -------
    (ndarray, ndarray), each shape (W, k, k)
        ``P[w, i, j]``: that column j's past improves column i's prediction (NaN: too short,
        constant, or i predicted exactly); ``within[w, i, j]``: i's own past predicts it to
        within its logged step (``RSS_r <= n q^2``, explaining all but :data:`_EXPLAINED` of
        its variance) or to the rounding of the arithmetic.
    """
    values = np.asarray(windows, dtype=np.float64)
    n_windows, n_samples, k = values.shape
    out = np.full((n_windows, k, k), np.nan)
    within = np.zeros((n_windows, k, k), dtype=bool)
    if n_samples - 3 * lags - 1 - gap < 1 or k < 2:  # too short for the full model
        return out, within
    varies = np.ptp(values, axis=1) > 0
    orders = _orders(values, lags)
    groups: dict[tuple[Any, ...], list[int]] = defaultdict(list)
    for w in range(n_windows):
        groups[(tuple(varies[w]), tuple(orders[w][varies[w]]))].append(w)
    steps = np.asarray(steps, dtype=np.float64)
    with _blas().limit(limits=1, user_api="blas"):
        for (mask, order), members in groups.items():
            chosen = np.flatnonzero(mask)
            if chosen.size < 2:
                continue
            # windows per stack: its pairs' factors within _CHUNK elements (bounded memory)
            size = chosen.size * (chosen.size - 1) * (n_samples + 1) * (2 * lags + 2)
            per = max(1, _CHUNK // size)
            for first in range(0, len(members), per):
                some = np.asarray(members[first : first + per])
                found, inside = _group(values[some][:, :, chosen], np.asarray(order), lags,
                                       gap, steps[some][:, chosen])
                rows = some[:, None, None]
                out[rows, chosen[:, None], chosen] = found
                within[rows, chosen[:, None], chosen] = inside
    return out, within


def _orders(values: np.ndarray, lags: int) -> np.ndarray:
    """Each column's difference order (module notes): the one whose differences vary least."""
    centred = values - values.mean(axis=1, keepdims=True)
    best = np.sqrt((centred**2).mean(axis=1))
    order = np.zeros(best.shape, dtype=np.intp)
    difference = values
    for q in range(1, min(lags, _MAX_ORDER) + 1):
        difference = np.diff(difference, axis=1)
        spread = difference.std(axis=1)
        lower = spread < best
        order[lower], best = q, np.where(lower, spread, best)
    return order


def _group(values: np.ndarray, orders: np.ndarray, p: int, gap: int,
           steps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`pair_p_values` of a stack of windows whose columns all vary and share orders."""
    n_windows, n_samples, kk = values.shape
    span = p + gap
    n = n_samples - span
    design, own, source, target = _design(values, orders, p, gap)
    scale = values.std(axis=1)  # (W, kk)
    level = (values - values.mean(axis=1, keepdims=True)) / scale[:, None, :]
    size = (level[:, span:] ** 2).sum(axis=1)  # the targets' own size, for exactness
    spread = ((level[:, span:] - level[:, span:].mean(axis=1, keepdims=True)) ** 2).sum(axis=1)
    step = steps / scale
    columns = design.shape[2]
    r_window = _triangular(design) if n > columns else design
    ahead, behind = np.nonzero(~np.eye(kk, dtype=bool))
    subset = np.column_stack([np.zeros(ahead.size, dtype=np.intp), own[ahead],
                              source[behind], target[ahead]])  # (pairs, 2p + 2)
    c = 2 * p + 1
    pairs = ahead.size
    # (W, pairs, 2p + 2, rows) gathered, read as (W pairs, rows, 2p + 2): each matrix in
    # the column-major order LAPACK takes, and no copy but the gather
    stacked = r_window.transpose(0, 2, 1)[:, subset].transpose(0, 1, 3, 2).reshape(
        n_windows * pairs, r_window.shape[1], c + 1)
    target_of = np.tile(ahead, n_windows)
    window_of = np.repeat(np.arange(n_windows), pairs)
    own_rss, values_out = _read(_householder(stacked), p, n)
    where = (window_of, target_of)
    # predicted by its own past to the rounding of the arithmetic: nothing to explain
    exact = own_rss <= (_EPS * max(n, c)) ** 2 * size[where]
    values_out[exact] = np.nan
    # within a step of its log, and its own past is what predicts it (rounding its past is
    # what a follower could undo): nothing left that the log can show
    inside = exact | ((own_rss <= n * step[where] ** 2) & (own_rss <= _EXPLAINED * spread[where]))
    shape = (n_windows, kk, kk)
    out, within = np.full(shape, np.nan), np.zeros(shape, dtype=bool)
    out[:, ahead, behind] = values_out.reshape(n_windows, pairs)
    within[:, ahead, behind] = inside.reshape(n_windows, pairs)
    return out, within


def _read(h: np.ndarray, p: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The restricted model's residual sum of squares and the F test's p-value of each pair's
    factorization ``h`` (:func:`_householder`: ``R[i, j] = h[j, i]``, ``i <= j``; design
    ``[1, own block, source block]``, then the target)."""
    c = 2 * p + 1
    y = h[:, c, : c + 1]  # R's last column
    full = y[:, c] ** 2
    gain = (y[:, p + 1 : c] ** 2).sum(axis=1)
    own = gain + full
    diagonal = np.abs(np.diagonal(h[:, :c, :c], axis1=1, axis2=2))
    flagged = np.flatnonzero(diagonal.min(axis=1) <= _SCREEN * diagonal.max(axis=1))
    if flagged.size:
        r = np.triu(h[flagged, :c, :c].transpose(0, 2, 1))
        y = y[flagged]
        flagged_full, flagged_own = _dropped(r, y[:, :c], n), _dropped(
            r[:, : p + 1, : p + 1], y[:, : p + 1], n)
        full[flagged] += flagged_full
        own[flagged] += flagged_own
        gain[flagged] = np.maximum(gain[flagged] + flagged_own - flagged_full, 0.0)
    dfd = n - c
    with np.errstate(divide="ignore", invalid="ignore"):
        found = special.fdtrc(p, dfd, gain / p / (full / dfd))  # F's upper tail (f.sf)
    found[~(full > 0.0)] = np.nan
    return own, found


def _design(values: np.ndarray, orders: np.ndarray, p: int,
            gap: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The windows' design (W, n, columns): the intercept, then each node's differenced lags
    (module notes), centred, scaled to unit norm but the targets (in the standardized unit);
    with each node's own block, source block (p columns each) and target column."""
    n_samples = values.shape[1]
    span = p + gap
    n = n_samples - span
    scale = values.std(axis=1, keepdims=True)
    # a difference's rounding: 2^q roundings of the largest value, in the standardized unit
    rounding = _EPS * np.abs(values).max(axis=1, keepdims=True) / scale
    columns: list[np.ndarray] = [np.ones((values.shape[0], n))]
    floors: list[Any] = [0.0]
    own, source, target = [], [], []
    for a, d in enumerate(orders.tolist()):
        differences = [(values[:, :, a] - values[:, :, a].mean(axis=1, keepdims=True))]
        for _ in range(d):
            differences.append(np.diff(differences[-1], axis=1))
        index: dict[tuple[int, int], int] = {}

        def column(q: int, lag: int, a: int = a, differences: list[np.ndarray] = differences,
                   index: dict[tuple[int, int], int] = index) -> int:
            if (q, lag) not in index:  # rows t = span..N-1 of Δ^q v(t - lag)
                index[(q, lag)] = len(columns)
                columns.append(differences[q][:, span - lag - q : n_samples - lag - q]
                               / scale[:, :, a])
                floors.append(2.0**q * rounding[:, 0, a])
            return index[(q, lag)]

        target.append(column(d, 0))
        own.append([column(q, 1) for q in range(d)] + [column(d, 1 + m) for m in range(p - d)])
        source.append([column(q, 1 + gap) for q in range(d)]
                      + [column(d, 1 + gap + m) for m in range(p - d)])
    design = np.stack(columns, axis=2)
    design[:, :, 1:] -= design[:, :, 1:].mean(axis=1, keepdims=True)
    norms = np.sqrt((design**2).sum(axis=1, keepdims=True))
    # A column within max(n, columns) times the rounding its differences carry (a ramp's
    # second difference) is zero, as least squares drops a singular value within
    # eps max(n, columns); scaled to unit norm it would be rounding noise made a regressor.
    floor = np.stack(np.broadcast_arrays(*floors), axis=1)[:, None, :]
    negligible = norms <= max(n, 2 * p + 2) * np.sqrt(n) * floor
    norms[:, :, target] = 1.0
    design /= np.where(norms > 0.0, norms, 1.0)
    design[np.broadcast_to(negligible, design.shape)] = 0.0
    return design, np.array(own, dtype=np.intp), np.array(source, dtype=np.intp), np.array(
        target, dtype=np.intp)


def _triangular(a: np.ndarray) -> np.ndarray:
    """The triangular factor ``R`` of ``a = Q R`` (of each matrix of a stack), without ``Q``."""
    factor: Any = np.linalg.qr  # NumPy's stubs lack mode "r" for stacks
    return np.asarray(factor(a, mode="r"))


def _householder(a: np.ndarray) -> np.ndarray:
    """LAPACK's Householder factorization of each matrix of a stack ``a`` (m, n), as
    ``(n, m)``: its triangular factor is ``R[i, j] = h[j, i]`` for ``i <= j`` (no copy of the
    triangle made)."""
    factor: Any = np.linalg.qr  # NumPy's stubs lack mode "raw" for stacks
    return np.asarray(factor(a, mode="raw")[0])


def _dropped(r: np.ndarray, y: np.ndarray, n: int) -> np.ndarray:
    """Per matrix of the stack ``r`` (and its target ``y``), the target's part that least
    squares leaves unexplained beyond ``r``'s own residual: along the singular directions of
    ``r`` at most ``eps max(n, columns) s_max``, which :func:`numpy.linalg.lstsq` treats as
    zero."""
    u, s, _ = np.linalg.svd(r)
    along = np.einsum("mij,mi->mj", u, y) ** 2
    return np.where(s <= _EPS * max(n, r.shape[-1]) * s[:, :1], along, 0.0).sum(axis=1)
