"""ROS bags: the messages of a robot's topics as a recording on one time grid.

A bag is what ROS writes: a ROS 2 bag folder (``metadata.yaml`` beside its ``.mcap`` or ``.db3``
files), one ``.mcap`` or ``.db3`` file of it, or a ROS 1 ``.bag`` file; it is read with
``rosbags`` (pure Python, no ROS install). A channel map's ``[bag]`` table names each signal's
topic and message field and lists the joints in axis order (:mod:`funcnet.robot.io.topics`). How
the messages become a recording:

- **Message types** are read from the definitions the bag carries (a ROS 2 bag stores each
  topic's, so ``control_msgs`` and a robot vendor's own messages are read without a ROS
  install); a bag that stores none is read with the ROS 2 Humble (ROS 1 Noetic) built-in types.
- **Joints** are matched by the names each message carries (``name``, ``joint_names``), not by
  their position in it: axis ``n`` is the ``n``-th joint of ``[bag] joints``. A field of one
  number per message is common to every axis and keeps its bare name.
- **Time** is each message's ``header.stamp`` or the time the bag logged it (``[bag] time``), in
  seconds from the start of the span every topic covers; the absolute start (UTC) is the
  recording's ``start_time``. A topic's stamps must increase.
- **One grid.** The topics are read over the span they share (a topic that reaches beyond it is
  named, with its ends, in one :class:`~funcnet.RecordingWarning`, ``problem="trimmed"``), on
  the grid of the finest step of any topic, as a SINUMERIK trace of several intervals: a topic
  whose stamps lie on that grid keeps its values, a slower one held from one message to the next
  (a staircase, its own step its ``interval``); a topic whose stamps do not lie on it (a clock
  that jitters, as the stamps of a driver's messages do) is interpolated linearly onto it, as
  ``off_grid="interpolate"`` does for a table. Either is said in one warning
  (``problem="regridded"``).
- **Units** are REP 103's, the format's own (``position``: rad, ``velocity``: rad/s,
  ``acceleration``: rad/s^2, ``effort``: N m), unless the map's ``[units]`` says otherwise (a
  driver that publishes motor current as effort: ``"A"``).
- A topic the bag lacks, a field its message lacks, a joint its names lack, a field that is
  empty or of another length than the names: an error naming it. A bag that cannot be read
  (corrupt, cut short while written): :class:`~funcnet.errors.TraceFormatError`.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from funcnet.errors import ChannelError, RecordingWarning, TraceError, TraceFormatError
from funcnet.robot.axes import qualified, split_qualified
from funcnet.robot.grid import GRID_TOLERANCE, GridSignals, time_grid
from funcnet.robot.io.channels import DEFAULT_CHANNEL_MAP, ChannelMap
from funcnet.robot.io.topics import BagLayout, TopicField
from funcnet.robot.signals import SignalInfo

__all__ = ["BAG_SUFFIXES", "is_bag", "read_bag", "REP103_UNITS"]

#: Files read as a ROS bag: ROS 2 storage files (MCAP, sqlite3) and ROS 1 bags.
BAG_SUFFIXES = (".mcap", ".db3", ".bag")
#: The units REP 103 gives a joint's fields (a revolute joint), by the field's last name.
REP103_UNITS = {
    "position": "rad", "positions": "rad", "velocity": "rad/s", "velocities": "rad/s",
    "acceleration": "rad/s^2", "accelerations": "rad/s^2", "effort": "N m",
}


def is_bag(path: Path) -> bool:
    """A ROS bag: a file of :data:`BAG_SUFFIXES`, or a folder holding ``metadata.yaml``.

    Examples
    --------
    >>> is_bag(Path("run.mcap")), is_bag(Path("run.csv"))
    (True, False)
    """
    if path.is_dir():
        return (path / "metadata.yaml").is_file()
    return path.suffix.lower() in BAG_SUFFIXES


@dataclass(frozen=True)
class _Stream:
    """The messages of one topic, on one clock, as read: the stamps and each signal's values."""

    topic: str
    time: str
    stamps: np.ndarray  # int64 nanoseconds
    signals: tuple[TopicField, ...]
    fields: tuple[str, ...]  # per signal, the field read
    values: tuple[np.ndarray, ...]  # per signal, (n_messages, n_joints) or (n_messages, 1)
    per_joint: tuple[bool, ...]


