"""The pairs/edges schema (one source) and the edge rule as pure functions of a pairs table."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ParameterError, ThresholdWarning
from funcnet.network import functional_network
from funcnet.network.rule import (
    combine_kinds,
    edge_kind,
    edges_from_pairs,
    kinds_for,
    pair_kinds,
)
from funcnet.network.schema import (
    EDGE_COLUMNS,
    EDGE_DTYPES,
    EDGE_KINDS,
    EVIDENCE_DTYPES,
    MEASURE_KINDS,
    PAIR_COLUMNS,
    PAIR_DTYPES,
    PAIR_KINDS,
    check_edges,
    check_pairs,
    edges_frame,
    empty_edges,
    empty_pairs,
    pairs_frame,
    typed_frame,
)
from funcnet.parameters import NetworkParameters


def hand_pairs(rows, *, degenerate=None):
    """A full-schema pairs table from (x, y, c_diff, t_diff) rows; the rule's columns blank."""
    n = len(rows)
    flags = degenerate or [False] * n
    columns = {name: [0.5] * n for name in PAIR_COLUMNS if PAIR_DTYPES[name] == "float64"}
    columns.update(
        x=[r[0] for r in rows],
        y=[r[1] for r in rows],
        c_diff=[r[2] for r in rows],
        t_diff=[r[3] for r in rows],
        eps_ordered=[True] * n,
        rate_exceeded=[False] * n,
        degenerate=flags,
        degenerate_reason=["y" if flag else "" for flag in flags],
        c_kind=["bidirectional"] * n,
        t_kind=["bidirectional"] * n,
        kind=["bidirectional"] * n,
        direction=["none"] * n,
        direction_reason=[""] * n,
    )
    return pairs_frame(columns)


