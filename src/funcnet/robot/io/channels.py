"""The channel map: which of a file's signals is which role, and where each signal is.

A :class:`ChannelMap` assigns roles (the paper's node names RP, AP, MP, RC, AC; section 3.2;
:data:`funcnet.robot.signals.ROLES`) to base names
(:func:`funcnet.robot.signals.parse_signal_name`), so one map serves every axis. A signal without
a role keeps its base name as column name (``nckServoDataFlwErr64``, ``aaStat``): short, a valid
identifier, and what the controller's own documentation calls it.

An entry is written ``"signal name" = "ROLE"``. The paper's five roles are case-insensitive
(``"rc"`` is ``RC``: columns are always named in capitals); any other role is an identifier kept
as written. An entry a user supplies (a dict or a TOML file, not one of the defaults) must match
a signal of the trace it is applied to: :func:`check_entries` refuses one that matches none, so
an entry written the wrong way round (``RC = "nckServoDataCmdCurr32"``) or naming a signal the
trace lacks is an error, not silently ignored.

Files that store signals as named arrays (MATLAB, HDF5) name a signal by its path: a struct's
field ``rec.ref_pos_deg``, a dataset ``/rec/ref_pos``. An entry names it by the whole path or by
any tail of it (``ref_pos_deg``, ``"rec.ref_pos_deg"``; :func:`resolve_fields`). The role
``time`` marks the file's time signal; a ``[units]`` table gives units to signals whose file does
not state them (``act_torque_abs_nm = "N m"``); the ``[signals]``, ``[layout]`` and ``[bag]``
tables say where a signal is in text files and ROS bags (:mod:`funcnet.robot.io.layout`,
:mod:`funcnet.robot.io.topics`). One parser (:func:`channel_map`) checks every table of a map
against the others.
"""
from __future__ import annotations

import functools
import os
import re
import tomllib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import MappingProxyType
from typing import Any

from funcnet.errors import ChannelError, ParameterError
from funcnet.robot.io.layout import SignalFile, signal_files
from funcnet.robot.io.topics import BagLayout, bag_layout
from funcnet.robot.signals import ROLES, parse_signal_name

__all__ = [
    "ChannelMap",
    "DEFAULT_CHANNEL_MAP",
    "channel_map",
    "check_entries",
    "field_keys",
    "resolve_fields",
    "TIME_ROLE",
]

_ROLE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
#: The role of a file's time signal (seconds), in any case.
TIME_ROLE = "time"


