"""Short pairs through the batched engine's kernel: ``cross_measures`` gives, bit for bit, the
general path's result (every field) and pyunicorn's values, on both sides of every switch."""

from __future__ import annotations

import dataclasses
import warnings
from typing import Any

import numpy as np
import pytest
from pyunicorn import timeseries as pyunicorn_timeseries  # a test dependency: never skipped

import funcnet.core._batch_kernels
from funcnet.core.embedding import MIN_STATES, embed
from funcnet.core.measures import cross_measures, pairwise_cross_measures
from funcnet.errors import DegenerateWarning, ParameterError, SignalError, ThresholdWarning
from funcnet.parameters import NetworkParameters

DIM, DELAY = 3, 10
SPAN = (DIM - 1) * DELAY
LIMIT = funcnet.core._batch_kernels.DIRECT_MAX_STATES
# Samples on both sides of each switch: the fewest states, the kernel's direct selection of the
# cross threshold (m * m < DIRECT_PAIRS) and of the auto thresholds (m (m - 1) / 2 <
# DIRECT_PAIRS), and the largest pair the kernel takes.
LENGTHS = [SPAN + MIN_STATES, SPAN + 78, SPAN + 79, SPAN + 111, SPAN + 112, 150,
           SPAN + LIMIT - 1, SPAN + LIMIT, SPAN + LIMIT + 1]


