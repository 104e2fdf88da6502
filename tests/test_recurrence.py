"""Embedding, thresholds and (cross-)recurrence matrices against a brute-force float64 reference.

The reference below holds the full distance matrix (fine for the small sizes used here) and
applies the threshold rules of README method step 4 literally: sort the candidate distances,
take the k-th with k = max(1, ceil(rate * P)) for the rate as written in decimal (exact rational
arithmetic); or pyunicorn's sorted full matrix at index int(rate * (P - 1)) with strict
comparison.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numba
import numpy as np
import pytest
from hypothesis import example, given, settings, strategies as st

import funcnet.core._keys as _keys
import funcnet.core.thresholds as order_statistic
from funcnet.core.embedding import embed, estimate_delay, estimate_dimension, signal_states
from funcnet.core.recurrence import (
    auto_recurrence,
    cross_recurrence,
    cross_recurrence_matrix,
    isrn_adjacency,
    recurrence_matrix,
)
from funcnet.errors import ParameterError, SignalError

METRICS = ("euclidean", "supremum", "manhattan")


def decimal_rank(rate, n_candidates):
    """k = max(1, ceil(rate * P)) for the rate as written in decimal (README method step 4)."""
    return max(1, math.ceil(Fraction(repr(rate)) * n_candidates))


# ----------------------------------------------------------------------------------------------
# brute-force reference (also imported by test_measures.py)


def reference_embed(x, dim, delay):
    x = np.asarray(x, dtype=np.float64)
    m = x.size - (dim - 1) * delay
    return np.array([[x[i + c * delay] for c in range(dim)] for i in range(m)], dtype=np.float64)


def reference_distances(a, b, metric):
    """Dense float64 distance matrix, coordinates accumulated in order (as pyunicorn does)."""
    diff = np.abs(a[:, None, :] - b[None, :, :])
    if metric == "supremum":
        return diff.max(axis=2)
    total = np.zeros(diff.shape[:2])
    for c in range(a.shape[1]):
        total = total + (diff[..., c] ** 2 if metric == "euclidean" else diff[..., c])
    return np.sqrt(total) if metric == "euclidean" else total


def reference_auto(states, *, rr=None, eps=None, metric="euclidean", theiler=0, rule="funcnet"):
    """(A, eps) of one signal by sorting every candidate distance."""
    d = reference_distances(states, states, metric)
    i, j = np.indices(d.shape)
    if rule == "funcnet":
        candidates = np.abs(i - j) > theiler
        if eps is None:
            values = np.sort(d[candidates])
            eps = values[decimal_rank(rr, values.size) - 1]
        return candidates & (d <= eps), float(eps)
    if eps is None:
        flat = np.sort(d.ravel())
        eps = flat[int(rr * (flat.size - 1))]
    adjacency = d < eps
    np.fill_diagonal(adjacency, False)
    return adjacency, float(eps)


def reference_cross(x_states, y_states, *, cr=None, eps=None, metric="euclidean", rule="funcnet"):
    d = reference_distances(x_states, y_states, metric)
    values = np.sort(d.ravel())
    if rule == "funcnet":
        if eps is None:
            eps = values[decimal_rank(cr, values.size) - 1]
        return d <= eps, float(eps)
    if eps is None:
        eps = values[int(cr * (values.size - 1))]
    return d < eps, float(eps)


def make_signal(kind, n, seed):
    """Signals of different character: noise, random walk, smooth, and quantized (ties)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    if kind == "noise":
        return rng.normal(size=n)
    if kind == "walk":
        return np.cumsum(rng.normal(size=n))
    if kind == "sine":
        return np.sin(0.3 * t + rng.uniform(0, 6)) + 0.05 * rng.normal(size=n)
    if kind == "quantized":
        return np.round(np.cumsum(rng.normal(size=n)))
    if kind == "levels":
        return rng.integers(0, 3, size=n).astype(float)
    raise ValueError(kind)


KINDS = ("noise", "walk", "sine", "quantized", "levels")


# ----------------------------------------------------------------------------------------------
# embedding


def test_embed_matches_definition():
    x = np.arange(20.0) ** 2
    states = embed(x, dim=4, delay=3)
    assert states.shape == (20 - 3 * 3, 4)
    assert states.dtype == np.float64
    np.testing.assert_array_equal(states, reference_embed(x, 4, 3))


def test_embed_dim_one_is_the_signal():
    np.testing.assert_array_equal(embed([3, 1, 2], 1, 5), [[3.0], [1.0], [2.0]])


