"""The unit of every signal, as its file or its channel map states it, and angles in degrees.

A signal's unit is what its file says (an HDF5 ``units`` attribute), else the channel map's
``[units]``, else what the format defines: a SINUMERIK trace states a ``unitsType`` only, and
its ``posn`` is degrees on the rotary axes it records (``current`` is A). A text table states
none: its unit is ``"unknown"`` (:func:`unit_of`).

The analyses that compare a motion with fixed thresholds or a calibration (the phases' 1 deg/s,
the backlash calibration in deg/min, arcmin and arcsec on a page) need positions in degrees:
:func:`in_degrees` converts the angles stated in radians (and their speeds) and says so; a
position of unknown unit is computed as degrees, as it always was, and labelled "unknown". A
unit that is not an angle where a position belongs (a torque mapped to RP) is an error naming
the signal.

Examples
--------
>>> from funcnet.robot.channels import SignalInfo
>>> unit_of(SignalInfo("q_target(axis 1)", None, None, 0.008, "rad"))
'rad'
>>> unit_of(SignalInfo("measPos2 [u1, 7]", "posn", "double", 0.002))
'deg'
>>> unit_of(SignalInfo("RP", None, None, 0.002))
'unknown'
>>> to_degrees("rad/s")
(57.29577951308232, 'deg/s')
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from funcnet.errors import ChannelError, RecordingWarning
from funcnet.robot.axes import split_qualified
from funcnet.robot.channels import SignalInfo
from funcnet.robot.recording import Recording

__all__ = [
    "UNKNOWN", "unit_of", "to_degrees", "in_degrees", "Units", "POSITION_ROLES", "SPEED_ROLES",
]

#: The unit of a signal whose file and channel map state none.
UNKNOWN = "unknown"
#: Roles that hold a position (an angle on a rotary axis) and a speed.
POSITION_ROLES = ("RP", "AP", "MP", "FE", "TORSION")
SPEED_ROLES = ("V", "VM")

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


@dataclass(frozen=True)
class Units:
    """What :func:`in_degrees` found and did.

    Attributes
    ----------
    position : str
        The unit the positions are now in: ``"deg"``, or ``"unknown"`` (computed as degrees).
    converted : tuple of str
        The columns converted, each ``"RP (rad)"``.
    unknown : tuple of str
        Position and speed columns of unknown unit.
    note : str
        One line saying both ("" when the positions were in degrees already).
    """

    position: str
    converted: tuple[str, ...] = ()
    unknown: tuple[str, ...] = ()
    note: str = ""


def in_degrees(recording: Recording, *, warn: bool = True) -> tuple[Recording, Units]:
    """The recording with its angles in degrees and its angular speeds in deg/s.

    Parameters
    ----------
    recording : Recording
    warn : bool
        Say a conversion or an unknown unit in one :class:`~funcnet.RecordingWarning`
        (``problem="unit"``); a recording converted before is not said again.

    Returns
    -------
    recording : Recording
        Columns in rad (rad/s, deg/min) converted, their ``unit`` relabelled; any other column
        as it was.
    units : Units

    Raises
    ------
    ChannelError
        A position (RP, AP, MP) or speed (V) column whose unit is stated and is not an angle
        (an angular speed); the message names the signal and its unit.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> data = pd.DataFrame({"RP": [0.0, math.pi]}, index=pd.Index([0.0, 0.008], name="time"))
    >>> rec = Recording(data, {"RP": "q_target"},
    ...                 {"RP": SignalInfo("q_target", None, None, 0.008, "rad")},
    ...                 sample_period=0.008)
    >>> deg, units = in_degrees(rec, warn=False)
    >>> deg.data["RP"].tolist(), deg.signals["RP"].unit, units.note
    ([0.0, 180.0], 'deg', 'converted from rad to deg (deg/s): RP (rad)')
    """
    data = recording.data
    signals = dict(recording.signals)
    scaled = {}
    converted: list[str] = []
    unknown: list[str] = []
    for column, info in recording.signals.items():
        role = split_qualified(column)[1]
        if role not in POSITION_ROLES + SPEED_ROLES:
            continue
        if info.converted_from is not None:  # converted before: said again, not scaled again
            converted.append(f"{column} ({info.converted_from})")
            continue
        unit = unit_of(info)
        if unit == UNKNOWN:
            unknown.append(column)
            continue
        found = to_degrees(unit)
        wanted = "an angle (deg, rad)" if role in POSITION_ROLES else "an angular speed (rad/s)"
        if found is None or (found[1] == "deg") != (role in POSITION_ROLES):
            raise ChannelError(
                recording.source or "<recording>",
                f"{column} ({info.name}) holds {unit}; {wanted} belongs there",
            )
        factor, target = found
        if factor != 1.0 or unit != target:
            scaled[column] = data[column] * factor
            signals[column] = replace(info, unit=target, converted_from=unit)
            converted.append(f"{column} ({unit})")
    if scaled:
        data = data.assign(**scaled)[list(data.columns)]
        recording = replace(recording, data=data, signals=signals)
    positions = [c for c in recording.signals if split_qualified(c)[1] in POSITION_ROLES]
    position = UNKNOWN if positions and all(c in unknown for c in positions) else "deg"
    parts = []
    if converted:
        units_from = sorted({c.split("(")[-1].rstrip(")") for c in converted})
        parts.append(f"converted from {', '.join(units_from)} to deg (deg/s): "
                     f"{', '.join(converted)}")
    if unknown:
        parts.append(f"no unit stated for {', '.join(unknown)}: computed as degrees (deg/s), "
                     "labelled unknown; a [units] table in the channel map states it")
    note = "; ".join(parts)
    if (scaled or unknown) and warn:  # a conversion made before was said then
        warnings.warn(
            RecordingWarning(f"{recording.source or '<recording>'}: {note}", problem="unit",
                             signals=tuple(c.split(" ")[0] for c in converted) + tuple(unknown)),
            stacklevel=2,
        )
    return recording, Units(position, tuple(converted), tuple(unknown), note)
