"""The set-point check and the direction reading (funcnet.network.setpoint, .direction)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import assume, given, settings, strategies as st

from funcnet.network import FunctionalNetwork, functional_network
from funcnet.network.direction import prediction_p, read_direction
from funcnet.network.precision import logged_step
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
    columns = np.column_stack([signals[k] for k in names])
    steps = np.array([1e-6, 1e-6, 0.0])  # six decimals; the current is computed
    found, within = _p_matrix(columns, 21, DIRECTION_GAP, steps)
    for i, target in enumerate(names):
        own = _own_rss(signals[target], 21, DIRECTION_GAP)
        for j, source in enumerate(names):
            if i == j:
                continue
            expected = _lstsq_p(signals[source], signals[target], 21, DIRECTION_GAP)
            assert (found[i, j] <= 0.025) == (expected <= 0.025), (source, target)
            if expected > 1e-12:
                assert found[i, j] == pytest.approx(expected, rel=1e-4, abs=1e-10)
            n = len(columns) - 21 - DIRECTION_GAP
            assert within[i, j] == (own <= n * steps[i] ** 2), (source, target)


def _own_rss(y, p, gap):
    """Residual sum of squares of y from its own past (lags 1..p), rows from p + gap on."""
    rows = np.array([[1.0, *(y[t - k] for k in range(1, p + 1))] for t in range(p + gap, len(y))])
    target = y[p + gap :]
    beta = np.linalg.lstsq(rows, target, rcond=None)[0]
    return float(((target - rows @ beta) ** 2).sum())


def test_a_target_its_own_past_predicts_exactly_shows_no_improvement():
    ramp = np.arange(200.0) ** 2  # a polynomial: its own past predicts it to rounding
    other = np.random.default_rng(0).standard_normal(200)
    assert np.isnan(prediction_p(other, ramp, 3))
    reading, reason = read_direction(other, ramp, 3, names=("AC", "RP"))
    assert reading == "none"
    assert "RP is predicted by its own past exactly or to within its logged step" in reason
    assert not np.isnan(prediction_p(ramp, other, 3))


@settings(max_examples=40, deadline=None)
@given(step=st.floats(1e-7, 1e-1), scale=st.floats(1e-3, 1e3), offset=st.floats(-1e3, 1e3),
       seed=st.integers(0, 2**16))
def test_logged_step_finds_the_grid_a_signal_was_logged_on(step, scale, offset, seed):
    """Values written on a grid of ``step``, then converted (scaled, shifted), moving up to
    thousands of steps per sample: the grid's step in the new unit, wherever it is over a
    billionth of the values (a log's decimals are far coarser); computed values have none."""
    rng = np.random.default_rng(seed)
    logged = np.cumsum(rng.integers(0, 4000, 500)) * step * scale + offset
    assume(step * scale >= 1e-9 * np.abs(logged).max())
    assert logged_step(logged) == pytest.approx(step * scale, rel=1e-6)
    assert logged_step(rng.standard_normal(500) * scale + offset) == 0.0


def test_logged_step_of_single_precision_is_its_spacing():
    """A channel stored in single precision: the root mean square of float32's spacing at its
    values (no coarser grid)."""
    values = np.float32(np.random.default_rng(3).uniform(-40.0, 40.0, 1000)).astype(np.float64)
    spacing = np.array([np.spacing(np.float32(abs(v))) for v in values], dtype=np.float64)
    assert logged_step(values) == pytest.approx(np.sqrt(np.mean(spacing**2)), rel=1e-12)


def _trajectory(n, seed):
    """A planned position: twice-integrated smooth random acceleration."""
    rng = np.random.default_rng(seed)
    acceleration = np.convolve(rng.standard_normal(n + 60), np.hanning(60), "valid")[:n]
    return np.cumsum(np.cumsum(acceleration))


def test_no_improvement_shown_into_a_signal_predicted_within_its_logged_step():
    """A set-point logged to a step its own past predicts it within: a signal following its
    true value improves its prediction (it undoes the rounding of the set-point's past), which
    the log cannot tell from a drive, so no arrow into it; the set-point's past still shows
    what it drives. Logged finer, the same pair is tested as before.

    Away from the level: AP's past for RP p < 1e-300, RP's for AP p 0.87 (the follower's
    noise seed chosen so; with seed 8 it was 0.024, under the level of 0.025, and the reading
    'none'); RP's past for the driven signal p < 1e-50."""
    rng = np.random.default_rng(15)
    setpoint = _trajectory(2000, 7)
    error = np.sqrt(_own_rss(setpoint, 5, 1) / (2000 - 6))  # the true value's own-past error
    # 300 errors, to two digits: the grid must not hang on the last bits of a fit (1.7)
    coarse = float(f"{300 * error:.2g}")
    logged = np.round(setpoint / coarse) * coarse
    assert np.sqrt(_own_rss(logged, 5, 1) / (2000 - 6)) <= 0.9 * coarse  # 1.39 of 1.7
    assert logged_step(logged) == pytest.approx(coarse, rel=1e-9)
    follower = setpoint + 0.01 * coarse * rng.standard_normal(2000)
    names = ("AP", "RP")
    assert prediction_p(follower, logged, 5) < 1e-100
    assert prediction_p(logged, follower, 5) > 0.5
    assert read_direction(follower, logged, 5, names=names, steps=(0.0, 0.0))[0] == "x->y"
    reading, reason = read_direction(follower, logged, 5, names=names)
    assert reading == "none" and reason.startswith("RP is predicted by its own past exactly or")
    driven = np.concatenate([[0.0] * 3, logged[:-3]]) + coarse * rng.standard_normal(2000)
    assert read_direction(logged, driven, 5)[0] == "x->y"
    fine = np.round(setpoint / error) * error
    assert "logged step" not in read_direction(follower, fine, 5)[1]


def test_a_coarse_signal_its_own_past_does_not_predict_can_be_driven():
    """A few levels of a driven signal: its own-past error is under a step (its whole spread
    is about a step), but its own past does not predict it, so the rounding of its past hides
    nothing and the drive reads. Away from the level: p 0 (below 1e-300) one way, 0.92 the
    other."""
    rng = np.random.default_rng(11)
    x = rng.standard_normal(2000)
    y = np.round(0.6 * np.concatenate([[0.0, 0.0], x[:-2]]))  # five levels, step 1
    assert np.sqrt(_own_rss(y, 3, 1) / (2000 - 4)) <= 1.0
    assert read_direction(x, y, 3)[0] == "x->y"


def test_a_driver_beyond_the_rounding_still_reads():
    """A target rounded to a step far below its innovations: the arrow stays (p 0 one way,
    0.60 the other: away from the level)."""
    rng = np.random.default_rng(9)
    x = rng.standard_normal(1500)
    y = np.zeros(1500)
    for t in range(3, 1500):
        y[t] = 0.5 * y[t - 1] + 0.8 * x[t - 3] + 0.3 * rng.standard_normal()
    assert read_direction(x, np.round(y, 2), 3)[0] == "x->y"


def test_one_sample_relation_has_no_direction_beyond_the_gap():
    """A channel logged a sample ahead of the other: their lag-1 relation is simultaneous.
    Away from the level: gap 0 p 0 and 0.76; gap 1 p 0.86 and 0.51; two samples late p 0 and
    0.55."""
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
    # away from the level: feedback p 2e-39 and 1e-37; the 12 samples p 0.72 and 0.68
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
    # away from the level: p 2e-165 one way, 0.96 the other
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


@pytest.mark.parametrize("recording", ["sinumerik", "kuka-axis-2", "kuka-robot"])
def test_direction_holds_on_real_recordings(recording):
    """On the real SINUMERIK and KUKA recordings (every phase window of an axis; the whole
    robot as one network) the reading points into a set-point for at most 5 % of the
    set-point pairs, and the set-points it reads are the ones the single-precision KUKA files
    and the decimal SINUMERIK trace log on a grid."""
    from conftest import KUKA, REPO, need_real_trace
    from funcnet.pipeline import window_networks
    from funcnet.robot import complete_span, detect_phases, phase_windows, read_recording

    kuka = KUKA / "kr300-run-A.mat"
    channels = REPO / "examples" / "kuka-kr300-channels.toml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if recording == "sinumerik":
            run = read_recording(need_real_trace())
        else:
            run = read_recording(kuka, channels=channels,
                                 axis=2 if recording == "kuka-axis-2" else None)
        windows = ([complete_span(run)] if run.axes
                   else list(phase_windows(detect_phases(run))))
        nets = list(window_networks(run, windows, constant="drop",
                                    errors="collect").values())
    check = setpoint_check(nets, column="direction")
    assert check.pairs > 0
    assert check.into <= 0.05 * check.pairs
    assert check.out > 0
    assert logged_step(run.data[[c for c in run.data.columns if node_role(c) == "RP"][0]]
                       .to_numpy(np.float64)) > 0


@pytest.mark.parametrize("steps", [{"Z": 1e-6}, {"A": -1.0}, {"A": float("nan")}])
def test_bad_steps_are_named(steps):
    from funcnet.errors import ParameterError

    rng = np.random.default_rng(2)
    data = pd.DataFrame({"A": rng.standard_normal(300), "B": rng.standard_normal(300)})
    with pytest.raises(ParameterError, match="steps"):
        functional_network(data, delay=1, steps=steps)
    with pytest.raises(ParameterError, match="steps"):
        read_direction(data["A"], data["B"], 3, names=("A", "B"),
                       steps=(1.0,) if "Z" in steps else (steps["A"], 0.0))