def test_pyunicorn_rule_casts_input_to_float32():
    x = np.tile([0.1, 0.2, 0.3, 1 / 3], 2)
    states = signal_states(x, dim=1, delay=1, rule="pyunicorn")
    np.testing.assert_array_equal(states[:, 0], x.astype(np.float32).astype(np.float64))
    np.testing.assert_array_equal(signal_states(x, dim=1, delay=1)[:, 0], x)


@pytest.mark.parametrize(
    ("kwargs", "error", "word"),
    [
        ({"x": np.arange(10.0), "dim": 0, "delay": 1}, ParameterError, "dim"),
        ({"x": np.arange(10.0), "dim": 2, "delay": 0}, ParameterError, "delay"),
        ({"x": np.arange(10.0), "dim": 2.5, "delay": 1}, ParameterError, "dim"),
        ({"x": np.arange(10.0), "dim": 2, "delay": True}, ParameterError, "delay"),
        ({"x": np.arange(5.0), "dim": 3, "delay": 3}, SignalError, "too short"),
        ({"x": [1.0, np.nan, 2.0], "dim": 1, "delay": 1}, SignalError, "NaN"),
        ({"x": [1.0, np.inf, 2.0], "dim": 1, "delay": 1}, SignalError, "infinite"),
        ({"x": np.ones((4, 2)), "dim": 1, "delay": 1}, SignalError, "one-dimensional"),
        ({"x": ["a", "b"], "dim": 1, "delay": 1}, SignalError, "real-valued"),
    ],
)
def test_embed_rejects_bad_input(kwargs, error, word):
    with pytest.raises(error, match=word):
        embed(**kwargs)


# ----------------------------------------------------------------------------------------------
# dense matrices against brute force


