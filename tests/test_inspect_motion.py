"""The inspection's motion summary counts the set-point's direction changes."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io

from conftest import KUKA, REPO
from funcnet.inspection.motion import motion_summary, numbered_moves
from funcnet.report.inspect import inspect_trace
from funcnet.robot import detect_phases, direction_changes, read_trace

CHANNELS = REPO / "examples" / "kuka-kr300-channels.toml"


def set_point_changes(path: Path, axis: int) -> int:
    """Direction changes by the definition, from the MAT file itself: the set-point's speed
    changes sign between two stretches where it exceeds 1 deg/s."""
    rec = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["rec"]
    v = np.gradient(np.asarray(rec.ref_pos_deg[axis - 1], float), rec.time_cont)
    signs = [s for s in np.where(v > 1, 1, np.where(v < -1, -1, 0)) if s]
    return sum(a != b for a, b in zip(signs, signs[1:], strict=False))


@pytest.mark.parametrize("run", ["A", "B"])
def test_the_moves_of_every_kuka_axis_count_its_direction_changes(run):
    path = KUKA / f"kr300-run-{run}.mat"
    for axis in range(1, 7):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the fields left out as constant
            rec = read_trace(path, channels=CHANNELS, axis=axis)
        moves = motion_summary(rec, numbered_moves(detect_phases(rec)))
        expected = set_point_changes(path, axis)
        where = f"run {run} axis {axis}"
        assert expected >= 1, where  # every axis reverses
        # one move from rest to rest, all its direction changes within it
        assert len(moves) == 1, where
        (row,) = moves.to_dict("records")
        assert row["direction changes"] == expected, where
        signs = row["direction"]
        assert len(signs) == expected + 1, where
        assert all(a != b for a, b in zip(signs, signs[1:], strict=False)), where


def test_point_to_point_moves_keep_one_direction_each(real_trace):
    rec = read_trace(real_trace)
    moves = motion_summary(rec, numbered_moves(detect_phases(rec)))
    assert moves["direction"].tolist() == ["+", "−", "+"]
    assert moves["direction changes"].tolist() == [0, 0, 0]
    # its two direction changes are after a rest, between the moves
    turns = direction_changes(rec)
    assert len(turns) == 2
    for turn, (_, before), (_, after) in zip(
        turns, moves.iloc[:-1].iterrows(), moves.iloc[1:].iterrows(), strict=True
    ):
        assert before["stop"] <= turn.time <= after["start"]


def test_the_report_says_where_the_set_point_turns(tmp_path):
    t = np.round(np.arange(0, 5, 0.004), 9)
    # out, back past the start and out again without a rest: turns at 1.5 and 3.5 s
    rp = 30 * np.sin(np.pi * np.clip(t - 0.5, 0, 4) / 2)
    ap = rp - 0.01 * np.gradient(rp, t)
    csv = tmp_path / "out-and-back.csv"
    pd.DataFrame({"time": t, "RP": rp, "AP": ap}).to_csv(csv, index=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        page = inspect_trace(csv, out_dir=tmp_path / "report", evidence=False)
    text = page.read_text()
    assert "It changes direction 2 time(s), at 1.50, 3.50 s: 2 within a move" in text
    assert "one way only" not in text
    one_way = tmp_path / "one-way.csv"
    pd.DataFrame({"time": t, "RP": 10 * np.clip(t - 1, 0, 2), "AP": 10 * np.clip(t - 1, 0, 2)}
                 ).to_csv(one_way, index=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        page = inspect_trace(one_way, out_dir=tmp_path / "one", evidence=False)
    assert "It never changes direction." in page.read_text()


def test_the_report_of_a_kuka_axis_names_its_turns_and_its_torque(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        page = inspect_trace(KUKA / "kr300-run-B.mat", channels=CHANNELS, axis=4,
                             out_dir=tmp_path, evidence=False)
    text = page.read_text()
    expected = set_point_changes(KUKA / "kr300-run-B.mat", 4)
    assert f"It changes direction {expected} time(s), at " in text
    assert f"{expected} within a move (no rest at the turn)" in text
    assert "peak torque |AC|" in text and " N m</li>" in text
