"""The backlash diagnosis of a recording with gaps: read segment by segment, nothing across a gap,
a direction change with a gap within what is read around it left out and said.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.diagnosis import diagnose_backlash, diagnose_recording, write_results
from funcnet.diagnosis.reversal_error import _blocks, fit_gear
from funcnet.robot import Recording, SignalInfo, read_trace
from funcnet.sim import Trial, simulate_trial

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

ROLES = ["RP", "AP", "MP", "RC", "AC"]


@pytest.fixture(scope="module")
def reverse_trial() -> pd.DataFrame:
    """Forward 1 deg and back with 2 arcmin of backlash: one reversal at 1.8 s, at rest from
    3.5 s to 5 s."""
    sim = simulate_trial(Trial("rev", "s", speed=175, tcp=1.6, step=1, reverse=True,
                               backlash=2 / 60, sensors="real", seed=3))  # fmt: skip
    return sim.data.round(6).reset_index()


@pytest.fixture(scope="module")
def smooth_trial() -> pd.DataFrame:
    """Out and back twice along smooth curves: three turns without a rest, at 0.64, 1.18 and
    1.72 s."""
    sim = simulate_trial(Trial("smooth", "s", speed=175, tcp=1.6, step=1, profile="smooth",
                               backlash=2 / 60, sensors="real", seed=1))  # fmt: skip
    return sim.data.round(6).reset_index()


def _csv(frame: pd.DataFrame, path: Path, gap: tuple[float, float] | None = None) -> Path:
    """The trial as a CSV file, its rows in ``gap`` left empty."""
    frame = frame.copy()
    if gap is not None:
        frame.loc[(frame["time"] >= gap[0]) & (frame["time"] < gap[1]), ROLES] = np.nan
    frame.to_csv(path, index=False)
    return path


def _changes(result):
    return [(r.change.kind, r.change.stop, r.change.start, r.change.direction, r.change.turn)
            for r in result.reversals]  # fmt: skip


def _inside(a: float, b: float, gap: tuple[float, float]) -> bool:
    return a < gap[1] and b > gap[0]


@pytest.mark.parametrize("gap", [(0.5, 0.6), (3.35, 3.45), (4.0, 4.3)],
                         ids=["in the move out", "in the move back", "at rest"])  # fmt: skip
def test_a_gap_away_from_the_reversal_leaves_it_and_its_lost_motion(tmp_path, reverse_trial, gap):
    (whole,) = diagnose_backlash(_csv(reverse_trial, tmp_path / "whole.csv"))
    (cut,) = diagnose_backlash(_csv(reverse_trial, tmp_path / "cut.csv", gap))
    assert _changes(whole) == [("reversal", 1.798, 1.806, -1, None)]
    assert _changes(cut) == _changes(whole)
    assert cut.lost_motion == pytest.approx(whole.lost_motion, rel=0.02)
    assert cut.backlash_score == pytest.approx(whole.backlash_score, rel=0.02)
    assert cut.reading is not None and cut.reading["arcmin_low"] <= 2 <= cut.reading["arcmin_high"]
    assert cut.segments == ((0.0, gap[0]), (gap[1], 5.002)) and cut.left_out == ()
    assert f"read in 2 segments, values missing at {gap[0]:g}-{gap[1]:g} s" in cut.message
    assert whole.segments == () and "segment" not in whole.message


@pytest.mark.parametrize("gap", [(0.2, 0.25), (2.1, 2.15)],
                         ids=["before the first turn", "after the last turn"])  # fmt: skip
def test_a_gap_away_from_the_continuous_turns_leaves_them_and_the_reversal_error(
    tmp_path, smooth_trial, gap
):
    (whole,) = diagnose_backlash(_csv(smooth_trial, tmp_path / "whole.csv"))
    (cut,) = diagnose_backlash(_csv(smooth_trial, tmp_path / "cut.csv", gap))
    assert [c[0] for c in _changes(whole)] == ["continuous"] * 3
    assert _changes(cut) == _changes(whole)
    assert cut.lost_motion == pytest.approx(whole.lost_motion, rel=0.02)
    for r, w in zip(cut.reversals, whole.reversals, strict=True):
        assert r.lost_motion == pytest.approx(w.lost_motion, rel=0.03)
        assert r.lost_motion_low < r.lost_motion < r.lost_motion_high
    # the gear is fitted over both segments: the samples in the gap are all it lacks
    assert cut.gear is not None and whole.gear is not None
    t = smooth_trial["time"].to_numpy()
    mp = smooth_trial["MP"].to_numpy()
    fast_in_gap = int(np.sum((np.abs(np.gradient(mp, t)) > 1.0) & (t >= gap[0]) & (t < gap[1])))
    assert whole.gear.samples - cut.gear.samples == pytest.approx(fast_in_gap, abs=2)
    assert cut.gear.compliance == pytest.approx(whole.gear.compliance, rel=0.05)


def test_a_gap_in_the_stretch_before_a_turn_leaves_that_turn_out_and_says_so(
    tmp_path, smooth_trial
):
    gap = (1.0, 1.05)  # in the 0.25 s before the second turn's stretch starts (1.118 s)
    (whole,) = diagnose_backlash(_csv(smooth_trial, tmp_path / "whole.csv"))
    path = _csv(smooth_trial, tmp_path / "cut.csv", gap)
    (cut,) = diagnose_backlash(path)
    second = whole.reversals[1].change
    assert _changes(cut) == [c for k, c in enumerate(_changes(whole)) if k != 1]
    (left,) = cut.left_out
    assert (left.stop, left.start, left.gap, left.across) == (second.stop, second.start, gap,
                                                             False)  # fmt: skip
    assert (f"1 direction change left out, a gap within what is read around it: "
            f"{second.stop:g}-{second.start:g} s (gap 1-1.05 s)") in cut.message
    assert "2 in continuous motion" in cut.message
    # no stretch read at a change kept lies in the gap
    assert not any(_inside(r.change.stop - 0.25, r.change.start + 0.25, gap)
                   for r in cut.reversals)  # fmt: skip
    # the JSON says the segments and what was left out
    (entry,) = json.loads(write_results([cut], tmp_path / "r.json").read_text())["traces"]
    assert entry["segments"] == [[0.0, 1.0], [1.05, 3.758]]
    assert entry["left_out"] == [{"stop": second.stop, "start": second.start,
                                  "gap": [1.0, 1.05], "across": False}]  # fmt: skip
    (plain,) = json.loads(write_results([whole], tmp_path / "w.json").read_text())["traces"]
    assert "segments" not in plain and "left_out" not in plain


def test_a_turn_within_a_gap_is_left_out_as_across(tmp_path, smooth_trial):
    gap = (1.15, 1.2)  # the second turn, at 1.178 s
    (cut,) = diagnose_backlash(_csv(smooth_trial, tmp_path / "cut.csv", gap))
    assert [round(r.change.turn, 3) for r in cut.reversals] == [0.638, 1.716]
    (left,) = cut.left_out
    assert left.across and left.gap == gap and left.stop <= gap[0] and left.start >= gap[1]
    assert f"(turns within {gap[0]:g}-{gap[1]:g} s)" in cut.message


def test_a_gap_near_the_reversal_leaves_no_reversal_and_says_why(tmp_path, reverse_trial):
    gap = (1.0, 1.1)  # within the second before the reversal, which the motor hysteresis reads
    (cut,) = diagnose_backlash(_csv(reverse_trial, tmp_path / "cut.csv", gap))
    assert cut.reversals == () and cut.backlash_score is None and cut.lost_motion is None
    assert cut.message.startswith("no direction change read; ")
    assert "moves one way only" not in cut.message
    assert "1 direction change left out" in cut.message and "(gap 1-1.1 s)" in cut.message


def test_the_command_line_reads_the_segments(tmp_path, reverse_trial):
    path = _csv(reverse_trial, tmp_path / "cut.csv", (3.35, 3.45))
    result = CliRunner().invoke(app, ["backlash", str(path), "--quiet"])
    assert result.exit_code == 0, result.output
    first = result.stdout.splitlines()[0]
    assert first.startswith(f"{path}: 1 reversal(s); ")
    assert first.endswith("; read in 2 segments, values missing at 3.35-3.45 s (nothing read "
                          "across a gap)")
    assert "lost_motion" in result.stdout.splitlines()[1]


def test_the_inspect_page_shows_the_diagnosis(tmp_path, reverse_trial):
    from funcnet.inspection import inspect_recording
    from funcnet.report.inspect import write_inspection

    path = _csv(reverse_trial, tmp_path / "cut.csv", (3.35, 3.45))
    ins = inspect_recording(read_trace(path), evidence=False)
    assert ins.backlash is not None and ins.backlash_error == ""
    html = write_inspection(ins, tmp_path / "page").read_text(encoding="utf-8")
    section = html[html.index('<section id="backlash">'):]
    section = re.sub(r"<[^>]+>", " ", section[:section.index("</section>")])
    assert "No diagnosis" not in section
    assert "1 reversal(s)" in section and "read in 2 segments" in section


def test_a_recording_without_gaps_is_diagnosed_as_a_window_of_it(reverse_trial):
    """A segment of a gapped recording is diagnosed as the same span cut out without a gap."""
    data = reverse_trial.set_index("time")
    data.index = pd.Index(data.index.to_numpy(dtype=np.float64), name="time")
    info = {c: SignalInfo(c, "posn" if c in ("RP", "AP", "MP") else "current", None, 0.002)
            for c in ROLES}  # fmt: skip
    gapped = data.copy()
    gapped.loc[(gapped.index >= 3.35) & (gapped.index < 3.45)] = np.nan
    rec = Recording(gapped, {}, info, sample_period=0.002, gaps=((3.35, 3.45),))
    first = Recording(data.loc[:3.3499], {}, info, sample_period=0.002)
    cut, alone = diagnose_recording(rec, "r"), diagnose_recording(first, "r")
    # the reversal and what is read there come from the first segment alone
    (r,), (a,) = cut.reversals, alone.reversals
    assert r.change == a.change and r.indicators == a.indicators and r.speed == a.speed
    assert r.lost_motion == a.lost_motion


def test_bootstrap_blocks_stay_within_their_segment():
    rng = np.random.default_rng(0)
    n, size = 300, 13
    # one segment: the plain circular draw, the same indices from the same seed
    np.testing.assert_array_equal(_blocks(np.random.default_rng(4), n, size),
                                  _blocks(np.random.default_rng(4), n, size, np.array([0])))
    firsts = np.array([0, 40, 41, 200])  # a segment of one sample among them
    segment = np.searchsorted(firsts, np.arange(n), side="right") - 1
    for _ in range(20):
        rows = _blocks(rng, n, size, firsts)
        assert rows.size == n and rows.min() >= 0 and rows.max() < n
        blocks = rows[: n // size * size].reshape(-1, size)
        assert all(np.unique(segment[b]).size == 1 for b in blocks)
    # every sample can be drawn (circular within each segment)
    drawn = np.concatenate([_blocks(rng, n, size, firsts) for _ in range(200)])
    assert np.unique(drawn).size == n


def test_the_gear_fit_reads_no_speed_across_a_gap():
    """An axis that moved while nothing was recorded: MP jumps by 30 deg across the gap."""
    t = np.arange(0, 8, 0.004).round(9)
    mp = 10 * np.sin(t) + np.where(t >= 4.2, 30.0, 0.0)
    vm = 10 * np.cos(t)
    torque = 3 * np.sin(2 * t)
    ap = mp - (0.001 * torque + 0.003 * vm + 0.02 * np.sign(vm))
    gap = (t >= 4.0) & (t < 4.2)
    frame = pd.DataFrame({"MP": mp, "AP": ap, "AC": torque}, index=pd.Index(t, name="time"))
    frame[gap] = np.nan
    info = {c: SignalInfo(c, "posn", None, 0.004) for c in frame}
    rec = Recording(frame, {}, info, sample_period=0.004, gaps=((4.0, 4.2),))
    fit = fit_gear(rec)
    assert (round(fit.compliance, 4), round(fit.skew, 4), round(fit.hysteresis, 3)) == (
        0.001, 0.003, 0.04)
    assert fit.rms < 1e-3
    # every sample outside the gap where the motor is fast is fitted, those beside it included
    assert fit.samples == int(np.sum(~gap & (np.abs(vm) > 1.0)))


@pytest.mark.parametrize("gap", [None, (3.35, 3.45)], ids=["no gap", "and a gap"])
def test_values_not_yet_written_at_the_start_are_no_move(tmp_path, reverse_trial, gap):
    """Every signal empty for the first 0.1 s: no gap and no direction change there."""
    frame = reverse_trial.copy()
    frame.loc[frame["time"] < 0.1, ROLES] = np.nan
    (late,) = diagnose_backlash(_csv(frame, tmp_path / "late.csv", gap))
    assert _changes(late) == [("reversal", 1.798, 1.806, -1, None)]
    assert late.left_out == ()
    assert late.segments == (() if gap is None else ((0.0, gap[0]), (gap[1], 5.002)))


@pytest.mark.parametrize(("gap", "count"), [((3.35, 3.45), "2 segments"),
                                            ((4.9, 5.1), "1 segment")],
                         ids=["within", "up to the end"])  # fmt: skip
def test_the_reader_and_the_diagnosis_count_the_same_segments(tmp_path, reverse_trial, gap,
                                                              count):  # fmt: skip
    from funcnet.errors import RecordingWarning

    path = _csv(reverse_trial, tmp_path / "cut.csv", gap)
    with pytest.warns(RecordingWarning) as caught:
        rec = read_trace(path)
    (said,) = [str(w.message) for w in caught if "missing values" in str(w.message)]
    assert len(rec.segments) == int(count[0])
    assert f"the recording is split into {count} and" in said
    (cut,) = diagnose_backlash(path)
    assert f"read in {count}, values missing at {rec.gaps[0][0]:g}-" in cut.message


def _set_point(t: np.ndarray, rp: np.ndarray, period: float,
               gaps: tuple[tuple[float, float], ...]) -> Recording:  # fmt: skip
    rp = rp.copy()
    for a, b in gaps:
        rp[(t >= a) & (t < b)] = np.nan
    return Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
                     {"RP": SignalInfo("RP", "posn", None, period)}, sample_period=period,
                     gaps=gaps)  # fmt: skip


def test_a_reversal_is_left_out_where_a_gap_cuts_its_restart_search_at_a_longer_dwell():
    """max_dwell 1 s: a reversal resting 0.8 s has its arm's restart sought up to 1.8 s after the
    start (the dwell and 1 s); a gap 1.7 s after the start lies within."""
    from funcnet.diagnosis.segments import segment_changes

    t = np.arange(0, 8, 0.002).round(9)
    rp = np.interp(t, [0, 2, 2.8, 5, 8], [0, 2, 2, 0, 0])  # out, 0.8 s at rest, back
    gap = (4.5, 4.55)
    rec = _set_point(t, rp, 0.002, (gap,))
    (change,) = segment_changes(_set_point(t, rp, 0.002, ()), max_dwell=1.0).changes
    assert change.kind == "reversal" and 0.5 < change.dwell < 1.0
    assert change.start + 1.5 < gap[0] < change.start + change.dwell + 1.0
    # the default max_dwell (0.5 s) finds a change after a standstill, its reach 1.5 s
    assert [c.kind for c in segment_changes(rec).changes] == ["after standstill"]
    longer = segment_changes(rec, max_dwell=1.0)
    assert longer.changes == ()
    (left,) = longer.left_out
    assert (left.stop, left.start, left.gap, left.across) == (change.stop, change.start, gap,
                                                             False)  # fmt: skip
    # a gap beyond the search (2.9 s after the start) leaves the reversal read
    far = segment_changes(_set_point(t, rp, 0.002, ((5.7, 5.75),)), max_dwell=1.0)
    assert far.changes == (change,)


def test_the_set_point_is_read_once_for_the_changes_and_those_across_gaps(monkeypatch):
    from funcnet.diagnosis import reversals
    from funcnet.diagnosis.segments import segment_changes

    calls = {"speed": 0, "turns": 0}
    speed, turns = reversals.segment_velocity, reversals.direction_changes

    def counted_speed(*args, **kwargs):
        calls["speed"] += 1
        return speed(*args, **kwargs)

    def counted_turns(*args, **kwargs):
        calls["turns"] += 1
        return turns(*args, **kwargs)

    monkeypatch.setattr(reversals, "segment_velocity", counted_speed)
    monkeypatch.setattr(reversals, "direction_changes", counted_turns)
    t = np.arange(0, 8, 0.002).round(9)
    # turns at 1, 3, 5 and 7 s; the one at 5 s within a gap
    rec = _set_point(t, 10 * np.sin(np.pi * t / 2), 0.002, ((2.8, 2.9), (4.9, 5.1)))
    found = segment_changes(rec)
    assert [round(c.turn, 2) for c in found.changes] == [1.0, 7.0]
    assert [(o.gap, o.across) for o in found.left_out] == [((2.8, 2.9), False),
                                                           ((4.9, 5.1), True)]  # fmt: skip
    # one speed of the set-point, and one search for turns per segment holding a turn
    assert calls == {"speed": 1, "turns": 3}


def test_a_turn_across_a_gap_between_two_ticks_names_that_gap():
    """A 4 ms grid (a decimated recording) with a 2 ms gap between two ticks: the set-point
    turns within it; an earlier gap is not the one named."""
    from funcnet.diagnosis.segments import segment_changes

    t = np.arange(0, 4, 0.004).round(9)
    gaps = ((0.5, 0.6), (2.002, 2.004))
    found = segment_changes(_set_point(t, -10 * np.abs(t - 2.002), 0.004, gaps))
    assert found.changes == ()
    (left,) = found.left_out
    assert left.across and left.gap == (2.002, 2.004)
    assert left.stop <= 2.004 and left.start >= 2.004
