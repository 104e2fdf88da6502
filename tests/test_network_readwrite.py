"""Readers and writers; one degenerate pair followed through every exporter."""

from __future__ import annotations

import dataclasses
import json
import warnings
from pathlib import Path

import networkx as nx
import numpy as np
import pandas as pd
import pytest

from funcnet.errors import DegenerateWarning, ParameterError, ThresholdWarning
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.network.readwrite import VERSION, fields_from_json, read_fields, to_json
from funcnet.network.schema import EDGE_COLUMNS, MEASURE_COLUMNS, PAIR_COLUMNS
from funcnet.parameters import NetworkParameters

V1_FILE = Path(__file__).parent / "data" / "network_v1.json"


def quantized_data(n=300, seed=1):
    """Two rough signals with one real arrow (B is a smoothed A) and a signal with 3 values."""
    rng = np.random.default_rng(seed)
    a = rng.random(n)
    b = np.convolve(a, np.ones(3) / 3, mode="same") + 0.05 * rng.random(n)
    q = np.round(2 * rng.random(n))
    return pd.DataFrame({"A": a, "B": b, "Q": q})


def network(data, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        return functional_network(data, delay=1, **kwargs)


def edge_list(edges):
    return list(edges[["source", "target", "degenerate"]].itertuples(index=False, name=None))


# --- one degenerate pair through everything -------------------------------------------------


def test_a_quantized_signal_is_degenerate_and_no_edge_by_default():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        net = functional_network(quantized_data(), delay=1, label="quantized")
    rows = net.pairs.set_index(["x", "y"])
    assert list(rows["degenerate"]) == [False, True, True]
    assert rows.loc[("A", "B"), "degenerate_reason"] == ""
    assert rows.loc[("A", "Q"), "degenerate_reason"] != ""
    assert rows.loc[("B", "Q"), "degenerate_reason"] != ""
    # The degenerate pairs carry the heaviest "arrows"; they are kept in the pairs table only.
    assert rows.loc[("A", "Q"), "weight"] > rows.loc[("A", "B"), "weight"]
    assert rows.loc[("A", "B"), "kind"] == "x->y"
    assert edge_list(net.edges) == [("A", "B", False)]
    assert "1 directed, 0 bidirectional, 0 conflict, 2 degenerate" in repr(net)
    degenerate = [w.message for w in caught if issubclass(w.category, DegenerateWarning)]
    assert len(degenerate) == 1
    assert set(degenerate[0].pairs) == {("A", "Q"), ("B", "Q")}

    kept = network(quantized_data(), degenerate="keep")
    assert kept.pairs.equals(net.pairs)
    assert edge_list(kept.edges) == [("A", "B", False), ("Q", "A", True), ("Q", "B", True)]
    assert kept.edges_for(degenerate="drop").equals(net.edges)
    assert net.edges_for(degenerate="keep").equals(kept.edges)


@pytest.mark.parametrize("policy", ["drop", "keep"])
def test_the_degenerate_flag_travels_through_every_exporter(tmp_path, policy):
    net = network(quantized_data(), degenerate=policy, label="quantized")
    expected = {("A", "B"): False} if policy == "drop" else {
        ("A", "B"): False, ("Q", "A"): True, ("Q", "B"): True
    }

    # networkx
    graph = net.to_networkx()
    assert list(graph.nodes) == ["A", "B", "Q"]  # Q stays a node without edges
    assert {(u, v): attrs["degenerate"] for u, v, attrs in graph.edges(data=True)} == expected
    assert graph.graph["parameters"]["degenerate"] == policy

    # GraphML, read by networkx itself
    path = net.write(tmp_path / "net.graphml")
    read = nx.read_graphml(path)
    assert {(u, v): attrs["degenerate"] for u, v, attrs in read.edges(data=True)} == expected
    assert all(type(attrs["degenerate"]) is bool for *_, attrs in read.edges(data=True))
    assert read.graph["label"] == "quantized" and read.graph["n_samples"] == 300
    assert NetworkParameters.from_mapping(json.loads(read.graph["parameters"])) == net.parameters
    assert FunctionalNetwork.read(path) == net

    # JSON, exact
    back = FunctionalNetwork.from_json(net.to_json())
    assert back == net
    pd.testing.assert_frame_equal(back.pairs, net.pairs)
    pd.testing.assert_frame_equal(back.edges, net.edges)
    for name in MEASURE_COLUMNS:
        np.testing.assert_array_equal(
            back.pairs[name].to_numpy().view(np.int64), net.pairs[name].to_numpy().view(np.int64)
        )
    assert list(back.pairs["degenerate_reason"]) == list(net.pairs["degenerate_reason"])
    assert FunctionalNetwork.read(net.write(tmp_path / "net.json")) == net


def test_equality_sees_the_degenerate_flag_and_the_new_fields():
    net = network(quantized_data(n=150))
    flipped = net.pairs.assign(degenerate=~net.pairs["degenerate"])
    assert dataclasses.replace(net, pairs=flipped) != net
    assert dataclasses.replace(net, n_samples=151) != net
    assert dataclasses.replace(net, window={"label": "w"}) != net
    assert dataclasses.replace(net, parameters=net.parameters.replace(mu_t=0.1)) != net


# --- JSON ----------------------------------------------------------------------------------


def test_window_and_channels_round_trip():
    data = quantized_data(n=150).assign(A2=lambda d: d["A"] ** 2, B2=lambda d: -d["B"] ** 3)
    net = network(data, nodes={"AA": ["A", "A2"], "B": ["B", "B2"]}, rr=(0.05, 0.1))
    net = dataclasses.replace(
        net,
        window={"label": "cruise", "start": 1.0, "stop": 1.6, "phase": None, "dropped": ("Q",)},
    )
    text = net.to_json()
    document = json.loads(text)
    assert document["version"] == VERSION == 2
    assert document["channels"] == {"AA": ["A", "A2"], "B": ["B", "B2"]}
    assert document["parameters"]["rr"] == [0.05, 0.1]
    back = FunctionalNetwork.from_json(text)
    assert back == net
    assert back.window == net.window and back.channels == net.channels
    assert back.parameters.rr == (0.05, 0.1)
    assert back.to_json() == text


def test_version_1_files_are_refused_by_version():
    # Version 1 was never released: its files are not read (the numbers are, below).
    with pytest.raises(ParameterError, match="unknown version 1"):
        FunctionalNetwork.read(V1_FILE)


def test_todays_code_reproduces_the_numbers_of_a_version_1_file():
    old = json.loads(V1_FILE.read_text(encoding="utf-8"))
    net = network(quantized_data(n=120), label="cruise")
    renamed = {"achieved_rr_x": "rr_x", "achieved_rr_y": "rr_y", "achieved_cr": "cr"}
    for name in MEASURE_COLUMNS:
        assert list(net.pairs[name]) == old["pairs"][renamed.get(name, name)], name
    for name in ("eps_ordered", "rate_exceeded", "degenerate", "c_kind", "t_kind", "kind",
                 "weight"):
        assert list(net.pairs[name]) == old["pairs"][name], name


@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ("not json", "not a funcnet functional network"),
        ("[1, 2]", "format is"),
        ('{"format": "funcnet.FunctionalNetwork", "version": 3}', "unknown version 3"),
        ('{"format": "funcnet.FunctionalNetwork", "version": 2}', "not a funcnet"),
    ],
)
def test_from_json_rejects_other_documents(text, pattern):
    with pytest.raises(ParameterError, match=pattern):
        fields_from_json(text)


