"""The unit of every signal, as its file or its channel map states it; angles in degrees, lengths
in millimetres.

A signal's unit is what its file says (an HDF5 ``units`` attribute), else the channel map's
``[units]``, else what the format defines: a SINUMERIK trace states a ``unitsType`` only, and
its ``posn`` is degrees on the rotary axes it records (``current`` is A). A text table states
none: its unit is ``"unknown"`` (:func:`unit_of`).

An axis turns (a rotary axis: positions are angles) or slides (a linear axis: a machine tool's
X, a gantry, a SCARA's quill: positions are lengths). The analyses compare a motion with fixed
thresholds or a calibration (the phases' 1 deg/s, the backlash calibration in deg/min) and a
page states small angles in arcmin and arcsec: :func:`in_axis_units` brings angles to degrees
(deg/s) and lengths to millimetres (mm/s) and says each conversion; a page then states a linear
axis's following error and lost motion in um (:func:`axis_scale`). A position of unknown unit is
computed as degrees, as it always was, and labelled "unknown". A unit that is neither an angle
nor a length where a position belongs (a torque mapped to RP), or an axis whose positions mix
the two, is an error naming the signal. A force (N) may stand where a current or a torque does
(AC, RC): it keeps its unit.

Examples
--------
>>> from funcnet.robot.signals import SignalInfo
>>> unit_of(SignalInfo("q_target(axis 1)", None, None, 0.008, "rad"))
'rad'
>>> unit_of(SignalInfo("measPos2 [u1, 7]", "posn", "double", 0.002))
'deg'
>>> unit_of(SignalInfo("RP", None, None, 0.002))
'unknown'
>>> to_degrees("rad/s")
(57.29577951308232, 'deg/s')
>>> to_axis_unit("mm/min")
(0.016666666666666666, 'mm/s')
>>> axis_scale("mm").fine
'um'
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from funcnet._lazy import deprecated_names
from funcnet.errors import ChannelError, RecordingWarning
from funcnet.robot.axes import split_qualified
from funcnet.robot.recording import Recording
from funcnet.robot.signals import SignalInfo

__all__ = [
    "UNKNOWN", "unit_of", "to_degrees", "to_axis_unit", "in_axis_units", "in_degrees", "Units",
    "POSITION_UNIT_ROLES", "SPEED_UNIT_ROLES", "AxisScale", "axis_scale", "position_unit",
]

#: The unit of a signal whose file and channel map state none.
UNKNOWN = "unknown"
#: Roles whose values are in a position's unit (an angle on a rotary axis, a length on a linear
#: one): the positions and their differences, the following error and the torsion.
POSITION_UNIT_ROLES = ("RP", "AP", "MP", "FE", "TORSION")
#: Roles whose values are in a speed's unit (deg/s, mm/s).
SPEED_UNIT_ROLES = ("V", "VM")

# What a SINUMERIK unitsType means on the rotary axes the traces record.
_FORMAT_UNITS = {"posn": "deg", "current": "A"}
_RAD = 180.0 / math.pi
# unit -> (factor to the degree unit, that unit)
_ANGLES = {
    "deg": (1.0, "deg"), "°": (1.0, "deg"), "degree": (1.0, "deg"), "degrees": (1.0, "deg"),
    "rad": (_RAD, "deg"), "radian": (_RAD, "deg"), "radians": (_RAD, "deg"),
    "deg/s": (1.0, "deg/s"), "°/s": (1.0, "deg/s"), "rad/s": (_RAD, "deg/s"),
    "deg/min": (1.0 / 60.0, "deg/s"), "rad/min": (_RAD / 60.0, "deg/s"),
}
# unit -> (factor to the millimetre unit, that unit)
_LENGTHS = {
    "mm": (1.0, "mm"), "m": (1000.0, "mm"), "um": (1e-3, "mm"), "µm": (1e-3, "mm"),
    "micron": (1e-3, "mm"), "mm/s": (1.0, "mm/s"), "m/s": (1000.0, "mm/s"),
    "um/s": (1e-3, "mm/s"), "µm/s": (1e-3, "mm/s"), "mm/min": (1.0 / 60.0, "mm/s"),
    "m/min": (1000.0 / 60.0, "mm/s"),
}


def unit_of(info: SignalInfo) -> str:
    """The signal's unit: the file's or the map's, else the format's, else ``"unknown"``.

    Parameters
    ----------
    info : SignalInfo

    Returns
    -------
    str
        ``info.unit``; else ``"deg"`` for a SINUMERIK ``posn``, ``"A"`` for its ``current``;
        else :data:`UNKNOWN`.

    Examples
    --------
    >>> unit_of(SignalInfo("act_torque_abs_nm", None, "double", 0.004, "N m"))
    'N m'
    >>> unit_of(SignalInfo("nckServoDataActCurr32 [u1, 7]", "current", "float", 0.002))
    'A'
    """
    if info.unit:
        return info.unit
    return _FORMAT_UNITS.get(info.units_type or "", UNKNOWN)


def to_degrees(unit: str) -> tuple[float, str] | None:
    """The factor that turns an angle or an angular speed into degrees (per second).

    Parameters
    ----------
    unit : str
        ``"rad"``, ``"deg"``, ``"rad/s"``, ``"deg/min"``, ... (case and blanks ignored).

    Returns
    -------
    (float, str) or None
        The factor and the unit it gives (``"deg"`` or ``"deg/s"``); None when ``unit`` is
        neither an angle nor an angular speed.

    Examples
    --------
    >>> to_degrees("deg/min")
    (0.016666666666666666, 'deg/s')
    >>> to_degrees("N m") is None
    True
    """
    return _ANGLES.get(unit.strip().lower().replace(" ", ""))


def to_axis_unit(unit: str) -> tuple[float, str] | None:
    """The factor that brings a position or speed to the axis's unit: deg (deg/s) for an angle,
    mm (mm/s) for a length.

    Parameters
    ----------
    unit : str
        ``"rad"``, ``"m"``, ``"um"``, ``"mm/min"``, ... (case and blanks ignored; ``μ`` as
        ``µ``).

    Returns
    -------
    (float, str) or None
        The factor and the unit it gives (``"deg"``, ``"deg/s"``, ``"mm"``, ``"mm/s"``); None
        when ``unit`` is neither.

    Examples
    --------
    >>> to_axis_unit("m/s"), to_axis_unit("um"), to_axis_unit("N") is None
    ((1000.0, 'mm/s'), (0.001, 'mm'), True)
    """
    key = unit.strip().replace(" ", "").replace("μ", "µ")
    return to_degrees(key) or _LENGTHS.get(key if key.startswith("µ") else key.lower())


@dataclass(frozen=True)
class AxisScale:
    """How an axis's positions and their small differences are stated on a page.

    Attributes
    ----------
    position : str
        ``"deg"``, ``"mm"``, or ``"unknown"`` (computed as degrees).
    speed : str
        ``"deg/s"``, ``"mm/s"``, or ``"unknown"``.
    fine, fine_factor : str, float
        Following error at rest and lost motion: arcsec (x 3600) on a rotary axis, um (x 1000)
        on a linear one; ``"(x 3600, unit unknown)"``, 3600 where the unit is unknown.
    coarse, coarse_factor : str, float
        A peak following error, a lost motion in a robot's table: arcmin (x 60), or um.
    linear : bool
        The axis slides (positions in mm).
    """

    position: str
    speed: str
    fine: str
    fine_factor: float
    coarse: str
    coarse_factor: float
    linear: bool = False

    @property
    def symbol(self) -> str:
        """The position's unit as an axis label says it: ``°``, ``mm``, ``unit unknown``."""
        return {"deg": "°", "mm": "mm"}.get(self.position, "unit unknown")


