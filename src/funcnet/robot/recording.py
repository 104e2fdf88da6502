"""A recording of robot axes: signals on a uniform time grid, with their metadata.

:func:`read_trace` reads SINUMERIK trace XML (:mod:`funcnet.robot.sinumerik`), CSV and Parquet
tables (:mod:`funcnet.robot.tables`), MATLAB and HDF5 files (:mod:`funcnet.robot.arrays`) into a
:class:`Recording`; :meth:`Recording.to_parquet` and :meth:`Recording.from_parquet` store it
without loss, metadata included. Whatever the format, a channel constant over the whole
recording is left out and the stretches with missing values are the recording's gaps, each said
in one :class:`~funcnet.RecordingWarning`.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from funcnet._io import atomic_path
from funcnet.errors import (
    ChannelError,
    ParameterError,
    RecordingWarning,
    TraceError,
    TraceFormatError,
    WindowError,
)
from funcnet.robot.arrays import ARRAY_SUFFIXES, read_array_file
from funcnet.robot.axes import axes_of, split_qualified
from funcnet.robot.channels import (
    ROLES,
    ChannelMap,
    SignalInfo,
    channel_map,
    check_entries,
    parse_signal_name,
)
from funcnet.robot.files import read_signal_files
from funcnet.robot.grid import (
    OFF_GRID,
    GridSignals,
    find_gaps,
    format_spans,
    segments_between,
    segments_phrase,
)
from funcnet.robot.rosbag import is_bag, read_bag
from funcnet.robot.sinumerik import read_sinumerik
from funcnet.robot.tables import read_csv_table, table_signals

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
        The axis read; None for a recording of several axes, whose columns are qualified by
        their axis (``A1.RP``, ``A2.MP``: :mod:`funcnet.robot.axes`).
    gaps : tuple of (float, float)
        The spans ``[start, stop)`` in seconds where a signal has no value after its first one
        (missing values in the file): they split the recording into :attr:`segments`, and no
        window spans one.
    time_origin : float
        Where the file's own clock stood at the recording's time 0, in seconds (controller
        uptime, Unix time; 0.0 for a log that starts at 0): the file's time is read from the
        recording's start (:mod:`funcnet.robot.clock`).
    time_unit : str or None
        The unit the file's time column was read in (``"us"``, ``"ISO 8601"``); None for
        seconds.

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
    gaps: tuple[tuple[float, float], ...] = ()
    time_origin: float = 0.0
    time_unit: str | None = None

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
        segments = f", segments={len(self.segments)}" if self.gaps else ""
        return (
            f"Recording(source={self.source!r}, duration={self.duration:g} s, "
            f"sample_period={self.sample_period:g} s, axis={self.axis}{segments}, "
            f"columns=[{columns}])"
        )

    @property
    def segments(self) -> list[tuple[float, float]]:
        """The spans ``[start, stop)`` (seconds) of the recording between its :attr:`gaps`.

        Examples
        --------
        >>> import numpy as np, pandas as pd
        >>> data = pd.DataFrame({"RP": np.arange(5.0)},
        ...                     index=pd.Index(np.arange(5) * 0.5, name="time"))
        >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.5)},
        ...                 sample_period=0.5, gaps=((1.0, 1.5),))
        >>> rec.segments
        [(0.0, 1.0), (1.5, 2.5)]
        """
        if len(self.data.index) == 0:
            return []
        t0 = float(self.data.index[0])
        return segments_between(self.gaps, t0, round(t0 + self.duration, 9))

    @property
    def axes(self) -> tuple[int, ...]:
        """The axes of a multi-axis recording (its columns ``A<n>.<name>``); () for one axis."""
        return axes_of(self.data.columns)

    def for_axis(self, axis: int) -> Recording:
        """One axis of a multi-axis recording, its columns named without the axis (``RP``).

        Signals common to every axis (columns not qualified by an axis) are kept; the gaps are
        those of the columns kept.

        Raises
        ------
        ParameterError
            ``axis`` is not one of :attr:`axes`.

        Examples
        --------
        >>> import numpy as np, pandas as pd
        >>> data = pd.DataFrame({"A1.RP": [0.0, 1.0], "A2.RP": [2.0, 3.0]},
        ...                     index=pd.Index([0.0, 0.004], name="time"))
        >>> info = SignalInfo("ref", None, None, 0.004)
        >>> rec = Recording(data, {"A1.RP": "ref(axis 1)", "A2.RP": "ref(axis 2)"},
        ...                 {"A1.RP": info, "A2.RP": info}, sample_period=0.004)
        >>> rec.axes, rec.for_axis(2).data["RP"].tolist(), rec.for_axis(2).roles
        ((1, 2), [2.0, 3.0], {'RP': 'ref(axis 2)'})
        """
        if axis not in self.axes:
            raise ParameterError.of("axis", f"must be one of {list(self.axes)}, got {axis!r}")
        names: dict[str, str] = {}
        for column in self.data.columns:
            owner, name = split_qualified(column)
            if owner in (None, axis) and name not in names.values():
                names[column] = name
        data = self.data[list(names)].set_axis(list(names.values()), axis=1)
        ticks, _ = find_gaps(data.to_numpy(dtype=np.float64))
        index = data.index
        gaps = tuple(
            (float(index[a]), round(float(index[b - 1]) + self.sample_period, 9))
            for a, b in ticks
        )
        return replace(
            self,
            data=data,
            roles={names[c]: name for c, name in self.roles.items() if c in names},
            signals={names[c]: info for c, info in self.signals.items() if c in names},
            axis=axis,
            gaps=gaps,
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
        for gap_start, gap_stop in self.gaps:
            if gap_start < stop and gap_stop > start:
                spans = ", ".join(f"[{a:g}, {b:g})" for a, b in self.segments)
                raise WindowError(
                    f"{self._where()}window [{start:g}, {stop:g}) s spans the gap "
                    f"[{gap_start:g}, {gap_stop:g}) s where values are missing; a window lies "
                    f"within one segment: {spans} s"
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
            "gaps": [list(gap) for gap in self.gaps],
            "time_origin": self.time_origin,
            "time_unit": self.time_unit,
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
                gaps=tuple((float(a), float(b)) for a, b in meta.get("gaps", [])),
                time_origin=float(meta.get("time_origin", 0.0)),
                time_unit=meta.get("time_unit"),
            )
        except (ValueError, KeyError, TypeError) as exc:
            raise TraceFormatError(path, f"recording metadata is unusable: {exc}") from exc


def _read_parquet_table(path: str | os.PathLike[str]) -> pa.Table:
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:  # ParquetFile rather than read_table: it keeps a column name given twice, to be said
        return pq.ParquetFile(path).read()
    except (pa.ArrowException, ValueError, OSError) as exc:
        raise TraceFormatError(path, f"not a readable Parquet file: {exc}") from exc


def _named_columns(path: Path, grid: GridSignals, cmap: ChannelMap) -> tuple[list[str], dict]:
    """Column names (by role, else by base name) and roles of a reader's signals."""
    if grid.columns is not None:
        return list(grid.columns), dict(grid.roles or {})
    check_entries(cmap, (info.name for info in grid.signals), path)
    columns: list[str] = []
    roles: dict[str, str] = {}
    origin: dict[str, str] = {}
    known_roles = set(cmap.roles.values())
    for info in grid.signals:
        role = cmap.role_of(info.name)
        column = role or cmap.column_of(info.name)
        if column in origin:
            what = f"role {column}" if role else f"column {column!r}"
            raise ChannelError(
                path, f"{what} is given by two signals: {origin[column]!r} and {info.name!r}"
            )
        origin[column] = info.name
        columns.append(column)
        # A column named A<n>.<role> (a multi-axis recording written out) keeps its role.
        if role or column in known_roles or split_qualified(column)[1] in ROLES:
            roles[column] = info.name
    return columns, roles


