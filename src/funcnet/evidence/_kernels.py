"""Compiled kernels of the evidence: windowed joint recurrences and sub-ISRN measures (private).

Recurrence matrices arrive dense, as ``uint8`` arrays (a window holds at most a few thousand
states, and every surrogate or resample reads them at arbitrary offsets, which dense rows make
a plain index). Surrogates never copy or recompute a matrix: a time offset of Y against X is a
shift of the indices at which ``A_Y`` is read.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit, prange

Array = np.ndarray
Int = int | np.integer[Any]


@njit(cache=True)
def _window_counts(a_x: Array, a_y: Array, start_x: Int, start_y: Int, length: Int,
                   theiler: Int) -> tuple[float, float, float]:
    """``(phi, mcr(x|y), mcr(y|x))`` of the window pairing ``x[start_x + i]`` with ``y[start_y + i]``.

    ``phi`` is the correlation of the indicators ``A_X[i, j]`` and ``A_Y[i, j]`` over the window's
    pairs ``i < j``, ``j - i > theiler``; ``mcr(x|y)`` the mean over the window's states of
    ``sum_j JR_ij / sum_j A_Y_ij`` (states without a Y-neighbour left out).
    """
    n_x = 0
    n_y = 0
    n_xy = 0
    sum_x_given_y = 0.0
    sum_y_given_x = 0.0
    rows_x = 0
    rows_y = 0
    for i in range(length):
        row_x = 0
        row_y = 0
        row_xy = 0
        ix = start_x + i
        iy = start_y + i
        for j in range(length):
            d = j - i
            if d <= theiler and d >= -theiler:
                continue
            bx = a_x[ix, start_x + j]
            by = a_y[iy, start_y + j]
            row_x += bx
            row_y += by
            row_xy += bx & by
        if row_y > 0:
            sum_x_given_y += row_xy / row_y
            rows_y += 1
        if row_x > 0:
            sum_y_given_x += row_xy / row_x
            rows_x += 1
        n_x += row_x
        n_y += row_y
        n_xy += row_xy
    # Every unordered pair was seen twice; the correlation is the same on ordered pairs.
    n_pairs = 0
    for i in range(length):
        low = i - theiler
        high = i + theiler
        excluded = min(high, length - 1) - max(low, 0) + 1
        n_pairs += length - excluded
    phi = 0.0
    if n_pairs > 0:
        px = n_x / n_pairs
        py = n_y / n_pairs
        var = px * (1.0 - px) * py * (1.0 - py)
        if var > 0.0:
            phi = (n_xy / n_pairs - px * py) / np.sqrt(var)
    x_given_y = sum_x_given_y / rows_y if rows_y else 0.0
    y_given_x = sum_y_given_x / rows_x if rows_x else 0.0
    return phi, x_given_y, y_given_x


@njit(cache=True, parallel=True)
def _windows(a_x: Array, a_y: Array, starts_x: Array, starts_y: Array, length: Int,
             theiler: Int) -> Array:
    """:func:`_window_counts` of every window ``(starts_x[k], starts_y[k])``: shape (K, 3)."""
    n = starts_x.size
    out = np.empty((n, 3), dtype=np.float64)
    for k in prange(n):
        phi, xy, yx = _window_counts(a_x, a_y, starts_x[k], starts_y[k], length, theiler)
        out[k, 0] = phi
        out[k, 1] = xy
        out[k, 2] = yx
    return out


@njit(cache=True)
def _direction(cross: Array, auto: Array, chosen: Array, buffer: Array) -> tuple[float, float]:
    """``(C, T)`` of one direction of the sub-ISRN on the states ``chosen`` (Eq. 6-9).

    ``cross`` rows are the nodes v (their states restricted to ``chosen``), columns the other
    system's states; ``auto`` is the other system's recurrence matrix.
    """
    n = chosen.size
    local_sum = 0.0
    triangles = 0
    triples = 0
    for a in range(n):
        v = chosen[a]
        k = 0
        for b in range(n):
            q = chosen[b]
            if cross[v, q]:
                buffer[k] = q
                k += 1
        pairs = 0
        for s in range(k):
            p = buffer[s]
            for t in range(s + 1, k):
                pairs += auto[p, buffer[t]]
        if k >= 2:
            local_sum += 2.0 * pairs / (k * (k - 1))
            triangles += 2 * pairs
            triples += k * (k - 1)
    c = local_sum / n if n else 0.0
    t = triangles / triples if triples else 0.0
    return c, t


@njit(cache=True, parallel=True)
def _sub_measures(a_x: Array, a_y: Array, cr_xy: Array, cr_yx: Array, chosen: Array) -> Array:
    """``(C^XY, C^YX, T^XY, T^YX)`` of the sub-ISRN of every row of ``chosen``: (R, 4)."""
    n_resamples = chosen.shape[0]
    out = np.empty((n_resamples, 4), dtype=np.float64)
    for r in prange(n_resamples):
        buffer = np.empty(chosen.shape[1], dtype=np.int64)
        c_xy, t_xy = _direction(cr_xy, a_y, chosen[r], buffer)
        c_yx, t_yx = _direction(cr_yx, a_x, chosen[r], buffer)
        out[r, 0] = c_xy
        out[r, 1] = c_yx
        out[r, 2] = t_xy
        out[r, 3] = t_yx
    return out
