"""Tests of funcnet.study: study files, task keys, the cache, resuming, local vs Dask execution."""

from __future__ import annotations

import hashlib
import itertools
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from funcnet.errors import StudyError
from funcnet.parameters import NetworkParameters
from funcnet.study import (
    PARAMETER_COLUMNS,
    Study,
    WindowSpec,
    load_results,
    load_study,
    parameter_grid,
    run_study,
)

pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")

# Two short simulated trials (about 3 s each at 500 Hz) keep every network small.
TRIALS = (
    ("quick-p12", 1.2),
    ("quick-p20", 2.0),
)
STUDY_TEXT = """
[recordings]
paths = ["plan/*.xml"]
[[windows]]
kind = "phases"
[[windows]]
kind = "range"
start = 0.5
stop = 1.1
[network]
delay = [5, 10]
"""


@pytest.fixture(scope="module")
def plan_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from funcnet.sim import Trial, write_plan

    folder = tmp_path_factory.mktemp("study") / "plan"
    trials = [Trial(name, "main", speed=350, tcp=tcp, step=1) for name, tcp in TRIALS]
    write_plan(trials, folder, workers=1)
    return folder


@pytest.fixture(scope="module")
def study_file(plan_dir: Path) -> Path:
    path = plan_dir.parent / "study.toml"
    path.write_text(STUDY_TEXT)
    return path


@pytest.fixture(scope="module")
def baseline(study_file: Path) -> tuple[Path, object]:
    """The uninterrupted local run every other run is compared with."""
    out = study_file.parent / "baseline"
    result = run_study(load_study(study_file), out, workers=2)
    return out, result


