"""Analysis windows and one functional network per window."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import (
    ChannelError,
    ParameterError,
    SignalError,
    StaircaseWarning,
    ThresholdWarning,
    WindowError,
)
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.robot.phases import detect_phases
from funcnet.robot.preprocess import add_derived_signals, resample
from funcnet.robot.recording import Recording, SignalInfo, read_trace
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
    network = networks[braking.label]
    assert network.nodes == expected.nodes
    pd.testing.assert_frame_equal(network.pairs, expected.pairs)
    # ... whose parameters also say where it comes from.
    assert network.parameters == {
        **expected.parameters,
        "window_start": braking.start,
        "window_stop": braking.stop,
        "phase": "braking",
        "source": real.source,
        "dropped": [],
    }
    assert "axis7-braking-trace.xml" in real.source


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


# --------------------------------------------------------------------------------------------
# a small synthetic recording: RP and AP move throughout, AC is constant before 1 s


@pytest.fixture(scope="module")
def synthetic() -> Recording:
    t = np.arange(0, 3, 0.002)
    data = pd.DataFrame(
        {
            "RP": np.sin(5 * t),
            "AP": np.sin(5 * t - 0.3),
            "AC": np.where(t < 1, 0.25, np.cos(7 * t)),
        },
        index=pd.Index(t, name="time"),
    )
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    return Recording(data, {}, info, source="/data/synthetic.csv", sample_period=0.002)


STILL = Window("still", 0.2, 0.8, phase="standstill")
MOVING = [Window(f"w{k}", 1.0 + 0.3 * k, 1.6 + 0.3 * k, phase="cruise") for k in range(4)]


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_networks_record_their_window_and_survive_json(synthetic):
    networks = phase_networks(synthetic, [STILL, *MOVING], signals=["RP", "AP"], delay=5)
    for window in (STILL, *MOVING):
        parameters = networks[window.label].parameters
        assert parameters["window_start"] == window.start
        assert parameters["window_stop"] == window.stop
        assert parameters["phase"] == window.phase
        assert parameters["source"] == "/data/synthetic.csv"
        assert parameters["dropped"] == []
        assert parameters["n_samples"] == round(window.duration / 0.002)
        again = FunctionalNetwork.from_json(networks[window.label].to_json())
        assert again == networks[window.label]
        assert again.parameters["window_start"] == window.start


def test_errors_inside_a_window_name_file_window_and_span(synthetic):
    with pytest.raises(SignalError) as caught:
        phase_networks(synthetic, [MOVING[0], STILL])
    # The same class and the original message, after the file, the label and the span.
    with pytest.raises(SignalError) as direct:
        functional_network(synthetic.window(STILL.start, STILL.stop).data)
    assert str(caught.value) == f"/data/synthetic.csv: window 'still' [0.2, 0.8) s: {direct.value}"
    assert "signal 'AC' is constant" in str(caught.value)
    # A window too short for the embedding: the error of functional_network, located.
    short = Window("short", 1.0, 1.01)
    with pytest.raises(SignalError, match=r"^/data/synthetic.csv: window 'short' \[1, 1.01\) s: "):
        phase_networks(synthetic, [short], delay=10)
    with pytest.raises(SignalError, match=r"window 'w0' .*at least two signals, got 1"):
        phase_networks(synthetic, [MOVING[0]], signals=["RP"], constant="drop")


def _kind(message) -> str:
    return re.sub(r" for \d+ pair\(s\):[^;]*", "", str(message).splitlines()[0])


def test_threshold_warnings_once_per_kind_naming_their_windows(synthetic):
    # Reference: the warnings of each window computed on its own.
    expected: dict[tuple[type, str], list[str]] = {}
    for window in MOVING:
        part = synthetic.window(window.start, window.stop).data
        with warnings.catch_warnings(record=True) as direct:
            warnings.simplefilter("always")
            functional_network(part, label=window.label, delay=5)
        for w in direct:
            if issubclass(w.category, ThresholdWarning):
                expected.setdefault((w.category, _kind(w.message)), []).append(window.label)
    assert expected and sum(len(v) for v in expected.values()) > len(expected)  # repeats exist
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        phase_networks(synthetic, MOVING, delay=5)
    threshold = [w for w in caught if issubclass(w.category, ThresholdWarning)]
    assert len(threshold) == len(expected)  # one per kind, not one per window
    for w in threshold:
        first, second = str(w.message).splitlines()
        concerned = expected[(w.category, first)]
        assert second == (
            f"/data/synthetic.csv: in {len(concerned)} of {len(MOVING)} window(s): "
            + ", ".join(repr(label) for label in concerned)
        )
        assert w.filename == __file__  # points at the caller's line


@pytest.mark.filterwarnings("ignore::funcnet.errors.ThresholdWarning")
def test_constant_signals_dropped_per_window(synthetic):
    windows = [STILL, MOVING[0]]
    networks = phase_networks(synthetic, windows, constant="drop")
    still, moving = networks["still"], networks["w0"]
    assert still.nodes == ("RP", "AP") and still.parameters["dropped"] == ["AC"]
    assert moving.nodes == ("RP", "AP", "AC") and moving.parameters["dropped"] == []
    # The network without AC is the network of RP and AP alone.
    alone = functional_network(synthetic.window(STILL.start, STILL.stop).data[["RP", "AP"]])
    pd.testing.assert_frame_equal(still.pairs, alone.pairs)
    # Without normalization a constant signal is no error: nothing is dropped.
    unscaled = phase_networks(synthetic, [STILL], constant="drop", normalize=None)
    assert unscaled["still"].nodes == ("RP", "AP", "AC")
    assert unscaled["still"].parameters["dropped"] == []
    with pytest.raises(WindowError, match=r"synthetic.csv: window 'still' .*\['AC'\].*two"):
        phase_networks(synthetic, [STILL], signals=["RP", "AC"], constant="drop")
    with pytest.raises(ParameterError, match="constant"):
        phase_networks(synthetic, [STILL], constant="ignore")


def test_threshold_warnings_of_one_kind_with_other_details_are_one_warning():
    # AC is quantized (too few distinct states) before 1.5 s, AP after: each window's warning
    # about a degenerate recurrence structure names its own signal.
    t = np.arange(0, 3, 0.002)
    ap, ac = np.sin(5 * t - 0.3), np.cos(7 * t)
    data = pd.DataFrame(
        {
            "RP": np.sin(5 * t),
            "AP": np.where(t >= 1.5, np.round(ap), ap),
            "AC": np.where(t < 1.5, np.round(ac), ac),
        },
        index=pd.Index(t, name="time"),
    )
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    recording = Recording(data, {}, info, source="q.csv", sample_period=0.002)
    windows = [Window("a", 0.2, 0.8), Window("b", 1.6, 2.2), Window("c", 0.9, 1.4)]
    direct = set()
    for window in windows:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            functional_network(recording.window(window.start, window.stop).data, delay=5)
        direct |= {str(w.message) for w in caught if str(w.message).startswith("degenerate")}
    assert len(direct) > 1  # the messages differ from window to window
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        phase_networks(recording, windows, delay=5)
    degenerate = [w for w in caught if str(w.message).startswith("degenerate")]
    assert len(degenerate) == 1 and degenerate[0].category is ThresholdWarning
    first, second = str(degenerate[0].message).splitlines()
    assert "signal AC" in first  # window 'a''s details
    assert second == "q.csv: in 3 of 3 window(s): 'a', 'b', 'c' (details as in 'a')"
