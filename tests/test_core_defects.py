"""Defects of the numerical core found in review, each pinned by a test that failed before.

Also the contracts the reshape added to the core: one parameter bundle, metric aliases,
multichannel nodes (against a brute-force reference), typed and pure threshold warnings.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import warnings
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import funcnet.core.thresholds as order_statistic
from funcnet.core.embedding import MIN_STATES, embed, signal_states
from funcnet.core.measures import (
    cross_measures,
    isrn_measures,
    pairwise_cross_measures,
    threshold_warnings,
)
from funcnet.core.recurrence import (
    PackedRecurrence,
    auto_recurrence,
    cross_recurrence,
    cross_recurrence_matrix,
    recurrence_matrix,
)
from funcnet.errors import DegenerateWarning, ParameterError, SignalError, ThresholdWarning
from funcnet.parameters import NetworkParameters
from test_measures import reference_direction
from test_recurrence import make_signal, reference_auto, reference_cross, reference_embed

SRC = Path(__file__).resolve().parents[1] / "src" / "funcnet"
CORE = ("core/embedding.py", "core/_isrn_kernels.py", "core/thresholds.py", "core/recurrence.py",
        "core/measures.py")


def sine_pair(n=251):
    t = np.linspace(0, 8 * np.pi, n)
    return np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)


# ----------------------------------------------------------------------------------------------
# isrn_measures(cr_yx=...) read a foreign or wrongly shaped matrix


def test_isrn_measures_takes_no_cr_yx_and_checks_shapes():
    x, y = sine_pair()
    xs, ys = embed(x, 3, 10), embed(y[:200], 3, 10)
    a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    cr_xy = cross_recurrence(xs, ys, cr=0.05)
    with pytest.raises(TypeError, match="cr_yx"):  # dropped: CR_YX is always cr_xy's transpose
        isrn_measures(a_x, a_y, cr_xy, cr_yx=cr_xy)  # type: ignore[call-arg]
    with pytest.raises(ParameterError, match="cr_xy has shape"):
        isrn_measures(a_x, a_y, cr_xy.transposed())
    with pytest.raises(ParameterError, match="a_x must be square"):
        isrn_measures(cr_xy, a_y, cr_xy)
    with pytest.raises(ParameterError, match="rows must be a uint64 array"):
        PackedRecurrence(np.zeros((3, 1), np.uint64), 200, 1.0, 0.0, None, 0, 9, None, False)


# ----------------------------------------------------------------------------------------------
# no environment change at import


def test_importing_and_running_the_core_leaves_the_environment_alone():
    code = (
        "import os, numpy as np\n"
        "before = dict(os.environ)\n"
        "import funcnet.core.measures, funcnet.core.recurrence\n"
        "t = np.linspace(0, 8 * np.pi, 120)\n"
        "funcnet.core.measures.cross_measures(np.sin(t), np.cos(t), delay=4, warn=False)\n"
        "changed = sorted(set(os.environ.items()) ^ set(before.items()))\n"
        "print(changed)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    assert done.stdout.strip() == "[]"


def test_no_thread_unsafe_warning_capture_in_the_core():
    for name in CORE:
        assert "catch_warnings" not in (SRC / name).read_text(), name


# ----------------------------------------------------------------------------------------------
# the exact decimal rank


def test_rank_is_exact_for_the_decimal_rate():
    # M = 20000, rr = 0.07: P = M (M - 1); 0.07 * P is 27998600.000000004 in float64.
    p = 20_000 * 19_999
    assert p == 399_980_000
    assert 0.07 * p > 27_998_600
    assert order_statistic._rank_from_rate(0.07, p) == 27_998_600
    assert order_statistic._rank_from_rate(0.05, p) == 19_999_000
    assert order_statistic._rank_from_rate(0.05, 10) == 1  # max(1, ...)
    assert order_statistic._rank_from_rate(1e-9, 10) == 1


@settings(max_examples=200, deadline=None)
@given(rate=st.floats(1e-6, 1 - 1e-6), n_candidates=st.integers(1, 10**12))
def test_rank_is_the_ceiling_of_the_decimal_product(rate, n_candidates):
    k = order_statistic._rank_from_rate(rate, n_candidates)
    exact = Fraction(repr(rate)) * n_candidates
    assert k == max(1, math.ceil(exact))
    assert k - 1 < exact <= k or k == 1


def test_pyunicorn_index_stays_as_pyunicorn_computes_it():
    # 0.29 * 100 is 28.999999999999996 in float64: pyunicorn's int() takes index 28, the exact
    # decimal would take 29. The compatibility rule keeps pyunicorn's float arithmetic.
    assert int(0.29 * 100) == 28
    assert order_statistic._pyunicorn_rank(0.29, None, 101) == 29  # index 28 -> 29 elements
    assert order_statistic._pyunicorn_rank(0.29, 10, 101) == 19


# ----------------------------------------------------------------------------------------------
# minimum number of states; degenerate (too few distinct states, constant) is a flag


def test_too_few_states_is_a_signal_error_naming_the_signal():
    x = np.sin(np.arange(200.0))
    short = x[: 2 * 10 + MIN_STATES - 1]  # dim 3, delay 10: MIN_STATES - 1 states
    with pytest.raises(SignalError, match=f"signal y is too short.*at least {MIN_STATES}"):
        cross_measures(x, short, warn=False)
    with pytest.raises(SignalError, match="signal 'AC' is too short"):
        pairwise_cross_measures([x[:30], x[:26]], names=["RP", "AC"])
    with pytest.raises(SignalError, match="states of x must be a 2-D array"):
        auto_recurrence(embed(x[:6], 1, 1), rr=0.05)
    signal_states(x[: 2 * 10 + MIN_STATES])  # exactly the minimum is fine


def test_few_distinct_states_is_a_flagged_result_not_an_error():
    levels = np.tile([0.0, 1.0], 100)
    result = cross_measures(levels, np.sin(np.arange(200.0)), dim=1, delay=1, warn=False)
    assert result.degenerate
    assert result.degenerate_reason == "signal x: threshold 0 (too few distinct states)"


@pytest.mark.parametrize("eps", [None, ((0.1, 0.1), 0.5)])
def test_a_constant_signal_gives_a_degenerate_result(eps):
    x, y = np.ones(200), np.sin(np.arange(200.0) / 5)
    with pytest.warns(ThresholdWarning) as record:  # eps_order too, with explicit thresholds
        result = cross_measures(y, x, eps=eps)
    assert result.degenerate
    assert result.degenerate_reason.startswith("signal y: constant (a single distinct state)")
    (typed,) = [w.message for w in record if w.category is DegenerateWarning]
    assert typed.signals == ("y",)
    assert typed.pairs == (("x", "y"),)


# ----------------------------------------------------------------------------------------------
# finite input and amplitudes that overflow the distance keys


def test_nan_in_a_channel_names_the_signal_and_channel():
    node = np.column_stack([np.sin(np.arange(100.0)), np.cos(np.arange(100.0))])
    node[40, 1] = np.nan
    with pytest.raises(SignalError, match=r"signal 'AP' \(channel 1\) has 1 NaN"):
        pairwise_cross_measures([np.sin(np.arange(100.0)), node], names=["RP", "AP"])


@pytest.mark.parametrize("metric", ["euclidean", "supremum", "manhattan"])
def test_huge_amplitudes_are_refused_not_reported_as_degenerate(metric):
    rng = np.random.default_rng(0)
    huge, plain = 1e308 * rng.uniform(-1, 1, 300), rng.normal(size=300)
    with pytest.raises(SignalError, match="signal x: amplitudes too large"):
        cross_measures(huge, plain, metric=metric, warn=False)
    with pytest.raises(SignalError, match="beyond float32"):
        cross_measures(plain, 1e200 * plain, rule="pyunicorn", warn=False)


def test_amplitudes_that_overflow_only_between_two_signals_are_refused():
    u = np.random.default_rng(1).uniform(0, 1, 200)
    x, y = 1e154 * u, -1e154 * u  # each alone squares to < 1.8e308, their distances do not
    auto_recurrence(embed(x, 1, 1), rr=0.05)
    with pytest.raises(SignalError, match="signals x and y: amplitudes too large"):
        cross_measures(x, y, dim=1, delay=1, warn=False)
    # Large but measurable amplitudes keep every number.
    scaled = cross_measures(1e150 * u, 1e150 * u[::-1], dim=1, delay=1, warn=False)
    plain = cross_measures(u, u[::-1], dim=1, delay=1, warn=False)
    assert (scaled.c_xy, scaled.t_yx) == (plain.c_xy, plain.t_yx)


# ----------------------------------------------------------------------------------------------
# the bisection fallback holds one row of keys per thread, not packed rows


def test_bisect_bracket_packs_nothing(monkeypatch):
    def no_packing(*args):
        raise AssertionError("the bisection must only count")

    monkeypatch.setattr(order_statistic, "_scan_rows", no_packing)
    xs = reference_embed(make_signal("noise", 600, 2), 2, 1)
    bt = np.ascontiguousarray(xs.T)
    lo, hi, share = order_statistic._bisect_bracket(xs, bt, False, 0, 0, 1000)
    keys = np.sort(((xs[:, None, :] - xs[None, :, :]) ** 2).sum(axis=2).ravel())
    assert lo < keys[999] <= hi
    assert share <= 1.0


# ----------------------------------------------------------------------------------------------
# one parameter contract; metric aliases


def test_parameters_object_and_overrides_agree():
    x, y = sine_pair()
    p = NetworkParameters(dim=2, delay=5, rr=0.1, cr=0.03, metric="manhattan")
    by_object = cross_measures(x, y, parameters=p, warn=False)
    by_keywords = cross_measures(
        x, y, dim=2, delay=5, rr=0.1, cr=0.03, metric="manhattan", warn=False
    )
    assert by_object == by_keywords
    assert by_object.parameters == p
    assert cross_measures(x, y, parameters=p, rr=0.2, warn=False).parameters == p.replace(rr=0.2)
    with pytest.raises(ParameterError, match="mu is not a parameter here"):
        cross_measures(x, y, mu=0.1)
    with pytest.raises(ParameterError, match="theiler is not a parameter here"):
        cross_recurrence_matrix(x, y, parameters=p, theiler=1)


def test_per_signal_rates_and_thresholds_equal_brute_force():
    x, y = make_signal("sine", 120, 1), make_signal("walk", 120, 2)
    result = cross_measures(x, y, dim=2, delay=2, rr=(0.1, 0.04), eps=((None, 0.5), None),
                            cr=0.06, warn=False)
    xs, ys = reference_embed(x, 2, 2), reference_embed(y, 2, 2)
    a_x, eps_x = reference_auto(xs, rr=0.1)
    a_y, eps_y = reference_auto(ys, eps=0.5)
    cr_xy, eps_xy = reference_cross(xs, ys, cr=0.06)
    assert (result.eps_x, result.eps_y, result.eps_xy) == (eps_x, eps_y, eps_xy)
    assert result.c_xy == pytest.approx(reference_direction(cr_xy, a_y)[1], abs=1e-12)
    assert result.t_yx == pytest.approx(reference_direction(cr_xy.T, a_x)[2], abs=1e-12)
    # A pair of a larger set records its own rates and thresholds.
    signals = [x, make_signal("noise", 120, 3), y]
    results = pairwise_cross_measures(
        signals, dim=2, delay=2, rr=(0.1, 0.2, 0.04), eps=((None, 0.3, 0.5), None), cr=0.06,
        warn=False,
    )
    pair = results[(0, 2)]
    assert pair.parameters.rr == (0.1, 0.04)
    assert pair.parameters.eps == ((None, 0.5), None)
    assert pair == cross_measures(x, y, parameters=pair.parameters, warn=False)


@pytest.mark.parametrize(("alias", "name"), [("chebyshev", "supremum"), ("cityblock", "manhattan")])
def test_metric_aliases(alias, name):
    x, y = sine_pair()
    np.testing.assert_array_equal(
        recurrence_matrix(x, metric=alias, rr=0.05), recurrence_matrix(x, metric=name, rr=0.05)
    )
    aliased = cross_measures(x, y, metric=alias, warn=False)
    assert aliased == cross_measures(x, y, metric=name, warn=False)
    assert aliased.parameters.metric == name


# ----------------------------------------------------------------------------------------------
# multichannel nodes


def test_multichannel_states_are_the_channels_embeddings_side_by_side():
    node = np.column_stack([np.arange(30.0), np.arange(30.0) ** 2, -np.arange(30.0)])
    states = signal_states(node, dim=2, delay=3)
    expected = np.hstack([reference_embed(node[:, c], 2, 3) for c in range(3)])
    np.testing.assert_array_equal(states, expected)
    assert states.flags.c_contiguous and states.shape == (27, 6)
    # One channel as (N, 1) is the scalar signal.
    np.testing.assert_array_equal(signal_states(node[:, :1]), signal_states(node[:, 0]))


@settings(max_examples=15, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    channels=st.integers(1, 3),
    metric=st.sampled_from(("euclidean", "supremum", "manhattan")),
    rates=st.tuples(st.floats(0.02, 0.3), st.floats(0.02, 0.3)),
)
def test_multichannel_cross_measures_equal_brute_force(seed, channels, metric, rates):
    # Two nodes of the same number of channels: CR_XY needs one common phase space.
    rng = np.random.default_rng(seed)
    node = np.cumsum(rng.normal(size=(70, channels)), axis=0)
    other = np.sin(np.arange(70)[:, None] / (3.0 + np.arange(channels))) + 0.1 * rng.normal(
        size=(70, channels)
    )
    rr, cr = rates
    result = cross_measures(node, other, dim=2, delay=2, rr=rr, cr=cr, metric=metric, warn=False)
    xs = np.hstack([reference_embed(node[:, c], 2, 2) for c in range(channels)])
    ys = np.hstack([reference_embed(other[:, c], 2, 2) for c in range(channels)])
    a_x, eps_x = reference_auto(xs, rr=rr, metric=metric)
    a_y, eps_y = reference_auto(ys, rr=rr, metric=metric)
    cr_xy, eps_xy = reference_cross(xs, ys, cr=cr, metric=metric)
    xy, yx = reference_direction(cr_xy, a_y), reference_direction(cr_xy.T, a_x)
    assert (result.eps_x, result.eps_y, result.eps_xy) == pytest.approx(
        (eps_x, eps_y, eps_xy), abs=1e-12
    )
    assert result.c_xy == pytest.approx(xy[1], abs=1e-12)
    assert result.c_yx == pytest.approx(yx[1], abs=1e-12)
    assert result.t_xy == pytest.approx(xy[2], abs=1e-12)
    assert result.t_yx == pytest.approx(yx[2], abs=1e-12)


def test_pairwise_takes_multichannel_nodes():
    rng = np.random.default_rng(4)
    node = np.cumsum(rng.normal(size=(150, 2)), axis=0)
    a = np.column_stack([np.sin(np.arange(150) / 4.0), np.cos(np.arange(150) / 5.0)])
    b = rng.normal(size=(150, 2))
    results = pairwise_cross_measures([a, node, b], names=["A", "N", "B"], dim=2, delay=2,
                                      warn=False)
    assert list(results) == [("A", "N"), ("A", "B"), ("N", "B")]
    assert results[("A", "N")] == cross_measures(a, node, dim=2, delay=2, warn=False)
    assert results[("N", "B")].m_x == 148
    with pytest.raises(SignalError, match="equal lengths"):
        pairwise_cross_measures([a, node[:100]], dim=2, delay=2)
    # A pair compares states in one phase space: the nodes need as many channels.
    with pytest.raises(SignalError, match="'N' has 2 channels and 'S' 1"):
        pairwise_cross_measures([node, a[:, 0]], names=["N", "S"], dim=2, delay=2)
    with pytest.raises(SignalError, match="x has 2 channels and y 1"):
        cross_measures(node, a[:, 0], dim=2, delay=2)


# ----------------------------------------------------------------------------------------------
# results keyed by names; typed, pure warnings


def test_pairwise_keys_by_names_and_warn_false_is_silent():
    signals = [np.sin(np.linspace(0, 20, 200) * (1 + k / 10)) for k in range(3)]
    eps = ((1.0, 1.0, 0.1), 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        results = pairwise_cross_measures(signals, names=["RP", "AP", "AC"], eps=eps, warn=False)
    assert list(results) == [("RP", "AP"), ("RP", "AC"), ("AP", "AC")]
    found = threshold_warnings(results)
    assert [type(w) for w in found] == [ThresholdWarning]
    assert found[0].problem == "eps_order"
    assert found[0].pairs == (("RP", "AC"), ("AP", "AC"))
    # Pure: asking again builds the same warnings, and nothing was emitted meanwhile.
    assert [(w.problem, w.pairs) for w in threshold_warnings(results)] == [
        ("eps_order", found[0].pairs)
    ]
    with pytest.warns(ThresholdWarning) as record:
        pairwise_cross_measures(signals, names=["RP", "AP", "AC"], eps=eps)
    assert [w.message.problem for w in record] == ["eps_order"]


def test_threshold_warnings_kinds():
    rng = np.random.default_rng(5)
    values = rng.integers(0, 10, size=(200, 3)).astype(float)
    results = pairwise_cross_measures(values, delay=1, warn=False)
    (tied,) = [w for w in threshold_warnings(results) if w.problem != "eps_order"]
    assert type(tied) is ThresholdWarning and tied.problem == "rate_exceeded"
    assert tied.pairs == (("0", "1"), ("0", "2"), ("1", "2"))
    ramp = [rng.random(200), rng.random(200), np.r_[np.zeros(180), np.linspace(0, 1, 20)]]
    results = pairwise_cross_measures(ramp, names=["RP", "AP", "AC"], delay=1, warn=False)
    (degenerate,) = [w for w in threshold_warnings(results) if w.problem == "degenerate"]
    assert isinstance(degenerate, DegenerateWarning)
    assert degenerate.signals == ("AC",)
    assert degenerate.located("w1").window == "w1"