def axis_scale(unit: str | None) -> AxisScale:
    """The :class:`AxisScale` of positions in ``unit`` (after :func:`in_axis_units`).

    Examples
    --------
    >>> axis_scale("deg").coarse, axis_scale("mm").coarse_factor, axis_scale(None).position
    ('arcmin', 1000.0, 'unknown')
    """
    if unit == "mm":
        return AxisScale("mm", "mm/s", "um", 1000.0, "um", 1000.0, linear=True)
    if unit == "deg":
        return AxisScale("deg", "deg/s", "arcsec", 3600.0, "arcmin", 60.0)
    return AxisScale(UNKNOWN, UNKNOWN, "(x 3600, unit unknown)", 3600.0,
                     "(x 60, unit unknown)", 60.0)


def position_unit(signals: dict[str, SignalInfo], axis: int | None = None) -> str:
    """The unit of an axis's positions: that of RP, else AP, else MP (``"deg"`` when there is
    none: an axis without a position is judged as the rotary axes it was built for).

    Parameters
    ----------
    signals : dict
        A recording's :attr:`~funcnet.robot.Recording.signals`.
    axis : int, optional
        The axis, in a recording of several (its columns ``A<n>.RP``).

    Examples
    --------
    >>> position_unit({"A3.RP": SignalInfo("q", None, None, 0.001, "mm")}, axis=3)
    'mm'
    """
    for role in ("RP", "AP", "MP"):
        column = role if axis is None else f"A{axis}.{role}"
        info = signals.get(column, signals.get(role) if axis is not None else None)
        if info is not None:
            return unit_of(info)
    return "deg"


