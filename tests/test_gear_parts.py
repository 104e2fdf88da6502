"""Backlash told from friction where the gear torque's sign allows (`gear_parts`): a synthetic
gear with known parts, the simulator's continuous trials, and the KUKA KR 300 runs."""

from __future__ import annotations

import dataclasses
import json
import warnings

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from conftest import KUKA, REPO
from funcnet.cli import app
from funcnet.diagnosis import diagnose_recording
from funcnet.diagnosis.dead_zone import gear_parts
from funcnet.diagnosis.reversals import motor_side_recording
from funcnet.robot import Recording, SignalInfo, read_trace
from funcnet.sim import Trial, simulate_trial
from funcnet.validation.sweep import simulated_recording

KUKA_MAP = REPO / "examples" / "kuka-kr300-channels.toml"


def _gear(dead_zone: float, friction: float, lead: float, seed: int = 0) -> Recording:
    """``MP - AP``: wind-up 0.001 deg per N m, encoders 3 ms apart, ``dead_zone`` (deg) flipping
    with the torque's sign, ``friction`` (deg) with the direction, noise 0.0005 deg; the torque
    leads the motion by ``lead`` rad (0: it keeps the direction's sign)."""
    t = np.arange(0, 12, 0.004)
    mp = 15 * np.sin(t)
    vm = 15 * np.cos(t)
    torque = 4 * np.cos(t + lead) + (0 if lead else 0.5 * np.sign(vm))
    rng = np.random.default_rng(seed)
    ap = mp - (0.001 * torque + 0.003 * vm + dead_zone / 2 * np.sign(torque)
               + friction / 2 * np.sign(vm) + 0.0005 * rng.standard_normal(t.size))  # fmt: skip
    data = pd.DataFrame({"MP": mp, "AP": ap, "AC": torque}, index=pd.Index(t, name="time"))
    info = {c: SignalInfo(c, "posn", None, 0.004) for c in data}
    return Recording(data, {}, info, source="synthetic", sample_period=0.004)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_known_dead_zone_and_friction_are_told_apart(seed):
    parts = gear_parts(_gear(0.02, 0.006, lead=0.8, seed=seed))
    assert parts.reason is None and 0.05 < parts.disagreeing < 0.95
    assert parts.dead_zone == pytest.approx(0.02, rel=0.05)
    assert parts.friction == pytest.approx(0.006, rel=0.15)
    assert parts.compliance == pytest.approx(0.001, rel=0.05)
    assert parts.dead_zone_low <= 0.02 <= parts.dead_zone_high
    assert parts.friction_low <= 0.006 <= parts.friction_high


def test_a_torque_with_the_directions_sign_does_not_tell_them_apart():
    parts = gear_parts(_gear(0.02, 0.006, lead=0.0))
    assert parts.dead_zone is None and parts.friction is None and parts.dead_zone_low is None
    assert "differ in sign" in parts.reason and parts.disagreeing < 0.05


def test_a_load_on_one_flank_is_said():
    rec = _gear(0.0, 0.006, lead=0.8)
    rec = dataclasses.replace(rec, data=rec.data.assign(AC=rec.data["AC"] - 10.0))
    parts = gear_parts(rec)
    assert parts.dead_zone is None and "keeps one sign" in parts.reason


def test_the_simulators_dead_zone_is_followed_where_the_torque_changes_sign():
    """Unloaded smooth trials at 175 deg/min and 2 m: the dead-zone term follows the backlash
    (the motor's own friction in the current reads it up to 0.25 arcmin high; 4 arcmin about 12 %
    low): docs/validation/backlash.md, section 5.1."""
    found = {}
    for arcmin in (0.0, 1.0, 4.0):
        trial = Trial("s", "s", speed=175, tcp=2.0, step=1, profile="smooth",
                      backlash=arcmin / 60, friction_scale=0.7, sensors="real")  # fmt: skip
        sim = simulate_trial(trial, seed=1)
        parts = gear_parts(motor_side_recording(simulated_recording(sim)), resamples=50)
        assert parts.dead_zone is not None, (arcmin, parts.reason)
        found[arcmin] = parts.dead_zone * 60
        assert abs(found[arcmin] - arcmin) <= max(0.25, 0.15 * arcmin), found
    assert found[0.0] < found[1.0] < found[4.0]


@pytest.mark.parametrize("run", ["A", "B"])
def test_the_kuka_runs_say_where_the_parts_are_told_apart(run, tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the constant channels, said in their own tests
        every = read_trace(KUKA / f"kr300-run-{run}.mat", channels=KUKA_MAP)
    for axis in (1, 2, 3):
        result = diagnose_recording(every.for_axis(axis), f"{run}{axis}")
        parts = result.gear_parts
        assert parts is not None and result.gear is not None
        if axis == 3:  # the arm's weight keeps the torque on one flank all run long
            assert parts.dead_zone is None and "keeps one sign" in parts.reason
        if parts.dead_zone is not None:
            assert parts.dead_zone_low <= parts.dead_zone <= parts.dead_zone_high
            assert parts.friction_low <= parts.friction <= parts.friction_high
        else:
            assert parts.reason
    out = tmp_path / "r.json"
    result = CliRunner().invoke(app, ["backlash", str(KUKA / f"kr300-run-{run}.mat"),
                                      "--channels", str(KUKA_MAP), "-o", str(out)])  # fmt: skip
    assert result.exit_code == 0, result.output
    traces = json.loads(out.read_text())["traces"]
    assert [t["gear_parts"] is not None for t in traces] == [True] * 3 + [False] * 3
    told = [t for t in traces if t["gear_parts"] and t["gear_parts"]["dead_zone"] is not None]
    assert all(f"dead zone {60 * t['gear_parts']['dead_zone']:.2f}" in result.output
               for t in told)  # fmt: skip


def test_the_lost_motion_figure_shows_the_step_it_reports_at_a_continuous_turn():
    """On a KUKA axis the figure's two bars (the means of what the gear does not explain
    before and after each turn) differ by the reversal error the diagnosis reports."""
    from funcnet.inspection import inspect_recording
    from funcnet.report.inspect_figures import figure_lost_motion

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rec = read_trace(KUKA / "kr300-run-A.mat", channels=KUKA_MAP, axis=2)
        ins = inspect_recording(rec, evidence=False)  # its threshold warnings tested elsewhere
    fig = figure_lost_motion(ins)
    assert fig is not None and len(fig.axes) == len(ins.backlash.reversals) == 3
    for ax, reversal in zip(fig.axes, ins.backlash.reversals, strict=True):
        before, after = (float(c.get_segments()[0][0][1]) for c in ax.collections[-2:])
        step = -reversal.change.direction * (before - after) / 3600
        # the step drawn is the estimate: the value where resolved, else below its bound
        if reversal.lost_motion is not None:
            assert step == pytest.approx(reversal.lost_motion, abs=1e-9)
        else:
            assert step < reversal.lost_motion_high and reversal.lost_motion_low == 0.0
        assert f"{reversal.change.turn:.2f} s" in ax.get_title()
