"""Robot-axis controller traces: reading, preprocessing, phases and windows.

Everything here sits below the numerical core and imports none of it: a trace becomes a
:class:`Recording` (:func:`read_trace`, :func:`read_recording`), its phases and windows are
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

from typing import TYPE_CHECKING

from funcnet._lazy import attach

_EXPORTS = {
    "Recording": "funcnet.robot.recording",
    "read_trace": "funcnet.robot.recording",
    "read_recording": "funcnet.robot.load",
    "SignalInfo": "funcnet.robot.channels",
    "ChannelMap": "funcnet.robot.channels",
    "DEFAULT_CHANNEL_MAP": "funcnet.robot.channels",
    "velocity": "funcnet.robot.preprocess",
    "add_derived_signals": "funcnet.robot.preprocess",
    "trim": "funcnet.robot.preprocess",
    "resample": "funcnet.robot.preprocess",
    "PHASES": "funcnet.robot.phases",
    "detect_phases": "funcnet.robot.phases",
    "direction_changes": "funcnet.robot.phases",
    "Turn": "funcnet.robot.phases",
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




if TYPE_CHECKING:  # what the lazy table exports, for type checkers and editors
    from funcnet.robot.channels import (
        DEFAULT_CHANNEL_MAP as DEFAULT_CHANNEL_MAP,
        ChannelMap as ChannelMap,
        SignalInfo as SignalInfo,
    )
    from funcnet.robot.load import read_recording as read_recording
    from funcnet.robot.phases import (
        PHASES as PHASES,
        Turn as Turn,
        detect_phases as detect_phases,
        direction_changes as direction_changes,
        phase_table as phase_table,
    )
    from funcnet.robot.preprocess import (
        add_derived_signals as add_derived_signals,
        resample as resample,
        trim as trim,
        velocity as velocity,
    )
    from funcnet.robot.recording import Recording as Recording, read_trace as read_trace
    from funcnet.robot.repeats import (
        Repetitions as Repetitions,
        find_repetitions as find_repetitions,
    )
    from funcnet.robot.windows import (
        PAPER_NODES as PAPER_NODES,
        Window as Window,
        complete_span as complete_span,
        fixed_windows as fixed_windows,
        paper_nodes as paper_nodes,
        phase_windows as phase_windows,
        reversal_windows as reversal_windows,
        sliding_windows as sliding_windows,
        span_window as span_window,
    )

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