@dataclass(frozen=True)
class Units:
    """What :func:`in_axis_units` found and did.

    Attributes
    ----------
    position : str
        The unit the positions are now in: ``"deg"``, ``"mm"`` (every axis linear), or
        ``"unknown"`` (computed as degrees).
    converted : tuple of str
        The columns converted, each ``"RP (rad)"``.
    unknown : tuple of str
        Position and speed columns of unknown unit.
    note : str
        One line saying both ("" when the positions were in degrees or mm already).
    """

    position: str
    converted: tuple[str, ...] = ()
    unknown: tuple[str, ...] = ()
    note: str = ""


def in_axis_units(recording: Recording, *, warn: bool = True) -> tuple[Recording, Units]:
    """The recording with its angles in degrees (deg/s) and its lengths in mm (mm/s).

    Parameters
    ----------
    recording : Recording
    warn : bool
        Say a conversion or an unknown unit in one :class:`~funcnet.RecordingWarning`
        (``problem="unit"``); a recording converted before is not said again.

    Returns
    -------
    recording : Recording
        Columns in rad (rad/s, deg/min), m or um (m/s, mm/min) converted, their ``unit``
        relabelled; any other column as it was.
    units : Units

    Raises
    ------
    ChannelError
        A position (RP, AP, MP) or speed (V) column whose unit is stated and is neither an
        angle nor a length (an angular or linear speed); an axis whose positions mix angles
        and lengths. The message names the signal and its unit.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> data = pd.DataFrame({"RP": [0.0, math.pi]}, index=pd.Index([0.0, 0.008], name="time"))
    >>> rec = Recording(data, {"RP": "q_target"},
    ...                 {"RP": SignalInfo("q_target", None, None, 0.008, "rad")},
    ...                 sample_period=0.008)
    >>> deg, units = in_axis_units(rec, warn=False)
    >>> deg.data["RP"].tolist(), deg.signals["RP"].unit, units.note
    ([0.0, 180.0], 'deg', 'converted from rad to deg (deg/s): RP (rad)')
    >>> rec = Recording(data, {"RP": "z"}, {"RP": SignalInfo("z", None, None, 0.008, "m")},
    ...                 sample_period=0.008)
    >>> in_axis_units(rec, warn=False)[0].signals["RP"].unit
    'mm'
    """
    data = recording.data
    signals = dict(recording.signals)
    scaled = {}
    converted: list[str] = []
    unknown: list[str] = []
    kinds: dict[int | None, tuple[str, str]] = {}  # axis -> (unit kind, the column saying it)
    for column, info in recording.signals.items():
        number, role = split_qualified(column)
        if role not in POSITION_UNIT_ROLES + SPEED_UNIT_ROLES:
            continue
        if info.converted_from is not None:  # converted before: said again, not scaled again
            converted.append(f"{column} ({info.converted_from})")
            _same_kind(recording, kinds, number, column, info.unit or "")
            continue
        unit = unit_of(info)
        if unit == UNKNOWN:
            unknown.append(column)
            continue
        found = to_axis_unit(unit)
        wanted = ("an angle (deg, rad) or a length (mm, m, um)" if role in POSITION_UNIT_ROLES
                  else "an angular speed (rad/s) or a linear one (mm/s)")
        if found is None or ("/" not in found[1]) != (role in POSITION_UNIT_ROLES):
            raise ChannelError(
                recording.source or "<recording>",
                f"{column} ({info.name}) holds {unit}; {wanted} belongs there",
            )
        _same_kind(recording, kinds, number, column, found[1])
        factor, target = found
        if factor != 1.0 or unit != target:
            scaled[column] = data[column] * factor
            signals[column] = replace(info, unit=target, converted_from=unit)
            converted.append(f"{column} ({unit})")
    if scaled:
        data = data.assign(**scaled)[list(data.columns)]
        recording = replace(recording, data=data, signals=signals)
    units = _summary(recording, converted, unknown, kinds)
    if (scaled or unknown) and warn:  # a conversion made before was said then
        warnings.warn(
            RecordingWarning(f"{recording.source or '<recording>'}: {units.note}",
                             problem="unit",
                             signals=tuple(c.split(" ")[0] for c in converted) + tuple(unknown)),
            stacklevel=2,
        )
    return recording, units


