"""Backlash diagnosis from controller traces, validated on a simulated sweep.

:mod:`~funcnet.diagnosis.reversals` finds the direction changes of an axis,
:mod:`~funcnet.diagnosis.indicators` computes the backlash indicators at a reversal (physical
baselines, motor-side functional-network features, the paper's signature),
:mod:`~funcnet.diagnosis.two_encoder` the two-encoder lost motion among them,
:mod:`~funcnet.validation.sweep` simulates the sweep and scores the indicators against the
truth, and :mod:`~funcnet.diagnosis.diagnose` diagnoses real traces
(:func:`diagnose_backlash`; :mod:`~funcnet.diagnosis.segments` reads a recording with gaps
segment by segment, :mod:`~funcnet.diagnosis.results` writes the diagnoses). Names are imported
lazily.

Examples
--------
>>> from funcnet.diagnosis import SCORE
>>> SCORE
'motor_hysteresis'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from funcnet._lazy import attach

_EXPORTS = {
    "DirectionChange": "funcnet.diagnosis.reversals",
    "find_direction_changes": "funcnet.diagnosis.reversals",
    "changes_across_gaps": "funcnet.diagnosis.reversals",
    "changes_within_and_across": "funcnet.diagnosis.reversals",
    "motor_side_recording": "funcnet.diagnosis.reversals",
    "INDICATORS": "funcnet.diagnosis.indicators",
    "MOTOR_SIDE": "funcnet.diagnosis.indicators",
    "reversal_indicators": "funcnet.diagnosis.indicators",
    "lost_motion": "funcnet.diagnosis.two_encoder",
    "ArmStart": "funcnet.diagnosis.two_encoder",
    "first_start": "funcnet.diagnosis.two_encoder",
    "run_sweep": "funcnet.validation.sweep",
    "folder_indicators": "funcnet.validation.sweep",
    "score_indicators": "funcnet.validation.sweep",
    "calibration": "funcnet.validation.sweep",
    "SCORE": "funcnet.diagnosis.diagnose",
    "MOTOR_LOOP_SCORE": "funcnet.diagnosis.diagnose",
    "BacklashResult": "funcnet.diagnosis.diagnose",
    "ReversalResult": "funcnet.diagnosis.diagnose",
    "diagnose_backlash": "funcnet.diagnosis.diagnose",
    "diagnose_recording": "funcnet.diagnosis.diagnose",
    "load_calibration": "funcnet.diagnosis.diagnose",
    "write_results": "funcnet.diagnosis.results",
    "trend_table": "funcnet.diagnosis.results",
}




if TYPE_CHECKING:  # what the lazy table exports, for type checkers and editors
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
    from funcnet.validation.sweep import (
        calibration as calibration,
        folder_indicators as folder_indicators,
        run_sweep as run_sweep,
        score_indicators as score_indicators,
    )

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
