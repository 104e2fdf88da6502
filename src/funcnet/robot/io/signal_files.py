"""A recording made of text files: one file per signal (a run's folder), or one log file.

A channel map's ``[signals]`` table names each signal's file and columns
(:mod:`funcnet.robot.io.layout`); :func:`read_signal_files` reads them and joins them on their time
stamps. How:

- Only the files the map names are read; any other file of the folder is ignored.
- A file's **last line without a line end** was cut while it was written (a logger stopped in the
  middle of a line: ``21.``): it is dropped. Every file with such a line is named in one
  :class:`~funcnet.RecordingWarning` (``problem="cut_line"``).
- Time (seconds, or the unit ``[units]`` states for the time column, or ISO 8601 date-times;
  an absolute clock read from the earliest file's first stamp: :mod:`funcnet.robot.io.clock`)
  must increase on a uniform grid (:func:`funcnet.robot.grid.time_grid`), the same period in
  every file. The signals are joined on their time stamps: where the files cover
  different spans (each cut at its own end), the recording is their **common span**, and every
  file that reached beyond it is named, with its own end, in one warning
  (``problem="trimmed"``).
- A row a file leaves out inside the span, or a cell without a number, is a gap (NaN; see
  :mod:`funcnet.robot.grid`). Text where a number belongs is an error naming the file, the line
  and the column.
- **Axes**: an entry with one column per axis gives, with ``axis=n``, its column ``n`` (counted
  from 1) named by its role (``RP``), else by its entry's name (``m_target``); without ``axis``
  every axis, the columns qualified by it (``A1.RP``, ``A2.RP``, ...; :mod:`funcnet.robot.axes`).
  An entry of one column is common to every axis and keeps its bare name.
- **Units** are the map's ``[units]``; a text file states none. A list of units gives an entry
  of one column per axis a unit per axis (``target = ["deg", "deg", "mm", "deg"]``).
"""

from __future__ import annotations

import io
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet.errors import (
    ChannelError,
    RecordingWarning,
    TraceError,
    TraceFormatError,
    caller_stacklevel,
)
from funcnet.robot.axes import qualified, split_qualified
from funcnet.robot.grid import GRID_TOLERANCE, GridSignals, time_grid
from funcnet.robot.io.channels import DEFAULT_CHANNEL_MAP, TIME_ROLE, ChannelMap
from funcnet.robot.io.clock import Clock, clock_seconds
from funcnet.robot.io.layout import SignalFile
from funcnet.robot.signals import SignalInfo

__all__ = ["read_signal_files", "FileTable"]


@dataclass(frozen=True)
class FileTable:
    """The columns one file gives, as read (before the files are joined).

    Attributes
    ----------
    path : Path
    time : ndarray, shape (N,)
        Seconds (an absolute clock's from the earliest file's first stamp:
        :mod:`funcnet.robot.io.clock`).
    columns : dict
        The column (position or header name) -> its values, float64 (NaN where a cell is empty).
    cut_line : str or None
        The last line, dropped because it has no line end; None when the file ends whole.
    clock : Clock or None
        The time column as read: its unit, and the file's clock at its first stamp.
    """

    path: Path
    time: np.ndarray
    columns: dict[int | str, np.ndarray]
    cut_line: str | None
    clock: Clock | None = None


def _separator(layout: SignalFile) -> dict[str, object]:
    if layout.separator == " ":
        return {"sep": r"\s+"}
    return {"sep": layout.separator, "skipinitialspace": True}


def _raw(path: Path, layouts: Sequence[SignalFile]) -> tuple[bytes, str | None]:
    """A file's bytes without a cut last line, and that line (None when the file ends whole)."""
    first = layouts[0]
    if any(layout.header != first.header or layout.separator != first.separator
           for layout in layouts):
        raise ChannelError(
            path, f"the channel map gives this file two layouts (header, separator) in "
            f"{', '.join(layout.signal for layout in layouts)}"
        )
    try:
        raw = path.read_bytes()
    except FileNotFoundError as exc:
        raise TraceError(path, f"no such file (the channel map names it for "
                         f"{', '.join(layout.signal for layout in layouts)})") from exc
    except OSError as exc:
        raise TraceError(path, f"cannot be read: {exc}") from exc
    cut_line = None
    if raw and not raw.endswith(b"\n"):
        end = raw.rfind(b"\n") + 1
        cut_line = raw[end:].decode("utf-8", "replace")
        raw = raw[:end]
    if not raw.strip():
        raise TraceFormatError(path, "empty file: no line to read")
    return raw, cut_line


