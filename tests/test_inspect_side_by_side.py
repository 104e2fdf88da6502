"""A robot's inspection computed side by side, in forked processes or threads: the same
results, warnings and progress as one computation after the other, whatever the scheduling."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io

from funcnet.errors import FuncnetWarning, RecordingWarning, ThresholdWarning
from funcnet.inspection import _side_by_side, inspect_robot
from funcnet.inspection._side_by_side import run_in_order
from funcnet.robot import read_trace

MAP = {"rec.t": "time", "rp": "RP", "ap": "AP", "mp": "MP", "tau": "AC"}


@pytest.fixture(scope="module")
def three_axes(tmp_path_factory) -> Path:
    """Three axes at 250 Hz, moves out and back; axis 3's torque holds still while it rests,
    so that windows leave it out (a warning), and the robot network flags pairs."""
    t = np.arange(0, 4, 0.004)
    rng = np.random.default_rng(11)
    rp = np.vstack([10 * np.sin(np.pi * t / 4) ** 2, -6 * np.sin(np.pi * t / 2) ** 2,
                    3 * np.clip(np.sin(np.pi * (t - 2) / 2), 0, None) ** 2])
    mp = rp + 0.001 * rng.standard_normal(rp.shape)
    ap = mp - 0.01 * np.gradient(rp, t, axis=1) + 0.0005 * rng.standard_normal(rp.shape)
    tau = np.gradient(np.gradient(rp, t, axis=1), t, axis=1) + 0.05 * rng.standard_normal(
        rp.shape)
    tau[2, t < 2] = 0.0
    path = tmp_path_factory.mktemp("robot") / "three-axes.mat"
    scipy.io.savemat(path, {"rec": {"t": t, "rp": rp, "ap": ap, "mp": mp, "tau": tau}})
    return path


def _inspected(path: Path, workers: int, **options) -> tuple[object, list[tuple], list[tuple]]:
    """The inspection, the warnings it emitted (class, text, file, line, in order) and its
    progress."""
    recording = read_trace(path, channels=MAP)
    calls: list[tuple] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        found = inspect_robot(recording, delay=5, workers=workers, **options,
                              evidence_options={"surrogates": 19, "resamples": 20},
                              progress=lambda *a: calls.append(a))
    return found, [(type(w.message), str(w.message), w.filename, w.lineno)
                   for w in caught], calls


def _same_table(a: pd.DataFrame, b: pd.DataFrame) -> None:
    """Equal bit for bit: the same columns, dtypes and values (NaN where NaN)."""
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        x, y = a[name].to_numpy(), b[name].to_numpy()
        assert x.dtype == y.dtype, name
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.int64), y.view(np.int64)), name
        else:
            assert x.tolist() == y.tolist(), name


def test_threads_give_the_serial_inspection_bit_for_bit(three_axes, monkeypatch):
    monkeypatch.setattr(_side_by_side, "forkable", lambda: False)
    serial, serial_warnings, serial_progress = _inspected(three_axes, workers=1)
    threaded, threaded_warnings, threaded_progress = _inspected(three_axes, workers=2)
    assert threaded.networks and list(threaded.networks) == list(serial.networks)
    for label, net in serial.networks.items():
        _same_table(threaded.networks[label].pairs, net.pairs)
        _same_table(threaded.networks[label].edges, net.edges)
    assert threaded.failures == serial.failures
    assert threaded.windows_note == serial.windows_note
    assert threaded.axis_errors == serial.axis_errors
    assert list(threaded.axes) == list(serial.axes) == [1, 2, 3]
    for axis, alone in serial.axes.items():
        other = threaded.axes[axis]
        assert list(other.networks) == list(alone.networks)
        for label, net in alone.networks.items():
            _same_table(other.networks[label].pairs, net.pairs)
        assert other.failures == alone.failures
        assert other.backlash_error == alone.backlash_error
        assert (other.backlash is None) == (alone.backlash is None)
        _same_table(other.moves, alone.moves)
        _same_table(other.problems, alone.problems)
    # the warnings of each computation, in the order of a loop over them, and the same steps
    # (where each is attributed to too: the line that called inspect_robot)
    assert any(issubclass(w[0], RecordingWarning) for w in serial_warnings)
    assert __file__ in {w[2] for w in serial_warnings}
    assert threaded_warnings == serial_warnings
    assert threaded_progress == serial_progress
    assert serial_progress[0][2] == "robot network" and serial_progress[-1][2] == "done"


def _emitting(name: str, barrier: threading.Barrier, category: type[Warning] = UserWarning):
    """A job that waits for the other, then warns three times, yielding between warnings."""

    def job() -> str:
        barrier.wait(timeout=30)
        for k in range(3):
            warnings.warn(category(f"{name} {k}"), stacklevel=1)
            time.sleep(0.01)  # the other thread warns meanwhile
        return name

    return job


def test_the_warnings_of_two_concurrent_jobs_stay_apart_in_their_order():
    for _ in range(5):  # schedulings differ from run to run; the result must not
        barrier = threading.Barrier(2)
        jobs = [_emitting("first", barrier), _emitting("second", barrier)]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            seen_in = []
            results = run_in_order(jobs, workers=2, done=seen_in.append, processes=False)
        assert results == ["first", "second"] and seen_in == [0, 1]
        assert [str(w.message) for w in caught] == [
            "first 0", "first 1", "first 2", "second 0", "second 1", "second 2"]
        assert all(w.filename == __file__ for w in caught)  # where each was raised


def test_the_callers_filters_decide_once_the_jobs_are_done():
    barrier = threading.Barrier(2)
    jobs = [_emitting("threshold", barrier, ThresholdWarning),
            _emitting("user", barrier, UserWarning)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", FuncnetWarning)
        run_in_order(jobs, workers=2, processes=False)
    assert [str(w.message) for w in caught] == ["user 0", "user 1", "user 2"]
    # the filters the caller set are in force again: the capture is gone
    with warnings.catch_warnings(record=True) as after:
        warnings.simplefilter("always")
        warnings.warn("after", stacklevel=1)
    assert [str(w.message) for w in after] == ["after"]


def test_an_error_of_a_job_is_raised_after_the_warnings_before_it():
    barrier = threading.Barrier(2)

    def failing() -> str:
        barrier.wait(timeout=30)
        warnings.warn("about to fail", stacklevel=1)
        raise ValueError("the second job failed")

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(ValueError, match="second job failed"):
            run_in_order([_emitting("first", barrier), failing], workers=2,
                         processes=False)
    assert [str(w.message) for w in caught] == ["first 0", "first 1", "first 2",
                                               "about to fail"]


def test_a_callers_own_thread_computes_in_one_thread():
    from concurrent.futures import ThreadPoolExecutor

    from funcnet.inspection._side_by_side import default_workers

    with ThreadPoolExecutor(max_workers=1) as pool:
        assert pool.submit(default_workers).result() == 1
    assert 1 <= default_workers() <= 4


def test_a_layer_that_cannot_take_two_threads_runs_the_jobs_in_the_callers_thread(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # Numba's workqueue layer stops the process when two threads enter parallel regions.
    monkeypatch.setattr(_side_by_side, "threadsafe_layer", lambda: False)
    names = run_in_order([threading.current_thread] * 3, workers=2, processes=False)
    assert names == [threading.main_thread()] * 3



def _warning_job(name: str, category: type[Warning] = UserWarning, fail: bool = False):
    """A job that warns three times and returns its process id (or raises)."""

    def job() -> tuple[str, int]:
        for k in range(3):
            warnings.warn(category(f"{name} {k}"), stacklevel=1)
        if fail:
            raise ValueError(f"{name} failed")
        return name, os.getpid()

    return job


def test_processes_give_results_warnings_and_steps_in_order():
    jobs = [_warning_job("first"), _warning_job("second", ThresholdWarning),
            _warning_job("third")]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", FuncnetWarning)  # the caller's filters decide
        seen_in: list[int] = []
        results = run_in_order(jobs, workers=2, done=seen_in.append, processes=True)
    assert [name for name, _ in results] == ["first", "second", "third"] and seen_in == [0, 1, 2]
    assert os.getpid() not in {pid for _, pid in results}  # computed in the children
    assert [str(w.message) for w in caught] == [
        "first 0", "first 1", "first 2", "third 0", "third 1", "third 2"]
    assert all(w.filename == __file__ for w in caught)


def test_a_default_filter_shows_a_childs_warning_once_per_place():
    # the registry of the place a warning is attributed to is the caller's, not a child's copy
    jobs = [_warning_job("same", UserWarning)] * 2
    with warnings.catch_warnings(record=True) as caught:
        warnings.resetwarnings()
        warnings.simplefilter("default")
        run_in_order([lambda: warnings.warn("once", stacklevel=1)] * 3, workers=2,
                     processes=True)
        run_in_order(jobs, workers=2, processes=True)
    assert [str(w.message) for w in caught] == ["once", "same 0", "same 1", "same 2"]


def test_an_error_in_a_child_is_raised_after_the_warnings_before_it():
    jobs = [_warning_job("first"), _warning_job("second", fail=True), _warning_job("third")]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(ValueError, match="second failed"):
            run_in_order(jobs, workers=2, processes=True)
    assert [str(w.message) for w in caught][:6] == [
        "first 0", "first 1", "first 2", "second 0", "second 1", "second 2"]


def test_processes_are_not_forked_once_numbas_thread_pool_runs():
    # a child of a process whose OpenMP pool runs would hang in its first parallel region
    _side_by_side.threadsafe_layer.__wrapped__()  # a parallel region: the pool starts
    assert not _side_by_side.forkable()


_FRESH = """
import pickle, sys, warnings
from numba.np.ufunc import parallel
from funcnet.inspection import _side_by_side, inspect_robot
from funcnet.robot import read_trace

