"""Linear axes: positions in m, mm, um; following error and lost motion in um.

The reference for the two-encoder lost motion of a linear axis is the same simulated trace read
as a rotary axis: written once in degrees and once as metres (the numbers divided by 1000, stated
``m``), the lengths come out in mm with the very numbers the angles have in degrees, so a linear
axis's lost motion in um is 1000 times the rotary one's in degrees. The MCS500's joint 3 is
checked against its own CSV, read by numpy.
"""

from __future__ import annotations

import json
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.errors import ChannelError, RecordingWarning
from funcnet.robot import read_trace
from funcnet.robot.recording import Recording
from funcnet.robot.signals import SignalInfo
from funcnet.robot.units import axis_scale, in_axis_units, position_unit, to_axis_unit

ROOT = Path(__file__).resolve().parents[1]
MCS500 = ROOT / "data" / "mecademic-mcs500" / "mcs500-two-cycles.csv"
MCS500_MAP = ROOT / "examples" / "mecademic-channels.toml"
runner = CliRunner()


def _one(column: str, unit: str, values: list[float]) -> Recording:
    data = pd.DataFrame({column: values},
                        index=pd.Index(0.002 * np.arange(len(values)), name="time"))
    return Recording(data, {}, {column: SignalInfo(column, None, None, 0.002, unit)},
                     sample_period=0.002)


# -- the units ---------------------------------------------------------------------------------


@pytest.mark.parametrize(("unit", "factor", "target"), [
    ("m", 1000.0, "mm"), ("mm", 1.0, "mm"), ("um", 1e-3, "mm"), ("µm", 1e-3, "mm"),
    ("m/s", 1000.0, "mm/s"), ("mm/min", 1 / 60, "mm/s"), ("rad", 180 / math.pi, "deg"),
])
def test_lengths_and_angles_come_to_the_axis_unit(unit, factor, target):
    assert to_axis_unit(unit) == (pytest.approx(factor), target)
    column = "V" if "/" in unit else "RP"
    rec, units = in_axis_units(_one(column, unit, [0.0, 1.0, 3.0]), warn=False)
    assert rec.data[column].tolist() == pytest.approx([0.0, factor, 3 * factor])
    assert rec.signals[column].unit == target


def test_an_axis_mixing_angles_and_lengths_is_refused():
    data = pd.DataFrame({"RP": [0.0, 1.0], "AP": [0.0, 1.0]},
                        index=pd.Index([0.0, 0.002], name="time"))
    rec = Recording(data, {}, {"RP": SignalInfo("q", None, None, 0.002, "deg"),
                               "AP": SignalInfo("z", None, None, 0.002, "mm")},
                    sample_period=0.002)
    with pytest.raises(ChannelError, match="either turns or slides"):
        in_axis_units(rec, warn=False)


def test_a_force_stands_where_a_current_does():
    rec, _ = in_axis_units(_one("AC", "N", [0.0, 2.0]), warn=False)
    assert rec.signals["AC"].unit == "N" and rec.data["AC"].tolist() == [0.0, 2.0]


def test_a_linear_axis_states_small_lengths_in_um():
    assert (axis_scale("mm").fine, axis_scale("mm").coarse) == ("um", "um")
    assert (axis_scale("deg").fine, axis_scale("deg").coarse) == ("arcsec", "arcmin")


# -- a simulated axis, read as rotary and as linear ------------------------------------------


@pytest.fixture(scope="module")
def twin_traces(tmp_path_factory):
    """One simulated reversal with backlash, as a rotary axis (deg) and a linear one (m)."""
    from funcnet.sim.axis import simulate_trial
    from funcnet.sim.trial import Trial

    root = tmp_path_factory.mktemp("twin")
    sim = simulate_trial(Trial(name="t", group="g", speed=175, tcp=1.6, step=1, reverse=True,
                               seed=3, backlash=0.05))
    data = sim.data[["RP", "AP", "MP", "AC"]]
    rotary = root / "rotary.csv"
    data.to_csv(rotary, index_label="time", float_format="%.9g")
    linear = root / "linear.csv"
    data.assign(RP=data["RP"] / 1000, AP=data["AP"] / 1000, MP=data["MP"] / 1000).to_csv(
        linear, index_label="time", float_format="%.12g")
    rotary_map = root / "rotary.toml"
    rotary_map.write_text('[units]\nRP = "deg"\nAP = "deg"\nMP = "deg"\nAC = "A"\n')
    linear_map = root / "linear.toml"
    linear_map.write_text('[units]\nRP = "m"\nAP = "m"\nMP = "m"\nAC = "A"\n')
    return root, (rotary, rotary_map), (linear, linear_map)


def _backlash_json(trace: Path, cmap: Path, out: Path) -> dict:
    result = runner.invoke(app, ["backlash", str(trace), "--channels", str(cmap), "-o", str(out)])
    assert result.exit_code == 0, result.output
    return json.loads(out.read_text())["traces"][0] | {"_output": result.output}


