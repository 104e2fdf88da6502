"""Tests of funcnet.network: pairs table, the mu edge rule, weights, export, errors."""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import fields

import networkx as nx
import numpy as np
import pandas as pd
import pytest

import funcnet.network.functional as network_module
from funcnet.core.measures import CrossMeasures, cross_measures
from funcnet.core.normalization import normalize
from funcnet.errors import ParameterError, SignalError, ThresholdWarning
from funcnet.network import (
    FunctionalNetwork,
    combine_kinds,
    edge_kind,
    functional_network,
)
from funcnet.parameters import NetworkParameters

MEASURE_COLUMNS = [
    "c_xy",
    "c_yx",
    "t_xy",
    "t_yx",
    "c_diff",
    "t_diff",
    "eps_x",
    "eps_y",
    "eps_xy",
    "achieved_rr_x",
    "achieved_rr_y",
    "achieved_cr",
]


# --- an independent dense float64 reference (README method steps 4-5) ---------------------


def brute_embed(x, dim, delay):
    m = len(x) - (dim - 1) * delay
    return np.array([[x[i + j * delay] for j in range(dim)] for i in range(m)])


def brute_distances(a, b, metric):
    diff = np.abs(a[:, None, :] - b[None, :, :])
    if metric == "euclidean":
        return np.sqrt(np.einsum("ijk,ijk->ij", diff, diff))
    if metric == "supremum":
        return diff.max(axis=2)
    return diff.sum(axis=2)


def kth_smallest(values, rate):
    k = max(1, math.ceil(rate * values.size - 1e-9))
    return np.sort(values, kind="stable")[k - 1]


def brute_cross(cross, auto):
    """Global cross-clustering and cross-transitivity of the rows of ``cross`` against ``auto``."""
    local, triangles, triples = [], 0, 0
    for row in cross.astype(float):
        k = row.sum()
        tri = row @ auto.astype(float) @ row
        local.append(tri / (k * (k - 1)) if k >= 2 else 0.0)
        triangles += tri
        triples += k * (k - 1)
    return float(np.mean(local)), (triangles / triples if triples else 0.0)


def brute_pair(x, y, *, dim, delay, rr, cr, metric):
    xs, ys = brute_embed(x, dim, delay), brute_embed(y, dim, delay)
    off = ~np.eye(len(xs), dtype=bool)
    d_x, d_y, d_xy = (
        brute_distances(xs, xs, metric),
        brute_distances(ys, ys, metric),
        brute_distances(xs, ys, metric),
    )
    eps_x, eps_y = kth_smallest(d_x[off], rr), kth_smallest(d_y[off], rr)
    eps_xy = kth_smallest(d_xy.ravel(), cr)
    a_x, a_y, c_xy_matrix = (d_x <= eps_x) & off, (d_y <= eps_y) & off, d_xy <= eps_xy
    c_xy, t_xy = brute_cross(c_xy_matrix, a_y)
    c_yx, t_yx = brute_cross(c_xy_matrix.T, a_x)
    return dict(
        c_xy=c_xy,
        c_yx=c_yx,
        t_xy=t_xy,
        t_yx=t_yx,
        c_diff=c_xy - c_yx,
        t_diff=t_xy - t_yx,
        eps_x=eps_x,
        eps_y=eps_y,
        eps_xy=eps_xy,
        achieved_rr_x=a_x.sum() / off.sum(),
        achieved_rr_y=a_y.sum() / off.sum(),
        achieved_cr=c_xy_matrix.sum() / c_xy_matrix.size,
    )


def brute_kind(c_diff, t_diff, mu, measure):
    def one(diff):
        if diff != 0 and diff <= -mu:
            return "x->y"
        if diff != 0 and diff >= mu:
            return "y->x"
        return "bidirectional"

    c, t = one(c_diff), one(t_diff)
    if measure == "clustering":
        return c
    if measure == "transitivity":
        return t
    if c == t:
        return c
    if "bidirectional" in (c, t):
        return c if t == "bidirectional" else t
    return "conflict"


def signals(n=90, seed=0):
    """Three signals of unequal character: a random walk, its noisy smoothed copy, a chaotic map."""
    rng = np.random.default_rng(seed)
    walk = rng.normal(size=n).cumsum()
    smooth = np.convolve(walk, np.ones(4) / 4, mode="same") + 0.3 * rng.normal(size=n)
    logistic = np.empty(n)
    logistic[0] = 0.2 + 0.5 * rng.random()
    for i in range(n - 1):
        logistic[i + 1] = 3.9 * logistic[i] * (1 - logistic[i])
    return np.column_stack([walk, smooth, logistic])


