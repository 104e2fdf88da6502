"""Where a signal is in a text file: the ``[signals]`` and ``[layout]`` tables of a channel map.

Many robots log one text file per signal (a Universal Robots log folder: ``log_q_target.csv``,
``log_i_actual.csv``, ...) or one file with a column per signal and joint (UR's RTDE log). A
channel map names such a signal and says where it is::

    [layout]                       # shared by every entry below unless it says otherwise
    header = false                 # the first line is data, not column names
    separator = ","                # blanks around a separator are ignored; " " is any blanks
    time = 0                       # the time column (seconds): its position from 0, or its name
    columns = [1, 2, 3, 4, 5, 6]   # the signal's columns, one per axis, axis 1 first

    [signals]
    q_target = "log_q_target.csv"  # the file, relative to the run's folder
    tcp_force = { file = "log_tcp_force.csv", columns = [1, 2, 3, 4, 5, 6] }

An entry without ``file`` is read from the recording file itself (a single-file log). The name
of an entry is the signal's name: ``[channels]`` gives it a role (``q_target = "RP"``) and
``[units]`` its unit, as for any other signal.

Examples
--------
>>> layout = signal_files({"q": "log_q.csv"}, {"columns": [1, 2]}, "map.toml")
>>> layout["q"]
SignalFile(signal='q', file='log_q.csv', header=False, separator=',', time=0, columns=(1, 2))
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from funcnet.errors import ChannelError

__all__ = ["SignalFile", "signal_files", "LAYOUT_KEYS"]

#: The keys of a ``[layout]`` table and of a ``[signals]`` entry (with ``file``).
LAYOUT_KEYS = ("header", "separator", "time", "columns")


@dataclass(frozen=True)
class SignalFile:
    """Where one signal is: its file and the layout of that file.

    Attributes
    ----------
    signal : str
        The signal's name (a ``[channels]`` or ``[units]`` key names it).
    file : str or None
        Relative to the run's folder; None: the recording file itself.
    header : bool
        The file's first line names its columns.
    separator : str
        ``","`` (blanks around it ignored), ``";"``, or ``" "`` for any run of blanks.
    time : int or str
        The time column (seconds): position from 0, or its name in the header.
    columns : tuple of int or str
        The signal's columns, one per axis (axis 1 first); a single column is a signal common
        to every axis.
    """

    signal: str
    file: str | None
    header: bool
    separator: str
    time: int | str
    columns: tuple[int | str, ...]


def _column(value: Any) -> bool:
    return (isinstance(value, int) and not isinstance(value, bool) and value >= 0) or (
        isinstance(value, str) and bool(value)
    )


def signal_files(
    signals: Mapping[str, Any], layout: Mapping[str, Any], origin: object
) -> dict[str, SignalFile]:
    """The ``[signals]`` entries of a channel map, each completed by ``[layout]``.

    Parameters
    ----------
    signals : mapping
        Signal name -> its file (a string), or a table with ``file`` and any key of
        :data:`LAYOUT_KEYS`.
    layout : mapping
        Defaults for every entry (:data:`LAYOUT_KEYS`).
    origin : path-like
        The channel map, named in errors.

    Returns
    -------
    dict
        Signal name -> :class:`SignalFile`.

    Raises
    ------
    ChannelError
        An unknown key, a value of the wrong type, an entry without columns, a column named by
        its header name in a file without a header.

    Examples
    --------
    >>> signal_files({"q": {"columns": ["q0", "q1"]}},
    ...              {"header": True, "separator": " ", "time": "timestamp"}, "m.toml")["q"]
    SignalFile(signal='q', file=None, header=True, separator=' ', time='timestamp', columns=('q0', 'q1'))
    """  # noqa: E501
    unknown = set(layout) - set(LAYOUT_KEYS)
    if unknown:
        raise ChannelError(
            origin, f"[layout]: unknown keys {sorted(unknown)}; it holds {', '.join(LAYOUT_KEYS)}"
        )
    found: dict[str, SignalFile] = {}
    for name, entry in signals.items():
        where = f"[signals] {name!r}"
        if isinstance(entry, str):
            entry = {"file": entry}
        if not isinstance(entry, Mapping):
            raise ChannelError(origin, f"{where}: give its file, or a table of file and layout")
        unknown = set(entry) - {"file", *LAYOUT_KEYS}
        if unknown:
            raise ChannelError(
                origin, f"{where}: unknown keys {sorted(unknown)}; an entry holds file, "
                f"{', '.join(LAYOUT_KEYS)}"
            )
        merged = {"header": False, "separator": ",", "time": 0, **layout, **entry}
        file, header, separator = merged.get("file"), merged["header"], merged["separator"]
        time, columns = merged["time"], merged.get("columns")
        if file is not None and (not isinstance(file, str) or not file.strip()):
            raise ChannelError(origin, f"{where}: file must be a file name, got {file!r}")
        if not isinstance(header, bool):
            raise ChannelError(origin, f"{where}: header must be true or false, got {header!r}")
        if not isinstance(separator, str) or len(separator) != 1:
            raise ChannelError(
                origin, f"{where}: separator must be one character (' ' for blanks), got "
                f"{separator!r}"
            )
        if isinstance(columns, (int, str)) and not isinstance(columns, bool):
            columns = [columns]
        if not isinstance(columns, list) or not columns or not all(map(_column, columns)):
            raise ChannelError(
                origin, f"{where}: columns must list the signal's columns, one per axis "
                f"(positions from 0, or header names), got {columns!r}"
            )
        if not _column(time):
            raise ChannelError(
                origin, f"{where}: time must be the time column's position from 0 or its "
                f"name, got {time!r}"
            )
        named = [c for c in [time, *columns] if isinstance(c, str)]
        if named and not header:
            raise ChannelError(
                origin, f"{where}: columns named {named} need header = true; a file without a "
                "header names its columns by position from 0"
            )
        found[name] = SignalFile(
            signal=name, file=file, header=header, separator=separator, time=time,
            columns=tuple(columns),
        )
    return found