@dataclass(frozen=True)
class ChannelMap:
    """A map from controller signal names to roles.

    A key without ``/`` matches a signal's base name on any path (``measPos2``); a key with a
    ``/`` matches path and base name (``/Nck/!SEMA/measPos2``). The ``[uU, N]`` suffix is never
    part of a key: the axis is chosen separately (``read_trace(..., axis=N)``).

    Parameters
    ----------
    roles : Mapping[str, str]
        Signal name (without suffix) -> role. Roles are identifiers; the paper's are
        :data:`ROLES`, in any case (``"ap"`` is stored as ``"AP"``), and :data:`TIME_ROLE`
        (stored as ``"time"``) marks a file's time signal.
    origin : str, optional
        The TOML file the map was read from, named in errors.
    units : Mapping[str, str or sequence of str], optional
        Signal name -> its unit, for files that do not state it; a list gives a signal of
        one column per axis a unit per axis (axis 1 first: ``["deg", "deg", "mm", "deg"]``).
        The time column's unit (``s``, ``ms``, ``us``, ``ns``) is given under its name or
        under ``time`` (:mod:`funcnet.robot.io.clock`).
    files : Mapping[str, SignalFile], optional
        Signal name -> the text file and columns it is read from (:mod:`funcnet.robot.io.layout`):
        a recording made of files, one per signal.
    axis_names : tuple of str, optional
        The axes' names, axis 1 first (``("base", "shoulder", ...)``), for pages.
    bag : BagLayout, optional
        Signal name -> the topic and message field it is read from (:mod:`funcnet.robot.io.topics`):
        a ROS bag.

    Examples
    --------
    >>> cmap = DEFAULT_CHANNEL_MAP.updated({"nckServoDataCmdCurr32Alt": "RC"})
    >>> cmap.role_of("/Nck/!SD/nckServoDataCmdCurr32Alt [u1, 1]")
    'RC'
    >>> cmap.role_of("/Nck/!SD/nckServoDataCmdCurr32 [u1, 1]") is None  # replaced for RC
    True
    >>> cmap.column_of("/Nck/!SD/nckServoDataFlwErr64 [u1, 1]")
    'nckServoDataFlwErr64'
    """

    roles: Mapping[str, str] = field(default_factory=dict)
    origin: str | None = None
    units: Mapping[str, str | tuple[str, ...]] = field(default_factory=dict)
    files: Mapping[str, SignalFile] = field(default_factory=dict)
    axis_names: tuple[str, ...] = ()
    bag: BagLayout | None = None

    def __post_init__(self) -> None:
        clean: dict[str, str] = {}
        for key, role in dict(self.roles).items():
            if not isinstance(key, str) or not isinstance(role, str) or not _ROLE.match(role):
                raise ParameterError(
                    f"channels: {key!r} -> {role!r}; a role must be an identifier such as 'RP'"
                )
            parts = parse_signal_name(key)
            if role.upper() in ROLES:
                role = role.upper()
            elif role.lower() == TIME_ROLE:
                role = TIME_ROLE
            clean[parts.path + parts.base] = role
        units: dict[str, str | tuple[str, ...]] = {}
        for key, unit in dict(self.units).items():
            if not isinstance(key, str) or not _unit_given(unit):
                raise ParameterError(
                    f"units: {key!r} -> {unit!r}; a unit is a text such as 'N m', or a list of "
                    "one per axis such as [\"deg\", \"deg\", \"mm\"]"
                )
            parts = parse_signal_name(key)
            units[parts.path + parts.base] = (
                unit.strip() if isinstance(unit, str) else tuple(u.strip() for u in unit)
            )
        object.__setattr__(self, "roles", MappingProxyType(clean))
        object.__setattr__(self, "units", MappingProxyType(units))
        object.__setattr__(self, "files", MappingProxyType(dict(self.files)))
        object.__setattr__(self, "axis_names", tuple(self.axis_names))

    def axis_label(self, axis: int) -> str:
        """``"axis 2"``, or ``"axis 2 (shoulder)"`` when the map names the axes."""
        if 1 <= axis <= len(self.axis_names):
            return f"axis {axis} ({self.axis_names[axis - 1]})"
        return f"axis {axis}"

    def unit(self, name: str, axis: int | None = None) -> str | None:
        """The unit the map states for signal ``name`` (of ``axis``, for a list), or None.

        Examples
        --------
        >>> cmap = ChannelMap(units={"q": ["deg", "mm"], "i": "A"})
        >>> cmap.unit("q", 2), cmap.unit("i", 2), cmap.unit("q"), cmap.unit("v")
        ('mm', 'A', None, None)
        """
        parts = parse_signal_name(name)
        unit = self.units.get(parts.path + parts.base, self.units.get(parts.base))
        if isinstance(unit, tuple):
            if axis is not None and 1 <= axis <= len(unit):
                return unit[axis - 1]
            return unit[0] if len(unit) == 1 else None
        return unit

    def time_unit(self, name: str | None = None) -> str | None:
        """The unit of the time column ``name``: given under its name, else under ``time``.

        Examples
        --------
        >>> ChannelMap(units={"time": "ms"}).time_unit("stamp"), ChannelMap().time_unit()
        ('ms', None)
        """
        for key in ([] if name is None else [name]) + [TIME_ROLE]:
            unit = self.units.get(key)
            if unit is not None:
                return unit if isinstance(unit, str) else ", ".join(unit)
        return None

    def role_of(self, name: str) -> str | None:
        """Return the role of the signal ``name`` (full controller name), or None."""
        parts = parse_signal_name(name)
        qualified = parts.path + parts.base
        if qualified in self.roles:
            return self.roles[qualified]
        return self.roles.get(parts.base)

    def column_of(self, name: str) -> str:
        """Return the column name for the signal ``name``: its role, else its base name."""
        return self.role_of(name) or parse_signal_name(name).base

    def updated(
        self,
        roles: Mapping[str, str],
        *,
        origin: str | None = None,
        units: Mapping[str, str | tuple[str, ...]] | None = None,
    ) -> ChannelMap:
        """Return this map with ``roles`` (and ``units``) added; a role given in ``roles``
        replaces its old keys."""
        new = ChannelMap(roles, units=units or {})
        new_roles = set(new.roles.values())
        kept = {key: role for key, role in self.roles.items() if role not in new_roles}
        return ChannelMap(
            {**kept, **new.roles}, origin=origin or self.origin, units={**self.units, **new.units},
            files=self.files, axis_names=self.axis_names, bag=self.bag,
        )


