"""Benchmark of a robot's inspection in threads: `inspect_robot` with one worker and with the
default, in one process, alternating.

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE PYTHONPATH=src python -m benchmarks.bench_robot_threads \
        [--rounds N] [--cases KUKA "UR5 No8"]

Times the computation behind a robot page (`funcnet.inspection.inspect_robot`, no drawing) on
the shipped KUKA run A and UR5 No8, once with ``workers=1`` (the robot network, then each
axis, one after the other) and once with the default (side by side in threads), alternating;
prints each run's wall and CPU seconds (the process's user + system over the call) and the
load average, and checks that both give the same pairs tables bit for bit.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "KUKA run A": ("data/kuka-kr300/kr300-run-A.mat", "examples/kuka-kr300-channels.toml"),
    "UR5 No8": ("data/ur5/Movement_No8_Singularity_Free_1", "examples/ur5-channels.toml"),
}


def _tables(found) -> dict[str, np.ndarray]:
    """Every pairs table of a robot inspection, its numbers as raw bits."""
    tables = {f"robot / {k}": net.pairs for k, net in found.networks.items()}
    for axis, one in found.axes.items():
        tables.update({f"axis {axis} / {k}": net.pairs for k, net in one.networks.items()})
    return {key: table.select_dtypes("number").to_numpy(np.float64, na_value=np.nan).view(np.int64)
            for key, table in tables.items()}


def main() -> None:
    from funcnet.inspection import inspect_robot
    from funcnet.inspection._threads import default_workers
    from funcnet.robot import read_trace
    from funcnet.robot.units import in_axis_units

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--cases", nargs="*", default=list(CASES))
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, "
          f"default workers {default_workers()}\n")
    print("| recording | workers | wall [s] | CPU [s] | load (1 min) |\n|---|---|---|---|---|")
    for case in args.cases:
        path, channels = CASES[case]
        recording, _ = in_axis_units(read_trace(ROOT / path, channels=ROOT / channels,
                                                keep_setpoint=True))
        found = {}
        for _ in range(args.rounds):
            for workers in (1, default_workers()):
                began, cpu = time.perf_counter(), os.times()
                found[workers] = inspect_robot(recording, workers=workers)
                after = os.times()
                spent = after.user - cpu.user + after.system - cpu.system
                print(f"| {case} | {workers} | {time.perf_counter() - began:.1f} | {spent:.1f} "
                      f"| {os.getloadavg()[0]:.1f} |", flush=True)
        one, many = (_tables(found[w]) for w in (1, default_workers()))
        same = one.keys() == many.keys() and all(np.array_equal(one[k], many[k]) for k in one)
        print(f"| {case} | | {len(one)} pairs tables, the same bit for bit: {same} | | |")


if __name__ == "__main__":
    main()
