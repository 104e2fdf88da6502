"""Benchmark of what `funcnet inspect` computes, without the page: the networks and evidence.

Run from the repository root::

    python -m benchmarks.bench_compute [--against DIR] [--rounds N] [--cases NAME ...]
                                       [--robot-network]

Times the computation of a robot page alone -- reading, phases, the robot network and each
axis's networks with their evidence, the warnings: the iteration of
:func:`funcnet.inspection.inspect_files`, with its default settings -- and not the figures and
page drawn after it (:mod:`benchmarks.bench_figures` times those). One process per run, on the
recordings of :mod:`benchmarks.bench_inspect` (``--cases`` picks them by the start of their
names: ``KUKA run A``, ``UR5 No5 with``). Each run gives the span's wall seconds and the CPU
seconds of the process over it (every thread's), and the peak resident memory of the process.
With ``--against DIR`` another checkout's ``src`` is timed too, alternating with this one
(``git worktree add DIR COMMIT``); the ratio column compares each code's CPU with this
checkout's. The load average is printed before and after: CPU seconds are the figure to compare
on a shared machine.

With ``--robot-network`` each process times the robot network alone (its measures, evidence and
direction reading: ``funcnet.inspection.robot._robot_network``, as ``inspect_robot`` calls it,
in the calling thread): one call to load the compiled kernels, then the median of three.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from benchmarks.bench_inspect import ROOT, _cases, add_common_arguments, checkouts

# The child: the span of the iteration alone (imports and the page left out), as JSON.
CHILD = """
import json, resource, sys, time, warnings
from funcnet.inspection import inspect_files
warnings.simplefilter("ignore")
arguments = sys.argv[1:]
channels = arguments[arguments.index("--channels") + 1] if "--channels" in arguments else None
found = inspect_files(arguments[0], channels=channels)
wall, cpu = time.perf_counter(), time.process_time()
list(iter(found))
wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps({"wall": wall, "cpu": cpu, "peak": peak}))
"""

# The child of --robot-network: the robot network alone, as inspect_robot computes it.
CHILD_ROBOT = """
import json, resource, statistics, sys, time, warnings
from funcnet.inspection.robot import _ready, _robot_network, robot_windows
from funcnet.inspection.run import in_axis_units
from funcnet.parameters import EvidenceSettings, resolve
from funcnet.robot import paper_nodes, read_trace
warnings.simplefilter("ignore")
arguments = sys.argv[1:]
channels = arguments[arguments.index("--channels") + 1] if "--channels" in arguments else None
recording, _ = in_axis_units(read_trace(arguments[0], channels=channels, keep_setpoint=True))
p = resolve(None, {})
nodes = paper_nodes(recording.data.columns)
windows, _ = robot_windows(recording, p)
_ready(recording)
walls, cpus = [], []
for _ in range(4):  # the first loads the compiled kernels
    wall, cpu = time.perf_counter(), time.process_time()
    _robot_network(recording, windows, nodes, p, True, EvidenceSettings())
    walls.append(time.perf_counter() - wall)
    cpus.append(time.process_time() - cpu)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps({"wall": statistics.median(walls[1:]), "cpu": statistics.median(cpus[1:]),
                  "peak": peak}))
"""


def time_compute(source: Path, arguments: list[str], child: str = CHILD) -> dict[str, float]:
    """One process importing ``source/src``: the computation's wall and CPU seconds, the peak
    memory in MiB."""
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    done = subprocess.run([sys.executable, "-c", child, *arguments], cwd=ROOT, env=environment,
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"inspecting {' '.join(arguments)} failed:\n{done.stderr}")
    return dict(json.loads(done.stdout.strip().splitlines()[-1]))


def _load() -> str:
    return "load {:.1f} {:.1f} {:.1f}".format(*os.getloadavg())


def main(argv: list[str] | None = None) -> None:
    """Print the table: one row per recording and code."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    add_common_arguments(parser)
    parser.add_argument("--robot-network", action="store_true",
                        help="time the robot network alone (median of three calls)")
    args = parser.parse_args(argv)
    codes = checkouts(args)
    cases = _cases(args.cases)
    if args.robot_network:  # a one-axis trace has no robot network
        for case in [case for case in cases if "whole robot" not in case]:
            print(f"# {case}: one axis, no robot network: left out")
            del cases[case]
    child = CHILD_ROBOT if args.robot_network else CHILD
    what = "the robot network alone" if args.robot_network else "the computation alone"
    print(f"## funcnet inspect, {what} (one process per run; {_load()})\n")
    print("| recording | code | CPU [s] (each round) | wall [s] | peak [MiB] | CPU / this |")
    print("|---|---|---|---|---|---|")
    for case, arguments in cases.items():
        runs: dict[str, list[dict[str, float]]] = {name: [] for name in codes}
        for _ in range(args.rounds):
            for name, source in codes.items():  # alternating: the load falls on both alike
                runs[name].append(time_compute(source, arguments, child))
        mine = statistics.median(r["cpu"] for r in runs["this checkout"])
        for name, found in runs.items():
            cpu = statistics.median(r["cpu"] for r in found)
            rounds = ", ".join(f"{r['cpu']:.1f}" for r in found)
            print(f"| {case} | {name} | **{cpu:.1f}** ({rounds}) | "
                  f"{statistics.median(r['wall'] for r in found):.1f} | "
                  f"{max(r['peak'] for r in found):.0f} | {cpu / mine:.2f} |", flush=True)
    print(f"\n{_load()}")


if __name__ == "__main__":
    main()
