"""funcnet.diagnosis: direction changes, the real trace, JSON results, trends."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet.diagnosis import (
    MOTOR_LOOP_SCORE,
    SCORE,
    diagnose_backlash,
    diagnose_recording,
    find_direction_changes,
    load_calibration,
    trend_table,
    write_results,
)
from funcnet.errors import ParameterError
from funcnet.report import write_backlash_page
from funcnet.robot import read_trace
from funcnet.sim import Trial, simulate_trial, write_trace


def _reversal_trace(tmp_path: Path, backlash_arcmin: float, name: str) -> tuple[Path, dict]:
    sim = simulate_trial(Trial(name, "s", speed=175, tcp=1.6, step=1, reverse=True,
                               backlash=backlash_arcmin / 60, sensors="real", seed=3))  # fmt: skip
    path = write_trace(tmp_path / f"{name}.xml", sim.data, intervals={"AP": 0.004, "MP": 0.004})
    return path, sim.truth


def test_the_real_trace_has_no_reversal_only_changes_after_long_standstills(real_trace, tmp_path):
    (result,) = diagnose_backlash(real_trace)
    assert result.backlash_score is None and result.reading is None
    kinds = [r.change.kind for r in result.reversals]
    assert kinds == ["after standstill", "after standstill"]
    assert all(r.change.dwell > 10 for r in result.reversals)
    assert "no reversal" in result.message
    # two-encoder statistics at the direction changes: a few thousandths of a degree
    assert 0.0005 < result.lost_motion < 0.01
    out = write_results([result], tmp_path / "r.json")
    traces = json.loads(out.read_text())["traces"]
    assert traces[0]["path"] == str(real_trace) and traces[0]["backlash_score"] is None
    assert {"path", "backlash_score", "lost_motion", "reversals"} <= set(traces[0])


def test_a_trace_that_moves_one_way_says_so(real_trace):
    rec = read_trace(real_trace)
    first_move = rec.window(0.0, 20.0)  # the real trace's first move only
    result = diagnose_recording(first_move, "first-move")
    assert result.reversals == () and result.backlash_score is None
    assert result.lost_motion is None
    assert result.message.startswith("no direction change")


def test_a_simulated_reversal_is_found_scored_and_read(tmp_path):
    path, truth = _reversal_trace(tmp_path, 2.0, "worn")
    (result,) = diagnose_backlash(path)
    (reversal,) = result.reversals
    assert reversal.change.kind == "reversal"
    assert reversal.speed == pytest.approx(60 / 0.85, rel=0.01)  # a 1 deg step never cruises
    assert result.backlash_score == reversal.indicators[SCORE]
    assert result.lost_motion == pytest.approx(truth["lost_motion"], rel=0.1)
    assert result.reading is not None and "arcmin" in result.reading["text"]
    assert result.reading["arcmin_low"] <= 2 <= result.reading["arcmin_high"]


def test_without_the_arm_encoder_the_motor_loop_indicator_is_read(tmp_path):
    sim = simulate_trial(Trial("noap", "s", speed=35, tcp=1.6, step=1, reverse=True,
                               backlash=2 / 60, sensors="real", position_feedback="motor",
                               seed=3))  # fmt: skip
    data = sim.data.drop(columns=["AP"])
    path = write_trace(tmp_path / "noap.xml", data, intervals={"MP": 0.004})
    (result,) = diagnose_backlash(path)
    assert result.score_indicator == MOTOR_LOOP_SCORE and result.lost_motion is None
    assert result.score_unit == "1" and result.to_dict()["score_unit"] == "1"
    assert result.backlash_score == result.reversals[0].indicators[MOTOR_LOOP_SCORE]
    assert result.reading is not None and result.reading["indicator"] == MOTOR_LOOP_SCORE


def test_several_traces_give_a_trend(real_trace, tmp_path):
    paths = [_reversal_trace(tmp_path, b, f"t{i}")[0] for i, b in enumerate((0.0, 1.0, 4.0))]
    results = diagnose_backlash(*paths, real_trace)
    table = trend_table(results)
    assert table["path"].tolist() == [str(p) for p in (*paths, real_trace)]
    scores = table["backlash_score"].tolist()
    assert scores[0] < scores[1] < scores[2] and np.isnan(scores[3])
    page = write_backlash_page(results, tmp_path / "trend.html").read_text()
    assert "<svg" in page and "t2.xml" in page


def test_no_path_and_a_wrong_suffix_are_parameter_errors(tmp_path):
    with pytest.raises(ParameterError):
        diagnose_backlash()
    with pytest.raises(ParameterError, match="json"):
        write_results([], tmp_path / "r.txt")
    with pytest.raises(ParameterError, match="write_backlash_page"):
        write_results([], tmp_path / "r.html")
    with pytest.raises(ParameterError, match="html"):
        write_backlash_page([], tmp_path / "r.json")


def test_the_html_page_holds_the_trend(real_trace, tmp_path):
    result = diagnose_recording(read_trace(real_trace).window(0.0, 20.0), "first-move")
    page = write_backlash_page([result], tmp_path / "r.html").read_text()
    assert "first-move" in page and "no direction change" in page and "model-based" in page


def test_direction_changes_of_the_real_trace(real_trace):
    changes = find_direction_changes(read_trace(real_trace))
    assert [c.direction for c in changes] == [-1, 1]


def test_the_calibration_ships_with_the_package():
    cal = load_calibration()
    assert cal["indicator"] == SCORE and set(cal["levels"]) == {"35", "70.6"}


def _shape(value):
    """The nesting of a JSON value: dict keys' shapes, list lengths, leaf types."""
    if isinstance(value, dict):
        return {key: _shape(item) for key, item in value.items()}
    if isinstance(value, list):
        return [len(value), sorted({type(v).__name__ for v in value})]
    return type(value).__name__


