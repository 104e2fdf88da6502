"""Evidence decided before it is paid for: whether a pair can reach alpha is known from the
window's size, and an untestable pair's intervals are drawn only when asked for."""

from __future__ import annotations

import math

import numpy as np
import pytest

from funcnet.errors import ParameterError
from funcnet.evidence import pairwise_evidence, planned_surrogates, surrogate_plan
from funcnet.evidence.dependence import MIN_WINDOW, decorrelation_time
from funcnet.network import add_evidence, functional_network


def _lattice_k(m: int, k: int, s0: int) -> int:
    """Independent reference: the shift lattice's size, from its definition (offsets +-s0 ...
    +-steps s0 with steps = min(ceil(K/2), floor(M/2) // s0), windows of M - steps s0 >= 20)."""
    steps = min(-(-k // 2), (m // 2) // s0)
    return 0 if steps < 1 or m - steps * s0 < MIN_WINDOW else 2 * steps


@pytest.mark.parametrize("m", [25, 40, 140, 498, 1000])
@pytest.mark.parametrize("s0", [1, 3, 20, 60])
@pytest.mark.parametrize("k", [1, 14, 99, 299])
def test_the_planned_surrogates_are_what_the_plan_holds(m, s0, k):
    planned = planned_surrogates("shift", m, k, min_shift=s0)
    assert planned == _lattice_k(m, k, s0)
    a = np.zeros((m, m), dtype=np.uint8)
    try:
        held = surrogate_plan("shift", a, k, min_shift=s0).surrogates
    except ParameterError:
        held = 0
    assert planned == held
    assert planned_surrogates("twin", m, k) == (k if m >= MIN_WINDOW else 0)


def _signals(n: int, seed: int) -> np.ndarray:
    """Smooth signals (long decorrelation: few shifts) and rough ones (many) side by side."""
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    smooth = [np.sin(2 * np.pi * t / 150 + phase) + 0.05 * rng.standard_normal(n)
              for phase in (0.0, 1.0)]
    rough = [rng.standard_normal(n) for _ in range(2)]
    return np.column_stack([*smooth, *rough])


def test_only_testable_pairs_get_intervals_and_they_are_the_same_numbers():
    data = _signals(400, 0)
    names = ["s1", "s2", "r1", "r2"]
    columns = [data[:, k] for k in range(4)]
    testable = pairwise_evidence(columns, names=names, delay=1, resamples=40, seed=3,
                                 intervals="testable")
    every = pairwise_evidence(columns, names=names, delay=1, resamples=40, seed=3,
                              intervals="all")
    # the reference: which pairs can reach alpha, from K alone (1/(K+1), BH over the pairs)
    k = np.array([every[key].surrogates for key in every], dtype=float)
    least = np.sort(1 / (k + 1))
    m = len(least)
    adjusted = np.minimum.accumulate((least * m / np.arange(1, m + 1))[::-1])[::-1]
    reachable = {1 / (kk + 1): a for kk, a in zip(np.sort(k)[::-1], adjusted, strict=True)}
    blind = {key: not reachable[1 / (every[key].surrogates + 1)] <= 0.05 for key in every}
    assert any(blind.values()) and not all(blind.values())  # both kinds of pair
    for key, one in every.items():
        other = testable[key]
        # the test's numbers never depend on the intervals drawn
        for field in ("coupling_statistic", "coupling_p", "surrogates", "direction_index",
                      "direction_p", "c_diff", "t_diff"):
            assert getattr(one, field) == getattr(other, field) or (
                math.isnan(getattr(one, field)) and math.isnan(getattr(other, field)))
        assert not math.isnan(one.c_diff_low)
        if blind[key]:
            assert math.isnan(other.c_diff_low) and math.isnan(other.t_diff_high)
            assert math.isnan(other.c_sign_fraction)
        else:  # the same resamples: the same interval, bit for bit
            assert (other.c_diff_low, other.c_diff_high, other.t_diff_low,
                    other.t_diff_high) == (one.c_diff_low, one.c_diff_high, one.t_diff_low,
                                           one.t_diff_high)


def test_by_default_only_coupled_pairs_get_intervals_and_they_are_the_same_numbers():
    rng = np.random.default_rng(4)
    x = rng.standard_normal(500)
    y = np.concatenate([[0.0], x[:-1]]) + 0.3 * rng.standard_normal(500)  # coupled to x
    columns = [x, y, rng.standard_normal(500), rng.standard_normal(500)]
    names = ["x", "y", "n1", "n2"]
    default = pairwise_evidence(columns, names=names, delay=1, resamples=30, seed=2)
    every = pairwise_evidence(columns, names=names, delay=1, resamples=30, seed=2,
                              intervals="all")
    coupled = {key for key, e in every.items() if e.coupled}
    assert ("x", "y") in coupled and len(coupled) < len(every)  # both kinds of pair
    for key, one in every.items():
        other = default[key]
        assert (other.coupling_p, other.coupled) == (one.coupling_p, one.coupled)
        if key in coupled:  # the same resamples: the same interval, bit for bit
            assert (other.c_diff_low, other.t_diff_high) == (one.c_diff_low, one.t_diff_high)
        else:
            assert math.isnan(other.c_diff_low) and not math.isnan(one.c_diff_low)


def test_a_network_whose_pairs_are_all_untestable_draws_no_interval_unless_asked():
    data = _signals(300, 1)[:, :2]  # two smooth signals: few shifts, K < 19
    plain = functional_network(data, names=["a", "b"], delay=1, warn=False)
    k = planned_surrogates("shift", 298, 99, min_shift=max(
        decorrelation_time(data[:, 0]), decorrelation_time(data[:, 1]), 3))
    assert 0 < k < 19  # 1/(K+1) > 0.05
    net = add_evidence(plain, data, resamples=30)
    row = net.pairs.iloc[0]
    assert row["evidence"] == "untestable" and row["surrogates"] == k
    assert math.isnan(row["c_diff_low"]) and net.evidence["intervals"] == "coupled"
    asked = add_evidence(plain, data, resamples=30, intervals="all")
    assert asked.pairs.iloc[0]["c_diff_low"] <= row["c_diff"] <= asked.pairs.iloc[0][
        "c_diff_high"]
    # the interval rule reads every pair's interval: it draws them whatever was asked
    ruled = add_evidence(plain, data, resamples=30, edge_rule="interval")
    assert ruled.pairs.iloc[0]["c_diff_low"] == asked.pairs.iloc[0]["c_diff_low"]
    assert ruled.evidence["intervals"] == "all"


def test_a_bad_intervals_option_is_named():
    with pytest.raises(ParameterError, match="intervals"):
        pairwise_evidence([np.arange(50.0), np.arange(50.0) ** 2], intervals="some")


@pytest.mark.parametrize("n", [150, 1200])  # the batched engine's windows, and longer ones
def test_the_tables_own_differences_give_the_intervals_computed_from_scratch(n):
    data = _signals(n, 2)
    names = ["s1", "s2", "r1", "r2"]
    plain = functional_network(data, names=names, delay=1, warn=False)
    net = add_evidence(plain, data, resamples=20, seed=5, intervals="all")
    scaled = (data - data.min(axis=0)) / np.ptp(data, axis=0)  # min-max, as the network
    fresh = pairwise_evidence([scaled[:, k] for k in range(4)], names=names, delay=1,
                              resamples=20, seed=5, intervals="all")
    for row in net.pairs.itertuples():
        one = fresh[(row.x, row.y)]
        assert (one.c_diff, one.t_diff) == (row.c_diff, row.t_diff)
        assert (one.c_diff_low, one.c_diff_high, one.t_diff_low, one.t_diff_high) == (
            row.c_diff_low, row.c_diff_high, row.t_diff_low, row.t_diff_high)
        assert one.coupling_p == row.coupling_p or (
            math.isnan(one.coupling_p) and math.isnan(row.coupling_p))
