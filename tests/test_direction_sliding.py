"""The direction reading of windows one row apart from shared factors (funcnet.network._sliding).

``sliding_p_values`` against ``pair_p_values`` (each window factored alone by LAPACK, the
reference) on the real SINUMERIK timeline's windows and on synthetic windows with a derived
velocity (a design whose columns are exactly dependent, read by dropping them), and against
exact rational arithmetic.

Wherever the reference does not hinge on how its input was rounded -- its p-values the same to
a relative 1e-7 whether the window is min-max normalized, z-scored or left as recorded, the same
numbers in exact arithmetic -- the sliding p-values agree with it to a relative 1e-6
(measured: 3e-8 at most),
and so do the NaN and within flags everywhere. Where it does hinge on it (a set-point's third
differences a little above rounding; a velocity whose dependence on the position's lags the
normalization's rounding hides from the SVD's threshold), the sliding reading is read from the
recording's rows as recorded: on the synthetic windows it is then the reference's own reading
of the raw rows; on the timeline the directions stay equal.
"""

from __future__ import annotations

import numpy as np
import pytest

from funcnet.network import _sliding
from funcnet.network._prediction import pair_p_values
from funcnet.network.direction import DIRECTION_GAP, window_directions, window_p_values
from funcnet.parameters import NetworkParameters
from test_direction_kernels import _exact_p

TOLERANCE = 1e-6
#: The reference is stable where two roundings of one window give p-values this close.
STABLE = 1e-7


def _minmax(part: np.ndarray) -> np.ndarray:
    return (part - part.min(axis=0)) / np.ptp(part, axis=0)