def _parse(path: Path, raw: bytes, layout: SignalFile) -> pd.DataFrame:
    """The text as a table (numbers as float64 where every cell of a column is one)."""
    try:
        table = pd.read_csv(
            io.BytesIO(raw), header=0 if layout.header else None, engine="c",
            skip_blank_lines=True, **_separator(layout),  # type: ignore[arg-type]
        )
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise TraceFormatError(path, f"not a readable text table: {exc}") from exc
    if layout.header:
        table.columns = [str(c).strip() for c in table.columns]
    return table


def _parse_together(raws: dict[Path, bytes], layout: SignalFile) -> list[dict] | None:
    """Headerless files of one separator and width parsed in one pass of Arrow's CSV reader
    (a parser call costs about as much as a small file's numbers; Arrow's is about 3x pandas'
    on these files), then split; None when they differ or the pass fails (each file is then
    parsed on its own by pandas, its errors naming it, a short row read as missing values)."""
    if layout.header or layout.separator == " ":
        return None
    separator = layout.separator.encode()
    widths = {raw[: raw.find(b"\n")].count(separator) for raw in raws.values()}
    if len(widths) != 1:
        return None
    import pyarrow as pa
    import pyarrow.csv as pacsv

    try:
        table = pacsv.read_csv(
            pa.py_buffer(b"".join(raws.values())),
            # one thread: as fast on these sizes, and a study runs one task per core
            read_options=pacsv.ReadOptions(autogenerate_column_names=True, use_threads=False),
            parse_options=pacsv.ParseOptions(delimiter=layout.separator),
        )
    except (pa.ArrowInvalid, pa.ArrowTypeError):
        return None
    columns = [table.column(j).to_numpy() for j in range(table.num_columns)]
    if any(c.dtype != np.float64 for c in columns):
        return None  # text or empty cells: pandas says where
    parts, at = [], 0
    for raw in raws.values():
        n = raw.count(b"\n")
        parts.append({j: c[at: at + n] for j, c in enumerate(columns)})
        at += n
    return parts


def _file_table(
    path: Path, table: pd.DataFrame | dict, layouts: Sequence[SignalFile], cut_line: str | None,
    cmap: ChannelMap,
) -> FileTable:
    """One file's time and the columns ``layouts`` need, as numbers (``table``: a parsed
    table, or its columns as arrays)."""
    first = layouts[0]
    wanted: list[int | str] = [first.time]
    for layout in layouts:
        wanted += [c for c in (layout.time, *layout.columns) if c not in wanted]
    present = list(table)
    missing = [c for c in wanted if c not in present]
    if missing:
        held = (f"its columns are {present}" if first.header
                else f"it has {len(present)} columns (0-{len(present) - 1})")
        raise ChannelError(
            path, f"the channel map reads columns {missing}, which the file does not have; "
            f"{held}"
        )
    line_offset = 2 if first.header else 1
    name = first.time if isinstance(first.time, str) else f"column {first.time}"
    clock = clock_seconds(
        path, table[first.time], cmap.time_unit(first.time if isinstance(first.time, str)
                                                else None), name,
        lambda row: f"line {row + line_offset}",
    )
    values: dict[int | str, np.ndarray] = {}
    for column in wanted[1:]:
        cells = table[column]
        if isinstance(cells, np.ndarray) or cells.dtype.kind in "fi":
            values[column] = np.asarray(cells, dtype=np.float64)
            continue
        numbers = pd.to_numeric(cells, errors="coerce").to_numpy(dtype=np.float64)
        text = cells.astype(str).str.strip()
        bad = np.isnan(numbers) & cells.notna().to_numpy() & ~text.str.lower().isin(
            ["", "nan", "na", "null"]).to_numpy()
        if bad.any():
            row = int(np.argmax(bad))
            raise TraceFormatError(
                path, f"line {row + line_offset}: column {column!r} holds {cells.iloc[row]!r}, "
                "not a number"
            )
        values[column] = numbers
    return FileTable(path, clock.seconds, values, cut_line, clock)


