"""Honest labels: a pair whose coupling test could not have rejected is ``untestable``.

The references are independent of :mod:`funcnet.evidence.reading`: the smallest adjusted p-value
by enumerating every p-value the tests could give, and whether a pair can be rejected at all by
the step-up condition of Benjamini and Hochberg (1995) itself.
"""

from __future__ import annotations

import itertools
import json
import math

import networkx as nx
import numpy as np
import pandas as pd
import pytest
from hypothesis import given, strategies as st

from funcnet import functional_network
from funcnet.evidence import EVIDENCE_LABELS, smallest_p_values, untestable
from funcnet.network import FunctionalNetwork
from funcnet.validation.systems import henon_pair


def _bh_brute(p: list[float]) -> list[float]:
    """BH-adjusted p-values written out: min over k >= rank of p_(k) m / k."""
    m = len(p)
    ranked = sorted(p)
    out = []
    for value in p:
        rank = ranked.index(value) + 1  # the first of ties: the min over k >= rank is the same
        out.append(min(1.0, min(ranked[k - 1] * m / k for k in range(rank, m + 1))))
    return out


def _can_reject(k: list[int], alpha: float) -> list[bool]:
    """BH's step-up rule: pair i is rejected iff some level j has p_i <= j alpha / m and at
    least j p-values at or below it; every p-value at its least 1/(K+1) is the best case."""
    tested = [v for v in k if v > 0]
    m = len(tested)
    least = [1 / (v + 1) for v in tested]
    out = []
    for v in k:
        if v == 0:
            out.append(False)
            continue
        out.append(any(1 / (v + 1) <= j * alpha / m
                       and sum(q <= j * alpha / m for q in least) >= j
                       for j in range(1, m + 1)))
    return out


@given(st.lists(st.integers(0, 5), min_size=1, max_size=4))
def test_smallest_p_values_is_the_least_any_data_could_give(k):
    tested = [i for i, v in enumerate(k) if v > 0]
    expected = [math.nan] * len(k)
    if tested:
        # every p-value each test can give: (1 + c) / (K + 1), c = 0..K
        grids = [[(1 + c) / (k[i] + 1) for c in range(k[i] + 1)] for i in tested]
        best = [math.inf] * len(tested)
        for p in itertools.product(*grids):
            best = [min(b, a) for b, a in zip(best, _bh_brute(list(p)), strict=True)]
        for i, b in zip(tested, best, strict=True):
            expected[i] = b
    np.testing.assert_allclose(smallest_p_values(k), expected, rtol=1e-12, equal_nan=True)


@given(st.lists(st.integers(0, 60), min_size=1, max_size=12),
       st.sampled_from([0.0103, 0.0497, 0.1013]))
def test_untestable_is_bh_never_rejecting(k, alpha):
    # levels off the exact ties j / (m (K + 1)), where the floating-point adjustment decides
    # (as it decides coupling_p) and the exact reference may not agree
    assert untestable(k, alpha).tolist() == [not r for r in _can_reject(k, alpha)]


def test_untestable_by_the_bound_alone_and_by_the_adjustment():
    # K = 4: 1/5 = 0.2 > 0.05 whatever else; K = 0: no surrogate
    assert untestable([4, 299], 0.05).tolist() == [True, False]
    assert untestable([0], 0.05).tolist() == [True]
    # K = 28 alone reaches 1/29 = 0.034, but not beside nine pairs of K = 4 (SINUMERIK cruise)
    assert untestable([28], 0.05).tolist() == [False]
    assert untestable([28] + [4] * 9, 0.05).tolist() == [True] * 10


def _henon_frame(n: int = 400) -> pd.DataFrame:
    data = henon_pair(n, 0.6, seed=1)
    rng = np.random.default_rng(3)
    return pd.DataFrame({"X": data[:, 0], "Y": data[:, 1], "N": rng.standard_normal(n)})