def quiet_network(data, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        return functional_network(data, **kwargs)


@pytest.mark.parametrize("metric", ["euclidean", "supremum", "manhattan"])
@pytest.mark.parametrize("method", ["minmax", "zscore", None])
def test_pairs_table_matches_brute_force(metric, method):
    data = signals()
    net = quiet_network(
        data,
        names=["walk", "smooth", "map"],
        dim=3,
        delay=2,
        rr=0.08,
        cr=0.06,
        metric=metric,
        normalize=method,
    )
    scaled = normalize(data, method)
    assert list(net.pairs[["x", "y"]].itertuples(index=False, name=None)) == [
        ("walk", "smooth"),
        ("walk", "map"),
        ("smooth", "map"),
    ]
    for row, (i, j) in zip(net.pairs.itertuples(), [(0, 1), (0, 2), (1, 2)], strict=True):
        expected = brute_pair(
            scaled[:, i], scaled[:, j], dim=3, delay=2, rr=0.08, cr=0.06, metric=metric
        )
        for name, value in expected.items():
            assert getattr(row, name) == pytest.approx(value, abs=1e-12, rel=0), name
        assert row.eps_ordered == (row.eps_xy < min(row.eps_x, row.eps_y))
        assert row.kind == brute_kind(row.c_diff, row.t_diff, 0.05, "both")
        assert row.weight == pytest.approx((abs(row.c_diff) + abs(row.t_diff)) / 2, abs=1e-15)


def test_pairs_equal_cross_measures_of_each_normalized_pair():
    # Reusing each signal's recurrence across its pairs must not change a single bit.
    data = signals(n=120, seed=4)
    net = quiet_network(data, delay=3)
    scaled = normalize(data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        for row, (i, j) in zip(net.pairs.itertuples(), [(0, 1), (0, 2), (1, 2)], strict=True):
            single = cross_measures(scaled[:, i], scaled[:, j], delay=3)
            for name in MEASURE_COLUMNS + ["eps_ordered", "rate_exceeded"]:
                assert getattr(row, name) == getattr(single, name), name
            assert row.degenerate == bool(single.degenerate)


# --- the mu rule, on crafted asymmetries --------------------------------------------------


def crafted(c_diff, t_diff, *, eps_ordered=True, rate_exceeded=False, degenerate=""):
    """A CrossMeasures with the given differences (other fields plausible placeholders)."""
    values = dict(
        c_xy=0.5 + c_diff / 2,
        c_yx=0.5 - c_diff / 2,
        t_xy=0.5 + t_diff / 2,
        t_yx=0.5 - t_diff / 2,
        c_diff=c_diff,
        t_diff=t_diff,
        eps_x=0.2,
        eps_y=0.25,
        eps_xy=0.1 if eps_ordered else 0.3,
        achieved_rr_x=0.05,
        achieved_rr_y=0.05,
        achieved_cr=0.05,
        eps_ordered=eps_ordered,
        rate_exceeded=rate_exceeded,
        degenerate=bool(degenerate),
        degenerate_reason=degenerate,
        m_x=40,
        m_y=40,
        parameters=NetworkParameters(),
    )
    return CrossMeasures(
        **{f.name: values[f.name] for f in fields(CrossMeasures) if f.name in values}
    )


@pytest.fixture
def fake_measures(monkeypatch):
    """Make functional_network see the crafted measures given per pair, in pair order."""
    calls = []

    def install(per_pair):
        def fake(signals, **kwargs):
            calls.append(kwargs)
            names = kwargs["names"]
            n = len(signals)
            keys = [(names[i], names[j]) for i in range(n) for j in range(i + 1, n)]
            assert len(keys) == len(per_pair)
            return dict(zip(keys, per_pair, strict=True))

        monkeypatch.setattr(network_module, "pairwise_cross_measures", fake)
        return calls

    return install


def noise(n_signals, n=40, seed=1):
    return np.random.default_rng(seed).normal(size=(n, n_signals))


RULE_CASES = [
    # c_diff, t_diff, mu, kind under "both"
    (-0.10, -0.08, 0.05, "x->y"),
    (0.10, 0.07, 0.05, "y->x"),
    (-0.10, 0.01, 0.05, "x->y"),  # one directed, one bidirectional
    (0.01, 0.06, 0.05, "y->x"),
    (0.01, -0.01, 0.05, "bidirectional"),
    (-0.10, 0.10, 0.05, "conflict"),  # opposite directions: no edge
    (-0.05, 0.0, 0.05, "x->y"),  # diff <= -mu is directed
    (0.05, 0.05, 0.05, "y->x"),
    (-0.0499, 0.0499, 0.05, "bidirectional"),
    (0.0, 0.0, 0.0, "bidirectional"),  # mu = 0: no asymmetry is still no direction
    (1e-12, 0.0, 0.0, "y->x"),
    (0.3, -0.3, 0.5, "bidirectional"),
]


@pytest.mark.parametrize(("c_diff", "t_diff", "mu", "both"), RULE_CASES)
@pytest.mark.parametrize("measure", ["both", "clustering", "transitivity"])
def test_edge_rule(fake_measures, c_diff, t_diff, mu, both, measure):
    fake_measures([crafted(c_diff, t_diff)])
    net = functional_network(noise(2), names=["X", "Y"], mu=mu, measure=measure)
    row = net.pairs.iloc[0]
    assert row["kind"] == brute_kind(c_diff, t_diff, mu, measure)
    assert brute_kind(c_diff, t_diff, mu, "both") == both
    assert row["c_kind"] == brute_kind(c_diff, t_diff, mu, "clustering")
    assert row["t_kind"] == brute_kind(c_diff, t_diff, mu, "transitivity")
    assert row["weight"] == (abs(c_diff) + abs(t_diff)) / 2  # Eq. 13, whatever the measure
    expected_edges = {
        "x->y": [("X", "Y", "directed")],
        "y->x": [("Y", "X", "directed")],
        "bidirectional": [("X", "Y", "bidirectional")],
        "conflict": [],
    }[row["kind"]]
    assert (
        list(net.edges[["source", "target", "kind"]].itertuples(index=False, name=None))
        == expected_edges
    )
    assert edge_kind(c_diff, mu) == row["c_kind"]
    assert combine_kinds(row["c_kind"], row["t_kind"]) == both


def four_node_network(fake_measures, **kwargs):
    # (A,B) x->y, (A,C) y->x, (A,D) conflict, (B,C) bidirectional, (B,D), (C,D) conflict.
    fake_measures(
        [
            crafted(-0.2, -0.1),
            crafted(0.1, 0.3),
            crafted(-0.2, 0.2),
            crafted(0.01, -0.02),
            crafted(0.1, -0.1),
            crafted(-0.3, 0.3),
        ]
    )
    return functional_network(noise(4), names=["A", "B", "C", "D"], label="crafted", **kwargs)


def test_edges_table(fake_measures):
    net = four_node_network(fake_measures)
    assert list(net.edges.itertuples(index=False, name=None)) == [
        ("A", "B", 0.15000000000000002, "directed", False),
        ("C", "A", 0.2, "directed", False),
        ("B", "C", 0.015, "bidirectional", False),
    ]
    assert list(net.pairs["kind"]) == [
        "x->y",
        "y->x",
        "conflict",
        "bidirectional",
        "conflict",
        "conflict",
    ]
    assert list(net.edges.dtypes.astype(str)) == ["str", "str", "float64", "str", "bool"]


def test_to_networkx_keeps_every_node_and_doubles_bidirectional_edges(fake_measures):
    graph = four_node_network(fake_measures).to_networkx()
    assert isinstance(graph, nx.DiGraph)
    assert list(graph.nodes) == ["A", "B", "C", "D"]  # D has no edge, only conflicts
    assert sorted(graph.edges) == [("A", "B"), ("B", "C"), ("C", "A"), ("C", "B")]
    arc = graph.edges["C", "A"]
    assert {k: arc[k] for k in ("weight", "kind", "degenerate")} == {
        "weight": 0.2, "kind": "directed", "degenerate": False}
    assert arc["direction"] == "none" and "too short" in arc["direction_reason"]
    assert (
        {k: graph.edges["B", "C"][k] for k in ("weight", "kind", "degenerate")}
        == {k: graph.edges["C", "B"][k] for k in ("weight", "kind", "degenerate")}
        == {"weight": 0.015, "kind": "bidirectional", "degenerate": False}
    )
    assert graph.graph["label"] == "crafted"
    assert graph.graph["parameters"]["mu"] == 0.05


def test_edges_for_each_measure(fake_measures):
    net = four_node_network(fake_measures)
    by_clustering = net.edges_for("clustering")
    # C_diff alone: A->B, C->A, A->D, B-C, D->B, A->... (C,D) -0.3 -> C->D.
    assert list(by_clustering[["source", "target", "kind"]].itertuples(index=False, name=None)) == [
        ("A", "B", "directed"),
        ("C", "A", "directed"),
        ("A", "D", "directed"),
        ("B", "C", "bidirectional"),
        ("D", "B", "directed"),
        ("C", "D", "directed"),
    ]
    by_transitivity = net.edges_for("transitivity")
    assert list(by_transitivity[["source", "target"]].itertuples(index=False, name=None)) == [
        ("A", "B"),
        ("C", "A"),
        ("D", "A"),
        ("B", "C"),
        ("B", "D"),
        ("D", "C"),
    ]
    assert net.edges_for("both").equals(net.edges)
    with pytest.raises(ParameterError, match="measure must be one of"):
        net.edges_for("degree")


def test_network_built_with_one_measure_can_give_the_combined_edges(fake_measures):
    net = four_node_network(fake_measures, measure="clustering")
    assert net.parameters.measure == "clustering"
    assert list(net.pairs["kind"]) == list(net.pairs["c_kind"])
    assert len(net.edges_for("both")) == 3


def test_calls_pairwise_once_with_the_parameters(fake_measures):
    calls = fake_measures([crafted(0.0, 0.0)] * 3)
    functional_network(
        noise(3), dim=4, delay=2, rr=0.1, cr=0.03, metric="supremum", rule="funcnet", theiler=1
    )
    assert calls == [
        dict(
            names=["0", "1", "2"],
            parameters=NetworkParameters(
                dim=4, delay=2, rr=0.1, cr=0.03, metric="supremum", rule="funcnet", theiler=1
            ),
            warn=True,
            step=1,  # every state: no max_states
        )
    ]


# --- warnings -----------------------------------------------------------------------------


def test_threshold_flags_reach_the_pairs_table(fake_measures):
    # The warnings themselves come from pairwise_cross_measures (test_measures.py).
    fake_measures(
        [
            crafted(0.0, 0.0, eps_ordered=False),
            crafted(0.0, 0.0),
            crafted(0.0, 0.0, rate_exceeded=True),
        ]
    )
    net = functional_network(noise(3), names=["RP", "AP", "AC"])
    assert list(net.pairs["eps_ordered"]) == [False, True, True]
    assert list(net.pairs["rate_exceeded"]) == [False, False, True]
    assert list(net.pairs["degenerate"]) == [False, False, False]


def test_degenerate_pairs_are_flagged_keep_their_kind_and_survive_json(fake_measures):
    per_pair = [
        crafted(-0.3, -0.3, degenerate="y"),
        crafted(-0.3, -0.3),
        crafted(0.3, 0.3, degenerate="x, xy"),
    ]
    fake_measures(per_pair)
    net = functional_network(noise(3), names=["RP", "AP", "V"])
    assert list(net.pairs.columns) == [
        "x", "y", *MEASURE_COLUMNS, "eps_ordered", "rate_exceeded", "degenerate",
        "degenerate_reason", "c_kind", "t_kind", "kind", "weight", "direction", "direction_reason",
    ]  # fmt: skip
    assert str(net.pairs["degenerate"].dtype) == "bool"
    assert list(net.pairs["degenerate"]) == [True, False, True]
    assert list(net.pairs["degenerate_reason"]) == ["y", "", "x, xy"]
    # the rule still gives every pair its kind; only the edges leave degenerate pairs out
    assert list(net.pairs["kind"]) == ["x->y", "x->y", "y->x"]
    assert list(net.edges[["source", "target"]].itertuples(index=False, name=None)) == [
        ("RP", "V")
    ]
    fake_measures(per_pair)
    kept = functional_network(noise(3), names=["RP", "AP", "V"], degenerate="keep")
    assert list(kept.edges["degenerate"]) == [True, False, True]
    back = FunctionalNetwork.from_json(net.to_json())
    pd.testing.assert_frame_equal(back.pairs, net.pairs)


def test_real_threshold_problems_warn_once_per_problem_with_names():
    # Integer-valued signals tie everywhere; min-max keeps the ties.
    rng = np.random.default_rng(5)
    data = pd.DataFrame(rng.integers(0, 4, size=(80, 3)), columns=["RP", "AP", "AC"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        net = functional_network(data, delay=1)
    threshold = [str(w.message) for w in caught if issubclass(w.category, ThresholdWarning)]
    problems = int((~net.pairs["eps_ordered"]).any()) + int(net.pairs["rate_exceeded"].any())
    assert net.pairs["rate_exceeded"].any()
    assert len(threshold) == problems  # core's own warnings are not repeated
    assert all(
        "(RP, AP)" in message or "(AP, AC)" in message or "(RP, AC)" in message
        for message in threshold
    )
    assert not any("(0, 1)" in message for message in threshold)
    # Attributed to the line that called functional_network, not to funcnet's own code.
    assert {w.filename for w in caught if issubclass(w.category, ThresholdWarning)} == {__file__}


def test_a_signal_that_barely_moves_gets_an_explicit_warning_naming_it():
    rng = np.random.default_rng(3)
    data = pd.DataFrame(
        {
            "RP": rng.random(200),
            "AP": rng.random(200),
            "AC": np.r_[np.full(180, 2.0), np.linspace(2.0, 2.001, 20)],  # min-max keeps it flat
        }
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        net = functional_network(data, delay=1)
    rows = net.pairs.set_index(["x", "y"])
    assert rows.loc[("RP", "AC"), "eps_y"] == 0.0 and rows.loc[("RP", "AC"), "achieved_rr_y"] > 0.8
    messages = [str(w.message) for w in caught if issubclass(w.category, ThresholdWarning)]
    degenerate = [m for m in messages if m.startswith("degenerate recurrence structure")]
    assert len(degenerate) == 1
    assert "signal AC (rr 0.8" in degenerate[0]
    assert "meaningless: (RP, AC), (AP, AC)" in degenerate[0]
    assert len(messages) == len(set(messages)) <= 3  # at most one per problem
    assert not any("ties at a threshold" in m for m in messages)


# --- inputs -------------------------------------------------------------------------------


def test_dataframe_columns_become_nodes_and_match_the_array_form():
    data = signals(n=70, seed=2)
    frame = pd.DataFrame(data, columns=["RP", "AP", "AC"])
    from_frame = quiet_network(frame, delay=2)
    from_array = quiet_network(data, names=["RP", "AP", "AC"], delay=2)
    assert from_frame.nodes == ("RP", "AP", "AC")
    assert from_frame == from_array
    unnamed = quiet_network(data, delay=2)
    assert unnamed.nodes == ("0", "1", "2")
    assert quiet_network(pd.DataFrame(data), delay=2).nodes == ("0", "1", "2")


def test_parameters_and_label_are_recorded():
    net = quiet_network(
        signals(n=60),
        delay=2,
        rr=0.1,
        mu=0.02,
        normalize="zscore",
        measure="transitivity",
        metric="manhattan",
        theiler=1,
        label="cruise",
    )
    assert net.parameters == NetworkParameters(
        dim=3,
        delay=2,
        rr=0.1,
        cr=0.05,
        mu=0.02,
        metric="manhattan",
        normalize="zscore",
        measure="transitivity",
        rule="funcnet",
        theiler=1,
    )
    assert net.n_samples == 60
    assert net.label == "cruise"


@pytest.mark.parametrize(
    ("kwargs", "error", "pattern"),
    [
        (dict(mu=-0.01), ParameterError, "mu must be finite and >= 0"),
        (dict(mu=float("nan")), ParameterError, "mu must be finite"),
        (dict(mu="0.05"), ParameterError, "mu must be a number"),
        (dict(measure="degree"), ParameterError, "measure must be one of"),
        (dict(normalize="robust"), ParameterError, "normalize must be one of"),
        (dict(names=["a", "b"]), ParameterError, "names has 2 entries for 3 signal"),
        (dict(names=["a", "b", "a"]), ParameterError, "names must be unique; repeated: a"),
        (dict(rr=1.5), ParameterError, "rr"),
        (dict(metric="cosine"), ParameterError, "metric"),
    ],
)
def test_bad_parameters(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        functional_network(signals(n=60), **kwargs)


BAD_VALUES = [
    # parameter, bad value, message
    ("dim", 0, "dim must be >= 1, got 0"),
    ("dim", 2.5, "dim must be an integer"),
    ("delay", 0, "delay must be >= 1, got 0"),
    ("delay", True, "delay must be an integer"),
    ("rr", 2, r"rr must be in \(0, 1\), got 2.0"),
    ("rr", 0.0, r"rr must be in \(0, 1\)"),
    ("rr", "0.05", "rr must be a number"),
    ("cr", 1.0, r"cr must be in \(0, 1\)"),
    ("mu", -0.01, "mu must be finite and >= 0"),
    ("mu", float("inf"), "mu must be finite"),
    ("metric", "cosine", "metric must be one of .*'cosine'"),
    ("normalize", "robust", "normalize must be one of"),
    ("measure", "degree", "measure must be one of"),
    ("rule", "scipy", "rule must be one of"),
    ("theiler", -1, "theiler must be >= 0"),
]


@pytest.mark.parametrize(("name", "value", "pattern"), BAD_VALUES)
def test_parameters_reject_each_bad_value_without_data(name, value, pattern):
    with pytest.raises(ParameterError, match=pattern) as without_data:
        NetworkParameters(**{name: value})
    assert name in str(without_data.value)
    # functional_network raises the very same message, before it looks at the data.
    with pytest.raises(ParameterError) as with_data:
        functional_network(signals(n=60), **{name: value})
    assert str(with_data.value) == str(without_data.value)
    with pytest.raises(ParameterError) as without_signals:
        functional_network(None, **{name: value})
    assert str(without_signals.value) == str(without_data.value)


def test_parameters_accept_every_option():
    NetworkParameters(dim=1, delay=1, rr=0.3, cr=1e-3, mu=0.0, metric="manhattan")
    NetworkParameters(normalize=None, measure="transitivity", rule="pyunicorn", theiler=0)
    with pytest.raises(ParameterError, match="theiler must be 0 with rule='pyunicorn'"):
        NetworkParameters(rule="pyunicorn", theiler=2)


def test_bad_signals_are_named():
    data = signals(n=60)
    with pytest.raises(SignalError, match="at least two signals, got 1"):
        functional_network(data[:, :1])
    with pytest.raises(SignalError, match="at least two signals, got 1"):
        functional_network(data[:, 0])
    frame = pd.DataFrame(data, columns=["RP", "AP", "AC"])
    frame.loc[7, "AP"] = np.nan
    with pytest.raises(SignalError, match="signal 'AP' holds NaN"):
        functional_network(frame)
    frame = pd.DataFrame(data, columns=["RP", "AP", "AC"]).assign(AC=2.0)
    with pytest.raises(SignalError, match="signal 'AC' is constant"):
        functional_network(frame)
    with pytest.raises(ParameterError, match="columns of data must be unique"):
        functional_network(pd.DataFrame(data, columns=["RP", "RP", "AC"]))
    with pytest.raises(SignalError, match="signal 'RP' is too short"):
        functional_network(pd.DataFrame(data[:15], columns=["RP", "AP", "AC"]), delay=10)


# --- export -------------------------------------------------------------------------------


def test_json_round_trip_is_exact():
    net = quiet_network(
        signals(n=80, seed=7),
        names=["RP", 'A"P', "Strom ÄC"],
        delay=2,
        label="braking 5000–5700 ms",
    )
    text = net.to_json()
    back = FunctionalNetwork.from_json(text)
    assert back == net
    for name in MEASURE_COLUMNS + ["weight"]:
        np.testing.assert_array_equal(
            back.pairs[name].to_numpy().view(np.int64), net.pairs[name].to_numpy().view(np.int64)
        )
    pd.testing.assert_frame_equal(back.pairs, net.pairs)
    pd.testing.assert_frame_equal(back.edges, net.edges)
    assert back.to_json() == text
    assert json.loads(text)["nodes"] == ["RP", 'A"P', "Strom ÄC"]


def test_json_round_trip_without_edges_or_label(fake_measures):
    fake_measures([crafted(-0.2, 0.2)])  # a conflict: no edge at all
    net = functional_network(noise(2), names=["X", "Y"])
    assert net.edges.empty and net.label is None
    back = FunctionalNetwork.from_json(net.to_json())
    assert back == net
    assert list(back.edges.dtypes.astype(str)) == ["str", "str", "float64", "str", "bool"]


def test_from_json_rejects_other_documents():
    with pytest.raises(ParameterError, match="not a funcnet functional network"):
        FunctionalNetwork.from_json('{"format": "something else"}')
    with pytest.raises(ParameterError, match="not a funcnet functional network"):
        FunctionalNetwork.from_json("not json")


def test_equality_sees_a_changed_number(fake_measures):
    fake_measures([crafted(-0.2, -0.1)])
    net = functional_network(noise(2), names=["X", "Y"])
    changed = FunctionalNetwork(
        net.nodes, net.pairs.assign(weight=0.5), net.edges, net.parameters, net.n_samples, net.label
    )
    assert changed != net
    assert FunctionalNetwork.from_json(net.to_json()) == net


def test_write_json_and_graphml(tmp_path, fake_measures):
    net = four_node_network(fake_measures)
    json_path = net.write(tmp_path / "net.json")
    assert FunctionalNetwork.from_json(json_path.read_text(encoding="utf-8")) == net
    graphml_path = net.write(tmp_path / "sub" / "net.GraphML")
    graph = nx.read_graphml(graphml_path)
    assert sorted(graph.nodes) == ["A", "B", "C", "D"]
    assert sorted(graph.edges) == [("A", "B"), ("B", "C"), ("C", "A"), ("C", "B")]
    assert graph.edges["A", "B"]["weight"] == 0.15000000000000002
    assert graph.edges["C", "B"]["kind"] == "bidirectional"
    assert graph.graph["label"] == "crafted"
    assert NetworkParameters.from_mapping(json.loads(graph.graph["parameters"])) == net.parameters
    # Atomic writes leave no temporary files behind.
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == ["net.GraphML", "net.json"]
    with pytest.raises(ParameterError, match=r"\.json or \.graphml"):
        net.write(tmp_path / "net.csv")
    assert not (tmp_path / "net.csv").exists()


def test_read_restores_the_written_network_exactly(tmp_path):
    net = quiet_network(
        signals(n=80, seed=7), names=["RP", 'A"P', "Strom ÄC"], delay=2, label="braking"
    )
    back = FunctionalNetwork.read(net.write(tmp_path / "net.json"))
    assert back == net
    for name in MEASURE_COLUMNS + ["weight"]:
        np.testing.assert_array_equal(
            back.pairs[name].to_numpy().view(np.int64), net.pairs[name].to_numpy().view(np.int64)
        )
    assert back.to_json() == net.to_json()
    assert FunctionalNetwork.read(str(tmp_path / "net.json")) == net  # a str path too


def test_read_refuses_what_it_cannot_restore(tmp_path, fake_measures):
    net = four_node_network(fake_measures)
    assert FunctionalNetwork.read(net.write(tmp_path / "net.graphml")) == net
    foreign = tmp_path / "foreign.graphml"
    nx.write_graphml(nx.DiGraph([("A", "B")]), foreign)  # no pairs table in it
    with pytest.raises(ParameterError, match=r"foreign\.graphml.*cannot be read back"):
        FunctionalNetwork.read(foreign)
    with pytest.raises(ParameterError, match=r"must end in \.json or \.graphml, got 'net\.csv'"):
        FunctionalNetwork.read(tmp_path / "net.csv")
    other = tmp_path / "other.json"
    other.write_text('{"format": "something else"}', encoding="utf-8")
    with pytest.raises(ParameterError, match=r"other\.json: text is not a funcnet"):
        FunctionalNetwork.read(other)
    binary = tmp_path / "binary.json"
    binary.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(ParameterError, match=r"binary\.json"):
        FunctionalNetwork.read(binary)
    with pytest.raises(FileNotFoundError):
        FunctionalNetwork.read(tmp_path / "missing.json")


def test_repr_is_short(fake_measures):
    net = four_node_network(fake_measures)
    assert repr(net) == (
        "FunctionalNetwork('crafted', 4 nodes, 2 directed, 1 bidirectional, "
        "3 conflict; measure='both', mu=0.05)"
    )
    html_text = net._repr_html_()
    assert html_text.count("<tr") == 4  # header + three edges
    assert "0.1500" in html_text
