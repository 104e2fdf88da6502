"""The asymmetry interval: rate model, properties, calibration on fixed seeds.

The calibration bounds are for a handful of pairs (seeds 0-29, below the benchmark's validation
seeds 2000-2199 and the 5000-5199 the fractions were chosen on); the full table is
benchmarks/bench_interval.py.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from funcnet.core.batch import DIRECT_MAX_STATES
from funcnet.core.embedding import signal_states
from funcnet.core.measures import isrn_measures
from funcnet.core.normalization import normalize
from funcnet.core.recurrence import auto_recurrence, cross_recurrence
from funcnet.errors import ParameterError
from funcnet.evidence import interval as interval_module
from funcnet.evidence.interval import (
    BETA_MAX,
    BETA_MIN,
    FRACTIONS,
    RESAMPLE_MAX_STATES,
    asymmetry_interval,
    asymmetry_intervals,
    half_samples,
    interval_from,
    rate_factor,
    resampled_differences,
    subsamples,
)
from funcnet.parameters import NetworkParameters
from funcnet.validation import systems


def _pair(data: np.ndarray, delay: int = 1) -> tuple[list[np.ndarray], tuple[float, float],
                                                     NetworkParameters]:
    p = NetworkParameters(delay=delay)
    values = normalize(data, "minmax")
    states = [signal_states(values[:, k], parameters=p) for k in (0, 1)]
    m = isrn_measures(auto_recurrence(states[0], parameters=p),
                      auto_recurrence(states[1], parameters=p),
                      cross_recurrence(states[0], states[1], parameters=p))
    return states, (m.c_diff, m.t_diff), p


# ---- the rate model -------------------------------------------------------------------------

@pytest.mark.parametrize("beta", [0.25, 0.5, 0.7, 1.0])
def test_rate_factor_recovers_a_known_rate(beta: float) -> None:
    # Spreads built from the model v(f) = s^2 ((1/f)^(2 beta) - 1) with s = 1: the rate and
    # k = s / sqrt(v(f1)) come back (up to the sampling noise of 20,000 normal values).
    f1, f2 = 0.45, 0.7
    v1, v2 = (1 / f1) ** (2 * beta) - 1, (1 / f2) ** (2 * beta) - 1
    rng = np.random.default_rng(1)
    got, k = rate_factor(rng.normal(0, math.sqrt(v1), 20_000),
                         rng.normal(0, math.sqrt(v2), 20_000), (f1, f2))
    if beta > BETA_MAX:  # faster than the cap: clipped
        assert got == BETA_MAX
        return
    assert got == pytest.approx(beta, abs=0.05)
    assert k == pytest.approx(1 / math.sqrt((1 / f1) ** (2 * got) - 1))
    assert k == pytest.approx(1 / math.sqrt(v1), rel=0.15)


def test_rate_factor_clips_and_degenerate_cases() -> None:
    rng = np.random.default_rng(2)
    same = rng.normal(0, 1, 4000)
    # Equal spreads at both sizes: slower than any rate -> BETA_MIN (the widest interval).
    assert rate_factor(same, same.copy(), (0.5, 0.75))[0] == BETA_MIN
    # A larger size without spread: the fastest rate accepted (the narrowest).
    assert rate_factor(same, np.zeros(10), (0.5, 0.75))[0] == BETA_MAX
    # No spread at all: the standard rate, and nothing to widen.
    assert rate_factor(np.zeros(10), np.zeros(10), (0.5, 0.75)) == (0.5, 1.0)
    with pytest.raises(ParameterError, match="fractions"):
        rate_factor(same, same, (0.75, 0.5))


def test_two_sizes_give_the_geometric_mean_of_both_extrapolations() -> None:
    # The half-width written out from the module notes: beta from the 95 %-quantiles of the
    # absolute deviations (solved here by a dense grid, not by the module's bisection), then
    # sqrt(k1 q1 k2 q2) with k_i = 1 / sqrt((1/f_i)^(2 beta) - 1).
    rng = np.random.default_rng(11)
    f1, f2 = 0.4, 0.75
    small = rng.normal(0, 1.0, (300, 2))
    large = rng.normal(0, 0.45, (300, 2))
    iv = interval_from(0.2, -0.1, small, rate_values=large, fractions=(f1, f2))
    for col, d, low, high, rate in [(0, 0.2, iv.c_diff_low, iv.c_diff_high, iv.c_rate),
                                    (1, -0.1, iv.t_diff_low, iv.t_diff_high, iv.t_rate)]:
        q1, q2 = (float(np.quantile(np.abs(v[:, col] - np.median(v[:, col])), 0.95))
                  for v in (small, large))
        grid = np.linspace(BETA_MIN, BETA_MAX, 200_001)
        model = ((1 / f1) ** (2 * grid) - 1) / ((1 / f2) ** (2 * grid) - 1)
        beta = float(grid[np.argmin(np.abs(model - (q1 / q2) ** 2))])
        assert rate == pytest.approx(beta, abs=1e-4)
        k1, k2 = (((1 / f) ** (2 * beta) - 1) ** -0.5 for f in (f1, f2))
        half = math.sqrt(k1 * q1 * k2 * q2)
        assert low == pytest.approx(d - half, rel=1e-4)
        assert high == pytest.approx(d + half, rel=1e-4)
    assert iv.resamples == 600


def test_one_size_without_spread_still_gives_a_wide_interval() -> None:
    # A geometric mean with a zero factor would give a zero-width interval: the size that has
    # a spread is extrapolated alone.
    rng = np.random.default_rng(5)
    small = rng.normal(0, 1.0, (200, 2))
    constant = np.zeros((200, 2))
    iv = interval_from(0.3, 0.1, small, rate_values=constant, fractions=(0.4, 0.75))
    assert iv.c_diff_high - iv.c_diff_low > 1.0 and iv.t_diff_high - iv.t_diff_low > 1.0
    # NaN resamples: NaN interval and NaN rate, not a made-up rate
    gaps = small.copy()
    gaps[3, 0] = np.nan
    iv = interval_from(0.3, 0.1, gaps, rate_values=small, fractions=(0.4, 0.75))
    assert np.isnan(iv.c_rate) and np.isnan(iv.c_diff_low) and not np.isnan(iv.t_rate)


def test_without_rate_values_k_is_one() -> None:
    # Without rate values: k = 1, the symmetric interval of the half-samples' spread.
    rng = np.random.default_rng(3)
    values = rng.normal(0, 1, (400, 2))
    plain = interval_from(0.1, -0.2, values)
    assert plain.c_rate == 0.5 and plain.resamples == 400
    half = np.quantile(np.abs(values[:, 0] - np.median(values[:, 0])), 0.95)
    assert plain.c_diff_low == pytest.approx(0.1 - half)
    assert plain.c_diff_high == pytest.approx(0.1 + half)
    with pytest.raises(ParameterError, match="fractions"):
        interval_from(0.1, 0.0, values, rate_values=values)


# ---- resampling ---------------------------------------------------------------------------

def _previous_half_samples(n_states: int, resamples: int, seed: int) -> np.ndarray:
    # The half-samples of the first version, written out: the same seed must keep the draws.
    length = math.ceil(math.sqrt(n_states))
    n_blocks = n_states // length
    rng = np.random.default_rng(seed)
    phase = rng.integers(0, n_states - n_blocks * length + 1, size=resamples)
    blocks = np.sort(np.argsort(rng.random((resamples, n_blocks)), axis=1)[:, :n_blocks // 2],
                     axis=1)
    starts = phase[:, None] + blocks * length
    return (starts[:, :, None] + np.arange(length)).reshape(resamples, -1)


def test_subsamples_half_is_half_samples_and_blocks_are_distinct() -> None:
    for n_states in (138, 298, 998):
        assert np.array_equal(half_samples(n_states, 7, seed=4),
                              _previous_half_samples(n_states, 7, 4))
    assert np.array_equal(subsamples(300, 7, 0.5, seed=4), half_samples(300, 7, seed=4))
    kept = subsamples(300, 5, FRACTIONS[1], seed=4)
    length = math.ceil(math.sqrt(300))
    assert kept.shape == (5, int(FRACTIONS[1] * (300 // length)) * length)
    smaller = subsamples(300, 5, FRACTIONS[0], seed=4)
    assert smaller.shape == (5, int(FRACTIONS[0] * (300 // length)) * length)
    assert 0 < FRACTIONS[0] < FRACTIONS[1] < 1
    for row in kept:  # without replacement, inside the window
        assert len(np.unique(row)) == row.size and row.min() >= 0 and row.max() < 300
    with pytest.raises(ParameterError, match="fraction"):
        subsamples(300, 5, 1.0)
    with pytest.raises(ParameterError, match="block"):
        subsamples(300, 5, 0.01)


def test_properties_contain_observed_sign_fraction_and_determinism() -> None:
    for seed, make in [(0, lambda: systems.white_noise(160, seed=0)),
                       (1, lambda: systems.logistic_pair(160, 3.7, 4.0, seed=1)),
                       (2, lambda: systems.henon_pair(160, 0.4, seed=2))]:
        states, (c, t), p = _pair(make())
        iv = asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, resamples=30,
                                seed=seed)
        assert iv.c_diff_low <= c <= iv.c_diff_high
        assert iv.t_diff_low <= t <= iv.t_diff_high
        assert 0.0 <= iv.c_sign_fraction <= 1.0 and 0.0 <= iv.t_sign_fraction <= 1.0
        assert BETA_MIN <= iv.c_rate <= BETA_MAX and BETA_MIN <= iv.t_rate <= BETA_MAX
        assert iv.resamples == 30
        again = asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, resamples=30,
                                   seed=seed)
        assert again == iv


def test_network_intervals_are_the_single_pair_intervals() -> None:
    # One set of resamples for three signals gives each pair what the pair alone gets.
    data = np.column_stack([systems.white_noise(150, seed=5), systems.henon_pair(150, seed=6)])
    p = NetworkParameters(delay=1)
    values = normalize(data, "minmax")
    states = [signal_states(values[:, k], parameters=p) for k in range(4)]
    pairs = [(0, 1), (1, 3), (0, 2)]
    observed = [(0.01 * k, -0.01 * k) for k in range(3)]
    many = asymmetry_intervals(states, pairs, observed, parameters=p, resamples=12, seed=7)
    for (i, j), (c, t), iv in zip(pairs, observed, many, strict=True):
        one = asymmetry_interval(states[i], states[j], c_diff=c, t_diff=t, parameters=p,
                                 resamples=12, seed=7)
        assert one == iv


def test_one_resample_falls_back_and_bad_arguments_raise() -> None:
    states, (c, t), p = _pair(systems.white_noise(120, seed=8))
    iv = asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, resamples=1)
    assert iv.resamples == 1 and iv.c_rate == 0.5
    assert iv.c_diff_low == iv.c_diff_high == c
    with pytest.raises(ParameterError, match="resamples"):
        asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, resamples=0)
    with pytest.raises(ParameterError, match="level"):
        asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, level=1.0)
    with pytest.raises(ParameterError, match="y_states"):
        asymmetry_interval(states[0], states[1][:-1], c_diff=c, t_diff=t)


def test_resampled_differences_renormalize_the_kept_states() -> None:
    # A resample that keeps every state reproduces the observed differences (the states are
    # min-max normalized already, so normalizing them again changes nothing).
    states, (c, t), p = _pair(systems.henon_pair(140, seed=9))
    every = np.arange(states[0].shape[0])[None, :]
    got = resampled_differences(states, [(0, 1)], every, parameters=p)[0, 0]
    assert got == pytest.approx([c, t], abs=1e-12)


# ---- calibration on a fixed small seed set ---------------------------------------------------

Make = Callable[[int, list[int]], np.ndarray]


def _coverage(make: Make, n: int, seeds: range, target: tuple[float, float], delay: int = 1,
              resamples: int = 40) -> tuple[float, float, list[float]]:
    hits_c, hits_t, widths = [], [], []
    batch = make(n, list(seeds))
    for k in range(len(seeds)):
        states, (c, t), p = _pair(batch[:, k], delay)
        iv = asymmetry_interval(*states, c_diff=c, t_diff=t, parameters=p, resamples=resamples,
                                seed=k)
        hits_c.append(iv.c_diff_low <= target[0] <= iv.c_diff_high)
        hits_t.append(iv.t_diff_low <= target[1] <= iv.t_diff_high)
        widths.append(iv.c_diff_high - iv.c_diff_low)
    return float(np.mean(hits_c)), float(np.mean(hits_t)), widths


@pytest.mark.parametrize(("make", "delay"), [
    (lambda n, s: systems.white_noise(n, seed=s), 1),
    (lambda n, s: systems.henon_pair(n, 0.0, seed=s), 1),
    (lambda n, s: systems.lorenz_pair(n, seed=s), 3),
], ids=["white-noise", "henon", "lorenz"])
def test_covers_zero_for_independent_copies(make: Make, delay: int) -> None:
    # 30 pairs at 140 samples (a noise, a map, a flow), against the truth 0 by symmetry; the
    # benchmark measures 0.90-0.99 on 200 pairs (docs): a bound 3 binomial SEs below 0.92
    # for 30 pairs is 0.77.
    cover_c, cover_t, _ = _coverage(make, 140, range(30), (0.0, 0.0), delay=delay)
    assert cover_c >= 0.75 and cover_t >= 0.75


def test_covers_the_mean_of_the_logistic_pair() -> None:
    # Mean C_diff / T_diff of 200 realizations (seeds 200-399), covered by the intervals of
    # 30 other realizations (seeds 0-29).
    make = lambda n, s: systems.logistic_pair(n, 3.7, 4.0, seed=s)  # noqa: E731
    batch = make(140, list(range(200, 400)))
    diffs = np.array([_pair(batch[:, k])[1] for k in range(200)])
    mean = (float(diffs[:, 0].mean()), float(diffs[:, 1].mean()))
    assert 0.2 < mean[0] < 0.35  # a real asymmetry without coupling (benchmark: 0.28)
    cover_c, cover_t, _ = _coverage(make, 140, range(30), mean)
    assert cover_c >= 0.75 and cover_t >= 0.75


def test_rate_narrows_the_interval_where_maps_converge_fast() -> None:
    # Henon copies at 300 samples: the spread of C_diff over realizations falls about like
    # 1/N there (docs), so the estimated rate must give narrower intervals than the plain
    # half-sample spread (k = 1) in most pairs, and still cover 0.
    make = lambda n, s: systems.henon_pair(n, 0.0, seed=s)  # noqa: E731
    cover_c, _, widths = _coverage(make, 300, range(20), (0.0, 0.0))
    batch = make(300, list(range(20)))
    plain = []
    for k in range(20):
        states, (c, t), p = _pair(batch[:, k])
        small = half_samples(states[0].shape[0], 20, seed=k)
        values = resampled_differences(states, [(0, 1)], small, parameters=p)[0]
        iv = interval_from(c, t, values)
        plain.append(iv.c_diff_high - iv.c_diff_low)
    assert np.median(widths) < np.median(plain)
    assert cover_c >= 0.75


def _one_resample_at_a_time(states: list[np.ndarray], pairs: list[tuple[int, int]],
                            chosen: np.ndarray, p: NetworkParameters) -> np.ndarray:
    """The reference: each resample's kept states normalized again per channel, thresholded and
    measured one pair at a time by the per-window path."""
    out = np.empty((len(pairs), len(chosen), 2))
    rates = p.rr if isinstance(p.rr, tuple) else (p.rr,) * len(states)
    for r, kept in enumerate(chosen):
        subsets = []
        for s in states:
            sub = s[kept].copy()
            if p.normalize is not None:
                for c in range(0, sub.shape[1], p.dim):
                    block = sub[:, c:c + p.dim]
                    low, span = ((block.min(), block.max() - block.min()) if
                                 p.normalize == "minmax" else (block.mean(), block.std()))
                    sub[:, c:c + p.dim] = (block - low) / span if span > 0 else block
            subsets.append(sub)
        for k, (i, j) in enumerate(pairs):
            m = isrn_measures(auto_recurrence(subsets[i], rr=rates[i], parameters=p),
                              auto_recurrence(subsets[j], rr=rates[j], parameters=p),
                              cross_recurrence(subsets[i], subsets[j], cr=p.cr, parameters=p))
            out[k, r] = m.c_diff, m.t_diff
    return out


@pytest.mark.parametrize("changes", [
    {}, {"metric": "supremum"}, {"metric": "manhattan"},
    {"rule": "pyunicorn", "metric": "supremum"}, {"theiler": 3}, {"normalize": "zscore"},
    {"rr": (0.05, 0.1, 0.08, 0.03)}, {"dim": 2, "delay": 3}, {"dim": 4, "delay": 2},
    {"normalize": None},
], ids=lambda c: ",".join(f"{k}={v}" for k, v in c.items()) or "defaults")
def test_all_resamples_in_one_pass_are_one_at_a_time_bit_for_bit(changes) -> None:
    # resampled_differences takes these through the batched engine's kernel
    p = NetworkParameters().replace(**changes)
    rng = np.random.default_rng(4)
    n = 260
    raw = np.column_stack([np.cumsum(rng.standard_normal(n)), rng.standard_normal(n),
                           np.sin(np.arange(n) / 7) + 0.1 * rng.standard_normal(n),
                           np.round(rng.standard_normal(n), 1)])  # ties
    values = raw if p.normalize is None else normalize(raw, p.normalize)
    states = [signal_states(values[:, k], parameters=p) for k in range(4)]
    pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    for fraction in (0.4, 0.75):
        chosen = subsamples(states[0].shape[0], 6, fraction, seed=2)
        got = resampled_differences(states, pairs, chosen, parameters=p)
        expected = _one_resample_at_a_time(states, pairs, chosen, p)
        assert np.array_equal(got.view(np.int64), expected.view(np.int64))


def test_resamples_of_some_pairs_keep_each_signal_with_its_rate() -> None:
    # pairs that leave signals out (1 here), with a rate per signal: the same numbers as one
    # resample and one pair at a time
    p = NetworkParameters(rr=(0.05, 0.1, 0.08, 0.03), delay=2)
    rng = np.random.default_rng(8)
    raw = np.column_stack([np.cumsum(rng.standard_normal(300)) for _ in range(4)])
    values = normalize(raw, p.normalize)
    states = [signal_states(values[:, k], parameters=p) for k in range(4)]
    pairs = [(0, 2), (2, 3), (0, 3)]
    chosen = subsamples(states[0].shape[0], 3, 0.4, seed=6)
    got = resampled_differences(states, pairs, chosen, parameters=p)
    expected = _one_resample_at_a_time(states, pairs, chosen, p)
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))


def test_multichannel_nodes_in_resamples_match_one_at_a_time() -> None:
    # nodes of two channels (states of 2 * dim coordinates): the same numbers
    p = NetworkParameters(delay=2)
    rng = np.random.default_rng(5)
    raw = normalize(rng.standard_normal((200, 4)).cumsum(axis=0), "minmax")
    states = [signal_states(raw[:, 2 * k:2 * k + 2], parameters=p) for k in range(2)]
    chosen = subsamples(states[0].shape[0], 4, 0.4, seed=1)
    got = resampled_differences(states, [(0, 1)], chosen, parameters=p)
    expected = _one_resample_at_a_time(states, [(0, 1)], chosen, p)
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))


def test_resamples_above_the_window_limit_go_through_the_kernel_bit_for_bit(monkeypatch) -> None:
    # Resamples of more states than the batched limit of plain windows (DIRECT_MAX_STATES),
    # up to RESAMPLE_MAX_STATES: the batched kernel, never the per-resample path, and the
    # numbers of one resample and one pair at a time.
    p = NetworkParameters()
    rng = np.random.default_rng(11)
    n = 2600
    t = np.arange(n)
    raw = np.column_stack([np.sin(t / 40) + 0.05 * rng.standard_normal(n),
                           np.cumsum(rng.standard_normal(n)),
                           np.sin(t / 40 + 0.3) ** 3 + 0.2 * rng.standard_normal(n)])
    values = normalize(raw, p.normalize)
    states = [signal_states(values[:, k], parameters=p) for k in range(3)]
    pairs = [(0, 1), (0, 2), (1, 2)]
    chosen = subsamples(states[0].shape[0], 2, 0.4, seed=3)
    assert DIRECT_MAX_STATES < chosen.shape[1] <= RESAMPLE_MAX_STATES
    expected = _one_resample_at_a_time(states, pairs, chosen, p)

    def no_fill(*args: object) -> None:
        raise AssertionError("the per-resample path was taken")

    monkeypatch.setattr(interval_module, "_fill", no_fill)
    got = resampled_differences(states, pairs, chosen, parameters=p)
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))