def quiet(data, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        return functional_network(data, **kwargs)


# --- schema -------------------------------------------------------------------------------


def test_schema_is_the_one_the_plan_lists():
    assert PAIR_COLUMNS == (
        "x", "y", "c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff", "eps_x", "eps_y",
        "eps_xy", "achieved_rr_x", "achieved_rr_y", "achieved_cr", "eps_ordered",
        "rate_exceeded", "degenerate", "degenerate_reason", "c_kind", "t_kind", "kind", "weight",
        "direction", "direction_reason",
    )  # fmt: skip
    assert EDGE_COLUMNS == ("source", "target", "weight", "kind", "degenerate")
    assert PAIR_KINDS == ("x->y", "y->x", "bidirectional", "conflict")
    assert EDGE_KINDS == ("directed", "bidirectional")
    assert tuple(PAIR_DTYPES) == PAIR_COLUMNS and tuple(EDGE_DTYPES) == EDGE_COLUMNS
    with pytest.raises(TypeError):
        PAIR_DTYPES["x"] = "object"  # type: ignore[index]


def test_a_real_networks_tables_follow_the_schema():
    rng = np.random.default_rng(0)
    data = pd.DataFrame(rng.random((120, 3)), columns=["RP", "AP", "AC"])
    net = quiet(data, delay=2)
    assert list(net.pairs.columns) == list(PAIR_COLUMNS)
    assert dict(net.pairs.dtypes.astype(str)) == dict(PAIR_DTYPES)
    assert list(net.edges.columns) == list(EDGE_COLUMNS)
    assert dict(net.edges.dtypes.astype(str)) == dict(EDGE_DTYPES)
    check_pairs(net.pairs)
    check_edges(net.edges)
    assert set(net.pairs["kind"]) <= set(PAIR_KINDS)
    assert set(net.pairs["c_kind"]) | set(net.pairs["t_kind"]) <= set(MEASURE_KINDS)
    assert set(net.edges["kind"]) <= set(EDGE_KINDS)
    # An empty table of each schema has the same dtypes.
    assert dict(empty_pairs().dtypes.astype(str)) == dict(PAIR_DTYPES)
    assert dict(empty_edges().dtypes.astype(str)) == dict(EDGE_DTYPES)


def test_frames_refuse_missing_or_unknown_columns():
    with pytest.raises(ParameterError, match="missing: .*weight"):
        pairs_frame({name: [] for name in PAIR_COLUMNS if name != "weight"})
    with pytest.raises(ParameterError, match="unknown: rr_x"):
        pairs_frame({**dict.fromkeys(PAIR_COLUMNS, []), "rr_x": []})
    with pytest.raises(ParameterError, match="edges must have exactly the columns"):
        edges_frame({"source": [], "target": [], "weight": [], "kind": []})


def test_check_pairs_names_the_first_difference():
    pairs = hand_pairs([("A", "B", 0.1, 0.1)])
    assert check_pairs(pairs) is pairs
    with pytest.raises(ParameterError, match="in this order"):
        check_pairs(pairs[list(reversed(PAIR_COLUMNS))])
    with pytest.raises(ParameterError, match="column degenerate must have dtype bool"):
        check_pairs(pairs.assign(degenerate=pairs["degenerate"].astype(object)))
    with pytest.raises(ParameterError, match="column kind holds 'a->b'"):
        check_pairs(pairs.assign(kind=pd.Series(["a->b"], dtype="str")))
    with pytest.raises(ParameterError, match="column c_kind holds 'conflict'"):
        check_pairs(pairs.assign(c_kind=pd.Series(["conflict"], dtype="str")))
    with pytest.raises(ParameterError, match="must be a pandas.DataFrame"):
        check_pairs({"x": []})
    with pytest.raises(ParameterError, match="column kind holds 'forward'"):
        check_edges(
            edges_frame({"source": ["A"], "target": ["B"], "weight": [0.1],
                         "kind": ["forward"], "degenerate": [False]})
        )


def series_built(columns, dtypes, index=None):
    """A table as one Series per column makes it: the reference the typed frames must equal."""
    frame = pd.DataFrame({name: pd.Series(list(columns[name]), dtype=dtype)
                          for name, dtype in dtypes.items()})
    if index is not None:
        frame.index = index
    return frame


def assert_identical(found, expected):
    """Equal cell for cell (floats bit for bit, -0.0 apart from 0.0), dtypes, columns, index."""
    pd.testing.assert_frame_equal(found, expected, check_exact=True)
    assert list(found.dtypes) == list(expected.dtypes)
    assert found.columns.dtype == expected.columns.dtype
    assert type(found.index) is type(expected.index) and found.index.equals(expected.index)
    for name in found.columns:
        if found[name].dtype == np.float64:
            assert found[name].to_numpy().tobytes() == expected[name].to_numpy().tobytes(), name


def mixed_columns(n, rng):
    """Every column of the pairs and evidence schema, each given another way: NumPy arrays of
    the column's dtype, object and unicode strings, lists, Series, ints for floats."""
    dtypes = {**PAIR_DTYPES, **EVIDENCE_DTYPES}
    columns = {}
    for k, (name, dtype) in enumerate(dtypes.items()):
        if dtype == "float64":
            values = rng.normal(size=n)
            values[::3] = [-0.0, np.nan, 0.0, np.inf][: len(values[::3])] if n >= 9 else -0.0
            columns[name] = [values, values.tolist(), pd.Series(values),
                             np.arange(n)][k % 4]
        elif dtype == "bool":
            flags = rng.random(n) < 0.5
            columns[name] = [flags, flags.tolist()][k % 2]
        elif dtype == "int64":
            columns[name] = rng.integers(0, 99, n)
        else:
            words = [f"w{i % 3}" for i in range(n)]
            columns[name] = [np.array(words, dtype=object), np.array(words), words,
                             pd.Series(words, dtype="str"), pd.Series(words, dtype=object)][k % 5]
    return columns, dtypes


def test_typed_frames_equal_the_ones_built_series_by_series():
    rng = np.random.default_rng(5)
    for n in (0, 1, 12):
        columns, dtypes = mixed_columns(n, rng)
        assert_identical(pairs_frame(columns), series_built(columns, dtypes))
        plain = {name: columns[name] for name in PAIR_COLUMNS}
        assert_identical(pairs_frame(plain), series_built(plain, PAIR_DTYPES))
        index = pd.RangeIndex(7, 7 + n)
        assert_identical(typed_frame(columns, dtypes, index=index),
                         series_built(columns, dtypes, index))
    # a string column with a missing value, a float column with one, from lists
    edges = {"source": ["A", None], "target": np.array(["B", None], dtype=object),
             "weight": [0.1, None], "kind": ["directed"] * 2, "degenerate": [False, True]}
    assert_identical(edges_frame(edges), series_built(edges, EDGE_DTYPES))
    with pytest.raises(ParameterError, match="edges must have equally long columns.*weight 1"):
        edges_frame({**edges, "weight": [0.1]})


def test_pair_kinds_converts_column_by_column_as_astype_does():
    """The rule's table, built at once, equals the old way: the columns set on a copy, then
    the schema's order and dtypes by ``astype`` (object columns, a shifted index, attrs)."""
    rng = np.random.default_rng(8)
    pairs = hand_pairs([("A", "B", c, t) for c, t in rng.normal(scale=0.1, size=(9, 2))])
    pairs = pairs.astype({"x": object, "c_xy": object, "degenerate": object, "weight": object})
    pairs.index = pd.RangeIndex(3, 12)
    pairs.attrs["source"] = "hand"
    for measure in ("both", "clustering"):
        p = NetworkParameters(mu=0.05, measure=measure)
        expected = pairs.copy()
        for name in ("c", "t"):
            expected[f"{name}_kind"] = pd.Series(
                [edge_kind(float(d), 0.05) for d in pairs[f"{name}_diff"]], index=pairs.index,
                dtype="str")
        expected["kind"] = kinds_for(expected, measure)
        expected["weight"] = (pairs["c_diff"].abs() + pairs["t_diff"].abs()) / 2
        expected = expected[list(PAIR_COLUMNS)].astype(dict(PAIR_DTYPES))
        found = pair_kinds(pairs, p)
        assert_identical(found, expected)
        assert found.attrs == {"source": "hand"}


# --- the rule, closed form ----------------------------------------------------------------


def test_mu_c_and_mu_t_judge_their_own_difference():
    pairs = hand_pairs(
        [
            ("A", "B", -0.08, -0.03),  # C directed under 0.05, T only under 0.02
            ("A", "C", 0.06, 0.01),
            ("B", "C", -0.12, 0.03),
            ("C", "D", 0.0, 0.0),
        ]
    )
    same = pair_kinds(pairs, mu=0.05)
    assert list(same["c_kind"]) == ["x->y", "y->x", "x->y", "bidirectional"]
    assert list(same["t_kind"]) == ["bidirectional"] * 4
    assert list(same["kind"]) == ["x->y", "y->x", "x->y", "bidirectional"]

    split = pair_kinds(pairs, mu_c=0.1, mu_t=0.02)
    assert list(split["c_kind"]) == ["bidirectional", "bidirectional", "x->y", "bidirectional"]
    assert list(split["t_kind"]) == ["x->y", "bidirectional", "y->x", "bidirectional"]
    assert list(split["kind"]) == ["x->y", "bidirectional", "conflict", "bidirectional"]

    # mu sets both; mu_c overrides it for C_diff only.
    only_c = pair_kinds(pairs, NetworkParameters(mu=0.02, mu_c=0.1))
    assert list(only_c["c_kind"]) == list(split["c_kind"])
    assert list(only_c["t_kind"]) == list(split["t_kind"])
    assert list(pair_kinds(pairs, mu_c=0.1, measure="transitivity")["kind"]) == list(
        same["t_kind"]
    )
    # Eq. 13 does not depend on mu.
    assert list(split["weight"]) == [(0.08 + 0.03) / 2, (0.06 + 0.01) / 2, (0.12 + 0.03) / 2, 0.0]
    check_pairs(split)


def test_mu_c_and_mu_t_reach_the_network(monkeypatch):
    import funcnet.network.functional as functional

    rows = {("A", "B"): (-0.08, -0.03), ("A", "C"): (0.06, 0.01), ("B", "C"): (-0.12, 0.03)}

    class Fake:
        def __init__(self, c_diff, t_diff):
            for name in PAIR_COLUMNS:
                if PAIR_DTYPES[name] == "float64":
                    setattr(self, name, 0.5)
            self.c_diff, self.t_diff = c_diff, t_diff
            self.eps_ordered, self.rate_exceeded = True, False
            self.degenerate, self.degenerate_reason = False, ""

    monkeypatch.setattr(
        functional,
        "pairwise_cross_measures",
        lambda signals, **kwargs: {key: Fake(*diffs) for key, diffs in rows.items()},
    )
    data = np.random.default_rng(0).random((40, 3))
    net = functional_network(data, names=["A", "B", "C"], mu_c=0.1, mu_t=0.02)
    assert list(net.pairs["kind"]) == ["x->y", "bidirectional", "conflict"]
    assert net.parameters.mu_clustering == 0.1 and net.parameters.mu_transitivity == 0.02
    assert list(net.edges[["source", "target", "kind"]].itertuples(index=False, name=None)) == [
        ("A", "B", "directed"),
        ("A", "C", "bidirectional"),
    ]
    assert "mu_c=0.1, mu_t=0.02" in repr(net)


def test_vectorized_rule_equals_the_scalar_functions_bit_for_bit():
    rng = np.random.default_rng(11)
    mu = 0.05
    diffs = np.r_[rng.normal(scale=0.08, size=400), [0.0, -0.0, mu, -mu, np.nextafter(mu, 0)]]
    c_diff, t_diff = diffs, rng.permutation(diffs)
    pairs = hand_pairs([("A", "B", c, t) for c, t in zip(c_diff, t_diff, strict=True)])
    for measure in ("both", "clustering", "transitivity"):
        out = pair_kinds(pairs, mu=mu, measure=measure)
        c_kinds = [edge_kind(float(c), mu) for c in c_diff]
        t_kinds = [edge_kind(float(t), mu) for t in t_diff]
        assert list(out["c_kind"]) == c_kinds
        assert list(out["t_kind"]) == t_kinds
        expected = {
            "both": [combine_kinds(c, t) for c, t in zip(c_kinds, t_kinds, strict=True)],
            "clustering": c_kinds,
            "transitivity": t_kinds,
        }[measure]
        assert list(out["kind"]) == expected
        assert list(kinds_for(out, measure)) == expected
        weights = [(abs(float(c)) + abs(float(t))) / 2 for c, t in zip(c_diff, t_diff, strict=True)]
        np.testing.assert_array_equal(
            out["weight"].to_numpy().view(np.int64), np.array(weights).view(np.int64)
        )


def test_pair_kinds_on_a_partial_table_appends_the_rule_columns():
    pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "c_diff": [-0.2], "t_diff": [0.0]})
    out = pair_kinds(pairs)
    assert list(out.columns) == ["x", "y", "c_diff", "t_diff", "c_kind", "t_kind", "kind", "weight"]
    assert list(pairs.columns) == ["x", "y", "c_diff", "t_diff"]  # not modified
    with pytest.raises(ParameterError, match="pairs needs the column.*t_diff"):
        pair_kinds(pairs.drop(columns="t_diff"))
    with pytest.raises(ParameterError, match="dim is not a parameter here"):
        pair_kinds(pairs, dim=2)
    with pytest.raises(ParameterError, match="mu_t must be finite and >= 0"):
        pair_kinds(pairs, mu_t=-1.0)


