"""A network on a bounded number of states: every d-th embedded state, each at the full rate.

The reference is a closed-form identity: when ``d`` divides the delay, every ``d``-th state of
``x`` embedded at ``(dim, delay)`` is a state of ``x[::d]`` embedded at ``(dim, delay / d)``,
value for value, so the thinned measures must equal those of the decimated signals bit for bit.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from funcnet.core.embedding import signal_states, thinned, thinning
from funcnet.core.measures import pairwise_cross_measures
from funcnet.errors import ParameterError
from funcnet.evidence.segment import segment_tests
from funcnet.inspection import inspect_robot, robot as robot_module
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.network.readwrite import to_json
from funcnet.parameters import EvidenceSettings, NetworkParameters
from funcnet.report.inspect import write_robot_inspection
from funcnet.robot.recording import Recording, SignalInfo

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

MEASURES = ["c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff", "eps_x", "eps_y", "eps_xy"]


def _signals(n: int = 1201, seed: int = 0) -> pd.DataFrame:
    """Three signals on [0, 1]: a rough driver, its smoothed follower, an unrelated one."""
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.standard_normal(n))
    y = np.convolve(x, np.ones(9) / 9, mode="same") + 0.2 * rng.standard_normal(n)
    z = np.sin(np.arange(n) / 37.0) + 0.1 * rng.standard_normal(n)
    data = pd.DataFrame({"x": x, "y": y, "z": z})
    return (data - data.min()) / (data.max() - data.min())


@pytest.mark.parametrize("step", [2, 5])
def test_thinned_measures_are_those_of_the_decimated_signals(step):
    data = _signals()
    signals = [data[c].to_numpy() for c in data]
    thin = pairwise_cross_measures(signals, names=list(data), delay=10, theiler=3, step=step,
                                   warn=False)
    decimated = pairwise_cross_measures([s[::step] for s in signals], names=list(data),
                                        delay=10 // step, theiler=-(-3 // step), warn=False)
    assert list(thin) == list(decimated)
    for key, result in thin.items():
        for name in MEASURES:
            assert getattr(result, name) == getattr(decimated[key], name), (key, name)
    # and not those of every state
    every = pairwise_cross_measures(signals, names=list(data), delay=10, theiler=3, warn=False)
    assert any(every[k].c_diff != thin[k].c_diff for k in thin)


def test_states_and_parameters_of_a_thinning():
    x = np.arange(50.0)
    assert np.array_equal(signal_states(x, delay=4, step=3), signal_states(x, delay=4)[::3])
    assert signal_states(x, delay=4, step=3).flags.c_contiguous
    assert thinned(NetworkParameters(theiler=7), 3).theiler == 3
    assert thinned(NetworkParameters(theiler=6), 3).theiler == 2
    assert thinning(2481, 2000) == 2 and thinning(2000, 2000) == 1
    with pytest.raises(ParameterError, match="step"):
        signal_states(x, step=0)


def test_a_bound_at_or_above_the_states_changes_nothing():
    data = _signals(400)
    states = 400 - 2 * 10
    plain = functional_network(data, warn=False, evidence=True, resamples=20)
    bounded = functional_network(data, warn=False, evidence=True, resamples=20,
                                 max_states=states)
    assert bounded.state_step == 1
    assert bounded == plain
    assert "state_step" not in to_json(plain)


def test_a_network_above_the_bound_reads_every_dth_state_and_every_sample_for_direction():
    data = _signals()
    network = functional_network(data, warn=False, max_states=600)
    assert network.state_step == 2 and network.n_samples == 1201
    decimated = functional_network(data.iloc[::2], warn=False, delay=5, normalize=None)
    every = functional_network(data, warn=False)
    pd.testing.assert_frame_equal(network.pairs[MEASURES], decimated.pairs[MEASURES],
                                  check_exact=True)
    # the direction reading is that of every sample, not of the thinned ones
    direction = [c for c in network.pairs.columns if c.startswith("direction")]
    assert direction
    pd.testing.assert_frame_equal(network.pairs[direction], every.pairs[direction],
                                  check_exact=True)
    again = FunctionalNetwork.from_json(to_json(network))
    assert again.state_step == 2 and again == network
    with pytest.raises(ParameterError, match="max_states"):
        functional_network(data, max_states=3)


def test_the_coupling_test_of_a_thinned_network_is_the_segment_test_at_its_step():
    data = _signals(2401, seed=4)[["x", "y"]]
    network = functional_network(data, warn=False, evidence=True, resamples=30,
                                 max_states=800)
    assert network.state_step == 3
    tests, step = segment_tests([data[c].to_numpy() for c in data], names=["x", "y"],
                                parameters=network.parameters, max_states=800)
    assert step == 3
    row = network.pairs.iloc[0]
    test = tests[("x", "y")]
    assert (row["coupling_p"], row["surrogates"]) == (test.p_value, test.surrogates)
    assert row["coupling_statistic"] == test.statistic
    if row["coupled"]:  # an interval brackets the thinned network's own difference
        assert row["c_diff_low"] <= row["c_diff"] <= row["c_diff_high"]


def _two_axes(n: int = 1600, period: float = 0.004) -> Recording:
    rng = np.random.default_rng(5)
    columns = {}
    for axis in (1, 2):
        rp = np.cumsum(rng.standard_normal(n))
        columns[f"A{axis}.RP"] = rp
        columns[f"A{axis}.AP"] = np.roll(rp, 2) + 0.3 * rng.standard_normal(n)
    data = pd.DataFrame(columns, index=pd.Index(np.arange(n) * period, name="time"))
    info = {c: SignalInfo(c, None, None, period) for c in columns}
    return Recording(data, {}, info, sample_period=period)


def test_the_robot_page_says_which_windows_read_fewer_states(monkeypatch, tmp_path):
    recording = _two_axes()
    monkeypatch.setattr(robot_module, "ROBOT_NETWORK_STATES", 500)
    found = inspect_robot(recording, backlash=False, delay=5,
                          evidence_options=EvidenceSettings(resamples=0))
    (label, network), = found.networks.items()
    assert network.state_step == 4  # 1,590 states, at most 500
    assert f"{label}: one in 4 of its 1,590 states" in found.windows_note
    assert "direction reading reads every sample" in found.windows_note
    reference = functional_network(recording.data, warn=False, delay=5, max_states=500)
    pd.testing.assert_frame_equal(network.pairs[MEASURES], reference.pairs[MEASURES],
                                  check_exact=True)
    page = write_robot_inspection(found, tmp_path)
    assert "one in 4 of its 1,590 states" in page.read_text()
    monkeypatch.setattr(robot_module, "ROBOT_NETWORK_STATES", 5000)
    whole = inspect_robot(recording, backlash=False, delay=5, evidence=False)
    assert next(iter(whole.networks.values())).state_step == 1
    assert "one in" not in whole.windows_note
    assert dataclasses.replace(network, state_step=1) != network


@pytest.mark.parametrize("rule", ["funcnet", "pyunicorn"])
def test_the_evidence_builds_each_recurrence_at_the_networks_threshold(rule):
    """Given the thresholds the rates found, the same matrices: the same evidence, bit for bit
    (quantized signals: ties at the thresholds)."""
    from funcnet.evidence.pairs import pairwise_evidence

    data = (_signals(500, seed=2) * 40).round() / 40
    signals = [data[c].to_numpy() for c in data]
    network = functional_network(data, warn=False, rule=rule, delay=4, normalize=None)
    pairs = network.pairs
    eps = [float(pairs.loc[pairs["x"] == "x", "eps_x"].iloc[0]),
           float(pairs.loc[pairs["x"] == "y", "eps_x"].iloc[0]),
           float(pairs.loc[pairs["y"] == "z", "eps_y"].iloc[0])]
    settings = dict(names=list(data), rule=rule, delay=4, resamples=20, intervals="all")
    searched = pairwise_evidence(signals, **settings)
    given = pairwise_evidence(signals, auto_eps=eps, **settings)
    assert list(given) == list(searched)
    pd.testing.assert_frame_equal(
        pd.DataFrame([dataclasses.asdict(e) for e in given.values()]),
        pd.DataFrame([dataclasses.asdict(e) for e in searched.values()]))


def test_a_node_with_a_zero_threshold_keeps_its_evidence():
    """A signal whose rate falls on tied zero distances (a set-point holding still for most of
    the window) has eps 0, which no explicit threshold can be: its rate is searched again."""
    data = _signals(400, seed=3)
    data["x"] = np.where(np.arange(400) < 300, 0.0, data["x"])
    network = functional_network(data, warn=False, evidence=True, resamples=0)
    assert (network.pairs.loc[network.pairs["x"] == "x", "eps_x"] == 0).all()
    assert network.pairs["coupling_p"].notna().all()
    plain = functional_network(data, warn=False)
    from funcnet.network import add_evidence
    pd.testing.assert_frame_equal(add_evidence(plain, data, resamples=0).pairs, network.pairs)
