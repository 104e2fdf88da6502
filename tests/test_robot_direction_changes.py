"""Direction changes of the set-point: after a standstill and in continuous motion."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import scipy.io

from conftest import shipped
from funcnet.errors import ChannelError, ParameterError
from funcnet.robot.grid import mask_runs
from funcnet.robot.phases import (
    SetpointTurn,
    detect_phases,
    direction_changes,
    merge_runs,
    move_threshold,
)
from funcnet.robot.recording import Recording, SignalInfo

DT = 0.004


def recording_of(rp: np.ndarray, dt: float = DT) -> Recording:
    t = np.round(np.arange(rp.size) * dt, 9)
    data = pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time"))
    return Recording(data, {}, {"RP": SignalInfo("RP", "posn", None, dt)}, sample_period=dt)


def expected_changes(time: np.ndarray, rp: np.ndarray, min_speed: float) -> list[tuple]:
    """The definition, computed plainly: the speed changes sign between two stretches where it
    exceeds ``min_speed``; returns (end of the stretch before, start of the one after, sign)."""
    v = np.gradient(rp, time)
    stretches = []  # (first index, last index, sign)
    for i, value in enumerate(v):
        sign = 1 if value > min_speed else -1 if value < -min_speed else 0
        if sign == 0:
            continue
        if stretches and stretches[-1][2] == sign and stretches[-1][1] == i - 1:
            stretches[-1][1] = i
        else:
            stretches.append([i, i, sign])
    return [
        (time[a[1]], time[b[0]], b[2])
        for a, b in zip(stretches, stretches[1:], strict=False)
        if a[2] != b[2]
    ]


def kuka_axes():
    for run in "AB":
        path = shipped("kuka-kr300", f"kr300-run-{run}.mat")
        rec = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["rec"]
        for axis in range(6):
            yield run, axis + 1, np.asarray(rec.time_cont, float), np.asarray(
                rec.ref_pos_deg[axis], float
            )


@pytest.mark.parametrize("min_speed", [1.0, None])
def test_every_direction_change_of_both_kuka_runs_is_found(min_speed):
    total = 0
    for run, axis, time, rp in kuka_axes():
        expected = expected_changes(time, rp, 1.0)
        found = direction_changes(recording_of(rp), min_speed=min_speed)
        where = f"run {run} axis {axis}"
        assert len(found) == len(expected), (where, expected, found)
        for (end, begin, sign), turn in zip(expected, found, strict=True):
            assert end - 0.1 <= turn.time <= begin + 0.1, (where, end, begin, turn)
            assert turn.direction == sign, where
            assert turn.stop <= turn.time <= turn.start, where
            # continuous motion: the set-point never rests at these turns
            assert turn.dwell <= 2 * DT, where
        total += len(expected)
    # 1-4 per axis, as the recordings' README says: 11 in run A, 16 in run B; none is one-way
    assert total == 27


def sine_recording(periods: float, amplitude: float = 30.0, period: float = 4.0):
    t = np.arange(0, periods * period, DT)
    return recording_of(amplitude * np.sin(2 * np.pi * t / period))


def test_a_sinusoid_turns_at_its_extremes():
    turns = direction_changes(sine_recording(2.5), min_speed=1.0)
    # closed form: the extremes of sin(2 pi t / 4) at t = 1, 3, 5, 7, 9
    np.testing.assert_allclose([c.time for c in turns], [1, 3, 5, 7, 9], atol=DT / 2)
    assert [c.direction for c in turns] == [-1, 1, -1, 1, -1]
    assert all(c.dwell <= DT and c.threshold == 1.0 for c in turns)
    # the bracket: |v| = 30 (pi/2) |cos| falls to 1 deg/s 1/(30 pi^2 / 4) s... within a tick
    half = np.arcsin(1.0 / (30 * np.pi / 2)) / (np.pi / 2)
    for c in turns:
        assert c.time - c.stop == pytest.approx(half, abs=1.5 * DT)
        assert c.start - c.time == pytest.approx(half, abs=1.5 * DT)


def test_several_reversals_of_unequal_size_within_one_move():
    t = np.arange(0, 10, DT)
    # a smooth multi-reversal excitation: two harmonics, windowed to rest at both ends
    window = np.sin(np.pi * t / 10) ** 2
    rp = window * (20 * np.sin(2 * np.pi * t / 5) + 8 * np.sin(2 * np.pi * t / 1.7))
    found = direction_changes(recording_of(rp), min_speed=1.0)
    expected = expected_changes(t, rp, 1.0)
    assert len(expected) >= 4
    assert len(found) == len(expected)
    for (end, begin, sign), turn in zip(expected, found, strict=True):
        assert end <= turn.time <= begin and turn.direction == sign
        # the turn is the position's extreme between the stretches
        inside = (t >= end) & (t <= begin)
        extreme = t[inside][np.argmax(-sign * rp[inside])]
        assert turn.time == pytest.approx(extreme, abs=DT)


def test_a_wiggle_below_the_threshold_is_no_direction_change():
    t = np.arange(0, 6, DT)
    bump = lambda centre, width: np.exp(-(((t - centre) / width) ** 2))  # noqa: E731
    for wiggle in (0.8, 0.5):
        # one way at up to 12 deg/s, a wiggle back, then on the same way
        v = 12 * bump(1.5, 0.4) - wiggle * bump(3.0, 0.2) + 12 * bump(4.5, 0.4)
        rec = recording_of(np.cumsum(v) * DT)
        assert np.gradient(rec.data["RP"].to_numpy(), DT).min() < -0.9 * wiggle  # it goes back
        assert direction_changes(rec, min_speed=1.0) == []
        # read with a threshold below the wiggle, the same motion has two changes
        assert [c.direction for c in direction_changes(rec, min_speed=0.3)] == [-1, 1]
    # the default threshold, 5 % of the peak speed (0.6 deg/s here), is above the smaller one
    assert direction_changes(rec) == []


def test_a_trapezoid_with_dwell_turns_in_the_middle_of_its_rest():
    # out at 10 deg/s (1 s ramps), rest 0.3 s, back
    knots = [0, 0.5, 1.5, 2.5, 3.5, 3.8, 4.8, 5.8, 6.8, 7.5]
    speeds = [0, 0, 10, 10, 0, 0, -10, -10, 0, 0]
    t = np.arange(0, 7.5, DT)
    rp = np.cumsum(np.interp(t, knots, speeds)) * DT
    (turn,) = direction_changes(recording_of(rp), min_speed=1.0)
    assert turn.time == pytest.approx(3.65, abs=DT)
    assert turn.direction == -1
    assert turn.dwell == pytest.approx(0.3, abs=3 * DT)
    # 1 deg/s is reached 0.1 s from the rest on both sides
    assert turn.stop == pytest.approx(3.4, abs=2 * DT)
    assert turn.start == pytest.approx(3.9, abs=2 * DT)
    assert turn.to_dict()["direction"] == -1 and isinstance(turn, SetpointTurn)


def test_one_way_and_standstill_have_none_and_bad_input_raises():
    t = np.arange(0, 2, DT)
    assert direction_changes(recording_of(5 * t**2)) == []
    assert direction_changes(recording_of(np.ones(50))) == []
    rec = sine_recording(1)
    for bad in ({"min_speed": 0.0}, {"min_speed": float("nan")}, {"relative": 1.5}):
        with pytest.raises(ParameterError):
            direction_changes(rec, **bad)
    with pytest.raises(ChannelError):
        direction_changes(rec, reference="AP")


# --------------------------------------------------------------------------------------------
# phases of continuous motion


def phases_of(rec: Recording, **options) -> pd.DataFrame:
    return detect_phases(rec, **options)


def phase_at(table: pd.DataFrame, time: float) -> str:
    row = table[(table["start"] <= time) & (time < table["stop"])]
    return str(row["phase"].iloc[0])


def assert_phases_read_the_motion(table, t, rp, changes, where):
    """Each direction change inside its own reversal phase; no other phase moves both ways
    faster than 1 deg/s; cruise holds the speed within 2 % of a local peak; spin-up speeds up
    and braking slows down; the table covers the recording."""
    assert table["start"].iloc[0] == 0.0, where
    np.testing.assert_array_equal(table["stop"].iloc[:-1], table["start"].iloc[1:])
    reversals = table[table["phase"] == "reversal"]
    assert len(reversals) == len(changes), (where, reversals, changes)
    v = np.gradient(rp, t)
    for (end, begin, _), row in zip(changes, reversals.itertuples(), strict=True):
        # the set-point's turn (its extreme between the two stretches) inside the reversal
        inside = (t >= end) & (t <= begin)
        extreme = t[inside][np.argmax(np.abs(rp[inside] - rp[inside][0]))]
        assert row.start <= extreme < row.stop, (where, extreme, row)
    for row in table.itertuples():
        part = (t >= row.start) & (t < row.stop)
        if row.phase != "reversal":
            assert not (v[part].max() > 1 and v[part].min() < -1), (where, row)
        speed = np.abs(v[part])
        if row.phase == "cruise":
            assert speed.min() >= 0.97 * speed.max(), (where, row)
        if row.phase in ("early spin-up", "late spin-up") and part.sum() > 2:
            assert speed[-1] > speed[0], (where, row)
        if row.phase == "braking" and part.sum() > 2:
            assert speed[-1] < speed[0], (where, row)


def test_phases_of_every_kuka_axis_read_the_continuous_motion():
    for run, axis, time, rp in kuka_axes():
        t = np.round(np.arange(rp.size) * DT, 9)
        table = detect_phases(recording_of(rp))
        changes = expected_changes(time, rp, 1.0)
        assert_phases_read_the_motion(table, t, rp, changes, f"run {run} axis {axis}")


def test_axis_1_of_run_a_out_and_back():
    # 0 -> 46 deg -> 0 with the direction change at 4.9 s: no braking through the turn
    (_, _, time, rp), *_ = kuka_axes()
    table = detect_phases(recording_of(rp))
    moving = table[table["phase"] != "standstill"]["phase"].tolist()
    assert moving == ["early spin-up", "late spin-up", "cruise", "braking", "reversal",
                      "late spin-up", "cruise", "braking"]
    assert phase_at(table, 4.9) == "reversal"
    # cruise at each peak speed: 25 deg/s out, 23 deg/s back
    v = np.gradient(rp, time)
    for row in table[table["phase"] == "cruise"].itertuples():
        part = (time >= row.start) & (time < row.stop)
        assert np.abs(v[part]).max() == pytest.approx(
            np.abs(v[(time < 4.9) if row.start < 4.9 else (time > 4.9)]).max(), rel=0.01
        )


def test_phases_of_a_windowed_multi_reversal_motion():
    t = np.arange(0, 10, DT)
    window = np.sin(np.pi * t / 10) ** 2
    rp = window * (20 * np.sin(2 * np.pi * t / 5) + 8 * np.sin(2 * np.pi * t / 1.7))
    table = detect_phases(recording_of(rp))
    assert_phases_read_the_motion(table, t, rp, expected_changes(t, rp, 1.0), "windowed")


def test_a_dip_between_two_humps_cuts_the_move_without_a_reversal():
    t = np.arange(0, 6, DT)
    bump = lambda centre, width: np.exp(-(((t - centre) / width) ** 2))  # noqa: E731
    v = 12 * bump(1.5, 0.4) + 1.5 + 12 * bump(4.5, 0.4)  # slows to ~1.5 deg/s, never rests
    v = v * np.clip(t / 0.5, 0, 1) * np.clip((6 - t) / 0.5, 0, 1)
    rp = np.cumsum(v) * DT
    table = detect_phases(recording_of(rp))
    phases = table["phase"].tolist()
    assert "reversal" not in phases and phases.count("cruise") == 2
    assert "standstill" not in phases[1:-1]
    assert phase_at(table, 3.0) in ("braking", "late spin-up")
    assert phases.count("early spin-up") == 1  # only the start from rest
    assert_phases_read_the_motion(table, t, rp, [], "dip")
    # without the dip rule (dip close to 0), one cruise spans both humps and the slow middle
    one = detect_phases(recording_of(rp), dip=1e-6)["phase"].tolist()
    assert one.count("cruise") == 1


def test_a_wiggle_below_the_threshold_makes_no_reversal():
    t = np.arange(0, 6, DT)
    bump = lambda centre, width: np.exp(-(((t - centre) / width) ** 2))  # noqa: E731
    v = 12 * bump(1.5, 0.4) - 0.5 * bump(3.0, 0.2) + 12 * bump(4.5, 0.4)
    rp = np.cumsum(v) * DT
    table = detect_phases(recording_of(rp))
    assert "reversal" not in table["phase"].tolist()
    assert table["phase"].tolist().count("cruise") == 2
    # a threshold below the wiggle reads it as two direction changes
    slow = detect_phases(recording_of(rp), min_speed=0.3)["phase"].tolist()
    assert slow.count("reversal") == 2


def test_a_trapezoid_with_dwell_keeps_the_point_to_point_phases():
    knots = [0, 0.5, 1.5, 2.5, 3.5, 3.8, 4.8, 5.8, 6.8, 7.5]
    speeds = [0, 0, 10, 10, 0, 0, -10, -10, 0, 0]
    t = np.arange(0, 7.5, DT)
    rp = np.cumsum(np.interp(t, knots, speeds)) * DT
    table = detect_phases(recording_of(rp))
    assert table["phase"].tolist() == [
        "standstill", "early spin-up", "late spin-up", "cruise", "braking", "reversal",
        "late spin-up", "cruise", "braking", "standstill",
    ]
    reversal = table[table["phase"] == "reversal"].iloc[0]
    # from half speed down (3.0 s) to half speed up (4.3 s), the 0.3 s rest included
    assert reversal["start"] == pytest.approx(3.0, abs=2 * DT)
    assert reversal["stop"] == pytest.approx(4.3, abs=2 * DT)
    cruise = table[table["phase"] == "cruise"].iloc[0]
    assert cruise["start"] == pytest.approx(1.5 - 0.02, abs=2 * DT)  # 98 % of 10 deg/s
    assert cruise["stop"] == pytest.approx(2.5 + 0.02, abs=2 * DT)


def test_turn_threshold_checks():
    rec = sine_recording(1)
    for bad in ({"min_speed": -1.0}, {"relative": 0.0}, {"dip": 1.0}):
        with pytest.raises(ParameterError, match=next(iter(bad))):
            detect_phases(rec, **bad)


def test_runs_and_their_merging_match_a_plain_loop():
    rng = np.random.default_rng(5)
    for _ in range(50):
        signed = rng.choice([-1.0, 0.0, 1.0], size=60, p=[0.3, 0.4, 0.3])
        runs = mask_runs(signed != 0)
        # plain: the ticks that move, grouped where consecutive
        moving = [i for i in range(signed.size) if signed[i] != 0]
        plain = []
        for i in moving:
            if plain and plain[-1][1] == i:
                plain[-1][1] = i + 1
            else:
                plain.append([i, i + 1])
        assert [(int(a), int(b)) for a, b in runs] == [tuple(r) for r in plain]
        for max_gap, period in ((3, 1.0), (0.01, DT)):
            merged = [list(r) for r in plain[:1]]
            for a, b in plain[1:]:
                same = np.sign(signed[merged[-1][0]:merged[-1][1]].sum()) == np.sign(
                    signed[a:b].sum())
                # a gap of fewer than 3 ticks merges in both settings: 3 ticks, and 0.01 s
                # at 4 ms (2.5 ticks)
                if same and (a - merged[-1][1]) < 3:
                    merged[-1][1] = b
                else:
                    merged.append([a, b])
            assert [(int(a), int(b)) for a, b in merge_runs(runs, signed, max_gap, period)] == [
                tuple(r) for r in merged
            ]


def test_the_move_threshold_is_1_deg_per_s_or_half_the_peak():
    assert move_threshold(np.array([0.0, 4.0, -3.0])) == 1.0
    assert move_threshold(np.array([0.1, -1.5, np.nan])) == 0.75
    assert move_threshold(np.array([0.1, -1.5]), min_speed=0.5) == 0.5
    assert move_threshold(np.array([np.nan, np.nan])) == 0.0
