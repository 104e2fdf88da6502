"""Keys of distances, compiled (private): a threshold's largest key, a key's distance.

Distances are compared through a monotone *key*: the sum of squares for "euclidean" (no square
root in the hot loops), the distance itself otherwise (``metric`` codes of
:data:`funcnet.core._isrn_kernels._METRIC_CODE`). A threshold eps becomes the largest key whose
distance is <= eps (< eps if strict), found with the same correctly rounded square root the
distance takes, so ``key <= bound`` decides exactly as the distance would.

One copy serves both paths: the per-window thresholds (:mod:`funcnet.core.thresholds`) call
these from Python, the batched kernels (:mod:`funcnet.core._batch_kernels`) from compiled code.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def next_up(x: float) -> float:
    """``np.nextafter(x, inf)`` for x < inf, by stepping the bit pattern."""
    if x == 0.0:
        return 5e-324
    bits = np.empty(1, dtype=np.float64)
    bits[0] = x
    as_int = bits.view(np.int64)
    as_int[0] += 1 if x > 0 else -1
    return bits[0]


@njit(cache=True)
def next_down(x: float) -> float:
    """``np.nextafter(x, -inf)`` for x > -inf."""
    return -next_up(-x)


@njit(cache=True)
def _within(key: float, eps: float, strict: bool) -> bool:
    distance = math.sqrt(key)
    return distance < eps if strict else distance <= eps


@njit(cache=True)
def key_bound(eps: float, strict: bool, metric: int) -> float:
    """The largest key whose distance is <= eps (< eps if strict); -inf when there is none.

    Examples
    --------
    >>> key_bound(0.5, False, 0), key_bound(0.5, False, 1)
    (0.25, 0.5)
    >>> key_bound(0.5, True, 1) < 0.5
    True
    """
    if metric != 0:
        bound = next_down(eps) if strict else eps
        return bound if bound >= 0 else -np.inf  # a distance is never negative
    if math.isinf(eps):
        return eps
    key = eps * eps if eps > 0 else 0.0
    while key > 0 and not _within(key, eps, strict):
        key = next_down(key)
    if not _within(key, eps, strict):
        return -np.inf
    while _within(next_up(key), eps, strict):
        key = next_up(key)
    return key


@njit(cache=True)
def key_distance(key: float, metric: int) -> float:
    """The distance of a key: its square root for "euclidean" (``metric`` 0), else itself.

    Examples
    --------
    >>> key_distance(0.25, 0), key_distance(0.25, 2)
    (0.5, 0.25)
    """
    return math.sqrt(key) if metric == 0 else key
