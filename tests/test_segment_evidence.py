"""The coupling test of a long segment on thinned states: its arithmetic, its bound, and a
robot recording cut into parts whose coupled pairs it finds where a part alone cannot."""

from __future__ import annotations

import dataclasses
import math
import tracemalloc

import numpy as np
import pandas as pd
import pytest

from funcnet.evidence.dependence import dependence_test, shift_plan
from funcnet.evidence.pairs import pairwise_evidence
from funcnet.evidence.reading import untestable
from funcnet.evidence.segment import (
    BYTES_PER_KEPT_CELL,
    BYTES_PER_SAMPLE,
    segment_test_bytes,
    segment_tests,
    thinning,
)
from funcnet.inspection import inspect_robot, robot as robot_module
from funcnet.parameters import EvidenceSettings, NetworkParameters
from funcnet.report.robot_summary import evidence_sentence
from funcnet.robot.recording import Recording, SignalInfo

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

DELAY = 5
PERIOD = 0.004


def _ar1(n: int, rng: np.random.Generator, phi: float = 0.95) -> np.ndarray:
    out = np.empty(n)
    out[0] = rng.standard_normal()
    noise = rng.standard_normal(n)
    for t in range(1, n):
        out[t] = phi * out[t - 1] + noise[t]
    return out


def _two_axes(n: int = 4800, seed: int = 3) -> Recording:
    """Two axes at 250 Hz: each axis's AP follows its RP (coupled), the axes independent."""
    rng = np.random.default_rng(seed)
    columns = {}
    for axis in (1, 2):
        rp = _ar1(n, rng)
        columns[f"A{axis}.RP"] = rp
        columns[f"A{axis}.AP"] = np.roll(rp, 2) + 0.3 * rng.standard_normal(n)
    data = pd.DataFrame(columns, index=pd.Index(np.arange(n) * PERIOD, name="time"))
    info = {c: SignalInfo(c, None, None, PERIOD) for c in columns}
    return Recording(data, {}, info, sample_period=PERIOD)


@pytest.mark.parametrize("n_states, bound", [(1, 1500), (1500, 1500), (1501, 1500),
                                             (5306, 1500), (899_980, 1500), (999, 7)])
def test_thinning_keeps_at_most_the_bound_with_the_least_stride(n_states, bound):
    step = thinning(n_states, bound)
    kept = len(range(0, n_states, step))
    assert kept <= bound
    # one less would keep more than the bound (or there is nothing to thin)
    assert step == 1 or len(range(0, n_states, step - 1)) > bound