def _write(folder: Path, text: str, name: str = "s.toml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


# --------------------------------------------------------------------------------------------
# study files


def test_load_study_reads_paths_windows_and_grid(tmp_path: Path) -> None:
    (tmp_path / "traces").mkdir()
    for name in ("b.xml", "a.xml", "c.csv"):
        (tmp_path / "traces" / name).write_text("x")
    path = _write(
        tmp_path,
        """
signals = ["RP", "AP", "V"]
[recordings]
paths = ["traces/*.xml", "traces/c.csv"]
axis = 7
[[windows]]
kind = "sliding"
width = 0.6
step = 0.3
[[windows]]
kind = "reversal"
shifts = [-0.02, 0.0, 0.02]
[network]
dim = [2, 3]
delay = [5, 10, 20]
mu = 0.1
normalize = "none"
""",
    )
    study = load_study(path)
    assert [p.relative_to(tmp_path).as_posix() for p in study.recordings] == [
        "traces/a.xml",
        "traces/b.xml",
        "traces/c.csv",
    ]
    assert study.signals == ("RP", "AP", "V")
    assert study.axis == 7
    assert study.base_dir == tmp_path.resolve()
    assert study.windows == (
        WindowSpec("sliding", (("step", 0.3), ("width", 0.6))),
        WindowSpec("reversal", (("shifts", [-0.02, 0.0, 0.02]), ("width", 0.2))),  # default width
    )
    grid = parameter_grid(study)
    expected = [
        NetworkParameters(dim=d, delay=t, mu=0.1, normalize=None)
        for d, t in itertools.product([2, 3], [5, 10, 20])
    ]
    assert grid == expected


def test_documented_example_study_loads() -> None:
    example = Path(__file__).parents[1] / "examples" / "study.toml"
    study = load_study(example)
    assert study.simulated == "paper" and study.recordings == ()
    assert [w.kind for w in study.windows] == ["fixed", "reversal"]
    assert study.signals == ("RP", "AP", "MP", "V", "RC", "AC")
    assert study.constant == "drop"  # so that the documented run has no failure
    assert len(parameter_grid(study)) == 2


@pytest.mark.parametrize(
    ("text", "key"),
    [
        ("[recordings]\npaths = [", "not valid TOML"),
        ('[recordings]\npaths = ["*.xml"]\ncolour = 1', "recordings.colour"),
        ('[recordings]\npaths = ["nothing-*.xml"]', "recordings.paths"),
        ("[recordings]\npaths = []", "recordings"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\nmux = 0.1', "[network] mux"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\ndim = "3"', "[network] dim"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\ndelay = []', "[network] delay"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\ndelay = [5, 5]', "[network] delay"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\neps = 0.1', "[network] eps"),
        ('[recordings]\npaths = ["*.xml"]\n[network]\nrr = [[0.1, 0.2]]', "[network] rr"),
        ('[recordings]\npaths = ["*.xml"]\n[[windows]]\nkind = "hourly"', "windows[0].kind"),
        ('[recordings]\npaths = ["*.xml"]\n[[windows]]\nkind = "sliding"\nwidth = 1', "step"),
        (
            '[recordings]\npaths = ["*.xml"]\n[[windows]]\nkind = "phases"\nwidht = 1',
            "windows[0].widht",
        ),
        (
            '[recordings]\npaths = ["*.xml"]\n[[windows]]\nkind = "range"\nstart = 2\nstop = 1',
            "windows[0].stop",
        ),
        ('signals = ["RP"]\n[recordings]\npaths = ["*.xml"]', "signals"),
        ('[recordings]\nsimulated = "missing-plan.toml"', "recordings.simulated"),
        ('[recordings]\npaths = ["*.xml"]\nchannels = "none.toml"', "recordings.channels"),
        ('constant = "ignore"\n[recordings]\npaths = ["*.xml"]', "constant"),
        ('[recordings]\npaths = ["*.xml"]\nresample = "spline"', "recordings.resample"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nalpha = 2.0', "[evidence] alpha"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nsurrogates = 0', "[evidence] surrogates"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nedge_rule = "mu"', "[evidence] edge_rule"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nlevel = 0.9', "[evidence] level"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nenabled = "yes"', "[evidence] enabled"),
        ('[recordings]\npaths = ["*.xml"]\n[evidence]\nsurrogate_method = "phase"',
         "[evidence] surrogate_method"),
        ('[recordings]\npaths = ["*.xml"]\n[stability]\ngrid = {radius = [1]}',
         "[stability] grid"),
        ('[recordings]\npaths = ["*.xml"]\n[stability]\ngrid = {rr = [2.0]}',
         "[stability] grid"),
    ],
)
def test_load_study_errors_name_file_and_key(tmp_path: Path, text: str, key: str) -> None:
    (tmp_path / "a.xml").write_text("x")
    path = _write(tmp_path, text)
    with pytest.raises(StudyError) as info:
        load_study(path)
    message = str(info.value)
    assert str(path) in message
    assert key in message


# --------------------------------------------------------------------------------------------
# a local run


def test_rows_hold_every_pair_window_and_parameter(baseline, study_file: Path) -> None:
    from funcnet import functional_network
    from funcnet.robot import detect_phases, phase_windows, read_recording

    out, result = baseline
    rows = load_results(out)
    assert result.computed == result.tasks and result.cached == 0 and not result.failures

    nodes = ["RP", "AP", "MP", "V", "RC", "AC"]  # every role of a simulated trace, plus V
    n_pairs = len(nodes) * (len(nodes) - 1) // 2
    expected_tasks = 0
    for name, _ in TRIALS:
        trace = study_file.parent / "plan" / f"{name}.xml"
        recording = read_recording(trace)
        windows = phase_windows(detect_phases(recording))
        expected_tasks += 2 * (len(windows) + 1)  # phases + one range, two delays
        mine = rows[rows["recording"] == f"plan/{name}.xml"]
        assert set(mine["trial"]) == {name}  # from manifest.csv
        assert set(mine["source_sha256"]) == {hashlib.sha256(trace.read_bytes()).hexdigest()}
        assert set(mine["window"]) == {w.label for w in windows} | {"0.500-1.100 s"}
        # An independent computation of one of the networks gives the same numbers.
        window = windows[-1]
        part = recording.window(window.start, window.stop).data[nodes]
        reference = functional_network(part, delay=5).pairs.reset_index(drop=True)
        got = mine[(mine["window"] == window.label) & (mine["delay"] == 5)]
        assert got["phase"].tolist() == [window.phase] * n_pairs
        assert got[["start", "stop"]].drop_duplicates().values.tolist() == [
            [window.start, window.stop]
        ]
        pd.testing.assert_frame_equal(
            got[reference.columns].reset_index(drop=True), reference, check_dtype=False
        )
    assert result.tasks == expected_tasks
    assert len(rows) == expected_tasks * n_pairs
    assert rows.groupby(["recording", "window", "delay"]).size().eq(n_pairs).all()
    # Every parameter has its column; the targets keep their names (rr, cr), the achieved
    # rates are the pairs table's achieved_rr_x, achieved_rr_y, achieved_cr.
    assert list(PARAMETER_COLUMNS) == list(NetworkParameters.names())
    for column in PARAMETER_COLUMNS.values():
        assert column in rows.columns
    assert PARAMETER_COLUMNS["degenerate"] == "degenerate_policy"
    assert set(rows["rr"]) == {0.05} and set(rows["degenerate_policy"]) == {"drop"}
    assert rows["degenerate"].dtype == bool
    assert set(rows["dim"]) == {3} and set(rows["delay"]) == {5, 10}
    assert set(rows["constant"]) == {"drop"} and set(rows["dropped"]) == {""}  # the default


def test_rows_are_plain_parquet_and_study_json_has_provenance(baseline) -> None:
    out, result = baseline
    files = sorted((out / "rows").glob("*.parquet"))
    assert len(files) == result.tasks
    for f in files[:3]:
        assert pq.read_schema(f).metadata is None  # no pandas-only metadata
    # The whole folder reads as one data set with pyarrow alone.
    table = pq.ParquetDataset(out / "rows").read()
    assert table.num_rows == len(load_results(out))
    document = json.loads((out / "study.json").read_text())
    assert document["status"] == "complete"
    assert document["run"]["tasks"] == result.tasks
    versions = document["provenance"]["versions"]
    assert versions["numpy"] == np.__version__ and versions["funcnet"]
    for name, _ in TRIALS:
        trace = out.parent / "plan" / f"{name}.xml"
        digest = hashlib.sha256(trace.read_bytes()).hexdigest()
        assert document["provenance"]["inputs"][f"plan/{name}.xml"] == digest


def test_rows_load_with_polars_and_duckdb(baseline) -> None:
    import duckdb
    import polars as pl

    out, _ = baseline
    key = ["source_sha256", "window", "delay", "x", "y"]
    expected = load_results(out).sort_values(key).reset_index(drop=True)
    pattern = str(out / "rows" / "*.parquet")
    from_polars = pl.read_parquet(pattern).to_pandas().sort_values(key).reset_index(drop=True)
    from_duckdb = duckdb.sql(f"SELECT * FROM '{pattern}'").df().sort_values(key)
    for frame in (from_polars, from_duckdb.reset_index(drop=True)):
        assert len(frame) == len(expected)
        for column in ("x", "y", "kind", "window"):
            assert frame[column].astype(str).tolist() == expected[column].astype(str).tolist()
        for column in ("c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff", "weight"):
            np.testing.assert_array_equal(frame[column].to_numpy(), expected[column].to_numpy())


def test_rerun_computes_nothing_and_a_new_grid_only_what_is_new(baseline, study_file) -> None:
    out, first = baseline
    before = load_results(out)
    again = run_study(load_study(study_file), out, workers=0)
    assert (again.computed, again.cached) == (0, first.tasks)
    pd.testing.assert_frame_equal(load_results(out), before)

    # Another grid: the shared half is reused, the old rows leave rows/ (kept in cache/) ...
    grid_file = _write(study_file.parent, STUDY_TEXT.replace("[5, 10]", "[10, 20]"), "g.toml")
    other = run_study(load_study(grid_file), out, workers=0)
    assert (other.computed, other.cached) == (first.tasks // 2, first.tasks // 2)
    assert set(load_results(out)["delay"]) == {10, 20}
    # ... and come back without being computed again.
    back = run_study(load_study(study_file), out, workers=0)
    assert (back.computed, back.cached) == (0, first.tasks)
    pd.testing.assert_frame_equal(load_results(out), before)


def test_failed_windows_are_recorded_and_not_retried(plan_dir: Path, tmp_path: Path) -> None:
    # Before the motion starts every position is constant: min-max normalization must refuse.
    trace = plan_dir / f"{TRIALS[0][0]}.xml"
    study = Study(
        recordings=(trace,),
        windows=(WindowSpec("range", (("start", 0.0), ("stop", 0.2))),),
        signals=("RP", "AP"),
        base_dir=plan_dir,
        constant="error",
    )
    result = run_study(study, tmp_path, workers=0)
    assert (result.tasks, result.computed, len(result.failures)) == (1, 1, 1)
    message = result.failures[0].message
    assert "signal 'AP' is constant" in message
    assert f"{trace.name}: window '0.000-0.200 s' [0, 0.2) s: " in message
    assert not list((tmp_path / "rows").glob("*.parquet"))
    again = run_study(study, tmp_path, workers=0)
    assert (again.computed, again.cached, len(again.failures)) == (0, 1, 1)
    with pytest.raises(StudyError, match="no study results"):
        load_results(tmp_path)


def test_constant_drop_leaves_constant_signals_out(plan_dir: Path, tmp_path: Path) -> None:
    from funcnet import functional_network
    from funcnet.robot import read_recording

    trace = plan_dir / f"{TRIALS[0][0]}.xml"
    text = (
        '{}[recordings]\npaths = ["plan/{}"]\n'
        '[[windows]]\nkind = "range"\nstart = 0.0\nstop = 0.2\n'
    )
    drop = load_study(_write(plan_dir.parent, text.format('constant = "drop"\n', trace.name),
                             "drop.toml"))
    error = load_study(_write(plan_dir.parent, text.format('constant = "error"\n', trace.name),
                              "error.toml"))
    default = load_study(_write(plan_dir.parent, text.format("", trace.name), "default.toml"))
    assert (drop.constant, error.constant, default.constant) == ("drop", "error", "drop")
    assert drop.to_dict()["constant"] == "drop"

    result = run_study(drop, tmp_path, workers=0)
    assert (result.tasks, result.computed, result.failures) == (1, 1, ())
    count, example = result.warnings["constant"]  # said, counted as the other problems are
    assert count == 1 and example.endswith("in 1 of 1 window(s): '0.000-0.200 s' (AP, V)")
    rows = load_results(tmp_path)
    # Before the motion AP (and V, derived from it) are constant: left out, and recorded so.
    part = read_recording(trace).window(0.0, 0.2).data
    constant = [c for c in ("RP", "AP", "MP", "V", "RC", "AC") if np.ptp(part[c]) == 0]
    assert constant == ["AP", "V"]
    kept = [c for c in ("RP", "AP", "MP", "V", "RC", "AC") if c not in constant]
    assert set(rows["constant"]) == {"drop"} and set(rows["dropped"]) == {"AP,V"}
    assert set(rows["signals"]) == {",".join(kept)} and len(rows) == 6
    reference = functional_network(part[kept]).pairs.reset_index(drop=True)
    pd.testing.assert_frame_equal(
        rows[reference.columns].reset_index(drop=True), reference, check_dtype=False
    )
    # "error" is another task (its own key): it fails, and the "drop" rows are kept aside.
    failed = run_study(error, tmp_path, workers=0)
    assert (failed.computed, len(failed.failures)) == (1, 1)
    assert "constant" in failed.failures[0].message
    back = run_study(drop, tmp_path, workers=0)
    assert (back.computed, back.cached, back.failures) == (0, 1, ())


def test_simulated_plan_is_written_then_analysed(tmp_path: Path) -> None:
    (tmp_path / "plan.toml").write_text(
        '[[group]]\nname = "fast"\nspeeds = [350]\ntcps = [1.2, 2.0]\nsteps = [1]\n'
    )
    path = _write(
        tmp_path,
        'signals = ["RP", "AP"]\n[recordings]\nsimulated = "plan.toml"\nseed = 4\n'
        '[[windows]]\nkind = "range"\nstart = 0.5\nstop = 1.0\n',
    )
    result = run_study(load_study(path), tmp_path / "out", workers=0)
    assert (result.tasks, result.computed) == (2, 2)
    rows = load_results(tmp_path / "out")
    assert rows["recording"].tolist() == [
        "out/plan/fast-v350-p12-s1.xml",
        "out/plan/fast-v350-p20-s1.xml",
    ]
    assert rows["trial"].tolist() == ["fast-v350-p12-s1", "fast-v350-p20-s1"]
    assert pd.read_csv(tmp_path / "out" / "plan" / "manifest.csv")["seed"].tolist() == [4, 4]


def test_sliding_windows_and_a_missing_reversal(plan_dir: Path, tmp_path: Path) -> None:
    from funcnet.robot import read_recording, sliding_windows

    trace = plan_dir / f"{TRIALS[1][0]}.xml"
    study = Study(
        recordings=(trace,),
        windows=(WindowSpec("reversal"), WindowSpec("sliding", (("step", 0.8), ("width", 0.4)))),
        signals=("AP", "V"),
        base_dir=plan_dir,
    )
    result = run_study(study, tmp_path, workers=0)
    expected = sliding_windows(read_recording(trace), 0.4, 0.8)
    assert not result.failures  # a forward-only trial simply has no reversal windows
    assert result.tasks == len(expected) > 2
    rows = load_results(tmp_path)
    assert rows["window"].tolist() == [w.label for w in expected]
    assert rows["start"].tolist() == [w.start for w in expected]
    assert rows["phase"].isna().all() and (rows["x"] + rows["y"] == "APV").all()


def test_invalid_parameter_value_stops_the_run(plan_dir: Path, tmp_path: Path) -> None:
    study = Study(
        recordings=(plan_dir / f"{TRIALS[0][0]}.xml",),
        windows=(WindowSpec("range", (("start", 0.5), ("stop", 1.0))),),
        parameters=(("mu", (-1.0,)),),
        base_dir=plan_dir,
    )
    with pytest.raises(StudyError, match=r"\[network\] mu must be finite and >= 0, got -1.0"):
        run_study(study, tmp_path / "out", workers=0)
    assert not (tmp_path / "out").exists()  # refused before anything was written


def test_concurrent_run_on_same_folder_is_refused(tmp_path: Path) -> None:
    import fcntl

    with open(tmp_path / ".lock", "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        with pytest.raises(StudyError, match="another study run"):
            run_study(Study(recordings=()), tmp_path)


# --------------------------------------------------------------------------------------------
# Dask, and a run killed with SIGKILL


def test_dask_cluster_gives_the_same_rows(baseline, study_file: Path) -> None:
    from distributed import LocalCluster

    out, result = baseline
    with LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        dask_out = study_file.parent / "dask"
        on_dask = run_study(load_study(study_file), dask_out, scheduler=cluster.scheduler_address)
    assert on_dask.computed == result.tasks
    pd.testing.assert_frame_equal(load_results(dask_out), load_results(out))
    assert sorted(p.name for p in (dask_out / "rows").iterdir()) == sorted(
        p.name for p in (out / "rows").iterdir()
    )


def test_dask_worker_threads_give_the_same_rows_and_warnings(baseline, study_file: Path) -> None:
    # Several tasks at once in the threads of one process: nothing is caught from the warnings
    # module, so the counts come out as on local processes.
    from distributed import LocalCluster

    out, result = baseline
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, protocol="tcp://",
                      host="127.0.0.1", dashboard_address=None) as cluster:
        threads_out = study_file.parent / "threads"
        on_threads = run_study(load_study(study_file), threads_out,
                               scheduler=cluster.scheduler_address)
    assert on_threads.computed == result.tasks
    assert on_threads.warnings == result.warnings  # counts and (task-order) examples
    pd.testing.assert_frame_equal(load_results(threads_out), load_results(out))


def _children(pid: int) -> set[int]:
    found = set()
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            found.add(int(stat.parent.name))
    return found


def _alive(pid: int) -> bool:
    try:
        state = (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def test_run_killed_with_sigkill_resumes_to_the_same_rows(baseline, study_file: Path) -> None:
    out, result = baseline
    killed_out = study_file.parent / "killed"
    command = [sys.executable, "-m", "funcnet.cli", "study", str(study_file)]
    command += ["--out", str(killed_out), "--workers", "2", "--quiet"]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = killed_out / "rows"
    deadline = time.monotonic() + 120
    workers: set[int] = set()
    while time.monotonic() < deadline and process.poll() is None:
        workers |= _children(process.pid)
        if rows.is_dir() and any(rows.glob("*.parquet")):
            break
        time.sleep(0.01)
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    done_at_kill = len(list(rows.glob("*.parquet")))
    assert 0 < done_at_kill < result.tasks, "the kill must land mid-way"
    # The workers notice their parent's death and exit: nothing is left running.
    deadline = time.monotonic() + 20
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert workers and not any(_alive(pid) for pid in workers)

    # Restarted (here in this process, to keep the test short) it computes only what is missing.
    resumed = run_study(load_study(study_file), killed_out, workers=0)
    assert resumed.cached >= done_at_kill
    assert resumed.computed + resumed.cached == result.tasks
    pd.testing.assert_frame_equal(load_results(killed_out), load_results(out))
    assert not [p for p in killed_out.rglob(".*.tmp")]


# --------------------------------------------------------------------------------------------
# the parameter contract at load time, the optional Dask extra, warnings from flags


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("rr = 2.0", "[network] rr must be in (0, 1), got 2.0"),
        ('metric = "cosine"', "[network] metric must be one of euclidean, supremum, manhattan"),
        ("dim = 0", "[network] dim must be >= 1, got 0"),
        ("delay = [5, 0]", "[network] delay must be >= 1, got 0"),
        ('normalize = "l2"', "[network] normalize must be one of minmax, zscore, none"),
    ],
)
def test_bad_network_values_are_rejected_when_the_file_is_read(
    tmp_path: Path, line: str, message: str
) -> None:
    (tmp_path / "plan.toml").write_text(
        '[[group]]\nname = "fast"\nspeeds = [350]\ntcps = [1.2]\nsteps = [1]\n'
    )
    path = _write(tmp_path, f'[recordings]\nsimulated = "plan.toml"\n[network]\n{line}\n')
    with pytest.raises(StudyError) as info:
        load_study(path)
    text = str(info.value)
    assert text.startswith(f"{path.resolve()}: {message}")
    assert "\n" not in text
    # Nothing was simulated or written: the file's folder holds only what the test wrote.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plan.toml", "s.toml"]


def test_bad_value_of_a_study_made_in_python_stops_before_simulating(tmp_path: Path) -> None:
    study = Study(simulated="paper", parameters=(("rr", (0.05, 2.0)),), base_dir=tmp_path)
    with pytest.raises(StudyError, match=r"^study: \[network\] rr must be in \(0, 1\), got 2.0$"):
        run_study(study, tmp_path / "out", workers=0)
    assert not (tmp_path / "out").exists()


def test_eps_pairs_and_none_in_the_network_table(tmp_path: Path) -> None:
    (tmp_path / "a.xml").write_text("x")
    one = load_study(_write(tmp_path, '[recordings]\npaths = ["*.xml"]\n'
                                      '[network]\neps = [0.2, "none"]\n', "one.toml"))
    assert [p.eps for p in parameter_grid(one)] == [(0.2, None)]
    grid = load_study(_write(tmp_path, '[recordings]\npaths = ["*.xml"]\n'
                                       '[network]\neps = [[0.2, 0.1], ["none", 0.3]]\n',
                             "grid.toml"))
    assert [p.eps for p in parameter_grid(grid)] == [(0.2, 0.1), (None, 0.3)]


def _small_trace(folder: Path, quantized: bool = False) -> Path:
    t = np.arange(0, 2, 0.002)
    ap = np.sin(5 * t - 0.3)
    frame = pd.DataFrame({
        "time": t,
        "RP": np.sin(5 * t),
        "AP": np.round(ap) if quantized else ap,
        "AC": np.cos(7 * t) + 0.1 * np.sin(31 * t),
    })
    path = folder / "trace.csv"
    frame.to_csv(path, index=False)
    return path


def test_missing_dask_names_the_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "distributed", None)  # as if funcnet[dask] were not there
    study = Study(recordings=(_small_trace(tmp_path),), signals=("RP", "AP"), base_dir=tmp_path,
                  windows=(WindowSpec("range", (("start", 0.2), ("stop", 1.8))),))
    for scheduler in ("local-cluster", "tcp://127.0.0.1:8786"):
        with pytest.raises(StudyError) as info:
            run_study(study, tmp_path / "out", scheduler=scheduler)
        assert "install funcnet[dask]" in str(info.value)
        assert "\n" not in str(info.value)
    assert not (tmp_path / "out").exists()
    # Local processes and in-process runs do not need Dask.
    assert run_study(study, tmp_path / "out", workers=0).computed == 1


def test_warnings_are_counted_from_the_pairs_flags(tmp_path: Path) -> None:
    from funcnet.study.tasks import task_warnings

    trace = _small_trace(tmp_path, quantized=True)  # AP takes three values: degenerate
    study = Study(recordings=(trace,), signals=("RP", "AP", "AC"), base_dir=tmp_path,
                  windows=(WindowSpec("range", (("start", 0.2), ("stop", 1.8))),))
    result = run_study(study, tmp_path / "out", workers=0)
    rows = load_results(tmp_path / "out")
    flagged = rows[rows["degenerate"]]
    assert len(flagged) > 0 and set(flagged["x"]) | set(flagged["y"]) >= {"AP"}
    count, example = result.warnings["degenerate"]
    assert count == 1  # one task has it
    assert example.startswith("trace.csv: ") and "AP" in example
    document = json.loads((tmp_path / "out" / "study.json").read_text())
    assert document["run"]["warnings"]["degenerate"]["tasks"] == 1
    # The same numbers from the pure function, whatever thread runs it.
    from concurrent.futures import ThreadPoolExecutor

    from funcnet import window_networks
    from funcnet.robot import Window, read_recording

    recording = read_recording(trace)
    window = Window("w", 0.2, 1.8)

    def problems(_: int) -> tuple[tuple[str, int, str], ...]:
        networks = window_networks(recording, [window], signals=["RP", "AP", "AC"])
        return task_warnings(networks, recording, ["RP", "AP", "AC"], "trace.csv")

    with ThreadPoolExecutor(4) as pool:
        seen = set(pool.map(problems, range(4)))
    assert len(seen) == 1
    (found,) = seen
    assert dict((p, n) for p, n, _ in found)["degenerate"] == int(rows["degenerate"].sum())


def test_staircases_are_reported_from_the_recording() -> None:
    from funcnet import window_networks
    from funcnet.robot import Recording, SignalInfo, Window
    from funcnet.study.tasks import task_warnings

    t = np.arange(0, 2, 0.002)
    ap = np.repeat(np.sin(5 * t[::2] - 0.3), 2)  # held for two ticks: a 4 ms signal
    data = pd.DataFrame({"RP": np.sin(5 * t), "AP": ap}, index=pd.Index(t, name="time"))
    info = {"RP": SignalInfo("RP", None, None, 0.002), "AP": SignalInfo("AP", None, None, 0.004)}
    recording = Recording(data, {}, info, source="trace.csv", sample_period=0.002)
    networks = window_networks(recording, [Window("w", 0.2, 1.8)], signals=["RP", "AP"])
    found = {p: (n, m) for p, n, m in task_warnings(networks, recording, ["RP", "AP"], "t.csv")}
    count, message = found["staircase"]
    assert count == 1 and message.startswith("t.csv: AP ")


def test_resample_option_reads_the_recordings_resampled(plan_dir: Path, tmp_path: Path) -> None:
    trace = plan_dir / f"{TRIALS[0][0]}.xml"
    text = (
        'signals = ["RP", "AP"]\n[recordings]\npaths = ["plan/{}"]\n{}'
        '[[windows]]\nkind = "range"\nstart = 0.5\nstop = 1.1\n'
    )
    native = load_study(_write(plan_dir.parent, text.format(trace.name, ""), "native.toml"))
    decimated = load_study(
        _write(plan_dir.parent, text.format(trace.name, 'resample = "decimate"\n'), "dec.toml")
    )
    assert (native.resample, decimated.resample) == (None, "decimate")
    run_study(native, tmp_path, workers=0)
    first = load_results(tmp_path)
    # Another task (its own key); the simulator logs every signal at 2 ms: the same numbers.
    second = run_study(decimated, tmp_path, workers=0)
    assert (second.computed, second.cached) == (1, 0)
    assert json.loads((tmp_path / "study.json").read_text())["study"]["resample"] == "decimate"
    pd.testing.assert_frame_equal(load_results(tmp_path), first)


def test_row_columns_are_identity_parameters_then_the_pairs_schema(baseline) -> None:
    from funcnet.network.schema import PAIR_COLUMNS
    from funcnet.study.store import IDENTITY_SCHEMA

    identity, parameters = list(IDENTITY_SCHEMA.names), list(PARAMETER_COLUMNS.values())
    # Disjoint: no column of one part may hide a column of another.
    assert len({*identity, *parameters, *PAIR_COLUMNS}) == (
        len(identity) + len(parameters) + len(PAIR_COLUMNS)
    )
    out, _ = baseline
    first = sorted((out / "rows").glob("*.parquet"))[0]
    assert pq.read_schema(first).names == [*identity, *parameters, *PAIR_COLUMNS]
    rows = load_results(out)
    assert rows["eps"].isna().all() and rows["mu_c"].isna().all()
    assert rows["achieved_cr"].between(0, 1).all()


# --------------------------------------------------------------------------------------------
# studies checked before they start; one reversal width


def test_a_signal_the_simulated_plan_cannot_have_stops_the_study_before_simulating(
        tmp_path: Path) -> None:
    from funcnet.errors import StudyError
    from funcnet.study import run_study
    from funcnet.study.spec import Study

    study = Study(simulated="paper", signals=("RP", "AP", "QQ", "V"))
    with pytest.raises(StudyError, match="QQ cannot be in the simulated plan's traces"):
        run_study(study, tmp_path / "out", workers=0)
    assert not (tmp_path / "out" / "plan").exists()  # nothing was simulated


def test_reversal_windows_have_one_documented_width_in_demo_and_study(tmp_path: Path) -> None:
    import inspect

    from funcnet.paper import analyses
    from funcnet.study import load_study
    from funcnet.study.spec import REVERSAL_WIDTH

    assert REVERSAL_WIDTH == analyses.REVERSAL_WIDTH == 0.2
    default = inspect.signature(analyses.run_paper_analyses).parameters["reversal_width"]
    assert default.default == REVERSAL_WIDTH
    toml = tmp_path / "s.toml"
    toml.write_text('[recordings]\nsimulated = "paper"\n[[windows]]\nkind = "reversal"\n',
                    encoding="utf-8")
    (spec,) = load_study(toml).windows
    assert dict(spec.options)["width"] == REVERSAL_WIDTH


def test_fixed_windows_mostly_outside_their_phase_are_flagged(plan_dir: Path,
                                                              tmp_path: Path) -> None:
    from funcnet.study import run_study
    from funcnet.study.spec import Study, WindowSpec

    # V350 trials: the cruise lasts ~140 ms, so its 600 ms fixed window is mostly braking
    study = Study(recordings=tuple(sorted(plan_dir.glob("*.xml")))[:1],
                  windows=(WindowSpec("fixed"),), signals=("RP", "AP", "AC"),
                  parameters=(("delay", (5,)),), constant="drop")
    result = run_study(study, tmp_path / "out", workers=0)
    count, example = result.warnings["window_overrun"]
    assert count >= 1 and "'cruise'" in example and "% outside" in example
    document = json.loads((tmp_path / "out" / "study.json").read_text())
    assert "window_overrun" in document["run"]["warnings"]



# --------------------------------------------------------------------------------------------
# evidence and stability in a study

EVIDENCE_STUDY = """
[recordings]
paths = ["trace.csv"]
[[windows]]
kind = "range"
start = 0.2
stop = 0.8
[network]
delay = 5
[evidence]
enabled = true
surrogates = 19
alpha = 0.05
seed = 1
resamples = 0
"""


def test_evidence_rows_carry_the_columns_and_are_not_reused_across_settings(
        tmp_path: Path) -> None:
    from funcnet import functional_network
    from funcnet.network.schema import EVIDENCE_COLUMNS
    from funcnet.robot import read_recording

    trace = _small_trace(tmp_path)
    plain_file = _write(tmp_path, EVIDENCE_STUDY.split("[evidence]")[0], "plain.toml")
    out = tmp_path / "out"
    plain = run_study(load_study(plain_file), out, workers=0)
    assert not set(EVIDENCE_COLUMNS) & set(load_results(out).columns)

    study = load_study(_write(tmp_path, EVIDENCE_STUDY))
    assert dict(study.evidence)["surrogates"] == 19 and study.to_dict()["evidence"]["seed"] == 1
    first = run_study(study, out, workers=0)
    assert (first.computed, first.cached) == (plain.tasks, 0)  # not the cached plain rows
    rows = load_results(out)
    assert set(EVIDENCE_COLUMNS) <= set(rows.columns)
    # the library's evidence on the same window, same settings
    recording = read_recording(trace)
    part = recording.window(0.2, 0.8).data[rows["signals"].iloc[0].split(",")]
    expected = functional_network(part, delay=5, evidence=True, surrogates=19, seed=1,
                                  resamples=0, warn=False).pairs
    assert rows["coupling_p"].tolist() == pytest.approx(expected["coupling_p"].tolist())
    assert rows["evidence"].tolist() == expected["evidence"].tolist()
    # unchanged settings: cached; another alpha: computed again
    again = run_study(load_study(_write(tmp_path, EVIDENCE_STUDY)), out, workers=0)
    assert (again.computed, again.cached) == (0, first.tasks)
    other = run_study(load_study(_write(tmp_path, EVIDENCE_STUDY.replace("0.05", "0.1"),
                                        "alpha.toml")), out, workers=0)
    assert other.computed == first.tasks
    # the plain study's rows come back from the cache, without evidence
    back = run_study(load_study(plain_file), out, workers=0)
    assert back.computed == 0 and "coupling_p" not in load_results(out).columns


def test_disabled_evidence_keeps_the_plain_keys(tmp_path: Path) -> None:
    _small_trace(tmp_path)
    plain = load_study(_write(tmp_path, EVIDENCE_STUDY.split("[evidence]")[0], "plain.toml"))
    off = load_study(_write(tmp_path, EVIDENCE_STUDY.replace("enabled = true",
                                                             "enabled = false")))
    assert off.evidence == () and plain.evidence == ()
    out = tmp_path / "out"
    first = run_study(plain, out, workers=0)
    assert run_study(off, out, workers=0).cached == first.tasks


def test_stability_columns_in_the_rows(tmp_path: Path) -> None:
    from funcnet.network.stability import edge_stability
    from funcnet.robot import read_recording

    trace = _small_trace(tmp_path)
    text = (EVIDENCE_STUDY.split("[evidence]")[0]
            + "[stability]\nenabled = true\ngrid = {mu = [0.02, 0.1], dim = [2]}\n")
    out = tmp_path / "out"
    result = run_study(load_study(_write(tmp_path, text)), out, workers=0)
    assert result.computed == 1
    rows = load_results(out)
    assert {"stability", "stability_mu", "stability_dim", "stability_settings"} <= set(rows)
    part = read_recording(trace).window(0.2, 0.8).data[rows["signals"].iloc[0].split(",")]
    expected = edge_stability(part, delay=5, grid={"mu": [0.02, 0.1], "dim": [2]}).table
    assert rows["stability"].tolist() == pytest.approx(expected["stability"].tolist())
    # another grid: computed again
    other = run_study(load_study(_write(tmp_path, text.replace("0.02", "0.03"), "o.toml")), out,
                      workers=0)
    assert other.computed == 1


def test_example_evidence_study_loads() -> None:
    example = Path(__file__).parents[1] / "examples" / "evidence_study.toml"
    study = load_study(example)
    settings = dict(study.evidence)
    assert settings["resamples"] == 0 and settings["edge_rule"] == "paper"
    assert study.stability == ()


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_a_tasks_rows_read_back_as_its_network():
    from funcnet.network import functional_network
    from funcnet.study import network_from_rows
    from funcnet.study.store import rows_table

    rng = np.random.default_rng(3)
    # a signal with three values: a degenerate pair, kept as an edge under degenerate="keep"
    data = pd.DataFrame({"RP": np.sin(np.arange(300) / 9), "AC": rng.normal(size=300),
                         "MP": np.repeat([0.0, 1.0, 0.5], 100)})
    net = functional_network(data, delay=2, degenerate="keep", mu_c=0.02, eps=(None, None),
                             evidence=True, surrogates=9, resamples=0, warn=False)
    assert net.pairs["degenerate"].any()
    identity = {"recording": "r.csv", "trial": "t", "source_sha256": "", "window": "cruise 1",
                "phase": "cruise", "offset": 0.0, "start": 1.0, "stop": 1.6,
                "signals": ",".join(net.nodes), "constant": "drop", "dropped": "V"}
    rows = rows_table(identity, net.parameters, net.pairs).to_pandas()
    again = network_from_rows(rows)
    assert again.parameters == net.parameters and again.nodes == net.nodes
    assert again.pairs.equals(net.pairs) and again.edges.equals(net.edges)
    assert again.edges["degenerate"].any()  # the rows' own policy, not a guess
    assert again.window == {"label": "cruise 1", "start": 1.0, "stop": 1.6, "phase": "cruise",
                            "offset": 0.0, "source": "r.csv", "dropped": ("V",)}
    # rows of older results without the policy column, NaN where the flag was not written
    old = rows.drop(columns=["degenerate_policy"]).assign(degenerate=np.nan)
    plain = network_from_rows(old)
    assert plain.parameters.degenerate == NetworkParameters().degenerate
    assert not plain.pairs["degenerate"].any()
