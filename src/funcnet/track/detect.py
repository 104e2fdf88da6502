"""The change detector: a self-starting CUSUM on each figure of each axis, within a program.

Each run's figure is compared with the healthy history of the same figure (the earlier runs of
the program on that axis, up to the first alarm): with mean ``m`` and standard deviation ``s``
of ``n`` earlier values, ``t = (x - m) / (s * sqrt(1 + 1/n))`` is Student-t with ``n - 1``
degrees of freedom when the figure is steady and normal, so ``u = Phi^-1(F_t(t))`` is exactly
standard normal, one run after the other independent (Hawkins' self-starting CUSUM, 1987): the
detector's false-alarm rate does not depend on how well the first runs estimated the level.
Two one-sided CUSUMs ``S+ = max(0, S+ + u - k)`` and ``S- = max(0, S- - u - k)`` raise an
alarm when one exceeds ``h`` (:data:`DRIFT` ``k = 0.5``, :data:`LEVEL` ``h = 5``): for steady
normal figures the average run length to a false alarm is about 465 runs per figure (0.2 % of
runs), measured in ``benchmarks/validate_track.py``. A shift of 1.5 spreads is found in about
6 runs, of 4 spreads or more at once.

The first :data:`LEARN` runs of a program only learn (no alarm); after an alarm the history stops
growing (a changed machine is no healthy history), the CUSUM restarts, and the runs after it are
judged against the history before it. A spread below :data:`SPREAD_FLOOR` of the mean is taken
as that floor (a figure the program fixes, such as its peak speed, repeats to many digits).

Examples
--------
>>> import numpy as np
>>> x = np.r_[np.random.default_rng(0).normal(1.0, 0.05, 24), [1.07, 2.0, 3.0]]
>>> found = detect_changes(x)
>>> [int(i) for i in np.flatnonzero(found.alarm)]
[25, 26]
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import stats

__all__ = ["LEARN", "DRIFT", "LEVEL", "SPREAD_FLOOR", "Detection", "detect_changes"]

#: Runs of a program that only learn.
LEARN = 5
#: The CUSUM's allowance k, in spreads.
DRIFT = 0.5
#: The CUSUM's decision level h.
LEVEL = 5.0
#: Relative floor of the history's spread.
SPREAD_FLOOR = 1e-3


@dataclass(frozen=True)
class Detection:
    """What :func:`detect_changes` found on one series (NaN values skipped and left NaN).

    Attributes
    ----------
    centre, spread : ndarray
        Per run, the healthy history's mean and spread it was judged against (NaN while
        learning).
    size : ndarray
        Per run, ``(x - centre) / spread``: how far it lies, in spreads.
    cusum : ndarray
        Per run, the larger of the two CUSUMs after it.
    alarm : ndarray of bool
        Per run, an alarm raised on it.
    """

    centre: np.ndarray = field(repr=False)
    spread: np.ndarray = field(repr=False)
    size: np.ndarray = field(repr=False)
    cusum: np.ndarray = field(repr=False)
    alarm: np.ndarray = field(repr=False)


def _standardised(v: np.ndarray, centre: np.ndarray, spread: np.ndarray, n: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """``size`` and the normal score ``u`` of values against histories of ``n`` values."""
    spread = np.maximum(spread, np.maximum(SPREAD_FLOOR * np.abs(centre), np.finfo(float).tiny))
    t = (v - centre) / (spread * np.sqrt(1.0 + 1.0 / n))
    u = stats.norm.ppf(np.clip(stats.t.cdf(t, n - 1), 1e-12, 1 - 1e-12))
    return (v - centre) / spread, u


def _growing(v: np.ndarray, first: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean and spread of ``v[:j]`` for every ``j >= first``, and ``j``."""
    n = np.arange(first, v.size, dtype=np.float64)
    shifted = v - v[0]  # a shift keeps the running sums well conditioned
    total, squares = np.cumsum(shifted)[first - 1:-1], np.cumsum(shifted ** 2)[first - 1:-1]
    mean = total / n
    variance = np.maximum(squares - n * mean ** 2, 0.0) / (n - 1)
    return mean + v[0], np.sqrt(variance), n


def detect_changes(values: np.ndarray, *, learn: int = LEARN, drift: float = DRIFT,
           level: float = LEVEL) -> Detection:
    """Run the detector over a figure's series, in time order (module notes).

    Parameters
    ----------
    values : array_like
        One figure of one axis, the runs of one program in time order; NaN where not read.
    learn : int
        Runs that only learn (at least 3).
    drift, level : float
        The CUSUM's ``k`` and ``h``.

    Returns
    -------
    Detection
    """
    x = np.asarray(values, dtype=np.float64)
    kept = np.flatnonzero(np.isfinite(x))
    v = x[kept]
    first = max(learn, 3)
    centre, spread, size, cusum = (np.full(v.size, np.nan) for _ in range(4))
    alarm = np.zeros(v.size, dtype=bool)
    if v.size > first:
        centre[first:], spread[first:], n = _growing(v, first)
        size[first:], u = _standardised(v[first:], centre[first:], spread[first:], n)
        high = low = 0.0
        for j in range(first, v.size):
            score = u[j - first]
            high, low = max(0.0, high + score - drift), max(0.0, low - score - drift)
            cusum[j] = max(high, low)
            if cusum[j] > level:
                alarm[j] = True
                high = low = 0.0
                if not alarm[:j].any():  # the first alarm: the history stops growing
                    rest = slice(j + 1, v.size)
                    centre[rest], spread[rest] = centre[j], spread[j]
                    size[rest], u[j + 1 - first:] = _standardised(
                        v[rest], centre[rest], spread[rest], np.full(v.size - j - 1, float(j)))
    out = [np.full(x.size, np.nan) for _ in range(4)]
    for full, part in zip(out, (centre, spread, size, cusum), strict=True):
        full[kept] = part
    flags = np.zeros(x.size, dtype=bool)
    flags[kept] = alarm
    return Detection(out[0], out[1], out[2], out[3], flags)
