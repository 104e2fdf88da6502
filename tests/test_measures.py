"""Cross-clustering, cross-transitivity and their per-node parts against a brute-force reference.

The reference builds the dense ISRN blocks with test_recurrence's reference and counts
cross-triangles with einsum: tri_v = sum_{p,q} CR[v,p] A_Y[p,q] CR[v,q] (README method step 5).
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st

from funcnet.core.embedding import signal_states
from funcnet.core.measures import (
    CrossMeasures,
    cross_degree,
    cross_measures,
    isrn_measures,
    local_cross_clustering,
    pairwise_cross_measures,
)
from funcnet.core.recurrence import auto_recurrence, cross_recurrence
from funcnet.errors import DegenerateWarning, ParameterError, SignalError, ThresholdWarning
from test_recurrence import (
    KINDS,
    METRICS,
    make_signal,
    reference_auto,
    reference_cross,
    reference_embed,
)


def reference_direction(cr_xy, a_y):
    """(local clustering, global clustering, transitivity, cross-degree) of X w.r.t. Y."""
    cr = cr_xy.astype(np.float64)
    degree = cr.sum(axis=1)
    triangles = np.einsum("vp,pq,vq->v", cr, a_y.astype(np.float64), cr)
    pairs = degree * (degree - 1)
    local = np.divide(triangles, pairs, out=np.zeros_like(triangles), where=pairs > 0)
    transitivity = triangles.sum() / pairs.sum() if pairs.sum() > 0 else 0.0
    return local, local.mean(), transitivity, degree


def reference_measures(
    x, y, *, dim, delay, rr, cr, eps=(None, None, None), metric, theiler=0, rule="funcnet"
):
    if rule == "pyunicorn":
        x, y = np.float32(x), np.float32(y)
    xs, ys = reference_embed(x, dim, delay), reference_embed(y, dim, delay)
    a_x, eps_x = reference_auto(xs, rr=rr, eps=eps[0], metric=metric, theiler=theiler, rule=rule)
    a_y, eps_y = reference_auto(ys, rr=rr, eps=eps[1], metric=metric, theiler=theiler, rule=rule)
    cr_xy, eps_xy = reference_cross(xs, ys, cr=cr, eps=eps[2], metric=metric, rule=rule)
    xy = reference_direction(cr_xy, a_y)
    yx = reference_direction(cr_xy.T, a_x)
    return xy, yx, (eps_x, eps_y, eps_xy), (a_x, a_y, cr_xy)


def assert_matches_reference(result, xy, yx, eps):
    assert result.c_xy == pytest.approx(xy[1], abs=1e-12)
    assert result.c_yx == pytest.approx(yx[1], abs=1e-12)
    assert result.t_xy == pytest.approx(xy[2], abs=1e-12)
    assert result.t_yx == pytest.approx(yx[2], abs=1e-12)
    assert result.c_diff == pytest.approx(xy[1] - yx[1], abs=1e-12)
    assert result.t_diff == pytest.approx(xy[2] - yx[2], abs=1e-12)
    assert (result.eps_x, result.eps_y, result.eps_xy) == pytest.approx(eps, abs=1e-12)
    assert result.eps_ordered == (eps[2] < min(eps[0], eps[1]))


@settings(max_examples=40, deadline=None)
@given(
    kinds=st.tuples(st.sampled_from(KINDS), st.sampled_from(KINDS)),
    seed=st.integers(0, 2**32 - 1),
    lengths=st.tuples(st.integers(25, 80), st.integers(25, 80)),
    dim=st.integers(1, 3),
    delay=st.integers(1, 3),
    metric=st.sampled_from(METRICS),
    rates=st.tuples(st.floats(0.01, 0.4), st.floats(0.01, 0.4)),
    theiler=st.integers(0, 3),
)
def test_cross_measures_by_rate_equal_brute_force(
    kinds, seed, lengths, dim, delay, metric, rates, theiler
):
    x = make_signal(kinds[0], lengths[0], seed)
    y = make_signal(kinds[1], lengths[1], seed + 7)
    rr, cr = rates
    xy, yx, eps, blocks = reference_measures(
        x, y, dim=dim, delay=delay, rr=rr, cr=cr, metric=metric, theiler=theiler
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        result = cross_measures(
            x, y, dim=dim, delay=delay, rr=rr, cr=cr, metric=metric, theiler=theiler
        )
    assert_matches_reference(result, xy, yx, eps)
    a_x, a_y, cr_xy = blocks
    m_x, m_y = a_x.shape[0], a_y.shape[0]
    candidates_x = (m_x - theiler) * (m_x - theiler - 1)
    candidates_y = (m_y - theiler) * (m_y - theiler - 1)
    assert result.achieved_rr_x == a_x.sum() / candidates_x
    assert result.achieved_rr_y == a_y.sum() / candidates_y
    assert result.achieved_cr == cr_xy.sum() / cr_xy.size
    assert (result.m_x, result.m_y) == (m_x, m_y)


@settings(max_examples=30, deadline=None)
@given(
    kinds=st.tuples(st.sampled_from(KINDS), st.sampled_from(KINDS)),
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(25, 80),
    metric=st.sampled_from(METRICS),
    scale=st.tuples(st.floats(0.05, 2.0), st.floats(0.05, 2.0), st.floats(0.02, 2.0)),
    rule=st.sampled_from(("funcnet", "pyunicorn")),
)
def test_cross_measures_with_explicit_eps_equal_brute_force(kinds, seed, n, metric, scale, rule):
    x = make_signal(kinds[0], n, seed)
    y = make_signal(kinds[1], n, seed + 1)
    eps = tuple(float(s * (np.ptp(x) + np.ptp(y) + 1.0) / 4) for s in scale)
    xy, yx, used, _ = reference_measures(
        x, y, dim=2, delay=2, rr=None, cr=None, eps=eps, metric=metric, rule=rule
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        result = cross_measures(
            x, y, dim=2, delay=2, eps=(eps[:2], eps[2]), metric=metric, rule=rule
        )
    assert_matches_reference(result, xy, yx, used)
    assert used == eps
    assert not result.rate_exceeded


@settings(max_examples=25, deadline=None)
@given(
    kinds=st.tuples(st.sampled_from(KINDS), st.sampled_from(KINDS)),
    seed=st.integers(0, 2**32 - 1),
    lengths=st.tuples(st.integers(25, 70), st.integers(25, 70)),
    metric=st.sampled_from(METRICS),
    rates=st.tuples(st.floats(0.02, 0.3), st.floats(0.02, 0.3)),
)
def test_local_clustering_and_cross_degree_equal_brute_force(kinds, seed, lengths, metric, rates):
    x = make_signal(kinds[0], lengths[0], seed)
    y = make_signal(kinds[1], lengths[1], seed + 3)
    rr, cr = rates
    xy, yx, _, _ = reference_measures(x, y, dim=2, delay=1, rr=rr, cr=cr, metric=metric)
    common = {"dim": 2, "delay": 1, "rr": rr, "cr": cr, "metric": metric}
    c_xy, c_yx = local_cross_clustering(x, y, **common)
    np.testing.assert_allclose(c_xy, xy[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c_yx, yx[0], rtol=0, atol=1e-12)
    k_xy, k_yx = cross_degree(x, y, **common)
    np.testing.assert_array_equal(k_xy, xy[3])
    np.testing.assert_array_equal(k_yx, yx[3])
    assert k_xy.dtype == np.int64


def test_fig2_pair_global_values_are_means_of_local_values():
    t = np.linspace(0, 8 * np.pi, 251)
    x = np.sin(t)
    y = np.sin(1.5 * t) + 0.3 * x
    eps = (0.15, 0.05)
    result = cross_measures(x, y, eps=eps)
    c_xy, c_yx = local_cross_clustering(x, y, eps=eps)
    assert result.c_xy == pytest.approx(c_xy.mean(), abs=1e-15)
    assert result.c_yx == pytest.approx(c_yx.mean(), abs=1e-15)
    assert result.eps_ordered
    assert result.parameters.eps == eps
    assert (result.m_x, result.m_y) == (231, 231)


def test_hand_built_network():
    # X has 2 nodes, Y has 3 nodes p, q, r with edges p-q and q-r (Fig. 3 of the paper):
    # v0 links to p, q, r -> 2 of its 3 neighbour pairs closed: C(v0) = 4 / 6;
    # v1 links to p only -> C(v1) = 0 (k < 2). T = 4 / 6 as v1 has no triple.
    # Y w.r.t. X: A_X is empty, so C^YX = T^YX = 0.
    from funcnet.core.recurrence import PackedRecurrence

    def packed(dense):
        dense = np.asarray(dense, dtype=bool)
        rows = np.zeros((dense.shape[0], 1), dtype=np.uint64)
        for i, j in zip(*np.nonzero(dense), strict=True):
            rows[i, 0] |= np.uint64(1) << np.uint64(j)
        return PackedRecurrence(
            rows, dense.shape[1], 1.0, 0.0, None, int(dense.sum()), dense.size, None, False
        )

    a_x = packed(np.zeros((2, 2)))
    a_y = packed([[0, 1, 0], [1, 0, 1], [0, 1, 0]])
    cr_xy = packed([[1, 1, 1], [1, 0, 0]])
    result = isrn_measures(a_x, a_y, cr_xy)
    assert result.c_xy == pytest.approx((4 / 6 + 0) / 2)
    assert result.t_xy == pytest.approx(4 / 6)
    assert (result.c_yx, result.t_yx) == (0.0, 0.0)


def test_isrn_measures_reuses_precomputed_structures():
    x, y = make_signal("sine", 300, 1), make_signal("walk", 300, 2)
    xs, ys = signal_states(x), signal_states(y)
    a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    cr_xy = cross_recurrence(xs, ys, cr=0.02)
    direct = isrn_measures(a_x, a_y, cr_xy)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        expected = cross_measures(x, y, rr=0.05, cr=0.02)
    for name in ("c_xy", "c_yx", "t_xy", "t_yx", "eps_x", "eps_y", "eps_xy", "achieved_cr"):
        assert getattr(direct, name) == getattr(expected, name)
    # Swapping X and Y swaps the directions.
    swapped = isrn_measures(a_y, a_x, cr_xy.transposed())
    assert (swapped.c_xy, swapped.t_xy) == (direct.c_yx, direct.t_yx)
    with pytest.raises(ParameterError, match="cr_xy"):
        isrn_measures(a_x, a_y, cross_recurrence(xs[:100], ys, cr=0.02))


def test_pairwise_equals_cross_measures_per_pair():
    signals = [
        make_signal(kind, 200, seed)
        for seed, kind in enumerate(("sine", "walk", "noise", "quantized"))
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        results = pairwise_cross_measures(signals, dim=2, delay=3, rr=0.08, cr=0.04, theiler=1)
        assert list(results) == [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
        for (i, j), result in results.items():
            expected = cross_measures(
                signals[i], signals[j], dim=2, delay=3, rr=0.08, cr=0.04, theiler=1
            )
            assert result == expected
        # A 2-D array or a DataFrame holds one signal per column.
        as_array = pairwise_cross_measures(
            np.column_stack(signals), dim=2, delay=3, rr=0.08, cr=0.04, theiler=1
        )
        frame = pd.DataFrame(np.column_stack(signals), columns=list("abcd"))
        as_frame = pairwise_cross_measures(frame, dim=2, delay=3, rr=0.08, cr=0.04, theiler=1)
    assert as_array == results
    assert as_frame == results


def test_pairwise_explicit_eps():
    signals = [make_signal("sine", 150, s) for s in range(3)]
    eps = ((0.2, 0.3, 0.25), 0.05)
    results = pairwise_cross_measures(signals, eps=eps)
    expected = cross_measures(signals[1], signals[2], eps=((0.3, 0.25), 0.05))
    assert results[(1, 2)].c_xy == expected.c_xy
    assert results[(1, 2)].t_yx == expected.t_yx
    assert (results[(0, 2)].eps_x, results[(0, 2)].eps_y) == (0.2, 0.25)
    # Only the cross threshold given: the auto-recurrences keep the rate.
    partial = pairwise_cross_measures(signals, rr=0.1, eps=(None, 0.05))
    assert partial[(0, 1)].achieved_rr_x == pytest.approx(0.1, abs=1e-3)
    assert partial[(0, 1)].eps_xy == 0.05


@pytest.mark.parametrize(
    ("signals", "kwargs", "error", "word"),
    [
        ([np.arange(50.0)], {}, SignalError, "at least two"),
        ([np.sin(np.arange(50.0)), np.sin(np.arange(60.0))], {}, SignalError, r"signals\[1\]"),
        (
            [np.sin(np.arange(50.0)), np.r_[np.arange(49.0), np.nan]],
            {},
            SignalError,
            r"signals\[1\]",
        ),
        ([np.sin(np.arange(50.0))] * 2, {"eps": {"auto": 0.1, "bad": 1}}, ParameterError, "eps"),
        ([np.sin(np.arange(50.0))] * 2, {"eps": ([0.1], None)}, ParameterError, "one per"),
        ([np.sin(np.arange(50.0))] * 2, {"eps": (None, -1.0)}, ParameterError, "eps"),
        ([np.sin(np.arange(50.0))] * 2, {"cr": 0}, ParameterError, "cr"),
        ([np.sin(np.arange(50.0))] * 2, {"metric": "cosine"}, ParameterError, "metric"),
        ([np.sin(np.arange(50.0))] * 2, {"rr": (0.1, 0.1, 0.1)}, ParameterError, "one per"),
        ([np.sin(np.arange(50.0))] * 2, {"mu": 0.1}, ParameterError, "mu is not a parameter"),
    ],
)
def test_pairwise_rejects_bad_input(signals, kwargs, error, word):
    with pytest.raises(error, match=word):
        pairwise_cross_measures(signals, dim=2, delay=1, **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "error", "word"),
    [
        ({"rr": 1.2}, ParameterError, "rr"),
        ({"cr": 0.0}, ParameterError, "cr"),
        ({"eps": ((0.1, 0.1), 0.0)}, ParameterError, "eps must be positive"),
        ({"eps": (0.1, 0.1, 0.1)}, ParameterError, r"eps must be \(auto, cross\)"),
        ({"rule": "exact"}, ParameterError, "rule"),
        ({"theiler": -2}, ParameterError, "theiler"),
        ({"dim": 30}, SignalError, "signal x is too short"),
    ],
)
def test_cross_measures_rejects_bad_input(kwargs, error, word):
    x = np.sin(np.arange(80.0))
    with pytest.raises(error, match=word):
        cross_measures(x, x, **kwargs)


def test_cross_measures_names_the_bad_signal():
    x = np.sin(np.arange(80.0))
    with pytest.raises(SignalError, match="signal y has 1 NaN or infinite"):
        cross_measures(x, np.r_[x[:-1], np.inf])


def test_threshold_warnings():
    t = np.linspace(0, 8 * np.pi, 251)
    x, y = np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)
    with pytest.warns(ThresholdWarning, match="not below eps_x and eps_y"):
        result = cross_measures(x, y, eps=(0.1, 0.2))
    assert not result.eps_ordered
    levels = np.tile([0.0, 1.0, 2.0, 1.0, 2.0], 30)
    with pytest.warns(ThresholdWarning) as record:
        result = cross_measures(levels, levels[::-1], dim=1, delay=1, rr=0.1, cr=0.02)
    # Three values only: eps is 0 everywhere, a degenerate structure, not a slight overshoot.
    assert result.rate_exceeded and result.degenerate
    assert result.degenerate_reason == (
        "signal x: threshold 0 (too few distinct states); signal y: threshold 0 (too few "
        "distinct states); cross-recurrence (x, y): threshold 0 (too few distinct states)"
    )
    assert any("degenerate recurrence structure of signal x" in str(w.message) for w in record)
    assert not any("ties" in str(w.message) for w in record)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ThresholdWarning)
        quiet = cross_measures(x, y, eps=(0.15, 0.05))
    assert quiet.eps_ordered and not quiet.rate_exceeded


def zero_distance_rate(signal, dim, delay):
    """Brute-force share of ordered state pairs i != j at distance 0."""
    states = reference_embed(signal, dim, delay)
    same = (states[:, None, :] == states[None, :, :]).all(axis=2)
    return (same.sum() - len(states)) / (len(states) * (len(states) - 1))


def test_gross_overshoot_gets_its_own_warning_naming_the_signal():
    # AC barely moves: 180 equal samples, then a short ramp (the user's eps_x = 0, rr_x = 0.83).
    rng = np.random.default_rng(3)
    signals = [rng.random(200), rng.random(200), np.r_[np.zeros(180), np.linspace(0, 1, 20)]]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        results = pairwise_cross_measures(signals, names=["RP", "AP", "AC"], delay=1)
    ac = results[("RP", "AC")]
    assert ac.eps_y == 0.0
    assert ac.achieved_rr_y == pytest.approx(zero_distance_rate(signals[2], 3, 1), abs=1e-12)
    assert ac.achieved_rr_y > 0.8
    assert [r.degenerate for r in results.values()] == [False, True, True]
    assert [r.degenerate_reason for r in results.values()] == [
        "", *["signal AC: threshold 0 (too few distinct states)"] * 2
    ]
    (typed,) = [w.message for w in caught if w.category is DegenerateWarning]
    assert typed.problem == "degenerate"
    assert typed.signals == ("AC",)
    assert typed.pairs == (("RP", "AC"), ("AP", "AC"))
    messages = [str(w.message) for w in caught if issubclass(w.category, ThresholdWarning)]
    degenerate = [m for m in messages if "degenerate" in m]
    assert len(degenerate) == 1
    assert degenerate[0].startswith("degenerate recurrence structure of signal AC (rr 0.8")
    assert "signal RP" not in degenerate[0] and "signal AP" not in degenerate[0]
    assert "barely moves" in degenerate[0]
    assert "2 pair(s) are meaningless: (RP, AC), (AP, AC)" in degenerate[0]
    # Its pairs are not listed again under the generic (slight overshoot) warning.
    assert not any("ties at a threshold" in m for m in messages)
    assert {w.filename for w in caught} == {__file__}


def test_slight_overshoot_keeps_the_generic_warning():
    # Integer values: ties at the threshold, yet rates stay close to the 0.05 target.
    values = np.random.default_rng(5).integers(0, 10, size=(200, 3)).astype(float)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        results = pairwise_cross_measures(values, names=["RP", "AP", "AC"], delay=1)
    for r in results.values():
        assert r.rate_exceeded and not r.degenerate
        assert 0.05 < max(r.achieved_rr_x, r.achieved_rr_y, r.achieved_cr) <= 0.1
        assert min(r.eps_x, r.eps_y, r.eps_xy) > 0
    messages = [str(w.message) for w in caught if issubclass(w.category, ThresholdWarning)]
    assert [m for m in messages if "ties" in m] == [
        "ties at a threshold pushed an achieved rate above its target for 3 pair(s): "
        "(RP, AP), (RP, AC), (AP, AC); see achieved_rr_x, achieved_rr_y, achieved_cr "
        "(rate_exceeded is True)"
    ]
    assert not any("degenerate" in m for m in messages)


def test_explicit_thresholds_are_never_degenerate():
    # An explicit eps has no target rate to overshoot, however many pairs it admits.
    x = np.sin(np.arange(100.0))
    result = cross_measures(x, np.cos(np.arange(100.0)), eps=(10.0, 1e-3))
    assert result.achieved_rr_x == 1.0 and not result.degenerate
    assert result.degenerate_reason == ""


def test_pairwise_warns_once_listing_the_pairs():
    signals = [np.sin(np.linspace(0, 20, 200) * (1 + k / 10)) for k in range(3)]
    with pytest.warns(ThresholdWarning) as record:
        pairwise_cross_measures(signals, eps=(0.05, 0.5))
    messages = [str(w.message) for w in record if issubclass(w.category, ThresholdWarning)]
    assert len(messages) == 1
    assert "(0, 1), (0, 2), (1, 2)" in messages[0]


def test_pairwise_names_the_signals_in_warnings_and_errors():
    signals = [np.sin(np.linspace(0, 20, 200) * (1 + k / 10)) for k in range(3)]
    # eps_xy = 0.5 is below eps_x = eps_y = 1.0 for (RP, AP) only.
    eps = ((1.0, 1.0, 0.1), 0.5)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        results = pairwise_cross_measures(signals, names=["RP", "AP", "AC"], eps=eps)
    assert [r.eps_ordered for r in results.values()] == [True, False, False]
    assert [str(w.message) for w in caught] == [
        "eps_xy is not below eps_x and eps_y for 2 pair(s): (RP, AC), (AP, AC); section 2.2 of "
        "the paper asks eps_xy < eps_x, eps_y for a modular ISRN (eps_ordered is False)"
    ]
    assert caught[0].filename == __file__  # the caller's line, not funcnet's
    with pytest.raises(SignalError, match="signal 'AC' has 1 NaN"):
        pairwise_cross_measures(
            [*signals[:2], np.r_[signals[2][:-1], np.nan]], names="RP AP AC".split()
        )
    with pytest.raises(ParameterError, match="names has 2 entries for 3 signals"):
        pairwise_cross_measures(signals, names=["RP", "AP"])


def test_cross_measures_is_a_frozen_result():
    result = cross_measures(np.sin(np.arange(100.0)), np.cos(np.arange(100.0)), cr=0.01)
    assert isinstance(result, CrossMeasures)
    with pytest.raises(AttributeError):
        result.c_xy = 0.0  # type: ignore[misc]
