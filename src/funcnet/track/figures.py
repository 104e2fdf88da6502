"""A run's health figures, per axis: what the inspect, backlash and compare pages compute.

Nothing is computed anew here: each figure is read from the library's own results.

``lost_motion``
    arcmin, the two-encoder lost motion (:func:`funcnet.diagnosis.diagnose_recording`);
``lost_motion_bound``
    arcmin, its upper bound where the data do not resolve it;
``backlash_score``
    the calibrated score (its indicator's unit: deg for ``motor_hysteresis``);
``fe_at_turns``
    arcmin, the following error's peak at the direction changes (one-encoder axes);
``current_at_turns``
    the current's step across the direction changes, its magnitude (the current's unit);
``friction``
    arcmin, the friction's share of the reversal error where the gear fit tells it apart;
``peak_speed``
    deg/s, the set-point's peak speed over the moves
    (:func:`funcnet.inspection.motion_summary`);
``departure``
    spreads, the run's largest departure from the band of its program's earlier runs, current
    residual or following error (:func:`funcnet.comparison.compare_runs`), NaN for a program's
    first run.

Examples
--------
>>> FIGURES["lost_motion"]
('lost motion', 'arcmin')
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet.errors import FuncnetError, FuncnetWarning, SignalError
from funcnet.robot.axes import qualified
from funcnet.robot.recording import Recording
from funcnet.robot.signals import SignalInfo

__all__ = ["FIGURES", "AxisFigures", "axis_figures", "run_axes", "trace_columns",
           "as_recording", "departures", "recorded_units"]

#: figure -> (label, unit), in the order pages show them.
FIGURES: dict[str, tuple[str, str]] = {
    "lost_motion": ("lost motion", "arcmin"),
    "lost_motion_bound": ("lost motion, upper bound", "arcmin"),
    "backlash_score": ("backlash score", "indicator unit"),
    "fe_at_turns": ("following error at the turns", "arcmin"),
    "current_at_turns": ("current step at the turns", "current unit"),
    "friction": ("friction share of the reversal error", "arcmin"),
    "peak_speed": ("peak set-point speed", "deg/s"),
    "departure": ("departure from the program's earlier runs", "spreads"),
}
#: The signals kept for later runs' departures (per axis).
KEPT = ("RP", "AP", "MP", "RC", "AC")
ARCMIN = 60.0


@dataclass(frozen=True)
class AxisFigures:
    """The figures of one axis of a run: figure -> value (NaN where not read), and why not."""

    axis: int
    values: dict[str, float]
    notes: tuple[str, ...]


def run_axes(recording: Recording) -> tuple[int, ...]:
    """The axes of a recording: its axes, or its one axis (1 when it does not say)."""
    return recording.axes or (recording.axis or 1,)


def _mean(values: Sequence[float | None]) -> float:
    kept = [abs(v) for v in values if v is not None and math.isfinite(v)]
    return float(np.mean(kept)) if kept else math.nan


def _arcmin(deg: float | None) -> float:
    return math.nan if deg is None else float(deg) * ARCMIN


def axis_figures(recording: Recording, axis: int) -> AxisFigures:
    """The figures of one axis (module notes), from a recording in degrees.

    Examples
    --------
    >>> from funcnet.sim import Trial, simulate_trial
    >>> from funcnet.validation.sweep import simulated_recording
    >>> sim = simulate_trial(Trial("t", "h", speed=350, tcp=1.2, step=3, reverse=True,
    ...                            backlash=1.5 / 60))
    >>> f = axis_figures(simulated_recording(sim), 1)
    >>> round(f.values["lost_motion"], 1), round(sim.truth["lost_motion"] * 60, 1)
    (1.7, 1.7)
    """
    from funcnet.diagnosis import diagnose_recording
    from funcnet.inspection.motion import motion_summary, segment_phases

    rec = recording.for_axis(axis) if recording.axes else recording
    values = dict.fromkeys(FIGURES, math.nan)
    notes: list[str] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FuncnetWarning)  # the figures' NaN say what is missing
        try:
            found = diagnose_recording(rec)
        except FuncnetError as error:
            notes.append(f"axis {axis}: no backlash diagnosis: {error}")
        else:
            values["lost_motion"] = _arcmin(found.lost_motion)
            if found.lost_motion is None and found.lost_motion_high is not None:
                values["lost_motion_bound"] = _arcmin(found.lost_motion_high)
            if found.backlash_score is not None:
                values["backlash_score"] = float(found.backlash_score)
            turns = [r.indicators for r in found.reversals]
            values["fe_at_turns"] = _mean([t.get("following_error_peak") for t in turns]) * ARCMIN
            values["current_at_turns"] = _mean([t.get("current_step") for t in turns])
            if found.gear_parts is not None:
                values["friction"] = _arcmin(found.gear_parts.friction)
        try:
            phases, turned = segment_phases(rec)
            moves = motion_summary(rec, phases, turned)
            if "peak speed" in moves:
                values["peak_speed"] = float(moves["peak speed"].max())
        except FuncnetError as error:
            notes.append(f"axis {axis}: no moves read: {error}")
    return AxisFigures(axis, values, tuple(notes))


def recorded_units(recording: Recording) -> dict[str, str]:
    """The units of the figures whose unit is the recording's: the current step's."""
    columns = [c for c in recording.data.columns if c == "AC" or c.endswith(".AC")]
    unit = recording.signals[columns[0]].unit if columns else None
    return {"current_at_turns": unit} if unit else {}


def trace_columns(recording: Recording) -> pd.DataFrame:
    """The signals a later run is compared with (:data:`KEPT`, per axis), as columns."""
    columns = [c for a in (recording.axes or (None,)) for role in KEPT
               if (c := (qualified(a, role) if a is not None else role))
               in recording.data.columns]
    return recording.data[columns]


def as_recording(data: pd.DataFrame, period: float, source: str) -> Recording:
    """A kept trace as a recording again (for :func:`departures`)."""
    info = {c: SignalInfo(c, None, None, period) for c in data.columns}
    return Recording(data, {}, info, source=source, sample_period=period)


def departures(run: Recording, references: Sequence[Recording]) -> tuple[dict[int, float], str]:
    """Per axis, RUN's largest departure from the references' band (spreads), and a note.

    No reference, or references the run cannot be aligned with: NaN, said in the note.
    """
    from funcnet.comparison import compare_runs
    from funcnet.comparison.align import SETPOINT_TOLERANCE

    axes = run_axes(run)
    if not references:
        return dict.fromkeys(axes, math.nan), "no earlier run of the program: no departure"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FuncnetWarning)
            # the kept traces are in degrees; compare's tolerance is stated for radians
            found = compare_runs(run, list(references), networks=False,
                                 tolerance=math.degrees(SETPOINT_TOLERANCE))
    except (SignalError, FuncnetError) as error:
        return dict.fromkeys(axes, math.nan), f"no departure: {error}"
    out = {}
    for axis in axes:
        sizes = [b.size for (_, a), b in found.bands.items() if a == axis]
        finite = [s[np.isfinite(s)] for s in sizes]
        out[axis] = max((float(s.max()) for s in finite if s.size), default=math.nan)
    return out, f"departure against {len(references)} earlier run(s) of the program"
