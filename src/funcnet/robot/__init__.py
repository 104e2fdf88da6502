"""Robot-axis controller traces: reading, preprocessing, phases and windows.

Everything here sits below the numerical core and imports none of it: a trace file becomes a
:class:`Recording` in :mod:`funcnet.robot.io`, the one place that reads files --
:func:`read_trace` reads it as it is, :func:`read_recording` also makes it ready for analysis
(angles in degrees, the derived signals the nodes need, one grid). Its phases and windows are
tables and :class:`Window` lists. Networks per window are made by
:func:`funcnet.window_networks` (:mod:`funcnet.pipeline`). The simulated axis lives in
:mod:`funcnet.sim`, which this package never imports. Names are imported lazily.

Examples
--------
>>> import funcnet.robot
>>> funcnet.robot.span_window(1.0, 1.28).label
'1.000-1.280 s'
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "Recording": "funcnet.robot.recording",
    "read_trace": "funcnet.robot.io.read",
    "read_recording": "funcnet.robot.io.read",
    "SignalInfo": "funcnet.robot.signals",
    "ChannelMap": "funcnet.robot.io.channels",
    "DEFAULT_CHANNEL_MAP": "funcnet.robot.io.channels",
    "velocity": "funcnet.robot.preprocess",
    "add_derived_signals": "funcnet.robot.preprocess",
    "trim": "funcnet.robot.preprocess",
    "resample": "funcnet.robot.preprocess",
    "PHASES": "funcnet.robot.phases",
    "detect_phases": "funcnet.robot.phases",
    "direction_changes": "funcnet.robot.phases",
    "SetpointTurn": "funcnet.robot.phases",
    "phase_table": "funcnet.robot.phases",
    "PAPER_NODES": "funcnet.robot.windows",
    "paper_nodes": "funcnet.robot.windows",
    "Window": "funcnet.robot.windows",
    "phase_windows": "funcnet.robot.windows",
    "fixed_windows": "funcnet.robot.windows",
    "reversal_windows": "funcnet.robot.windows",
    "sliding_windows": "funcnet.robot.windows",
    "span_window": "funcnet.robot.windows",
    "complete_span": "funcnet.robot.windows",
    "Repetitions": "funcnet.robot.repeats",
    "find_repetitions": "funcnet.robot.repeats",
}

# Renamed names, still given with a DeprecationWarning.
_RENAMED = {"Turn": "SetpointTurn"}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS, deprecated=_RENAMED)
