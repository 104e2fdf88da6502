"""Backlash diagnosis from controller traces, read on a calibration from a simulated sweep.

:mod:`~funcnet.diagnosis.reversals` finds the direction changes of an axis,
:mod:`~funcnet.diagnosis.indicators` computes the backlash indicators at a reversal (physical
baselines, motor-side functional-network features, the paper's signature),
:mod:`~funcnet.diagnosis.two_encoder` the two-encoder lost motion among them, and
:mod:`~funcnet.diagnosis.diagnose` diagnoses real traces
(:func:`diagnose_backlash`; :mod:`~funcnet.diagnosis.segments` reads a recording with gaps
segment by segment, :mod:`~funcnet.diagnosis.results` writes the diagnoses). The shipped
calibration (``calibration.json``) is data; the sweep it comes from is the bench's
(:mod:`funcnet.validation.sweep`), which this package never imports. Names are imported lazily.

Examples
--------
>>> from funcnet.diagnosis import SCORE
>>> SCORE
'motor_hysteresis'
"""

from __future__ import annotations

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

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
