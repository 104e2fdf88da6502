"""The plan of experiments, the manifest, and the SINUMERIK writer read back by the trace reader."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pandas as pd
import pytest
from lxml import etree

import funcnet.sim.plan as plan_module
from funcnet.errors import ParameterError, SignalError, StudyError
from funcnet.robot.io.read import read_trace
from funcnet.sim.axis import AxisParameters, simulate_trial
from funcnet.sim.plan import MANIFEST_COLUMNS, paper_plan, read_plan, write_plan
from funcnet.sim.trial import Trial
from funcnet.sim.writer import role_names, write_trace


def documented_plan() -> str:
    """The plan file shown in the module's docstring: the documentation itself is tested."""
    block = plan_module.__doc__.split("::\n", 1)[1].split("\nEvery key", 1)[0]
    return textwrap.dedent(block)


@pytest.fixture(scope="module")
def paper_dir(tmp_path_factory):
    """The whole paper plan written once (a few seconds)."""
    out = tmp_path_factory.mktemp("paper")
    calls = []
    manifest = write_plan(paper_plan(), out, seed=3, progress=lambda *a: calls.append(a), workers=1)
    return out, manifest, calls


@pytest.fixture(scope="module")
def paper_simulations():
    """Every trial of the paper plan simulated with the seed of ``paper_dir`` (about 2 s)."""
    return {trial.name: simulate_trial(trial, seed=3) for trial in paper_plan()}


def test_paper_plan_is_table_1():
    plan = paper_plan()
    groups = pd.DataFrame([vars(t) for t in plan]).groupby("group")
    main = groups.get_group("main")
    assert len(main) == 27 and not main["reverse"].any()
    assert sorted(set(main["speed"])) == [35, 175, 350]
    assert sorted(set(main["step"])) == [1, 3, 10]
    assert len(main.drop_duplicates(["speed", "tcp", "step"])) == 27
    friction = groups.get_group("static-friction")
    assert len(friction) == 3 and set(friction["speed"]) == {1} and set(friction["step"]) == {1}
    backlash = groups.get_group("backlash")
    assert len(backlash) == 6 and backlash["reverse"].all() and set(backlash["step"]) == {1}
    assert sorted(set(backlash["speed"])) == [35, 175]
    for group in (main, friction, backlash):
        assert set(group["tcp"]) == {1.2, 1.6, 2.0}
    assert len({t.name for t in plan}) == 36


def test_every_paper_trace_reads_back_to_the_simulated_values(paper_dir, paper_simulations):
    out, manifest, calls = paper_dir
    table = pd.read_csv(manifest)
    assert list(table.columns) == list(MANIFEST_COLUMNS)
    assert [c[:2] for c in calls] == [(i, 36) for i in range(1, 37)]
    assert sorted(p.name for p in out.glob("*.xml")) == sorted(table["file"])
    for trial in paper_plan():
        recording = read_trace(out / f"{trial.name}.xml")
        assert recording.roles == role_names(1)
        assert recording.sample_period == pytest.approx(0.002)
        expected = paper_simulations[trial.name].data
        assert len(recording.data) == len(expected)
        np.testing.assert_allclose(recording.data.index, expected.index, atol=1e-9)
        for role in expected.columns:
            np.testing.assert_allclose(
                recording.data[role],
                expected[role],
                rtol=0,
                atol=5e-7 + 1e-12,
                err_msg=f"{trial.name} {role}",
            )


def test_every_paper_trial_ends_settled_at_its_target(paper_simulations):
    params = AxisParameters()
    count = 360 / params.arm_encoder_counts  # deg, one arm-encoder step
    motor_count = 360 / params.motor_encoder_counts / params.gear_ratio  # joint side
    for trial in paper_plan():
        sim = paper_simulations[trial.name]
        target = 0.0 if trial.reverse else trial.step
        tail = sim.data.iloc[-100:]  # the last 0.2 s
        assert sim.data["RP"].iloc[-1] == pytest.approx(target, abs=1e-12), trial.name
        # within a few encoder steps of the target, and still
        assert np.abs(tail["AP"] - target).max() <= 4 * count, trial.name
        assert tail["AP"].max() - tail["AP"].min() <= 2 * count, trial.name
        assert np.abs(sim.states["arm_velocity"].iloc[-100:]).max() < 1e-4, trial.name  # deg/s
        # the motor holds the gear wound up against the resting arm; its speed loop's integrator
        # still creeps it by a count or two (stick-slip against its own static friction)
        assert tail["MP"].max() - tail["MP"].min() <= 4 * motor_count, trial.name


