"""Nodes of a functional network: multichannel nodes, per-node rates, bad inputs."""

from __future__ import annotations

import math
import warnings
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest

import funcnet.network.functional as functional
from funcnet.core.measures import cross_measures
from funcnet.core.normalization import normalize
from funcnet.errors import ParameterError, SignalError, ThresholdWarning
from funcnet.network import functional_network
from funcnet.parameters import NetworkParameters


def quiet(data, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        return functional_network(data, **kwargs)


def recording(n=110, seed=3):
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    return pd.DataFrame(
        {
            "AP": np.sin(t / 7) + 0.2 * rng.random(n),
            "MP": np.sin(t / 7 + 0.3) + 0.2 * rng.random(n),
            "AC": rng.random(n),
            "V": np.cos(t / 5) + 0.1 * rng.random(n),
            "RP": np.sin(t / 7 - 0.2),
            "RC": np.cos(t / 7) + 0.3 * rng.random(n),
        }
    )


# --- an independent dense reference for multichannel states ------------------------------


def brute_states(columns, dim, delay):
    """Each channel embedded (Eq. 1), the states concatenated channel after channel."""
    m = len(columns[0]) - (dim - 1) * delay
    return np.hstack(
        [np.array([[x[i + j * delay] for j in range(dim)] for i in range(m)]) for x in columns]
    )


def kth(values, rate):
    k = max(1, math.ceil(Fraction(repr(rate)) * values.size))
    return np.sort(values, kind="stable")[k - 1]


def brute_cross(cross, auto):
    local, triangles, triples = [], 0, 0
    for row in cross.astype(float):
        k = row.sum()
        tri = row @ auto.astype(float) @ row
        local.append(tri / (k * (k - 1)) if k >= 2 else 0.0)
        triangles += tri
        triples += k * (k - 1)
    return float(np.mean(local)), (triangles / triples if triples else 0.0)


def brute_pair(xs, ys, rr_x, rr_y, cr):
    def dist(a, b):
        diff = a[:, None, :] - b[None, :, :]
        return np.sqrt(np.einsum("ijk,ijk->ij", diff, diff))

    off = ~np.eye(len(xs), dtype=bool)
    d_x, d_y, d_xy = dist(xs, xs), dist(ys, ys), dist(xs, ys)
    a_x = (d_x <= kth(d_x[off], rr_x)) & off
    a_y = (d_y <= kth(d_y[off], rr_y)) & off
    c = d_xy <= kth(d_xy.ravel(), cr)
    c_xy, t_xy = brute_cross(c, a_y)
    c_yx, t_yx = brute_cross(c.T, a_x)
    return dict(c_xy=c_xy, c_yx=c_yx, t_xy=t_xy, t_yx=t_yx)


# --- multichannel nodes --------------------------------------------------------------------


def test_a_multichannel_node_equals_its_concatenated_embedding():
    data = recording()
    groups = {"axis": ["AP", "MP"], "drive": ["AC", "V"], "set": ["RP", "RC"]}
    net = quiet(data, nodes=groups, delay=2, rr=0.08)
    assert net.nodes == ("axis", "drive", "set")
    assert net.channels == {name: tuple(columns) for name, columns in groups.items()}
    scaled = normalize(data)  # every channel on its own
    states = {
        name: brute_states([scaled[c].to_numpy() for c in columns], 3, 2)
        for name, columns in groups.items()
    }
    assert states["axis"].shape == (106, 6)
    for row in net.pairs.itertuples():
        expected = brute_pair(states[row.x], states[row.y], 0.08, 0.08, 0.05)
        for name, value in expected.items():
            assert getattr(row, name) == pytest.approx(value, abs=1e-12, rel=0), (row.x, row.y)


def test_single_column_nodes_are_bit_for_bit_the_plain_columns():
    data = recording()
    plain = quiet(data[["AP", "AC", "V"]], delay=2)
    grouped = quiet(data, nodes={"AP": ["AP"], "AC": "AC", "V": "V"}, delay=2)
    assert grouped.pairs.equals(plain.pairs) and grouped.edges.equals(plain.edges)
    assert grouped.nodes == plain.nodes and grouped.channels is not None
    # Renaming a node changes its name only.
    renamed = quiet(data, nodes={"arm": "AP", "AC": "AC", "V": "V"}, delay=2)
    assert list(renamed.pairs["x"]) == ["arm", "arm", "AC"]
    assert renamed.pairs.drop(columns=["x", "y"]).equals(plain.pairs.drop(columns=["x", "y"]))


# --- per-node rates ------------------------------------------------------------------------


def test_per_node_rates_reach_the_measures(monkeypatch):
    seen = []

    def fake(signals, **kwargs):
        seen.append(kwargs["parameters"])
        raise SignalError("stop here")

    monkeypatch.setattr(functional, "pairwise_cross_measures", fake)
    with pytest.raises(SignalError, match="stop here"):
        functional_network(recording()[["AP", "MP", "AC", "V"]], rr=(0.05, 0.1, 0.2, 0.05),
                           eps=((None, 0.3, None, None), None))
    assert seen[0].rr == (0.05, 0.1, 0.2, 0.05)
    assert seen[0].eps == ((None, 0.3, None, None), None)


def test_per_node_rates_give_the_pairs_their_own_rates():
    data = recording()
    rates = (0.05, 0.1, 0.15)
    net = quiet(data[["AP", "AC", "V"]], delay=2, rr=rates)
    scaled = normalize(data[["AP", "AC", "V"]].to_numpy())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        for row, (i, j) in zip(net.pairs.itertuples(), [(0, 1), (0, 2), (1, 2)], strict=True):
            single = cross_measures(scaled[:, i], scaled[:, j], delay=2, rr=(rates[i], rates[j]))
            for name in ("c_xy", "c_yx", "t_xy", "t_yx", "eps_x", "eps_y", "eps_xy",
                         "achieved_rr_x", "achieved_rr_y"):
                assert getattr(row, name) == getattr(single, name), name
    rows = net.pairs.set_index(["x", "y"])
    assert rows.loc[("AP", "AC"), "achieved_rr_y"] == pytest.approx(0.1, abs=0.01)
    assert rows.loc[("AC", "V"), "achieved_rr_y"] == pytest.approx(0.15, abs=0.01)
    assert net.parameters.rr == rates


# --- bad inputs ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("nodes", "error", "pattern"),
    [
        (["AP", "AC"], ParameterError, "nodes must be a mapping"),
        ({"axis": ["AP", "XX"], "AC": "AC"}, ParameterError,
         r"node 'axis' names unknown column\(s\) 'XX' \(columns: AP, MP, AC, V, RP, RC\)"),
        ({"axis": ["AP", "MP"], "arm": "AP"}, ParameterError,
         "column 'AP' is in node 'axis' and in node 'arm'"),
        ({"axis": ["AP", "AP"], "AC": "AC"}, ParameterError, "column 'AP' is in node 'axis'"),
        ({"axis": [], "AC": "AC"}, ParameterError, "node 'axis' must be a column or a non-empty"),
        ({"axis": 3, "AC": "AC"}, ParameterError, "node 'axis' must be a column"),
        ({"axis": ["AP", "MP"]}, SignalError, "at least two signals, got 1"),
        ({"axis": ["AP", "MP"], "AC": "AC"}, ParameterError,
         "same number of columns .*'axis' 2, 'AC' 1"),
        ({}, SignalError, "at least two signals, got 0"),
    ],
)  # fmt: skip
def test_bad_nodes_are_named(nodes, error, pattern):
    with pytest.raises(error, match=pattern):
        functional_network(recording(), nodes=nodes)


