"""The backlash sweep plan, seeds in plans, and the indicators on a fixed small sweep."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ParameterError, StudyError
from funcnet.robot import read_trace
from funcnet.sim.plan import (
    ARCMIN,
    MANIFEST_COLUMNS,
    backlash_sweep_plan,
    named_plan,
    read_plan,
    write_plan,
)
from funcnet.validation.sweep import run_sweep, score_indicators


def test_the_sweep_has_the_issue_grid():
    plan = backlash_sweep_plan()
    assert len(plan) == 6 * 2 * 3 * 3 * 3 * 3 * 2 >= 500
    assert {round(t.backlash / ARCMIN, 9) for t in plan} == {0, 0.25, 0.5, 1, 2, 4}
    assert {t.seed for t in plan} == {1, 2, 3} and {t.noise_scale for t in plan} == {1, 2}
    assert all(t.reverse and t.sensors == "real" for t in plan)
    assert len({t.name for t in plan}) == len(plan)
    assert [t.name for t in read_plan("backlash-sweep")] == [t.name for t in plan]
    assert len(named_plan("paper")) == 36
    with pytest.raises(ParameterError, match="plan"):
        named_plan("nope")


def test_seeds_in_a_toml_group_give_one_trial_each_and_reach_the_manifest(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(
        '[[group]]\nname = "s"\nspeeds = [350]\ntcps = [1.2]\nsteps = [1]\n'
        'direction = "forward+reverse"\nbacklash = 0.0041667\nseeds = [4, 5]\nsensors = "real"\n'
    )
    trials = read_plan(path)
    assert [t.name for t in trials] == [
        "s-v350-p12-s1-b0.0041667-r4",
        "s-v350-p12-s1-b0.0041667-r5",
    ]
    manifest = pd.read_csv(write_plan(trials, tmp_path / "out"))
    assert list(manifest.columns) == list(MANIFEST_COLUMNS)
    assert manifest["seed"].tolist() == [4, 5]
    assert manifest["file"].tolist() == [f"{t.name}.xml" for t in trials]
    assert manifest["backlash"].tolist() == [0.0041667] * 2
    assert (manifest["lost_motion"] > 0.0041667).all()
    assert manifest["sensors"].tolist() == ["real", "real"]
    rec = read_trace(tmp_path / "out" / manifest["file"][0])
    assert rec.signals["AP"].interval == 0.004 and rec.signals["MP"].interval == 0.004
    other = read_trace(tmp_path / "out" / manifest["file"][1])
    assert not np.array_equal(rec.data["AC"], other.data["AC"])  # each seed its own noise


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("seeds = [1.5]", "seeds"),
        ("seeds = [-1]", "seeds"),
        ('arm_model = "soft"', "arm_model"),
    ],
)
def test_bad_seeds_and_options_are_named(tmp_path, text, match):
    path = tmp_path / "p.toml"
    path.write_text(f'[[group]]\nname = "s"\nspeeds = [35]\ntcps = [1.2]\nsteps = [1]\n{text}\n')
    with pytest.raises(StudyError, match=match):
        read_plan(path)


@pytest.fixture(scope="module")
def small_sweep() -> pd.DataFrame:
    """A fixed small sweep: 0, 0.5, 2, 4 arcmin x both speeds x two stiffnesses, seed 1."""
    plan = backlash_sweep_plan(backlash_arcmin=(0, 0.5, 2, 4), tcps=(1.6,),
                               friction_scales=(1.0,), stiffness_scales=(0.7, 1.4), seeds=(1,),
                               noise_scales=(1.0,))  # fmt: skip
    return run_sweep(plan, networks=False)


def test_two_encoder_lost_motion_follows_the_truth(small_sweep):
    some = small_sweep[small_sweep["backlash_arcmin"] > 0]
    error = some["lost_motion"] / some["true_lost_motion"] - 1
    # measured max 3.1 % (the restart fitted from the reading's own difference, MP - AP from the
    # motor's turn); docs/validation/backlash.md gives the sweep's figures
    assert error.abs().max() < 0.05


def test_motor_hysteresis_separates_backlash_on_the_small_sweep(small_sweep):
    scores = score_indicators(small_sweep, ["motor_hysteresis"], resamples=50)
    assert (scores["auc_0.5_vs_0"] == 1.0).all()
    assert (scores["rho"] > 0.8).all()


def test_auc_and_rho_with_intervals_on_known_data():
    table = pd.DataFrame({"speed": 35.0, "noise_scale": 1.0,
                          "backlash_arcmin": [0, 0, 0.5, 1, 2, 4],
                          "x": [0.0, 0.3, 0.2, 0.4, 0.5, 0.6]})  # fmt: skip
    row = score_indicators(table, ["x"], resamples=200).iloc[0]
    assert row["auc_0.5_vs_0"] == pytest.approx(7 / 8)
    assert row["auc_2_vs_0.5"] == 1.0
    assert row["auc_0.5_vs_0_low"] <= row["auc_0.5_vs_0"] <= row["auc_0.5_vs_0_high"]
    assert row["rho_low"] <= row["rho"] <= row["rho_high"]


# --------------------------------------------------------------------------------------------
# the functional-network features: batched windows, the coupling test alone; traces on disk


def test_fn_features_equal_the_per_window_networks_with_evidence():
    """The batched windows and the coupling test alone give what one network per window with
    evidence gave (the features' definition, module notes of funcnet.diagnosis.indicators)."""
    from funcnet.diagnosis.indicators import reversal_indicators
    from funcnet.diagnosis.reversals import find_direction_changes, motor_side_recording
    from funcnet.network import functional_network
    from funcnet.sim.axis import simulate_trial
    from funcnet.validation.sweep import simulated_recording

    trial = backlash_sweep_plan(backlash_arcmin=(2,), speeds=(35,), tcps=(1.6,),
                                friction_scales=(1.0,), stiffness_scales=(1.0,), seeds=(2,),
                                noise_scales=(1.0,))[0]  # fmt: skip
    rec = motor_side_recording(simulated_recording(simulate_trial(trial, seed=2)))
    change = next(c for c in find_direction_changes(rec) if c.kind == "reversal")
    found = reversal_indicators(rec, change, evidence=True)

    def summary(start, nodes):
        part = rec.window(start, start + 0.6).data[list(nodes)]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            net = functional_network(part, warn=False, evidence=True, resamples=1)
        pairs, edges = net.pairs, net.edges
        return (float(np.mean(np.abs(pairs["c_diff"]) + np.abs(pairs["t_diff"]))),
                float(len(edges)), float(edges.loc[edges["source"] == "VM", "weight"].abs().sum()),
                float(pairs["coupled"].sum()), edges)  # fmt: skip

    start = found["turn_time"] - 0.1
    after, before = summary(start, ("MP", "VM", "RC", "AC")), summary(start - 0.6,
                                                                      ("MP", "VM", "RC", "AC"))
    for k, name in enumerate(("fn_asymmetry", "fn_edges", "fn_vm_out", "fn_coupled")):
        assert found[name] == after[k] - before[k], name
    # the resampling intervals cost time and change no indicator
    with_intervals = reversal_indicators(rec, change, evidence=True, intervals=3)
    assert with_intervals == pytest.approx(found, nan_ok=True)
    edges = summary(start, ("RP", "AP", "MP", "V", "RC", "AC"))[4]
    directed = set(zip(edges["source"], edges["target"], strict=True))
    expected = all(("V", n) in directed for n in ("RP", "AP", "MP", "RC", "AC")) and {
        ("MP", "AP"), ("AP", "RP")} <= directed
    assert found["signature"] == float(expected)


@pytest.fixture(scope="module")
def written_sweep(tmp_path_factory):
    """A handful of reversal trials written as `funcnet simulate` writes them."""
    folder = tmp_path_factory.mktemp("sweep")
    plan = backlash_sweep_plan(backlash_arcmin=(0, 0.5, 2), speeds=(35, 175), tcps=(1.6,),
                               friction_scales=(1.0,), stiffness_scales=(0.7, 1.4), seeds=(1,),
                               noise_scales=(1.0,))  # fmt: skip
    write_plan(plan, folder)
    return folder, plan


def test_folder_indicators_read_the_traces_and_the_manifest_truth(written_sweep):
    from funcnet.validation.sweep import folder_indicators

    folder, plan = written_sweep
    table = folder_indicators(folder)
    manifest = pd.read_csv(folder / "manifest.csv")
    assert table["name"].tolist() == manifest["name"].tolist() == [t.name for t in plan]
    assert np.allclose(table["backlash_arcmin"], manifest["backlash"] * 60)
    assert table["true_lost_motion"].tolist() == manifest["lost_motion"].tolist()
    assert set(table["peak_speed"]) == {35.0, 70.6}
    # the traces on disk give the in-memory sweep's indicators (its recordings hold what the
    # files hold)
    memory = run_sweep(plan, evidence=True)
    for name in ("lost_motion", "motor_hysteresis", "fn_asymmetry", "fn_edges", "fn_coupled"):
        assert np.allclose(table[name], memory[name], rtol=1e-9, equal_nan=True), name
    some = table[table["backlash_arcmin"] > 0]
    assert (np.abs(some["lost_motion"] / some["true_lost_motion"] - 1) < 0.05).all()


def test_folder_indicators_without_a_manifest_name_the_file(tmp_path):
    from funcnet.errors import TraceError
    from funcnet.validation.sweep import folder_indicators

    with pytest.raises(TraceError, match="manifest.csv"):
        folder_indicators(tmp_path)
