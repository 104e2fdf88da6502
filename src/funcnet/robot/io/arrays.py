"""Recordings stored as named arrays: MATLAB files (MAT 5, MAT 7.3) and HDF5 files.

Such a file holds variables -- a MATLAB struct's fields, an HDF5 file's datasets -- named by
their path: ``rec.ref_pos_deg`` (MATLAB, fields joined by ``.``), ``/rec/ref_pos`` (HDF5). MAT 5
is read with :func:`scipy.io.loadmat`; MAT 7.3 is HDF5 underneath and read with h5py, as are
``.h5``/``.hdf5`` files. How the variables become signals:

- **Time** is the variable the channel map gives the role ``time`` (``"rec.time_cont" =
  "time"``), else the one variable called ``time`` (in any case, on any path); seconds (or
  the unit ``[units]`` states for it: :mod:`funcnet.robot.io.clock`), read from the first stamp,
  increasing, on a uniform grid of any period (:func:`funcnet.robot.grid.time_grid`).
- **Signals** are the numeric variables beside the time (in the same struct or group), and any
  variable the channel map names, anywhere in the file, that have one sample per time stamp. A
  variable with several rows of samples (shape ``(axes, N)``, or ``(N, axes)`` as MATLAB 7.3
  stores it) is a **multi-axis** signal: row ``n`` is axis ``n`` (1-based). Variables of another
  length (parameters, results) are not signals and are not read, unless the map names them: then
  it is an error.
- **One axis or all.** With ``axis=n`` every multi-axis signal gives its row ``n`` and the
  columns are named as for a one-axis trace (``RP``, ``act_vel_mot_deg_per_s``). Without it, a
  file of several axes is one recording whose columns are ``A1.RP``, ``A2.RP``, ...
  (:mod:`funcnet.robot.axes`); a signal of one row is common to all and keeps its bare name.
- A column is named by its role, else by its variable's last name; two variables of one last
  name are named by their whole paths instead.
- A missing value (NaN) or a time stamp the file leaves out is a gap; an infinite value is an
  error naming the variable and the sample.
- **Units**: HDF5's ``units`` (or ``unit``) attribute, else the channel map's ``[units]``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from funcnet.errors import ChannelError, TraceFormatError
from funcnet.robot.axes import qualified, split_qualified
from funcnet.robot.grid import GridSignals, place_on_grid, time_grid
from funcnet.robot.io.channels import TIME_ROLE, ChannelMap, field_keys, resolve_fields
from funcnet.robot.io.clock import Clock, clock_seconds
from funcnet.robot.signals import SignalInfo

__all__ = ["ARRAY_SUFFIXES", "read_array_file", "StoredArray"]

#: File suffixes read as arrays: MATLAB (MAT 5 or 7.3) and HDF5.
ARRAY_SUFFIXES = (".mat", ".h5", ".hdf5")


@dataclass(frozen=True)
class StoredArray:
    """A numeric variable of a file, as stored.

    Attributes
    ----------
    name : str
        Its path (``rec.ref_pos_deg``, ``/rec/ref_pos``).
    parent : str
        The path of the struct or group that holds it (``rec``, ``/rec``; ``""`` at the top of a
        MATLAB file).
    values : ndarray
        As stored (any numeric dtype and shape).
    unit : str or None
        As the file states it.
    """

    name: str
    parent: str
    values: np.ndarray
    unit: str | None = None


def _numeric(values: Any) -> bool:
    return isinstance(values, np.ndarray) and values.dtype.kind in "fiub" and values.size > 1


def _mat5_arrays(path: Path) -> list[StoredArray]:
    """Every numeric array of a MAT 5 file, walking its structs."""
    import scipy.io

    try:
        content = scipy.io.loadmat(
            path, squeeze_me=True, struct_as_record=False, chars_as_strings=True
        )
    except (ValueError, TypeError, NotImplementedError, OSError, EOFError,
            scipy.io.matlab.MatReadError) as exc:
        raise TraceFormatError(path, f"not a readable MATLAB file: {exc}") from exc
    found: list[StoredArray] = []

    def walk(items: list[tuple[str, Any]], parent: str) -> None:
        for key, value in items:
            name = f"{parent}.{key}" if parent else key
            if isinstance(value, scipy.io.matlab.mat_struct):
                walk([(f, getattr(value, f)) for f in value._fieldnames], name)
            elif _numeric(value):
                found.append(StoredArray(name, parent, value))

    walk([(k, v) for k, v in content.items() if not k.startswith("__")], "")
    return found


def _text(value: Any) -> str | None:
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return _text(value.item())
    return value if isinstance(value, str) else None


def _hdf5_arrays(path: Path, *, matlab: bool) -> list[StoredArray]:
    """Every numeric dataset of an HDF5 file (MATLAB 7.3: struct fields joined by ``.``)."""
    import h5py

    found: list[StoredArray] = []

    def visit(name: str, item: Any) -> None:
        if not isinstance(item, h5py.Dataset) or any(p.startswith("#") for p in name.split("/")):
            return  # MATLAB keeps cell contents and references under #refs#
        if matlab and _text(item.attrs.get("MATLAB_class")) in ("char", "cell", None):
            return
        if item.dtype.kind not in "fiub" or item.size <= 1:
            return
        parts = name.split("/")
        if matlab:
            full, parent = ".".join(parts), ".".join(parts[:-1])
        else:
            full, parent = "/" + name, "/" + "/".join(parts[:-1])
        unit = _text(item.attrs.get("units", item.attrs.get("unit")))
        found.append(StoredArray(full, parent, item[()], unit))

    try:
        with h5py.File(path, "r") as file:
            file.visititems(visit)
    except (OSError, ValueError, KeyError) as exc:
        raise TraceFormatError(path, f"not a readable HDF5 file: {exc}") from exc
    return found


def _stored_arrays(path: Path) -> tuple[list[StoredArray], str]:
    """The file's numeric arrays and the separator of their paths."""
    import h5py

    suffix = path.suffix.lower()
    if suffix == ".mat":
        if h5py.is_hdf5(path):  # MAT 7.3
            return _hdf5_arrays(path, matlab=True), "."
        return _mat5_arrays(path), "."
    if not h5py.is_hdf5(path):
        raise TraceFormatError(path, "not an HDF5 file")
    return _hdf5_arrays(path, matlab=False), "/"