#: SINUMERIK defaults (paper section 3.2; ``../shared/data/sinumerik/README.md``).
#: ``nckServoDataCmdCurr32`` (RC) is an assumed name: no real trace with it is at hand.
DEFAULT_CHANNEL_MAP = ChannelMap(
    {
        "nckServoDataCmdPos2ndEnc64": "RP",
        "measPos2": "AP",
        "measPos1": "MP",
        "nckServoDataCmdCurr32": "RC",
        "nckServoDataActCurr32": "AC",
    }
)


def channel_map(
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
) -> ChannelMap:
    """Resolve a channel map from a map, a dict of overrides, or a TOML file.

    Parameters
    ----------
    channels : ChannelMap, dict, path or None
        None gives :data:`DEFAULT_CHANNEL_MAP`. A dict ``{signal name: role}`` is applied over the
        defaults (a role it names replaces the default signal for that role). A TOML file holds
        the same pairs in a ``[channels]`` table, and ``defaults = false`` at top level to start
        from an empty map instead of the defaults; an optional ``[units]`` table gives signals
        their units. The paper's roles are case-insensitive. Each entry that is not one of the
        defaults must match a signal of the trace it is used on (see :func:`check_entries`)::

            defaults = true
            [channels]
            nckServoDataCmdCurr32Set = "RC"

        A MATLAB file (``examples/kuka-kr300-channels.toml``)::

            defaults = false
            [channels]
            "rec.time_cont" = "time"
            ref_pos_deg = "RP"
            act_torque_abs_nm = "AC"
            [units]
            act_torque_abs_nm = "N m"

    Returns
    -------
    ChannelMap

    Raises
    ------
    ChannelError
        The TOML file cannot be read or has the wrong shape (the message names the file).
    ParameterError
        A role is not an identifier.

    References
    ----------
    Paper section 3.2: the recorded signals RP, AP, MP, RC and AC.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> toml = pathlib.Path(tempfile.mkdtemp()) / "roles.toml"
    >>> _ = toml.write_text('[channels]\\nmyCurrentSetpoint = "RC"\\n')
    >>> channel_map(toml).role_of("/Nck/!SD/myCurrentSetpoint [u1, 1]")
    'RC'
    >>> channel_map({"measPos1": "AP", "measPos2": "MP"}).role_of("measPos2")
    'MP'
    """
    if channels is None:
        return DEFAULT_CHANNEL_MAP
    if isinstance(channels, ChannelMap):
        return channels
    if isinstance(channels, Mapping):
        return DEFAULT_CHANNEL_MAP.updated(channels)
    path = Path(channels)
    try:
        # read once per content: a study or a loop over runs reads one map many times
        stat = path.stat()
        return _map_file(str(path), stat.st_mtime_ns, stat.st_size)
    except OSError as exc:
        raise ChannelError(path, f"cannot read the channel map: {exc}") from exc


