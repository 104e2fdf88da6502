"""funcnet.evidence: the dependence test, its surrogates, the intervals, and pinned error rates.

The error-rate tests run a fixed seed set (seeds 0..n-1 of funcnet.validation.systems) and allow for
binomial noise: a false-positive count must stay within 0.05 + 3 standard errors of its pairs,
power at least the bound given. They were set from the measured rates in docs/validation/evidence.md
(measured on seeds from 1000 on), not tuned on these seeds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from funcnet.core.embedding import embed
from funcnet.core.measures import cross_measures
from funcnet.core.recurrence import auto_recurrence
from funcnet.errors import ParameterError
from funcnet.evidence import (
    asymmetry_interval,
    benjamini_hochberg,
    decorrelation_time,
    default_surrogates,
    dependence_test,
    evidence_label,
    half_samples,
    interval_kind,
    pairwise_evidence,
    resampled_differences,
    shift_plan,
)
from funcnet.evidence.dependence import surrogate_plan
from funcnet.evidence.surrogates import twin_groups, twin_plan
from funcnet.validation import systems


def minmax(x):
    return (x - x.min()) / (x.max() - x.min())


def dense(states):
    return auto_recurrence(states, rr=0.05).to_dense().astype(np.uint8)


def p_values(batch, delay=1, dim=3, surrogates=99):
    """Unadjusted p-values of the dependence test of every pair of a batch (n, k, 2)."""
    out = []
    for k in range(batch.shape[1]):
        x, y = batch[:, k, 0], batch[:, k, 1]
        xs, ys = embed(x, dim, delay), embed(y, dim, delay)
        s0 = max(decorrelation_time(x), decorrelation_time(y), (dim - 1) * delay + 1)
        plan = shift_plan(xs.shape[0], surrogates, min_shift=s0)
        out.append(dependence_test(dense(xs), dense(ys), plan).p_value)
    return np.array(out)


def bound(pairs, alpha=0.05):
    """Most rejections allowed among ``pairs`` null pairs: alpha + 3 binomial SE."""
    return math.floor(pairs * (alpha + 3 * math.sqrt(alpha * (1 - alpha) / pairs)))


# --- the pieces ------------------------------------------------------------------------------


def test_default_surrogates_allow_a_lone_discovery():
    for m in (1, 3, 15, 45):
        k = default_surrogates(m, 0.05)
        assert k >= 99 and 1 / (k + 1) <= 0.05 / m
    assert default_surrogates(15) == 299


def test_benjamini_hochberg_matches_the_step_up_rule():
    p = np.array([0.001, 0.008, 0.039, 0.041, 0.042, 0.06, 0.074, 0.205, np.nan])
    adjusted = benjamini_hochberg(p)
    m = 8
    order = np.argsort(p[:m])
    expected = np.minimum.accumulate((p[:m][order] * m / np.arange(1, m + 1))[::-1])[::-1]
    np.testing.assert_allclose(adjusted[:m][order], expected)
    assert np.isnan(adjusted[-1])
    assert (benjamini_hochberg(p[:m]) >= p[:m]).all()


@settings(max_examples=300, deadline=None)
@given(st.lists(st.one_of(st.floats(0.0, 1.0), st.sampled_from([0.0, 1.0, 0.05, np.nan])),
                max_size=60))
def test_benjamini_hochberg_is_scipys_bit_for_bit(values):
    from scipy.stats import false_discovery_control

    p = np.asarray(values, dtype=np.float64)
    adjusted = benjamini_hochberg(p)
    valid = ~np.isnan(p)
    assert np.isnan(adjusted[~valid]).all()
    if valid.any():
        expected = false_discovery_control(p[valid], method="bh")
        assert np.array_equal(adjusted[valid], np.asarray(expected, dtype=np.float64))


def test_shift_plan_windows_stay_inside_and_form_a_lattice():
    plan = shift_plan(298, 99, min_shift=4)
    assert plan.surrogates == 2 * (int(0.5 * 298) // 4) == 74  # capped by half the window
    offsets = plan.starts_y - plan.starts_x
    assert (offsets % 4 == 0).all() and (offsets != 0).all()
    assert len(set(offsets)) == plan.surrogates
    for start in (*plan.starts_x, *plan.starts_y, plan.observed):
        assert 0 <= start and start + plan.length <= plan.n_states
    with pytest.raises(ParameterError, match="surrogates"):
        shift_plan(30, 99, min_shift=20)
    with pytest.raises(ParameterError, match="surrogates"):
        shift_plan(300, 0)


def test_decorrelation_time_of_noise_and_a_ramp():
    assert decorrelation_time(np.random.default_rng(0).standard_normal(400)) == 1
    # The (biased) autocorrelation of a ramp falls below 1/e only at a fifth of its length.
    assert decorrelation_time(np.arange(100.0)) > 15


def test_the_test_is_symmetric_and_the_direction_flips():
    data = systems.henon_pair(300, 0.6, seed=0)
    a_x, a_y = dense(embed(data[:, 0], 3, 1)), dense(embed(data[:, 1], 3, 1))
    plan = shift_plan(298, 99, min_shift=3)
    forward, backward = dependence_test(a_x, a_y, plan), dependence_test(a_y, a_x, plan)
    assert forward.p_value == pytest.approx(1 / (plan.surrogates + 1))
    # Swapping X and Y mirrors every window (offset o <-> -o): phi and p stay, the index flips.
    assert forward.statistic == pytest.approx(backward.statistic)
    assert forward.p_value == backward.p_value
    assert forward.direction_index == pytest.approx(-backward.direction_index)


def test_a_shift_of_the_whole_pair_changes_nothing_but_a_shift_of_y_destroys_coupling():
    data = systems.henon_pair(400, 0.6, seed=3)
    (p_coupled,) = p_values(data[:, None, :])
    shifted = np.column_stack([data[:200, 0], data[100:300, 1]])
    (p_shifted,) = p_values(shifted[:, None, :])
    assert p_coupled <= 0.02 and p_shifted > 0.05


def test_interval_contains_the_observed_value_and_half_samples_have_no_duplicates():
    chosen = half_samples(298, 50, seed=1)
    for row in chosen:
        assert len(np.unique(row)) == row.size and (np.diff(row) > 0).all()
    data = systems.henon_pair(300, 0.0, seed=4)
    x, y = minmax(data[:, 0]), minmax(data[:, 1])
    m = cross_measures(x, y, delay=1, warn=False)
    xs, ys = embed(x, 3, 1), embed(y, 3, 1)
    iv = asymmetry_interval(xs, ys, c_diff=m.c_diff, t_diff=m.t_diff, resamples=60, seed=0,
                            parameters=m.parameters)
    assert iv.c_diff_low <= m.c_diff <= iv.c_diff_high
    assert iv.t_diff_low <= m.t_diff <= iv.t_diff_high
    assert 0.0 <= iv.c_sign_fraction <= 1.0
    again = asymmetry_interval(xs, ys, c_diff=m.c_diff, t_diff=m.t_diff, resamples=60, seed=0,
                               parameters=m.parameters)
    assert again == iv  # the seed fixes the resamples
    with pytest.raises(ParameterError, match="level"):
        asymmetry_interval(xs, ys, c_diff=0.0, t_diff=0.0, level=1.5)


def test_a_resample_of_every_state_reproduces_the_network_numbers():
    data = systems.logistic_pair(200, 3.7, 4.0, seed=2)
    x, y = minmax(data[:, 0]), minmax(data[:, 1])
    m = cross_measures(x, y, delay=1, warn=False)
    states = [embed(x, 3, 1), embed(y, 3, 1)]
    everything = np.arange(198)[None, :]
    values = resampled_differences(states, [(0, 1)], everything, parameters=m.parameters)
    # The states of min-max normalized signals are already normalized: the same numbers.
    assert values[0, 0, 0] == m.c_diff and values[0, 0, 1] == m.t_diff


def test_interval_rule_and_labels():
    assert interval_kind(0.08, 0.02, 0.1, 0.05) == "y->x"
    assert interval_kind(0.08, -0.01, 0.1, 0.05) == "bidirectional"
    assert interval_kind(-0.03, -0.05, -0.01, 0.05) == "bidirectional"  # below mu
    assert evidence_label(True, "", "bidirectional") == "coupled"
    assert evidence_label(False, "", "conflict") == "not-coupled"


# --- pinned error rates (fixed seeds, binomial margins) ------------------------------------


@pytest.mark.parametrize(
    "name, batch, delay",
    [
        ("white noise", lambda s: systems.white_noise(300, seed=s), 1),
        ("Henon C=0", lambda s: systems.henon_pair(300, 0.0, seed=s), 1),
        ("Lorenz copies", lambda s: systems.lorenz_pair(300, seed=s, transient=20.0), 3),
    ],
)
def test_false_positive_rate_on_uncoupled_pairs(name, batch, delay):
    pairs = 40
    p = p_values(batch(list(range(pairs))), delay=delay)
    assert int((p <= 0.05).sum()) <= bound(pairs), name


def test_power_on_coupled_henon_maps():
    # Target: power >= 0.9 at C = 0.4, N = 500; measured 1.00 on 200 pairs.
    p = p_values(systems.henon_pair(500, 0.4, seed=list(range(20))))
    assert int((p <= 0.05).sum()) >= 17


def test_interval_covers_zero_for_independent_realizations_of_one_process():
    covered = 0
    pairs = 30
    batch = systems.white_noise(300, seed=list(range(pairs)))
    for k in range(pairs):
        x, y = minmax(batch[:, k, 0]), minmax(batch[:, k, 1])
        m = cross_measures(x, y, delay=1, warn=False)
        iv = asymmetry_interval(embed(x, 3, 1), embed(y, 3, 1), c_diff=m.c_diff,
                                t_diff=m.t_diff, resamples=60, seed=k, parameters=m.parameters)
        covered += iv.c_diff_low <= 0 <= iv.c_diff_high
    # Nominal 0.95, but for white noise under min-max the interval is too narrow: measured
    # 0.875 on 40 other pairs (docs/validation/evidence.md, seeds 1000-1039). The bound is that rate
    # minus 3 binomial SE over 30 pairs: it pins today's behaviour, it does not claim validity.
    assert covered >= 20


# --- twin surrogates, resamples=0, the peers' adapters ----------------------------------------


def phi_reference(a_x, a_y):
    """phi of two full recurrence matrices, straight from its definition (pairs i < j)."""
    upper = np.triu_indices(a_x.shape[0], 1)
    x, y = a_x[upper].astype(float), a_y[upper].astype(float)
    return float(np.corrcoef(x, y)[0, 1])


def test_twin_groups_are_identical_neighbourhoods():
    data = systems.henon_pair(200, 0.0, seed=5)
    a = dense(embed(data[:, 1], 3, 1))
    labels = twin_groups(a)
    r = a.astype(bool) | np.eye(a.shape[0], dtype=bool)
    for i in range(0, a.shape[0], 7):
        same = np.flatnonzero((r == r[:, [i]]).all(axis=0))  # columns equal to column i
        assert set(same) == set(np.flatnonzero(labels == labels[i]))
    assert 0 < np.sum(np.bincount(labels)[labels] > 1) < a.shape[0]  # some twins, not all


def test_twin_surrogates_move_to_a_successor_of_the_state_or_of_a_twin():
    a = dense(embed(systems.logistic_pair(150, seed=2)[:, 0], 3, 1))
    labels = twin_groups(a)
    m = a.shape[0]
    plan = twin_plan(a, 20, seed=3)
    assert plan.indices.shape == (20, m) and plan.twins > 0
    jumps = 0
    for row in plan.indices:
        for k, nxt in zip(row[:-1], row[1:], strict=True):
            successor = nxt - 1
            if successor == k:
                continue
            if successor >= 0 and labels[successor] == labels[k]:
                jumps += 1  # moved on from a twin of k
                continue
            # Otherwise only a restart, after k or one of its twins reached the end.
            assert np.any(labels[m - 1] == labels[k]), (k, nxt)
    assert jumps > 0
    again = twin_plan(a, 20, seed=3)
    assert np.array_equal(again.indices, plan.indices)  # the seed fixes the surrogates


def test_twin_test_statistic_matches_the_definition_and_detects_coupling():
    data = systems.henon_pair(300, 0.6, seed=0)
    a_x, a_y = dense(embed(data[:, 0], 3, 1)), dense(embed(data[:, 1], 3, 1))
    result = dependence_test(a_x, a_y, surrogate_plan("twin", a_y, 99, seed=1))
    assert result.statistic == pytest.approx(phi_reference(a_x, a_y), abs=1e-12)
    assert result.surrogates == 99 and result.p_value == pytest.approx(0.01)
    with pytest.raises(ParameterError, match="surrogate_method"):
        surrogate_plan("phase", a_y, 99)


def test_twin_false_positives_on_uncoupled_maps():
    # Measured 0.000-0.100 on 40 pairs per length (seeds 1000-1039, docs/validation/evidence.md);
    # these are other seeds. Twins are not valid for equal-period oscillators (docs): not tested
    # here.
    pairs = 40
    batch = systems.henon_pair(300, 0.0, seed=list(range(pairs)))
    rejected = 0
    for k in range(pairs):
        a_x = dense(embed(batch[:, k, 0], 3, 1))
        a_y = dense(embed(batch[:, k, 1], 3, 1))
        rejected += dependence_test(a_x, a_y, twin_plan(a_y, 99, seed=k)).p_value <= 0.05
    assert rejected <= bound(pairs)


def test_resamples_zero_skips_the_intervals_and_keeps_the_test():
    data = systems.henon_pair(300, 0.6, seed=1)
    signals = [minmax(data[:, 0]), minmax(data[:, 1])]
    full = pairwise_evidence(signals, delay=1, resamples=30)[(0, 1)]
    bare = pairwise_evidence(signals, delay=1, resamples=0)[(0, 1)]
    assert np.isnan([bare.c_diff_low, bare.c_diff_high, bare.t_diff_low, bare.t_diff_high,
                     bare.c_sign_fraction, bare.t_sign_fraction]).all()
    assert (bare.coupling_p, bare.coupled, bare.surrogates, bare.direction) == (
        full.coupling_p, full.coupled, full.surrogates, full.direction)
    assert (bare.c_diff, bare.t_diff) == (full.c_diff, full.t_diff)
    with pytest.raises(ParameterError, match="resamples"):
        pairwise_evidence(signals, delay=1, resamples=-1)


def _bench():
    import importlib.util
    import sys
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_evidence.py"
    spec = importlib.util.spec_from_file_location("bench_evidence", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("bench_evidence", module)  # its dataclasses look themselves up
    spec.loader.exec_module(module)
    return module


def test_peer_adapters_on_a_coupled_and_an_uncoupled_pair():
    pytest.importorskip("pyEDM")
    pytest.importorskip("tigramite")
    bench = _bench()
    coupled = systems.henon_pair(500, 0.6, seed=7)
    uncoupled = systems.henon_pair(500, 0.0, seed=7)
    ccm = bench.ccm_decision(coupled[:, 0], coupled[:, 1])
    assert ccm["coupled"] and ccm["direction"] == "x->y" and ccm["rho_xy"] > ccm["rho_yx"]
    assert not bench.ccm_decision(uncoupled[:, 0], uncoupled[:, 1])["coupled"]
    pcmci = bench.pcmci_decision(coupled[:, 0], coupled[:, 1])
    assert pcmci["coupled"] and pcmci["direction"] in ("x->y", "")
    # ParCorr is linear: on nonlinear maps it can see residual structure, so the uncoupled
    # pair for PCMCI is independent noise (its rate on uncoupled maps is in the benchmark).
    noise = systems.white_noise(500, seed=7)
    assert not bench.pcmci_decision(noise[:, 0], noise[:, 1])["coupled"]
