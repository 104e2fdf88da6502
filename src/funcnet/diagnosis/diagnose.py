"""Backlash diagnosis of real traces: find the direction changes, compute, read on the sweep.

:func:`diagnose_backlash` reads traces (SINUMERIK XML, CSV, Parquet), finds the direction
changes of the set-point, computes at each reversal the motor-side indicator the simulated
sweep supports best (:data:`SCORE`, see ``docs/validation/backlash.md``) and, when the trace has the
arm-side encoder AP, the two-encoder lost motion; and reads the score on the sweep's
calibration, which ships with the package (``calibration.json``, written by
``benchmarks/bench_backlash.py --calibrate``). The reading is **model-based**: it says which
backlash widths gave such values on the simulated axis, not on this machine. The results are
written by :mod:`~funcnet.diagnosis.results` (JSON, the trend table and its page). A recording
with gaps is read segment by segment (:mod:`~funcnet.diagnosis.segments`).

Length: over 600 lines because the two-encoder and the one-encoder diagnosis, their results and
the lost motion's bound belong together.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from importlib import resources
from typing import Any

import numpy as np
import pandas as pd

from funcnet.diagnosis.dead_zone import GearParts, gear_parts
from funcnet.diagnosis.indicators import reversal_indicators, with_contact_score
from funcnet.diagnosis.reversal_error import (
    GearFit,
    fit_gear,
    reversal_error,
    torque_column,
    torque_traversed,
)
from funcnet.diagnosis.reversals import MAX_DWELL, DirectionChange, motor_side_recording
from funcnet.diagnosis.segments import (
    LeftOut,
    segment_changes,
    segment_first_start,
    segment_part,
    segments_note,
)
from funcnet.diagnosis.two_encoder import lost_motion
from funcnet.errors import ParameterError
from funcnet.robot.io.channels import ChannelMap
from funcnet.robot.io.read import read_trace
from funcnet.robot.preprocess import encoder_step, velocity
from funcnet.robot.recording import Recording
from funcnet.robot.units import Units, in_axis_units, unit_of

__all__ = [
    "SCORE",
    "MOTOR_LOOP_SCORE",
    "ReversalResult",
    "BacklashResult",
    "diagnose_backlash",
    "diagnose_recording",
    "resolved_lost_motion",
    "load_calibration",
    "MODEL_NOTE",
]

#: The indicator reported as ``backlash_score`` when the trace has the arm encoder AP (so the
#: position loop can read it, as on the paper's robot): the motor-side indicator with the best
#: detection on the simulated sweep (``docs/validation/backlash.md``).
SCORE = "motor_hysteresis"
#: ``backlash_score`` of a trace without AP: its position loop must read the motor encoder,
#: where ``motor_hysteresis`` sees nothing; the best motor-side indicator of that sweep
#: (:func:`funcnet.diagnosis.indicators.with_contact_score`: motor travel to the gear's contact and
#: the current's step there, each against the sweep's no-backlash trials).
MOTOR_LOOP_SCORE = "motor_contact"

#: What every reading says about itself.
MODEL_NOTE = (
    "model-based: read on the simulated sweep (funcnet.sim), not on this machine; a "
    "real axis differs in its mechanics, tuning and noise"
)


@dataclass(frozen=True)
class ReversalResult:
    """One direction change of a trace and what was measured there.

    Attributes
    ----------
    change : DirectionChange
    speed : float
        deg/min, the set-point's peak speed in the move after the change (the calibration is
        keyed by it).
    backlash_score : float or None
        The trace's score indicator (deg) at a reversal; None after a standstill (the
        calibration holds reversals only).
    lost_motion : float or None
        Two-encoder lost motion (deg; None without AP, when the arm does not restart, or where
        the data do not resolve it: ``lost_motion_reason``): :func:`.two_encoder.lost_motion`,
        at a continuous change :func:`.reversal_error`. Never negative.
    indicators : dict
        Every motor-side indicator computed there (physical ones; NaN -> None).
    traversed : bool
        The gear torque changed sign there, beyond its noise (:func:`.torque_traversed`).
    lost_motion_low, lost_motion_high : float or None
        deg, the lost motion's interval: at a continuous change the bootstrap's 95 %; where the
        arm rests, the simulated sweep's validated accuracy (5 % or two arm-encoder steps,
        whichever is more; docs/validation/backlash.md section 3.1). Where the lost motion is
        not resolved (the interval reaches 0) ``low`` is 0 and ``high`` the bound.
    lost_motion_reason : str or None
        Why ``lost_motion`` is None where it was measured: below what the estimate resolves.
    lost_motion_terms : tuple of str
        The error terms the interval carries (``"noise"``, ``"motor friction bias"``,
        ``"sweep accuracy"``).
    """

    change: DirectionChange
    speed: float
    backlash_score: float | None
    lost_motion: float | None
    indicators: dict[str, float | None] = field(default_factory=dict)
    traversed: bool = False
    lost_motion_low: float | None = None
    lost_motion_high: float | None = None
    lost_motion_reason: str | None = None
    lost_motion_terms: tuple[str, ...] = ()

    def to_dict(self, length: float = 1.0) -> dict[str, Any]:
        """JSON-ready; ``length`` scales the lost motion and the following error (1000: a
        linear axis's mm to um)."""
        indicators = dict(self.indicators)
        if indicators.get("following_error_peak") is not None:
            indicators["following_error_peak"] = _scaled(indicators["following_error_peak"],
                                                         length)
        return {
            **self.change.to_dict(),
            "speed": self.speed,
            "backlash_score": self.backlash_score,
            "lost_motion": _scaled(self.lost_motion, length),
            "lost_motion_low": _scaled(self.lost_motion_low, length),
            "lost_motion_high": _scaled(self.lost_motion_high, length),
            "lost_motion_reason": self.lost_motion_reason,
            "lost_motion_terms": list(self.lost_motion_terms),
            "traversed": self.traversed,
            "indicators": indicators,
        }


def _scaled(value: float | None, factor: float) -> float | None:
    return None if value is None else value * factor


@dataclass(frozen=True)
class BacklashResult:
    """The diagnosis of one trace.

    Attributes
    ----------
    path : str
        As given.
    score_indicator : str
        :data:`SCORE` when the trace has AP, :data:`MOTOR_LOOP_SCORE` without it.
    backlash_score : float or None
        Mean of ``score_indicator`` over the trace's reversals (higher = more backlash; in
        :attr:`score_unit`: deg for ``motor_hysteresis``, dimensionless for
        ``motor_contact``); None without a reversal.
    score_spread : float or None
        Uncertainty of ``backlash_score``: the scatter (half the 10-90 % range) of the score
        on the simulated sweep at the backlash width read, with friction, stiffness, TCP and
        noise varied; None without a reading.
    lost_motion : float or None
        Mean two-encoder lost motion over every direction change measured (deg); None without
        AP, and where the data do not resolve it (``lost_motion_reason``). Never negative.
    lost_motion_spread : float or None
        Half the range of the lost motions over the direction changes (None with fewer than
        two, or without a resolved ``lost_motion``).
    reversals : tuple of ReversalResult
        Every direction change (reversals and changes after a standstill), in time order; in
        a recording with gaps, those of every segment (none left out: ``left_out``).
    reading : dict or None
        The calibration's reading: ``indicator``, ``speed`` (calibrated speed used),
        ``extrapolated`` (always False now: a reading outside the calibrated speeds is None),
        ``arcmin_low``, ``arcmin_high`` and ``text``; None without a score, and where the
        trace's speed or signals lie outside those the calibration was made on
        (``reading_reason`` says which).
    message : str
        One line saying what was found.
    reading_reason : str or None
        Why ``reading`` is None (None when there is a reading).
    lost_motion_reason : str or None
        Why ``lost_motion`` is None: no AP, no direction change, or below what the estimate
        resolves (``"below what this estimate resolves: <= 0.2 arcmin"``; None when there is
        one).
    gear : GearFit or None
        With AP and continuous changes: the gear's fit over the recording (:func:`.fit_gear`).
    gear_parts : GearParts or None
        With ``gear``: backlash (dead zone) and friction told apart where the torque's sign
        allows, else why not (:func:`.gear_parts`).
    axis : int or None
        The axis diagnosed, when the trace held several (one result per axis).
    segments : tuple of (float, float)
        s, the segments a recording with gaps was read in; () without gaps (the JSON then
        has neither this nor ``left_out``).
    left_out : tuple of LeftOut
        The direction changes left out: a gap within what is read around them.
    units : str or None
        What was done to the units (positions converted from rad to deg or from m to mm, or of
        unknown unit and computed as degrees); None when the trace's positions are in degrees
        or mm. The JSON then has the key ``units``.
    position_unit : str
        ``"deg"`` (a rotary axis), ``"mm"`` (a linear one: its lost motion and following
        error are computed in mm, and the JSON states them in um, ``length_unit``; the
        calibration, made on rotary axes, is not read), or ``"unknown"``.
    lost_motion_low, lost_motion_high : float or None
        deg, the axis's lost motion's interval: the means of its direction changes' interval
        ends (the mean's error terms, added up as if they agreed: its bias does not average
        out); unresolved, 0 and the bound. None without a lost motion measured.
    lost_motion_terms : tuple of str
        The error terms of that interval (every direction change's).
    """

    path: str
    score_indicator: str
    backlash_score: float | None
    score_spread: float | None
    lost_motion: float | None
    lost_motion_spread: float | None
    reversals: tuple[ReversalResult, ...]
    reading: dict[str, Any] | None
    message: str
    reading_reason: str | None = None
    lost_motion_reason: str | None = None
    gear: GearFit | None = None
    gear_parts: GearParts | None = None
    axis: int | None = None
    segments: tuple[tuple[float, float], ...] = ()
    left_out: tuple[LeftOut, ...] = ()
    units: str | None = None
    lost_motion_low: float | None = None
    lost_motion_high: float | None = None
    lost_motion_terms: tuple[str, ...] = ()
    position_unit: str = "deg"

    @property
    def score_unit(self) -> str:
        """``"deg"`` (``"mm"`` on a linear axis) for ``motor_hysteresis``; ``"1"`` (a sum of
        robust z-scores) otherwise."""
        if self.score_indicator == "none":  # one encoder: no score
            return "none"
        return ("mm" if self.position_unit == "mm" else "deg") if self.score_indicator == SCORE \
            else "1"

    @property
    def length_unit(self) -> str:
        """The unit of the lost motion and the following error in the JSON: ``"um"`` on a
        linear axis, else ``"deg"``."""
        return "um" if self.position_unit == "mm" else "deg"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (the names other tools read: path, backlash_score, lost_motion, ...);
        the lost motion and the following error in :attr:`length_unit`."""
        k = 1000.0 if self.position_unit == "mm" else 1.0
        return {
            "path": self.path, "axis": self.axis,
            "position_unit": self.position_unit,
            "length_unit": self.length_unit,
            "backlash_score": self.backlash_score,
            "score_indicator": self.score_indicator,
            "score_unit": self.score_unit,
            "score_spread": self.score_spread,
            "lost_motion": _scaled(self.lost_motion, k),
            "lost_motion_low": _scaled(self.lost_motion_low, k),
            "lost_motion_high": _scaled(self.lost_motion_high, k),
            "lost_motion_terms": list(self.lost_motion_terms),
            "lost_motion_spread": _scaled(self.lost_motion_spread, k),
            "reversals": [r.to_dict(k) for r in self.reversals],
            "reading": self.reading,
            "reading_reason": self.reading_reason,
            "lost_motion_reason": self.lost_motion_reason,
            "gear": None if self.gear is None else self.gear.to_dict(),
            "gear_parts": None if self.gear_parts is None else self.gear_parts.to_dict(),
            **({"segments": [list(s) for s in self.segments],
                "left_out": [o.to_dict() for o in self.left_out]} if self.segments else {}),
            **({"units": self.units} if self.units else {}),
            "message": self.message,
            "note": MODEL_NOTE,
        }


def load_calibration() -> dict[str, Any]:
    """The sweep's calibration shipped with the package (``calibration.json``).

    Examples
    --------
    >>> cal = load_calibration()
    >>> cal["indicator"] == SCORE, sorted(cal["levels"])  # the set-point's peak speeds
    (True, ['35', '70.6'])
    >>> cal["motor_loop"]["indicator"] == MOTOR_LOOP_SCORE
    True
    """
    text = resources.files("funcnet.diagnosis").joinpath("calibration.json").read_text("utf-8")
    data: dict[str, Any] = json.loads(text)
    return data


def _none(value: float) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


def _move_speed(rec: Recording, change: DirectionChange) -> float:
    t = rec.data.index.to_numpy()
    rp = rec.data["RP"].to_numpy(dtype=np.float64)
    v = np.abs(velocity(rp, rec.sample_period))
    part = (t >= change.start) & (t <= change.start + 60.0)
    return float(v[part].max() * 60.0) if part.any() else math.nan


def _reading(score: float, speed: float, calibration: Mapping[str, Any]) -> dict[str, Any]:
    levels = calibration["levels"]
    speeds = sorted(float(s) for s in levels)
    nearest = min(speeds, key=lambda s: abs(math.log(s / speed)) if speed > 0 else s)
    table = levels[f"{nearest:g}"]
    quantiles = list(calibration["quantiles"])
    lo_i, hi_i = 0, len(quantiles) - 1
    widths = sorted(float(b) for b in table)
    inside = [b for b in widths if table[f"{b:g}"][lo_i] <= score <= table[f"{b:g}"][hi_i]]
    if not inside:  # between the bands or beyond them: the nearest median
        inside = [min(widths, key=lambda b: abs(table[f"{b:g}"][len(quantiles) // 2] - score))]
    low, high = min(inside), max(inside)
    span = f"{low:g} arcmin" if low == high else f"{low:g}-{high:g} arcmin"
    text = (
        f"on the simulated sweep at {nearest:g} deg/min, {calibration['indicator']} values "
        f"like this came with {span} of backlash"
    )
    return {
        "indicator": calibration["indicator"],
        "speed": nearest,
        "extrapolated": False,  # a speed outside the calibrated ones is not read (_outside)
        "arcmin_low": low,
        "arcmin_high": high,
        "text": text,
    }


def _spread(score: float, reading: Mapping[str, Any], calibration: Mapping[str, Any]) -> float:
    table = calibration["levels"][f"{reading['speed']:g}"]
    bands = [
        (q[-1] - q[0]) / 2
        for b, q in table.items()
        if reading["arcmin_low"] <= float(b) <= reading["arcmin_high"]
    ]
    return float(np.mean(bands)) if bands else math.nan


@dataclass(frozen=True)
class _Axis:
    """What every direction change of one axis is read with (:func:`_change_result`)."""

    has_ap: bool
    indicator: str
    table: Mapping[str, Any]
    arm_start: Any
    gear: GearFit | None
    quantum: float
    fine: tuple[float, str]  # how a bound is said: arcmin from deg, um from mm
    # the reversal errors' bootstrap refits of the gear, shared by the axis's changes
    refits: dict[tuple[int, ...], list[np.ndarray]] = field(default_factory=dict)


def _change_result(
    rec: Recording, change: DirectionChange, axis: _Axis
) -> tuple[ReversalResult, tuple[float, float, float, tuple[str, ...]] | None]:
    """One direction change measured, and its lost motion's estimate (lost, low, high, terms)
    where it has one."""
    part = segment_part(rec, change)  # the recording itself without gaps
    speed = _move_speed(part, change)
    traversed = torque_traversed(rec, change)
    low = high = None
    terms: tuple[str, ...] = ()
    score = lost = None
    shown: dict[str, float | None] = {}
    if change.kind == "reversal":
        values = reversal_indicators(part, change, networks=False, arm_start=axis.arm_start)
        if not axis.has_ap:
            row = pd.DataFrame([{**values, "peak_speed": speed}])
            contact = with_contact_score(row, axis.table["reference"])["motor_contact"]
            values["motor_contact"] = float(contact.iloc[0])
        score = _none(values[axis.indicator])
        lost = _none(values["lost_motion"]) if axis.has_ap else None
        shown = {k: _none(v) for k, v in values.items() if k != "signature"}
    elif change.kind == "continuous":
        # the motor-side score is calibrated on reversals where the arm rests at the turn
        if axis.has_ap:
            error = reversal_error(rec, change, axis.gear, traversed=traversed,
                                   refits=axis.refits)
            lost, low, high = _none(error.lost_motion), _none(error.low), _none(error.high)
            terms = error.terms
    else:
        lost = _none(lost_motion(part, change)) if axis.has_ap else None
    if lost is not None and change.kind != "continuous":
        # the sweep's validated accuracy: 5 % or two arm-encoder steps (section 3.1)
        width = max(0.05 * abs(lost), 2 * axis.quantum)
        low, high = lost - width, lost + width
        terms = ("sweep accuracy",)
    estimate = ((lost, low, high, terms) if lost is not None and low is not None
                and high is not None else None)
    shown_lost = resolved_lost_motion(lost, low, high, *axis.fine)
    return (ReversalResult(change, speed, score, shown_lost[0], shown, traversed, shown_lost[1],
                           shown_lost[2], shown_lost[3], terms), estimate)


def _score_reading(
    score: float | None, results: list[ReversalResult], changes: list[DirectionChange],
    linear: bool, rec: Recording, table: Mapping[str, Any], has_ap: bool,
) -> tuple[dict[str, Any] | None, float | None, str | None]:
    """The calibration's reading of the score, its spread, and why there is none."""
    if changes and linear:
        return None, None, ("a linear axis (mm): the calibration was made on rotary axes (deg, "
                            "deg/min) and is not read on it")
    if score is not None:
        speed = float(np.mean([r.speed for r in results if r.backlash_score is not None]))
        reason = _outside(speed, rec, table, has_ap)
        if reason is not None:
            return None, None, reason
        reading = _reading(score, speed, table)
        return reading, _none(_spread(score, reading, table)), None
    if changes:
        return None, None, ("no reversal with a rest at the turn: the calibration holds such "
                            "reversals only")
    return None, None, "no direction change"


def _two_encoder_message(results: list[ReversalResult], reading: dict[str, Any] | None,
                         reason: str | None, max_dwell: float, measured: bool,
                         left_out: bool) -> str:
    """The one line saying what was found at the direction changes (before the gaps' note)."""
    n_rev = sum(r.change.kind == "reversal" for r in results)
    n_cont = sum(r.change.kind == "continuous" for r in results)
    if not results:
        return ("no direction change: the axis moves one way only; no backlash indicator"
                if not left_out else "no direction change read; no backlash indicator")
    if n_rev == 0:
        rest = len(results) - n_cont
        found = (f"{n_cont} in continuous motion (the arm never rests)"
                 + (f", {rest} after a standstill" if rest else "") if n_cont
                 else f"{len(results)} direction change(s) after a standstill")  # fmt: skip
        return (
            f"no reversal (a direction change within {max_dwell:g} s): {found}; the motor-side "
            "score is calibrated on reversals only"
            + ("; two-encoder lost motion measured there" if measured else "")
        )
    return f"{n_rev} reversal(s); " + (
        reading["text"] if reading else f"no reading ({reason})" if reason else "no score"
    )


def diagnose_recording(
    recording: Recording,
    path: str | None = None,
    *,
    calibration: Mapping[str, Any] | None = None,
    max_dwell: float = MAX_DWELL,
) -> BacklashResult:
    """:func:`diagnose_backlash` for a recording already read.

    Parameters
    ----------
    recording : Recording
        With RP and MP, RC or AC; AP optional.
    path : str, optional
        Reported as the result's ``path`` (default the recording's source).
    calibration : mapping, optional
        Default :func:`load_calibration`.
    max_dwell : float
        Longest standstill (s) of a reversal.

    Returns
    -------
    BacklashResult
        A recording with gaps is read segment by segment (:mod:`.segments`): no direction
        change, window, fit row or bootstrap block spans a gap; a change with a gap within what
        is read around it is left out; ``message`` says both.
    """
    cal = load_calibration() if calibration is None else calibration
    where = path if path is not None else (recording.source or "<recording>")
    # The calibration, the thresholds and arcmin are in degrees: angles stated in rad are
    # converted (said); a unit that is no angle where a position belongs is an error.
    recording, units = in_axis_units(recording)
    if "MP" not in recording.data.columns and "RP" in recording.data.columns:
        return _one_encoder(recording, str(where), units, max_dwell)
    linear = units.position == "mm"
    fine = (1000.0, "um") if linear else (60.0, "arcmin")
    rec = motor_side_recording(recording)
    segmented = segment_changes(rec, max_dwell=max_dwell)
    changes = list(segmented.changes)
    has_ap = "AP" in rec.data.columns and bool(np.isfinite(rec.data["AP"]).any())
    indicator, table = (SCORE, cal) if has_ap else (MOTOR_LOOP_SCORE, cal["motor_loop"])
    # the axis's start from rest, fitted once for every reversal's lost motion
    resting = [c for c in changes if c.kind != "continuous"]
    arm_start = segment_first_start(rec) if has_ap and resting else None
    # the gear between the encoders, fitted once for every continuous change's reversal error
    continuous = len(resting) < len(changes)
    gear = fit_gear(rec) if has_ap and continuous else None
    quantum = encoder_step(rec.data["AP"].to_numpy(dtype=np.float64)) if has_ap else math.nan
    results = []
    estimates: list[tuple[float, float, float, tuple[str, ...]]] = []  # lost, low, high, terms
    axis = _Axis(has_ap, indicator, table, arm_start, gear, quantum, fine)
    for change in changes:
        result, estimate = _change_result(rec, change, axis)
        results.append(result)
        if estimate is not None:
            estimates.append(estimate)
    scores = [r.backlash_score for r in results if r.backlash_score is not None]
    losses = [lost for lost, *_ in estimates]
    axis_lost = resolved_lost_motion(
        float(np.mean(losses)) if losses else None,
        float(np.mean([e[1] for e in estimates])) if estimates else None,
        float(np.mean([e[2] for e in estimates])) if estimates else None, *fine)
    score = float(np.mean(scores)) if scores else None
    reading, spread, reason = _score_reading(score, results, changes, linear, rec, table, has_ap)
    message = _two_encoder_message(results, reading, reason, max_dwell, bool(losses),
                                   bool(segmented.left_out))
    message = "; ".join(m for m in (message, segments_note(segmented)) if m)
    lost_reason = (axis_lost[3] if losses else "no AP" if not has_ap else "no direction change"
                   if not changes else "the arm does not restart")  # fmt: skip
    return BacklashResult(
        units=units.note or None,
        position_unit=units.position,
        path=str(where),
        score_indicator=indicator,
        backlash_score=score,
        score_spread=spread,
        lost_motion=axis_lost[0],
        lost_motion_spread=(float(np.ptp(losses) / 2) if len(losses) > 1
                            and axis_lost[0] is not None else None),
        reversals=tuple(results),
        reading=reading,
        message=message,
        reading_reason=None if reading is not None else reason,
        lost_motion_reason=lost_reason,
        gear=gear,
        gear_parts=gear_parts(rec) if gear is not None else None,
        segments=segmented.segments,
        left_out=segmented.left_out,
        lost_motion_low=axis_lost[1],
        lost_motion_high=axis_lost[2],
        lost_motion_terms=tuple(dict.fromkeys(t for *_, terms in estimates for t in terms)),
    )


#: Seconds either side of a direction change read for the one-encoder signatures.
_AROUND_TURN = 0.1


def _span(low: float, high: float) -> str:
    """``"1.2-3.4"``, or one number where both ends print alike."""
    a, b = f"{low:.3g}", f"{high:.3g}"
    return a if a == b else f"{a}-{b}"


def _one_encoder(
    recording: Recording, where: str, units: Units, max_dwell: float
) -> BacklashResult:
    """The diagnosis of an axis with one measured position (no motor encoder MP).

    The motor-side score and the lost motion between two encoders cannot be computed; what
    the data hold is given at every direction change of the set-point RP (a push on the arm
    moves AP, never RP, so it is no direction change): the following error RP - AP at the
    turn (deg; ``following_error_peak``) and the current's step across it (the mean of AC,
    else RC, in the 0.1 s after the next move starts minus that in the 0.1 s before the move
    before it ends; ``current_step``, in the current's unit).
    """
    rec = recording
    segmented = segment_changes(rec, max_dwell=max_dwell)
    changes = list(segmented.changes)
    t = rec.data.index.to_numpy()
    has_ap = "AP" in rec.data.columns
    current = next((c for c in ("AC", "RC") if c in rec.data.columns), None)
    fe = (rec.data["RP"] - rec.data["AP"]).to_numpy(dtype=np.float64) if has_ap else None
    results = []
    for change in changes:
        values: dict[str, float | None] = {}
        if fe is not None:
            near = (t >= change.stop - _AROUND_TURN) & (t <= change.start + _AROUND_TURN)
            values["following_error_peak"] = (_none(float(np.nanmax(np.abs(fe[near]))))
                                              if near.any() else None)  # fmt: skip
        if current is not None:
            amps = rec.data[current].to_numpy(dtype=np.float64)
            before = (t >= change.stop - _AROUND_TURN) & (t < change.stop)
            after = (t >= change.start) & (t < change.start + _AROUND_TURN)
            values["current_step"] = (
                _none(float(np.nanmean(amps[after]) - np.nanmean(amps[before])))
                if before.any() and after.any() else None
            )
        part = segment_part(rec, change)
        # ``traversed`` reads the gear's torque from the motor's acceleration: not without MP
        results.append(ReversalResult(change, _move_speed(part, change), None, None, values))
    need = "the backlash score and the lost motion need a second encoder (MP, the motor's)"
    found = f"{len(changes)} direction change(s) of the set-point"
    if changes:
        found += " at " + ", ".join(f"{r.change.stop:.2f}" for r in results) + " s"
        peaks = [r.indicators.get("following_error_peak") for r in results]
        peaks_ = [p for p in peaks if p is not None]
        if peaks_:
            k, label = {"deg": (60.0, "arcmin"), "mm": (1000.0, "um")}.get(
                units.position, (60.0, "x 60, unit unknown"))
            found += (f"; following error |RP - AP| there "
                      f"{_span(k * min(peaks_), k * max(peaks_))} {label}")
        steps = [r.indicators.get("current_step") for r in results]
        steps_ = [abs(v) for v in steps if v is not None]
        if steps_ and current is not None:
            unit = unit_of(rec.signals[current])
            found += (f"; {current} steps by {_span(min(steps_), max(steps_))} {unit} "
                      "across a turn")
    message = "; ".join(m for m in (
        f"one measured position per joint ({'AP' if has_ap else 'none'}): {need}", found,
        segments_note(segmented)) if m)
    return BacklashResult(
        path=where, score_indicator="none", backlash_score=None, score_spread=None,
        lost_motion=None, lost_motion_spread=None, reversals=tuple(results), reading=None,
        message=message, reading_reason=need, lost_motion_reason="one encoder per joint, no MP",
        segments=segmented.segments, left_out=segmented.left_out, units=units.note or None,
        position_unit=units.position,
    )


def resolved_lost_motion(lost: float | None, low: float | None, high: float | None,
                         scale: float = 60.0, unit: str = "arcmin",
                         ) -> tuple[float | None, float | None, float | None, str | None]:
    """A lost motion as it may be said: the estimate where its interval lies above 0, else
    none, with 0 and the bound as its interval and the reason.

    A lost motion is never negative; an interval reaching 0 (or below it: the estimator's bias
    beyond its bound) says only that the lost motion is below what the estimate resolves: the
    interval's upper end, or its width where that end is below 0.

    Parameters
    ----------
    lost, low, high : float or None
        deg (mm on a linear axis), the estimate and its interval.
    scale, unit : float, str
        How the reason states the bound: arcmin (60) from deg, um (1000) from mm.

    Returns
    -------
    tuple
        ``(lost_motion, low, high, reason)``; the reason None where resolved (or nothing
        measured).

    Examples
    --------
    >>> resolved_lost_motion(0.01, 0.008, 0.012)
    (0.01, 0.008, 0.012, None)
    >>> lost, low, high, reason = resolved_lost_motion(-0.0015, -0.0018, 0.003)
    >>> lost, low, high, reason
    (None, 0.0, 0.003, 'below what this estimate resolves: <= 0.18 arcmin')
    """
    if lost is None or low is None or high is None:
        return lost, low, high, None
    if low > 0:
        return lost, low, high, None
    bound = high if high > 0 else high - low
    return None, 0.0, bound, (f"below what this estimate resolves: <= {bound * scale:.2g} "
                              f"{unit}")


def _outside(speed: float, rec: Recording, table: Mapping[str, Any], has_ap: bool) -> str | None:
    """Why a score cannot be read on the calibration (None when it can): the trace's speed
    outside the calibrated speeds, or (without AP, where the score reads the current) a current
    signal that is not a current."""
    speeds = sorted(float(s) for s in table["levels"])
    # 5 % either side: the calibration's keys are the sweep's peak speeds rounded to 0.1 deg/min
    if not (min(speeds) / 1.05 <= speed <= max(speeds) * 1.05):
        return (
            f"the trace's {speed:.0f} deg/min is outside the calibrated speeds "
            f"{min(speeds):g}-{max(speeds):g} deg/min"
        )
    if not has_ap:
        name = torque_column(rec)
        units = rec.signals[name].units_type if name in rec.signals else None
        if units not in (None, "current"):
            return f"{name} is a {units} signal; the calibration was made on a current (A)"
    return None


def diagnose_backlash(
    *paths: str | os.PathLike[str],
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
    axis: int | None = None,
    calibration: Mapping[str, Any] | None = None,
    max_dwell: float = MAX_DWELL,
) -> list[BacklashResult]:
    """Diagnose backlash in traces of one axis, each on its own.

    Parameters
    ----------
    *paths : path-like
        Traces (:func:`funcnet.robot.read_trace`); a trace over time each for a trend.
    channels, axis
        As for :func:`funcnet.robot.read_trace`.
    calibration : mapping, optional
        Default: the calibration shipped with the package (:func:`load_calibration`).
    max_dwell : float
        Longest standstill (s) between two moves of a reversal.

    Returns
    -------
    list of BacklashResult
        One per path (per axis of a file of several read without ``axis``), in order. A trace
        without a direction change is a result (``message`` says so), not an error.

    Raises
    ------
    ParameterError
        No path.
    TraceError, ChannelError
        A trace cannot be read, or has no RP or MP.

    References
    ----------
    Paper section 5.1 (reversal signature, diagnosis without additional sensors).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from funcnet.sim import Trial, simulate_trial, write_trace
    >>> sim = simulate_trial(Trial("rev", "s", speed=175, tcp=1.6, step=1, reverse=True,
    ...                            backlash=2 / 60, sensors="real", seed=1))
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rev.xml"
    >>> _ = write_trace(path, sim.data, intervals={"AP": 0.004, "MP": 0.004})
    >>> result, = diagnose_backlash(path)
    >>> len(result.reversals), result.backlash_score > 0.02
    (1, True)
    >>> abs(result.lost_motion / sim.truth["lost_motion"] - 1) < 0.1
    True
    """
    if not paths:
        raise ParameterError.of("paths", "give at least one trace")
    cal = load_calibration() if calibration is None else calibration
    # a set-point that never moves is kept: an axis at rest is a result, not a missing RP
    recordings = [(path, read_trace(path, channels=channels, axis=axis, keep_setpoint=True))
                  for path in paths]
    return [
        replace(diagnose_recording(rec if n is None else rec.for_axis(n), str(path),
                                   calibration=cal, max_dwell=max_dwell), axis=n)
        for path, rec in recordings for n in rec.axes or (None,)
    ]
