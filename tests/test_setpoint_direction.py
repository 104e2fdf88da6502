"""The set-point check and the direction reading (funcnet.network.setpoint, .direction)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet.network import FunctionalNetwork, functional_network
from funcnet.network.direction import prediction_p, read_direction
from funcnet.network.setpoint import node_role, setpoint_check


@pytest.fixture(scope="module")
def simulated_networks(tmp_path_factory: pytest.TempPathFactory) -> list[FunctionalNetwork]:
    """Every moving phase of two simulated trials of the paper's plan (fixed seeds)."""
    from funcnet.pipeline import window_networks
    from funcnet.robot import detect_phases, phase_windows, read_recording
    from funcnet.sim import Trial, write_plan

    folder = tmp_path_factory.mktemp("setpoint")
    trials = [Trial("a", "main", speed=175, tcp=1.6, step=3),
              Trial("b", "main", speed=350, tcp=2.0, step=10)]
    write_plan(trials, folder, workers=1)
    nets: list[FunctionalNetwork] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for trial in trials:
            recording = read_recording(Path(folder) / f"{trial.name}.xml")
            windows = list(phase_windows(detect_phases(recording)))
            nets += list(window_networks(recording, windows).values())
    return nets


def _plain_count(nets: list[FunctionalNetwork], column: str) -> dict[str, list[int]]:
    """into / out / undirected per pair type, counted row by row."""
    counts: dict[str, list[int]] = {}
    for net in nets:
        for row in net.pairs.itertuples(index=False):
            if row.degenerate:
                continue
            arrow = getattr(row, column)
            roles = (row.x.split(".")[-1], row.y.split(".")[-1])
            if roles == ("RP", "RP"):
                key = "RP-RP"
                slot = 0 if arrow in ("x->y", "y->x") else 2
            elif roles[0] == "RP":
                key = roles[1]
                slot = 0 if arrow == "y->x" else 1 if arrow == "x->y" else 2
            elif roles[1] == "RP":
                key = roles[0]
                slot = 0 if arrow == "x->y" else 1 if arrow == "y->x" else 2
            else:
                continue
            counts.setdefault(key, [0, 0, 0])[slot] += 1
    return counts


@pytest.mark.parametrize("column", ["kind", "direction"])
def test_setpoint_check_counts_a_simulated_axis_exactly(simulated_networks, column):
    check = setpoint_check(simulated_networks, column=column)
    found = {row.pair_type: [row.into, row.out, row.undirected]
             for row in check.table().itertuples(index=False)}
    assert found == _plain_count(simulated_networks, column)
    assert check.networks == len(simulated_networks) > 0
    assert check.pairs == sum(sum(v) for v in found.values()) > 0
    assert f"out of it {check.out} times" in check.sentence() or check.out == 1


def test_setpoint_check_between_set_points_and_degenerate_pairs():
    pairs = pd.DataFrame({
        "x": ["A1.RP", "A1.RP", "A1.RP", "A1.AP", "A1.RP", "A2.MP"],
        "y": ["A2.RP", "A2.AC", "A1.MP", "A1.AC", "A1.AC", "A1.RP"],
        "kind": ["x->y", "y->x", "x->y", "y->x", "bidirectional", "x->y"],
        "degenerate": [False, False, False, False, False, True],
    })
    check = setpoint_check({"w": pairs})
    assert check.table().values.tolist() == [
        ["AC", 1, 0, 1, 2], ["MP", 0, 1, 0, 1], ["RP-RP", 1, 0, 0, 1]]
    assert (check.into, check.between, check.out) == (2, 1, 1)
    assert "once between two set-points" in check.sentence()
    assert node_role("A12.RP") == "RP" and node_role("RP.x") == "RP.x"


def _lstsq_p(x, y, p, gap):
    """The reference: lag rows built one by one, each model solved by least squares (SVD)."""
    from scipy import stats

    xs, ys = (x - x.mean()) / x.std(), (y - y.mean()) / y.std()
    own_rows, full_rows, target = [], [], []
    for t in range(p + gap, len(x)):
        own = [1.0] + [ys[t - k] for k in range(1, p + 1)]
        own_rows.append(own)
        full_rows.append(own + [xs[t - gap - k] for k in range(1, p + 1)])
        target.append(ys[t])
    rss = []
    for rows in (own_rows, full_rows):
        a, b = np.array(rows), np.array(target)
        beta = np.linalg.lstsq(a, b, rcond=None)[0]
        rss.append(float(((b - a @ beta) ** 2).sum()))
    dfd = len(target) - 2 * p - 1
    return stats.f.sf(max(rss[0] - rss[1], 0.0) / p / (rss[1] / dfd), p, dfd)


@pytest.mark.parametrize("gap", [0, 1, 2])
def test_prediction_p_matches_least_squares(gap):
    rng = np.random.default_rng(3)
    x = rng.standard_normal(120)
    y = np.roll(x, 3) * 0.5 + rng.standard_normal(120)
    assert prediction_p(x, y, 3, gap=gap) == pytest.approx(_lstsq_p(x, y, 3, gap), rel=1e-8)
    assert prediction_p(y, x, 3, gap=gap) == pytest.approx(_lstsq_p(y, x, 3, gap), rel=1e-8)