@functools.lru_cache(maxsize=32)
def _map_file(name: str, mtime_ns: int, size: int) -> ChannelMap:
    """:func:`channel_map` of a TOML file, cached by its name, modification time and size."""
    path = Path(name)
    try:
        document = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ChannelError(path, f"cannot read the channel map: {exc}") from exc
    table = document.get("channels", {})
    units = document.get("units", {})
    use_defaults = document.get("defaults", True)
    files = document.get("signals", {})
    layout = document.get("layout", {})
    axis_names = document.get("axis_names", [])
    unknown = set(document) - {"channels", "defaults", "units", "signals", "layout", "axis_names",
                               "bag"}
    if (
        not isinstance(table, dict)
        or not isinstance(units, dict)
        or not isinstance(use_defaults, bool)
        or not isinstance(files, dict)
        or not isinstance(layout, dict)
        or not isinstance(axis_names, list)
        or not all(isinstance(name, str) for name in axis_names)
        or unknown
        or not all(isinstance(role, str) for role in table.values())
    ):
        raise ChannelError(
            path,
            "a channel map is a [channels] table of 'signal name = \"ROLE\"' pairs, an "
            "optional [units] table of 'signal name = \"unit\"' pairs, optional [signals] and "
            "[layout] tables naming a file per signal, an optional [bag] table naming a topic "
            "per signal, an optional 'axis_names = [...]' and an "
            "optional top-level 'defaults = true|false'"
            + (f"; unknown keys {sorted(unknown)}" if unknown else ""),
        )
    try:
        start = DEFAULT_CHANNEL_MAP if use_defaults else ChannelMap()
        updated = start.updated(table, origin=str(path), units=units)
    except ParameterError as exc:
        raise ChannelError(path, str(exc)) from exc
    if "bag" in document:
        updated = replace(updated, bag=bag_layout(document["bag"], path))
    if not files and not axis_names:
        return updated
    return replace(updated, files=signal_files(files, layout, path), axis_names=tuple(axis_names))


def check_entries(cmap: ChannelMap, names: Iterable[str], path: object) -> None:
    """Refuse a user-supplied entry of a channel map that matches no signal of a trace.

    Parameters
    ----------
    cmap : ChannelMap
        The map in use. Entries equal to one of :data:`DEFAULT_CHANNEL_MAP` are not checked:
        the defaults name signals a trace may lack (``nckServoDataCmdCurr32``).
    names : iterable of str
        Full controller names of the trace's signals (of the axis read).
    path : path-like
        The trace, named in errors.

    Raises
    ------
    ChannelError
        An entry matches no signal. The message names the trace, the map's file (when read from
        TOML) and the entry, and -- when the key is one of :data:`ROLES` and the value is not --
        says that entries are ``"signal name" = "ROLE"``.

    Examples
    --------
    >>> names = ["/Nck/!SEMA/measPos2 [u1, 1]", "/Nck/!SD/nckServoDataCmdCurr32 [u1, 1]"]
    >>> check_entries(channel_map({"measPos2": "ap"}), names, "t.xml")  # matches: no error
    >>> check_entries(channel_map({"RC": "nckServoDataCmdCurr32"}), names, "t.xml")
    Traceback (most recent call last):
    ...
    funcnet.errors.ChannelError: t.xml: channels: entry 'RC' = 'nckServoDataCmdCurr32' matches no signal of the trace; entries are "signal name" = "ROLE": did you mean 'nckServoDataCmdCurr32' = 'RC'?
    """  # noqa: E501
    parts = [parse_signal_name(name) for name in names]
    present = {p.base for p in parts} | {p.path + p.base for p in parts}
    _refuse_unmatched(cmap, present, sorted({p.base for p in parts}), path)


def _unit_given(unit: object) -> bool:
    """A unit as a map may give it: a text, or a non-empty list of texts (one per axis)."""
    if isinstance(unit, str):
        return bool(unit.strip())
    return (isinstance(unit, (list, tuple)) and bool(unit)
            and all(isinstance(u, str) and u.strip() for u in unit))


