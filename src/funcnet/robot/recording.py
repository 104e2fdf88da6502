"""A recording of one robot axis: signals on a uniform time grid, with their metadata.

:func:`read_trace` reads SINUMERIK trace XML (:mod:`funcnet.robot.sinumerik`), CSV and Parquet
into a :class:`Recording`; :meth:`Recording.to_parquet` and :meth:`Recording.from_parquet` store
it without loss, metadata included.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from funcnet._io import atomic_path
from funcnet.errors import ChannelError, ParameterError, TraceError, TraceFormatError, WindowError
from funcnet.robot.channels import (
    ChannelMap,
    SignalInfo,
    channel_map,
    check_entries,
    parse_signal_name,
    select_axis,
)
from funcnet.robot.sinumerik import read_sinumerik

if TYPE_CHECKING:
    import pyarrow as pa

__all__ = ["Recording", "read_trace", "SignalInfo"]

_PARQUET_KEY = b"funcnet.recording"
_PARQUET_FORMAT = "funcnet.recording/1"
# Relative tolerance, in ticks, for times that should lie on the grid.
_GRID_TOLERANCE = 1e-3


def _time_index(n_ticks: int, sample_period: float, t0: float = 0.0) -> pd.Index:
    # Rounded to the nanosecond so that tick k is the decimal k * period a trace writes.
    return pd.Index(np.round(t0 + np.arange(n_ticks) * sample_period, 9), name="time")


@dataclass(frozen=True, eq=False, repr=False)
class Recording:
    """Signals of one axis on a uniform grid, with where they came from.

    Attributes
    ----------
    data : DataFrame
        One column per signal, float64; the index, named ``time``, is float64 seconds from the
        start of the first data frame on a uniform grid of ``sample_period``, every tick present.
        A value is the last one recorded at or before its tick (never interpolated or shifted);
        NaN before a signal's first record and between data frames.
    roles : dict
        Column name -> the controller's signal name, for the columns the channel map gave a role
        (``RP``, ``AP``, ``MP``, ``RC``, ``AC``).
    signals : dict
        Column name -> :class:`SignalInfo` (controller name, ``unitsType``, data type, native
        interval), for every column, in column order.
    source : str or None
        The file read.
    start_time : str or None
        The first data frame's ``startTime`` (ISO 8601, as the controller wrote it).
    sample_period : float
        The grid interval in seconds (the finest native interval; 0.002 on a SINUMERIK servo).
    axis : int or None
        The axis read.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> data = pd.DataFrame({"RP": np.arange(5.0)},
    ...                     index=pd.Index(np.arange(5) * 0.002, name="time"))
    >>> rec = Recording(data, roles={}, signals={"RP": SignalInfo("RP", "posn", None, 0.002)},
    ...                 sample_period=0.002)
    >>> rec.window(0.002, 0.006).data["RP"].tolist()
    [1.0, 2.0]
    >>> rec.duration
    0.01
    >>> rec
    Recording(source=None, duration=0.01 s, sample_period=0.002 s, axis=None, columns=[RP])
    """

    data: pd.DataFrame
    roles: dict[str, str]
    signals: dict[str, SignalInfo]
    source: str | None = None
    start_time: str | None = None
    sample_period: float = 0.002
    axis: int | None = None

    def __post_init__(self) -> None:
        index = self.data.index
        if index.name != "time" or index.dtype != np.float64:
            raise ParameterError("data: the index must be float64 seconds named 'time'")
        if list(self.data.columns) != list(self.signals):
            raise ParameterError("signals: one SignalInfo per column of data, in column order")
        if not set(self.roles) <= set(self.data.columns):
            raise ParameterError(
                f"roles: {sorted(set(self.roles) - set(self.data.columns))} are not columns"
            )
        if not (self.sample_period > 0 and math.isfinite(self.sample_period)):
            raise ParameterError(f"sample_period: must be > 0, got {self.sample_period}")

    def __repr__(self) -> str:
        # Short: the data and the signal metadata are a table and a dict away.
        columns = ", ".join(
            f"{column} ({parse_signal_name(self.roles[column]).base})"
            if column in self.roles
            else column
            for column in self.data.columns
        )
        return (
            f"Recording(source={self.source!r}, duration={self.duration:g} s, "
            f"sample_period={self.sample_period:g} s, axis={self.axis}, columns=[{columns}])"
        )

    @property
    def duration(self) -> float:
        """The time the grid covers, in seconds: number of ticks times the sample period."""
        return round(len(self.data) * self.sample_period, 9)

    def _where(self) -> str:
        return f"{self.source}: " if self.source else ""

    def window(self, start: float, stop: float) -> Recording:
        """Return the ticks with ``start <= time < stop`` (seconds) as a recording.

        Raises
        ------
        WindowError
            The window is empty or reaches outside the recording; the message names the file.
        """
        index = self.data.index
        if len(index) == 0:
            raise WindowError(f"{self._where()}the recording is empty")
        t0 = float(index[0])
        end = t0 + self.duration
        tolerance = _GRID_TOLERANCE * self.sample_period
        if not (start < stop) or start < t0 - tolerance or stop > end + tolerance:
            raise WindowError(
                f"{self._where()}window [{start:g}, {stop:g}) s is not inside the recording "
                f"[{t0:g}, {end:g}) s"
            )
        first = math.ceil((start - t0) / self.sample_period - _GRID_TOLERANCE)
        last = math.ceil((stop - t0) / self.sample_period - _GRID_TOLERANCE)
        if last <= first:
            raise WindowError(
                f"{self._where()}window [{start:g}, {stop:g}) s holds no tick of the "
                f"{self.sample_period:g} s grid"
            )
        return replace(self, data=self.data.iloc[first:last])

    def to_parquet(self, path: str | os.PathLike[str]) -> Path:
        """Write the recording to a Parquet file (atomically), metadata included.

        The data are stored as they are (float64, NaN kept), the metadata as JSON in the file's
        schema metadata under ``funcnet.recording``; :meth:`from_parquet` restores both exactly.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.Table.from_pandas(self.data, preserve_index=True)
        metadata = {
            "format": _PARQUET_FORMAT,
            "roles": self.roles,
            "signals": {column: asdict(info) for column, info in self.signals.items()},
            "source": self.source,
            "start_time": self.start_time,
            "sample_period": self.sample_period,
            "axis": self.axis,
        }
        schema_metadata = {**(table.schema.metadata or {}), _PARQUET_KEY: json.dumps(metadata)}
        table = table.replace_schema_metadata(schema_metadata)
        with atomic_path(path) as tmp:
            pq.write_table(table, tmp)
        return Path(path)

    @classmethod
    def from_parquet(cls, path: str | os.PathLike[str]) -> Recording:
        """Read a recording written by :meth:`to_parquet`.

        Raises
        ------
        TraceFormatError
            Not a Parquet file, or one without recording metadata.
        """
        table = _read_parquet_table(path)
        raw = (table.schema.metadata or {}).get(_PARQUET_KEY)
        if raw is None:
            raise TraceFormatError(path, "a Parquet file without funcnet recording metadata")
        try:
            meta = json.loads(raw)
            if meta.get("format") != _PARQUET_FORMAT:
                raise ValueError(f"unknown format {meta.get('format')!r}")
            signals = {column: SignalInfo(**info) for column, info in meta["signals"].items()}
            data = table.to_pandas()
            return cls(
                data=data,
                roles=dict(meta["roles"]),
                signals=signals,
                source=meta["source"],
                start_time=meta["start_time"],
                sample_period=float(meta["sample_period"]),
                axis=meta["axis"],
            )
        except (ValueError, KeyError, TypeError) as exc:
            raise TraceFormatError(path, f"recording metadata is unusable: {exc}") from exc


