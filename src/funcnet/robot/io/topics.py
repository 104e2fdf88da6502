"""Where a signal is in a ROS bag: the ``[bag]`` table of a channel map.

A ROS bag (ROS 2: MCAP or sqlite3; ROS 1: ``.bag``) holds messages on topics. A channel map
names each signal by its topic and the message field that holds it, and lists the joints in axis
order; a field that holds one value per joint is matched to the joints by the names the message
carries (``name`` of a ``sensor_msgs/msg/JointState``, ``joint_names`` of a
``control_msgs/msg/JointTrajectoryControllerState``), never by position::

    [bag]
    time = "header"                 # each message's header.stamp; "log": when the bag logged it
    joints = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]   # axis 1 first

    [bag.signals]
    joint_velocity = { topic = "/joint_states", field = "velocity" }
    # several fields: the first one the message has (a newer and an older message version)
    reference = { topic = "/state", field = ["reference.positions", "desired.positions"] }

An entry may give its own ``time``. The name of an entry is the signal's name: ``[channels]``
gives it a role and ``[units]`` its unit, as for any other signal
(:func:`funcnet.robot.io.rosbag.read_bag` says how the messages become a recording).

Examples
--------
>>> layout = bag_layout({"joints": ["a", "b"], "signals": {
...     "q": {"topic": "/joint_states", "field": "position"}}}, "map.toml")
>>> layout.joints, layout.signals["q"]
(('a', 'b'), TopicField(signal='q', topic='/joint_states', fields=('position',), time='header'))
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, TypeGuard

from funcnet.errors import ChannelError

__all__ = ["TopicField", "BagLayout", "bag_layout", "BAG_TIMES"]

#: Where a message's time comes from: its ``header.stamp``, or when the bag logged it.
BAG_TIMES = ("header", "log")


@dataclass(frozen=True)
class TopicField:
    """Where one signal is in a bag.

    Attributes
    ----------
    signal : str
        The signal's name (a ``[channels]`` or ``[units]`` key names it).
    topic : str
    fields : tuple of str
        The message field, dotted into sub-messages (``reference.positions``); several: the
        first one the message has.
    time : {"header", "log"}
        Each message's ``header.stamp``, or the time the bag logged it.
    """

    signal: str
    topic: str
    fields: tuple[str, ...]
    time: str


@dataclass(frozen=True)
class BagLayout:
    """The ``[bag]`` table of a channel map.

    Attributes
    ----------
    joints : tuple of str
        The joints' names in the messages, axis 1 first.
    signals : mapping
        Signal name -> :class:`TopicField`.
    """

    joints: tuple[str, ...]
    signals: Mapping[str, TopicField] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "signals", MappingProxyType(dict(self.signals)))


def _texts(value: Any) -> TypeGuard[list[str]]:
    return isinstance(value, list) and bool(value) and all(
        isinstance(v, str) and v.strip() for v in value)


def _time(value: Any, where: str, origin: object) -> str:
    if value not in BAG_TIMES:
        raise ChannelError(
            origin, f"{where}: time must be \"header\" (each message's header.stamp) or "
            f"\"log\" (when the bag logged it), got {value!r}"
        )
    return str(value)


def _entry(name: str, entry: Any, time: str, origin: object) -> TopicField:
    where = f"[bag.signals] {name!r}"
    if not isinstance(entry, Mapping):
        raise ChannelError(origin, f"{where}: give a table of topic and field")
    unknown = set(entry) - {"topic", "field", "time"}
    if unknown:
        raise ChannelError(
            origin, f"{where}: unknown keys {sorted(unknown)}; an entry holds topic, field, time"
        )
    topic, fields = entry.get("topic"), entry.get("field")
    if not isinstance(topic, str) or not topic.strip():
        raise ChannelError(origin, f"{where}: topic must name a topic ('/joint_states'), got "
                           f"{topic!r}")
    if isinstance(fields, str):
        fields = [fields]
    if not _texts(fields):
        raise ChannelError(
            origin, f"{where}: field must name the message field ('position', "
            f"'reference.positions') or list fields to try in order, got {fields!r}"
        )
    return TopicField(name, topic.strip(), tuple(f.strip() for f in fields),
                      _time(entry.get("time", time), where, origin))


def bag_layout(table: Any, origin: object) -> BagLayout:
    """The ``[bag]`` table of a channel map, checked.

    Parameters
    ----------
    table : mapping
        ``time`` (:data:`BAG_TIMES`, default ``"header"``), ``joints`` (the joints' names, axis 1
        first) and ``signals`` (signal name -> a table of ``topic``, ``field`` and optionally
        ``time``).
    origin : path-like
        The channel map, named in errors.

    Returns
    -------
    BagLayout

    Raises
    ------
    ChannelError
        An unknown key, a value of the wrong type, no joints or a joint named twice, no signal.

    Examples
    --------
    >>> bag_layout({"joints": ["a"], "signals": {}}, "m.toml")
    Traceback (most recent call last):
    ...
    funcnet.errors.ChannelError: m.toml: [bag]: signals must name at least one signal: ...
    """
    if not isinstance(table, Mapping):
        raise ChannelError(origin, "[bag] must be a table of time, joints and signals")
    unknown = set(table) - {"time", "joints", "signals"}
    if unknown:
        raise ChannelError(
            origin, f"[bag]: unknown keys {sorted(unknown)}; it holds time, joints, signals"
        )
    joints, signals = table.get("joints"), table.get("signals")
    if not _texts(joints) or len({j.strip() for j in joints}) != len(joints):
        raise ChannelError(
            origin, f"[bag]: joints must list the joints' names as the messages give them, axis "
            f"1 first, each once; got {joints!r}"
        )
    if not isinstance(signals, Mapping) or not signals:
        raise ChannelError(
            origin, "[bag]: signals must name at least one signal: [bag.signals] "
            "name = { topic = \"/joint_states\", field = \"position\" }"
        )
    time = _time(table.get("time", "header"), "[bag]", origin)
    return BagLayout(
        tuple(j.strip() for j in joints),
        {name: _entry(name, entry, time, origin) for name, entry in signals.items()},
    )