def test_the_memory_bound_is_its_arithmetic_and_holds_what_the_test_allocates():
    kept = 1500
    expected = (30 * kept * kept + 30 * (kept * kept // 2 // 5) * 2
                + kept * kept * BYTES_PER_KEPT_CELL + 5326 * BYTES_PER_SAMPLE)
    assert segment_test_bytes(30, 5326) == expected
    # past the bound of kept states, only one signal's whole-segment arrays grow
    assert segment_test_bytes(24, 2_000_000) - segment_test_bytes(24, 1_000_000) == \
        1_000_000 * BYTES_PER_SAMPLE
    rng = np.random.default_rng(0)
    segment_tests([rng.standard_normal(2000) for _ in range(2)], names=["a", "b"])  # compiled
    for n in (40_000, 160_000):
        signals = [rng.standard_normal(n) for _ in range(4)]
        tracemalloc.start()
        try:
            segment_tests(signals, names=list("abcd"), max_states=600, max_surrogates=19)
            _, peak = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
        assert peak <= segment_test_bytes(4, n, max_states=600)


def test_thinned_test_is_the_plain_test_on_every_dth_state():
    rng = np.random.default_rng(1)
    x = _ar1(3000, rng)
    y = np.roll(x, 1) + 0.5 * rng.standard_normal(3000)
    p = NetworkParameters(delay=DELAY)
    tests, step = segment_tests([x, y], names=["x", "y"], parameters=p, max_states=700,
                                surrogates=40)
    assert step == 5
    from funcnet.core.embedding import signal_states
    from funcnet.core.recurrence import auto_recurrence
    from funcnet.evidence.dependence import decorrelation_time
    dense = [auto_recurrence(signal_states(s, parameters=p)[::step], rr=0.05,
                             parameters=p).to_dense().astype(np.uint8) for s in (x, y)]
    s0 = math.ceil(max(decorrelation_time(x), decorrelation_time(y), 2 * DELAY + 1) / step)
    reference = dependence_test(dense[0], dense[1], shift_plan(dense[0].shape[0], 40,
                                                                min_shift=s0))
    found = tests[("x", "y")]
    assert (found.statistic, found.p_value, found.surrogates) == (
        reference.statistic, reference.p_value, reference.surrogates)


def test_given_tests_are_read_as_the_own_ones():
    """pairwise_evidence with the tests it would run given gives the same evidence."""
    rng = np.random.default_rng(2)
    signals = [_ar1(600, rng, 0.5) for _ in range(3)]
    own = pairwise_evidence(signals, names=list("abc"), delay=1, resamples=0)
    tests, step = segment_tests(signals, names=list("abc"),
                                parameters=NetworkParameters(delay=1))
    assert step == 1
    given = pairwise_evidence(signals, names=list("abc"), delay=1, resamples=0, tests=tests)
    assert list(given) == list(own)
    pd.testing.assert_frame_equal(pd.DataFrame([dataclasses.asdict(e) for e in given.values()]),
                                  pd.DataFrame([dataclasses.asdict(e) for e in own.values()]))


def test_a_long_segment_in_parts_finds_its_coupled_pairs_and_not_the_others(monkeypatch):
    recording = _two_axes()
    monkeypatch.setattr(robot_module, "ROBOT_MAX_STATES", 300)
    found = inspect_robot(recording, backlash=False, delay=DELAY,
                          evidence_options=EvidenceSettings(resamples=50))
    assert len(found.windows) == robot_module.ROBOT_MAX_WINDOWS
    assert found.windows[0].label.startswith("part 1 of 16:")
    # a part alone: K = 2 floor(150 / s0), too few to reach alpha whatever the data
    s0 = 2 * DELAY + 1
    part_k = shift_plan(300, 10**4, min_shift=max(s0, 19)).surrogates
    assert untestable([part_k] * 6, 0.05).all()
    assert "coupling test of each part is its whole segment's" in found.windows_note
    for label, pairs in found.pairs.items():
        by_pair = {(x, y): row for x, y, row in zip(pairs["x"], pairs["y"],
                                                    pairs.itertuples(), strict=True)}
        assert set(pairs["surrogates"]) == {120}, label  # K asked for 6 pairs: 119
        for pair, row in by_pair.items():
            within = pair[0][:2] == pair[1][:2]
            if within:  # each axis's AP follows its RP: the smallest p-value, adjusted
                # the smallest p-value 1 / 121, adjusted over 6 pairs with 2 at it
                assert row.coupled and row.coupling_p == pytest.approx(3 / 121), (label, pair)
                assert row.evidence.startswith("coupled")
            else:
                assert not row.coupled and row.coupling_p >= 0.15, (label, pair)
            # the parts draw no interval
            assert np.isnan(row.c_diff_low)


def test_a_node_constant_in_one_part_keeps_the_pairs_of_the_others(monkeypatch):
    # A1.AP constant through part 1 only: part 1 leaves it out, part 2 keeps it. The segment's
    # test must key each pair as every part does (the robot's order), not by first appearance
    # (which would put A1.AP after A2.AP and key its pairs backwards).
    recording = _two_axes()
    data = recording.data.copy()
    data.iloc[:300, data.columns.get_loc("A1.AP")] = 0.0
    recording = dataclasses.replace(recording, data=data)
    monkeypatch.setattr(robot_module, "ROBOT_MAX_STATES", 300)
    found = inspect_robot(recording, backlash=False, delay=DELAY,
                          evidence_options=EvidenceSettings(resamples=50))
    assert not found.failures
    first, second = list(found.pairs.values())[:2]
    assert "A1.AP" not in set(first["x"]) | set(first["y"])
    assert len(first) == 3 and len(second) == 6
    assert "coupling test of each part is its whole segment's" in found.windows_note
    # the other axis's coupled pair is read from the segment's test in both parts
    for pairs in (first, second):
        row = pairs[(pairs["x"] == "A2.RP") & (pairs["y"] == "A2.AP")].iloc[0]
        assert row.coupled and set(pairs["surrogates"]) == {120}
    # a part computes no interval: its page sentence points to no option that would draw one
    assert found.networks[next(iter(found.pairs))].evidence["resamples"] == 0
    assert "--intervals all" in evidence_sentence(second)
    assert "--intervals all" not in evidence_sentence(second, intervals=False)


def _symmetric(rng: np.random.Generator, m: int, rate: float) -> np.ndarray:
    upper = np.triu((rng.random((m, m)) < rate).astype(np.uint8), 1)
    return upper + upper.T


@pytest.mark.parametrize("theiler", [0, 4])
def test_a_signal_read_through_its_complement_gives_the_same_counts(theiler):
    from funcnet.evidence._kernels import _flipped_windows, _windows
    from funcnet.evidence.dependence import recurrent_pairs
    from funcnet.evidence.segment import _complement

    rng = np.random.default_rng(3)
    plan = shift_plan(300, 30, min_shift=3)
    starts_x = np.concatenate([[plan.observed], plan.starts_x]).astype(np.int64)
    starts_y = np.concatenate([[plan.observed], plan.starts_y]).astype(np.int64)
    for rate_x, rate_y in [(0.05, 0.05), (0.95, 0.05), (0.05, 0.9), (0.95, 0.9)]:
        a_x, a_y = _symmetric(rng, 300, rate_x), _symmetric(rng, 300, rate_y)
        plain = _windows(a_y, recurrent_pairs(a_x), recurrent_pairs(a_y), starts_x, starts_y,
                         plan.length, theiler)
        flip_x, flip_y = rate_x > 0.5, rate_y > 0.5
        e_x = _complement(a_x, theiler) if flip_x else a_x
        e_y = _complement(a_y, theiler) if flip_y else a_y
        flipped = _flipped_windows(e_y, recurrent_pairs(e_x), recurrent_pairs(e_y), starts_x,
                                   starts_y, plan.length, theiler, flip_x, flip_y)
        assert np.array_equal(plain, flipped)  # bit for bit: the same integer counts


def test_a_set_point_at_rest_is_tested_as_the_plain_test_reads_it():
    # a set-point that rests but for one move: its thinned states tie at 0 on most pairs, so
    # the segment's test reads it through its complement; the result is the plain test's
    import warnings

    from funcnet.core.embedding import signal_states
    from funcnet.core.recurrence import auto_recurrence
    from funcnet.evidence.dependence import decorrelation_time
    from funcnet.evidence.segment import _mostly_recurrent

    rng = np.random.default_rng(2)
    t = np.arange(3000)
    x = np.where((t >= 1400) & (t < 1700), np.sin(np.pi * (t - 1400) / 300), 0.0)  # out, back
    y = np.roll(x, 2) + 0.05 * rng.standard_normal(3000)
    p = NetworkParameters(delay=DELAY)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tests, step = segment_tests([x, y], names=["x", "y"], parameters=p, max_states=700,
                                    surrogates=40)
        dense = [auto_recurrence(signal_states(s, parameters=p)[::step], rr=0.05,
                                 parameters=p).to_dense().astype(np.uint8) for s in (x, y)]
    assert _mostly_recurrent(dense[0], 0) and not _mostly_recurrent(dense[1], 0)
    s0 = math.ceil(max(decorrelation_time(x), decorrelation_time(y), 2 * DELAY + 1) / step)
    reference = dependence_test(dense[0], dense[1], shift_plan(dense[0].shape[0], 40,
                                                                min_shift=s0))
    found = tests[("x", "y")]
    assert (found.statistic, found.p_value, found.direction_index, found.surrogates) == (
        reference.statistic, reference.p_value, reference.direction_index,
        reference.surrogates)
    assert np.array_equal(found.null_statistics, reference.null_statistics)
