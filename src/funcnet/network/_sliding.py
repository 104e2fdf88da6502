"""The direction reading of windows that slide one row at a time: factors shared along the run.

:func:`sliding_p_values` returns what :func:`funcnet.network._prediction.pair_p_values` returns
for windows cut from one recording every sample (a sliding timeline), at a fifth of its
cost. Its notes (differenced lags, the negligible-column rule, the rank screen) hold here;
what changes is how each window's least squares is factored.

Why windows can share their factors
    Least squares does not depend on a column's centring (the intercept takes it) nor on its
    scale, so a window's design is, up to those, the rows of one design over the whole run:
    the recording's own differences, centred and scaled once per run. Consecutive windows then
    share all rows but one. Windows whose nodes take the same difference orders (decided on
    each window as before) form a run; a run of :data:`MIN_RUN` windows or more is read here,
    any other window by ``pair_p_values``.

The factorization (orthogonal throughout, no downdating)
    Rows enter a triangular factor by Givens rotations (``3 c^2`` flops a row, ``c = 2 p + 2``
    columns: intercept, own lags, source lags, target). For a block of :data:`BLOCK`
    consecutive windows the rows common to all of them are factored once, as two factors that
    grow from a boundary row, one backwards and one forwards (each row enters each once), then
    merged; each window adds its own few rows. Every ordered pair of the window is a lane of
    the same arithmetic (vectorized across pairs). Compiled, no BLAS: the same bits whatever
    the CPU's kernel.

Reading a window's factor (the rank screen, without the SVD)
    The old design's diagonal is this factor's divided by the window's column norms (a
    negligible column's norm taken as 0: it is dropped, as the old design zeroes it). Where it
    spans less than ``1 / _SCREEN`` the old path asks singular values: directions at most
    ``eps max(n, 2 p + 1) s_max`` are dropped. Here the columns whose diagonal is under the
    screen are dropped as the factor is read, in order (each row rotated into the columns after
    it), and the drop is certified: with ``V`` the dropped columns' combinations that the
    design nearly annihilates (each dropped column minus its least squares on the kept ones
    before it), Courant-Fischer bounds the as many smallest singular values by
    ``|R V L^-T|_F``, ``L L^T = V^T V``; where that is within ``eps max(n, 2 p + 1)`` times a
    lower bound on ``s_max`` (and likewise for the own columns), least squares' SVD drops as
    many directions, and the least squares on the kept columns is its truncated one (to the
    angle between the two spans). A window with any lane not certified goes to
    ``pair_p_values``, SVD and all. On the SINUMERIK timeline the velocity derived from the
    measured position makes 17 of a pair's 43 columns dependent: their diagonals sit near
    1e-13, the kept ones above 1e-3, the bound a quarter of the threshold.

Where the inputs' rounding sets the reading
    The rows here are the recording's as recorded; the old path reads each window normalized.
    Where a column is a little above rounding (a set-point's third differences on a ramp) or
    the normalization's rounding hides a dependence from the SVD's threshold, the old path's
    own p-values move when the same window is rounded otherwise (z-scored instead of min-max),
    and these differ as much (tests/test_direction_sliding.py).
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
from numba import njit
from scipy import special

from funcnet.network._prediction import _EPS, _EXPLAINED, _SCREEN, _orders, pair_p_values

#: Windows in a block that share the factor of their common rows (the arithmetic per window is
#: least near 5: a merge of two triangles per block against a few added rows per window).
BLOCK = 5
#: Shortest run read by sliding factors: a run first pays for the rows of one whole window, so
#: a single window costs about what LAPACK's factorization of each pair does.
MIN_RUN = 2


def sliding_p_values(windows: np.ndarray, values: np.ndarray, firsts: np.ndarray, lags: int,
                     gap: int, steps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~funcnet.network._prediction.pair_p_values` of windows cut from one recording.

    Parameters
    ----------
    windows : ndarray, shape (W, N, k)
        The windows as the reading sees them (normalized).
    values : ndarray, shape (T, k)
        The recording's rows: window ``w`` is an affine map of each column of
        ``values[firsts[w] : firsts[w] + N]``.
    firsts : ndarray of int, shape (W,)
    lags, gap, steps
        As ``pair_p_values``.

    Returns
    -------
    (ndarray, ndarray), each shape (W, k, k)
        As ``pair_p_values``: the p-values to a relative 1e-6 (measured: 3e-8) wherever those
        do not hinge on how the window was rounded (module notes), the flags equal.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(400).cumsum()
    >>> y = np.roll(x, 3) + rng.standard_normal(400)
    >>> values = np.column_stack([x, y])
    >>> windows = np.stack([values[s : s + 150] for s in range(20)])
    >>> found, _ = sliding_p_values(windows, values, np.arange(20), 5, 1, np.zeros((20, 2)))
    >>> reference, _ = pair_p_values(windows, 5, 1, np.zeros((20, 2)))
    >>> bool(np.allclose(found, reference, rtol=1e-8, equal_nan=True))
    True
    """
    windows = np.asarray(windows, dtype=np.float64)
    n_windows, n_samples, k = windows.shape
    p, span = lags, lags + gap
    if n_samples - 3 * lags - 1 - gap < 1 or k < 2 or n_windows == 0:
        return pair_p_values(windows, lags, gap, steps)
    orders = _orders(windows, lags)
    norms, negligible = _column_norms(windows, orders, p, gap)
    runs = _runs(windows, np.asarray(firsts), orders)
    out = np.full((n_windows, k, k), np.nan)
    within = np.zeros((n_windows, k, k), dtype=bool)
    left = np.ones(n_windows, dtype=bool)
    raw = np.lib.stride_tricks.sliding_window_view(np.asarray(values, dtype=np.float64),
                                                   n_samples, axis=0)
    spread_raw = raw[np.asarray(firsts)].std(axis=2)  # (W, k)
    all_steps = np.asarray(steps, dtype=np.float64)

    def read(run: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        start, stop = run
        return _run(windows[start:stop], values, int(firsts[start]), orders[start],
                    negligible[start:stop], norms[start:stop], spread_raw[start:stop], p, span,
                    all_steps[start:stop])

    # Runs are independent: read over the cores (the factors release the interpreter), each
    # with the same arithmetic as alone; the longest first, so that the cores end together.
    workers = min(len(runs), os.cpu_count() or 1)
    runs = sorted(runs, key=lambda run: run[0] - run[1])
    if workers > 1:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            readings = list(pool.map(read, runs))
    else:
        readings = [read(run) for run in runs]
    for (start, stop), (found, inside, ok) in zip(runs, readings, strict=True):
        rows = np.arange(start, stop)[ok]
        out[rows], within[rows] = found[ok], inside[ok]
        left[rows] = False
    if left.any():
        rest = np.flatnonzero(left)
        out[rest], within[rest] = pair_p_values(windows[rest], lags, gap,
                                                np.asarray(steps)[rest])
    return out, within


def _runs(windows: np.ndarray, firsts: np.ndarray, orders: np.ndarray) -> list[tuple[int, int]]:
    """``(start, stop)`` of each run of at least :data:`MIN_RUN` windows: one row apart, every
    node varying, the same orders."""
    varies = (np.ptp(windows, axis=1) > 0).all(axis=1)
    same = ((np.diff(firsts) == 1) & (orders[1:] == orders[:-1]).all(axis=1) & varies[1:]
            & varies[:-1])
    breaks = np.flatnonzero(~same) + 1
    edges = np.concatenate([[0], breaks, [len(windows)]])
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=True)
            if b - a >= MIN_RUN and varies[a]]