def test_a_document_with_a_bad_parameter_or_table_is_refused():
    net = network(quantized_data(n=100))
    document = json.loads(to_json(net))
    document["parameters"]["rr"] = 2.0
    with pytest.raises(ParameterError, match=r"rr must be in \(0, 1\)"):
        FunctionalNetwork.from_json(json.dumps(document))
    document = json.loads(to_json(net))
    del document["pairs"]["degenerate_reason"]
    with pytest.raises(ParameterError, match="missing: degenerate_reason"):
        FunctionalNetwork.from_json(json.dumps(document))
    assert set(json.loads(to_json(net))["pairs"]) == set(PAIR_COLUMNS)
    assert set(json.loads(to_json(net))["edges"]) == set(EDGE_COLUMNS)


# --- files ---------------------------------------------------------------------------------


def test_files_that_hold_no_network_are_named(tmp_path):
    foreign = tmp_path / "foreign.graphml"
    nx.write_graphml(nx.DiGraph([("A", "B")]), foreign)
    with pytest.raises(ParameterError, match=r"foreign\.graphml: .*cannot be read back"):
        read_fields(foreign)
    broken = tmp_path / "broken.graphml"
    broken.write_text("<graphml><graph", encoding="utf-8")
    with pytest.raises(ParameterError, match=r"broken\.graphml: not a GraphML file"):
        read_fields(broken)
    with pytest.raises(ParameterError, match=r"path must end in \.json or \.graphml"):
        read_fields(tmp_path / "net.gml")
    net = network(quantized_data(n=100))
    with pytest.raises(ParameterError, match=r"path must end in \.json or \.graphml"):
        net.write(tmp_path / "net.gml")
    assert not (tmp_path / "net.gml").exists()
    with pytest.raises(FileNotFoundError):
        read_fields(tmp_path / "missing.graphml")


def test_networkx_is_imported_only_by_what_uses_it():
    """A report and the command line start without networkx (its import is slow); the graph
    writers still give a networkx graph and a GraphML file."""
    import subprocess
    import sys

    code = ("import sys, funcnet, funcnet.cli, funcnet.report.inspect, funcnet.network; "
            "print('networkx' in sys.modules)")
    found = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True)
    assert found.stdout.strip() == "False"
    network = functional_network(quantized_data(), delay=1)
    assert isinstance(network.to_networkx(), nx.DiGraph)