def test_manifest_holds_parameters_and_ground_truth(paper_dir):
    _, manifest, _ = paper_dir
    table = pd.read_csv(manifest).set_index("name")
    base = table.loc["main-v35-p16-s3"]
    assert (base["speed"], base["tcp"], base["step"], base["seed"]) == (35, 1.6, 3, 3)
    assert base["backlash"] == 0.02 and math.isnan(base["lost_motion"])
    assert 0.1 < base["breakaway_time"] < 0.5
    reverse = table[table["reverse"]]
    assert len(reverse) == 6
    assert (reverse["lost_motion"] > reverse["backlash"]).all()
    np.testing.assert_allclose(
        reverse["lost_motion"],
        reverse["backlash"] + reverse["windup_forward"] + reverse["windup_reverse"],
        rtol=1e-9,
    )
    truth = simulate_trial(paper_plan()[-1], seed=3).truth
    assert table.loc[paper_plan()[-1].name, "lost_motion"] == truth["lost_motion"]


def test_rerun_skips_written_trials_and_rewrites_changed_ones(tmp_path):
    trials = [Trial("a", "main", 350, 1.2, 1), Trial("b", "backlash", 175, 1.2, 1, True)]
    manifest = write_plan(trials, tmp_path)
    before = {p.name: p.stat().st_mtime_ns for p in tmp_path.glob("*.xml")}
    first = manifest.read_bytes()
    calls = []
    write_plan(trials, tmp_path, progress=lambda *a: calls.append(a))
    assert {p.name: p.stat().st_mtime_ns for p in tmp_path.glob("*.xml")} == before
    assert manifest.read_bytes() == first
    assert [c[2] for c in calls] == ["a", "b"]
    # a damaged file is written again, to the same bytes; another seed changes the trace
    good = (tmp_path / "a.xml").read_bytes()
    (tmp_path / "a.xml").write_bytes(b"<broken/>")
    write_plan(trials, tmp_path)
    assert (tmp_path / "a.xml").read_bytes() == good
    write_plan(trials[:1], tmp_path, seed=1)
    assert (tmp_path / "a.xml").read_bytes() != good
    assert list(pd.read_csv(manifest)["name"]) == ["a"]


def test_processes_write_the_same_bytes(tmp_path):
    trials = [Trial(f"t{i}", "main", 350, 1.2, 1 + i) for i in range(3)]
    serial = write_plan(trials, tmp_path / "serial", workers=1)
    parallel = write_plan(trials, tmp_path / "parallel", workers=2)
    assert serial.read_bytes() == parallel.read_bytes()
    for trial in trials:
        name = f"{trial.name}.xml"
        assert (serial.parent / name).read_bytes() == (parallel.parent / name).read_bytes()


def test_write_plan_rejects_duplicate_names(tmp_path):
    with pytest.raises(ParameterError, match="unique"):
        write_plan([Trial("a", "g", 35, 1.2, 1)] * 2, tmp_path)


