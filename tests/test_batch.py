"""The batched engine gives the per-window path's numbers, bit for bit, and the pipeline's
networks and warnings through it are those of the per-window path."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pandas as pd
import pytest

import funcnet.core.batch
import funcnet.pipeline
from funcnet.core import _batch_kernels
from funcnet.core.batch import DIRECT_MAX_STATES, RESULT_FIELDS, BatchPairs, applies, batch_pairs
from funcnet.errors import FuncnetWarning, ParameterError, SignalError
from funcnet.network import functional_network
from funcnet.network.schema import RESULT_COLUMNS
from funcnet.parameters import NetworkParameters
from funcnet.pipeline import window_networks
from funcnet.robot.recording import Recording, SignalInfo
from funcnet.robot.windows import Window


def _network_pairs(window: np.ndarray, names: list[str], p: NetworkParameters) -> pd.DataFrame:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return functional_network(window, names=names, parameters=p).pairs


def _random_window(rng: np.random.Generator, n_samples: int, n_signals: int) -> np.ndarray:
    """Signals of different character; some quantized (ties), some staircases."""
    t = np.arange(n_samples)
    columns = []
    for _ in range(n_signals):
        kind = rng.integers(0, 5)
        if kind == 0:
            column = rng.random(n_samples)
        elif kind == 1:
            column = np.sin(rng.uniform(0.02, 0.3) * t + rng.uniform(0, 6))
            column += 0.05 * rng.normal(size=n_samples)
        elif kind == 2:  # coarse quantization: many tied distances
            column = np.round(rng.random(n_samples) * rng.integers(2, 6))
        elif kind == 3:  # a staircase (every value held for 2 samples)
            column = np.repeat(np.cumsum(rng.normal(size=n_samples // 2 + 1)), 2)[:n_samples]
        else:
            column = np.round(np.cumsum(rng.normal(size=n_samples)) * 4) / 4
        if np.ptp(column) == 0:
            column[0] += 1.0
        columns.append(column * rng.uniform(0.1, 100) + rng.uniform(-50, 50))
    return np.column_stack(columns)


def _assert_identical(result: BatchPairs, w: int, expected: pd.DataFrame) -> None:
    for q in range(len(result.pairs)):
        for name in RESULT_COLUMNS:
            got, want = result[name][w, q], expected[name].iloc[q]
            assert got == want, (w, q, name, got, want)
            if isinstance(want, float):  # the same bits (0.0 and -0.0 compare equal)
                assert np.float64(got).tobytes() == np.float64(want).tobytes(), (w, q, name)
    assert list(zip(expected["x"], expected["y"], strict=True)) == list(result.pairs)


CASES: list[dict[str, Any]] = [
    {"metric": "euclidean", "rule": "funcnet", "theiler": 0, "normalize": "minmax"},
    {"metric": "supremum", "rule": "pyunicorn", "theiler": 0, "normalize": "minmax"},
    {"metric": "euclidean", "rule": "pyunicorn", "theiler": 0, "normalize": "zscore"},
    {"metric": "manhattan", "rule": "funcnet", "theiler": 3, "normalize": "zscore"},
    {"metric": "supremum", "rule": "funcnet", "theiler": 7, "normalize": None},
    {"metric": "euclidean", "rule": "funcnet", "theiler": 1, "normalize": "minmax", "rr": 0.1,
     "cr": 0.02, "dim": 2, "delay": 3},
    {"metric": "euclidean", "rule": "pyunicorn", "theiler": 0, "normalize": None, "rr": 0.03,
     "cr": 0.08, "dim": 4, "delay": 5},
    {"metric": "chebyshev", "rule": "funcnet", "theiler": 2, "normalize": "minmax", "rr": 0.07},
]


def test_the_result_fields_are_the_pairs_tables() -> None:
    assert RESULT_FIELDS == RESULT_COLUMNS


@pytest.mark.parametrize("case", range(len(CASES)))
def test_random_windows_of_random_lengths(case: int) -> None:
    p = NetworkParameters(**CASES[case])
    rng = np.random.default_rng(100 + case)
    n_signals = int(rng.integers(2, 6))
    names = [f"s{i}" for i in range(n_signals)]
    windows = [_random_window(rng, int(rng.integers(45, 260)), n_signals) for _ in range(10)]
    result = batch_pairs(windows, names=names, parameters=p)
    assert len(result) == len(windows)
    for w, window in enumerate(windows):
        _assert_identical(result, w, _network_pairs(window, names, p))


@pytest.mark.parametrize("direct_pairs", [0, 10**12])
def test_sampled_bracket_and_direct_selection(
    direct_pairs: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(_batch_kernels, "DIRECT_PAIRS", direct_pairs)
    for case in (0, 1, 3):
        p = NetworkParameters(**CASES[case])
        rng = np.random.default_rng(200 + case)
        windows = [_random_window(rng, int(rng.integers(40, 200)), 3) for _ in range(5)]
        result = batch_pairs(windows, parameters=p)
        for w, window in enumerate(windows):
            _assert_identical(result, w, _network_pairs(window, ["0", "1", "2"], p))


def test_per_signal_rates_and_measures_of_a_window() -> None:
    from funcnet.core.measures import pairwise_cross_measures
    from funcnet.core.normalization import normalize

    p = NetworkParameters(rr=(0.05, 0.2, 0.01), cr=0.1)
    rng = np.random.default_rng(4)
    stack = np.stack([_random_window(rng, 140, 3) for _ in range(4)])
    result = batch_pairs(stack, names=["a", "b", "c"], parameters=p)
    for w in range(4):
        _assert_identical(result, w, _network_pairs(stack[w], ["a", "b", "c"], p))
        single = pairwise_cross_measures(normalize(stack[w]), names=["a", "b", "c"],
                                         parameters=p, warn=False)
        assert result.measures(w) == single
    from_offsets = batch_pairs(stack.reshape(-1, 3), np.arange(5) * 140, names=["a", "b", "c"],
                               parameters=p)
    for name in RESULT_FIELDS:
        assert (from_offsets[name] == result[name]).all()


def test_degenerate_blocks_constant_signals_and_reasons() -> None:
    rng = np.random.default_rng(3)
    two_values = np.column_stack([np.tile([0.0, 1.0], 40), rng.random(80), rng.random(80)])
    constant = np.column_stack([np.full(80, 2.5), rng.random(80), np.round(rng.random(80))])
    for rule in ("funcnet", "pyunicorn"):
        p = NetworkParameters(rule=rule, normalize=None)
        result = batch_pairs([two_values, constant], names=["a", "b", "c"], parameters=p)
        for w, window in enumerate([two_values, constant]):
            _assert_identical(result, w, _network_pairs(window, ["a", "b", "c"], p))
        assert result["degenerate"].any(axis=1).all()
        assert "signal a: constant" in result["degenerate_reason"][1, 0]


def test_long_windows_and_explicit_thresholds_take_the_per_window_path(
    monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(funcnet.core.batch, "DIRECT_MAX_STATES", 100)
    rng = np.random.default_rng(11)
    windows = [_random_window(rng, n, 3) for n in (90, 150, 260)]
    for p in (NetworkParameters(rule="pyunicorn"), NetworkParameters(eps=(0.2, None))):
        result = batch_pairs(windows, parameters=p)
        for w, window in enumerate(windows):
            _assert_identical(result, w, _network_pairs(window, ["0", "1", "2"], p))
    assert applies(120, NetworkParameters()) and not applies(150, NetworkParameters())


def test_huge_amplitudes_are_the_per_window_paths_error() -> None:
    window = np.column_stack([np.linspace(0, 1e300, 100), np.linspace(1, 0, 100)])
    with pytest.raises(SignalError, match="window 0: .*too large"):
        batch_pairs([window], normalize=None)


def test_errors_name_the_window_and_the_signal() -> None:
    rng = np.random.default_rng(0)
    windows = [rng.random((60, 2)), rng.random((60, 2))]
    windows[1][:, 1] = 4.0
    with pytest.raises(SignalError, match="window 1: signal 'b' is constant"):
        batch_pairs(windows, names=["a", "b"])
    windows[1][:, 1] = rng.random(60)
    windows[1][5, 0] = np.nan
    with pytest.raises(SignalError, match="window 1: signal 'a' holds NaN"):
        batch_pairs(windows, names=["a", "b"])
    with pytest.raises(SignalError, match="window 0: .*7"):
        batch_pairs([rng.random((26, 2))])
    with pytest.raises(ParameterError, match="theiler"):
        batch_pairs([rng.random((60, 2))], theiler=39)
    with pytest.raises(ParameterError, match="rr"):
        batch_pairs([rng.random((60, 2))], rr=1.5)
    with pytest.raises(ParameterError, match="mu"):
        batch_pairs([rng.random((60, 2))], mu=0.1)
    with pytest.raises(ParameterError, match="offsets"):
        batch_pairs(rng.random((60, 2)), [0, 70])
    with pytest.raises(ParameterError, match="rr"):
        batch_pairs([rng.random((60, 2))], rr=(0.1, 0.2, 0.3))


def test_pairwise_sum_is_numpys() -> None:
    rng = np.random.default_rng(5)
    for n in [*range(1, 300), 1000, 4097, 9000]:
        a = rng.random(n) ** 3
        assert _batch_kernels._mean(a) == a.mean()


def test_selection_with_ties() -> None:
    rng = np.random.default_rng(9)
    for _ in range(200):
        n = int(rng.integers(1, 400))
        a = np.round(rng.random(n) * rng.integers(1, 8))
        k = int(rng.integers(0, n))
        assert _batch_kernels._select(a.copy(), n, k) == np.sort(a)[k]


def test_direct_limit_covers_the_papers_windows() -> None:
    assert DIRECT_MAX_STATES >= 300


# --------------------------------------------------------------------------------------------
# the pipeline through the batch


def _recording(seconds: float = 3.0) -> Recording:
    t = np.round(np.arange(0, seconds, 0.002), 9)
    rng = np.random.default_rng(1)
    data = pd.DataFrame(
        {
            "RP": np.sin(2 * t),
            "AP": np.round(np.sin(2 * t - 0.1) * 300) / 300,
            "V": np.cos(2 * t) + 0.01 * rng.normal(size=t.size),
            "AC": np.where(t < 2.0, rng.normal(size=t.size), np.round(rng.normal(size=t.size))),
        },
        index=pd.Index(t, name="time"),
    )
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    return Recording(data, {}, info, source="trace.csv", sample_period=0.002)


def _networks(batched: bool, monkeypatch: pytest.MonkeyPatch, *args: Any,
              **kwargs: Any) -> tuple[dict[str, Any], list[FuncnetWarning]]:
    with monkeypatch.context() as patch:
        if not batched:
            patch.setattr(funcnet.pipeline, "_batched_networks", lambda *a, **k: ({}, []))
        calls: list[int] = []
        original = funcnet.core.batch.batch_pairs
        patch.setattr(funcnet.core.batch, "batch_pairs",
                      lambda *a, **k: calls.append(1) or original(*a, **k))
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            networks = window_networks(*args, **kwargs)
        assert bool(calls) == batched
    found = [w.message for w in caught if isinstance(w.message, FuncnetWarning)]
    return networks, found  # type: ignore[return-value]


def _same_warnings(a: list[FuncnetWarning], b: list[FuncnetWarning]) -> None:
    assert [(type(w), w.problem, w.pairs, w.signals, w.window, str(w)) for w in a] == [
        (type(w), w.problem, w.pairs, w.signals, w.window, str(w)) for w in b
    ]


@pytest.mark.parametrize("case", [0, 1, 4, 7])
def test_window_networks_through_the_batch_equal_the_per_window_path(
    case: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rec = _recording()
    windows = [Window(f"w{k}", 0.1 + 0.13 * k, 0.4 + 0.13 * k) for k in range(20)]
    p = NetworkParameters(**CASES[case])
    batched, batch_warnings = _networks(True, monkeypatch, rec, windows, parameters=p)
    single, single_warnings = _networks(False, monkeypatch, rec, windows, parameters=p)
    assert list(batched) == list(single)
    for label in single:
        assert batched[label] == single[label], label
    _same_warnings(batch_warnings, single_warnings)
    assert any(w.problem in ("eps_order", "rate_exceeded") for w in single_warnings)


def test_window_networks_falls_back_where_the_batch_does_not_apply(
    monkeypatch: pytest.MonkeyPatch
) -> None:
    rec = _recording()
    data = rec.data.copy()
    data.loc[data.index < 0.5, "V"] = 1.0  # constant in the first window
    still = Recording(data, {}, rec.signals, source="trace.csv", sample_period=0.002)
    windows = [Window("still", 0.1, 0.4), Window("moving", 1.0, 1.3)]
    # a window with a constant signal goes the per-window way; the others stay in the batch
    single, single_warnings = _networks(False, monkeypatch, still, windows, constant="drop")
    mixed, mixed_warnings = _networks(True, monkeypatch, still, windows, constant="drop")
    assert mixed == single and mixed["still"].window["dropped"] == ("V",)
    _same_warnings(mixed_warnings, single_warnings)
    for args, kwargs in (
        ((rec, [Window("long", 0.1, 2.0)]), {}),
        ((rec, windows), {"eps": (0.2, 0.1)}),
    ):
        single, single_warnings = _networks(False, monkeypatch, *args, **kwargs)
        with monkeypatch.context() as patch:
            patch.setattr(funcnet.core.batch, "batch_pairs", None)  # must not be reached
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                again = window_networks(*args, **kwargs)
        assert again == single
        _same_warnings([w.message for w in caught  # type: ignore[misc]
                        if isinstance(w.message, FuncnetWarning)], single_warnings)


def test_window_networks_of_different_lengths_and_a_long_window(
    monkeypatch: pytest.MonkeyPatch
) -> None:
    rec = _recording()
    windows = [Window("a", 0.1, 0.4), Window("b", 0.5, 1.1), Window("long", 0.9, 2.8),
               Window("c", 2.0, 2.25)]
    p = NetworkParameters(rule="pyunicorn", metric="supremum")
    batched, batch_warnings = _networks(True, monkeypatch, rec, windows, parameters=p)
    single, single_warnings = _networks(False, monkeypatch, rec, windows, parameters=p)
    assert batched == single
    _same_warnings(batch_warnings, single_warnings)


@pytest.mark.parametrize("method", ["minmax", "zscore", None])
def test_stacked_normalization_and_steps_are_each_windows_own(method):
    """The pipeline normalizes and reads the steps of windows of one length as one stack: the
    same bits as the per-window functions (normalize, window_steps, normalized_steps), on
    windows of two lengths, with float32-stored columns (their own spacing read)."""
    from funcnet.core.normalization import normalize
    from funcnet.network.precision import normalized_steps
    from funcnet.pipeline import _normalized_parts, window_steps

    rng = np.random.default_rng(7)
    names = ["RP", "AP", "V"]
    channel = {"RP": 1e-3, "AP": 0.0, "V": 2.0**-30}
    parts = []
    for w in range(12):
        part = rng.normal(size=(150 + (w % 2), 3)).cumsum(axis=0) * 10.0 ** (w % 4)
        part[:, 1] = np.float32(part[:, 1])  # stored in single precision
        if w % 3 == 0:
            part[:, 2] = np.float32(part[:, 2] * 1e-3)
        parts.append(part)
    normalized, steps = _normalized_parts(parts, names, method, channel)
    for part, mine, found in zip(parts, normalized, steps, strict=True):
        reference = normalize(part, method)
        assert mine.tobytes() == reference.tobytes()
        expected = normalized_steps(list(window_steps(part, names, channel).values()), part,
                                    reference)
        assert found.tobytes() == expected.tobytes()
    assert (steps[:, 1] > 0).all()  # the float32 column's own spacing (its channel says 0)


def test_measures_of_some_pairs_are_those_of_all():
    rng = np.random.default_rng(3)
    result = batch_pairs(np.stack([_random_window(rng, 150, 4) for _ in range(2)]))
    every = result.measures(1)
    some = result.measures(1, [4, 0, 2])
    assert list(some) == [result.pairs[4], result.pairs[0], result.pairs[2]]
    assert all(some[pair] == every[pair] for pair in some)


def test_each_window_has_the_warnings_its_own_pairs_table_calls_for(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Windows flagged alike share their warnings' text; each is still its own, located, and
    those of windows with a degenerate pair print that window's rates."""
    from funcnet.pipeline import window_warnings

    batched: list[Any] = []
    original = funcnet.pipeline._batched_networks
    monkeypatch.setattr(funcnet.pipeline, "_batched_networks",
                        lambda *a, **k: batched.append(original(*a, **k)) or batched[-1])
    rec = _recording()
    windows = [Window(f"w{k}", 0.1 + 0.05 * k, 0.4 + 0.05 * k) for k in range(50)]
    problems = set()
    for case in (0, 4):
        batched.clear()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            window_networks(rec, windows, parameters=NetworkParameters(**CASES[case]))
        networks, found = batched[0]
        assert len(networks) == len(windows)
        _same_warnings(found, window_warnings(networks))
        assert len({(w.problem, w.pairs) for w in found}) < len(found)  # some alike
        problems |= {w.problem for w in found}
    assert problems == {"eps_order", "rate_exceeded", "degenerate"}
