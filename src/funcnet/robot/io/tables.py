"""Recordings stored as tables: CSV, and Parquet files not written by funcnet.

A table has a header row, a ``time`` column (seconds, or the unit the channel map states, or ISO
8601 date-times: :mod:`funcnet.robot.io.clock`) and one column per signal (a SINUMERIK
name with its ``[u1, N]`` suffix, a role, or any name). How its cells are read:

- A cell that is empty or says ``NaN``/``NA``/``null`` is a missing value: NaN. Before a
  signal's first value it is a value not recorded yet; after it, a gap (see
  :mod:`funcnet.robot.grid`).
- Any other text where a number belongs is an error naming the file, the line and the column;
  so is time that is missing, not a number, or does not increase.
- A column name given twice is left out, both times, with a :class:`~funcnet.RecordingWarning`
  -- unless it is ``time``, a role (``RP``) or a channel-map entry: then which one to read is not
  for the reader to choose, and it is an error.
- Rows on the grid of the smallest time step; a row left out of the file (a sparse export that
  writes only changes) carries the previous row forward; a time off the grid is an error that
  offers the interpolation (:func:`~funcnet.robot.grid.time_grid`).
"""

from __future__ import annotations

import csv
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet.errors import ChannelError, RecordingWarning, TraceFormatError, caller_stacklevel
from funcnet.robot.grid import GridSignals, place_on_grid, time_grid
from funcnet.robot.io.channels import ChannelMap
from funcnet.robot.io.clock import clock_seconds
from funcnet.robot.signals import ROLES, SignalInfo, select_axis

__all__ = ["read_csv_table", "table_signals", "MISSING_CELLS"]

#: Cell texts (in any case, blanks around them ignored) that mean "no value".
MISSING_CELLS = frozenset({"", "nan", "na", "n/a", "null", "none"})


def _is_time(name: str) -> bool:
    return name.strip().lower() == "time"


def _without_duplicates(path: Path, names: list[str], cmap: ChannelMap) -> list[int]:
    """Positions of the columns to read: a name given twice is left out (said), or refused."""
    seen: dict[str, list[int]] = {}
    for position, name in enumerate(names):
        seen.setdefault(name, []).append(position)
    twice = {name: positions for name, positions in seen.items() if len(positions) > 1}
    for name, positions in twice.items():
        if _is_time(name) or cmap.role_of(name) is not None or name in ROLES:
            what = "the time column" if _is_time(name) else f"channel {name!r}"
            raise ChannelError(
                path, f"{what} is given {len(positions)} times (columns "
                f"{', '.join(str(p + 1) for p in positions)}); which one to read is ambiguous"
            )
    if twice:
        listed = "; ".join(
            f"{name!r} (columns {', '.join(str(p + 1) for p in positions)})"
            for name, positions in twice.items()
        )
        warnings.warn(
            RecordingWarning(
                f"{path}: column names given more than once, each left out: {listed}",
                problem="duplicate", signals=tuple(twice),
            ),
            stacklevel=caller_stacklevel(),
        )
    return [p for p, name in enumerate(names) if name not in twice]


def _numbers(
    path: Path, column: pd.Series, name: str, where: Callable[[int], str]
) -> np.ndarray:
    """A column as float64: missing cells NaN, any other text an error naming its line."""
    converted = pd.to_numeric(column, errors="coerce").to_numpy(dtype=np.float64)
    bad = ~np.isfinite(converted)
    if bad.any():
        text = column.astype(str).str.strip().str.lower()
        missing = (column.isna() | text.isin(MISSING_CELLS)).to_numpy()
        bad &= ~missing
        if bad.any():
            row = int(np.argmax(bad))
            raise TraceFormatError(
                path, f"{where(row)}: column {name!r} holds {column.iloc[row]!r}, not a number"
            )
    return converted


def table_signals(
    path: Path,
    table: pd.DataFrame,
    cmap: ChannelMap,
    axis: int | None,
    *,
    line_offset: int,
    off_grid: str = "error",
) -> GridSignals:
    """A table with a ``time`` column (CSV, plain Parquet) -> its signals on their grid.

    ``line_offset`` turns a row position into a line of the file (2 for a CSV with a header);
    0 for Parquet, which has no lines: errors then name the row.
    """

    def where(row: int) -> str:
        return f"line {row + line_offset}" if line_offset else f"row {row}"

    names = [str(c) for c in table.columns]
    kept = _without_duplicates(path, names, cmap)
    time_columns = [p for p in kept if _is_time(names[p])]
    if len(time_columns) != 1:
        raise TraceFormatError(path, f"needs exactly one 'time' column; it has {names}")
    if len(table) == 0:
        raise TraceFormatError(path, "has no rows")
    time_at = time_columns[0]
    clock = clock_seconds(path, table.iloc[:, time_at], cmap.time_unit(names[time_at]),
                          names[time_at], where)
    time = clock.seconds
    period, ticks = time_grid(path, time, where, off_grid=off_grid)
    signal_at = [p for p in kept if p != time_at]
    keep, axis = select_axis([names[p] for p in signal_at], axis, path)
    signal_at = [p for p, wanted in zip(signal_at, keep, strict=True) if wanted]
    if not signal_at:
        raise TraceFormatError(path, "has a time column but no signal column")
    columns = [_numbers(path, table.iloc[:, p], names[p], where) for p in signal_at]
    values = place_on_grid(time, np.column_stack(columns), period, ticks)
    return GridSignals(
        signals=tuple(SignalInfo(names[p], None, None, period, cmap.unit(names[p]))
                      for p in signal_at),
        values=values,
        sample_period=period,
        t0=float(np.round(time[0], 9)),
        axis=axis,
        start_time=clock.start_time,
        time_origin=clock.origin,
        time_unit=None if clock.unit == "s" else clock.unit,
    )


def read_csv_table(
    path: Path, cmap: ChannelMap, axis: int | None, *, off_grid: str = "error"
) -> GridSignals:
    """A CSV file -> its signals on their grid (see the module's rules)."""
    try:
        with path.open(newline="", encoding="utf-8") as stream:
            header = next(csv.reader(stream), None)
        if header is None:
            raise TraceFormatError(path, "empty file: not a trace")
        if not any(name.strip() for name in header):
            raise TraceFormatError(path, "not a readable CSV file: its first line names no column")
        # Text is converted here, not by pandas, so that 'abc' is reported with its line; the
        # header is read apart so that a name given twice stays visible as such.
        table = pd.read_csv(
            path, header=None, skiprows=1, names=list(range(len(header))), dtype=str,
            keep_default_na=False, skip_blank_lines=False,
        )
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError,
            csv.Error) as exc:
        raise TraceFormatError(path, f"not a readable CSV file: {exc}") from exc
    table.columns = pd.Index(header)
    return table_signals(path, table, cmap, axis, line_offset=2, off_grid=off_grid)
