"""Alignment of one run of a program on another, cycle by cycle, on the position set-points.

A robot program runs the same set-point path every time, but a recording may start at another
moment, hold more cycles than another, or slow down locally (a controller pausing under a push).
:func:`align_on_setpoints` therefore aligns piece by piece: RUN is cut into short pieces
(``step`` seconds), each matched with its context (``window`` seconds around it, the set-points
of every axis) against every offset of the reference. Every offset whose root-mean-square
set-point difference is within ``tolerance`` and smallest in its stretch of such offsets is a
match: one per cycle of the reference that runs through the piece. A piece no offset matches is
not covered by that reference: nothing is compared there.

Examples
--------
>>> import numpy as np
>>> t = np.arange(0, 12, 0.01)
>>> ref = np.c_[np.sin(2 * np.pi * t / 3), np.cos(2 * np.pi * t / 3)]  # four cycles of 3 s
>>> run = ref[50:650]                                                   # starts 0.5 s later
>>> a = align_on_setpoints(run, ref, period=0.01)
>>> float(a.covered.mean()), sorted(set(a.matches[0][a.matches[0] >= 0].tolist()))
(1.0, [50, 350, 650, 950])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy.signal import fftconvolve

from funcnet.errors import ParameterError

__all__ = ["Alignment", "align_on_setpoints", "SETPOINT_TOLERANCE"]

#: Default largest root-mean-square set-point difference (per axis, in the set-point's unit) of
#: a match: two runs of one program agree to ~1e-4 rad; another program differs by ~0.1-1 rad.
SETPOINT_TOLERANCE = 0.02


@dataclass(frozen=True)
class Alignment:
    """Where each tick of RUN lies in a reference.

    Attributes
    ----------
    matches : ndarray of int, shape (n_run, k)
        Per tick of RUN, the reference ticks that match it (one per cycle of the reference
        through it), -1 where fewer than ``k`` do.
    distance : ndarray of float, shape (n_run,)
        The RMS set-point difference of the best match of each tick's piece (NaN: none).
    tolerance : float
        The tolerance used.
    """

    matches: np.ndarray = field(repr=False)
    distance: np.ndarray = field(repr=False)
    tolerance: float

    @property
    def covered(self) -> np.ndarray:
        """Boolean per tick of RUN: some tick of the reference matches it."""
        return self.matches[:, 0] >= 0

    @property
    def cycles(self) -> np.ndarray:
        """Number of matches (cycles of the reference) per tick of RUN."""
        return (self.matches >= 0).sum(axis=1)


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    edges = np.flatnonzero(np.diff(np.r_[0, mask.astype(np.int8), 0]))
    return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2], strict=True)]


def align_on_setpoints(
    run: np.ndarray,
    reference: np.ndarray,
    *,
    period: float,
    window: float = 1.0,
    step: float = 0.2,
    tolerance: float = SETPOINT_TOLERANCE,
) -> Alignment:
    """Align RUN on a reference by its position set-points, piece by piece (module notes).

    Parameters
    ----------
    run, reference : ndarray, shape (n, axes) and (m, axes)
        The position set-points of every axis, one row per tick, on one sample period.
    period : float
        The sample period in seconds.
    window : float
        Seconds of set-point matched around each piece (its context: long enough to tell a
        stop before a move from the stop after it).
    step : float
        Seconds of each piece: the alignment's resolution in time (a local slow-down is
        followed piece by piece).
    tolerance : float
        Largest RMS set-point difference per axis of a match.

    Returns
    -------
    Alignment

    Raises
    ------
    ParameterError
        Arrays of another shape, too short for ``window``, or a bad ``window``/``step``/
        ``tolerance``.
    """
    run = np.asarray(run, dtype=np.float64)
    reference = np.asarray(reference, dtype=np.float64)
    if run.ndim != 2 or reference.ndim != 2 or run.shape[1] != reference.shape[1]:
        raise ParameterError.of("reference", f"set-points of {run.shape} and {reference.shape}: "
                                "one column per axis, the same axes")
    if not (period > 0 and window > 0 and step > 0 and tolerance > 0):
        raise ParameterError("period, window, step and tolerance must be > 0")
    width = max(int(round(window / period)), 2)
    piece = max(int(round(step / period)), 1)
    # A recording with gaps (NaN rows) is aligned segment by segment: no match spans a gap.
    run_parts = _runs(np.isfinite(run).all(axis=1))
    ref_parts = [(a, b) for a, b in _runs(np.isfinite(reference).all(axis=1)) if b - a >= width]
    if not ref_parts:
        raise ParameterError.of("reference", f"no stretch of {window:g} s without missing "
                                "set-points to align on")
    found: list[list[int]] = [[] for _ in range(len(run))]
    best = np.full(len(run), np.nan)
    for ra, rb in run_parts:
        for fa, fb in ref_parts:
            shifts, low = _align_part(run[ra:rb], reference[fa:fb], width, piece, tolerance)
            for tick, (ticks, dist) in enumerate(zip(shifts, low, strict=True)):
                found[ra + tick].extend(fa + t for t in ticks)
                if not best[ra + tick] <= dist:
                    best[ra + tick] = dist
    k_max = max([len(f) for f in found] + [1])
    matches = np.full((len(run), k_max), -1, dtype=np.int64)
    for tick, ticks in enumerate(found):
        matches[tick, :len(ticks)] = sorted(ticks)
    return Alignment(matches=matches, distance=best, tolerance=tolerance)


def _align_part(run: np.ndarray, reference: np.ndarray, width: int, piece: int,
                tolerance: float) -> tuple[list[list[int]], np.ndarray]:
    """Matches (reference ticks) and best RMS distance per tick of one stretch without gaps.

    A piece no offset matches with the full context is tried again with half of it, then a
    quarter (down to the piece itself): where the run slows down within the context, one
    offset cannot match all of it, but it matches a shorter stretch.
    """
    n = len(run)
    ticks: list[list[int]] = [[] for _ in range(n)]
    low = np.full(n, np.inf)
    firsts = np.arange(0, n, piece)
    todo = np.ones(firsts.size, dtype=bool)
    w = width
    while todo.any():
        _match_pieces(run, reference, min(w, n), piece, tolerance, firsts, todo, ticks, low)
        if w <= piece or w <= 2:
            break
        w = max(w // 2, piece, 2)
    return ticks, low


def _match_pieces(run: np.ndarray, reference: np.ndarray, width: int, piece: int,
                  tolerance: float, firsts: np.ndarray, todo: np.ndarray,
                  ticks: list[list[int]], low: np.ndarray) -> None:
    """Match the pieces still ``todo`` with a context of ``width`` ticks (in place)."""
    n, m = len(run), len(reference)
    if width < 2 or m < width:
        return
    chosen = np.flatnonzero(todo)
    firsts = firsts[chosen]
    refs = sliding_window_view(reference, width, axis=0)  # (m - width + 1, axes, width)
    ref_sq = (refs ** 2).sum(axis=(1, 2))
    stops = np.minimum(firsts + piece, n)
    lows = np.clip((firsts + stops) // 2 - width // 2, 0, n - width)
    segments = run[lows[:, None] + np.arange(width)]  # (pieces, width, axes)
    # ||seg - ref_k||^2 = |seg|^2 + |ref_k|^2 - 2 <seg, ref_k>; the cross terms of every piece
    # and offset at once, by FFT
    cross = sum(
        fftconvolve(reference[None, :, j], segments[:, ::-1, j], mode="valid", axes=1)
        for j in range(reference.shape[1])
    )
    seg_sq = (segments ** 2).sum(axis=(1, 2))
    rms = np.sqrt(np.maximum(seg_sq[:, None] + ref_sq[None, :] - 2 * cross, 0.0)
                  / (width * reference.shape[1]))
    for p, (first, stop, a) in enumerate(zip(firsts, stops, lows, strict=True)):
        offsets = [lo + int(np.argmin(rms[p, lo:hi])) - int(a)
                   for lo, hi in _runs(rms[p] <= tolerance)]
        low[first:stop] = np.minimum(low[first:stop], rms[p].min())
        if offsets:
            todo[chosen[p]] = False
            for tick in range(first, stop):
                ticks[tick] = [tick + k for k in offsets if 0 <= tick + k < m]