def _layout(path: Path, cmap: ChannelMap) -> BagLayout:
    """The map's ``[bag]`` table; its ``[channels]`` and ``[units]`` name its signals."""
    origin = cmap.origin or "the channel map"
    if cmap.bag is None:
        raise ChannelError(
            path, f"a ROS bag is read through a channel map with a [bag] table naming each "
            f"signal's topic and field ({origin} has none); see examples/ros2-channels.toml"
        )
    if cmap.files:
        raise ChannelError(path, f"{origin}: give either [signals] (text files) or [bag], not both")
    names = sorted(cmap.bag.signals)
    for key in cmap.units:
        if key not in cmap.bag.signals:
            raise ChannelError(path, f"{origin}: unit of {key!r} given, but no signal of [bag] "
                               f"is called so; its signals are {names}")
    for key, role in cmap.roles.items():
        # the SINUMERIK defaults of a map without "defaults = false" name no signal of a bag
        if key not in cmap.bag.signals and DEFAULT_CHANNEL_MAP.roles.get(key) != role:
            raise ChannelError(path, f"{origin}: entry {key!r} = {role!r} names no signal of "
                               f"[bag]; its signals are {names}")
    return cmap.bag


def _fields_of(value: Any) -> list[str]:
    if not dataclasses.is_dataclass(value):
        return []
    return [f.name for f in dataclasses.fields(value) if not f.name.startswith("__")]


def _get(message: Any, dotted: str) -> tuple[bool, Any]:
    """The value at a dotted field path, and whether the message has it."""
    value = message
    for part in dotted.split("."):
        if part not in _fields_of(value):
            return False, None
        value = getattr(value, part)
    return True, value


def _field(path: Path, topic: str, entry: TopicField, message: Any) -> tuple[str, bool]:
    """The field an entry reads (the first it lists that the message has, filled), and whether
    it holds one value per joint."""
    present = [(f, v) for f in entry.fields for ok, v in [_get(message, f)] if ok]
    if not present:
        kind = getattr(message, "__msgtype__", type(message).__name__)
        raise ChannelError(
            path, f"[bag.signals] {entry.signal!r}: {topic} ({kind}) has no field "
            f"{' nor '.join(map(repr, entry.fields))}; its fields are {_fields_of(message)}"
        )
    dotted, value = next(((f, v) for f, v in present if np.size(v) > 0), present[0])
    if isinstance(value, bool | int | float | np.number):
        return dotted, False
    if isinstance(value, np.ndarray | list | tuple) and all(
            isinstance(v, bool | int | float | np.number) for v in np.ravel(value)):
        if np.size(value) == 0:
            raise ChannelError(
                path, f"[bag.signals] {entry.signal!r}: {topic} field {dotted!r} is empty: the "
                "bag does not record it (drop its entry)"
            )
        return dotted, True
    raise ChannelError(
        path, f"[bag.signals] {entry.signal!r}: {topic} field {dotted!r} holds "
        f"{type(value).__name__}, not a number nor one number per joint"
    )


def _joint_index(
    path: Path, topic: str, names: tuple[str, ...] | None, joints: Sequence[str], number: int
) -> np.ndarray:
    """Where each joint of the map is in a message's names."""
    if names is None:
        raise ChannelError(path, f"{topic} carries no joint names (name, joint_names): its "
                           "values cannot be matched to the joints")
    missing = [j for j in joints if j not in names]
    if missing:
        raise ChannelError(
            path, f"joint {missing[0]!r} of [bag] joints is not among the names {topic} carries "
            f"(message {number}): {list(names)}"
        )
    return np.array([names.index(j) for j in joints])


def _stamp(path: Path, topic: str, message: Any) -> Any:
    """The message's ``header.stamp``; a message without one is an error saying what to do."""
    ok, stamp = _get(message, "header.stamp")
    if not ok:
        raise ChannelError(
            path, f"{topic} ({getattr(message, '__msgtype__', '?')}) has no header.stamp; read "
            "it at the time the bag logged it (time = \"log\")"
        )
    return stamp


def _names(message: Any) -> tuple[str, ...] | None:
    for key in ("joint_names", "name"):
        value = getattr(message, key, None)
        if isinstance(value, list):
            return tuple(value)
    return None