def _read_tables(
    by_file: dict[Path, list[SignalFile]], cmap: ChannelMap
) -> dict[Path, FileTable]:
    """Every file the map names, read; their times from the earliest file's first stamp."""
    raws = {file: _raw(file, layouts) for file, layouts in by_file.items()}
    layouts_ = [layouts[0] for layouts in by_file.values()]
    same = all((one.header, one.separator) == (layouts_[0].header, layouts_[0].separator)
               for one in layouts_)
    parts = _parse_together({f: r for f, (r, _) in raws.items()}, layouts_[0]) if same else None
    if parts is None:
        parts = [_parse(file, raws[file][0], by_file[file][0]) for file in by_file]
    tables = {file: _file_table(file, part, by_file[file], raws[file][1], cmap)
              for file, part in zip(by_file, parts, strict=True)}
    # files on one absolute clock share the earliest file's origin (0 for a relative one)
    origins = [t.clock.origin for t in tables.values() if t.clock is not None and t.clock.origin]
    origin = min(origins, default=0.0)
    return {file: replace(t, time=t.time + (t.clock.origin - origin))
            if t.clock and t.clock.origin else t for file, t in tables.items()}


def _shown(text: str, limit: int = 24) -> str:
    return repr(text if len(text) <= limit else text[:limit] + "...")


def read_signal_files(
    path: Path, cmap: ChannelMap, axis: int | None, *, off_grid: str = "error"
) -> GridSignals:
    """The signals a channel map names in text files, joined on their time stamps.

    Parameters
    ----------
    path : Path
        A run's folder (the entries' files are relative to it), or a log file (the entries
        without ``file``).
    cmap : ChannelMap
        With its ``files`` (:attr:`ChannelMap.files`).
    axis : int or None
        The axis to read (from 1); None reads every axis.
    off_grid : {"error", "interpolate"}
        See :func:`funcnet.robot.grid.time_grid`.

    Returns
    -------
    GridSignals
        With its column names and roles; the common span of the files.

    Raises
    ------
    TraceError
        A file the map names is not there.
    TraceFormatError
        Not a readable table; text where a number belongs; time not increasing or off its
        grid; files of different sample periods, or without a common span.
    ChannelError
        A column the map names is not in its file; ``axis`` not in the recording; a
        ``[channels]`` or ``[units]`` entry that names no signal; two signals for one role; an
        entry with a file given a log file, or one without a file given a folder.

    Examples
    --------
    >>> import pathlib, tempfile, warnings
    >>> from funcnet.robot.io.channels import ChannelMap
    >>> from funcnet.robot.io.layout import signal_files
    >>> run = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (run / "q.csv").write_text("0.000, 1.0, 2.0\\n0.008, 1.5, 2.5\\n0.016, 2.0, 3.0\\n")
    >>> _ = (run / "i.csv").write_text("0.000, 0.1, 0.2\\n0.008, 0.3, 0.4\\n0.0")
    >>> files = signal_files({"q": "q.csv", "i": "i.csv"}, {"columns": [1, 2]}, "m.toml")
    >>> cmap = ChannelMap({"q": "RP"}, files=files)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     grid = read_signal_files(run, cmap, axis=2)
    >>> print("\\n".join(str(w.message).split(": ", 1)[1] for w in caught))
    last line cut (no line end), dropped: i.csv ('0.0')
    files end at different times; read over the time stamps they share, 0-0.008 s: q.csv (last at 0.016 s)
    >>> grid.columns, grid.values.tolist()
    (('RP', 'i'), [[2.0, 0.2], [2.5, 0.4]])
    """  # noqa: E501
    folder = path.is_dir()
    entries = list(cmap.files.values())
    misplaced = [e.signal for e in entries if (e.file is None) == folder]
    if misplaced:
        raise ChannelError(
            path, f"the channel map {cmap.origin or ''} names "
            + (f"no file for {misplaced}: give the log file, not a folder" if folder else
               f"files for {misplaced} relative to a run's folder: give the folder, not a file")
        )
    by_file: dict[Path, list[SignalFile]] = {}
    for entry in entries:
        by_file.setdefault(path / entry.file if entry.file else path, []).append(entry)
    _check_names(cmap, path)
    tables = _read_tables(by_file, cmap)

    def name(file: Path) -> str:
        return file.name if folder else str(file)

    cut = [f"{name(file)} ({_shown(t.cut_line)})" for file, t in tables.items()
           if t.cut_line is not None]
    if cut:
        warnings.warn(
            RecordingWarning(
                f"{path}: last line cut (no line end), dropped: {', '.join(cut)}",
                problem="cut_line", signals=tuple(e.signal for f, t in tables.items()
                                                  if t.cut_line is not None for e in by_file[f]),
            ),
            stacklevel=caller_stacklevel(),
        )
    grids = {}
    for file, table in tables.items():
        def where(row: int, header: bool = by_file[file][0].header) -> str:
            return f"line {row + (2 if header else 1)}"
        grids[file] = time_grid(file, table.time, where, off_grid=off_grid)
    periods = {file: period for file, (period, _) in grids.items()}
    period = min(periods.values())
    odd = [f"{name(f)} ({p:g} s)" for f, p in periods.items()
           if abs(p - period) > GRID_TOLERANCE * period]
    if odd:
        finest = next(name(f) for f, p in periods.items() if p == period)
        raise TraceFormatError(
            path, f"the files are sampled at different periods: {finest} every {period:g} s, "
            f"{', '.join(odd)}; resample them to one period first"
        )
    start = max(float(t.time[0]) for t in tables.values())
    stop = min(float(t.time[-1]) for t in tables.values())
    if stop <= start:
        raise TraceFormatError(
            path, "the files have no time span in common: "
            + ", ".join(f"{name(f)} {t.time[0]:g}-{t.time[-1]:g} s" for f, t in tables.items())
        )
    tolerance = GRID_TOLERANCE * period
    beyond = []
    for f, t in tables.items():
        ends = ([f"first at {t.time[0]:g} s"] if t.time[0] < start - tolerance else []) + (
            [f"last at {t.time[-1]:g} s"] if t.time[-1] > stop + tolerance else [])
        if ends:
            beyond.append(f"{name(f)} ({', '.join(ends)})")
    if beyond:
        warnings.warn(
            RecordingWarning(
                f"{path}: files {_which_ends(beyond)} at different times; read over the time "
                f"stamps they share, {start:g}-{stop:g} s: "
                f"{', '.join(beyond)}",
                problem="trimmed", signals=tuple(e.signal for e in entries),
            ),
            stacklevel=caller_stacklevel(),
        )
    n_ticks = int(np.floor((stop - start) / period + GRID_TOLERANCE)) + 1
    return _joined(path, cmap, axis, by_file, tables, grids, start, period, n_ticks)


