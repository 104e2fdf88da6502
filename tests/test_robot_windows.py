"""Analysis windows and one functional network per window."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from funcnet.errors import ChannelError, ParameterError, StaircaseWarning, WindowError
from funcnet.network import functional_network
from funcnet.robot.phases import detect_phases
from funcnet.robot.preprocess import add_derived_signals, resample
from funcnet.robot.recording import Recording, read_trace
from funcnet.robot.windows import (
    Window,
    fixed_windows,
    phase_networks,
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


# Real signals do not always give eps_XY < eps_X, eps_Y; the network says so, and that is not
# what this test is about.
@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_per_phase_of_the_real_braking_motion(real, phases):
    first_move = phase_windows(phases)[:4]
    with pytest.warns(StaircaseWarning, match=r"\['AP', 'MP'\].*4 ms"):
        networks = phase_networks(real, first_move)
    assert list(networks) == ["early spin-up 1", "late spin-up 1", "cruise 1", "braking 1"]
    for window in first_move:
        network = networks[window.label]
        assert network.label == window.label
        assert network.nodes == ("RP", "AP", "MP", "V", "AC")  # the paper's, RC not recorded
        assert len(network.pairs) == 10
    # The braking network is the network of the braking window cut by hand.
    braking = first_move[-1]
    index = real.data.index
    cut = real.data[(index >= braking.start - 1e-9) & (index < braking.stop - 1e-9)]
    assert len(cut) == round(braking.duration / 0.002)
    expected = functional_network(cut[["RP", "AP", "MP", "V", "AC"]], label=braking.label)
    assert networks[braking.label] == expected


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_after_decimation_warn_no_staircase(real, phases):
    coarse = resample(real)
    braking = phase_windows(phases, include=["braking"])[:1]
    with warnings.catch_warnings():
        warnings.simplefilter("error", StaircaseWarning)
        networks = phase_networks(coarse, braking, signals=["RP", "AP", "AC"], dim=2, delay=5)
    network = networks["braking 1"]
    assert network.nodes == ("RP", "AP", "AC")
    assert network.parameters["dim"] == 2 and network.parameters["delay"] == 5


@pytest.mark.filterwarnings("ignore::funcnet.errors.StaircaseWarning")
def test_phase_networks_refuses_bad_windows(real):
    with pytest.raises(WindowError, match=r"axis7-braking-trace.xml: window \[40, 50\) s"):
        phase_networks(real, [Window("late", 40.0, 50.0)])
    with pytest.raises(WindowError, match="'AP' has no recorded value"):
        phase_networks(real, [Window("start", 0.0, 0.2)], signals=["RP", "AP"])
    with pytest.raises(WindowError, match="occur more than once"):
        phase_networks(real, [Window("w", 1.0, 2.0), Window("w", 2.0, 3.0)])
    with pytest.raises(ChannelError, match="'RC'"):
        phase_networks(real, [Window("w", 7.0, 8.0)], signals=["RP", "RC"])
    assert np.isnan(real.data.at[0.0, "AP"])