def _read_topic(
    path: Path, reader: Any, topic: str, entries: Sequence[TopicField], joints: Sequence[str]
) -> list[_Stream]:
    """One topic's messages, deserialized once, as a stream per clock its entries read."""
    from operator import attrgetter

    connections = [c for c in reader.connections if c.topic == topic]
    logged: list[int] = []
    headers: list[int] = []
    rows: list[list[np.ndarray]] = [[] for _ in entries]
    chosen: list[tuple[str, bool]] = []
    getters: list[Callable[[Any], Any]] = []
    indices: dict[tuple[str, ...] | None, np.ndarray] = {}
    header = any(e.time == "header" for e in entries)
    for number, (connection, log_ns, raw) in enumerate(
            reader.messages(connections=connections), start=1):
        message = reader.deserialize(raw, connection.msgtype)
        if not chosen:
            chosen = [_field(path, topic, e, message) for e in entries]
            getters = [attrgetter(dotted) for dotted, _ in chosen]
        logged.append(log_ns)
        if header:  # checked on the first message; the type is the same on every one
            stamp = message.header.stamp if headers else _stamp(path, topic, message)
            headers.append(int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec))
        names = None
        if any(per_joint for _, per_joint in chosen):
            names = _names(message)
            if names not in indices:
                indices[names] = _joint_index(path, topic, names, joints, number)
        for j, ((dotted, per_joint), getter) in enumerate(zip(chosen, getters, strict=True)):
            value = getter(message)
            if not per_joint:
                rows[j].append(np.array([float(value)]))
                continue
            value = np.asarray(value, dtype=np.float64)
            if names is None or len(value) != len(names):
                raise TraceFormatError(
                    path, f"{topic} message {number}: field {dotted!r} holds {len(value)} values "
                    f"for {0 if names is None else len(names)} joint names"
                )
            rows[j].append(value[indices[names]])
    if len(logged) < 2:
        raise TraceFormatError(path, f"{topic} holds {len(logged)} message(s); a recording "
                               "needs at least two")
    streams = []
    for clock, stamps in (("header", headers), ("log", logged)):
        picked = [j for j, e in enumerate(entries) if e.time == clock]
        if picked:
            streams.append(_Stream(
                topic, clock, np.array(stamps, dtype=np.int64),
                tuple(entries[j] for j in picked), tuple(chosen[j][0] for j in picked),
                tuple(np.vstack(rows[j]) for j in picked),
                tuple(chosen[j][1] for j in picked),
            ))
    return streams


def _read_streams(path: Path, layout: BagLayout) -> list[_Stream]:
    """Every topic the map names, read from the bag."""
    from rosbags.highlevel import AnyReader, AnyReaderError
    from rosbags.highlevel.anyreader import ReaderErrors
    from rosbags.typesys import Stores, get_typestore

    by_topic: dict[str, list[TopicField]] = {}
    for entry in layout.signals.values():
        by_topic.setdefault(entry.topic, []).append(entry)
    store = Stores.ROS1_NOETIC if path.suffix.lower() == ".bag" else Stores.ROS2_HUMBLE
    try:
        with AnyReader([path], default_typestore=get_typestore(store)) as reader:
            present = sorted(reader.topics)
            for topic, entries in by_topic.items():
                if topic not in present:
                    raise ChannelError(
                        path, f"topic {topic} (of {', '.join(e.signal for e in entries)}) is not "
                        f"in the bag; its topics are {present}"
                    )
            return [stream for topic, entries in by_topic.items()
                    for stream in _read_topic(path, reader, topic, entries, layout.joints)]
    except (AnyReaderError, *ReaderErrors) as exc:
        raise TraceFormatError(path, f"not a readable ROS bag: {exc}") from exc


@dataclass(frozen=True)
class _Placed:
    """A stream on the common grid: per signal its values, and the stream's own interval."""

    values: tuple[np.ndarray, ...]
    interval: float
    said: str | None  # how it was put on the grid, when not as recorded


def _own_grids(path: Path, streams: Sequence[_Stream]) -> list[tuple[float, bool]]:
    """Each stream's step (its smallest, or its median when off a grid) and whether its stamps
    lie on a uniform grid; stamps that do not increase are an error naming the message."""
    grids = []
    for stream in streams:
        def where(row: int, topic: str = stream.topic) -> str:
            return f"{topic} message {row + 1}"

        seconds = (stream.stamps - stream.stamps[0]) / 1e9
        period, ticks = time_grid(path, seconds, where, off_grid="interpolate")
        grids.append((period, ticks is not None))
    return grids


def _held(stream: _Stream, seconds: np.ndarray, ratio: int, n_ticks: int) -> tuple[np.ndarray, ...]:
    """A stream on the grid: each tick the last message at or before it, within the stream's
    own step (a message the stream leaves out is a gap, NaN)."""
    ticks = np.round(seconds).astype(np.int64)
    grid = np.arange(n_ticks)
    row = np.searchsorted(ticks, grid, side="right") - 1
    stale = (row < 0) | (grid - ticks[np.clip(row, 0, None)] >= ratio)
    row = np.clip(row, 0, None)
    out = []
    for values in stream.values:
        on = values[row]
        on[stale] = np.nan
        out.append(on)
    return tuple(out)


