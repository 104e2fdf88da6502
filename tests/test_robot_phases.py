"""Motion phases from the reference motion, and phases given by hand."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ChannelError, ParameterError, SignalError
from funcnet.robot.io.read import read_trace
from funcnet.robot.phases import PHASES, detect_phases, phase_table
from funcnet.robot.recording import Recording, SignalInfo

DT = 0.002
A, TJ, TA = 2.0, 0.2, 0.3  # acceleration, jerk time, constant-acceleration time
VC = A * (TJ + TA)  # cruise speed


def move_acceleration(t0: float, cruise: float, sign: float = 1.0) -> tuple[list, list]:
    """Breakpoints of a jerk-limited move's acceleration starting at t0."""
    ramp = [0, TJ, TJ + TA, 2 * TJ + TA]
    up = [t0 + r for r in ramp]
    down_start = up[-1] + cruise
    down = [down_start + r for r in ramp]
    return up + down, [0, sign * A, sign * A, 0, 0, -sign * A, -sign * A, 0]


def recording_of(times: list, accel: list, duration: float) -> Recording:
    t = np.round(np.arange(0, duration, DT), 9)
    acc = np.interp(t, times, accel)
    speed = np.cumsum(acc) * DT
    rp = np.cumsum(speed) * DT
    data = pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time"))
    return Recording(data, {}, {"RP": SignalInfo("RP", "posn", "double", DT)}, source="sim.xml")


def rows(table: pd.DataFrame) -> list[str]:
    return table["phase"].tolist()


def test_jerk_limited_move_boundaries_match_the_closed_form():
    times, accel = move_acceleration(1.0, cruise=1.0)
    table = detect_phases(recording_of(times, accel, 5.0))
    assert rows(table) == [
        "standstill",
        "early spin-up",
        "late spin-up",
        "cruise",
        "braking",
        "standstill",
    ]
    start = dict(zip(table["phase"], table["start"], strict=False))
    # Early spin-up ends when the acceleration reaches 95 % of A: 0.95 TJ after the start.
    assert start["late spin-up"] == pytest.approx(1.0 + 0.95 * TJ, abs=3 * DT)
    # Cruise starts when v = 0.98 VC in the jerk-down ramp: VC - v = A s^2 / (2 TJ).
    s = math.sqrt(0.02 * VC * 2 * TJ / A)
    assert start["cruise"] == pytest.approx(1.0 + 2 * TJ + TA - s, abs=3 * DT)
    braking_start = 1.0 + 2 * TJ + TA + 1.0
    assert start["braking"] == pytest.approx(braking_start + s, abs=3 * DT)
    # Motion starts when v first exceeds 1e-4 VC: A t^2 / (2 TJ) = 1e-4 VC.
    assert start["early spin-up"] == pytest.approx(1.0 + math.sqrt(2e-4 * VC * TJ / A), abs=3 * DT)
    # The table covers the recording without gaps.
    assert table["start"].iloc[0] == 0.0 and table["stop"].iloc[-1] == pytest.approx(5.0)
    np.testing.assert_array_equal(table["stop"].iloc[:-1], table["start"].iloc[1:])


def forward_and_back(dwell: float) -> Recording:
    t1, a1 = move_acceleration(0.5, cruise=0.5)
    t2, a2 = move_acceleration(t1[-1] + dwell, cruise=0.5, sign=-1.0)
    return recording_of(t1 + t2, a1 + a2, t2[-1] + 0.5)


def test_reversal_between_opposite_moves():
    rec = forward_and_back(dwell=0.1)
    table = detect_phases(rec)
    assert rows(table) == [
        "standstill",
        "early spin-up",
        "late spin-up",
        "cruise",
        "braking",
        "reversal",
        "late spin-up",
        "cruise",
        "braking",
        "standstill",
    ]
    reversal = table[table["phase"] == "reversal"].iloc[0]
    speed = np.abs(np.gradient(rec.data["RP"].to_numpy(), DT))
    inside = (rec.data.index >= reversal["start"]) & (rec.data.index < reversal["stop"])
    # Inside the reversal the reference is slower than half its cruise speed, and it changes sign.
    assert speed[inside].max() <= 0.5 * VC * 1.01
    v = np.gradient(rec.data["RP"].to_numpy(), DT)[inside]
    assert v[0] > 0 > v[-1]
    # It is bounded by where the speed crosses 0.5 VC: half-way down the braking, in closed form
    # the jerk-limited profile passes 0.5 VC in the middle of its constant-deceleration ramp.
    half_speed_time = 0.5 + 2 * (2 * TJ + TA) + 0.5 - (TJ + TA / 2)
    assert reversal["start"] == pytest.approx(half_speed_time, abs=3 * DT)