def test_the_shipped_calibration_is_what_derive_calibration_makes():
    # A small fixture sweep in the shipped calibration's grid (speeds, widths): the derivation
    # gives a file of the shipped file's shape, with levels equal to plain quantiles.
    from funcnet.diagnosis.diagnose import MOTOR_LOOP_SCORE
    from funcnet.validation.sweep import derive_calibration

    shipped = load_calibration()
    rng = np.random.default_rng(0)
    speeds = [float(s) for s in shipped["levels"]]
    widths = [float(b) for b in shipped["levels"]["35"]]
    rows = [{"peak_speed": s, "backlash_arcmin": b, SCORE: b / 60 + rng.normal(0, 0.002),
             "motor_travel": 1 + b + rng.normal(0, 0.1), "current_step": rng.normal(0.5, 0.1)}
            for s in speeds for b in widths for _ in range(7)]
    sweep = pd.DataFrame(rows)
    cal = derive_calibration(sweep, sweep, source="fixture", motor_source="fixture")
    shipped_shape, derived_shape = _shape(shipped), _shape(cal)
    for part in (shipped_shape, derived_shape):
        part.pop("source"), part["motor_loop"].pop("source")
    assert derived_shape == shipped_shape
    for s in speeds:
        for b in widths:
            values = sweep[(sweep.peak_speed == s) & (sweep.backlash_arcmin == b)][SCORE]
            expected = np.quantile(values.to_numpy(), cal["quantiles"])
            assert cal["levels"][f"{s:g}"][f"{b:g}"] == pytest.approx(expected)
    healthy = sweep[(sweep.backlash_arcmin == 0) & (sweep.peak_speed == speeds[0])]
    median, iqr = cal["motor_loop"]["reference"][f"{speeds[0]:g}"]["motor_travel"]
    assert median == pytest.approx(healthy.motor_travel.median())
    assert iqr == pytest.approx(healthy.motor_travel.quantile(0.75)
                                - healthy.motor_travel.quantile(0.25))
    assert cal["motor_loop"]["indicator"] == MOTOR_LOOP_SCORE
