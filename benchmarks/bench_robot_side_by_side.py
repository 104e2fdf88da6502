"""Benchmark of a robot's inspection side by side: `inspect_robot` one computation after the
other, in threads, and in forked processes, each in a fresh process.

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE PYTHONPATH=src python -m benchmarks.bench_robot_side_by_side \
        [--rounds N] [--cases KUKA "UR5 No5 wd"]

Times the computation behind a robot page (`funcnet.inspection.inspect_robot`, no drawing) on
the shipped recordings, with ``workers=1`` (the robot network, then each axis), with the
default in threads, and with the default in forked processes (a process that has not started
Numba's thread pool, as the command line), alternating; each run in a fresh interpreter, its
wall and CPU seconds (its own and its children's, over the call) printed with the load
average; checks that the three give the same pairs tables bit for bit.
"""

from __future__ import annotations

import argparse
import os
import pickle
import resource
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "KUKA run A": ("data/kuka-kr300/kr300-run-A.mat", "examples/kuka-kr300-channels.toml"),
    "UR5 No8": ("data/ur5/Movement_No8_Singularity_Free_1", "examples/ur5-channels.toml"),
    "UR5 No5 wd": ("data/ur5/Movement_No5_Acc_slow_w_disturbance",
                   "examples/ur5-channels.toml"),
}
MODES = ("one after the other", "threads", "processes")


def _tables(found) -> dict[str, np.ndarray]:
    """Every pairs table of a robot inspection, its numbers as raw bits."""
    tables = {f"robot / {k}": net.pairs for k, net in found.networks.items()}
    for axis, one in found.axes.items():
        tables.update({f"axis {axis} / {k}": net.pairs for k, net in one.networks.items()})
    return {key: table.select_dtypes("number").to_numpy(np.float64, na_value=np.nan).view(np.int64)
            for key, table in tables.items()}


def _cpu() -> float:
    own, children = (resource.getrusage(who) for who in (resource.RUSAGE_SELF,
                                                         resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _one(case: str, mode: str, out: str) -> None:
    """One timed run in this (fresh) process; (wall, CPU, tables) pickled to ``out``."""
    from funcnet.inspection import _side_by_side, inspect_robot
    from funcnet.robot import read_trace
    from funcnet.robot.units import in_axis_units

    warnings.simplefilter("ignore")
    path, channels = CASES[case]
    recording, _ = in_axis_units(read_trace(ROOT / path, channels=ROOT / channels,
                                            keep_setpoint=True))
    if mode == "threads":
        _side_by_side.threadsafe_layer()  # Numba's pool started here: no fork, threads
    began, cpu = time.perf_counter(), _cpu()
    found = inspect_robot(recording, workers=1 if mode == MODES[0] else None)
    wall, spent = time.perf_counter() - began, _cpu() - cpu
    with open(out, "wb") as f:
        pickle.dump((wall, spent, _tables(found)), f)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--cases", nargs="*", default=list(CASES))
    parser.add_argument("--one", nargs=3, metavar=("CASE", "MODE", "OUT"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        _one(*args.one)
        return
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs\n")
    print("| recording | computed | wall [s] | CPU [s] | load (1 min) |\n|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for case in args.cases:
            tables = {}
            for _ in range(args.rounds):
                for mode in MODES:
                    out = str(Path(folder) / "run.pickle")
                    subprocess.run([sys.executable, "-m", "benchmarks.bench_robot_side_by_side",
                                    "--one", case, mode, out], check=True, cwd=ROOT)
                    with open(out, "rb") as f:
                        wall, spent, tables[mode] = pickle.load(f)
                    print(f"| {case} | {mode} | {wall:.1f} | {spent:.1f} "
                          f"| {os.getloadavg()[0]:.1f} |", flush=True)
            one = tables[MODES[0]]
            same = all(t.keys() == one.keys() and all(np.array_equal(one[k], t[k]) for k in one)
                       for t in tables.values())
            print(f"| {case} | | {len(one)} pairs tables, the same bit for bit: {same} | | |")


if __name__ == "__main__":
    main()
