"""functional_network(..., evidence=True): the columns, the readings, the formats, the switch."""

from __future__ import annotations

import warnings

import networkx as nx
import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ParameterError
from funcnet.network import FunctionalNetwork, add_evidence, functional_network
from funcnet.network.schema import EVIDENCE_COLUMNS, PAIR_COLUMNS, check_pairs
from funcnet.validation import systems


@pytest.fixture(scope="module")
def data():
    # a -> b coupled Henon maps; c, d uncoupled logistic maps r = 3.7, 4.0 (an arrow without
    # coupling, tests/test_direction.py).
    return np.column_stack([
        systems.henon_pair(400, 0.6, seed=0), systems.logistic_pair(400, 3.7, 4.0, seed=1),
    ])


@pytest.fixture(scope="module")
def networks(data):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = functional_network(data, names=list("abcd"), delay=1)
        full = functional_network(data, names=list("abcd"), delay=1, evidence=True,
                                  resamples=100)
    return plain, full


def test_evidence_is_off_by_default_and_leaves_the_plain_network_unchanged(networks):
    plain, full = networks
    assert list(plain.pairs.columns) == list(PAIR_COLUMNS) and plain.evidence is None
    assert list(full.pairs.columns) == [*PAIR_COLUMNS, *EVIDENCE_COLUMNS]
    # The paper's numbers and kinds are the plain network's, bit for bit.
    assert full.pairs[list(PAIR_COLUMNS)].equals(plain.pairs)
    assert full.edges.equals(plain.edges)
    check_pairs(full.pairs)


def test_readings_of_known_pairs(networks):
    _, full = networks
    pairs = full.pairs.set_index(["x", "y"])
    assert pairs.loc[("a", "b"), "coupled"]
    assert pairs.loc[("a", "b"), "evidence"] in ("coupled", "coupled-directed")
    # Uncoupled logistic maps: the paper's rule draws an arrow, nothing supports coupling.
    row = pairs.loc[("c", "d")]
    assert row["kind"] == "y->x" and not row["coupled"] and row["evidence"] == "asymmetry-only"
    # 6 pairs: the default K is 6 / 0.05 - 1 = 119; the coupled pairs' intervals are drawn
    # (by default theirs only) and hold their difference.
    assert (full.pairs["surrogates"] == 120).all()  # an even lattice: 2 x 60
    coupled = full.pairs["coupled"].astype(bool)
    drawn = full.pairs[coupled]
    assert len(drawn) and (drawn["c_diff_low"] <= drawn["c_diff"]).all()
    assert (drawn["c_diff"] <= drawn["c_diff_high"]).all()
    assert full.pairs.loc[~coupled, "c_diff_low"].isna().all()
    assert full.evidence["alpha"] == 0.05 and full.evidence["edge_rule"] == "paper"


def test_the_seed_reproduces_the_table(data, networks):
    _, full = networks
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        again = functional_network(data, names=list("abcd"), delay=1, evidence=True,
                                   resamples=100)
    assert again == full


def test_json_graphml_and_networkx_carry_the_evidence(networks, tmp_path):
    _, full = networks
    assert FunctionalNetwork.from_json(full.to_json()) == full
    for suffix in ("json", "graphml"):
        assert FunctionalNetwork.read(full.write(tmp_path / f"n.{suffix}")) == full
    graph = full.to_networkx()
    (arc,) = [a for s, t, a in graph.edges(data=True) if {s, t} == {"c", "d"}]
    assert arc["evidence"] == "asymmetry-only" and arc["coupled"] is False
    read = nx.read_graphml(tmp_path / "n.graphml")
    assert {a["evidence"] for _, _, a in read.edges(data=True)} <= {
        "coupled-directed", "coupled", "not-coupled", "asymmetry-only"}


def test_interval_edge_rule(data):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        network = functional_network(data, names=list("abcd"), delay=1, evidence=True,
                                     resamples=100, edge_rule="interval")
    pairs = network.pairs
    directed = pairs["c_kind"].isin(["x->y", "y->x"])
    excludes = (pairs["c_diff_low"] > 0) | (pairs["c_diff_high"] < 0)
    assert (~directed | excludes).all()  # directed only when the interval excludes 0
    assert network.evidence["edge_rule"] == "interval"