def _listed(names: Sequence[str], limit: int = 8) -> str:
    shown = ", ".join(names[:limit])
    return shown + (f" and {len(names) - limit} more" if len(names) > limit else "")


def _assemble(
    path: Path, grid: GridSignals, cmap: ChannelMap, keep_setpoint: bool = False
) -> Recording:
    """A reader's signals -> a Recording: constant channels left out, gaps found; both said."""
    columns, roles = _named_columns(path, grid, cmap)
    values = grid.values
    infos = list(grid.signals)
    # fmin/fmax skip NaN without copying the table; a column without any value compares False.
    low, high = np.fmin.reduce(values, axis=0), np.fmax.reduce(values, axis=0)
    # One tick says nothing about constancy.
    constant = ~(high > low) if len(values) > 1 else np.zeros(len(columns), dtype=bool)
    if keep_setpoint:  # a set-point that never moves says the axis rests: a page reports it
        constant &= np.array([split_qualified(c)[1] != "RP" for c in columns], dtype=bool)
    if constant.all():
        raise TraceFormatError(
            path, f"every signal is constant over the whole recording ({_listed(columns)})"
        )
    if constant.any():
        dropped = [c for c, flat in zip(columns, constant, strict=True) if flat]
        detail = [
            f"{c} = {low[j]:g}" if np.isfinite(low[j]) else f"{c} (no value)"
            for j, c in enumerate(columns) if constant[j]
        ]
        warnings.warn(
            RecordingWarning(
                f"{path}: constant over the whole recording, left out: {_listed(detail, 12)}",
                problem="constant", signals=tuple(dropped),
            ),
            stacklevel=3,
        )
        keep = np.flatnonzero(~constant)
        values = values[:, keep]
        columns = [columns[j] for j in keep]
        infos = [infos[j] for j in keep]
        roles = {c: name for c, name in roles.items() if c in columns}
    index = _time_index(len(values), grid.sample_period, grid.t0)
    ticks, missing = find_gaps(values)
    gaps = tuple(_gap_span(index, grid.sample_period, a, b) for a, b in ticks)
    data = pd.DataFrame(values, index=index, columns=columns, copy=False)
    recording = Recording(
        data=data,
        roles=roles,
        signals=dict(zip(columns, infos, strict=True)),
        source=str(path),
        start_time=grid.start_time,
        sample_period=grid.sample_period,
        axis=grid.axis,
        gaps=gaps,
        time_origin=grid.time_origin,
        time_unit=grid.time_unit,
    )
    if gaps:
        where = [
            f"{format_spans([(a, b)])} ({_listed([columns[j] for j in which], 4)})"
            for (a, b), which in zip(gaps, missing, strict=True)
        ]
        warnings.warn(
            RecordingWarning(
                f"{path}: missing values at {_listed(where, 4)}: the recording is split into "
                f"{segments_phrase(recording.segments)} and no window spans a gap",
                problem="gap",
                signals=tuple(dict.fromkeys(columns[j] for which in missing for j in which)),
            ),
            stacklevel=3,
        )
    return recording


