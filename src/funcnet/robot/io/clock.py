"""A file's time column as seconds from the recording's start: its unit, its origin, its dates.

Controllers stamp their samples in many ways: seconds from the start of the log (a UR log
folder), seconds of controller uptime (UR's RTDE log), microseconds of the real-time clock (a
Mecademic log), nanoseconds of Unix time (ROS), or ISO 8601 date-times. Every reader turns its
time column into seconds here (:func:`clock_seconds`), by these rules:

- **The unit** is the channel map's: ``[units] timestamp = "us"`` for a column called
  ``timestamp`` (or ``time = "ms"`` for the time column whatever its name); one of
  :data:`TIME_UNITS`. A column of ISO 8601 date-times (``2024-03-07T14:23:02.001``) states its
  own.
- **A column of numbers without a unit** is seconds, when its step is one a controller log can
  have (:data:`PLAUSIBLE_STEP`, 1 us to 0.5 s). Any other step is never guessed: an error says
  the step and what it would be in each unit, and how to state the unit. A log truly sampled
  slower than every 0.5 s states ``"s"``.
- **The origin**: a clock that reads :data:`ABSOLUTE_CLOCK` (1000 s, about 17 min) or more at
  the first sample counts from something before the recording (controller uptime, Unix time),
  and so does a date-time: it is read from the recording's start, its first sample at 0 s, and
  the clock's reading there is kept as the recording's ``time_origin`` (seconds on the file's
  clock) and, for date-times, its ``start_time``. A time column that starts lower (0 s, or 3 s
  into an export) keeps its values.

Examples
--------
>>> clock = clock_seconds("log.csv", np.array([107742743000.0, 107742744000.0]), "us",
...                       "timestamp")
>>> clock.seconds.tolist(), clock.origin, clock.unit
([0.0, 0.001], 107742.743, 'us')
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet.errors import ChannelError, TraceFormatError

__all__ = ["TIME_UNITS", "PLAUSIBLE_STEP", "ABSOLUTE_CLOCK", "Clock", "clock_seconds",
           "time_unit_factor"]

#: The units a time column may be stated in, and their factor to seconds.
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9}
#: The steps (seconds) a controller log's time column of unstated unit may have: 1 us to 0.5 s.
PLAUSIBLE_STEP = (1e-6, 0.5)
#: A first stamp (seconds) from which a clock is read from the recording's start.
ABSOLUTE_CLOCK = 1000.0


@dataclass(frozen=True)
class Clock:
    """A time column read as seconds from its first stamp.

    Attributes
    ----------
    seconds : ndarray, shape (N,)
        Seconds, from ``origin`` (NaN where a stamp is missing).
    origin : float
        Where the file's own clock stood at 0 s: its first stamp for an absolute clock (Unix
        time for date-times), else 0.0 (the stamps kept as written).
    unit : str
        The unit read: as stated, ``"s"`` when none is, ``"ISO 8601"`` for date-times.
    start_time : str or None
        The first date-time as the file writes it (date-time columns only).
    """

    seconds: np.ndarray
    origin: float
    unit: str
    start_time: str | None = None


def time_unit_factor(unit: str, name: str, path: object) -> float:
    """The factor from a time column's stated unit to seconds.

    Raises
    ------
    ChannelError
        ``unit`` is not one of :data:`TIME_UNITS` (the message names the column).

    Examples
    --------
    >>> time_unit_factor("ms", "t", "log.csv")
    0.001
    """
    factor = TIME_UNITS.get(unit.strip().lower().replace("μ", "µ"))
    if factor is None:
        raise ChannelError(
            path, f"the unit of time column {name!r} is {unit!r}; a time unit is one of "
            f"{', '.join(u for u in TIME_UNITS if u != 'µs')}"
        )
    return factor


def _dates(cells: pd.Series) -> np.ndarray | None:
    """Nanoseconds of Unix time of ISO 8601 date-times (a missing cell -1), or None when the
    cells are not date-times."""
    text = cells.astype(str).str.strip()
    present = cells.notna().to_numpy() & (text != "").to_numpy()
    if not present.any() or not text[present].str.match(r"^\d{4}-\d{2}-\d{2}[T ]\d").all():
        return None
    try:
        stamps = pd.to_datetime(text.where(present), format="ISO8601", utc=True)
    except (ValueError, TypeError):
        return None
    nanoseconds = stamps.to_numpy(dtype="datetime64[ns]").astype(np.int64)
    return np.where(present, nanoseconds, -1)


def _implausible(path: object, name: str, raw: np.ndarray) -> None:
    """Refuse a time column of unstated unit whose step is no controller log's in seconds."""
    steps = np.diff(raw[np.isfinite(raw)])
    steps = steps[steps > 0]
    if not len(steps):
        return  # not increasing: the grid says where
    step = float(np.median(steps))
    low, high = PLAUSIBLE_STEP
    if low <= step <= high:
        return
    readings = ", ".join(
        f"as {unit} every {_duration(step * factor)}"
        for unit, factor in TIME_UNITS.items() if unit not in ("s", "µs")
    )
    raise ChannelError(
        path, f"time column {name!r} steps by {step:g} per sample with no unit stated: as "
        f"seconds a sample every {_duration(step)}, no controller log's step (1 us to 0.5 s); "
        f"{readings}; state its unit in the channel map: [units] {name} = \"us\" (one of s, "
        "ms, us, ns)"
    )


