"""The direction reading of many windows in one stacked pass (funcnet.network.direction).

``window_directions`` (every window of a call at once, windows of one length and layout
stacked) against ``direction_columns`` window by window -- the readings' sentences equal, the
p-values bit for bit -- and against least squares written pair by pair on the lags as they
stand (well-conditioned windows: a relative 1e-8).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from funcnet.network._prediction import pair_p_values
from funcnet.network.direction import (
    DIRECTION_GAP,
    _p_matrix,
    direction_columns,
    direction_lags,
    window_directions,
)
from funcnet.parameters import NetworkParameters

NAMES = ["RP", "AP", "AC"]
PAIRS = [("RP", "AP"), ("RP", "AC"), ("AP", "AC")]


def _recording(n: int = 900, seed: int = 0) -> np.ndarray:
    """A set-point logged to 4 decimals (ramps and smooth turns), a measured position two
    samples behind, a current."""
    rng = np.random.default_rng(seed)
    acceleration = np.convolve(rng.standard_normal(n + 40), np.hanning(40), "valid")[:n]
    acceleration[300:420] = 0.0  # a stretch at constant speed: a ramp
    setpoint = np.cumsum(np.cumsum(acceleration)) / 100
    measured = np.concatenate([setpoint[:2], setpoint[:-2]]) + 1e-3 * rng.standard_normal(n)
    current = np.gradient(np.gradient(setpoint)) * 50 + 0.2 * rng.standard_normal(n)
    return np.column_stack([np.round(setpoint, 4), measured, current])


def _windows() -> list[np.ndarray]:
    values = _recording()
    found = [values[start : start + 150] for start in range(0, 700, 37)]
    found += [values[40:191], values[500:700]]  # other lengths
    held = values[100:250].copy()
    held[:, 2] = 0.5  # a constant current
    return [*found, held]


def test_stacked_readings_equal_the_per_window_ones():
    parameters = NetworkParameters(delay=3)  # 7 lags: windows of 150 read
    windows = _windows()
    rng = np.random.default_rng(1)
    degenerate = rng.random((len(windows), len(PAIRS))) < 0.2
    steps = np.tile([1e-4, 0.0, 0.0], (len(windows), 1))
    stacked = window_directions(windows, NAMES, PAIRS, degenerate, parameters, steps)
    expected: dict[str, list[str]] = {"direction": [], "direction_reason": []}
    for window, flags, step in zip(windows, degenerate, steps, strict=True):
        table = pd.DataFrame({"x": [x for x, _ in PAIRS], "y": [y for _, y in PAIRS],
                              "degenerate": flags})
        read = direction_columns(table, dict(zip(NAMES, window.T, strict=True)), parameters,
                                 steps=dict(zip(NAMES, step.tolist(), strict=True)))
        for name in expected:
            expected[name] += read[name]
    assert stacked == expected
    assert {"x->y", "y->x", "none"} <= set(stacked["direction"])  # the test reads something
    assert any("constant" in reason for reason in stacked["direction_reason"])
    # the p-values bit for bit: a stack of windows of one length against each alone
    lags = direction_lags(parameters)
    same = [w for w in windows if w.shape[0] == 150]
    found, within = pair_p_values(np.stack(same), lags, DIRECTION_GAP,
                                  np.tile([1e-4, 0.0, 0.0], (len(same), 1)))
    for k, window in enumerate(same):
        alone, inside = _p_matrix(window, lags, DIRECTION_GAP, np.array([1e-4, 0.0, 0.0]))
        np.testing.assert_array_equal(found[k], alone)
        np.testing.assert_array_equal(within[k], inside)


def _lstsq_p(x: np.ndarray, y: np.ndarray, p: int, gap: int) -> float:
    """Least squares pair by pair on the standardized lags as they stand (SVD)."""
    from scipy import stats

    xs, ys = (x - x.mean()) / x.std(), (y - y.mean()) / y.std()
    t = np.arange(p + gap, x.size)
    own = np.column_stack([np.ones(t.size)] + [ys[t - k] for k in range(1, p + 1)])
    full = np.column_stack([own] + [xs[t - gap - k] for k in range(1, p + 1)])
    rss = [float(((ys[t] - a @ np.linalg.lstsq(a, ys[t], rcond=None)[0]) ** 2).sum())
           for a in (own, full)]
    dfd = t.size - 2 * p - 1
    return float(stats.f.sf((rss[0] - rss[1]) / p / (rss[1] / dfd), p, dfd))


@pytest.mark.parametrize("seed", range(3))
def test_stacked_p_values_match_least_squares_pair_by_pair(seed):
    """Noisy coupled signals (lags far from collinear): both designs well conditioned."""
    rng = np.random.default_rng(seed)
    n, lags = 600, 6
    x = rng.standard_normal(n).cumsum() * 0.3 + rng.standard_normal(n)
    y = np.concatenate([[0.0] * 3, 0.4 * x[:-3]]) + rng.standard_normal(n)
    z = rng.standard_normal(n)
    values = np.column_stack([x, y, z])
    windows = np.stack([values[k * 150 : k * 150 + 150] for k in range(4)])
    found, _ = pair_p_values(windows, lags, DIRECTION_GAP, np.zeros((4, 3)))
    for w, window in enumerate(windows):
        for i in range(3):
            for j in range(3):
                if i != j:
                    expected = _lstsq_p(window[:, j], window[:, i], lags, DIRECTION_GAP)
                    assert found[w, i, j] == pytest.approx(expected, rel=1e-8, abs=1e-300)