def _gap_span(index: pd.Index, period: float, first: int, stop: int) -> tuple[float, float]:
    """Ticks ``[first, stop)`` as seconds ``[start, end)``."""
    return float(index[first]), float(round(float(index[stop - 1]) + period, 9))


def read_trace(
    path: str | os.PathLike[str],
    *,
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
    axis: int | None = None,
    off_grid: str = "error",
    keep_setpoint: bool = False,
) -> Recording:
    """Read a controller trace into a :class:`Recording`.

    Parameters
    ----------
    path : path-like
        ``.xml``: SINUMERIK Solution Line trace (see :mod:`funcnet.robot.sinumerik`).
        ``.csv``: a header row, a ``time`` column in seconds and one column per signal
        (:mod:`funcnet.robot.tables`). ``.parquet``/``.pq``: a file written by
        :meth:`Recording.to_parquet` (returned as written), or a table like the CSV.
        ``.mat`` (MAT 5 or MAT 7.3), ``.h5``/``.hdf5``: signals as named arrays beside a time
        array (:mod:`funcnet.robot.arrays`). A ROS bag (its folder, or a ``.mcap``, ``.db3``
        or ``.bag`` file) through a channel map with a ``[bag]`` table
        (:mod:`funcnet.robot.rosbag`).
    channels : ChannelMap, dict, TOML path or None
        Signal name -> role (see :func:`funcnet.robot.channels.channel_map`); None uses the
        SINUMERIK defaults. Columns are named by role, other signals by their base name.
    axis : int, optional
        The axis to read when the trace holds several (1-based). A MATLAB or HDF5 file with one
        row per axis read without it is one recording of every axis, its columns qualified
        by axis (``A1.RP``; :mod:`funcnet.robot.axes`).
    off_grid : {"error", "interpolate"}
        Time stamps of a table or array file off the grid of their smallest step: an error
        (which offers this), or every signal interpolated linearly onto a grid of the median
        step (:func:`funcnet.robot.grid.time_grid`).
    keep_setpoint : bool
        Keep a set-point RP (``A<n>.RP``) that is constant over the whole recording, as the
        page of an axis at rest needs it; by default it is left out as any constant channel.

    Returns
    -------
    Recording
        A channel constant over the whole recording (an encoder not fitted reads all zeros) is
        left out; missing values after a signal's first one are the recording's ``gaps``. Each
        is said by one :class:`~funcnet.RecordingWarning`.

    Raises
    ------
    TraceError
        There is no such file (the message names it).
    TraceFormatError
        The file is not a readable trace of its kind; text where a number belongs; time that is
        not a number, does not increase, or is off its grid; every signal constant. The message
        has the path, and the line (sample) or the signal where it helps.
    ChannelError
        A channel is missing, duplicated, or two signals claim one role; several axes and no
        ``axis`` (SINUMERIK, tables); an entry of ``channels`` that is not a default matches no
        signal of the trace (see :func:`funcnet.robot.channels.check_entries`).
    ParameterError
        ``off_grid`` is not one of its values.

    References
    ----------
    Paper section 3.2 (signals RP, AP, MP, RC, AC recorded at 500 Hz) and 3.3 (XML log files).

    Examples
    --------
    >>> import pathlib, tempfile, warnings
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tiny.csv"
    >>> _ = path.write_text('time,"measPos2 [u1, 1]","aaStat [u1, 1]","aaTyp [u1, 1]"\\n'
    ...                     "0.000,1.0,4,0\\n0.002,1.5,5,0\\n0.006,2.0,4,0\\n")
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     rec = read_trace(path)
    >>> print(caught[0].message)
    /.../tiny.csv: constant over the whole recording, left out: aaTyp = 0
    >>> rec.data
              AP  aaStat
    time
    0.000  1.0     4.0
    0.002  1.5     5.0
    0.004  1.5     5.0
    0.006  2.0     4.0
    >>> rec.roles, rec.axis, rec.sample_period
    ({'AP': 'measPos2 [u1, 1]'}, 1, 0.002)
    """
    path = Path(path)
    cmap = channel_map(channels)
    if off_grid not in OFF_GRID:
        raise ParameterError.of("off_grid", f"must be one of {', '.join(OFF_GRID)}; "
                                f"got {off_grid!r}")
    if cmap.bag is not None or is_bag(path):
        return _assemble(path, read_bag(path, cmap, axis, off_grid=off_grid), cmap, keep_setpoint)
    if cmap.files and path.exists():
        grid = read_signal_files(path, cmap, axis, off_grid=off_grid)
        return _assemble(path, grid, cmap, keep_setpoint)
    if path.is_dir():
        raise TraceFormatError(
            path, "is a directory, not a trace file; a run's folder of one file per signal is "
            "read through a channel map whose [signals] table names the files"
        )
    if not path.exists():  # a FuncnetError naming the file, as every other unreadable trace
        raise TraceError(path, "no such file")
    suffix = path.suffix.lower()
    if suffix == ".xml":
        trace = read_sinumerik(path, axis=axis)
        grid = GridSignals(
            signals=trace.signals,
            values=trace.values,
            sample_period=trace.sample_period,
            start_time=trace.start_time,
            axis=trace.axis,
        )
    elif suffix == ".csv":
        if path.stat().st_size == 0:
            raise TraceFormatError(path, "empty file: not a trace")
        grid = read_csv_table(path, cmap, axis, off_grid=off_grid)
    elif suffix in (".parquet", ".pq"):
        table = _read_parquet_table(path)
        if _PARQUET_KEY in (table.schema.metadata or {}):
            recording = Recording.from_parquet(path)
            check_entries(cmap, (info.name for info in recording.signals.values()), path)
            return recording
        frame = table.to_pandas()
        if frame.index.name is not None:
            frame = frame.reset_index()
        grid = table_signals(path, frame, cmap, axis, line_offset=0, off_grid=off_grid)
    elif suffix in ARRAY_SUFFIXES:
        grid = read_array_file(path, cmap, axis, off_grid=off_grid)
    else:
        raise TraceFormatError(
            path, f"unknown trace format {suffix!r}; use .xml, .csv, .parquet, "
            f"{', '.join(ARRAY_SUFFIXES)}"
        )
    return _assemble(path, grid, cmap, keep_setpoint)