def test_bad_evidence_arguments_are_named(data):
    with pytest.raises(ParameterError, match="edge_rule"):
        functional_network(data, edge_rule="interval")  # needs evidence=True
    with pytest.raises(ParameterError, match="edge_rule"):
        functional_network(data, evidence=True, edge_rule="strict")
    with pytest.raises(ParameterError, match="alpha"):
        functional_network(data, delay=1, evidence=True, alpha=1.5, warn=False)


def test_twin_surrogates_and_no_intervals_pass_through(data, networks):
    _, full = networks
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        twin = functional_network(data, names=list("abcd"), delay=1, evidence=True,
                                  resamples=0, surrogate_method="twin")
    assert twin.evidence["surrogate_method"] == "twin" and twin.evidence["resamples"] == 0
    assert full.evidence["surrogate_method"] == "shift"
    # Twins need no shortened window: K is what was asked (119 for 6 pairs).
    assert (twin.pairs["surrogates"] == 119).all()
    for column in ("c_diff_low", "c_diff_high", "t_diff_low", "t_diff_high",
                   "c_sign_fraction", "t_sign_fraction"):
        assert twin.pairs[column].isna().all(), column
    pairs = twin.pairs.set_index(["x", "y"])
    assert pairs.loc[("a", "b"), "coupled"] and not pairs.loc[("c", "d"), "coupled"]
    assert FunctionalNetwork.from_json(twin.to_json()) == twin
    with pytest.raises(ParameterError, match="surrogate_method"):
        functional_network(data, delay=1, evidence=True, surrogate_method="circular",
                           warn=False)


def test_add_evidence_to_a_plain_network_equals_computing_it_with_evidence(data, networks):
    plain, full = networks
    assert add_evidence(plain, data, resamples=100) == full
    frame = pd.DataFrame(data, columns=list("abcd"))
    assert add_evidence(plain, frame[list("dcba")], resamples=100) == full  # by column name
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        interval = functional_network(data, names=list("abcd"), delay=1, evidence=True,
                                      resamples=100, edge_rule="interval")
    assert add_evidence(plain, data, resamples=100, edge_rule="interval") == interval


def test_add_evidence_to_multichannel_nodes(data):
    frame = pd.DataFrame(data, columns=["a1", "a2", "b1", "b2"])
    nodes = {"A": ["a1", "a2"], "B": ["b1", "b2"]}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = functional_network(frame, nodes=nodes, delay=1)
        full = functional_network(frame, nodes=nodes, delay=1, evidence=True, resamples=20)
    assert add_evidence(plain, frame, resamples=20) == full


def test_add_evidence_refuses_data_that_is_not_the_networks(data, networks):
    plain, full = networks
    with pytest.raises(ParameterError, match="data.*399 samples.*400"):
        add_evidence(plain, data[:-1])
    with pytest.raises(ParameterError, match="data.*no column.*'d'"):
        add_evidence(plain, pd.DataFrame(data[:, :3], columns=list("abc")))
    with pytest.raises(ParameterError, match="network.*already"):
        add_evidence(full, data)
    with pytest.raises(ParameterError, match="surrogates"):
        add_evidence(plain, data, surrogates=0)


def test_add_evidence_takes_the_frame_the_network_was_computed_from(data):
    frame = pd.DataFrame(data)  # integer column labels: the network names them "0" ... "3"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = functional_network(frame, delay=1)
        full = functional_network(frame, delay=1, evidence=True, resamples=20)
    assert add_evidence(plain, frame, resamples=20) == full
    extra = frame.assign(unused=np.arange(len(frame)))  # other columns are ignored
    assert add_evidence(plain, extra, resamples=20) == full


def test_add_evidence_asks_for_a_frame_for_multichannel_nodes(data):
    frame = pd.DataFrame(data, columns=["a1", "a2", "b1", "b2"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = functional_network(frame, nodes={"A": ["a1", "a2"], "B": ["b1", "b2"]},
                                   delay=1)
    with pytest.raises(ParameterError, match="data must be a DataFrame with the channel"):
        add_evidence(plain, data)