def _smooth_window(seed, n=160):
    """A jerk-limited-looking set-point logged to 6 decimals, a lagging measured position, a
    rough current: lagged columns nearly collinear, as in a robot's phase window."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / 125.0
    setpoint = np.round(0.3 * t**2 + 0.05 * np.sin(3 * t), 6)
    measured = np.round(np.concatenate([[setpoint[0]] * 3, setpoint[:-3]])
                        + 1e-4 * np.cumsum(rng.standard_normal(n)) / 10, 6)
    current = np.gradient(np.gradient(setpoint)) * 1e4 + 0.3 * rng.standard_normal(n)
    return {"RP": setpoint, "AP": measured, "AC": current}


@pytest.mark.parametrize("seed", range(4))
def test_direction_columns_agree_with_pairwise_least_squares(seed):
    """Every ordered pair of one window, read at once from one QR, against least squares run
    pair by pair: p-values close, decisions equal, on nearly collinear smooth windows."""
    from funcnet.network.direction import DIRECTION_GAP, _p_matrix

    signals = _smooth_window(seed)
    names = list(signals)
    found = _p_matrix(np.column_stack([signals[k] for k in names]), 21, DIRECTION_GAP)
    for i, target in enumerate(names):
        for j, source in enumerate(names):
            if i == j:
                continue
            expected = _lstsq_p(signals[source], signals[target], 21, DIRECTION_GAP)
            assert (found[i, j] <= 0.025) == (expected <= 0.025), (source, target)
            if expected > 1e-12:
                assert found[i, j] == pytest.approx(expected, rel=1e-4, abs=1e-10)


def test_a_target_its_own_past_predicts_exactly_is_untestable():
    ramp = np.arange(200.0) ** 2  # a polynomial: its own past predicts it to rounding
    other = np.random.default_rng(0).standard_normal(200)
    assert np.isnan(prediction_p(other, ramp, 3))
    assert read_direction(other, ramp, 3)[1].startswith("a signal constant or predicted")
    assert not np.isnan(prediction_p(ramp, other, 3))


def test_one_sample_relation_has_no_direction_beyond_the_gap():
    """A channel logged a sample ahead of the other: their lag-1 relation is simultaneous."""
    rng = np.random.default_rng(5)
    x = rng.standard_normal(500)
    y = np.concatenate([[0.0], x[:-1]]) + 0.2 * rng.standard_normal(500)
    assert read_direction(x, y, 3, gap=0)[0] == "x->y"
    assert read_direction(x, y, 3)[0] == "none"
    late = np.concatenate([[0.0, 0.0], x[:-2]]) + 0.2 * rng.standard_normal(500)
    assert read_direction(x, late, 3)[0] == "x->y"
    with pytest.raises(Exception, match="gap"):
        prediction_p(x, y, 3, gap=-1)


def test_read_direction_abstains_on_feedback_and_short_windows():
    rng = np.random.default_rng(4)
    n = 600
    x, y = np.zeros(n), np.zeros(n)
    for t in range(1, n):  # each drives the other (stable: eigenvalues 0.9 and 0.1)
        x[t] = 0.5 * x[t - 1] + 0.4 * y[t - 2] + rng.standard_normal()
        y[t] = 0.5 * y[t - 1] + 0.4 * x[t - 2] + rng.standard_normal()
    assert read_direction(x, y, 2)[0] == "none"
    assert "each past" in read_direction(x, y, 2)[1]
    assert read_direction(x[:11], y[:11], 3) == (
        "none", "window too short: 11 samples for 3 lags (needs at least 12)")
    assert read_direction(x[:12], y[:12], 3)[1].startswith("neither") or "each" in \
        read_direction(x[:12], y[:12], 3)[1]


def test_direction_out_of_the_set_point_on_simulated_phases(simulated_networks):
    check = setpoint_check(simulated_networks, column="direction")
    rp_pairs = check.pairs
    assert check.out >= 0.5 * rp_pairs
    assert check.into <= 0.05 * rp_pairs


def test_direction_always_in_the_table_and_files(tmp_path):
    rng = np.random.default_rng(0)
    x = rng.standard_normal(300)
    y = np.concatenate([[0.0, 0.0], x[:-2]]) + 0.3 * rng.standard_normal(300)
    net = functional_network(np.column_stack([x, y]), names=["RP", "AC"], delay=1, warn=False)
    assert net.pairs.loc[0, "direction"] == "x->y"
    assert FunctionalNetwork.read(net.write(tmp_path / "n.graphml")) == net
    graph = net.to_networkx()
    assert {d["direction"] for _, _, d in graph.edges(data=True)} == {"RP->AC"}
    # A file written before the reading: its old conditional-recurrence columns give way.
    document = json.loads(net.to_json())
    for name in ("direction", "direction_reason"):
        document["pairs"].pop(name)
    document["pairs"]["direction_index"] = [0.1]
    old = FunctionalNetwork.from_json(json.dumps(document))
    assert old.pairs.loc[0, "direction"] == "none"
    assert "written before" in old.pairs.loc[0, "direction_reason"]
    assert "direction_index" not in old.pairs.columns


def test_drawings_take_the_direction_and_keep_the_rule_one_option_away():
    from funcnet.plot import plot_network

    pairs = pd.DataFrame({"x": ["RP", "RP", "AP"], "y": ["AP", "AC", "AC"],
                          "kind": ["y->x", "y->x", "bidirectional"], "weight": [0.2, 0.1, 0.0],
                          "direction": ["x->y", "none", "y->x"]})
    net = FunctionalNetwork.from_pairs(pairs)

    def gids(ax):
        return sorted(p.get_gid() for p in ax.patches if p.get_gid().startswith("edge:"))

    assert gids(plot_network(net, arrows="direction")) == [
        "edge:AC->AP:directed", "edge:RP->AC:none", "edge:RP->AP:directed"]
    assert gids(plot_network(net)) == gids(plot_network(net, arrows="rule")) == [
        "edge:AC->RP:directed", "edge:AP->AC:bidirectional", "edge:AP->RP:directed"]
    with pytest.raises(Exception, match="arrows"):
        plot_network(net, arrows="kind")
