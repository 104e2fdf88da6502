"""``funcnet network`` on recordings of several axes: the KUKA KR 300 runs with a channel map;
a UR5 run whose current set-point is constant in one window."""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

from conftest import KUKA, shipped
from funcnet.cli import app

ROOT = Path(__file__).resolve().parents[1]
RUN = KUKA / "kr300-run-A.mat"
KUKA_MAP = ROOT / "examples" / "kuka-kr300-channels.toml"

runner = CliRunner()


def _library_pairs(signals, window, axis=None) -> pd.DataFrame:
    from funcnet import window_networks
    from funcnet.robot import Window, read_recording

    recording = read_recording(RUN, channels=KUKA_MAP, axis=axis, signals=signals)
    chosen = Window("w", *window)
    return window_networks(recording, [chosen], signals=signals)["w"].pairs


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_network_of_every_axis_with_qualified_nodes(tmp_path):
    out = tmp_path / "net.csv"
    nodes = "A1.RP,A1.MP,A2.RP,A2.V"
    result = runner.invoke(app, ["network", str(RUN), "--channels", str(KUKA_MAP),
                                 "--signals", nodes, "--window", "2:3", "-o", str(out)])
    assert result.exit_code == 0, result.output
    pairs = pd.read_csv(out)
    expected = _library_pairs(nodes.split(","), (2.0, 3.0))
    assert list(pairs["x"]) == list(expected["x"]) and list(pairs["y"]) == list(expected["y"])
    pd.testing.assert_series_equal(pairs["c_diff"], expected["c_diff"], check_names=False,
                                   rtol=0, atol=1e-15)
    # The constant channels the reader left out are said in one line, not merely counted.
    said = [line for line in result.stderr.splitlines() if "constant over the whole" in line]
    assert len(said) == 1 and "A4.AP = 0" in said[0]


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_network_default_nodes_of_a_multi_axis_file_are_every_axis_roles(tmp_path):
    out = tmp_path / "net.csv"
    result = runner.invoke(app, ["network", str(RUN), "--channels", str(KUKA_MAP),
                                 "--window", "1:1.6", "-o", str(out)])
    assert result.exit_code == 0, result.output
    pairs = pd.read_csv(out)
    nodes = list(dict.fromkeys([*pairs["x"], *pairs["y"]]))
    # RP, MP and the torque of six axes, AP of axes 1-3: 21 nodes, grouped per axis.
    assert nodes == ["A1.RP", "A1.AP", "A1.MP", "A1.AC", "A2.RP", "A2.AP", "A2.MP", "A2.AC",
                     "A3.RP", "A3.AP", "A3.MP", "A3.AC", "A4.RP", "A4.MP", "A4.AC",
                     "A5.RP", "A5.MP", "A5.AC", "A6.RP", "A6.MP", "A6.AC"]
    assert len(pairs) == 21 * 20 // 2


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_network_of_one_axis_is_a_one_axis_network(tmp_path):
    out = tmp_path / "net.csv"
    result = runner.invoke(app, ["network", str(RUN), "--channels", str(KUKA_MAP), "--axis", "2",
                                 "--window", "2:3", "-o", str(out)])
    assert result.exit_code == 0, result.output
    pairs = pd.read_csv(out)
    expected = _library_pairs(None, (2.0, 3.0), axis=2)
    assert set(pairs["x"]) | set(pairs["y"]) == {"RP", "AP", "MP", "V", "AC"}
    pd.testing.assert_series_equal(pairs["t_diff"], expected["t_diff"], check_names=False,
                                   rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    ("options", "needles"),
    [
        (["--phase", "cruise"], ["holds axes 1-6", "give --axis N"]),
        (["--list-phases"], ["holds axes 1-6", "give --axis N"]),
        (["--axis", "8"], ["axis 8 is not in the file; it holds axes 1-6"]),
        (["--signals", "A1.RP,A7.MP"], ["--signals: A7.MP not in kr300-run-A.mat"]),
    ],
)
def test_network_multi_axis_errors_are_one_line(options, needles):
    result = runner.invoke(app, ["network", str(RUN), "--channels", str(KUKA_MAP), *options])
    assert result.exit_code == 2, result.output
    errors = [line for line in result.stderr.splitlines() if line.startswith("funcnet: error:")]
    assert len(errors) == 1 and "Traceback" not in result.output
    for needle in needles:
        assert needle in errors[0]


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_backlash_of_every_axis_is_each_axis_on_its_own(tmp_path):
    import json

    from funcnet.diagnosis import diagnose_backlash

    every = diagnose_backlash(RUN, channels=KUKA_MAP)
    assert [r.axis for r in every] == [1, 2, 3, 4, 5, 6]
    for result in every[::2]:
        (alone,) = diagnose_backlash(RUN, channels=KUKA_MAP, axis=result.axis)
        assert alone.axis is None
        assert {**result.to_dict(), "axis": None} == alone.to_dict()
    # AP on 1-3 only: a lost motion or its bound there, none without AP
    assert [r.lost_motion_high is None for r in every] == [False] * 3 + [True] * 3
    out = tmp_path / "b.json"
    result = runner.invoke(app, ["backlash", str(RUN), "--channels", str(KUKA_MAP), "-o", str(out)])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert [line.split(": ")[0] for line in lines if line.startswith(str(RUN))] == [
        f"{RUN} axis {n}" for n in range(1, 7)]
    entries = json.loads(out.read_text())["traces"]
    assert [entry["axis"] for entry in entries] == [1, 2, 3, 4, 5, 6]