def inspected(workers):
    calls = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        found = inspect_robot(read_trace(sys.argv[1], channels=MAP), delay=5, workers=workers,
                              evidence_options={"surrogates": 19, "resamples": 20},
                              progress=lambda *a: calls.append(a))
    return found, [(type(w.message).__name__, str(w.message), w.lineno) for w in caught], calls

forked = _side_by_side.forkable()
side_by_side = inspected(2)
pool_here = parallel._is_initialized  # False: the parallel kernels ran in the children
with open(sys.argv[2], "wb") as out:
    pickle.dump((forked, pool_here, side_by_side, inspected(1)), out)
"""


def test_a_fresh_process_computes_in_children_the_serial_inspection_bit_for_bit(
        three_axes, tmp_path):
    script = tmp_path / "fresh.py"
    script.write_text(f"MAP = {MAP!r}\n" + _FRESH)
    out = tmp_path / "found.pickle"
    subprocess.run([sys.executable, str(script), str(three_axes), str(out)], check=True,
                   timeout=600)
    with out.open("rb") as f:
        forked, pool_here, (found, found_warnings, found_steps), (serial, serial_warnings,
                                                                  serial_steps) = pickle.load(f)
    assert forked and not pool_here
    for label, net in serial.networks.items():
        _same_table(found.networks[label].pairs, net.pairs)
    for axis, alone in serial.axes.items():
        for label, net in alone.networks.items():
            _same_table(found.axes[axis].networks[label].pairs, net.pairs)
        _same_table(found.axes[axis].moves, alone.moves)
    assert found.failures == serial.failures and found.axis_errors == serial.axis_errors
    assert any(name == "RecordingWarning" for name, *_ in serial_warnings)
    assert found_warnings == serial_warnings and found_steps == serial_steps
