"""The robot network's windows at a bounded size: a segment whole under the bound, in equal
parts above it, at most ROBOT_MAX_WINDOWS of them on a page."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io

from funcnet.inspection import inspect_robot, robot as robot_module
from funcnet.inspection.robot import robot_windows
from funcnet.parameters import NetworkParameters
from funcnet.pipeline import window_networks
from funcnet.report.inspect import write_robot_inspection
from funcnet.robot import read_trace
from funcnet.robot.windows import paper_nodes, span_window

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

MAP = {"rec.t": "time", "rp": "RP", "ap": "AP", "tau": "AC"}
DELAY = 5


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """Two axes at 250 Hz over 4 s (1,000 samples), each moving out and back."""
    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(7)
    rp = np.vstack([10 * np.sin(np.pi * t / 4) ** 2, -6 * np.sin(np.pi * t / 2) ** 2])
    ap = rp - 0.01 * np.gradient(rp, t, axis=1) + 0.0005 * rng.standard_normal(rp.shape)
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1) + 0.05 * rng.standard_normal(
        rp.shape)
    path = Path(tmp_path_factory.mktemp("bound")) / "two-axes.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "tau": tau}})
    return read_trace(path, channels=MAP)


def _states(window, recording) -> int:
    return len(recording.window(window.start, window.stop).data) - 2 * DELAY


def test_under_the_bound_the_whole_recording_is_one_window_as_before(recording):
    p = NetworkParameters(delay=DELAY)
    windows, note = robot_windows(recording, p)
    ((a, b),) = recording.segments
    assert note == "" and windows == (dataclasses.replace(
        span_window(a, b), label=f"whole recording {a:g}-{b:g} s"),)
    found = inspect_robot(recording, evidence=False, backlash=False, delay=DELAY)
    # The network of the old design: one window over the segment, computed directly.
    nodes = paper_nodes(recording.data.columns)
    reference = window_networks(recording, windows, signals=nodes, parameters=p,
                                constant="drop")
    assert list(found.networks) == list(reference)
    for label, net in reference.items():
        pd.testing.assert_frame_equal(found.networks[label].pairs, net.pairs)
    assert found.windows_note == ""


def test_above_the_bound_equal_consecutive_parts_within_it(recording, monkeypatch, tmp_path):
    monkeypatch.setattr(robot_module, "ROBOT_MAX_STATES", 300)
    p = NetworkParameters(delay=DELAY)
    windows, note = robot_windows(recording, p)
    ((a, b),) = recording.segments
    samples = len(recording.data)
    # The fewest parts of at most 300 states: 1,000 samples, 10 lost to the embedding per part.
    assert len(windows) == math.ceil(samples / (300 + 2 * DELAY)) == 4
    assert windows[0].start == a and windows[-1].stop == b
    assert all(w.stop == v.start for w, v in zip(windows[:-1], windows[1:], strict=True))
    states = [_states(w, recording) for w in windows]
    assert max(states) <= 300 and sum(s + 2 * DELAY for s in states) == samples
    assert max(states) - min(states) <= 1
    assert [w.label.split(":")[0] for w in windows] == [f"part {k} of 4" for k in range(1, 5)]
    assert "4 consecutive parts" in note
    found = inspect_robot(recording, evidence=False, backlash=False, delay=DELAY)
    assert [w.label for w in found.windows] == [w.label for w in windows]
    # Each part's network is the plain window network of its span.
    nodes = paper_nodes(recording.data.columns)
    for window in windows:
        (alone,) = window_networks(recording, [window], signals=nodes, parameters=p,
                                   constant="drop").values()
        pd.testing.assert_frame_equal(found.networks[window.label].pairs, alone.pairs)
    page = write_robot_inspection(found, tmp_path / "page").read_text()
    assert "4 consecutive parts of at most 300 states" in page


def test_at_most_the_cap_of_windows_spread_over_the_recording(recording, monkeypatch):
    monkeypatch.setattr(robot_module, "ROBOT_MAX_STATES", 40)
    windows, note = robot_windows(recording, NetworkParameters(delay=DELAY))
    parts = math.ceil(len(recording.data) / (40 + 2 * DELAY))
    assert parts == 20 > robot_module.ROBOT_MAX_WINDOWS
    assert len(windows) == robot_module.ROBOT_MAX_WINDOWS
    numbers = [int(w.label.split()[1]) for w in windows]
    assert numbers[0] == 1 and numbers[-1] == parts and numbers == sorted(set(numbers))
    assert all(w.label.startswith(f"part {k} of {parts}:") for k, w in zip(numbers, windows,
                                                                          strict=True))
    assert f"{robot_module.ROBOT_MAX_WINDOWS} of them" in note
    # Evenly spread: the gaps between chosen part numbers differ by at most one.
    gaps = np.diff(numbers)
    assert gaps.max() - gaps.min() <= 1