def _read_parquet_table(path: str | os.PathLike[str]) -> pa.Table:
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:
        return pq.read_table(path)
    except (pa.ArrowException, ValueError) as exc:
        raise TraceFormatError(path, f"not a readable Parquet file: {exc}") from exc


def _assemble(
    path: Path,
    infos: Sequence[SignalInfo],
    values: np.ndarray,
    *,
    cmap: ChannelMap,
    sample_period: float,
    start_time: str | None,
    axis: int | None,
    t0: float = 0.0,
) -> Recording:
    """Name the columns by role (else by base name) and wrap everything in a Recording."""
    check_entries(cmap, (info.name for info in infos), path)
    columns: list[str] = []
    roles: dict[str, str] = {}
    origin: dict[str, str] = {}
    known_roles = set(cmap.roles.values())
    for info in infos:
        role = cmap.role_of(info.name)
        column = role or cmap.column_of(info.name)
        if column in origin:
            what = f"role {column}" if role else f"column {column!r}"
            raise ChannelError(
                path, f"{what} is given by two signals: {origin[column]!r} and {info.name!r}"
            )
        origin[column] = info.name
        columns.append(column)
        if role or column in known_roles:
            roles[column] = info.name
    data = pd.DataFrame(
        values, index=_time_index(len(values), sample_period, t0), columns=columns, copy=False
    )
    return Recording(
        data=data,
        roles=roles,
        signals=dict(zip(columns, infos, strict=True)),
        source=str(path),
        start_time=start_time,
        sample_period=sample_period,
        axis=axis,
    )


