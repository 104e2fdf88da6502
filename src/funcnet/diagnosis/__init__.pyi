"""Type stub of funcnet.diagnosis: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.diagnosis.diagnose import (
    MOTOR_LOOP_SCORE as MOTOR_LOOP_SCORE,
    SCORE as SCORE,
    BacklashResult as BacklashResult,
    ReversalResult as ReversalResult,
    diagnose_backlash as diagnose_backlash,
    diagnose_recording as diagnose_recording,
    load_calibration as load_calibration,
)
from funcnet.diagnosis.indicators import (
    INDICATORS as INDICATORS,
    MOTOR_SIDE as MOTOR_SIDE,
    reversal_indicators as reversal_indicators,
)
from funcnet.diagnosis.results import trend_table as trend_table, write_results as write_results
from funcnet.diagnosis.reversals import (
    DirectionChange as DirectionChange,
    changes_across_gaps as changes_across_gaps,
    changes_within_and_across as changes_within_and_across,
    find_direction_changes as find_direction_changes,
    motor_side_recording as motor_side_recording,
)
from funcnet.diagnosis.two_encoder import (
    ArmStart as ArmStart,
    first_start as first_start,
    lost_motion as lost_motion,
)

__all__: list[str]