def test_bad_data_is_named():
    data = recording()
    with pytest.raises(SignalError, match=r"1-D or 2-D .*shape \(2, 3, 4\)"):
        functional_network(np.zeros((2, 3, 4)))
    with pytest.raises(SignalError, match="signals must be real numbers"):
        functional_network(np.array([["a", "b"], ["c", "d"]]))
    with pytest.raises(SignalError, match="signal 'AP' is not numeric"):
        functional_network(data.assign(AP="x"))
    # A column left out of every node is not read at all.
    only = quiet(data.assign(note="x"), nodes={"AP": "AP", "V": "V"}, delay=2)
    assert only.nodes == ("AP", "V")
    with pytest.raises(SignalError, match="signal 'MP' is constant"):
        functional_network(data.assign(MP=1.0), nodes={"axis": ["AP", "MP"], "v": ["V", "AC"]})
    with pytest.raises(ParameterError, match=r"names has 2 entries for 6 signal\(s\)"):
        functional_network(data.to_numpy(), names=["a", "b"])
    with pytest.raises(ParameterError, match="rr"):
        functional_network(data, rr=(0.05, 0.1))  # one rate per node, 6 nodes


def test_parameters_object_and_overrides_combine():
    data = recording()
    base = NetworkParameters(delay=2, mu=0.1)
    net = quiet(data, parameters=base, rr=0.1)
    assert net.parameters == base.replace(rr=0.1)
    with pytest.raises(ParameterError, match="radius is not a network parameter"):
        functional_network(data, radius=0.1)
    with pytest.raises(ParameterError, match="parameters must be a NetworkParameters"):
        functional_network(data, parameters={"delay": 2})