def _time_array(
    path: Path, arrays: list[StoredArray], roles: Mapping[str, str], separator: str
) -> StoredArray:
    """The file's time: the variable with the role ``time``, else the one called ``time``."""
    given = [a for a in arrays if roles.get(a.name) == TIME_ROLE]
    if len(given) > 1:
        raise ChannelError(
            path, f"several variables have the role time: {', '.join(a.name for a in given)}; "
            f"name one by its path ('\"{given[-1].name}\" = \"time\"')"
        )
    if given:
        return given[0]
    named = [a for a in arrays if field_keys(a.name, separator)[-1].lower() == TIME_ROLE]
    if len(named) == 1:
        return named[0]
    candidates = [a.name for a in arrays if TIME_ROLE in a.name.lower()]
    raise ChannelError(
        path,
        ("several variables are called time: " + ", ".join(a.name for a in named)
         if named else "no variable is called time")
        + "; name the time signal in the channel map ('\"NAME\" = \"time\"')"
        + (f"; candidates: {', '.join(candidates)}" if candidates else ""),
    )


def _rows(array: StoredArray, n_samples: int) -> np.ndarray | None:
    """The array as rows of samples (axes x N), or None when it is not N samples long."""
    values = np.squeeze(array.values)
    if values.ndim == 1:
        return values[np.newaxis, :] if len(values) == n_samples else None
    if values.ndim != 2:
        return None
    if values.shape[1] == n_samples:  # one row per axis (also when square)
        return values
    if values.shape[0] == n_samples:  # one column per axis (MATLAB 7.3 transposes)
        return values.T
    return None


def _time_seconds(
    path: Path, time_array: StoredArray, units: Mapping[str, Any], cmap: ChannelMap
) -> tuple[Clock, Callable[[int], str]]:
    """The time variable in seconds (:mod:`funcnet.robot.io.clock`), and where a sample is."""
    time = np.squeeze(time_array.values).astype(np.float64)
    if time.ndim != 1:
        raise TraceFormatError(
            path, f"time {time_array.name!r} has shape {time_array.values.shape}; it must be a "
            "vector of time stamps in seconds"
        )

    def where(sample: int) -> str:
        return f"{time_array.name} sample {sample + 1}"

    stated = units.get(time_array.name)
    clock = clock_seconds(path, time, stated if isinstance(stated, str) else cmap.time_unit(),
                          time_array.name, where)
    return clock, where


def _signal_rows(
    path: Path, arrays: list[StoredArray], time_array: StoredArray, roles: Mapping[str, str],
    n_samples: int,
) -> list[tuple[StoredArray, np.ndarray]]:
    """The signals beside the time (or named by the map), each as rows of samples."""
    signals: list[tuple[StoredArray, np.ndarray]] = []
    misfits: list[StoredArray] = []
    for array in arrays:
        if array is time_array or (array.parent != time_array.parent and array.name not in roles):
            continue
        rows = _rows(array, n_samples)
        if rows is None:
            if array.name in roles:
                misfits.append(array)
            continue
        signals.append((array, rows))
    read_roles = {roles.get(a.name) for a, _ in signals}
    for array in misfits:  # an entry that names several variables needs one of them to fit
        if roles[array.name] not in read_roles:
            raise ChannelError(
                path, f"{array.name!r} (role {roles[array.name]}) has shape "
                f"{array.values.shape}, not one row of {n_samples} samples per axis as its "
                f"time {time_array.name!r}"
            )
    if not signals:
        raise TraceFormatError(path, f"has a time {time_array.name!r} but no signal beside it")
    return signals