@settings(max_examples=40, deadline=None)
@given(
    kind=st.sampled_from(KINDS),
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(20, 70),
    dim=st.integers(1, 4),
    delay=st.integers(1, 3),
    metric=st.sampled_from(METRICS),
    rr=st.floats(0.005, 0.6),
    theiler=st.integers(0, 4),
)
def test_recurrence_matrix_by_rate_equals_brute_force(
    kind, seed, n, dim, delay, metric, rr, theiler
):
    x = make_signal(kind, n, seed)
    states = reference_embed(x, dim, delay)
    expected, eps = reference_auto(states, rr=rr, metric=metric, theiler=theiler)
    result = auto_recurrence(states, rr=rr, metric=metric, theiler=theiler)
    np.testing.assert_array_equal(result.to_dense(), expected)
    assert abs(result.eps - eps) <= 1e-12
    m = states.shape[0]
    assert result.n_candidates == (m - theiler) * (m - theiler - 1)
    assert result.n_recurrent == expected.sum()
    assert result.rate == expected.sum() / result.n_candidates
    k = decimal_rank(rr, result.n_candidates)
    assert result.rank == k
    # Symmetric pairs: an odd k is always exceeded by one; only ties exceed it further.
    assert result.rate_exceeded == (expected.sum() > 2 * ((k + 1) // 2))
    dense = recurrence_matrix(x, dim=dim, delay=delay, rr=rr, metric=metric, theiler=theiler)
    np.testing.assert_array_equal(dense, expected)


@settings(max_examples=30, deadline=None)
@given(
    kind=st.sampled_from(KINDS),
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(12, 70),
    metric=st.sampled_from(METRICS),
    quantile=st.floats(0.0, 1.0),
    theiler=st.integers(0, 3),
)
def test_recurrence_matrix_with_explicit_eps_equals_brute_force(
    kind, seed, n, metric, quantile, theiler
):
    x = make_signal(kind, n, seed)
    states = reference_embed(x, 2, 2)
    # A threshold that is often exactly one of the distances (ties with "<=").
    distances = reference_distances(states, states, metric)
    eps = float(np.quantile(distances[distances > 0], quantile)) if (distances > 0).any() else 1.0
    expected, _ = reference_auto(states, eps=eps, metric=metric, theiler=theiler)
    result = recurrence_matrix(x, dim=2, delay=2, eps=eps, metric=metric, theiler=theiler)
    np.testing.assert_array_equal(result, expected)
    assert auto_recurrence(states, eps=eps, metric=metric, theiler=theiler).eps == eps


@settings(max_examples=40, deadline=None)
@given(
    kinds=st.tuples(st.sampled_from(KINDS), st.sampled_from(KINDS)),
    seed=st.integers(0, 2**32 - 1),
    lengths=st.tuples(st.integers(10, 60), st.integers(10, 60)),
    metric=st.sampled_from(METRICS),
    cr=st.floats(0.002, 0.7),
    rule=st.sampled_from(("funcnet", "pyunicorn")),
)
def test_cross_recurrence_matrix_equals_brute_force(kinds, seed, lengths, metric, cr, rule):
    x = make_signal(kinds[0], lengths[0], seed)
    y = make_signal(kinds[1], lengths[1], seed + 1)
    if rule == "pyunicorn":
        x, y = x.astype(np.float32), y.astype(np.float32)
    xs, ys = reference_embed(x, 2, 1), reference_embed(y, 2, 1)
    expected, eps = reference_cross(xs, ys, cr=cr, metric=metric, rule=rule)
    result = cross_recurrence(xs, ys, cr=cr, metric=metric, rule=rule)
    np.testing.assert_array_equal(result.to_dense(), expected)
    assert abs(result.eps - eps) <= 1e-12
    assert result.rate == expected.sum() / expected.size
    dense = cross_recurrence_matrix(x, y, dim=2, delay=1, cr=cr, metric=metric, rule=rule)
    np.testing.assert_array_equal(dense, expected)
    np.testing.assert_array_equal(result.transposed().to_dense(), expected.T)


@settings(max_examples=25, deadline=None)
@given(
    kind=st.sampled_from(KINDS),
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(12, 60),
    metric=st.sampled_from(METRICS),
    rr=st.floats(0.005, 0.6),
)
def test_pyunicorn_rule_auto_recurrence_equals_reference(kind, seed, n, metric, rr):
    x = make_signal(kind, n, seed)
    states = signal_states(x, dim=3, delay=1, rule="pyunicorn")
    expected, eps = reference_auto(states, rr=rr, metric=metric, rule="pyunicorn")
    result = auto_recurrence(states, rr=rr, metric=metric, rule="pyunicorn")
    np.testing.assert_array_equal(result.to_dense(), expected)
    assert result.eps == eps
    assert not result.rate_exceeded
    np.testing.assert_array_equal(
        recurrence_matrix(x, dim=3, delay=1, rr=rr, metric=metric, rule="pyunicorn"), expected
    )


@pytest.mark.parametrize("metric", METRICS)
@pytest.mark.parametrize("kind", ["sine", "quantized", "levels"])
def test_sampled_bracket_path_is_exact(metric, kind):
    # More candidate pairs than are collected directly: the threshold comes from a sampled
    # bracket, a counting pass and a partial sort. Quantized signals put ties on the bracket.
    n = 820
    x, y = make_signal(kind, n, 3), make_signal("walk", n, 4)
    xs, ys = reference_embed(x, 3, 5), reference_embed(y, 3, 5)
    assert xs.shape[0] ** 2 // 2 > order_statistic._DIRECT_PAIRS
    expected, eps = reference_auto(xs, rr=0.05, metric=metric, theiler=2)
    result = auto_recurrence(xs, rr=0.05, metric=metric, theiler=2)
    np.testing.assert_array_equal(result.to_dense(), expected)
    assert result.eps == eps
    expected, eps = reference_cross(xs, ys, cr=0.03, metric=metric)
    result = cross_recurrence(xs, ys, cr=0.03, metric=metric)
    np.testing.assert_array_equal(result.to_dense(), expected)
    assert result.eps == eps


@pytest.mark.parametrize("kind", ["noise", "levels"])
def test_band_overflow_fallback_is_exact(monkeypatch, kind):
    # No room for the pairs inside the bracket: a second pass collects them.
    monkeypatch.setattr(order_statistic, "_BAND_SLACK", 0.0)
    x, y = make_signal(kind, 800, 6), make_signal("sine", 800, 7)
    xs, ys = reference_embed(x, 2, 1), reference_embed(y, 2, 1)
    expected, eps = reference_cross(xs, ys, cr=0.05)
    result = cross_recurrence(xs, ys, cr=0.05)
    assert result.eps == eps
    np.testing.assert_array_equal(result.to_dense(), expected)
    expected, eps = reference_auto(xs, rr=0.05, theiler=1)
    result = auto_recurrence(xs, rr=0.05, theiler=1)
    assert result.eps == eps
    np.testing.assert_array_equal(result.to_dense(), expected)


def _exact_reversed_cross():
    """A noise signal's states against themselves reversed at cr = 0.05: the cross recurrence,
    checked equal to the brute-force one (threshold and every cell), and the states."""
    x = make_signal("noise", 800, 5)
    xs = reference_embed(x, 2, 1)
    expected, eps = reference_cross(xs, xs[::-1].copy(), cr=0.05)
    result = cross_recurrence(xs, xs[::-1].copy(), cr=0.05)
    assert result.eps == eps
    np.testing.assert_array_equal(result.to_dense(), expected)
    return xs, result


@pytest.mark.parametrize("limit", [1 << 22, 1000])
def test_bracket_fallback_when_the_sample_misses(monkeypatch, limit):
    # A zero-width bracket almost surely misses the order statistic; the next, unbounded one
    # (bisection of the key range down to `limit` pairs) must still give the exact value.
    monkeypatch.setattr(order_statistic, "_BRACKET_WIDTHS", (0.0, math.inf))
    monkeypatch.setattr(order_statistic, "_BAND_LIMIT", limit)
    calls = []
    bisect = order_statistic._bisect_bracket
    monkeypatch.setattr(
        order_statistic, "_bisect_bracket", lambda *args: calls.append(args) or bisect(*args)
    )
    _exact_reversed_cross()
    assert calls


def test_sample_draws_are_the_seeded_generators_each_time(monkeypatch):
    # the first draw of a size and rank is made once for all its blocks; a wider bracket
    # resumes the generator after it: the draws are those of one generator seeded
    # [rows, cols, rank], every time
    rng = np.random.default_rng([700, 650, 1234])
    first, second = (order_statistic._draw(rng, 700, 650) for _ in range(2))
    for _ in range(2):
        rows, cols, state = order_statistic._first_draw(700, 650, 1234)
        assert np.array_equal(rows, first[0]) and np.array_equal(cols, first[1])
        assert not rows.flags.writeable
    draws = []
    sample = order_statistic._sample_bracket
    monkeypatch.setattr(order_statistic, "_BRACKET_WIDTHS", (0.0, 0.0, math.inf))
    monkeypatch.setattr(order_statistic, "_sample_bracket",
                        lambda *args: draws.append(args[-1]) or sample(*args))
    xs, result = _exact_reversed_cross()
    m = xs.shape[0]
    seeded = np.random.default_rng([m, m, result.rank])
    assert len(draws) == 2  # each zero-width bracket missed
    for got in draws:
        want = order_statistic._draw(seeded, m, m)
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])


