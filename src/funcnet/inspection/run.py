"""A trace file read and inspected: one axis, or each axis of a robot and the robot as a whole.

:func:`inspect_file` is what ``funcnet inspect FILE`` computes before anything is drawn: it reads
the file (:func:`funcnet.robot.read_trace`) and hands the recording to
:func:`~funcnet.inspection.inspect_recording`, or, for a recording of several axes read without
``axis``, to :func:`~funcnet.inspection.inspect_robot`.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any, Unpack

from funcnet.inspection.robot import RobotInspection, inspect_robot
from funcnet.inspection.trace import TraceInspection, inspect_recording
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides
from funcnet.robot import read_trace
from funcnet.robot.units import in_axis_units

__all__ = ["inspect_file"]


def inspect_file(
    path: str | os.PathLike[str],
    *,
    channels: Any = None,
    axis: int | None = None,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    progress: Callable[[int, int, str], None] | None = None,
    evidence_options: EvidenceSettings | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> TraceInspection | RobotInspection:
    """Read one trace file and inspect it: one axis, or a robot of several.

    Parameters
    ----------
    path : path-like
        A trace file (:func:`funcnet.robot.read_trace`: SINUMERIK XML, CSV, Parquet, MATLAB,
        HDF5).
    channels, axis
        As :func:`funcnet.robot.read_trace`. A file of several axes read without ``axis`` is
        inspected as a robot (``signals`` then names the robot network's nodes, ``A1.RP``, ...).
    signals, parameters, evidence, progress, evidence_options, **overrides
        As :func:`~funcnet.inspection.inspect_recording`.

    Returns
    -------
    TraceInspection or RobotInspection

    Raises
    ------
    TraceError
        The file cannot be read.
    ParameterError
        A bad network parameter or evidence option.

    Examples
    --------
    >>> inspect_file("missing.xml")
    Traceback (most recent call last):
        ...
    funcnet.errors.TraceError: missing.xml: no such file
    """
    # Thresholds, arcmin and arcsec are in degrees: angles in rad converted (said); a
    # set-point that never moves is kept, for the page of an axis at rest.
    recording, _ = in_axis_units(read_trace(path, channels=channels, axis=axis,
                                         keep_setpoint=True))
    if recording.axes:
        return inspect_robot(recording, signals=signals, parameters=parameters,
                             evidence=evidence, progress=progress,
                             evidence_options=evidence_options, **overrides)
    return inspect_recording(recording, signals=signals, parameters=parameters,
                             evidence=evidence, progress=progress,
                             evidence_options=evidence_options, **overrides)
