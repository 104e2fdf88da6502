"""Time stamps onto a uniform grid, and the gaps where a recording has no values.

Every reader ends here: a file's time stamps become ticks of one sample period
(:func:`time_grid`), the samples are placed on those ticks (:func:`place_on_grid`), and the
stretches where a signal has no value after its first one are the recording's gaps
(:func:`find_gaps`, runs of ticks as :func:`mask_runs` finds them). A file reader returns a
:class:`GridSignals`; :func:`funcnet.robot.read_trace` turns it into a
:class:`~funcnet.robot.Recording`.

The rules, the same for every format:

- Time must be a finite number that increases from sample to sample: otherwise an error names
  the file and the line (or sample) where it does not.
- The sample period is the smallest step between time stamps, rounded to the nanosecond; any
  period, not only a controller's 2 ms. A time stamp farther than a thousandth of a tick from the
  grid is an error that offers ``resample="interpolate"``: then every signal is interpolated
  linearly onto a grid of the median step, rounded to the microsecond.
- A sample a file leaves out (a step of several periods) is, in a table (CSV, Parquet), the
  previous row carried forward (a sparse export writes only changes); in a file of arrays
  (MATLAB, HDF5), a gap.
- A value that is missing (NaN, an empty cell) after a signal's first value is a gap; the values
  before a signal's first one (a 4 ms signal not yet written on a 2 ms grid) are not.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from funcnet.errors import TraceFormatError
from funcnet.robot.signals import SignalInfo

__all__ = [
    "GridSignals", "time_grid", "place_on_grid", "find_gaps", "mask_runs", "segments_between",
    "segments_phrase", "OFF_GRID", "format_spans",
]

#: What to do with time stamps off their grid: refuse them, or interpolate onto the grid.
OFF_GRID = ("error", "interpolate")
# Relative tolerance, in ticks, for times that should lie on the grid.
GRID_TOLERANCE = 1e-3


@dataclass(frozen=True)
class GridSignals:
    """Signals of one file on a uniform grid, before they become a recording.

    Attributes
    ----------
    signals : tuple of SignalInfo
        One per column of ``values``.
    values : ndarray, shape (n_ticks, n_signals)
        float64; NaN where there is no value.
    sample_period : float
        Seconds.
    t0 : float
        Time of the first tick, seconds.
    start_time : str or None
        When the recording started, as the file says it.
    axis : int or None
        The axis read.
    columns : tuple of str or None
        Column names when the reader names the columns itself (multi-axis files); None lets the
        channel map name them.
    roles : dict or None
        Column -> controller name for the columns with a role, with ``columns``.
    time_origin : float
        The file's clock at time 0 (seconds: controller uptime, Unix time), when the reader
        read its time from the recording's start (:mod:`funcnet.robot.io.clock`).
    time_unit : str or None
        The unit the time column was read in (``"us"``, ``"ISO 8601"``); None: seconds, or a
        format whose time is its own (SINUMERIK).
    """

    signals: tuple[SignalInfo, ...]
    values: np.ndarray
    sample_period: float
    t0: float = 0.0
    start_time: str | None = None
    axis: int | None = None
    columns: tuple[str, ...] | None = None
    roles: dict[str, str] | None = None
    time_origin: float = 0.0
    time_unit: str | None = None


def time_grid(
    path: object,
    time: np.ndarray,
    where: Callable[[int], str],
    *,
    off_grid: str = "error",
) -> tuple[float, np.ndarray | None]:
    """The sample period of a file's time stamps and each stamp's tick.

    Parameters
    ----------
    path : path-like
        The file, named in errors.
    time : ndarray, shape (N,)
        The time stamps in seconds, as read (NaN where a stamp is not a number).
    where : callable
        Sample position -> where it is in the file (``"line 7"``, ``"sample 7"``), for errors.
    off_grid : {"error", "interpolate"}
        What to do with stamps off the grid.

    Returns
    -------
    period : float
        The grid interval in seconds.
    ticks : ndarray of int64 or None
        The tick of each stamp (from the first, 0); None when the stamps are off the grid and
        ``off_grid="interpolate"``: then the grid is ``time[0] + k * period`` up to the last
        stamp, and the values are interpolated onto it by :func:`place_on_grid`.

    Raises
    ------
    TraceFormatError
        Fewer than two stamps; a stamp that is not a finite number; time that does not increase;
        stamps off the grid with ``off_grid="error"`` (the message offers the interpolation).

    Examples
    --------
    >>> period, ticks = time_grid("t.csv", np.array([0.0, 0.004, 0.012]), lambda i: f"line {i}")
    >>> period, ticks.tolist()
    (0.004, [0, 1, 3])
    >>> time_grid("t.csv", np.array([0.0, 0.004, 0.0081, 0.012]), lambda i: f"line {i}")
    Traceback (most recent call last):
    ...
    funcnet.errors.TraceFormatError: t.csv: line 1: time 0.004 is not on the 0.0039 s grid of its smallest step (...); resample=...
    """  # noqa: E501
    if off_grid not in OFF_GRID:
        raise ValueError(f"off_grid must be one of {OFF_GRID}, got {off_grid!r}")
    if len(time) < 2:
        raise TraceFormatError(path, "needs at least two samples to know its sample period")
    bad = ~np.isfinite(time)
    if bad.any():
        row = int(np.argmax(bad))
        raise TraceFormatError(path, f"{where(row)}: time is missing ({float(time[row])!r})")
    steps = np.diff(time)
    if (steps <= 0).any():
        row = int(np.argmax(steps <= 0)) + 1
        raise TraceFormatError(
            path,
            f"{where(row)}: time {float(time[row])!r} does not increase "
            f"(the sample before is at {float(time[row - 1])!r})",
        )
    period = float(np.round(steps.min(), 9))
    position = (time - time[0]) / period
    ticks = np.round(position).astype(np.int64)
    off = np.abs(position - ticks) > GRID_TOLERANCE
    if not off.any():
        return period, ticks
    median = float(np.round(np.median(steps), 6)) or period
    if off_grid == "interpolate":
        return median, None
    row = int(np.argmax(off))
    raise TraceFormatError(
        path,
        f"{where(row)}: time {float(time[row])!r} is not on the {period:g} s grid of its "
        f"smallest step ({int(off.sum())} of {len(time)} stamps are off it); "
        f"resample='interpolate' (--resample interpolate) interpolates every signal onto a "
        f"{median:g} s grid",
    )


def place_on_grid(
    time: np.ndarray,
    values: np.ndarray,
    period: float,
    ticks: np.ndarray | None,
    *,
    left_out: str = "carry",
) -> np.ndarray:
    """The samples of a file on the ticks of its grid.

    Parameters
    ----------
    time : ndarray, shape (N,)
        Increasing time stamps, seconds.
    values : ndarray, shape (N, k)
        The samples (NaN where missing).
    period : float
        The grid interval.
    ticks : ndarray of int or None
        Each stamp's tick (:func:`time_grid`); None to interpolate linearly onto the grid (a grid
        tick between a missing value and its neighbour stays missing).
    left_out : {"carry", "gap"}
        A tick no stamp falls on: the previous sample carried forward, or NaN.

    Returns
    -------
    ndarray, shape (n_ticks, k)

    Examples
    --------
    >>> v = np.array([[1.0], [2.0], [4.0]])
    >>> place_on_grid(np.array([0, 1, 3.0]), v, 1.0, np.array([0, 1, 3]))[:, 0].tolist()
    [1.0, 2.0, 2.0, 4.0]
    >>> place_on_grid(np.array([0, 1, 3.0]), v, 1.0, np.array([0, 1, 3]), left_out="gap")[:, 0]
    array([ 1.,  2., nan,  4.])
    >>> place_on_grid(np.array([0, 1.2, 2.0]), v, 0.5, None)[:, 0].tolist()
    [1.0, 1.41..., 1.83..., 2.75, 4.0]
    """
    if ticks is None:
        n_ticks = int(np.floor((time[-1] - time[0]) / period + GRID_TOLERANCE)) + 1
        grid = time[0] + np.arange(n_ticks) * period
        right = np.clip(np.searchsorted(time, grid, side="left"), 0, len(time) - 1)
        left = np.clip(right - 1, 0, len(time) - 1)
        out = np.empty((n_ticks, values.shape[1]))
        for j in range(values.shape[1]):
            column = values[:, j]
            out[:, j] = np.interp(grid, time, np.nan_to_num(column))
            # A grid tick is missing where either sample it is interpolated between is.
            on_sample = np.isclose(time[right], grid, rtol=0.0, atol=GRID_TOLERANCE * period)
            missing = np.isnan(column[right]) | (np.isnan(column[left]) & ~on_sample)
            out[missing, j] = np.nan
        return out
    present = np.zeros(int(ticks[-1]) + 1, dtype=bool)
    present[ticks] = True
    if left_out == "carry":
        row_of_tick = np.cumsum(present) - 1
        return values[row_of_tick]
    out = np.full((len(present), values.shape[1]), np.nan)
    out[ticks] = values
    return out


def mask_runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Maximal runs of True as ``(first, stop)`` tick pairs (``first <= tick < stop``).

    Parameters
    ----------
    mask : ndarray of bool, shape (N,)

    Returns
    -------
    list of (int, int)
        The runs in order; empty when no tick is True.

    Examples
    --------
    >>> [(int(a), int(b)) for a, b in mask_runs(np.array([0, 1, 1, 0, 1], dtype=bool))]
    [(1, 3), (4, 5)]
    """
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True))


