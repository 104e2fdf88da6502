"""A controller's signal: its name (path, base name, axis), its metadata, the paper's roles.

A SINUMERIK trace names a signal by a path, a name and an address, e.g.
``/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 7]``: the path ``/Nck/!SD/``, the base name
``nckServoDataCmdPos2ndEnc64`` and the suffix ``[u1, 7]`` whose second number is the axis
(:func:`parse_signal_name`; :func:`select_axis` keeps one axis's signals). What a file says of
a signal -- unit, data type, native interval -- is its :class:`SignalInfo`, kept with the
recording. The paper's five signals are the :data:`ROLES` (section 3.2); a channel map
(:mod:`funcnet.robot.io.channels`) gives them to a file's signals.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from funcnet.errors import ChannelError

__all__ = ["ROLES", "SignalInfo", "SignalName", "parse_signal_name", "select_axis"]

#: The five signals the paper records (section 3.2), in the paper's order.
ROLES = ("RP", "AP", "MP", "RC", "AC")

_SIGNAL_NAME = re.compile(
    r"^\s*(?P<path>.*/)?(?P<base>[^/\[\]]*?)\s*(?:\[\s*u(?P<unit>\d+)\s*,\s*(?P<axis>\d+)\s*\])?\s*$"
)


@dataclass(frozen=True)
class SignalInfo:
    """What a trace says about one signal.

    Attributes
    ----------
    name : str
        The controller's full signal name (``/Nck/!SEMA/measPos2 [u1, 7]``), or for a derived
        signal the expression it was computed from (``RP - AP``).
    units_type : str or None
        The trace's ``unitsType`` (``posn``, ``velo``, ``veloRot``, ``accel``, ``current``,
        ``none``); None when the file does not say (CSV).
    data_type : str or None
        The trace's ``dataType`` (``double``, ``float``, ``uword``); values are held as float64.
    interval : float
        The native interval in seconds: a value can change at most this often. A signal whose
        interval is coarser than the recording's grid is a staircase on that grid.
    unit : str or None
        The physical unit (``"deg"``, ``"N m"``) where the file or the channel map states it;
        a torque standing in the role of the current AC shows its unit here.
    converted_from : str or None
        The unit the file holds, when the values were converted to ``unit``
        (:func:`funcnet.robot.units.in_axis_units`: rad to deg, m to mm).
    """

    name: str
    units_type: str | None
    data_type: str | None
    interval: float
    unit: str | None = None
    converted_from: str | None = None


@dataclass(frozen=True)
class SignalName:
    """A controller signal name split into its parts (see :func:`parse_signal_name`)."""

    full: str
    path: str
    base: str
    unit: int | None
    axis: int | None


def parse_signal_name(name: str) -> SignalName:
    """Split a SINUMERIK signal name into path, base name, unit and axis.

    Parameters
    ----------
    name : str
        E.g. ``/Nck/!SD/nckServoDataActCurr32 [u1, 7]``; the path and the ``[uU, N]`` suffix are
        optional.

    Returns
    -------
    SignalName
        ``base`` is the name without path and suffix, ``axis`` is ``N`` (None without a suffix).

    Examples
    --------
    >>> parse_signal_name("/Nck/!SD/nckServoDataActCurr32 [u1, 7]")
    SignalName(full='/Nck/!SD/nckServoDataActCurr32 [u1, 7]', path='/Nck/!SD/', base='nckServoDataActCurr32', unit=1, axis=7)
    >>> parse_signal_name("measPos2").axis is None
    True
    """  # noqa: E501
    match = _SIGNAL_NAME.match(name)
    if match is None or not match["base"]:
        return SignalName(name, "", name.strip(), None, None)
    return SignalName(
        full=name,
        path=match["path"] or "",
        base=match["base"],
        unit=None if match["unit"] is None else int(match["unit"]),
        axis=None if match["axis"] is None else int(match["axis"]),
    )



def select_axis(
    names: Iterable[str], axis: int | None, path: object
) -> tuple[list[bool], int | None]:
    """Choose the signals of one axis.

    Parameters
    ----------
    names : iterable of str
        Full controller signal names.
    axis : int or None
        The axis to keep. None is allowed when at most one axis is present.
    path : path-like
        The file, named in errors.

    Returns
    -------
    keep : list of bool
        Per name: it belongs to ``axis`` or names no axis at all.
    axis : int or None
        The axis read (the only one present when ``axis`` was None).

    Raises
    ------
    ChannelError
        Several axes and none chosen, or the chosen axis is absent; the message lists the axes.
        (When no signal names an axis, every signal is kept whatever ``axis`` says.)

    Examples
    --------
    >>> select_axis(["measPos2 [u1, 1]", "measPos2 [u1, 2]", "aaStop"], 2, "t.xml")
    ([False, True, True], 2)
    """
    axes = [parse_signal_name(name).axis for name in names]
    present = sorted({a for a in axes if a is not None})
    if axis is None:
        if len(present) > 1:
            raise ChannelError(
                path, f"the trace holds axes {present}; choose one with axis=<one of them>"
            )
        axis = present[0] if present else None
    elif present and axis not in present:
        raise ChannelError(path, f"axis {axis} is not in the trace; it holds axes {present}")
    return [a is None or a == axis for a in axes], axis