def _interpolated(stream: _Stream, seconds: np.ndarray, step: float,
                  n_ticks: int) -> tuple[np.ndarray, ...]:
    """A stream interpolated linearly onto the grid (``seconds`` in ticks); a tick inside a
    step over 1.5 of the stream's median step (a message left out) is a gap, NaN."""
    grid = np.arange(n_ticks, dtype=np.float64)
    right = np.clip(np.searchsorted(seconds, grid, side="left"), 1, len(seconds) - 1)
    wide = (seconds[right] - seconds[right - 1]) > 1.5 * step
    hole = wide & (grid > seconds[right - 1]) & (grid < seconds[right])
    out = []
    for values in stream.values:
        on = np.column_stack([np.interp(grid, seconds, values[:, k])
                              for k in range(values.shape[1])])
        on[hole] = np.nan
        out.append(on)
    return tuple(out)


def _place(
    streams: Sequence[_Stream], grids: Sequence[tuple[float, bool]], origin: int, period: float,
    n_ticks: int,
) -> list[_Placed]:
    """Every stream on the common grid (see the module's rules)."""
    placed = []
    for stream, (step, uniform) in zip(streams, grids, strict=True):
        seconds = (stream.stamps - origin) / 1e9 / period  # in ticks of the common grid
        on = uniform and bool(np.all(np.abs(seconds - np.round(seconds)) <= GRID_TOLERANCE))
        ratio = int(round(step / period))
        if on and abs(step - ratio * period) <= GRID_TOLERANCE * period:
            said = (None if ratio == 1 else
                    f"{stream.topic} every {step:g} s, each value held to its next message")
            placed.append(_Placed(_held(stream, seconds, ratio, n_ticks), step, said))
            continue
        steps = np.diff(stream.stamps) / 1e9
        median = float(np.median(steps))
        said = (f"{stream.topic} (steps {steps.min() * 1e3:.4g}-{steps.max() * 1e3:.4g} ms, "
                "off the grid) interpolated linearly")
        placed.append(_Placed(_interpolated(stream, seconds, median / period, n_ticks),
                              period, said))
    return placed


def _span(path: Path, streams: Sequence[_Stream], period: float) -> tuple[int, int]:
    """The first and the last tick every stream covers (ns); the streams beyond it said."""
    origin = max(int(s.stamps[0]) for s in streams)
    stop = min(int(s.stamps[-1]) for s in streams)
    if stop <= origin:
        raise TraceFormatError(
            path, "the topics have no time span in common: " + ", ".join(
                f"{s.topic} {(s.stamps[0] - streams[0].stamps[0]) / 1e9:g}-"
                f"{(s.stamps[-1] - streams[0].stamps[0]) / 1e9:g} s" for s in streams)
        )
    tolerance = GRID_TOLERANCE * period * 1e9
    beyond = []
    for s in streams:
        ends = ([f"first at {(s.stamps[0] - origin) / 1e9:g} s"]
                if s.stamps[0] < origin - tolerance else []) + (
            [f"last at {(s.stamps[-1] - origin) / 1e9:g} s"]
            if s.stamps[-1] > stop + tolerance else [])
        if ends:
            beyond.append(f"{s.topic} ({', '.join(ends)})")
    if beyond:
        warnings.warn(RecordingWarning(
            f"{path}: topics start or end at different times; read over the span they share, "
            f"0-{(stop - origin) / 1e9:g} s: {', '.join(beyond)}",
            problem="trimmed", signals=tuple(e.signal for s in streams for e in s.signals),
        ), stacklevel=4)
    return origin, stop


def _unit(given: Any, dotted: str, joint: int | None) -> str | None:
    """The map's unit (one, or one per axis), else REP 103's for the field."""
    if isinstance(given, str):
        return given
    if isinstance(given, Sequence) and joint is not None and joint <= len(given):
        return str(given[joint - 1])
    return REP103_UNITS.get(dotted.rsplit(".", 1)[-1])