def _from_table(
    path: Path, table: pd.DataFrame, cmap: ChannelMap, axis: int | None, *, line_offset: int
) -> Recording:
    """A table with a ``time`` column (CSV, plain Parquet) -> Recording.

    ``line_offset`` turns a row position into a line of the file (2 for a CSV with a header);
    0 for Parquet, which has no lines: errors then name the row.
    """

    def where(row: int) -> str:
        return f"line {row + line_offset}" if line_offset else f"row {row}"

    names = [str(c) for c in table.columns]
    time_columns = [c for c in names if c.strip().lower() == "time"]
    if len(time_columns) != 1:
        raise TraceFormatError(path, f"needs exactly one 'time' column; it has {names}")
    time_name = time_columns[0]
    if len(table) == 0:
        raise TraceFormatError(path, "has no rows")
    numeric: dict[str, np.ndarray] = {}
    for name in names:
        column = table[name]
        converted = pd.to_numeric(column, errors="coerce").to_numpy(dtype=np.float64)
        bad = ~np.isfinite(converted)
        if name != time_name:  # empty before a signal's first value: not recorded yet (NaN),
            # as the XML reader leaves it, so that a CSV written from rec.data reads back
            empty = (column.isna() | column.astype(str).str.strip().eq("")).to_numpy()
            bad &= ~np.cumprod(empty).astype(bool)
        if bad.any():
            row = int(np.argmax(bad))
            raise TraceFormatError(
                path, f"{where(row)}: column {name!r} holds {column.iloc[row]!r}, not a number"
            )
        numeric[name] = converted
    time = numeric.pop(time_name)
    steps = np.diff(time)
    if (steps <= 0).any():
        row = int(np.argmax(steps <= 0)) + 1
        raise TraceFormatError(path, f"{where(row)}: time {float(time[row])!r} does not increase")
    if len(time) < 2:
        raise TraceFormatError(path, "needs at least two rows to know its sample period")
    period = float(np.round(steps.min(), 9))
    position = (time - time[0]) / period
    ticks = np.round(position).astype(np.int64)
    off = np.abs(position - ticks) > _GRID_TOLERANCE
    if off.any():
        row = int(np.argmax(off))
        raise TraceFormatError(
            path, f"{where(row)}: time {float(time[row])!r} is not on the {period:g} s grid"
        )
    signal_names = list(numeric)
    keep, axis = select_axis(signal_names, axis, path)
    signal_names = [name for name, kept in zip(signal_names, keep, strict=True) if kept]
    if not signal_names:
        raise TraceFormatError(path, "has a time column but no signal column")
    # Rows left out of the file (a sparse export) carry the previous row forward.
    present = np.zeros(int(ticks[-1]) + 1, dtype=bool)
    present[ticks] = True
    row_of_tick = np.cumsum(present) - 1
    values = np.column_stack([numeric[name][row_of_tick] for name in signal_names])
    infos = [SignalInfo(name, None, None, period) for name in signal_names]
    return _assemble(
        path,
        infos,
        values,
        cmap=cmap,
        sample_period=period,
        start_time=None,
        axis=axis,
        t0=float(np.round(time[0], 9)),
    )