def _run(windows: np.ndarray, values: np.ndarray, first: int, orders: np.ndarray,
         negligible: np.ndarray, norms: np.ndarray, spread_raw: np.ndarray, p: int, span: int,
         steps: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """p-values, within flags and whether each window's factors read (the screen) of one run."""
    n_windows, n_samples, k = windows.shape
    n = n_samples - span
    rows = n_windows - 1 + n
    bank, sigma = _bank(values[first : first + n_windows - 1 + n_samples], orders, p, span, rows)
    ahead, behind = np.nonzero(~np.eye(k, dtype=bool))
    c = 2 * p + 2
    design = np.empty((rows, c, ahead.size))
    design[:, 0] = 1.0
    design[:, 1 : p + 1] = bank[:, ahead, 1 : p + 1].transpose(0, 2, 1)
    design[:, p + 1 : 2 * p + 1] = bank[:, behind, p + 1 :].transpose(0, 2, 1)
    design[:, c - 1] = bank[:, ahead, 0]
    # the windows' column norms in the run's unit (the screen reads the old design's diagonal)
    unit = norms * (spread_raw / windows.std(axis=1))[:, :, None] / np.where(sigma > 0, sigma,
                                                                              np.inf)
    unit[negligible] = 0.0  # a zero norm: the column is dropped as the old design zeroes it
    window_norms = np.empty((n_windows, c, ahead.size))
    window_norms[:, 0] = math.sqrt(n)
    window_norms[:, 1 : p + 1] = unit[:, ahead, 1 : p + 1].transpose(0, 2, 1)
    window_norms[:, p + 1 : 2 * p + 1] = unit[:, behind, p + 1 :].transpose(0, 2, 1)
    window_norms[:, c - 1] = 1.0
    read = np.zeros((n_windows, 3, ahead.size))
    limits = np.array([_EPS * max(n, c - 1), _EPS * max(n, p + 1)])  # s_max >= 1: unit columns
    _slide(design, n, BLOCK, window_norms, p, limits, _SCREEN, read)
    full, gain, status = read[:, 0], read[:, 1], read[:, 2]
    zero = negligible[:, ahead, 0]  # a negligible target: predicted exactly
    full[zero], gain[zero] = 0.0, 0.0
    # in the old unit: the target standardized over its window
    own = (gain + full) * (sigma[:, 0] / spread_raw)[:, ahead] ** 2
    found, inside = _decide(windows, own, gain, full, p, span, steps, ahead, behind)
    return found, inside, np.asarray((status > 0).all(axis=1))


def _decide(windows: np.ndarray, own: np.ndarray, gain: np.ndarray, full: np.ndarray, p: int,
            span: int, steps: np.ndarray, ahead: np.ndarray,
            behind: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The F test's p-values and the within flags (``pair_p_values``' rules)."""
    n_windows, n_samples, k = windows.shape
    n, c = n_samples - span, 2 * p + 1
    scale = windows.std(axis=1)
    level = (windows - windows.mean(axis=1, keepdims=True)) / scale[:, None, :]
    size = (level[:, span:] ** 2).sum(axis=1)
    spread = ((level[:, span:] - level[:, span:].mean(axis=1, keepdims=True)) ** 2).sum(axis=1)
    step = steps / scale
    with np.errstate(divide="ignore", invalid="ignore"):
        found = special.fdtrc(p, n - c, gain / p / (full / (n - c)))
    found[~(full > 0.0)] = np.nan
    exact = own <= (_EPS * max(n, c)) ** 2 * size[:, ahead]
    found[exact] = np.nan
    inside = exact | ((own <= n * step[:, ahead] ** 2) & (own <= _EXPLAINED * spread[:, ahead]))
    out = np.full((n_windows, k, k), np.nan)
    within = np.zeros((n_windows, k, k), dtype=bool)
    out[:, ahead, behind], within[:, ahead, behind] = found, inside
    return out, within


def _bank(values: np.ndarray, orders: np.ndarray, p: int, span: int,
          rows: int) -> tuple[np.ndarray, np.ndarray]:
    """Each node's columns over a run, ``(rows, k, 2 p + 1)``: target, own lags, source lags
    (``_prediction``'s differenced lags), each centred and scaled to unit root mean square over
    the run; with those scales ``(k, 2 p + 1)``."""
    k = values.shape[1]
    gap = span - p
    bank = np.empty((rows, k, 2 * p + 1))
    for a, d in enumerate(orders.tolist()):
        column = values[:, a] - values[:, a].mean()
        differences = [column]
        for _ in range(d):
            differences.append(np.diff(differences[-1]))
        for index, (q, lag) in enumerate(_columns(d, p, gap)):
            begin = span - lag - q
            bank[:, a, index] = differences[q][begin : begin + rows]
    bank -= bank.mean(axis=0)
    sigma = np.sqrt((bank**2).mean(axis=0))
    bank /= np.where(sigma > 0, sigma, 1.0)
    return bank, sigma


def _columns(d: int, p: int, gap: int) -> list[tuple[int, int]]:
    """A node's ``(difference order, lag)`` columns: target, own lags, source lags."""
    own = [(q, 1) for q in range(d)] + [(d, 1 + m) for m in range(p - d)]
    source = [(q, 1 + gap) for q in range(d)] + [(d, 1 + gap + m) for m in range(p - d)]
    return [(d, 0), *own, *source]


def _column_norms(windows: np.ndarray, orders: np.ndarray, p: int,
                  gap: int) -> tuple[np.ndarray, np.ndarray]:
    """Every window's centred column norms ``(W, k, 2 p + 1)`` (in the window's unit) and which
    columns are negligible (``_prediction``'s rule)."""
    table = np.array([_columns(d, p, gap) for d in range(min(p, 8) + 1)], dtype=np.int64)
    norms, floors = _norms_kernel(windows, orders.astype(np.int64), table, p + gap)
    n = windows.shape[1] - p - gap
    return norms, norms <= max(n, 2 * p + 2) * math.sqrt(n) * floors


@njit(cache=True)
def _norms_kernel(windows: Any, orders: Any, table: Any, span: int) -> Any:  # pragma: no cover
    n_windows, n_samples, k = windows.shape
    n = n_samples - span
    columns = table.shape[1]
    norms = np.empty((n_windows, k, columns))
    floors = np.empty((n_windows, k, columns))
    differences = np.empty((table.shape[0], n_samples))
    for w in range(n_windows):
        for a in range(k):
            d = orders[w, a]
            v = windows[w, :, a]
            mean = v.mean()
            top = 0.0
            for t in range(n_samples):
                differences[0, t] = v[t] - mean
                top = max(top, abs(v[t]))
            for q in range(1, d + 1):
                for t in range(n_samples - q):
                    differences[q, t] = differences[q - 1, t + 1] - differences[q - 1, t]
            for index in range(columns):
                q, lag = table[d, index, 0], table[d, index, 1]
                begin = span - lag - q
                total = 0.0
                for t in range(n):
                    total += differences[q, begin + t]
                centre = total / n
                square = 0.0
                for t in range(n):
                    deviation = differences[q, begin + t] - centre
                    square += deviation * deviation
                norms[w, a, index] = math.sqrt(square)
                floors[w, a, index] = 2.0**q * _EPS * top
    return norms, floors


@njit(cache=True)
def _add(r: Any, x: Any, start: int, cs: Any, sn: Any) -> None:  # pragma: no cover
    """Givens rotations adding the row ``x`` (c, lanes) to each lane's triangle ``r``
    (c, c, lanes) from column ``start`` on; ``x`` is overwritten."""
    c, _, lanes = r.shape
    for s in range(start, c):
        for lane in range(lanes):
            a, b = r[s, s, lane], x[s, lane]
            h = math.sqrt(a * a + b * b)
            if h > 0.0:
                cs[lane], sn[lane] = a / h, b / h
                r[s, s, lane] = h
            else:
                cs[lane], sn[lane] = 1.0, 0.0
        for j in range(s + 1, c):
            for lane in range(lanes):
                a, b = r[s, j, lane], x[j, lane]
                r[s, j, lane] = cs[lane] * a + sn[lane] * b
                x[j, lane] = cs[lane] * b - sn[lane] * a


@njit(cache=True)
def _merge(r: Any, other: Any, cs: Any, sn: Any, row: Any) -> None:  # pragma: no cover
    """Add the rows of the triangles ``other`` to ``r``."""
    c, _, lanes = r.shape
    for s in range(c):
        nonzero = False
        for lane in range(lanes):
            nonzero |= other[s, s, lane] != 0.0
        if nonzero:
            row[:] = other[s]
            _add(r, row, s, cs, sn)


def _boundary(lo: int, block: int, common: int) -> int:  # pragma: no cover
    """The boundary row of the block whose common rows begin at ``lo``: the first of
    ``block - 1 + m common`` at or after ``lo`` (one lies in any ``common`` rows)."""
    return block - 1 + -(-max(lo - block + 1, 0) // common) * common


_boundary_kernel = njit(cache=True)(_boundary)


@njit(cache=True, nogil=True)
def _slide(design: Any, n: int, block: int, norms: Any, p: int, limits: Any,
           screen: float, out: Any) -> None:  # pragma: no cover
    """Every window's factor of a run (module notes) read into ``out`` (W, 3, lanes): the full
    model's residual sum of squares, the improvement, and 1 where the screen passed."""
    rows, c, lanes = design.shape
    n_windows = rows - n + 1
    common = n - block + 1
    cs, sn = np.empty(lanes), np.empty(lanes)
    row = np.empty((c, lanes))
    factor, merged, work = np.zeros((c, c, lanes)), np.zeros((c, c, lanes)), np.zeros((c, c, lanes))
    first = 0
    while first < n_windows:
        # consecutive blocks whose common rows hold one boundary row
        boundary = _boundary_kernel(min(first + block, n_windows) - 1, block, common)
        count = 1
        while first + count * block < n_windows and _boundary_kernel(
                min(first + (count + 1) * block, n_windows) - 1, block, common) == boundary:
            count += 1
        lows = np.empty(count, dtype=np.int64)
        for m in range(count):
            lows[m] = min(first + (m + 1) * block, n_windows) - 1
        suffixes = np.empty((count, c, c, lanes))
        for m in range(count):
            if lows[m] == boundary:  # no rows before the boundary
                suffixes[m] = 0.0
        factor[:] = 0.0
        for x in range(boundary - 1, lows[0] - 1, -1):  # the suffix factors, backwards
            row[:] = design[x]
            _add(factor, row, 0, cs, sn)
            for m in range(count):
                if lows[m] == x:
                    suffixes[m] = factor
        factor[:] = 0.0
        top = boundary
        for m in range(count):  # the prefix factor, forwards; each block's common rows
            begin = first + m * block
            while top < begin + n:
                row[:] = design[top]
                _add(factor, row, 0, cs, sn)
                top += 1
            if boundary - lows[m] >= top - boundary:
                merged[:] = suffixes[m]
                _merge(merged, factor, cs, sn, row)
            else:
                merged[:] = factor
                _merge(merged, suffixes[m], cs, sn, row)
            _block(merged, work, design, begin, lows[m], n, norms, p, limits, screen, out,
                   cs, sn, row)
        first += count * block


@njit(cache=True)
def _block(common: Any, work: Any, design: Any, begin: int, lo: int, n: int, norms: Any,
           p: int, limits: Any, screen: float, out: Any, cs: Any, sn: Any,
           row: Any) -> None:  # pragma: no cover
    """The windows ``begin .. lo`` of one block from the factor of their common rows
    ``lo .. begin + n - 1`` (overwritten): each adds the rows before ``lo`` and after it."""
    for a in range(lo, begin - 1, -1):
        if a < lo:
            row[:] = design[a]
            _add(common, row, 0, cs, sn)
        work[:] = common
        for x in range(begin + n, a + n):
            row[:] = design[x]
            _add(work, row, 0, cs, sn)
        _read(work, norms[a], p, limits, screen, out[a])


@njit(cache=True)
def _read(r: Any, norms: Any, p: int, limits: Any, screen: float,
          out: Any) -> None:  # pragma: no cover
    """Each lane's residual sum of squares, improvement and screen (module notes) from its
    factor ``r`` (c, c, lanes) and the window's column norms ``norms`` (c, lanes)."""
    c, _, lanes = r.shape
    y = c - 1
    single = np.empty((c, c))
    for lane in range(lanes):
        low, high = np.inf, 0.0
        for s in range(y):
            d = abs(r[s, s, lane]) / norms[s, lane] if norms[s, lane] > 0.0 else 0.0
            low, high = min(low, d), max(high, d)
        if low > screen * high:
            out[2, lane] = 1.0
            column = r[:, y, lane]
        else:  # drop the dependent columns, then screen the kept ones (module notes)
            for s in range(y):
                scale = 1.0 / norms[s, lane] if norms[s, lane] > 0.0 else 0.0
                for i in range(c):
                    single[i, s] = r[i, s, lane] * scale
                single[s + 1 :, s] = 0.0
            single[:, y] = r[:, y, lane]
            # the SVD's threshold, eps max(n, columns) s_max, from below: s_max >= |R v| / |v|
            full = limits[0] * _largest(single, y)
            own = limits[1] * _largest(single, p + 1)
            out[2, lane] = 1.0 if _drop(single, p, screen * high, full, own) else 0.0
            column = single[:, y]
        out[0, lane] = column[y] ** 2
        gain = 0.0
        for s in range(p + 1, y):
            gain += column[s] ** 2
        out[1, lane] = gain


@njit(cache=True)
def _drop(r: Any, p: int, below: float, limit_full: float,
          limit_own: float) -> bool:  # pragma: no cover
    """Drop the columns of the unit-column factor ``r`` (c, c; the target last) whose diagonal
    is at most ``below``, in order, each row rotated into the columns after it. True where
    least squares' SVD drops as many directions: :func:`_bounds` of the dropped singular values
    within ``limit_full`` (and, of the own columns, ``limit_own``)."""
    c = r.shape[0]
    y = c - 1
    before = r[:y, :y].copy()
    kept = np.zeros(y, dtype=np.bool_)
    null = np.zeros((y, y))  # row m: a combination of the columns that r maps to ~0
    count, own_count = 0, 0
    tail = np.empty(c)
    for s in range(y):
        if abs(r[s, s]) > below:
            kept[s] = True
            continue
        vector = null[count]
        vector[s] = 1.0
        for i in range(s - 1, -1, -1):  # minus its coefficients on the kept columns before it
            if kept[i]:
                total = r[i, s]
                for j in range(i + 1, s):
                    total += r[i, j] * vector[j]  # zero where not kept
                vector[i] = -total / r[i, i]
        count += 1
        own_count += s <= p
        tail[:] = r[s]
        r[s] = 0.0
        _add_single(r, tail, s + 1)
    if count == 0:
        return True
    full, own = _bounds(before, null, count, own_count)
    return full <= limit_full and own <= limit_own


@njit(cache=True)
def _bounds(r: Any, null: Any, count: int,
            own_count: int) -> tuple[float, float]:  # pragma: no cover
    """Upper bounds on the ``count`` smallest singular values of the triangle ``r`` and on the
    ``own_count`` smallest of its own columns, from the combinations ``V`` (``null``, its first
    ``count`` columns) that ``r`` nearly annihilates: by Courant-Fischer over the span of ``V``,
    ``s <= |R V (V^T V)^-1/2|_2 <= |R V L^-T|_F`` with ``L L^T = V^T V`` (the own columns' ``V``
    being the first ``own_count``)."""
    y = r.shape[0]
    lower = np.zeros((count, count))  # Cholesky of V^T V, in loops (no BLAS)
    for i in range(count):
        for j in range(i + 1):
            total = 0.0
            for m in range(y):
                total += null[i, m] * null[j, m]
            for m in range(j):
                total -= lower[i, m] * lower[j, m]
            lower[i, j] = math.sqrt(total) if i == j else total / lower[j, j]
    image = np.zeros((count, y))  # (R V)^T
    for m in range(count):
        for i in range(y):
            total = 0.0
            for j in range(i, y):
                total += r[i, j] * null[m, j]
            image[m, i] = total
    full, own = 0.0, 0.0
    for m in range(count):  # rows of L^-1 (R V)^T, by forward substitution
        square = 0.0
        for i in range(y):
            total = image[m, i]
            for j in range(m):
                total -= lower[m, j] * image[j, i]
            image[m, i] = total / lower[m, m]
            square += image[m, i] ** 2
        full += square
        own += square if m < own_count else 0.0
    return math.sqrt(full), math.sqrt(own)


@njit(cache=True)
def _largest(r: Any, size: int) -> float:  # pragma: no cover
    """A lower bound on the largest singular value of the leading ``size`` columns of the
    triangle ``r``: its largest row norm (``|R^T e_i| <= s_max``), at least 1 (unit columns)."""
    found = 1.0
    for i in range(size):
        total = 0.0
        for j in range(i, size):
            total += r[i, j] * r[i, j]
        found = max(found, math.sqrt(total))
    return found


@njit(cache=True)
def _add_single(r: Any, x: Any, start: int) -> None:  # pragma: no cover
    """:func:`_add` of one triangle ``r`` (c, c) and row ``x`` (c,)."""
    c = r.shape[0]
    for s in range(start, c):
        a, b = r[s, s], x[s]
        h = math.sqrt(a * a + b * b)
        if h == 0.0:
            continue
        cs, sn = a / h, b / h
        r[s, s] = h
        for j in range(s + 1, c):
            a, b = r[s, j], x[j]
            r[s, j] = cs * a + sn * b
            x[j] = cs * b - sn * a