# --- edges --------------------------------------------------------------------------------


def test_edges_leave_out_degenerate_pairs_unless_kept():
    pairs = pair_kinds(
        hand_pairs(
            [("A", "B", -0.3, -0.3), ("A", "C", 0.3, 0.2), ("B", "C", 0.0, 0.01),
             ("B", "D", -0.3, 0.3)],
            degenerate=[False, True, True, False],
        )
    )  # fmt: skip
    dropped = edges_from_pairs(pairs)
    assert list(dropped.itertuples(index=False, name=None)) == [
        ("A", "B", 0.3, "directed", False)
    ]
    kept = edges_from_pairs(pairs, degenerate="keep")
    assert list(kept.itertuples(index=False, name=None)) == [
        ("A", "B", 0.3, "directed", False),
        ("C", "A", 0.25, "directed", True),
        ("B", "C", 0.005, "bidirectional", True),
    ]
    check_edges(kept)
    # Another measure: the conflict of (B, D) under "both" is a direction under C alone.
    by_c = edges_from_pairs(pairs, measure="clustering")
    assert list(by_c[["source", "target"]].itertuples(index=False, name=None)) == [
        ("A", "B"),
        ("B", "D"),
    ]


def test_edges_from_pairs_refuses_bad_arguments():
    pairs = pair_kinds(hand_pairs([("A", "B", -0.3, -0.3)]))
    with pytest.raises(ParameterError, match="degenerate must be one of drop, keep; got 'hide'"):
        edges_from_pairs(pairs, degenerate="hide")
    with pytest.raises(ParameterError, match="measure must be one of"):
        edges_from_pairs(pairs, measure="degree")
    with pytest.raises(ParameterError, match="needs the column.*degenerate"):
        edges_from_pairs(pairs.drop(columns="degenerate"))
    with pytest.raises(ParameterError, match="needs the column.*c_kind"):
        edges_from_pairs(pairs.drop(columns="c_kind"), measure="both")
    assert edges_from_pairs(pairs.iloc[:0]).equals(empty_edges())
