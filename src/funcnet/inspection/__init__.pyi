"""Type stub of funcnet.inspection: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.inspection.motion import (
    motion_summary as motion_summary,
    numbered_moves as numbered_moves,
)
from funcnet.inspection.repeated import (
    RepeatedInspection as RepeatedInspection,
    inspect_repetitions as inspect_repetitions,
    repetitions_of as repetitions_of,
)
from funcnet.inspection.robot import (
    RobotInspection as RobotInspection,
    inspect_robot as inspect_robot,
    pair_scope as pair_scope,
)
from funcnet.inspection.run import (
    FileInspections as FileInspections,
    inspect_file as inspect_file,
    inspect_files as inspect_files,
)
from funcnet.inspection.trace import (
    DETRENDED_NODES as DETRENDED_NODES,
    TraceInspection as TraceInspection,
    inspect_recording as inspect_recording,
)

__all__: list[str]