@settings(max_examples=200, deadline=None)
@given(
    eps=st.floats(1e-6, 1e3),
    relative=st.floats(-1e-12, 1e-12),
    strict=st.booleans(),
)
def test_squared_bound_decides_exactly_like_the_distance(eps, relative, strict):
    bound = order_statistic._key_bound(eps, strict, 0)
    for key in (bound, math.nextafter(bound, math.inf), eps * eps * (1 + relative)):
        distance = math.sqrt(key)
        assert (key <= bound) == (distance < eps if strict else distance <= eps)


def _brute_key_bound(eps: float, strict: bool, metric: int) -> float:
    """The largest non-negative float key whose distance is within eps, by bisection of the
    keys' bit patterns (non-negative floats order as their bits); -inf when not even 0 is."""

    def within(bits: int) -> bool:
        key = float(np.int64(bits).view(np.float64))
        distance = float(np.sqrt(key)) if metric == 0 else key
        return distance < eps if strict else distance <= eps

    lo, hi = 0, int(np.float64(np.inf).view(np.int64))  # within(lo) holds, within(hi) not
    if not within(lo):
        return -math.inf
    while hi - lo > 1:
        middle = (lo + hi) // 2
        lo, hi = (middle, hi) if within(middle) else (lo, middle)
    return float(np.int64(lo).view(np.float64))


@numba.njit
def _compiled_key_bound(eps, strict, metric):
    return _keys.key_bound(eps, strict, metric)  # as the batched kernels call it


@settings(max_examples=300, deadline=None)
@example(eps=5e-324, ulps=-2, strict=False, metric=1)  # a negative eps: no key, as at 0 strict
@example(eps=5e-324, ulps=-1, strict=True, metric=2)
@given(
    eps=st.one_of(st.floats(5e-324, 1e300), st.floats(1e-6, 1e3).map(lambda v: v * v)),
    ulps=st.integers(-3, 3),
    strict=st.booleans(),
    metric=st.sampled_from([0, 1, 2]),
)
def test_the_one_key_bound_is_the_brute_force_bound_bit_for_bit(eps, ulps, strict, metric):
    for _ in range(abs(ulps)):  # a few ulps off a square: where rounding of the root decides
        eps = math.nextafter(eps, math.copysign(math.inf, ulps))
    want = _brute_key_bound(eps, strict, metric)
    for got in (order_statistic._key_bound(eps, strict, metric),
                _compiled_key_bound(eps, strict, metric)):
        assert np.float64(got).view(np.int64) == np.float64(want).view(np.int64)


