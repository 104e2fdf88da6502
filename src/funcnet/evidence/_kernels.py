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
def _window_counts(a_y: Array, pairs_x: Array, pairs_y: Array, start_x: Int, start_y: Int,
                   length: Int, theiler: Int) -> tuple[float, float, float]:
    """``(phi, mcr(x|y), mcr(y|x))`` of the window pairing ``x[start_x + i]``, ``y[start_y + i]``.

    ``phi`` is the correlation of the indicators ``A_X[i, j]`` and ``A_Y[i, j]`` over the
    window's pairs ``i < j``, ``j - i > theiler``; ``mcr(x|y)`` the mean over the window's states
    of ``sum_j JR_ij / sum_j A_Y[i, j]`` (states without a Y-neighbour left out). ``pairs_x``
    and ``pairs_y`` list the recurrent pairs ``(i, j)``, ``i < j``, of each whole matrix: a
    window visits them, not its ``L^2`` cells.
    """
    row_x = np.zeros(length, dtype=np.int64)
    row_y = np.zeros(length, dtype=np.int64)
    row_xy = np.zeros(length, dtype=np.int64)
    n_x = 0
    n_y = 0
    n_xy = 0
    stop_x = start_x + length
    for k in range(pairs_x.shape[0]):
        i = pairs_x[k, 0]
        j = pairs_x[k, 1]
        if i < start_x or j >= stop_x or j - i <= theiler:
            continue
        u = i - start_x
        v = j - start_x
        n_x += 1
        row_x[u] += 1
        row_x[v] += 1
        if a_y[start_y + u, start_y + v]:
            n_xy += 1
            row_xy[u] += 1
            row_xy[v] += 1
    stop_y = start_y + length
    for k in range(pairs_y.shape[0]):
        i = pairs_y[k, 0]
        j = pairs_y[k, 1]
        if i < start_y or j >= stop_y or j - i <= theiler:
            continue
        n_y += 1
        row_y[i - start_y] += 1
        row_y[j - start_y] += 1
    sum_x_given_y = 0.0
    sum_y_given_x = 0.0
    rows_x = 0
    rows_y = 0
    for u in range(length):
        if row_y[u] > 0:
            sum_x_given_y += row_xy[u] / row_y[u]
            rows_y += 1
        if row_x[u] > 0:
            sum_y_given_x += row_xy[u] / row_x[u]
            rows_x += 1
    gap = min(theiler + 1, length)
    n_pairs = (length - gap) * (length - gap + 1) // 2
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
def _windows(a_y: Array, pairs_x: Array, pairs_y: Array, starts_x: Array, starts_y: Array,
             length: Int, theiler: Int) -> Array:
    """:func:`_window_counts` of every window ``(starts_x[k], starts_y[k])``: shape (K, 3)."""
    n = starts_x.size
    out = np.empty((n, 3), dtype=np.float64)
    for k in prange(n):
        phi, xy, yx = _window_counts(
            a_y, pairs_x, pairs_y, starts_x[k], starts_y[k], length, theiler
        )
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
        for first in range(k):
            p = buffer[first]
            for second in range(first + 1, k):
                pairs += auto[p, buffer[second]]
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