#: The former name of :func:`in_axis_units`, from when every axis turned.
in_degrees = in_axis_units


def _same_kind(recording: Recording, kinds: dict[int | None, tuple[str, str]],
               number: int | None, column: str, unit: str) -> None:
    """Refuse an axis whose positions and speeds mix angles and lengths."""
    kind = "length" if unit.startswith("mm") else "angle"
    seen = kinds.setdefault(number, (kind, column))
    if seen[0] != kind:
        raise ChannelError(
            recording.source or "<recording>",
            f"{column} holds {'a length' if kind == 'length' else 'an angle'} and {seen[1]} "
            f"{'a length' if seen[0] == 'length' else 'an angle'}: one axis either turns or "
            "slides; state its units alike"
        )


def _summary(recording: Recording, converted: list[str], unknown: list[str],
             kinds: dict[int | None, tuple[str, str]]) -> Units:
    """:class:`Units` of the conversion, with its one line."""
    positions = [c for c in recording.signals if split_qualified(c)[1] in POSITION_UNIT_ROLES]
    linear = bool(kinds) and all(kind == "length" for kind, _ in kinds.values())
    position = (UNKNOWN if positions and all(c in unknown for c in positions)
                else "mm" if linear else "deg")
    parts = []
    if converted:
        units_from = sorted({c.split("(")[-1].rstrip(")") for c in converted})
        lengths = any(kind == "length" for kind, _ in kinds.values())
        angles = any(kind == "angle" for kind, _ in kinds.values())
        target = " and ".join((["deg (deg/s)"] if angles or not lengths else [])
                              + (["mm (mm/s)"] if lengths else []))
        parts.append(f"converted from {', '.join(units_from)} to {target}: "
                     f"{', '.join(converted)}")
    if unknown:
        parts.append(f"no unit stated for {', '.join(unknown)}: computed as degrees (deg/s), "
                     "labelled unknown; a [units] table in the channel map states it")
    return Units(position, tuple(converted), tuple(unknown), "; ".join(parts))


# Renamed names, still given with a DeprecationWarning.
__getattr__ = deprecated_names(
    __name__, {"POSITION_ROLES": "POSITION_UNIT_ROLES", "SPEED_ROLES": "SPEED_UNIT_ROLES"}
)
