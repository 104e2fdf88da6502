"""Inspection of a recording of several axes: each axis on its own, the robot as one network."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.inspection import inspect_recording, inspect_robot, pair_scope
from funcnet.robot import read_trace

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

MAP = {"rec.t": "time", "rp": "RP", "ap": "AP", "mp": "MP", "tau": "AC"}


@pytest.fixture(scope="module")
def two_axes(tmp_path_factory) -> Path:
    """Two axes at 250 Hz, each a smooth move out and back; the arm lags the motor."""
    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(5)
    rp = np.vstack([10 * np.sin(np.pi * t / 4) ** 2, -6 * np.sin(np.pi * t / 2) ** 2])
    mp = rp + 0.001 * rng.standard_normal(rp.shape)
    ap = mp - 0.01 * np.gradient(rp, t, axis=1) + 0.0005 * rng.standard_normal(rp.shape)
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1) + 0.05 * rng.standard_normal(
        rp.shape)
    path = tmp_path_factory.mktemp("robot") / "two-axes.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "mp": mp, "tau": tau}})
    return path


def test_pair_scope_reads_the_axes_from_the_names():
    pairs = pd.DataFrame({"x": ["A1.RP", "A1.RP", "A2.MP"], "y": ["A1.AP", "A2.RP", "A10.AC"]})
    scoped = pair_scope(pairs)
    assert scoped["scope"].tolist() == ["within-axis", "between-axes", "between-axes"]
    assert scoped["axis_y"].tolist() == [1, 2, 10]
    assert list(pairs.columns) == ["x", "y"]  # a copy


def test_inspect_robot_is_each_axis_and_one_network(two_axes):
    recording = read_trace(two_axes, channels=MAP)
    found = inspect_robot(recording, evidence=False, backlash=False, delay=5)
    assert sorted(found.axes) == [1, 2] and found.axis_errors == {}
    # Each axis exactly as its own one-axis inspection.
    alone = inspect_recording(read_trace(two_axes, channels=MAP, axis=2), evidence=False,
                              backlash=False, delay=5)
    assert list(found.axes[2].networks) == list(alone.networks)
    for label, net in alone.networks.items():
        pd.testing.assert_frame_equal(found.axes[2].networks[label].pairs, net.pairs)
    # One robot network over the whole recording, nodes grouped per axis.
    assert found.signals == ("A1.RP", "A1.AP", "A1.MP", "A1.AC",
                             "A2.RP", "A2.AP", "A2.MP", "A2.AC")
    (label,) = found.networks
    pairs = found.pairs[label]
    assert len(pairs) == 8 * 7 // 2
    within = pairs["scope"] == "within-axis"
    assert within.sum() == 2 * 6 and (~within).sum() == 16
    assert (pairs.loc[within, "axis_x"] == pairs.loc[within, "axis_y"]).all()
    assert (pairs.loc[~within, "axis_x"] != pairs.loc[~within, "axis_y"]).all()
    np.testing.assert_array_equal(pairs["c_diff"], found.networks[label].pairs["c_diff"])


def test_inspect_robot_evidence_columns(two_axes):
    recording = read_trace(two_axes, channels=MAP)
    nodes = ["A1.RP", "A1.MP", "A2.RP"]
    found = inspect_robot(recording, signals=nodes, evidence=True, backlash=False, delay=5,
                          evidence_options={"surrogates": 19, "resamples": 0})
    (pairs,) = found.pairs.values()
    assert {"coupling_p", "evidence", "scope"} <= set(pairs.columns)
    assert pairs["scope"].tolist() == ["within-axis", "between-axes", "between-axes"]


def test_inspect_command_on_a_file_of_several_axes(two_axes, tmp_path):
    out = tmp_path / "report"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = CliRunner().invoke(app, ["inspect", str(two_axes), "--channels",
                                          _map_file(tmp_path), "--no-evidence", "-o", str(out),
                                          "--quiet"])
    assert result.exit_code == 0, result.output
    robot = (out / "index.html").read_text()
    assert "What the robot does" in robot and "between-axes" in robot
    assert 'href="axis-1/index.html"' in robot and (out / "figures/robot-network-1.png").exists()
    for axis in (1, 2):
        assert "What the axis does" in (out / f"axis-{axis}" / "index.html").read_text()
    # --axis N: today's one-axis report of that axis.
    one = tmp_path / "one"
    result = CliRunner().invoke(app, ["inspect", str(two_axes), "--channels",
                                      _map_file(tmp_path), "--axis", "2", "--no-evidence",
                                      "-o", str(one), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "What the axis does" in (one / "index.html").read_text()
    assert not (one / "axis-2").exists()


def _map_file(folder: Path) -> str:
    path = folder / "map.toml"
    path.write_text("defaults = false\n[channels]\n"
                    + "".join(f'"{k}" = "{v}"\n' for k, v in MAP.items()))
    return str(path)


def test_robot_table_says_why_an_axis_has_no_lost_motion(tmp_path):
    # Axis 2 has no arm-side encoder (it reads all zeros, as on axes 4-6 of the KUKA runs): the
    # robot page's lost motion is a dash there with a note that says why, not a number or "nan".
    from funcnet.report.robot_summary import axis_findings

    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(5)
    rp = np.vstack([10 * np.sin(np.pi * t / 4) ** 2, -6 * np.sin(np.pi * t / 2) ** 2])
    mp = rp + 0.001 * rng.standard_normal(rp.shape)
    ap = mp - 0.01 * np.gradient(rp, t, axis=1)
    ap[1] = 0.0
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1)
    path = tmp_path / "no-ap.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "mp": mp, "tau": tau}})
    found = inspect_robot(read_trace(path, channels=MAP), evidence=False, delay=5)
    findings = axis_findings(found.axes, found.axis_errors, tuple(found.recording.axes),
                             found.source)
    rows = findings.table.set_index("axis")
    assert rows.loc["2", "lost motion [arcmin]"] == "—"
    notes = dict(findings.notes)
    assert notes["no lost motion: no AP"] == (2,)
    cited = [int(k) for k in rows.loc["2", "notes"].split(", ")]
    assert list(notes).index("no lost motion: no AP") + 1 in cited
    lost = rows.loc["1", "lost motion [arcmin]"]
    assert lost.startswith("≤ ") or float(lost) > 0
    # no cell says None or names the file
    for cell in findings.table.to_numpy().ravel():
        assert "None" not in cell and "nan" not in cell and str(path) not in cell


def _three_axes(folder: Path) -> Path:
    """Three axes moving alike (the same finding on each), each turning twice."""
    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(7)
    rp = np.vstack([(8 + k) * np.sin(2 * np.pi * t / 3 + k) for k in range(3)])
    mp = rp + 0.001 * rng.standard_normal(rp.shape)
    ap = mp - 0.01 * np.gradient(rp, t, axis=1) + 0.0005 * rng.standard_normal(rp.shape)
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1) + 0.05 * rng.standard_normal(
        rp.shape)
    path = folder / "three-axes.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "mp": mp, "tau": tau}})
    return path


def long_texts_said_more_than_twice(document: str) -> list[str]:
    """A plain reference: every cell, paragraph and item of more than 60 characters said more
    than twice on a page (numbers read as #)."""
    import re
    from collections import Counter
    from html.parser import HTMLParser

    class Blocks(HTMLParser):
        def __init__(self):
            super().__init__()
            self.open, self.texts = [], []

        def handle_starttag(self, tag, attrs):
            if tag in ("td", "th", "p", "li"):
                self.open.append("")

        def handle_endtag(self, tag):
            if tag in ("td", "th", "p", "li") and self.open:
                self.texts.append(" ".join(self.open.pop().split()))

        def handle_data(self, data):
            if self.open:
                self.open[-1] += data

    blocks = Blocks()
    blocks.feed(document)
    long = Counter(re.sub(r"[0-9.]+", "#", t) for t in blocks.texts if len(t) > 60)
    return [t for t, n in long.items() if n > 2]


def test_no_long_text_is_said_more_than_twice_on_a_robot_page(tmp_path):
    out = tmp_path / "report"
    result = CliRunner().invoke(app, ["inspect", str(_three_axes(tmp_path)), "--channels",
                                      _map_file(tmp_path), "-o", str(out), "--quiet",
                                      "--surrogates", "19", "--resamples", "20"])
    assert result.exit_code == 0, result.output
    for page in [out / "index.html", *sorted(out.glob("axis-*/index.html"))]:
        text = page.read_text()
        assert not long_texts_said_more_than_twice(text), page
    robot = (out / "index.html").read_text()
    # the three axes share their findings: said once, naming the axes
    assert "(axes 1, 2, 3)" in robot
    assert ">None<" not in robot and str(tmp_path) not in robot