def find_gaps(values: np.ndarray) -> tuple[list[tuple[int, int]], list[list[int]]]:
    """The stretches of ticks where a signal has no value after its first one.

    Parameters
    ----------
    values : ndarray, shape (n_ticks, k)

    Returns
    -------
    gaps : list of (int, int)
        Half-open tick ranges ``[first, stop)``, in order, where at least one signal is missing
        after its first value (and up to the end when it stops early).
    columns : list of list of int
        Per gap, the signals missing in it.

    Examples
    --------
    >>> v = np.array([[np.nan, 1], [1, 2], [np.nan, 3], [np.nan, np.nan], [4, 5]])
    >>> find_gaps(v)
    ([(2, 4)], [[0, 1]])
    """
    missing = np.isnan(values)
    started = np.logical_or.accumulate(~missing, axis=0)
    hole = missing & started
    any_hole = hole.any(axis=1)
    if not any_hole.any():
        return [], []
    gaps = [(int(a), int(b)) for a, b in mask_runs(any_hole)]
    columns = [np.flatnonzero(hole[a:b].any(axis=0)).tolist() for a, b in gaps]
    return gaps, columns


def segments_between(
    gaps: Sequence[tuple[float, float]], start: float, stop: float
) -> list[tuple[float, float]]:
    """The spans of ``[start, stop)`` between the ``gaps`` (half-open spans, seconds).

    Examples
    --------
    >>> segments_between([(1.0, 1.5), (3.0, 3.2)], 0.0, 5.0)
    [(0.0, 1.0), (1.5, 3.0), (3.2, 5.0)]
    """
    spans, at = [], start
    for a, b in sorted(gaps):
        if a > at:
            spans.append((at, min(a, stop)))
        at = max(at, b)
    if at < stop:
        spans.append((at, stop))
    return [(a, b) for a, b in spans if b > a]