def read_array_file(
    path: Path, cmap: ChannelMap, axis: int | None, *, off_grid: str = "error"
) -> GridSignals:
    """A MATLAB or HDF5 file -> its signals on their grid (see the module's rules).

    Parameters
    ----------
    path : Path
    cmap : ChannelMap
        Entries name variables by their path or any tail of it.
    axis : int or None
        The axis to read (1-based); None reads every axis.
    off_grid : {"error", "interpolate"}
        See :func:`funcnet.robot.grid.time_grid`.

    Returns
    -------
    GridSignals
        With its column names and roles.

    Raises
    ------
    TraceFormatError
        Not a readable file; time not a number, not increasing or off its grid; an infinite
        value; no signal beside the time.
    ChannelError
        No time signal, or two; a variable the map names that is not a signal of the time's
        length; two signals for one role; an entry that names no variable; ``axis`` not in the
        file.
    """
    arrays, separator = _stored_arrays(path)
    roles, units = resolve_fields(cmap, [a.name for a in arrays], separator, path)
    time_array = _time_array(path, arrays, roles, separator)
    clock, where = _time_seconds(path, time_array, units, cmap)
    time = clock.seconds
    period, ticks = time_grid(path, time, where, off_grid=off_grid)
    signals = _signal_rows(path, arrays, time_array, roles, len(time))
    n_axes = max(rows.shape[0] for _, rows in signals)
    if axis is not None and not (n_axes > 1 and 1 <= axis <= n_axes):
        held = f"axes 1-{n_axes}" if n_axes > 1 else "one axis (its signals have one row each)"
        raise ChannelError(path, f"axis {axis} is not in the file; it holds {held}")
    leaves = [field_keys(a.name, separator)[-1] for a, _ in signals]
    columns: list[str] = []
    infos: list[SignalInfo] = []
    role_of: dict[str, str] = {}
    values: list[np.ndarray] = []
    origin: dict[str, str] = {}
    for (array, rows), leaf in zip(signals, leaves, strict=True):
        role = roles.get(array.name)
        base = role or (leaf if leaves.count(leaf) == 1 else array.name)
        picked: list[tuple[int | None, np.ndarray]]
        if rows.shape[0] == 1:
            picked = [(None, rows[0])]
        elif axis is not None:
            picked = [(axis, rows[axis - 1])] if axis <= rows.shape[0] else []
        else:
            picked = [(n + 1, rows[n]) for n in range(rows.shape[0])]
        for number, row in picked:
            column = base if number is None or axis is not None else qualified(number, base)
            name = array.name if number is None else f"{array.name}(axis {number})"
            if column in origin:
                raise ChannelError(
                    path, f"{'role ' + column if role else repr(column)} is given by two "
                    f"signals: {origin[column]!r} and {name!r}"
                )
            origin[column] = name
            row = row.astype(np.float64, copy=False)  # a view: the table below is the copy
            if np.isinf(row).any():
                sample = int(np.argmax(np.isinf(row)))
                raise TraceFormatError(
                    path,
                    f"{name} sample {sample + 1}: {float(row[sample])!r} is not a finite number",
                )
            columns.append(column)
            values.append(row)
            infos.append(SignalInfo(name, None, str(array.values.dtype), period,
                                    array.unit or _axis_unit(units.get(array.name), number)))
            if role:
                role_of[column] = name
    # Grouped per axis (signals common to all first), in the file's order within an axis.
    order = sorted(range(len(columns)), key=lambda j: split_qualified(columns[j])[0] or 0)
    ordered = [values[j] for j in order]
    table = (place_on_grid(time, np.column_stack(ordered), period, ticks, left_out="gap")
             if ticks is None else _on_grid(ordered, ticks))
    return GridSignals(
        signals=tuple(infos[j] for j in order),
        values=table,
        sample_period=period,
        t0=float(np.round(time[0], 9)),
        axis=axis,
        columns=tuple(columns[j] for j in order),
        roles=role_of,
        start_time=clock.start_time,
        time_origin=clock.origin,
        time_unit=None if clock.unit == "s" else clock.unit,
    )


def _on_grid(rows: list[np.ndarray], ticks: np.ndarray) -> np.ndarray:
    """The rows as the columns of a table on the grid, NaN at a tick no stamp falls on (as
    :func:`~funcnet.robot.grid.place_on_grid` with ``left_out="gap"``), written in place: the
    signals are copied once, not stacked first (a long recording's peak memory)."""
    n_ticks = int(ticks[-1]) + 1
    whole = len(ticks) == n_ticks
    out = np.empty((n_ticks, len(rows))) if whole else np.full((n_ticks, len(rows)), np.nan)
    for j, row in enumerate(rows):
        if whole:
            out[:, j] = row
        else:
            out[ticks, j] = row
    return out


def _axis_unit(unit: str | tuple[str, ...] | None, axis: int | None) -> str | None:
    """A unit the map states, of ``axis`` where it lists one per axis."""
    if isinstance(unit, tuple):
        if axis is not None and 1 <= axis <= len(unit):
            return unit[axis - 1]
        return unit[0] if len(unit) == 1 else None
    return unit