# --------------------------------------------------------------------------------------------
# a signal constant in one window of a real run: left out of that window, said in one line

UR5_MAP = ROOT / "examples" / "ur5-channels.toml"


@pytest.fixture(scope="module")
def ur5_constant_rc(tmp_path_factory) -> Path:
    """The shipped UR5 run No8 with joint 6's current set-point held at 0 through its last
    braking (15.2-15.75 s), as other UR5 runs log it: RC constant in that window alone."""
    import shutil

    source = shipped("ur5", "Movement_No8_Singularity_Free_1")
    run = tmp_path_factory.mktemp("ur5") / source.name
    shutil.copytree(source, run)
    path = run / "log_i_target.csv"
    rows = [line.split(", ") for line in path.read_text().splitlines()]
    for fields in rows:
        if 15.2 <= float(fields[0]) <= 15.75:
            fields[6] = "0.000000"
    path.write_text("".join(", ".join(fields) + "\n" for fields in rows))
    return run


def _left_out(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if "constant inside the window" in line]


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_network_leaves_a_signal_constant_in_one_window_out_of_it(ur5_constant_rc, tmp_path):
    from funcnet.network import FunctionalNetwork

    arguments = ["network", str(ur5_constant_rc), "--channels", str(UR5_MAP), "--axis", "6"]
    strict = runner.invoke(app, [*arguments, "--strict-constant"])
    assert strict.exit_code == 2, strict.output
    assert "window 'braking 4'" in strict.stderr
    assert "signal 'RC' is constant (value 0)" in strict.stderr
    out = tmp_path / "net.json"
    result = runner.invoke(app, [*arguments, "-o", str(out)])
    assert result.exit_code == 0, result.output
    (said,) = _left_out(result.stderr)
    assert said.startswith(f"funcnet: warning: {ur5_constant_rc}: constant inside the window, ")
    assert "--strict-constant makes it an error" in said
    assert re.search(r"in 1 of \d+ window\(s\): 'braking 4' \(RC\)$", said), said
    braking = FunctionalNetwork.read(tmp_path / "net-braking-4.json")
    assert "RC" not in braking.nodes and tuple(braking.window["dropped"]) == ("RC",)
    cruise = FunctionalNetwork.read(tmp_path / "net-cruise-4.json")
    assert "RC" in cruise.nodes and tuple(cruise.window["dropped"]) == ()


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_stability_leaves_a_signal_constant_in_one_window_out_of_it(ur5_constant_rc, tmp_path):
    arguments = ["stability", str(ur5_constant_rc), "--channels", str(UR5_MAP), "--axis", "6",
                 "--phase", "braking 4", "--vary", "mu=0.1"]
    strict = runner.invoke(app, [*arguments, "--strict-constant"])
    assert strict.exit_code == 2 and "'RC' is constant" in strict.stderr, strict.output
    out = tmp_path / "stability.csv"
    result = runner.invoke(app, [*arguments, "-o", str(out)])
    assert result.exit_code == 0, result.output
    (said,) = _left_out(result.stderr)
    assert said.endswith("in 1 of 1 window(s): 'braking 4' (RC)"), said
    table = pd.read_csv(out)
    assert len(table) > 0 and "RC" not in set(table["x"]) | set(table["y"])