def test_read_plan_expands_groups(tmp_path):
    path = tmp_path / "plan.toml"
    path.write_text(documented_plan())
    trials = read_plan(path)
    assert len(trials) == 27 + 3 + 2 * 3
    plant = [t for t in trials if t.group == "plant-like"]
    assert [(t.noise_scale, t.seed) for t in plant] == [(n, s) for n in (1, 2) for s in (1, 2, 3)]
    assert {(t.sensors, t.arm_model, t.position_feedback) for t in plant} == {
        ("real", "elastic", "motor")
    }
    assert plant[4].name == "plant-like-v175-p20-s1-b0.0083333-n2-r2"
    main = {(t.speed, t.tcp, t.step) for t in trials if t.group == "main"}
    assert main == {(t.speed, t.tcp, t.step) for t in paper_plan() if t.group == "main"}
    worn = [t for t in trials if t.group == "worn-gear"]
    assert [t.backlash for t in worn] == [0.02, 0.05, 0.1]
    assert all(t.reverse and t.friction_scale == 1.5 and t.stiffness_scale == 0.7 for t in worn)
    assert worn[1].name == "worn-gear-v35-p16-s1-b0.05-f1.5-k0.7"


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("group = [", "not a valid TOML"),
        ("speeds = [1]", "list of \\[\\[group\\]\\]"),
        ('[[group]]\nname = "a"\ntcps = [1.6]\nsteps = [1]', "missing key 'speeds'"),
        ('[[group]]\nname = "a"\nspeeds = [1]\ntcps = [1.6]\nsteps = [1]\nspeed = 3', "unknown"),
        ('[[group]]\nname = "a"\nspeeds = ["fast"]\ntcps = [1.6]\nsteps = [1]', "'speeds'"),
        (
            '[[group]]\nname = "a"\nspeeds = [1]\ntcps = [1.6]\nsteps = [1]\ndirection = "back"',
            "'direction'",
        ),
        ('[[group]]\nname = "a"\nspeeds = [1, 1]\ntcps = [1.6]\nsteps = [1]', "twice"),
    ],
)
def test_read_plan_errors_name_file_and_key(tmp_path, text, match):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(StudyError, match=match) as info:
        read_plan(path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize(
    ("speeds", "match"),
    [("[-5]", "a-v-5-p16-s1: speed"), ("[35, 0.001]", "a-v0.001-p16-s1: the trace would span")],
)
def test_read_plan_rejects_values_out_of_range(tmp_path, speeds, match):
    path = tmp_path / "plan.toml"
    path.write_text(f'[[group]]\nname = "a"\nspeeds = {speeds}\ntcps = [1.6]\nsteps = [1]')
    with pytest.raises(ParameterError, match=match) as info:
        read_plan(path)
    assert str(info.value).startswith(f"{path}: group 1 (a): Trial ")


def test_read_plan_names_a_missing_file(tmp_path):
    with pytest.raises(StudyError, match="cannot read the plan") as info:
        read_plan(tmp_path / "absent.toml")
    assert str(tmp_path / "absent.toml") in str(info.value)


def test_write_plan_refuses_an_overlong_trial_before_writing(tmp_path):
    trials = [Trial("quick", "main", 350, 1.2, 1), Trial("slow", "main", 0.001, 1.2, 1)]
    with pytest.raises(ParameterError, match="Trial slow: the trace would span"):
        write_plan(trials, tmp_path / "out")
    assert not (tmp_path / "out").exists()


# --- the writer ----------------------------------------------------------------------------


def _records(path):
    root = etree.parse(str(path)).getroot()
    return root, [dict(rec.attrib) for rec in root.iter("rec")]


def test_writer_is_sparse_and_carries_values_forward(tmp_path):
    values = {"RP": [0.0, 0.0, 0.0, 1.0, 1.0], "AC": [0.5, 0.5000001, 0.5, 0.5, -0.0000001]}
    frame = pd.DataFrame(values, index=pd.Index(np.arange(5) * 0.002, name="time"))
    path = write_trace(tmp_path / "t.xml", frame, session_name='a&b <"c">', axis=3)
    root, records = _records(path)
    assert root.tag == "traceSession"
    assert root.find("traceCaptureSetup_V20/sessionSettings").get("sessionName") == 'a&b <"c">'
    rate = root.find("traceCaptureSetup_V20/sampleRateSettings")
    assert float(rate.get("servoSampleRate")) == 0.002
    header = root.find("traceData/dataFrame/frameHeader")
    assert header.get("stopInc") == "0.008000"
    signals = root.findall("traceData/dataFrame/dataSignal")
    assert [(s.get("id"), s.get("name"), s.get("datapointCount")) for s in signals] == [
        ("f1", "/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 3]", "5"),
        ("f2", "/Nck/!SD/nckServoDataActCurr32 [u1, 3]", "5"),
    ]
    # a value is written when it changes at six decimals; the last record repeats everything;
    # -0.000000 is written as 0.000000
    assert records == [
        {"time": "0.000000", "f1": "0.000000", "f2": "0.500000"},
        {"time": "0.006000", "f1": "1.000000"},
        {"time": "0.008000", "f1": "1.000000", "f2": "0.000000"},
    ]


def test_writer_rejects_bad_input(tmp_path):
    index = pd.Index([0.0, 0.002, 0.005], name="time")
    with pytest.raises(ParameterError, match="uniform"):
        write_trace(tmp_path / "t.xml", pd.DataFrame({"RP": [0.0, 1, 2]}, index=index))
    good = pd.Index([0.0, 0.002, 0.004], name="time")
    with pytest.raises(ParameterError, match="columns"):
        write_trace(tmp_path / "t.xml", pd.DataFrame({"XX": [0.0, 1, 2]}, index=good))
    with pytest.raises(SignalError, match="RP"):
        write_trace(tmp_path / "t.xml", pd.DataFrame({"RP": [0.0, np.nan, 2]}, index=good))
    assert not (tmp_path / "t.xml").exists()