def _which_ends(beyond: Sequence[str]) -> str:
    """"start", "end" or "start and end": which ends of the files differ."""
    starts = any("first at" in b for b in beyond)
    ends = any("last at" in b for b in beyond)
    return "start and end" if starts and ends else "start" if starts else "end"


def _check_names(cmap: ChannelMap, path: Path) -> None:
    """Every ``[channels]`` and ``[units]`` entry names a signal of ``[signals]`` (or the time
    column), and a list of units gives one per column."""
    signals = sorted(cmap.files)
    times = {TIME_ROLE} | {e.time for e in cmap.files.values() if isinstance(e.time, str)}
    for key, unit in cmap.units.items():
        if key in times and not isinstance(unit, str):
            raise ChannelError(
                path, f"channel map {cmap.origin or ''}: the time column {key!r} has one unit, "
                f"not a list: got {list(unit)}"
            )
        entry = cmap.files.get(key)
        if entry is not None and isinstance(unit, tuple) and len(unit) != len(entry.columns):
            raise ChannelError(
                path, f"channel map {cmap.origin or ''}: [units] {key!r} lists {len(unit)} "
                f"units for its {len(entry.columns)} columns; give one per column (axis 1 "
                "first), or one unit for all"
            )
        if key not in cmap.files and key not in times:
            raise ChannelError(
                path, f"channel map {cmap.origin or ''}: unit of {key!r} given, but no signal "
                f"is called so; its signals are {signals}"
            )
    for key, role in cmap.roles.items():
        if key not in cmap.files and DEFAULT_CHANNEL_MAP.roles.get(key) != role:
            raise ChannelError(
                path, f"channel map {cmap.origin or ''}: entry {key!r} = {role!r} names no "
                f"signal of [signals]; its signals are {signals}"
            )


