"""Benchmark of the engineer's report: `funcnet inspect` end to end on the real recordings.

Run from the repository root::

    python -m benchmarks.bench_inspect [--against DIR] [--rounds N] [--cases NAME ...]
                                       [--no-every-interval]

Times the whole command as a process (start-up, reading, phases, networks, evidence, figures,
page) on the SINUMERIK trace, on the whole KUKA KR 300 run A with its channel map (six axes and
the robot-wide network with evidence; target 20 s on the 2-core machine) and on the UR5 run
Movement_No8_Singularity_Free_1 (six joints; target 30 s). The UR5 run
Movement_No5_Acc_slow_no_disturbance (26 s; its 30-node robot network is testable, so 435
pairs' intervals are drawn: minutes) runs only when named (``--cases "UR5 No5"``). In the same
run the competitor is the same code drawing every pair's intervals (``--intervals all``: the old
path, where the intervals of pairs whose coupling test cannot reach alpha were bootstrapped too;
``--no-every-interval`` leaves it out); with ``--against DIR`` another checkout's ``src`` is
timed as well (a copy of another branch: ``git archive main | tar -x -C DIR``). The runs
alternate. Each gives its wall seconds and the CPU seconds of the process (user + system): on a
machine shared with other work the wall time is inflated by the load, the CPU time much less
(the load average is printed before and after).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "data"  # the SINUMERIK trace (no licence: not shipped)
SHIPPED = ROOT / "data"
CASES = {
    "SINUMERIK trace": [str(SHARED / "sinumerik" / "axis7-braking-trace.xml")],
    "KUKA run A, whole robot": [str(SHIPPED / "kuka-kr300" / "kr300-run-A.mat"), "--channels",
                                str(ROOT / "examples" / "kuka-kr300-channels.toml")],
    "UR5 No8, six joints": [str(SHIPPED / "ur5" / "Movement_No8_Singularity_Free_1"),
                            "--channels", str(ROOT / "examples" / "ur5-channels.toml")],
}
TARGETS = {"KUKA run A, whole robot": 20.0, "UR5 No8, six joints": 30.0}
# Named only: minutes per run.
OPT_IN = {"UR5 No5, six joints": [str(SHIPPED / "ur5" / "Movement_No5_Acc_slow_no_disturbance"),
                                  "--channels", str(ROOT / "examples" / "ur5-channels.toml")]}


def time_inspect(source: Path, arguments: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds of one `funcnet inspect` process importing ``source/src``."""
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    command = [sys.executable, "-c", "from funcnet.cli import main; main()", "inspect",
               *arguments, "--quiet"]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([*command, "-o", out], check=True, capture_output=True, cwd=ROOT,
                       env=environment)
        wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--against", type=Path, default=None,
                        help="another checkout (its src/ is imported) to compare with")
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--cases", nargs="*", default=None,
                        help="case names to run (a prefix each: SINUMERIK, KUKA, UR5)")
    parser.add_argument("--no-every-interval", action="store_true",
                        help="leave out the competitor drawing every pair's intervals")
    args = parser.parse_args(argv)
    runs: dict[str, tuple[Path, list[str]]] = {
        "every interval (--intervals all)": (ROOT, ["--intervals", "all"]),
        "this checkout": (ROOT, []),
    }
    if args.no_every_interval:
        del runs["every interval (--intervals all)"]
    if args.against is not None:
        runs = {"before (--against)": (args.against.resolve(), []), **runs}
    cases = {name: case for name, case in CASES.items()
             if args.cases is None or any(name.startswith(c) for c in args.cases)}
    cases.update({name: case for name, case in OPT_IN.items()
                  if args.cases is not None and any(name.startswith(c) for c in args.cases)})
    print("## funcnet inspect, end to end (one process)\n")
    print(f"- load average before: {os.getloadavg()[0]:.2f} (1 min)\n")
    print("| recording | code | wall [s], median (rounds) | CPU [s] | wall / this | CPU / this "
          "| target [s] |")
    print("|---|---|---|---|---|---|---|")
    for case, arguments in cases.items():
        walls: dict[str, list[float]] = {name: [] for name in runs}
        cpus: dict[str, list[float]] = {name: [] for name in runs}
        for _ in range(args.rounds):
            for name, (source, extra) in runs.items():
                wall, cpu = time_inspect(source, [*arguments, *extra])
                walls[name].append(wall)
                cpus[name].append(cpu)
        mine = statistics.median(walls["this checkout"])
        mine_cpu = statistics.median(cpus["this checkout"])
        target = TARGETS.get(case)
        for name in runs:
            wall = statistics.median(walls[name])
            cpu = statistics.median(cpus[name])
            rounds = ", ".join(f"{w:.0f}" for w in walls[name])
            print(f"| {case} | {name} | **{wall:.0f}** ({rounds}) | {cpu:.0f} | "
                  f"{wall / mine:.1f} | {cpu / mine_cpu:.1f} | "
                  f"{'' if target is None else f'{target:.0f}'} |", flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