def test_long_dwell_is_no_reversal_unless_allowed():
    rec = forward_and_back(dwell=1.0)
    assert "reversal" not in rows(detect_phases(rec))
    assert "reversal" in rows(detect_phases(rec, reversal_dwell=1.5))


def test_same_direction_moves_are_no_reversal():
    t1, a1 = move_acceleration(0.5, cruise=0.5)
    t2, a2 = move_acceleration(t1[-1] + 0.05, cruise=0.5)
    table = detect_phases(recording_of(t1 + t2, a1 + a2, t2[-1] + 0.5))
    assert "reversal" not in rows(table) and rows(table).count("cruise") == 2


def test_real_trace_phases(real_trace):
    rec = read_trace(real_trace)
    table = detect_phases(rec)
    moving = ["early spin-up", "late spin-up", "cruise", "braking"]
    assert rows(table) == [
        "standstill",
        *moving,
        "standstill",
        *moving,
        "standstill",
        *moving,
        "standstill",
    ]
    rp = rec.data["RP"]
    for row in table.itertuples():
        part = rp[(rp.index >= row.start) & (rp.index < row.stop - 1e-9)]
        if row.phase == "standstill":
            assert part.nunique() == 1, row
        if row.phase == "cruise":
            slope = np.abs(np.diff(part.to_numpy())) / 0.002
            np.testing.assert_allclose(slope, 108.0, rtol=0.03)
    # The first motion starts where RP first changes (6.408 s; the smoothing of Eq. 12 looks
    # one tick ahead).
    assert table.loc[1, "start"] == pytest.approx(6.408, abs=0.0021)


def test_threshold_checks_and_missing_reference():
    rec = forward_and_back(dwell=0.1)
    for name in ("standstill", "cruise", "early", "reversal"):
        with pytest.raises(ParameterError, match=name):
            detect_phases(rec, **{name: 1.5})
    with pytest.raises(ParameterError, match="reversal_dwell"):
        detect_phases(rec, reversal_dwell=-1)
    with pytest.raises(ChannelError, match="sim.xml.*'AP'"):
        detect_phases(rec, reference="AP")
    gap = rec.data.copy()
    gap.iloc[0, 0] = np.nan
    with pytest.raises(SignalError, match="RP has no value at 0 s"):
        detect_phases(Recording(gap, {}, rec.signals, source="sim.xml"))


def test_standing_still_is_one_phase():
    data = pd.DataFrame({"RP": np.ones(10)}, index=pd.Index(np.arange(10) * 0.002, name="time"))
    rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.002)})
    assert rows(detect_phases(rec)) == ["standstill"]


def test_phase_table_by_hand():
    expected = pd.DataFrame(
        {"phase": ["early spin-up", "cruise"], "start": [0.0, 1.0], "stop": [0.22, 5.0]}
    )
    given = [
        {"early spin-up": (0, 0.22), "cruise": (1, 5)},
        [("early spin-up", 0, 0.22), ("cruise", 1, 5)],
        expected,
    ]
    for phases in given:
        pd.testing.assert_frame_equal(phase_table(phases), expected, check_dtype=False)
    for bad, match in [
        ({"cruise": (5, 1)}, "start < stop"),
        ([("cruise", 1)], "not \\(phase, start, stop\\)"),
        ([("", 0, 1)], "needs a phase name"),
        ([("cruise", "soon", 1)], "not a number"),
        (pd.DataFrame({"phase": ["x"]}), "lacks the columns"),
    ]:
        with pytest.raises(ParameterError, match=match):
            phase_table(bad)
    assert PHASES[0] == "standstill"


def test_a_slow_move_written_with_finite_decimals_is_one_move():
    # At 1 deg/min a set-point written with 6 decimals stands still for a few ticks while it
    # creeps off its start and onto its target; those ticks must not split the move.
    times, accel = move_acceleration(1.0, cruise=2.0)
    rec = recording_of(times, accel, 6.0)
    slow = rec.data["RP"] * (1.0 / 60.0) / VC  # scale the cruise speed to 1 deg/min
    quantized = Recording(
        pd.DataFrame({"RP": np.round(slow.to_numpy(), 6)}, index=rec.data.index),
        {},
        rec.signals,
        source="slow.xml",
    )
    # the split it fixes (with a turn threshold below the creep, which is otherwise no move)
    assert rows(detect_phases(quantized, min_gap=0.0, relative=1e-3)).count("cruise") > 1
    table = detect_phases(quantized)
    assert rows(table) == [
        "standstill",
        "early spin-up",
        "late spin-up",
        "cruise",
        "braking",
        "standstill",
    ]
