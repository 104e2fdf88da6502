"""Type stub of funcnet.robot: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.robot.io.channels import (
    DEFAULT_CHANNEL_MAP as DEFAULT_CHANNEL_MAP,
    ChannelMap as ChannelMap,
)
from funcnet.robot.io.read import read_recording as read_recording, read_trace as read_trace
from funcnet.robot.phases import (
    PHASES as PHASES,
    SetpointTurn as SetpointTurn,
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
from funcnet.robot.recording import Recording as Recording
from funcnet.robot.repeats import Repetitions as Repetitions, find_repetitions as find_repetitions
from funcnet.robot.signals import SignalInfo as SignalInfo
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

__all__: list[str]