def _pair(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    x = np.sin(0.05 * t) + 0.1 * rng.normal(size=n)
    y = np.sin(0.065 * t + 0.5) + 0.3 * x + 0.1 * rng.normal(size=n)
    return x, y


@pytest.fixture
def kernel_calls(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Counts the pairs that took the kernel (so that a test knows which path it compared)."""
    calls: list[int] = []
    original = funcnet.core._batch_kernels.pair_kernel

    def counted(x: np.ndarray, *args: Any) -> Any:
        result = original(x, *args)
        if result[0]:  # the kernel took the pair (not: its values are not plain)
            calls.append(x.size)
        return result

    monkeypatch.setattr(funcnet.core._batch_kernels, "pair_kernel", counted)
    return calls


def _general(x: Any, y: Any, p: NetworkParameters) -> Any:
    """The general path: a two-signal network's pair (each block packed and validated)."""
    return pairwise_cross_measures([x, y], names=["x", "y"], parameters=p, warn=False)[("x", "y")]


def _assert_same(got: Any, want: Any) -> None:
    for field in dataclasses.fields(got):
        a, b = getattr(got, field.name), getattr(want, field.name)
        assert a == b, (field.name, a, b)
        assert type(a) is type(b), (field.name, type(a), type(b))
        if isinstance(b, float):  # the same bits (0.0 and -0.0 compare equal)
            assert np.float64(a).tobytes() == np.float64(b).tobytes(), field.name


@pytest.mark.parametrize("n", LENGTHS)
@pytest.mark.parametrize(
    "options",
    [
        {"metric": "supremum", "rule": "pyunicorn"},
        {"metric": "euclidean", "rule": "funcnet"},
        {"metric": "manhattan", "rule": "funcnet", "theiler": 2, "rr": (0.08, 0.03), "cr": 0.1},
        {"metric": "euclidean", "rule": "pyunicorn", "rr": 0.1, "cr": 0.02},
    ],
)
def test_short_pairs_are_the_general_paths(n: int, options: dict[str, Any],
                                           kernel_calls: list[int]) -> None:
    p = NetworkParameters(dim=DIM, delay=DELAY, **options)
    x, y = _pair(n, seed=n)
    result = cross_measures(x, y, parameters=p, warn=False)
    assert kernel_calls == ([n] if n - SPAN <= LIMIT else [])
    _assert_same(result, _general(x, y, p))


@pytest.mark.parametrize(
    ("n", "metric"),
    # pyunicorn takes about a second per pair at the longest: those in one metric only.
    [(n, metric) for n in (SPAN + MIN_STATES, SPAN + 78, SPAN + 79, SPAN + 111, 150)
     for metric in ("supremum", "euclidean")]
    + [(SPAN + LIMIT, "supremum"), (SPAN + LIMIT + 1, "supremum")],
)
def test_short_pairs_are_pyunicorns(n: int, metric: str, kernel_calls: list[int]) -> None:
    x, y = _pair(n, seed=n + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        result = cross_measures(x, y, dim=DIM, delay=DELAY, metric=metric, rule="pyunicorn")
    network = pyunicorn_timeseries.InterSystemRecurrenceNetwork(
        embed(x, DIM, DELAY), embed(y, DIM, DELAY), metric=metric,
        recurrence_rate=(0.05, 0.05, 0.05), silence_level=3,
    )
    assert kernel_calls == ([n] if n - SPAN <= LIMIT else [])
    assert result.c_xy == network.cross_global_clustering_xy()
    assert result.c_yx == network.cross_global_clustering_yx()
    assert result.t_xy == network.cross_transitivity_xy()
    assert result.t_yx == network.cross_transitivity_yx()
    assert result.achieved_cr == network.cross_recurrence_rate()


def test_degenerate_and_quantized_pairs_and_their_warnings(kernel_calls: list[int]) -> None:
    rng = np.random.default_rng(3)
    cases = [
        (np.zeros(150), rng.random(150)),  # constant: threshold 0
        (np.round(rng.random(150) * 2), rng.random(150)),  # three values: rate over twice
        (np.repeat(np.arange(75.0), 2), np.round(np.sin(np.arange(150) / 9), 1)),  # ties
        (np.arange(150), np.arange(150) % 7),  # integers, as given
        (list(np.sin(np.arange(150) / 5)), np.cos(np.arange(150) / 4).astype(np.float32)),
    ]
    for x, y in cases:
        with warnings.catch_warnings(record=True) as short_warnings:
            warnings.simplefilter("always")
            result = cross_measures(x, y)
        with warnings.catch_warnings(record=True) as general_warnings:
            warnings.simplefilter("always")
            pairwise_cross_measures([x, y], names=["x", "y"], warn=True)
        _assert_same(result, _general(x, y, NetworkParameters()))
        assert [str(w.message) for w in short_warnings] == [
            str(w.message) for w in general_warnings
        ]
    assert len(kernel_calls) == len(cases)
    assert cross_measures(np.zeros(150), rng.random(150), warn=False).degenerate


def test_inputs_the_kernel_does_not_take_go_the_general_way(kernel_calls: list[int]) -> None:
    x, y = _pair(150)
    two_channels = np.column_stack([x, y])
    general = [
        cross_measures(x, y, eps=((0.2, 0.3), 0.1), warn=False),  # explicit thresholds
        cross_measures(x, y[:140], warn=False),  # unequal lengths
        cross_measures(two_channels, two_channels[::-1], warn=False),  # multichannel nodes
        cross_measures(x * 1e100, y * 1e100, warn=False),  # beyond float32
    ]
    assert kernel_calls == []
    assert all(not r.degenerate for r in general[:3])
    bad = x.copy()
    bad[7] = np.nan
    with pytest.raises(SignalError, match="signal x has 1 NaN or infinite value"):
        cross_measures(bad, y)
    with pytest.raises(SignalError, match="signal y must be real-valued"):
        cross_measures(x, y.astype(complex))
    with pytest.raises(SignalError, match="too short for the embedding"):
        cross_measures(x[:26], y[:26])
    with pytest.raises(ParameterError, match="rr must be one rate or one per signal"):
        cross_measures(x, y, rr=(0.05, 0.05, 0.05))
    with pytest.raises(SignalError, match="amplitudes too large"):
        cross_measures(x * 1e300, y)
    assert kernel_calls == []


def test_keyword_parameters_are_checked_on_every_call() -> None:
    x, y = _pair(150)
    _assert_same(cross_measures(x, y, dim=3, warn=False), _general(x, y, NetworkParameters(dim=3)))
    for bad, message in ((3.0, "dim must be an integer"), (True, "dim must be an integer"),
                         (0, "dim must be >= 1")):
        with pytest.raises(ParameterError, match=message):
            cross_measures(x, y, dim=bad)
    with pytest.raises(ParameterError, match="mu is not a parameter here"):
        cross_measures(x, y, mu=0.1)
    assert cross_measures(x, y, rr=0.1, warn=False).parameters == NetworkParameters(rr=0.1)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cross_measures(np.zeros(150), y)
    assert [type(w.message) for w in caught] == [ThresholdWarning, DegenerateWarning]


def test_repeated_warnings_point_at_the_call_each_time() -> None:
    x, y = _pair(150)
    for _ in range(2):  # the second call reuses the pair's warnings
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = cross_measures(x, y, dim=DIM, delay=DELAY, metric="supremum",
                                    rule="pyunicorn")
        assert not result.eps_ordered and not result.degenerate
        assert [w.message.problem for w in caught] == ["eps_order"]  # type: ignore[union-attr]
        assert caught[0].filename == __file__