def test_a_linear_axis_gets_its_lost_motion_in_um_in_the_json(twin_traces):
    root, (rotary, rotary_map), (linear, linear_map) = twin_traces
    deg = _backlash_json(rotary, rotary_map, root / "rotary.json")
    mm = _backlash_json(linear, linear_map, root / "linear.json")
    assert deg["position_unit"] == "deg" and deg["length_unit"] == "deg"
    assert mm["position_unit"] == "mm" and mm["length_unit"] == "um"
    assert deg["lost_motion"] is not None and deg["lost_motion"] > 0
    assert mm["lost_motion"] == pytest.approx(1000 * deg["lost_motion"], rel=1e-6)
    for a, b in zip(deg["reversals"], mm["reversals"], strict=True):
        if a["lost_motion"] is not None:
            assert b["lost_motion"] == pytest.approx(1000 * a["lost_motion"], rel=1e-6)
    # the calibration was made on rotary axes: read on the rotary twin, not on the linear one
    assert mm["reading"] is None and "linear axis" in mm["reading_reason"]
    shown = re.search(r"lost_motion ([\d.]+)", mm["_output"])
    assert shown and " um" in mm["_output"].splitlines()[1]
    assert float(shown.group(1)) == pytest.approx(1000 * deg["lost_motion"], abs=0.006)


def test_a_linear_axis_page_states_um_and_mm_per_s(twin_traces, tmp_path):
    root, _, (linear, linear_map) = twin_traces
    result = runner.invoke(app, ["inspect", str(linear), "--channels", str(linear_map),
                                 "--no-evidence", "-o", str(tmp_path / "page"), "-q"])
    assert result.exit_code == 0, result.output
    page = (tmp_path / "page" / "index.html").read_text()
    assert "lost motion [um]" in page and "peak |FE| [um]" in page and "mm/s" in page
    assert "arcsec" not in page.split("Parameters and provenance")[0]
    rec, _ = in_axis_units(read_trace(linear, channels=linear_map), warn=False)
    fe = (rec.data["RP"] - rec.data["AP"]).abs().max() * 1000  # um, from the file itself
    peak = re.search(r"peak following error \|RP − AP\| ([\d.]+) um", page)
    assert peak and float(peak.group(1)) == pytest.approx(fe, rel=2e-3)


# -- the MCS500: joint 3 is a vertical linear axis in mm --------------------------------------


def test_the_mcs500_keeps_a_unit_per_axis():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        rec = read_trace(MCS500, channels=MCS500_MAP)
    units = {column: info.unit for column, info in rec.signals.items()}
    assert units == {f"A{n}.{role}": ("mm" if n == 3 else "deg")
                     for n in (1, 2, 3, 4) for role in ("RP", "AP")}
    assert position_unit(rec.signals, axis=3) == "mm"
    assert position_unit(rec.signals, axis=1) == "deg"


def test_the_mcs500_pages_say_its_clock_turns_and_joint_3_in_mm(tmp_path):
    out = tmp_path / "mcs500"
    result = runner.invoke(app, ["inspect", str(MCS500), "--channels", str(MCS500_MAP),
                                 "--no-evidence", "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    page = (out / "index.html").read_text()
    assert "1.697 s sampled every 1 ms" in page and "107742.743" in page
    rows = pd.read_html(str(out / "index.html"), match="direction changes")[0]
    rows = rows.set_index("axis")
    assert rows.loc[1, "direction changes"] == 3
    assert rows.loc[3, "peak speed"].endswith("mm/s") and rows.loc[3, "peak following error"
                                                                   ].endswith("um")
    assert rows.loc[1, "peak speed"].endswith("°/s") and rows.loc[1, "peak following error"
                                                                  ].endswith("arcmin")
    # joint 3's peak following error against the file: |RP - AP| over its moves, mm -> um
    raw = pd.read_csv(MCS500, skipinitialspace=True)
    fe = (raw["TargetJointPos_2"] - raw["JointPos_2"]).abs().max() * 1000
    assert float(rows.loc[3, "peak following error"].split()[0]) == pytest.approx(fe, rel=2e-3)
    joint3 = (out / "axis-3" / "index.html").read_text()
    assert "peak |FE| [um]" in joint3
    assert re.search(r"peak set-point speed [\d.]+ mm/s", joint3)


def test_the_mcs500_joint_3_alone_and_its_backlash_json(tmp_path):
    out = tmp_path / "joint3"
    result = runner.invoke(app, ["inspect", str(MCS500), "--channels", str(MCS500_MAP),
                                 "--axis", "3", "--no-evidence", "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    page = (out / "index.html").read_text()
    assert "peak |FE| [um]" in page and "distance [mm]" in page
    assert "It changes direction 3 time(s)" in page
    json_out = tmp_path / "b.json"
    result = runner.invoke(app, ["backlash", str(MCS500), "--channels", str(MCS500_MAP),
                                 "-o", str(json_out)])
    assert result.exit_code == 0, result.output
    traces = {t["axis"]: t for t in json.loads(json_out.read_text())["traces"]}
    assert traces[3]["position_unit"] == "mm" and traces[3]["length_unit"] == "um"
    assert traces[1]["position_unit"] == "deg"
    raw = pd.read_csv(MCS500, skipinitialspace=True)
    t = (raw["timestamp"] - raw["timestamp"][0]) * 1e-6
    fe = (raw["TargetJointPos_2"] - raw["JointPos_2"]).abs().to_numpy()
    for change in traces[3]["reversals"]:
        # the reference: |RP - AP| within 0.1 s of the turn, from the file, mm -> um
        near = (t >= change["stop"] - 0.1) & (t <= change["start"] + 0.1)
        expected = fe[near.to_numpy()].max() * 1000
        assert change["indicators"]["following_error_peak"] == pytest.approx(expected,
                                                                             rel=1e-6)
    assert "um" in result.output