def segments_phrase(spans: Sequence[tuple[float, float]]) -> str:
    """How many segments ``spans`` are, in words, as every message about gaps says it.

    Parameters
    ----------
    spans : sequence of (float, float)
        The segments (:func:`segments_between`, :attr:`funcnet.robot.Recording.segments`).

    Returns
    -------
    str
        ``"1 segment"``, ``"2 segments"``, ...

    Examples
    --------
    >>> segments_phrase(segments_between([(4.0, 5.0)], 0.0, 5.0))  # a gap up to the end
    '1 segment'
    >>> segments_phrase(segments_between([(1.0, 1.5)], 0.0, 5.0))
    '2 segments'
    """
    return f"{len(spans)} segment{'' if len(spans) == 1 else 's'}"


def format_spans(spans: Sequence[tuple[float, float]]) -> str:
    """Time spans as the messages and reports write them: ``"3.5-3.8 s, 5-5.2 s"``.

    Parameters
    ----------
    spans : sequence of (float, float)
        Start and end in seconds (gaps, segments).

    Returns
    -------
    str
        Each span ``start-end s`` (``%g``), comma-separated; "" for none.

    Examples
    --------
    >>> format_spans([(3.5, 3.8), (5.0, 5.2)])
    '3.5-3.8 s, 5-5.2 s'
    """
    return ", ".join(f"{a:g}-{b:g} s" for a, b in spans)