def _duration(seconds: float) -> str:
    """``"1 ms"``, ``"16.7 min"``: a duration in the unit that reads best."""
    for unit, size in (("d", 86400.0), ("h", 3600.0), ("min", 60.0), ("s", 1.0),
                       ("ms", 1e-3), ("us", 1e-6)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds * 1e9:.3g} ns"


def clock_seconds(
    path: object,
    cells: np.ndarray | pd.Series | Sequence[object],
    unit: str | None,
    name: str,
    where: Callable[[int], str] | None = None,
) -> Clock:
    """A time column as seconds from its first stamp (see the module's rules).

    Parameters
    ----------
    path : path-like
        The file, named in errors.
    cells : array or Series
        The column as read: numbers (NaN where missing), or text (ISO 8601 date-times, or
        numbers written as text).
    unit : str or None
        The unit the channel map states (:data:`TIME_UNITS`); None: seconds if plausible.
    name : str
        The column's name, in messages.
    where : callable, optional
        Row position -> where it is in the file (``"line 7"``), for errors.

    Returns
    -------
    Clock

    Raises
    ------
    ChannelError
        An unknown unit; no unit stated and a step no controller log has in seconds.
    TraceFormatError
        Text that is neither a number nor an ISO 8601 date-time (the message names the row).

    Examples
    --------
    >>> clock = clock_seconds("a.csv", pd.Series(["2024-03-07T14:23:02.000",
    ...                                          "2024-03-07T14:23:02.002"]), None, "time")
    >>> clock.seconds.tolist(), clock.start_time, clock.unit
    ([0.0, 0.002], '2024-03-07T14:23:02.000', 'ISO 8601')
    >>> clock_seconds("a.csv", np.array([0.0, 1000.0, 2000.0]), None, "timestamp")
    Traceback (most recent call last):
    ...
    funcnet.errors.ChannelError: a.csv: time column 'timestamp' steps by 1000 per sample with no unit stated: as seconds a sample every 16.7 min, ...
    """  # noqa: E501
    series = cells if isinstance(cells, pd.Series) else pd.Series(np.asarray(cells))
    if series.dtype.kind == "M":  # a date-time column of a Parquet file
        series = series.dt.strftime("%Y-%m-%dT%H:%M:%S.%f")
    if series.dtype.kind in "fiu":
        raw = series.to_numpy(dtype=np.float64)
    else:
        nanoseconds = _dates(series)
        if nanoseconds is not None:
            return _from_dates(series, nanoseconds)
        raw = pd.to_numeric(series, errors="coerce").to_numpy(dtype=np.float64)
        text = series.astype(str).str.strip().str.lower()
        bad = np.isnan(raw) & series.notna().to_numpy() & ~text.isin(
            ["", "nan", "na", "n/a", "null", "none"]).to_numpy()
        if bad.any():
            row = int(np.argmax(bad))
            at = where(row) if where is not None else f"row {row + 1}"
            raise TraceFormatError(
                path, f"{at}: time column {name!r} holds {series.iloc[row]!r}, neither a "
                "number nor an ISO 8601 date-time"
            )
    if unit is None:
        _implausible(path, name, raw)
        factor, unit = 1.0, "s"
    else:
        factor = time_unit_factor(unit, name, path)
    finite = np.flatnonzero(np.isfinite(raw))
    first = raw[finite[0]] if len(finite) else 0.0
    if abs(first * factor) < ABSOLUTE_CLOCK:
        return Clock(raw * factor, 0.0, unit)
    # from the first stamp before scaling: a large clock reading keeps its small steps exact
    return Clock((raw - first) * factor, float(np.round(first * factor, 9)), unit)


def _from_dates(series: pd.Series, nanoseconds: np.ndarray) -> Clock:
    """:class:`Clock` of date-times (Unix nanoseconds, -1 where missing)."""
    present = nanoseconds >= 0
    first = int(nanoseconds[present][0])
    seconds = np.where(present, (nanoseconds - first) / 1e9, np.nan)
    text = str(series[present].iloc[0]).strip()
    return Clock(seconds, first / 1e9, "ISO 8601", text)