def _read_csv(path: Path, cmap: ChannelMap, axis: int | None) -> Recording:
    try:
        table = pd.read_csv(path, skip_blank_lines=False, dtype=str, keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        if path.stat().st_size == 0:
            raise TraceFormatError(path, "empty file: not a trace") from None
        raise TraceFormatError(path, f"not a readable CSV file: {exc}") from exc
    # Text is converted here, not by pandas, so that 'NaN', '' and 'abc' are all reported
    # with their line.
    return _from_table(path, table, cmap, axis, line_offset=2)


def _read_parquet(path: Path, cmap: ChannelMap, axis: int | None) -> Recording:
    table = _read_parquet_table(path)
    if _PARQUET_KEY in (table.schema.metadata or {}):
        recording = Recording.from_parquet(path)
        check_entries(cmap, (info.name for info in recording.signals.values()), path)
        return recording
    frame = table.to_pandas()
    if frame.index.name is not None:
        frame = frame.reset_index()
    return _from_table(path, frame, cmap, axis, line_offset=0)


def read_trace(
    path: str | os.PathLike[str],
    *,
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
    axis: int | None = None,
) -> Recording:
    """Read a controller trace into a :class:`Recording`.

    Parameters
    ----------
    path : path-like
        ``.xml``: SINUMERIK Solution Line trace (see :mod:`funcnet.robot.sinumerik`).
        ``.csv``: a header row, a ``time`` column in seconds and one column per signal; every
        cell a finite number (a signal's cells may be empty before its first value: NaN
        there); rows on a uniform grid (the smallest time step), rows left out
        carry the previous row's values forward. ``.parquet``/``.pq``: a file written by
        :meth:`Recording.to_parquet` (returned as written), or a table like the CSV.
    channels : ChannelMap, dict, TOML path or None
        Signal name -> role (see :func:`funcnet.robot.channels.channel_map`); None uses the
        SINUMERIK defaults. Columns are named by role, other signals by their base name.
    axis : int, optional
        The axis to read when the trace holds several.

    Returns
    -------
    Recording

    Raises
    ------
    TraceError
        There is no such file (the message names it).
    TraceFormatError
        The file is not a readable trace of its kind; the message has the path, and the line or
        the signal where it helps.
    ChannelError
        A channel is missing, duplicated, or two signals claim one role; several axes and no
        ``axis``; an entry of ``channels`` that is not a default matches no signal of the trace
        (see :func:`funcnet.robot.channels.check_entries`).

    References
    ----------
    Paper section 3.2 (signals RP, AP, MP, RC, AC recorded at 500 Hz) and 3.3 (XML log files).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tiny.csv"
    >>> _ = path.write_text('time,"measPos2 [u1, 1]","aaStat [u1, 1]"\\n'
    ...                     "0.000,1.0,4\\n0.002,1.5,4\\n0.006,2.0,4\\n")
    >>> rec = read_trace(path)
    >>> rec.data
              AP  aaStat
    time
    0.000  1.0     4.0
    0.002  1.5     4.0
    0.004  1.5     4.0
    0.006  2.0     4.0
    >>> rec.roles, rec.axis, rec.sample_period
    ({'AP': 'measPos2 [u1, 1]'}, 1, 0.002)
    """
    path = Path(path)
    cmap = channel_map(channels)
    if path.is_dir():
        raise TraceFormatError(path, "is a directory, not a trace file")
    if not path.exists():  # a FuncnetError naming the file, as every other unreadable trace
        raise TraceError(path, "no such file")
    suffix = path.suffix.lower()
    if suffix == ".xml":
        trace = read_sinumerik(path, axis=axis)
        return _assemble(
            path,
            trace.signals,
            trace.values,
            cmap=cmap,
            sample_period=trace.sample_period,
            start_time=trace.start_time,
            axis=trace.axis,
        )
    if suffix == ".csv":
        return _read_csv(path, cmap, axis)
    if suffix in (".parquet", ".pq"):
        return _read_parquet(path, cmap, axis)
    raise TraceFormatError(path, f"unknown trace format {suffix!r}; use .xml, .csv or .parquet")
