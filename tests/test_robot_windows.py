"""Analysis windows; one functional network per window is tested in test_pipeline.py."""

from __future__ import annotations

import pandas as pd
import pytest

from funcnet.errors import ParameterError, WindowError
from funcnet.robot.io.read import read_trace
from funcnet.robot.phases import detect_phases
from funcnet.robot.preprocess import add_derived_signals
from funcnet.robot.recording import Recording
from funcnet.robot.windows import (
    Window,
    fixed_windows,
    phase_windows,
    reversal_windows,
    sliding_windows,
)


@pytest.fixture(scope="module")
def real(real_trace) -> Recording:
    return add_derived_signals(read_trace(real_trace), ["V"])


@pytest.fixture(scope="module")
def phases(real):
    return detect_phases(real)


def test_phase_windows_number_repeated_phases(phases):
    windows = phase_windows(phases)
    assert [w.label for w in windows[:4]] == [
        "early spin-up 1",
        "late spin-up 1",
        "cruise 1",
        "braking 1",
    ]
    assert len(windows) == 12 and all(w.phase != "standstill" for w in windows)
    assert [w.label for w in phase_windows(phases, include=["cruise"])] == [
        "cruise 1",
        "cruise 2",
        "cruise 3",
    ]
    moving = phases[phases["phase"] != "standstill"]
    assert [(w.start, w.stop) for w in windows] == list(
        zip(moving["start"], moving["stop"], strict=True)
    )


def test_fixed_windows_of_the_velocity_study(phases):
    windows = fixed_windows(phases)
    assert [w.label for w in windows[:3]] == ["spin-up 1", "cruise 1", "braking 1"]
    first = phases.drop_duplicates("phase")
    starts = dict(zip(first["phase"], first["start"], strict=True))
    assert windows[0].start == starts["early spin-up"] and windows[0].duration == 0.28
    assert windows[1].start == starts["cruise"] and windows[1].duration == 0.6
    assert windows[2].start == starts["braking"] and windows[2].duration == 0.6
    assert len(windows) == 9
    # A late spin-up without an early one (after a reversal) anchors the spin-up window.
    by_hand = {"reversal": (1.0, 1.3), "late spin-up": (1.3, 1.6), "cruise": (1.6, 2.0)}
    assert [(w.label, w.start) for w in fixed_windows(by_hand, {"spin-up": 0.1})] == [
        ("spin-up", 1.3)
    ]
    with pytest.raises(ParameterError, match="lengths"):
        fixed_windows(phases, {"cruise": 0})


def test_reversal_windows():
    table = {"cruise": (0.5, 1.7), "reversal": (1.7, 2.0), "late spin-up": (2.0, 2.3)}
    windows = reversal_windows(table)
    assert [w.label for w in windows] == [
        "reversal -40 ms",
        "reversal -20 ms",
        "reversal +0 ms",
        "reversal +20 ms",
        "reversal +40 ms",
    ]
    assert [w.offset for w in windows] == [-0.04, -0.02, 0.0, 0.02, 0.04]
    assert [(w.start, w.stop) for w in windows] == [
        (1.66, 1.96),
        (1.68, 1.98),
        (1.7, 2.0),
        (1.72, 2.02),
        (1.74, 2.04),
    ]
    centred = reversal_windows(table, shifts=(0.0,), width=0.1)
    assert (centred[0].start, centred[0].stop) == (1.8, 1.9)
    two = reversal_windows([("reversal", 1, 2), ("reversal", 3, 4)], shifts=(0.0,))
    assert [w.label for w in two] == ["reversal 1 +0 ms", "reversal 2 +0 ms"]
    with pytest.raises(WindowError, match="no reversal"):
        reversal_windows({"cruise": (0, 1)})


def test_sliding_windows(real):
    windows = sliding_windows(real, 10.0, 5.0)
    assert [(w.start, w.stop) for w in windows] == [
        (0.0, 10.0),
        (5.0, 15.0),
        (10.0, 20.0),
        (15.0, 25.0),
        (20.0, 30.0),
        (25.0, 35.0),
        (30.0, 40.0),
        (35.0, 45.0),
    ]
    part = sliding_windows(real, 0.1, 0.04, start=7.0, stop=7.2)
    assert [w.label for w in part] == ["7.000-7.100 s", "7.040-7.140 s", "7.080-7.180 s"]
    with pytest.raises(WindowError, match="axis7-braking-trace.xml.*longer than"):
        sliding_windows(real, 60.0, 1.0)
    with pytest.raises(ParameterError, match="step"):
        sliding_windows(real, 1.0, 0.0)
    with pytest.raises(WindowError, match="start < stop"):
        Window("w", 2.0, 1.0)


def _rows(recording: Recording, window: Window) -> pd.Index:
    """The ticks ``start <= t < stop``, selected by comparison (no tolerance)."""
    index = recording.data.index
    return index[(index >= window.start) & (index < window.stop)]


def test_a_window_holds_the_rows_from_start_to_before_stop(real, phases):
    windows = [
        *sliding_windows(real, 10.0, 5.0),
        *sliding_windows(real, 0.011, 0.003, start=7.0, stop=7.05),  # off the 2 ms grid
        *phase_windows(phases),
        *fixed_windows(phases),
    ]
    for window in windows:
        rows = real.window(window.start, window.stop).data.index
        assert rows.equals(_rows(real, window)), window
        assert rows[0] >= window.start and rows[-1] < window.stop
    # 7.000-7.011 s on a 2 ms grid: 7.000 ... 7.010; the next window starts between ticks.
    first, second = sliding_windows(real, 0.011, 0.003, start=7.0, stop=7.05)[:2]
    assert real.window(first.start, first.stop).data.index.tolist() == [
        7.0, 7.002, 7.004, 7.006, 7.008, 7.01
    ]
    assert real.window(second.start, second.stop).data.index[0] == 7.004
    # A window ending on a tick leaves that tick to the next window: consecutive sliding
    # windows with step == width tile the recording without overlap.
    tiles = sliding_windows(real, 1.0, 1.0, start=7.0, stop=10.0)
    counts = [len(real.window(w.start, w.stop).data) for w in tiles]
    assert counts == [500, 500, 500]
    assert len(real.window(7.0, 10.0).data) == sum(counts)
