"""A trace file into a :class:`~funcnet.robot.Recording`, whatever its format: the entry points.

:func:`read_trace` reads the file as it is: SINUMERIK trace XML
(:mod:`~funcnet.robot.io.sinumerik`), CSV and Parquet tables (:mod:`~funcnet.robot.io.tables`),
MATLAB and HDF5 files (:mod:`~funcnet.robot.io.arrays`), a folder of text files
(:mod:`~funcnet.robot.io.signal_files`) or a ROS bag (:mod:`~funcnet.robot.io.rosbag`).
Whatever the format, a channel constant over the whole recording is left out and the stretches
with missing values are the recording's gaps, each said in one :class:`~funcnet.RecordingWarning`.

:func:`read_recording` is what the analyses read: :func:`read_trace`, angles in degrees
(:func:`funcnet.robot.units.in_axis_units`), then the derived signals a selection of nodes
needs, on one grid (:func:`funcnet.robot.prepare.prepare_recording`) -- the study, the paper's
analyses and the command line all read traces through it.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet.errors import (
    ChannelError,
    ParameterError,
    RecordingWarning,
    TraceError,
    TraceFormatError,
)
from funcnet.robot.axes import split_qualified
from funcnet.robot.grid import (
    OFF_GRID,
    GridSignals,
    find_gaps,
    format_spans,
    segments_phrase,
)
from funcnet.robot.io.arrays import ARRAY_SUFFIXES, read_array_file
from funcnet.robot.io.channels import ChannelMap, channel_map, check_entries
from funcnet.robot.io.rosbag import is_bag, read_bag
from funcnet.robot.io.signal_files import read_signal_files
from funcnet.robot.io.sinumerik import read_sinumerik
from funcnet.robot.io.tables import read_csv_table, table_signals
from funcnet.robot.prepare import check_resample, prepare_recording
from funcnet.robot.recording import PARQUET_KEY, Recording, read_parquet_table, time_index
from funcnet.robot.signals import ROLES
from funcnet.robot.units import in_axis_units

__all__ = ["read_trace", "read_recording"]


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
    index = time_index(len(values), grid.sample_period, grid.t0)
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
        ``.xml``: SINUMERIK Solution Line trace (see :mod:`funcnet.robot.io.sinumerik`).
        ``.csv``: a header row, a ``time`` column in seconds and one column per signal
        (:mod:`funcnet.robot.io.tables`). ``.parquet``/``.pq``: a file written by
        :meth:`Recording.to_parquet` (returned as written), or a table like the CSV.
        ``.mat`` (MAT 5 or MAT 7.3), ``.h5``/``.hdf5``: signals as named arrays beside a time
        array (:mod:`funcnet.robot.io.arrays`). A ROS bag (its folder, or a ``.mcap``, ``.db3``
        or ``.bag`` file) through a channel map with a ``[bag]`` table
        (:mod:`funcnet.robot.io.rosbag`).
    channels : ChannelMap, dict, TOML path or None
        Signal name -> role (see :func:`funcnet.robot.io.channels.channel_map`); None uses the
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
        signal of the trace (see :func:`funcnet.robot.io.channels.check_entries`).
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
        table = read_parquet_table(path)
        if PARQUET_KEY in (table.schema.metadata or {}):
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


def read_recording(
    path: str | os.PathLike[str],
    *,
    signals: Sequence[str] | None = None,
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
    axis: int | None = None,
    resample: str | None = None,
) -> Recording:
    """Read a trace and add the derived signals a selection needs (V by default).

    Parameters
    ----------
    path : path-like
        Trace file: SINUMERIK XML, CSV or Parquet (:func:`~funcnet.robot.read_trace`).
    signals : sequence of str, optional
        The nodes that will be used; the derived ones among them (V, FE, TORSION,
        :func:`~funcnet.robot.add_derived_signals`) are computed on the whole recording, before
        any windowing, so that no window loses samples at its ends. Default: V, when the trace
        has AP.
    channels, axis
        Passed to :func:`~funcnet.robot.read_trace`.
    resample : {"decimate", "interpolate"}, optional
        Bring the signals onto one grid without staircases (:func:`~funcnet.robot.resample`
        with its default period); the derived signals are then recomputed from the resampled
        inputs, so that V is the velocity of the decimated or interpolated AP. ``"interpolate"``
        also puts time stamps that are off their grid onto it (``off_grid="interpolate"`` of
        :func:`~funcnet.robot.read_trace`).

    Returns
    -------
    Recording
        Angles stated in rad converted to degrees (:func:`funcnet.robot.units.in_axis_units`,
        said in one warning). With the derived signals as its last columns. In a recording of
        several axes (columns
        ``A1.RP``, ...) a derived signal is named with its axis (``A1.V``) and computed from
        that axis's inputs; none is derived unless named.

    Raises
    ------
    ParameterError
        ``resample`` is not one of :data:`funcnet.robot.prepare.RESAMPLE_METHODS` (checked
        before the file is read),
        or a derived signal is unknown.
    TraceError
        The file cannot be read (see :func:`~funcnet.robot.read_trace`).
    ChannelError
        A derived signal's input is not in the trace.

    References
    ----------
    Paper section 3.3, Eq. 11-12 (V from AP).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "trace.csv"
    >>> _ = path.write_text("time,AP,RP\\n0,0,0\\n0.002,1,1\\n0.004,3,2\\n0.006,6,3\\n")
    >>> read_recording(path).data.columns.tolist()
    ['AP', 'RP', 'V']
    >>> read_recording(path, signals=["RP", "FE"]).data["FE"].tolist()
    [0.0, 0.0, -1.0, -3.0]
    """
    check_resample(resample)
    off_grid = "interpolate" if resample == "interpolate" else "error"
    # A set-point that never moves is kept: where the axis rests is said, not a missing RP.
    recording = read_trace(path, channels=channels, axis=axis, off_grid=off_grid,
                           keep_setpoint=True)
    # Phases and thresholds are in degrees: angles in rad converted, each said.
    recording, _ = in_axis_units(recording)
    return prepare_recording(recording, signals=signals, resample=resample)