def _columns(
    path: Path, cmap: ChannelMap, joints: Sequence[str], axis: int | None,
    streams: Sequence[_Stream], placed: Sequence[_Placed],
) -> tuple[list[str], list[SignalInfo], list[np.ndarray], dict[str, str]]:
    """The streams' signals as columns, named and ordered as the files' readers name them."""
    columns: list[str] = []
    infos: list[SignalInfo] = []
    values: list[np.ndarray] = []
    roles: dict[str, str] = {}
    origin: dict[str, str] = {}
    for stream, on in zip(streams, placed, strict=True):
        for j, entry in enumerate(stream.signals):
            role = cmap.role_of(entry.signal)
            base = role or entry.signal
            dotted, table = stream.fields[j], on.values[j]
            picked: list[tuple[int | None, int]]
            if not stream.per_joint[j]:
                picked = [(None, 0)]
            elif axis is not None:
                picked = [(axis, axis - 1)]
            else:
                picked = [(n + 1, n) for n in range(len(joints))]
            for number, k in picked:
                name = base if number is None or axis is not None else qualified(number, base)
                source = (f"{stream.topic} {dotted}" if number is None
                          else f"{stream.topic} {dotted} ({joints[number - 1]})")
                if name in origin:
                    raise ChannelError(
                        path, f"{'role ' + name if role else repr(name)} is given by two "
                        f"signals: {origin[name]!r} and {source!r}")
                origin[name] = source
                columns.append(name)
                values.append(table[:, k])
                infos.append(SignalInfo(source, None, None, on.interval,
                                        _unit(cmap.units.get(entry.signal), dotted, number)))
                if role:
                    roles[name] = source
    return columns, infos, values, roles


def read_bag(
    path: Path, cmap: ChannelMap, axis: int | None, *, off_grid: str = "error"
) -> GridSignals:
    """A ROS bag -> the signals its channel map names, on one grid (see the module's rules).

    Parameters
    ----------
    path : Path
        A ROS 2 bag folder (``metadata.yaml`` beside its storage files), one ``.mcap`` or
        ``.db3`` file, or a ROS 1 ``.bag`` file.
    cmap : ChannelMap
        With its ``bag`` (:class:`funcnet.robot.io.topics.BagLayout`).
    axis : int or None
        The axis to read (from 1: the joint listed ``axis``-th); None reads every axis.
    off_grid : {"error", "interpolate"}
        Accepted for the readers' common signature: a bag's stamps off a uniform grid are
        always interpolated, and said (a message stream is not a sampled log).

    Returns
    -------
    GridSignals
        Time 0 at the start of the span every topic covers; its absolute time (UTC, ISO 8601)
        as ``start_time``.

    Raises
    ------
    TraceError
        No such file or folder.
    TraceFormatError
        Not a readable bag (a folder without ``metadata.yaml``); a topic of fewer than two
        messages; stamps that do not increase; a field of another length than the message's
        joint names; no span every topic covers.
    ChannelError
        The map has no ``[bag]`` table; a topic, field or joint the map names that the bag
        lacks; a field that is empty or not numbers; ``axis`` not one of the joints; a
        ``[channels]`` or ``[units]`` entry that names no signal; two signals for one role.

    Examples
    --------
    >>> read_bag(Path("missing.mcap"), ChannelMap(), None)
    Traceback (most recent call last):
    ...
    funcnet.errors.TraceError: missing.mcap: no such file
    """
    del off_grid  # a bag is always put on its grid as the module says
    if not path.exists():
        raise TraceError(path, "no such file")
    if path.is_dir() and not (path / "metadata.yaml").is_file():
        raise TraceFormatError(path, "a folder without metadata.yaml: not a ROS 2 bag's folder")
    layout = _layout(path, cmap)
    if axis is not None and not 1 <= axis <= len(layout.joints):
        raise ChannelError(path, f"axis {axis} is not in the recording; [bag] joints lists "
                           f"axes 1-{len(layout.joints)}: {list(layout.joints)}")
    streams = _read_streams(path, layout)
    grids = _own_grids(path, streams)
    period = min(step for step, _ in grids)
    origin, stop = _span(path, streams, period)
    n_ticks = int(np.floor((stop - origin) / 1e9 / period + GRID_TOLERANCE)) + 1
    placed = _place(streams, grids, origin, period, n_ticks)
    said = [p.said for p in placed if p.said]
    if said:
        warnings.warn(RecordingWarning(
            f"{path}: topics put on one grid of {period:g} s (the finest step): "
            + "; ".join(said), problem="regridded",
            signals=tuple(e.signal for s, p in zip(streams, placed, strict=True) if p.said
                          for e in s.signals),
        ), stacklevel=3)
    columns, infos, values, roles = _columns(path, cmap, layout.joints, axis, streams, placed)
    order = sorted(range(len(columns)), key=lambda j: split_qualified(columns[j])[0] or 0)
    start = datetime.fromtimestamp(origin // 1_000_000_000, tz=UTC).replace(
        microsecond=origin % 1_000_000_000 // 1000)
    return GridSignals(
        signals=tuple(infos[j] for j in order),
        values=np.column_stack([values[j] for j in order]),
        sample_period=period,
        t0=0.0,
        start_time=start.isoformat(),
        axis=axis,
        columns=tuple(columns[j] for j in order),
        roles=roles,
    )