def _refuse_unmatched(
    cmap: ChannelMap, present: set[str], signals: list[str], path: object
) -> None:
    """The check of :func:`check_entries`, given the keys that match a signal (the time
    column's unit, under ``time``, matches the time whatever the file calls it)."""
    for key in cmap.units:
        if key not in present and key != TIME_ROLE:
            where = "channel map " + cmap.origin if cmap.origin else "units"
            raise ChannelError(
                path, f"{where}: unit of {key!r} given, but no signal is called so; its signals "
                f"are {signals}"
            )
    for key, role in cmap.roles.items():
        if key in present or DEFAULT_CHANNEL_MAP.roles.get(key) == role:
            continue
        message = (
            f"{'channel map ' + cmap.origin if cmap.origin else 'channels'}: entry {key!r} = "
            f"{role!r} matches no signal of the trace"
        )
        if key.upper() in ROLES and role.upper() not in ROLES:
            message += (
                f'; entries are "signal name" = "ROLE": did you mean {role!r} = {key.upper()!r}?'
            )
        else:
            message += f"; its signals are {signals}"
        raise ChannelError(path, message)


def field_keys(name: str, separator: str) -> list[str]:
    """The channel-map keys that name a signal stored at a path, the most specific first.

    Parameters
    ----------
    name : str
        The signal's path in its file: ``rec.ref_pos_deg`` (MATLAB, ``separator="."``) or
        ``/rec/ref_pos`` (HDF5, ``separator="/"``).
    separator : str

    Returns
    -------
    list of str
        The whole path, then each shorter tail of it.

    Examples
    --------
    >>> field_keys("rec.ref_pos_deg", ".")
    ['rec.ref_pos_deg', 'ref_pos_deg']
    >>> field_keys("/run/rec/ref_pos", "/")
    ['/run/rec/ref_pos', 'run/rec/ref_pos', 'rec/ref_pos', 'ref_pos']
    """
    parts = name.strip(separator).split(separator)
    tails = [separator.join(parts[i:]) for i in range(len(parts))]
    return list(dict.fromkeys([name, *tails]))


def resolve_fields(
    cmap: ChannelMap, names: Iterable[str], separator: str, path: object
) -> tuple[dict[str, str], dict[str, Any]]:
    """Roles and units of signals named by their path in a file of arrays.

    Parameters
    ----------
    cmap : ChannelMap
    names : iterable of str
        Every signal's path (see :func:`field_keys`).
    separator : str
        ``"."`` for MATLAB structs, ``"/"`` for HDF5 groups.
    path : path-like
        The file, named in errors.

    Returns
    -------
    roles : dict
        Signal path -> role, for the signals an entry names (the most specific entry wins).
    units : dict
        Signal path -> unit (a tuple of one per axis where the map lists them), for the
        signals the ``[units]`` table names.

    Raises
    ------
    ChannelError
        An entry (not one of the defaults) or a unit names no signal of the file.

    Examples
    --------
    >>> cmap = ChannelMap({"ref_pos_deg": "RP", "rec.time_cont": "time"}, units={"tau": "N m"})
    >>> resolve_fields(cmap, ["rec.time_cont", "rec.ref_pos_deg", "rec.tau"], ".", "r.mat")
    ({'rec.time_cont': 'time', 'rec.ref_pos_deg': 'RP'}, {'rec.tau': 'N m'})
    """
    names = list(names)
    keys = {name: field_keys(name, separator) for name in names}

    def lookup(table: Mapping[str, str | tuple[str, ...]]) -> dict[str, Any]:
        found = {}
        for name in names:
            for key in keys[name]:
                if key in table:
                    found[name] = table[key]
                    break
        return found

    present = {key for options in keys.values() for key in options}
    _refuse_unmatched(cmap, present, names, path)
    return lookup(cmap.roles), lookup(cmap.units)