def test_few_surrogates_read_untestable_numbers_unchanged():
    data = _henon_frame()
    # 9 surrogates asked: no p-value below 1/10, so nothing can be rejected at 0.05 ...
    few = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, surrogates=9,
                             warn=False)
    pairs = few.pairs
    assert set(pairs["evidence"]) == {"untestable"}
    assert not pairs["coupled"].any()
    assert (pairs["surrogates"] == 10).all()  # the lattice holds 2 ceil(9/2)
    assert pairs["evidence_reason"].tolist() == [
        "K=10 surrogates: smallest p 0.0909 > alpha 0.05"] * 3
    # ... while at alpha 0.2 it is tested: the labels follow the test, the kinds are kept
    wide = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, surrogates=9,
                              alpha=0.2, warn=False)
    assert "untestable" not in set(wide.pairs["evidence"])
    numbers = [c for c in pairs.columns if c not in ("coupled", "evidence", "evidence_reason",
                                                      "coupling_p", "direction_p", "direction")]
    pd.testing.assert_frame_equal(pairs[numbers], wide.pairs[numbers])
    np.testing.assert_array_equal(pairs["coupling_p"], wide.pairs["coupling_p"])
    tested = wide.pairs.set_index(["x", "y"])
    assert tested.loc[("X", "Y"), "evidence"].startswith("coupled")
    assert tested.loc[("X", "Y"), "evidence_reason"].startswith("coupling_p ")
    for row in wide.pairs.itertuples():
        if row.evidence in ("not-coupled", "asymmetry-only"):
            assert row.evidence_reason.startswith(f"coupling_p {row.coupling_p:.3g} > alpha 0.2")
            assert (row.evidence == "asymmetry-only") == (row.kind in ("x->y", "y->x"))


def test_untestable_keeps_the_arrow_in_kind_and_the_edge():
    data = _henon_frame()
    few = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, surrogates=9,
                             warn=False)
    plain = functional_network(data, dim=2, delay=1, warn=False)
    assert few.pairs["kind"].tolist() == plain.pairs["kind"].tolist()
    pd.testing.assert_frame_equal(few.edges, plain.edges)


def test_the_label_and_reason_travel_through_json_graphml_networkx(tmp_path):
    net = functional_network(_henon_frame(), dim=2, delay=1, evidence=True, resamples=0,
                             surrogates=9, warn=False)
    for suffix in (".json", ".graphml"):
        back = FunctionalNetwork.read(net.write(tmp_path / f"net{suffix}"))
        assert back == net
        assert back.pairs["evidence_reason"].tolist() == net.pairs["evidence_reason"].tolist()
    graph = nx.read_graphml(tmp_path / "net.graphml")
    for _, _, arc in graph.edges(data=True):
        assert arc["evidence"] == "untestable"
        assert arc["evidence_reason"].startswith("K=10 surrogates")
    for _, _, arc in net.to_networkx().edges(data=True):
        assert arc["evidence"] == "untestable" and "evidence_reason" in arc


def test_a_json_file_written_before_the_label_reads_with_it(tmp_path):
    net = functional_network(_henon_frame(), dim=2, delay=1, evidence=True, resamples=0,
                             surrogates=9, warn=False)
    document = json.loads(net.to_json())
    # what the earlier version wrote: no reason column, the tested labels
    pairs = document["pairs"]
    del pairs["evidence_reason"]
    pairs["evidence"] = ["asymmetry-only" if k in ("x->y", "y->x") else "not-coupled"
                         for k in pairs["kind"]]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(document))
    back = FunctionalNetwork.read(old)
    assert back == net
    assert set(back.pairs["evidence"]) == {"untestable"}


def test_the_vocabulary_has_untestable():
    assert "untestable" in EVIDENCE_LABELS and EVIDENCE_LABELS[0] == "coupled-directed"


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_real_trace_inspect_says_untestable_and_never_not_coupled_for_it(real_trace):
    """On the SINUMERIK trace the phase windows leave 2-28 surrogates: no pair can be rejected
    at 0.05, and inspect says so instead of 'not-coupled' or 'asymmetry-only'."""
    from funcnet.inspection import inspect_recording
    from funcnet.robot import read_trace

    ins = inspect_recording(read_trace(real_trace), backlash=False)
    assert len(ins.networks) == 12
    labels = []
    for label, net in ins.networks.items():
        pairs = net.pairs
        can = _can_reject(pairs["surrogates"].astype(int).tolist(), 0.05)
        for row, reject in zip(pairs.itertuples(), can, strict=True):
            labels.append(row.evidence)
            if not reject:
                assert row.evidence == "untestable", (label, row.x, row.y)
                assert row.evidence_reason.startswith(f"K={row.surrogates} surrogates")
            else:
                assert row.evidence != "untestable", (label, row.x, row.y)
    assert labels.count("untestable") >= 1
    counts = pd.Series(labels).value_counts().to_dict()
    # every pair of every window: the windows hold at most 28 surrogates beside pairs with 2-4
    assert counts == {"untestable": 120}
