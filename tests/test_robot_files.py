"""A recording made of text files: a folder of one file per signal, a single RTDE log, units.

References are plain loops and arithmetic written here: the rows a file holds, the stamps the
files share, degrees as radians times 180 / pi.
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.errors import ChannelError, RecordingWarning, TraceFormatError
from funcnet.robot import read_recording, read_trace
from funcnet.robot.units import in_degrees

ROOT = Path(__file__).resolve().parents[1]
UR5_MAP = ROOT / "examples" / "ur5-channels.toml"
RTDE_MAP = ROOT / "examples" / "ur5-rtde-channels.toml"
RTDE_SAMPLE = ROOT / "tests" / "data" / "ur5-rtde-sample.csv"
runner = CliRunner()


def _rows(n: int, period: float, value) -> list[str]:
    return [", ".join([f"{k * period:.6f}", *(f"{value(k, j):.6f}" for j in range(6))])
            for k in range(n)]


def _q(k: int, j: int) -> float:
    """A set-point that goes out and back (a turn at tick 60) on every joint, in rad."""
    return 0.1 * j + 0.004 * (60 - abs(k - 60))


def _folder(tmp_path: Path, *, cut: bool = True) -> Path:
    """A UR-like run: q_target 120 rows, q_actual 110 rows, i_target 100 rows and a last line
    cut in the middle of a number, qd_actual 115 rows; start_time.csv not named by the map."""
    run = tmp_path / "run"
    run.mkdir()
    period = 0.008
    q = _rows(120, period, _q)
    (run / "log_q_target.csv").write_text("\n".join(q) + "\n")
    (run / "log_q_actual.csv").write_text(
        "\n".join(_rows(110, period, lambda k, j: _q(max(k - 2, 0), j))) + "\n")
    current = "\n".join(_rows(100, period, lambda k, j: 0.5 * math.copysign(1, 60 - k) + j))
    (run / "log_i_target.csv").write_text(current + ("\n0.80" if cut else "\n"))
    (run / "log_i_actual.csv").write_text(current + "\n")
    (run / "log_qd_actual.csv").write_text(
        "\n".join(_rows(115, period, lambda k, j: 0.5 if k < 60 else -0.5)) + "\n")
    (run / "log_qd_target.csv").write_text(
        "\n".join(_rows(115, period, lambda k, j: 0.5 if k < 60 else -0.5)) + "\n")
    (run / "log_m_target.csv").write_text(
        "\n".join(_rows(118, period, lambda k, j: 2.0 * j + k / 100)) + "\n")
    (run / "start_time.csv").write_text("1386431091.89\n" * 10)
    return run


def test_a_folder_of_files_joined_on_the_stamps_they_share(tmp_path):
    run = _folder(tmp_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rec = read_trace(run, channels=UR5_MAP, axis=2)
    said = [w.message for w in caught if isinstance(w.message, RecordingWarning)]
    problems = {w.problem: str(w) for w in said}
    # one line for the cut line, one for the trimmed ends: each names its files
    assert "log_i_target.csv ('0.80')" in problems["cut_line"]
    trimmed = problems["trimmed"]
    shortest = min(100, 110, 115, 118, 120)  # i_target and i_actual: 100 rows
    assert f"0-{(shortest - 1) * 0.008:g} s" in trimmed
    for name, rows in (("log_q_target.csv", 120), ("log_q_actual.csv", 110),
                       ("log_m_target.csv", 118)):
        assert f"{name} (last at {(rows - 1) * 0.008:g} s)" in trimmed
    assert "log_i_actual.csv (" not in trimmed  # it ends where the span ends
    assert "start_time" not in trimmed
    # the common span, joint 2 (the file's column 2), every value where it was written
    assert len(rec.data) == shortest
    assert rec.sample_period == 0.008 and rec.axis == 2
    assert list(rec.data.columns) == ["RP", "AP", "qd_target", "V", "RC", "AC", "m_target"]
    for k in (0, 37, shortest - 1):
        assert rec.data["RP"].iloc[k] == pytest.approx(_q(k, 1))
        assert rec.data["AP"].iloc[k] == pytest.approx(_q(max(k - 2, 0), 1))
        assert rec.data["m_target"].iloc[k] == pytest.approx(2.0 + k / 100)
    assert rec.signals["RP"].unit == "rad" and rec.signals["m_target"].unit == "N m"
    assert rec.roles["RC"] == "i_target(axis 2)"


def test_the_whole_arm_is_one_recording_of_qualified_columns(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        rec = read_trace(_folder(tmp_path, cut=False), channels=UR5_MAP)
    assert rec.axes == (1, 2, 3, 4, 5, 6)
    assert [c for c in rec.data.columns if c.endswith(".RP")] == [f"A{j}.RP" for j in range(1, 7)]
    for j in range(1, 7):  # joint j is the file's column j, after the time
        assert rec.data[f"A{j}.RP"].iloc[10] == pytest.approx(_q(10, j - 1))
    assert rec.for_axis(6).data["m_target"].iloc[3] == pytest.approx(2.0 * 5 + 0.03)


def test_folder_errors_name_the_file_column_and_axis(tmp_path):
    run = _folder(tmp_path, cut=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        with pytest.raises(ChannelError, match=r"axis 7 is not in the recording; it holds axes"):
            read_trace(run, channels=UR5_MAP, axis=7)
    (run / "log_m_target.csv").unlink()
    with pytest.raises(Exception, match=r"log_m_target.csv: no such file .*m_target"):
        read_trace(run, channels=UR5_MAP)
    (run / "log_m_target.csv").write_text("0.000, 1, 2, 3, 4, 5, 6\n0.008, 1, 2, x, 4, 5, 6\n")
    with pytest.raises(TraceFormatError, match=r"log_m_target.csv: line 2: column 3 holds 'x'"):
        read_trace(run, channels=UR5_MAP)
    with pytest.raises(TraceFormatError, match="is a directory.*\\[signals\\]"):
        read_trace(run)


def test_rtde_sample_read_by_its_header_names():
    rec = read_trace(RTDE_SAMPLE, channels=RTDE_MAP, axis=1)
    lines = RTDE_SAMPLE.read_text().splitlines()
    header = lines[0].split()
    first = [float(v) for v in lines[1].split()]
    last = [float(v) for v in lines[-1].split()]
    assert header[0] == "timestamp" and header[-1] == "actual_current_5"
    assert len(rec.data) == len(lines) - 1
    # the controller's uptime is read from the recording's start, its reading there kept
    assert rec.data.index[0] == 0.0 and rec.time_origin == pytest.approx(first[0])
    second = float(lines[2].split()[0])
    assert rec.data.index[1] == pytest.approx(second - first[0])
    assert rec.data["RP"].iloc[0] == first[header.index("target_q_0")]
    assert rec.data["AC"].iloc[-1] == last[header.index("actual_current_0")]
    assert rec.data["target_moment"].iloc[-1] == last[header.index("target_moment_0")]
    assert rec.signals["AC"].unit == "A"


def test_a_radian_log_is_converted_to_degrees_and_said(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        raw = read_trace(_folder(tmp_path, cut=False), channels=UR5_MAP, axis=1)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        deg, units = in_degrees(raw)
    assert np.allclose(deg.data["RP"], raw.data["RP"] * 180 / math.pi)
    assert np.allclose(deg.data["V"], raw.data["V"] * 180 / math.pi)
    assert deg.data["RC"].equals(raw.data["RC"])  # amperes stay amperes
    assert deg.signals["RP"].unit == "deg" and deg.signals["RP"].converted_from == "rad"
    assert deg.signals["V"].unit == "deg/s"
    assert units.position == "deg" and "RP (rad)" in units.note
    assert [w.message.problem for w in caught] == ["unit"]
    again, units_again = in_degrees(deg, warn=False)  # converted once, not twice
    assert again.data["RP"].equals(deg.data["RP"]) and units_again.converted == units.converted


def test_a_unit_that_is_no_angle_where_a_position_belongs_is_an_error(tmp_path):
    run = _folder(tmp_path, cut=False)
    bad = tmp_path / "bad.toml"
    bad.write_text(UR5_MAP.read_text().replace('q_target = "rad"', 'q_target = "N m"'))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        with pytest.raises(ChannelError, match=r"RP \(q_target\(axis 1\)\) holds N m; an angle"):
            read_recording(run, channels=bad, axis=1)


def test_a_table_without_units_is_unknown_and_said(tmp_path):
    path = tmp_path / "t.csv"
    t = np.arange(100) * 0.002
    path.write_text("time,RP,AP\n" + "\n".join(f"{a},{np.sin(a)},{np.sin(a)}" for a in t))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rec = read_recording(path, signals=["RP", "AP"])
    said = [str(w.message) for w in caught if getattr(w.message, "problem", None) == "unit"]
    assert len(said) == 1 and "no unit stated for RP, AP" in said[0]
    assert rec.data["RP"].iloc[50] == pytest.approx(np.sin(t[50]))  # computed as it was


def test_one_encoder_backlash_gives_what_the_data_hold(tmp_path):
    from funcnet.diagnosis import diagnose_backlash

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        result, = diagnose_backlash(_folder(tmp_path, cut=False), channels=UR5_MAP, axis=3)
    assert result.backlash_score is None and result.lost_motion is None
    assert "need a second encoder" in result.message
    turn, = result.reversals  # the set-point's one turn, at tick 60
    assert turn.change.stop <= 60 * 0.008 <= turn.change.start
    # the following error |RP - AP| near the turn, in degrees: a loop over the ticks
    t = np.arange(100) * 0.008
    peak = max(abs(_q(k, 2) - _q(max(k - 2, 0), 2)) for k in range(100)
               if turn.change.stop - 0.1 <= t[k] <= turn.change.start + 0.1)
    assert turn.indicators["following_error_peak"] == pytest.approx(peak * 180 / math.pi)
    # the current steps from +0.5 to -0.5 A across the turn
    assert turn.indicators["current_step"] == pytest.approx(-1.0)
    assert "converted from rad" in result.to_dict()["units"]


def test_cli_on_a_folder_and_its_one_line_errors(tmp_path):
    run = _folder(tmp_path)
    out = tmp_path / "b.json"
    result = runner.invoke(app, ["backlash", str(run), "--channels", str(UR5_MAP), "--axis", "2",
                                 "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "axis 2 (shoulder)" in result.stdout and "second encoder" in result.stdout
    assert "last line cut" in result.stderr and "files end at different times" in result.stderr
    written, = json.loads(out.read_text())["traces"]
    assert written["backlash_score"] is None and written["axis"] is None
    bad = runner.invoke(app, ["backlash", str(run), "--channels", str(UR5_MAP), "--axis", "9"])
    assert bad.exit_code == 2
    assert bad.stderr.count("\n") == 1 and "axis 9 is not in the recording" in bad.stderr
    bare = runner.invoke(app, ["network", str(run)])
    assert bare.exit_code == 2 and bare.stderr.count("\n") == 1
    assert "is a directory" in bare.stderr


def _resting(tmp_path: Path) -> Path:
    """A run in which the arm never moves: the set-point holds, AP jitters, currents hold."""
    run = tmp_path / "rest"
    run.mkdir()
    rng = np.random.default_rng(3)
    jitter = rng.normal(0, 2e-5, (400, 6))
    files = {
        "log_q_target.csv": lambda k, j: 0.3 * j,
        "log_q_actual.csv": lambda k, j: 0.3 * j + jitter[k, j],
        "log_qd_target.csv": lambda k, j: 0.0,
        "log_qd_actual.csv": lambda k, j: jitter[k, j] * 100,
        "log_i_target.csv": lambda k, j: 1.0 * j + jitter[k, j],
        "log_i_actual.csv": lambda k, j: 2.0 * j + jitter[k, j],
        "log_m_target.csv": lambda k, j: 3.0 * j + jitter[k, j],
    }
    for name, value in files.items():
        (run / name).write_text("\n".join(_rows(400, 0.008, value)) + "\n")
    return run, jitter


def test_an_arm_at_rest_gets_a_page_that_says_so(tmp_path):
    run, jitter = _resting(tmp_path)
    out = tmp_path / "page"
    result = runner.invoke(app, ["inspect", str(run), "--channels", str(UR5_MAP), "--axis", "3",
                                 "--no-evidence", "-q", "-o", str(out)])
    assert result.exit_code == 0, result.output
    page = (out / "index.html").read_text()
    assert "What axis 3 (elbow) does" in page
    assert "the set-point never moves: the axis rests over the whole recording" in page
    # |RP - AP| at rest in arcsec of the converted degrees, from the files as written
    rp = np.loadtxt(run / "log_q_target.csv", delimiter=",")[:, 3]
    ap = np.loadtxt(run / "log_q_actual.csv", delimiter=",")[:, 3]
    mean = np.mean(np.abs(rp - ap)) * 180 / math.pi * 3600
    assert f"|RP − AP| {mean:.3g} arcsec on average" in page
    assert "AC 4 A on average" in page  # 2.0 * j with j = 2, as written


def test_a_robot_at_rest_gets_its_pages_with_their_figures(tmp_path):
    # The whole arm never moves: the robot's page and every axis's page, each axis's motion
    # figure showing what it measured at rest (not an empty frame); the conversion from rad
    # said once on the robot's page, as the map's units state it.
    import tomllib

    from PIL import Image

    run, _ = _resting(tmp_path)
    out = tmp_path / "page"
    result = runner.invoke(app, ["inspect", str(run), "--channels", str(UR5_MAP),
                                 "--no-evidence", "-q", "-o", str(out)])
    assert result.exit_code == 0, result.output
    robot = (out / "index.html").read_text()
    spec = tomllib.loads(UR5_MAP.read_text())
    roles = {spec["channels"][name]: unit for name, unit in spec["units"].items()
             if name in spec["channels"] and unit.startswith("rad")}
    said = ("Converted to degrees (deg/s) from the unit the file holds: "
            + ", ".join(f"{role} ({unit})" for role, unit in roles.items())
            + " on axes 1, 2, 3, 4, 5, 6.")
    assert list(roles) == ["RP", "AP", "V"]
    assert robot.count(said) == 1
    for axis in range(1, 7):
        page = (out / f"axis-{axis}" / "index.html").read_text()
        assert "the whole trace (the axis never moves)" in page
        image = np.asarray(Image.open(out / f"axis-{axis}" / "figures" / "motion.png"))
        # the lower half holds the panels at rest: drawn, not left white
        lower = image[image.shape[0] // 2:, :, :3]
        assert (lower < 200).any(axis=2).mean() > 0.01


def test_the_motion_figure_at_rest_draws_the_whole_trace():
    import pandas as pd

    from funcnet.inspection import inspect_recording
    from funcnet.report.inspect_figures import figure_motion
    from funcnet.robot import Recording, SignalInfo

    t = np.arange(0, 2, 0.004)
    rng = np.random.default_rng(1)
    data = pd.DataFrame({"RP": np.full(t.size, 12.0), "AP": 12.0 + 1e-4 * rng.standard_normal(
        t.size), "AC": 3.0 + 1e-3 * rng.standard_normal(t.size)},
        index=pd.Index(t.round(9), name="time"))
    info = {c: SignalInfo(c, "posn", "double", 0.004) for c in data}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ins = inspect_recording(Recording(data, {}, info, source="rest.csv",
                                          sample_period=0.004), evidence=False)
    assert len(ins.moves) == 0
    fig = figure_motion(ins)
    top, *panels = fig.axes
    assert [ax.get_ylabel().split(" [")[0] for ax in panels] == ["position", "V", "AC",
                                                                 "RP − AP"]
    assert panels[0].get_title(loc="left").startswith("(b) no move: at rest over 0.00")
    for ax in panels:  # every sample of the trace, not a zoom on a move
        for line in ax.lines:
            assert len(line.get_xdata()) == t.size
    ap = next(line for line in panels[0].lines if line.get_label() == "AP")
    assert np.allclose(ap.get_ydata(), data["AP"].to_numpy())


def test_network_leaves_out_phases_too_short_for_the_embedding(tmp_path):
    from funcnet.robot import detect_phases, phase_windows

    run = _folder(tmp_path, cut=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        rec = read_recording(run, channels=UR5_MAP, axis=1)
    windows = list(phase_windows(detect_phases(rec)))
    need = (3 - 1) * 5 + 7  # dim 3, delay 5
    lengths = {w.label: int(round((w.stop - w.start) / rec.sample_period)) for w in windows}
    short = [label for label, n in lengths.items() if n < need]
    assert short and len(short) < len(windows)  # the case is there to test
    out = tmp_path / "net.json"
    result = runner.invoke(app, ["network", str(run), "--channels", str(UR5_MAP), "--axis", "1",
                                 "--delay", "5", "--signals", "RP,AP",
                                 "-o", str(out)])
    assert result.exit_code == 0, result.output
    line, = [x for x in result.stderr.splitlines() if f"shorter than the {need} samples" in x]
    for label in short:
        assert f"{label!r} ({lengths[label]} samples)" in line
    assert len(list(tmp_path.glob("net-*.json"))) == len(windows) - len(short)


def test_detrended_without_mp_leaves_torsion_out_before_computing(tmp_path):
    from funcnet.inspection import inspect_recording

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        rec, _ = in_degrees(read_trace(_folder(tmp_path, cut=False), channels=UR5_MAP, axis=1))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        found = inspect_recording(rec, signals=["FE", "TORSION", "V", "RC", "AC"],
                                  evidence=False, backlash=False, delay=2)
    assert found.signals == ("FE", "V", "RC", "AC")
    said = [w.message for w in caught if getattr(w.message, "problem", "") == "missing_signal"]
    assert len(said) == 1 and "TORSION (MP - AP) needs MP" in str(said[0])


def test_a_study_skips_and_lists_windows_where_the_arm_stands_still(tmp_path):
    run = _folder(tmp_path, cut=False)
    rest, _ = _resting(tmp_path)
    study = tmp_path / "study.toml"
    study.write_text(
        'signals = ["RP", "AP", "AC"]\n[recordings]\n'
        f'paths = ["{run.name}", "{rest.name}"]\n'
        f'channels = "{UR5_MAP}"\naxis = 1\n'
        '[[windows]]\nkind = "range"\nstart = 0.0\nstop = 0.79\n'
        '[network]\ndelay = 2\n')
    out = tmp_path / "out"
    result = runner.invoke(app, ["study", str(study), "--out", str(out), "-q"])
    assert result.exit_code == 0, result.output
    run_record = json.loads((out / "study.json").read_text())["run"]
    assert run_record["failures"] == []
    skipped, = run_record["skipped"]
    assert skipped["recording"].startswith("rest") and "stands still" in skipped["message"]
    assert "skipped: 1 window(s) where the axis stands still" in result.stderr


def test_repetitions_say_why_a_move_was_not_taken():
    import pandas as pd

    from funcnet.robot import Recording, SignalInfo, find_repetitions

    t = np.arange(0, 12, 0.01)

    def ramp(t0, length):  # a move up of ``length`` seconds at constant speed, then a rest
        return np.clip(t - t0, 0, length)

    rp = ramp(0.5, 1.5) + ramp(3.0, 1.5) + ramp(6.0, 3.0)  # two alike, one twice as long
    data = pd.DataFrame({"RP": rp, "AC": np.gradient(rp)}, index=pd.Index(t.round(9), name="time"))
    rec = Recording(data, {}, {c: SignalInfo(c, None, None, 0.01) for c in data},
                    sample_period=0.01)
    found = find_repetitions(rec)
    assert len(found) == 2 and found.others == 1
    why, = found.left_out
    import re

    assert why.startswith("recording 1 move 3: ") and "more than 2%" in why
    theirs, first = map(int, re.findall(r"(\d+) samples long against (\d+)", why)[0])
    # the moves as written, 3.0 s and 1.5 s at 10 ms, give or take their edge samples
    assert abs(theirs - 300) <= 4 and abs(first - 150) <= 4


def test_files_that_start_late_are_read_from_the_first_stamp_all_share(tmp_path):
    from funcnet.robot.io.channels import ChannelMap
    from funcnet.robot.io.layout import signal_files
    from funcnet.robot.io.signal_files import read_signal_files

    (tmp_path / "q.csv").write_text("".join(f"{k * 0.008:.3f}, {k}\n" for k in range(6)))
    (tmp_path / "i.csv").write_text("".join(f"{k * 0.008:.3f}, {10 * k}\n" for k in range(2, 8)))
    files = signal_files({"q": "q.csv", "i": "i.csv"}, {"columns": [1]}, "m.toml")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        grid = read_signal_files(tmp_path, ChannelMap({"q": "RP"}, files=files), None)
    said, = [str(w.message) for w in caught]
    assert "files start and end at different times" in said
    assert "q.csv (first at 0 s)" in said and "i.csv (last at 0.056 s)" in said
    # ticks 2-5 are the ones both files hold: a plain loop over them
    assert grid.t0 == pytest.approx(0.016)
    assert grid.values.tolist() == [[float(k), 10.0 * k] for k in range(2, 6)]