def test_key_bound_at_zero():
    # eps = 0 (an order statistic among tied, resting samples): only key 0, and none if strict
    assert order_statistic._key_bound(0.0, False, 0) == 0.0 == _brute_key_bound(0.0, False, 0)
    assert order_statistic._key_bound(0.0, True, 0) == -math.inf
    for metric in (1, 2):
        assert order_statistic._key_bound(0.0, False, metric) == 0.0
        assert order_statistic._key_bound(0.0, True, metric) == -math.inf  # no key is within


def test_rate_times_pairs_a_hair_above_an_integer_takes_no_extra_pair():
    # README method step 4: k = max(1, ceil(rate * P)) in exact decimal. 0.07 * 100 is
    # 7.000000000000001 in float64, so a float ceil would take 8 of the 100 cross pairs.
    assert 0.07 * 100 > 7
    rng = np.random.default_rng(0)
    xs, ys = rng.normal(size=(10, 2)), rng.normal(size=(10, 2))
    result = cross_recurrence(xs, ys, cr=0.07)
    assert (result.rank, result.n_recurrent) == (7, 7)
    assert result.eps == np.sort(reference_distances(xs, ys, "euclidean").ravel())[6]
    assert not result.rate_exceeded


def test_ties_push_the_rate_above_target():
    # Three levels: most distances are 0, 1 or 2, so the k-th value is shared by many pairs.
    x = np.tile([0.0, 1.0, 2.0, 1.0], 20)
    result = auto_recurrence(embed(x, 1, 1), rr=0.1)
    assert result.rate_exceeded
    assert result.rate > 0.1
    assert result.n_recurrent > result.rank


@pytest.mark.parametrize("rule", ["funcnet", "pyunicorn"])
def test_isrn_adjacency_blocks(rule):
    t = np.linspace(0, 8 * np.pi, 120)
    x, y = np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)
    eps_x, eps_y, eps_xy = 0.3, 0.35, 0.1
    adjacency = isrn_adjacency(
        x, y, dim=3, delay=4, eps=((eps_x, eps_y), eps_xy), metric="supremum", rule=rule
    )
    xs = signal_states(x, dim=3, delay=4, rule=rule)
    ys = signal_states(y, dim=3, delay=4, rule=rule)
    a_x, _ = reference_auto(xs, eps=eps_x, metric="supremum", rule=rule)
    a_y, _ = reference_auto(ys, eps=eps_y, metric="supremum", rule=rule)
    cr_xy, _ = reference_cross(xs, ys, eps=eps_xy, metric="supremum", rule=rule)
    np.testing.assert_array_equal(adjacency, np.block([[a_x, cr_xy], [cr_xy.T, a_y]]))


def test_isrn_adjacency_mixes_explicit_eps_and_rates():
    x, y = make_signal("sine", 90, 1), make_signal("walk", 90, 2)
    adjacency = isrn_adjacency(
        x, y, dim=2, delay=3, rr=0.1, cr=0.05, eps=((None, 0.5), None), theiler=1
    )
    xs, ys = reference_embed(x, 2, 3), reference_embed(y, 2, 3)
    a_x, _ = reference_auto(xs, rr=0.1, theiler=1)
    a_y, _ = reference_auto(ys, eps=0.5, theiler=1)
    cr_xy, _ = reference_cross(xs, ys, cr=0.05)
    np.testing.assert_array_equal(adjacency, np.block([[a_x, cr_xy], [cr_xy.T, a_y]]))


def test_cross_recurrence_matrix_has_no_theiler_and_keeps_its_diagonal():
    # A Theiler window concerns states of one system; the cross block compares two and keeps
    # every pair, so the same signal against itself is recurrent on the whole diagonal. The
    # parameter, once accepted and ignored, is refused.
    x = make_signal("sine", 90, 1)
    plain = cross_recurrence_matrix(x, x, dim=2, delay=3, cr=0.05)
    assert plain.diagonal().all()
    for theiler in (3, 0, -1):
        with pytest.raises(ParameterError, match="theiler is not a parameter here"):
            cross_recurrence_matrix(x, x, dim=2, delay=3, cr=0.05, theiler=theiler)


