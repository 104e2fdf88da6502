"""The inspection of a controller trace: what is the axis doing?

:mod:`~funcnet.inspection.motion` reads the moves of a recording (times, direction, distance,
speeds, currents, following error); :mod:`~funcnet.inspection.trace` computes everything the
engineer's report (:mod:`funcnet.report.inspect`) shows of one trace: the moves, a functional
network per phase of every move with its evidence, the windows or parts that could not be
computed, and the backlash diagnosis (:func:`inspect_recording`, a :class:`TraceInspection`);
:mod:`~funcnet.inspection.robot` does it for each axis of a recording of several axes and adds
the robot-wide network, its pairs told apart within and between axes (:func:`inspect_robot`).
:mod:`~funcnet.inspection.repeated` reads the repetitions of one motion in the traces together
(:func:`inspect_repetitions`, :func:`repetitions_of` the inspections).
:mod:`~funcnet.inspection.run` reads a trace file and inspects it as one axis or as a robot
(:func:`inspect_file`), and the files of ``funcnet inspect`` one after the other
(:func:`inspect_files`). The report (:mod:`funcnet.report`) only draws what these return. Names
are imported lazily.

Examples
--------
>>> from funcnet.inspection import DETRENDED_NODES
>>> DETRENDED_NODES[:2]
('FE', 'TORSION')
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "numbered_moves": "funcnet.inspection.motion",
    "motion_summary": "funcnet.inspection.motion",
    "TraceInspection": "funcnet.inspection.trace",
    "inspect_recording": "funcnet.inspection.trace",
    "DETRENDED_NODES": "funcnet.inspection.trace",
    "RobotInspection": "funcnet.inspection.robot",
    "inspect_robot": "funcnet.inspection.robot",
    "pair_scope": "funcnet.inspection.robot",
    "RepeatedInspection": "funcnet.inspection.repeated",
    "inspect_repetitions": "funcnet.inspection.repeated",
    "repetitions_of": "funcnet.inspection.repeated",
    "inspect_file": "funcnet.inspection.run",
    "inspect_files": "funcnet.inspection.run",
    "FileInspections": "funcnet.inspection.run",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