def _joined(
    path: Path,
    cmap: ChannelMap,
    axis: int | None,
    by_file: dict[Path, list[SignalFile]],
    tables: dict[Path, FileTable],
    grids: dict[Path, tuple[float, np.ndarray | None]],
    start: float,
    period: float,
    n_ticks: int,
) -> GridSignals:
    """The entries' columns on the common grid, named and ordered as the module says."""
    n_axes = max(len(e.columns) for e in cmap.files.values())
    if axis is not None and not (n_axes > 1 and 1 <= axis <= n_axes):
        held = f"axes 1-{n_axes}" if n_axes > 1 else "one axis (its signals have one column each)"
        raise ChannelError(path, f"axis {axis} is not in the recording; it holds {held}")
    columns: list[str] = []
    infos: list[SignalInfo] = []
    roles: dict[str, str] = {}
    values: list[np.ndarray] = []
    origin: dict[str, str] = {}
    for file, layouts in by_file.items():
        table = tables[file]
        _, ticks = grids[file]
        # The file's samples on the common grid: tick 0 is `start`.
        rows: slice | None = None
        if ticks is not None:
            offset = int(round((table.time[0] - start) / period))
            ticks = ticks + offset
            inside = (ticks >= 0) & (ticks < n_ticks)
            # every tick of the span present once, in order: the rows are a slice
            first = int(np.argmax(inside)) if inside.any() else 0
            if (inside.sum() == n_ticks and ticks[first] == 0
                    and ticks[first + n_ticks - 1] == n_ticks - 1):
                rows = slice(first, first + n_ticks)
        for layout in layouts:
            role = cmap.role_of(layout.signal)
            base = role or layout.signal
            picked: list[tuple[int | None, int | str]]
            if len(layout.columns) == 1:
                picked = [(None, layout.columns[0])]
            elif axis is not None:
                picked = [(axis, layout.columns[axis - 1])] if axis <= len(layout.columns) else []
            else:
                picked = list(enumerate(layout.columns, start=1))
            for number, column in picked:
                name = base if number is None or axis is not None else qualified(number, base)
                source = f"{layout.signal}" if number is None else f"{layout.signal}(axis {number})"
                if name in origin:
                    raise ChannelError(
                        path, f"{'role ' + name if role else repr(name)} is given by two "
                        f"signals: {origin[name]!r} and {source!r}"
                    )
                origin[name] = source
                raw = table.columns[column]
                if ticks is None:  # off its grid, interpolated onto the common one
                    grid_time = start + np.arange(n_ticks) * period
                    on = np.interp(grid_time, table.time, raw, left=np.nan, right=np.nan)
                elif rows is not None:
                    on = raw[rows]
                else:
                    on = np.full(n_ticks, np.nan)
                    on[ticks[inside]] = raw[inside]
                columns.append(name)
                values.append(on)
                infos.append(SignalInfo(source, None, None, period,
                                        cmap.unit(layout.signal, number)))
                if role:
                    roles[name] = source
    order = sorted(range(len(columns)), key=lambda j: split_qualified(columns[j])[0] or 0)
    clock = _first_clock(tables)
    return GridSignals(
        signals=tuple(infos[j] for j in order),
        values=np.column_stack([values[j] for j in order]),
        sample_period=period,
        t0=float(np.round(start, 9)),
        axis=axis,
        columns=tuple(columns[j] for j in order),
        roles=roles,
        start_time=clock.start_time if clock else None,
        time_origin=clock.origin if clock else 0.0,
        time_unit=None if clock is None or clock.unit == "s" else clock.unit,
    )


def _first_clock(tables: dict[Path, FileTable]) -> Clock | None:
    """The clock the recording's time is read from: the earliest absolute one, else any."""
    clocks = [t.clock for t in tables.values() if t.clock is not None]
    return min(clocks, key=lambda c: (c.origin == 0.0, c.origin)) if clocks else None
