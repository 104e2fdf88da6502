"""A robot's runs kept and trended (funcnet.track): the store, the detector, the commands."""

from __future__ import annotations

import json
import math
import os
import sqlite3
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.track import store as kept
from funcnet.track.add import RunTask, _time, iso_time
from funcnet.track.detect import DRIFT, LEARN, LEVEL, detect_changes

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
UR5_MAP = ROOT / "examples" / "ur5-channels.toml"
runner = CliRunner()


def _row(robot: str, checksum: str, day: int = 1) -> kept.RunRow:
    return kept.RunRow(robot, f"2026-01-{day:02d}T08:00:00+00:00", "given", "P-1",
                       f"run-{checksum}.xml", checksum)


# --------------------------------------------------------------------------------------------
# the store


def test_a_run_is_kept_once_per_robot_and_once_per_robot_only(tmp_path: Path) -> None:
    path = tmp_path / "fleet.sqlite"
    with kept.open_store(path) as db:
        assert kept.add_run(db, _row("r1", "abc"), {(1, "lost_motion"): 0.5})
        assert not kept.add_run(db, _row("r1", "abc", day=2), {(1, "lost_motion"): 0.9})
        assert kept.add_run(db, _row("r2", "abc"), {(1, "lost_motion"): 0.7})
    runs = kept.read_runs(path)
    assert sorted(runs["robot"]) == ["r1", "r2"]
    figures = kept.read_figures(path, "r1")
    assert figures["value"].tolist() == [0.5]  # the second add wrote nothing


