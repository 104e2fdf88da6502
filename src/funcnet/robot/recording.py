"""A recording of robot axes: signals on a uniform time grid, with their metadata.

A :class:`Recording` is what every reader makes of a file (:func:`funcnet.robot.read_trace`,
:mod:`funcnet.robot.io`): a table of signals on one time grid, each column's
:class:`~funcnet.robot.SignalInfo`, the roles, the gaps (the stretches with missing values) and
the axes. :meth:`Recording.to_parquet` and :meth:`Recording.from_parquet` store it without
loss, metadata included.
"""
from __future__ import annotations

import json
import math
import os
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from funcnet._io import atomic_path
from funcnet.errors import ParameterError, TraceFormatError, WindowError
from funcnet.robot.axes import axes_of, split_qualified
from funcnet.robot.grid import find_gaps, segments_between
from funcnet.robot.signals import SignalInfo, parse_signal_name

if TYPE_CHECKING:
    import pyarrow as pa

__all__ = ["Recording", "SignalInfo"]

#: The key of a Parquet file's metadata under which :meth:`Recording.to_parquet` stores its own.
PARQUET_KEY = b"funcnet.recording"
_PARQUET_FORMAT = "funcnet.recording/1"
# Relative tolerance, in ticks, for times that should lie on the grid.
_GRID_TOLERANCE = 1e-3


def time_index(n_ticks: int, sample_period: float, t0: float = 0.0) -> pd.Index:
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
        recording's start (:mod:`funcnet.robot.io.clock`).
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
        first, last = self.rows(start, stop)
        return replace(self, data=self.data.iloc[first:last])

    def rows(self, start: float, stop: float) -> tuple[int, int]:
        """The rows ``first, last`` of :meth:`window` (``data.iloc[first:last]``), without
        building the recording: many windows' rows cost no table each.

        Raises
        ------
        WindowError
            As :meth:`window`.

        Examples
        --------
        >>> import numpy as np, pandas as pd
        >>> data = pd.DataFrame({"RP": np.arange(5.0)},
        ...                     index=pd.Index(np.arange(5) * 0.5, name="time"))
        >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.5)},
        ...                 sample_period=0.5)
        >>> rec.rows(0.5, 1.5)
        (1, 3)
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
        return first, last

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
        schema_metadata = {**(table.schema.metadata or {}), PARQUET_KEY: json.dumps(metadata)}
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
        table = read_parquet_table(path)
        raw = (table.schema.metadata or {}).get(PARQUET_KEY)
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


def read_parquet_table(path: str | os.PathLike[str]) -> pa.Table:
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:  # ParquetFile rather than read_table: it keeps a column name given twice, to be said
        return pq.ParquetFile(path).read()
    except (pa.ArrowException, ValueError, OSError) as exc:
        raise TraceFormatError(path, f"not a readable Parquet file: {exc}") from exc