# ----------------------------------------------------------------------------------------------
# bad parameters


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [
        ({"rr": 0.0}, "rr"),
        ({"rr": 1.0}, "rr"),
        ({"rr": -0.2}, "rr"),
        ({"rr": float("nan")}, "rr"),
        ({"rr": "0.05"}, "rr"),
        ({"eps": 0.0}, "eps"),
        ({"eps": -1.0}, "eps"),
        ({"eps": float("inf")}, "eps"),
        ({"metric": "cosine"}, "metric"),
        ({"rule": "scipy"}, "rule"),
        ({"theiler": -1}, "theiler"),
        ({"theiler": 1, "rule": "pyunicorn"}, "theiler"),
        ({"theiler": 500}, "theiler"),
        ({"dim": 0}, "dim"),
        ({"delay": -3}, "delay"),
    ],
)
def test_recurrence_matrix_rejects_bad_parameters(kwargs, word):
    with pytest.raises(ParameterError, match=word):
        recurrence_matrix(np.sin(np.arange(100.0)), **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [({"cr": 1.5}, "cr"), ({"eps": -0.1}, "eps"), ({"metric": "l2"}, "metric")],
)
def test_cross_recurrence_matrix_rejects_bad_parameters(kwargs, word):
    x = np.sin(np.arange(60.0))
    with pytest.raises(ParameterError, match=word):
        cross_recurrence_matrix(x, x, dim=2, delay=1, **kwargs)


def test_errors_name_the_signal():
    good = np.sin(np.arange(60.0))
    with pytest.raises(SignalError, match="signal y"):
        cross_recurrence_matrix(good, np.r_[good[:-1], np.nan], dim=2, delay=1)
    with pytest.raises(SignalError, match="signal x .*too short"):
        cross_recurrence_matrix(good[:5], good, dim=3, delay=2)
    with pytest.raises(ParameterError, match="eps must be positive"):
        isrn_adjacency(good, good, dim=2, delay=1, eps=((0.1, 0.0), 0.1))
    with pytest.raises(ParameterError, match=r"eps must be \(auto, cross\)"):
        isrn_adjacency(good, good, dim=2, delay=1, eps=(0.1, 0.1, 0.1))
    with pytest.raises(SignalError, match="same dim"):
        cross_recurrence(embed(good, 2, 1), embed(good, 3, 1))


# ----------------------------------------------------------------------------------------------
# embedding parameters


@pytest.mark.parametrize("period", [40.5, 63.7, 100.0, 157.08])
def test_estimate_delay_is_a_quarter_period_for_a_sine(period):
    x = np.sin(2 * np.pi * np.arange(4000) / period)
    assert abs(estimate_delay(x) - period / 4) <= 1.0


def test_estimate_delay_errors():
    with pytest.raises(SignalError, match="constant"):
        estimate_delay(np.ones(100))
    with pytest.raises(ParameterError, match="bins"):
        estimate_delay(np.arange(100.0), bins=1)
    with pytest.raises(SignalError, match="no minimum"):
        estimate_delay(np.arange(100.0), max_delay=10)


def _henon(n):
    u, v, series = 0.1, 0.1, []
    for _ in range(n + 100):
        u, v = 1 - 1.4 * u * u + v, 0.3 * u
        series.append(u)
    return np.array(series[100:])


def _lorenz_x(n, dt=0.01):
    from scipy.integrate import solve_ivp

    def field(_, s):
        return [10 * (s[1] - s[0]), s[0] * (28 - s[2]) - s[1], s[0] * s[1] - 8 / 3 * s[2]]

    t = np.arange(n + 1000) * dt
    solution = solve_ivp(field, (0, t[-1]), [1.0, 1.0, 1.0], t_eval=t, rtol=1e-9, atol=1e-9)
    return solution.y[0, 1000:]


@pytest.mark.parametrize("method", ["fnn", "cao"])
def test_estimate_dimension_of_known_systems(method):
    assert estimate_dimension(_henon(3000), delay=1, method=method) == 2
    assert estimate_dimension(_lorenz_x(4000), delay=10, method=method) == 3


def test_estimate_dimension_errors():
    with pytest.raises(ParameterError, match="method"):
        estimate_dimension(np.arange(100.0), delay=1, method="pca")
    with pytest.raises(SignalError, match="constant"):
        estimate_dimension(np.ones(100), delay=1)
    with pytest.raises(SignalError, match="too short"):
        estimate_dimension(np.arange(20.0), delay=5)