def _relative(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Relative differences of p-values, 0 where ``b`` is not shown (NaN or under 1e-300)."""
    shown = ~np.isnan(b) & (b > 1e-300)
    difference = np.abs(np.where(shown, a - b, 0.0)) / np.where(shown, b, 1.0)
    return np.nan_to_num(difference, nan=np.inf)


def _compare(values: np.ndarray, firsts: np.ndarray, length: int, lags: int,
             monkeypatch: pytest.MonkeyPatch, share: float) -> tuple[np.ndarray, ...]:
    """The sliding reading (asserting it read at least ``share`` of the windows itself; the
    others: runs too short, or near-dependent columns the SVD keeps), the reference, and which
    p-values the reference reads the same under another rounding of its input."""
    fallen: list[int] = []

    def counted(stack: np.ndarray, *args: object) -> tuple[np.ndarray, np.ndarray]:
        fallen.append(len(stack))
        return pair_p_values(stack, *args)  # type: ignore[arg-type]

    raw = np.stack([values[f : f + length] for f in firsts])
    windows = np.stack([_minmax(part) for part in raw])
    steps = np.zeros((len(windows), windows.shape[2]))
    monkeypatch.setattr(_sliding, "pair_p_values", counted)
    found, within = _sliding.sliding_p_values(windows, values, firsts, lags, DIRECTION_GAP,
                                              steps)
    monkeypatch.undo()
    assert sum(fallen) <= (1.0 - share) * len(windows)
    reference, inside = pair_p_values(windows, lags, DIRECTION_GAP, steps)
    np.testing.assert_array_equal(within, inside)
    np.testing.assert_array_equal(np.isnan(found), np.isnan(reference))
    scored = (raw - raw.mean(axis=1, keepdims=True)) / raw.std(axis=1, keepdims=True)
    other, _ = pair_p_values(scored, lags, DIRECTION_GAP, steps)
    rows, _ = pair_p_values(raw, lags, DIRECTION_GAP, steps)
    stable = (_relative(other, reference) <= STABLE) & (_relative(rows, reference) <= STABLE)
    assert stable.mean() >= 0.5
    assert (_relative(found, reference)[stable] <= TOLERANCE).all()
    return found, reference, stable, raw


def test_sliding_readings_match_on_the_real_timeline(real_trace, monkeypatch):
    from funcnet.robot import add_derived_signals, read_trace

    recording = add_derived_signals(read_trace(real_trace), ["V"])
    values = recording.data[["RP", "AP", "MP", "V", "AC"]].to_numpy(np.float64)
    start = int(np.flatnonzero(np.ptp(np.lib.stride_tricks.sliding_window_view(
        values[:, 0], 150), axis=1) > 0)[0])  # the first window where the set-point moves
    firsts = np.arange(start + 300, start + 600)
    found, reference, _, _ = _compare(values, firsts, 150, 21, monkeypatch, 0.9)
    # decisions (each way at 0.025) equal away from the level, on every window
    away = ~np.isnan(reference) & ((reference < 0.025 / 3) | (reference > 0.025 * 3))
    assert ((found[away] <= 0.025) == (reference[away] <= 0.025)).all()


def _derived(n: int, seed: int) -> np.ndarray:
    """A set-point (ramps and turns), a measured position behind it, its velocity (exactly
    dependent on the position's lags), a noisy current."""
    rng = np.random.default_rng(seed)
    acceleration = np.convolve(rng.standard_normal(n + 40), np.hanning(40), "valid")[:n]
    acceleration[200:300] = 0.0
    setpoint = np.cumsum(np.cumsum(acceleration)) / 100
    measured = np.concatenate([setpoint[:2], setpoint[:-2]]) + 1e-3 * rng.standard_normal(n)
    velocity = np.concatenate([[0.0], np.diff(measured)]) / 0.002
    current = np.gradient(np.gradient(setpoint)) * 50 + 0.2 * rng.standard_normal(n)
    return np.column_stack([setpoint, measured, velocity, current])


@pytest.mark.parametrize("seed", range(2))
def test_sliding_readings_match_on_windows_with_dependent_columns(seed, monkeypatch):
    values = _derived(700, seed)
    firsts = np.arange(20, 420)
    # the ramp's windows hold columns a little above rounding, which the SVD keeps: read alone
    found, reference, stable, raw = _compare(values, firsts, 150, 21, monkeypatch, 0.6)
    # the position and its velocity: dependent columns dropped, the p-values still read
    assert np.isfinite(found[:, 1, 2]).mean() > 0.9
    # where the reference hinges on its input's rounding, the sliding reading is its reading
    # of the recording's rows as they are
    apart = (~stable & (_relative(found, reference) > TOLERANCE)).any(axis=(1, 2))
    rows, _ = pair_p_values(raw[apart], 21, DIRECTION_GAP, np.zeros((apart.sum(), 4)))
    assert (_relative(found[apart], rows).max(axis=(1, 2)) <= TOLERANCE).mean() >= 0.9


def test_sliding_p_values_match_exact_arithmetic():
    """Well-conditioned noisy lags (5 of them): the sliding factors against integer Gram
    determinants of the levels as they stand."""
    rng = np.random.default_rng(3)
    n = 260
    x = rng.standard_normal(n).cumsum() * 0.3 + rng.standard_normal(n)
    y = np.concatenate([[0.0] * 3, 0.4 * x[:-3]]) + rng.standard_normal(n)
    values = np.column_stack([x, y])
    firsts = np.arange(0, 200)
    windows = np.stack([values[f : f + 60] for f in firsts])
    found, _ = _sliding.sliding_p_values(windows, values, firsts, 5, DIRECTION_GAP,
                                         np.zeros((200, 2)))
    for w in (0, 77, 199):
        part = values[firsts[w] : firsts[w] + 60]
        for i, j in ((1, 0), (0, 1)):
            exact = _exact_p(part[:, j], part[:, i], 5, DIRECTION_GAP)
            assert found[w, i, j] == pytest.approx(exact, rel=1e-7)


def test_window_directions_read_the_same_through_the_recording_rows():
    """Without the derived velocity (whose reading alone hinges on the rounding, above)."""
    values = _derived(600, 5)[:, [0, 1, 3]]
    firsts = np.arange(30, 230)
    windows = [_minmax(values[f : f + 150]) for f in firsts]
    names = ["RP", "AP", "AC"]
    pairs = [(a, b) for k, a in enumerate(names) for b in names[k + 1 :]]
    degenerate = np.zeros((len(windows), len(pairs)), dtype=bool)
    steps = np.zeros((len(windows), 3))
    parameters = NetworkParameters()
    sliding = window_directions(windows, names, pairs, degenerate, parameters, steps,
                                origin=(values, firsts))
    alone = window_directions(windows, names, pairs, degenerate, parameters, steps)
    assert sliding["direction"] == alone["direction"]
    assert {"x->y", "none"} <= set(sliding["direction"])


def test_runs_read_over_the_cores_are_read_as_one_by_one(monkeypatch):
    """The runs of a timeline read in threads give the bits of a serial reading; the p-values
    read apart and handed over give the same columns."""
    values = _derived(700, 2)[:, [0, 1, 3]]
    firsts = np.concatenate([np.arange(20, 140), np.arange(200, 260), np.arange(300, 420)])
    windows = np.stack([_minmax(values[f : f + 150]) for f in firsts])
    steps = np.zeros((len(windows), 3))
    threads = _sliding.sliding_p_values(windows, values, firsts, 21, DIRECTION_GAP, steps)
    monkeypatch.setattr(_sliding.os, "cpu_count", lambda: 1)
    serial = _sliding.sliding_p_values(windows, values, firsts, 21, DIRECTION_GAP, steps)
    assert threads[0].tobytes() == serial[0].tobytes()
    assert threads[1].tobytes() == serial[1].tobytes()
    names, parameters = ["RP", "AP", "AC"], NetworkParameters()
    pairs = [("RP", "AP"), ("RP", "AC"), ("AP", "AC")]
    degenerate = np.zeros((len(windows), 3), dtype=bool)
    degenerate[5, 1] = True
    found = window_p_values(list(windows), parameters, steps, origin=(values, firsts))
    assert window_directions(list(windows), names, pairs, degenerate, parameters, steps,
                             origin=(values, firsts), p_values=found) == window_directions(
        list(windows), names, pairs, degenerate, parameters, steps, origin=(values, firsts))
