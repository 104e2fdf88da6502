"""A recording with missing values: the gap splits it into segments, no phase, move or window
spans it, and the reports say where."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.inspection import inspect_recording, inspect_robot
from funcnet.inspection.motion import (
    motion_summary,
    numbered_moves,
    segment_phases,
    turns_across_gaps,
)
from funcnet.report.inspect_text import summary_html
from funcnet.robot import detect_phases, direction_changes, read_trace

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")


def _smooth_move(t: np.ndarray, start: float, stop: float, distance: float) -> np.ndarray:
    s = np.clip((t - start) / (stop - start), 0, 1)
    return distance * (s - np.sin(2 * np.pi * s) / (2 * np.pi))


def _write_trace(path: Path, missing: tuple[float, float] | None, *,
                 more: tuple[tuple[float, float], ...] = (), jitter: float = 0.0) -> Path:
    """Out at 0.5-2.5 s and back at 5-7 s (20 deg); the rows in ``missing`` (and ``more``) left
    empty; a set-point noise of ``jitter`` deg (standard deviation) when given."""
    t = np.round(np.arange(0, 8, 0.002), 9)
    rp = _smooth_move(t, 0.5, 2.5, 20) + _smooth_move(t, 5, 7, -20)
    if jitter:
        rp = rp + jitter * np.random.default_rng(1).standard_normal(t.size)
    rng = np.random.default_rng(0)
    ap = np.concatenate([[0.0] * 3, rp[:-3]]) + 1e-4 * rng.standard_normal(t.size)
    ac = np.gradient(np.gradient(ap)) * 1e4 + rng.normal(0, 0.05, t.size)
    frame = pd.DataFrame({"time": t, "RP": rp, "AP": ap, "AC": ac})
    for a, b in ([missing] if missing is not None else []) + list(more):
        frame.loc[(t >= a) & (t < b), ["RP", "AP", "AC"]] = np.nan
    frame.to_csv(path, index=False, float_format="%.9g")
    return path


def _gap_in_file(path: Path) -> tuple[float, float]:
    """The gap as the file has it: the first empty row's time and the next full row's."""
    frame = pd.read_csv(path)
    empty = frame["RP"].isna().to_numpy()
    first = int(np.argmax(empty))
    after = first + int(np.argmax(~empty[first:]))
    return float(frame["time"][first]), float(frame["time"][after])


def _overlaps(start: float, stop: float, gap: tuple[float, float]) -> bool:
    return start < gap[1] and stop > gap[0]


def test_a_gap_within_a_move_splits_it_and_the_page_says_where(tmp_path):
    csv = _write_trace(tmp_path / "cut.csv", missing=(1.2, 1.3))  # in move 1's spin-up
    gap = _gap_in_file(csv)
    out = tmp_path / "report"
    result = CliRunner().invoke(app, ["inspect", str(csv), "--no-evidence", "-o", str(out),
                                      "--quiet"])
    assert result.exit_code == 0, result.output
    # the command line says where, in one line
    said = [line for line in result.stderr.splitlines() if "missing values" in line]
    assert said == [f"funcnet: warning: {csv}: missing values at {gap[0]:g}-{gap[1]:g} s "
                    "(RP, AP, AC): the recording is split into 2 segments and no window spans "
                    "a gap"]
    html = (out / "index.html").read_text(encoding="utf-8")
    summary = re.sub(r"<[^>]+>", "", html[html.index('id="summary"'):html.index('class="toc"')])
    # the spans written as the command line writes them
    assert (f"Values are missing in 1 gap, {gap[0]:g}-{gap[1]:g} s "
            f"({gap[1] - gap[0]:.1f} s): the recording is read as 2 segments, 0-{gap[0]:g} s "
            f"and {gap[1]:g}-8 s, and no phase, move or window spans a gap.") in summary
    assert f"A gap cuts move 1 ({gap[0]:g}-{gap[1]:g} s), move 2" in summary
    assert "dark grey: a gap" in html
    assert "cut by a gap" in html  # the moves table's column

    ins = inspect_recording(read_trace(csv), evidence=False, backlash=False)
    assert ins.gaps == (gap,) and ins.segments == ((0.0, gap[0]), (gap[1], 8.0))
    # no phase, move or window spans the gap, and the phases cover everything else
    assert not any(_overlaps(r.start, r.stop, gap) for r in ins.phases.itertuples())
    assert not any(_overlaps(m.start, m.stop, gap) for m in ins.moves.itertuples())
    assert not any(_overlaps(w.start, w.stop, gap) for w in ins.windows)
    covered = (ins.phases["stop"] - ins.phases["start"]).sum()
    assert covered == pytest.approx(8.0 - (gap[1] - gap[0]))
    # the move the gap interrupts is two moves, each marked; the one back is whole
    assert list(ins.moves["stop"])[0] == gap[0] and list(ins.moves["start"])[1] == gap[1]
    assert list(ins.moves["cut by a gap"]) == [f"{gap[0]:g}-{gap[1]:g} s"] * 2 + [""]
    # V is derived within each segment: no window next to the gap lacks it
    assert not any("no recorded value" in f.message for f in ins.failures)
    v = ins.recording.data["V"]
    inside = (v.index >= gap[0]) & (v.index < gap[1])
    assert v[~inside].notna().all() and v[inside].isna().all()


def test_the_overview_figure_shades_the_gap(tmp_path):
    from funcnet.report.inspect_figures import figure_motion

    csv = _write_trace(tmp_path / "cut.csv", missing=(3.5, 3.8))  # at rest between the moves
    gap = _gap_in_file(csv)
    ins = inspect_recording(read_trace(csv), evidence=False, backlash=False)
    fig = figure_motion(ins)
    top = fig.axes[0]
    shaded = [c for c in top.collections if c.get_gid() == "gap:gap"]
    assert len(shaded) == 1
    (rectangle,) = shaded[0].get_paths()  # in (time, axes fraction)
    xs, ys = rectangle.vertices[:, 0], rectangle.vertices[:, 1]
    assert (xs.min(), xs.max()) == pytest.approx(gap)
    assert (ys.min(), ys.max()) == (0.0, 1.0)
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert "gap (values missing)" in labels
    # no move touches a gap at rest: no zoomed panel shades it
    assert not any(c.get_gid() == "gap:gap" for ax in fig.axes[1:] for c in ax.collections)


def test_a_gap_at_rest_leaves_the_moves_as_without_it(tmp_path):
    with_gap = read_trace(_write_trace(tmp_path / "gap.csv", missing=(3.5, 3.8)))
    without = read_trace(_write_trace(tmp_path / "whole.csv", missing=None))
    assert without.gaps == () and with_gap.gaps == ((3.5, 3.8),)
    phases, turns = segment_phases(with_gap)
    whole = numbered_moves(detect_phases(without))
    moves = motion_summary(with_gap, phases, turns)
    reference = motion_summary(without, whole, direction_changes(without))
    pd.testing.assert_frame_equal(moves.drop(columns="cut by a gap"), reference)
    assert list(moves["cut by a gap"]) == ["", ""]
    # the rest between the moves loses the gap's 0.3 s, nothing else
    moving = whole[whole["move"] > 0].reset_index(drop=True)
    pd.testing.assert_frame_equal(phases[phases["move"] > 0].reset_index(drop=True), moving)
    # the one turn, at rest, falls in the gap: no segment holds it, it is carried across
    assert len(direction_changes(without)) == 1 and turns == ()
    back = reference["start"][1]
    assert turns_across_gaps(moves, with_gap.gaps) == ((reference["stop"][0], back),)
    ins = inspect_recording(with_gap, evidence=False, backlash=False)
    assert ins.turns_across_gaps == ((reference["stop"][0], back),)
    summary = re.sub(r"<[^>]+>", "", summary_html(ins))
    assert "never changes direction" not in summary
    assert ("It changes direction 1 time(s): 1 across a gap (it turns across the gap "
            "3.5-3.8 s).") in summary


def test_a_recording_without_gaps_reads_as_before(tmp_path):
    rec = read_trace(_write_trace(tmp_path / "whole.csv", missing=None))
    phases, turns = segment_phases(rec)
    pd.testing.assert_frame_equal(phases, numbered_moves(detect_phases(rec)))
    assert turns == tuple(direction_changes(rec))
    ins = inspect_recording(rec, evidence=False, backlash=False)
    assert ins.gaps == () and ins.segments == ((0.0, 8.0),)
    assert "cut by a gap" not in ins.moves
    from funcnet.report.inspect import write_inspection

    html = write_inspection(ins, tmp_path / "page").read_text(encoding="utf-8")
    shown = html[:html.index('id="parameters"')]  # the provenance names this test's command
    assert "gap" not in shown.lower()


def test_a_resting_segment_with_a_jittering_set_point_is_no_move(tmp_path):
    # two short gaps at rest cut out a segment (3.1-4 s) where the set-point only jitters; its
    # speed is read against the whole recording's peak, not against its own jitter
    whole = read_trace(_write_trace(tmp_path / "whole.csv", None, jitter=1e-4))
    cut = read_trace(_write_trace(tmp_path / "cut.csv", (3.0, 3.1), more=((4.0, 4.1),),
                                  jitter=1e-4))
    assert cut.gaps == ((3.0, 3.1), (4.0, 4.1))
    reference = motion_summary(whole, numbered_moves(detect_phases(whole)),
                               direction_changes(whole))
    assert len(reference) == 2 and reference["direction changes"].sum() == 0
    phases, turns = segment_phases(cut)
    moves = motion_summary(cut, phases, turns)
    pd.testing.assert_frame_equal(moves.drop(columns="cut by a gap"), reference)
    middle = phases[(phases["start"] >= 3.1) & (phases["stop"] <= 4.0)]
    assert set(middle["phase"]) == {"standstill"}
    # the one turn (at rest, 2.5-5 s) is across both gaps: none within a segment
    assert len(direction_changes(whole)) == 1 and turns == ()
    assert turns_across_gaps(moves, cut.gaps) == ((reference["stop"][0],
                                                   reference["start"][1]),)
    ins = inspect_recording(cut, evidence=False, backlash=False)
    summary = re.sub(r"<[^>]+>", "", summary_html(ins))
    assert ("It changes direction 1 time(s): 1 across a gap (it turns across the gaps "
            "3-3.1 s, 4-4.1 s).") in summary


def test_numbered_moves_starts_a_move_after_a_gap():
    phases = pd.DataFrame({"phase": ["cruise", "braking", "cruise", "standstill", "cruise"],
                           "start": [0.0, 1.0, 2.5, 3.0, 4.0],
                           "stop": [1.0, 2.0, 3.0, 4.0, 5.0]})
    assert numbered_moves(phases)["move"].tolist() == [1, 1, 2, 0, 3]


def test_the_robot_page_says_where_in_each_axis_section(tmp_path):
    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(5)
    rp = np.vstack([10 * np.sin(np.pi * t / 4) ** 2, -6 * np.sin(np.pi * t / 2) ** 2])
    mp = rp + 0.001 * rng.standard_normal(rp.shape)
    ap = mp - 0.01 * np.gradient(rp, t, axis=1)
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1)
    missing = (t >= 1.6) & (t < 1.8)
    tau[0, missing] = np.nan  # axis 1's torque only
    gap = (float(t[missing][0]), float(t[~missing & (t > 1.6)][0]))
    path = tmp_path / "robot.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "mp": mp, "tau": tau}})
    channels = {"rec.t": "time", "rp": "RP", "ap": "AP", "mp": "MP", "tau": "AC"}
    found = inspect_robot(read_trace(path, channels=channels), evidence=False, backlash=False,
                          delay=5)
    assert [(w.start, w.stop) for w in found.windows] == [(0.0, gap[0]), (gap[1], 4.0)]
    assert found.axes[1].gaps == (gap,) and found.axes[2].gaps == ()
    assert not any(_overlaps(w.start, w.stop, gap) for w in found.axes[1].windows)
    from funcnet.report.inspect import write_robot_inspection

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        page = write_robot_inspection(found, tmp_path / "report")
    html = page.read_text(encoding="utf-8")
    axes = html[html.index('id="axes"'):html.index('id="robot"')]
    sentence = (f"Values are missing in 1 gap, {gap[0]:g}-{gap[1]:g} s (0.2 s): the recording "
                f"is read as 2 segments, 0-{gap[0]:g} s and {gap[1]:g}-4 s")
    assert sentence in axes
    assert sentence in (tmp_path / "report" / "axis-1" / "index.html").read_text()
    assert "Values are missing" not in (tmp_path / "report" / "axis-2" / "index.html").read_text()