def test_a_crash_mid_write_leaves_the_store_as_it_was(tmp_path: Path) -> None:
    path = tmp_path / "fleet.sqlite"
    with kept.open_store(path) as db:
        kept.add_run(db, _row("r1", "first"), {(1, "lost_motion"): 0.5})
    # A process killed inside its transaction: the run row and some figures written, no commit.
    code = (
        "import os, sqlite3\n"
        f"db = sqlite3.connect({str(path)!r}, isolation_level=None)\n"
        "db.execute('BEGIN IMMEDIATE')\n"
        "db.execute(\"INSERT INTO runs (robot, time, time_from, program, source, checksum) \"\n"
        "           \"VALUES ('r1', '2026-01-02', 'given', 'P-1', 'x', 'second')\")\n"
        "db.execute('INSERT INTO figures VALUES (2, 1, \"lost_motion\", 9.0)')\n"
        "os._exit(9)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], timeout=60)
    assert result.returncode == 9
    runs = kept.read_runs(path)
    assert runs["checksum"].tolist() == ["first"]
    assert kept.read_figures(path)["value"].tolist() == [0.5]
    with kept.open_store(path) as db:  # and the store takes the next run
        assert kept.add_run(db, _row("r1", "second", day=2), {(1, "lost_motion"): 0.6})


def test_an_error_inside_a_write_rolls_the_whole_run_back(tmp_path: Path) -> None:
    path = tmp_path / "fleet.sqlite"
    with kept.open_store(path) as db:
        # the run row and its figures are written before the trace, which cannot be bound
        with pytest.raises(sqlite3.Error):
            kept.add_run(db, _row("r1", "a"), {(1, "lost_motion"): 0.5},
                         trace=object())  # type: ignore[arg-type]
    assert kept.read_runs(path).empty and kept.read_figures(path).empty


_WRITER = """
import sys
from funcnet.track import store as kept
path, robot, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
for k in range(n):
    row = kept.RunRow(robot, f"2026-01-01T00:00:{k:02d}+00:00", "given", "P-1", f"{k}.xml",
                      f"{robot}-{k}")
    with kept.open_store(path) as db:
        assert kept.add_run(db, row, {(a, "lost_motion"): float(k) for a in range(1, 7)},
                            trace=bytes(20000))
"""


def test_two_processes_writing_at_once_both_land(tmp_path: Path) -> None:
    path = tmp_path / "fleet.sqlite"
    with kept.open_store(path):
        pass
    writers = [subprocess.Popen([sys.executable, "-c", _WRITER, str(path), robot, "40"],
                                env=ENV) for robot in ("left", "right")]
    assert [w.wait(timeout=120) for w in writers] == [0, 0]
    runs = kept.read_runs(path)
    assert runs.groupby("robot").size().to_dict() == {"left": 40, "right": 40}
    assert len(kept.read_figures(path)) == 80 * 6


def test_a_file_that_is_no_store_is_refused_in_one_line(tmp_path: Path) -> None:
    path = tmp_path / "notes.txt"
    path.write_text("not a database, " * 100)
    with pytest.raises(Exception, match="not a funcnet store"):
        kept.read_runs(path)


# --------------------------------------------------------------------------------------------
# the run's time


def test_the_time_given_then_the_files_own_then_its_modification_time(tmp_path: Path) -> None:
    run = tmp_path / "run.csv"
    run.write_text("t\n")
    os.utime(run, (1767600000, 1767600000))  # 2026-01-05T08:00:00Z
    assert _time(RunTask(str(run), time="2026-03-01T10:00:00+01:00"), "2020-01-01") == (
        "2026-03-01T09:00:00+00:00", "given")
    assert _time(RunTask(str(run)), "2025-12-24T06:00:00") == ("2025-12-24T06:00:00+00:00",
                                                               "file")
    assert _time(RunTask(str(run)), None) == ("2026-01-05T08:00:00+00:00", "mtime")
    with pytest.raises(ValueError, match="time"):
        iso_time("yesterday")


# --------------------------------------------------------------------------------------------
# the detector


def _standard_cusum(u: np.ndarray) -> bool:
    """The textbook two-sided CUSUM on known N(0, 1) scores: any alarm."""
    high = low = 0.0
    for score in u:
        high, low = max(0.0, high + score - DRIFT), max(0.0, low - score - DRIFT)
        if max(high, low) > LEVEL:
            return True
    return False


def test_the_self_starting_detector_alarms_as_often_as_the_known_parameter_cusum() -> None:
    # Unknown level and spread, learnt from the series itself, give the false-alarm rate of a
    # CUSUM that knows them (the self-starting transform is exact for normal figures).
    rng = np.random.default_rng(7)
    series, runs = 400, 200
    own = np.mean([detect_changes(rng.normal(3.0, 0.2, runs)).alarm.any() for _ in range(series)])
    known = np.mean([_standard_cusum(rng.normal(0, 1, runs - LEARN)) for _ in range(series)])
    # about 0.34 both: 4 binomial spreads of the difference apart would be 0.13
    assert abs(own - known) < 0.13
    assert 0.2 < own < 0.5


def test_the_learning_runs_never_alarm_and_a_step_is_found_at_once() -> None:
    x = np.r_[[1.0, 50.0, -30.0, 1.0, 2.0], np.random.default_rng(3).normal(1, 0.1, 20)]
    assert not detect_changes(x).alarm[:LEARN].any()
    y = np.r_[np.random.default_rng(4).normal(1, 0.1, 20), 3.0, np.nan, 3.0]  # 20 spreads
    found = detect_changes(y)
    assert found.alarm[20] and math.isnan(found.size[21]) and not found.alarm[21]
    assert found.centre[22] == pytest.approx(np.mean(y[:20]))  # judged against the history


# --------------------------------------------------------------------------------------------
# a simulated history: 24 healthy runs, then backlash 0.57, 1.5 and 3 arcmin


def test_no_alarm_on_a_healthy_run_and_worn_backlash_found_by_the_third_worn_run() -> None:
    from funcnet.track.figures import axis_figures
    from funcnet.validation.histories import history_recordings

    figures = [axis_figures(r, 1).values for r in history_recordings(0)]
    first = {}
    for name in ("lost_motion", "backlash_score", "current_at_turns", "peak_speed"):
        found = detect_changes(np.array([f[name] for f in figures]))
        assert not found.alarm[:24].any(), name
        assert np.nanmax(found.cusum[:24]) < LEVEL - 2  # far from the level, not at its edge
        alarms = np.flatnonzero(found.alarm)
        if alarms.size:
            first[name] = int(alarms[0])
    assert min(first.values()) <= 26
    assert first["lost_motion"] == 25  # 1.5 arcmin: 65 spreads above the healthy mean


# --------------------------------------------------------------------------------------------
# the commands, on real runs


def _funcnet(*args: str) -> Any:
    return runner.invoke(app, list(args))


def test_ur5_clean_repeats_raise_nothing_and_the_pushed_run_stands_out(
        ur5_runs: Path, tmp_path: Path) -> None:
    from funcnet.track import add_runs

    store = tmp_path / "ur5.sqlite"
    runs = [("Movement_No8_Singularity_Free_1", "2013-06-01"),
            ("Movement_No9_Singularity_Free_NoDist", "2013-06-02"),
            ("Movement_No9_Singularity_Free_ForceSensor", "2013-06-03"),
            ("Movement_No5_Acc_slow_no_disturbance", "2013-06-04")]
    for name, day in runs:
        add_runs([ur5_runs / name], store, "ur5", channels=str(UR5_MAP), time=day)
    again = _funcnet("track", "add", str(ur5_runs / runs[0][0]), "--store", str(store),
                     "--robot", "ur5", "--channels", str(UR5_MAP))
    assert again.exit_code == 0 and "already kept" in again.stdout
    out = tmp_path / "page"
    shown = _funcnet("track", "show", "--store", str(store), "-o", str(out))
    assert shown.exit_code == 0, shown.stderr
    listed = json.loads((out / "runs.json").read_text())
    programs = [r["program"] for r in listed]
    assert programs[0] == programs[1] == programs[2] != programs[3]  # No5 is another program
    assert json.loads((out / "alarms.json").read_text()) == []
    figures = kept.read_figures(store, "ur5")
    departure = figures[figures["figure"] == "departure"].pivot(index="run", columns="axis",
                                                                 values="value")
    clean, pushed = departure.loc[2], departure.loc[3]
    assert departure.loc[1].isna().all()  # the program's first run: nothing to depart from
    assert pushed[2] > 4 * clean[2] and pushed[1] > 3 * clean[1]  # shoulder, base
    assert "<svg" in (out / "index.html").read_text()


def test_two_track_add_at_once_both_land_and_bad_input_is_one_line(tmp_path: Path) -> None:
    from funcnet.validation.histories import write_history

    paths = write_history(tmp_path / "runs", 5, healthy=2, worn=())
    store = tmp_path / "fleet.sqlite"
    adds = [subprocess.Popen([sys.executable, "-m", "funcnet", "track", "add", str(p),
                              "--store", str(store), "--robot", "cell-4"], env=ENV,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for p in paths]
    outputs = [a.communicate(timeout=300) for a in adds]
    assert [a.returncode for a in adds] == [0, 0], outputs
    runs = kept.read_runs(store, "cell-4")
    assert len(runs) == 2 and set(runs["time_from"]) == {"file"}
    bad = _funcnet("track", "add", str(paths[0]), "--store", str(store), "--robot", "x",
                   "--time", "soon")
    assert bad.exit_code == 2 and bad.stderr.count("\n") == 1 and "soon" in bad.stderr
    broken = tmp_path / "broken.xml"
    broken.write_text("<trace>")
    partly = _funcnet("track", "add", str(broken), str(paths[1]), "--store",
                      str(tmp_path / "other.sqlite"), "--robot", "cell-5")
    assert partly.exit_code == 2 and partly.stderr.count("\n") == 1
    assert "broken.xml" in partly.stderr
    assert len(kept.read_runs(tmp_path / "other.sqlite", "cell-5")) == 1  # the readable one kept
    missing = _funcnet("track", "show", "--store", str(tmp_path / "none.sqlite"), "-o",
                       str(tmp_path / "o"))
    assert missing.exit_code == 2 and "no such store" in missing.stderr


# --------------------------------------------------------------------------------------------
# many runs in one call


def _other_program(folder: Path, days: list[float]) -> list[Path]:
    """Runs of a second program (a 5 deg move instead of the history's 8 deg)."""
    from datetime import timedelta

    from funcnet.sim import AxisParameters, Trial, simulate_trial, write_trace
    from funcnet.validation.histories import FIRST_DAY, SETTLE

    paths = []
    for k, day in enumerate(days):
        trial = Trial(f"other-{k}", "track", speed=300.0, tcp=1.2, step=5.0, reverse=True,
                      seed=11 + k)
        sim = simulate_trial(trial, AxisParameters(settle_time=SETTLE), seed=11)
        start = (FIRST_DAY + timedelta(days=day)).isoformat()
        paths.append(write_trace(folder / f"{trial.name}.xml", sim.data.round(6),
                                 start_time=start))
    return paths


def _whole_store(path: Path) -> dict[str, Any]:
    """Every table of a store, as plain values (NaN as None)."""
    with sqlite3.connect(path) as db:
        return {table: sorted(db.execute(f"SELECT * FROM {table}").fetchall(), key=repr)
                for table in ("runs", "figures", "programs", "traces")}


def test_many_runs_in_one_call_give_the_store_of_one_call_each(tmp_path: Path,
                                                                monkeypatch) -> None:
    from funcnet.track import add_runs
    from funcnet.validation.histories import write_history

    folder = tmp_path / "runs"
    # 7 runs of one program (more than the 5 references), 2 of another between them in time
    history = write_history(folder, 5, healthy=6, worn=(1.5,))
    other = _other_program(folder, [2.5, 8.0])
    every = [*history, *other, history[0]]  # the first again: kept once
    reads = {"runs": 0, "programs": 0}
    for name in reads:
        original = getattr(kept, f"read_{name}")

        def counted(*args: Any, _name: str = name, _original: Any = original) -> Any:
            reads[_name] += 1
            return _original(*args)

        monkeypatch.setattr(kept, f"read_{name}", counted)
    at_once = add_runs(every, tmp_path / "at-once.sqlite", "cell")
    assert reads == {"runs": 1, "programs": 1}  # read once per call, not once per run
    assert sum(a.added for a in at_once) == 9 and not any(a.error for a in at_once)

    one_by_one = tmp_path / "one-by-one.sqlite"
    in_time = sorted(at_once, key=lambda a: (a.time, a.source))
    for added in in_time:
        add_runs([added.source], one_by_one, "cell")
    first, second = _whole_store(tmp_path / "at-once.sqlite"), _whole_store(one_by_one)
    assert first == second
    programs = {row[4] for row in first["runs"]}  # id, robot, time, time_from, program
    assert len(programs) == 2 and len(first["runs"]) == 9
    # the departure of the history's last run is against the program's 5 earliest runs
    counts = {row[0]: row[3] for row in first["figures"] if row[2] == "departure_references"}
    assert sorted(counts.values()) == [0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 4.0, 5.0, 5.0]


def test_runs_read_on_a_dask_cluster_give_the_store_read_here(tmp_path: Path) -> None:
    # Dask worker threads in this process (1 worker, 2 threads): the runs are read there, kept
    # here; the store and what is said of each run are the serial call's.
    from distributed import LocalCluster

    from funcnet.track import add_runs
    from funcnet.validation.histories import write_history

    paths = write_history(tmp_path / "runs", 6, healthy=3, worn=())
    broken = tmp_path / "runs" / "broken.xml"
    broken.write_text("<trace>")
    given = [*paths, broken, paths[1]]  # an unreadable run, and one run twice
    serial = add_runs(given, tmp_path / "serial.sqlite", "cell")
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, protocol="tcp://",
                      host="127.0.0.1", dashboard_address=None) as cluster:
        on_dask = add_runs(given, tmp_path / "dask.sqlite", "cell",
                           scheduler=cluster.scheduler_address)
    assert _whole_store(tmp_path / "dask.sqlite") == _whole_store(tmp_path / "serial.sqlite")

    def said(found: list[Any]) -> list[tuple[Any, ...]]:
        return sorted((a.source, a.added, a.error, a.time, a.program, a.notes) for a in found)

    assert said(on_dask) == said(serial)
    assert [a.added for a in serial].count(True) == 3 and sum(a.error for a in serial) == 1
