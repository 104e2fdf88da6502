"""Benchmark of the engineer's report: `funcnet inspect` end to end on the real recordings.

Run from the repository root::

    python -m benchmarks.bench_inspect [--against DIR] [--rounds N] [--cases NAME ...]
                                       [--every-interval]

Times the whole command as a process (start-up, reading, phases, networks, evidence, figures,
page), one process per run, on every real recording there is: the KUKA KR 300 runs A and B
(whole robot; target 12 s on the 2-core machine, goal 10 s), the five UR5 runs and the
Mecademic MCS500 log shipped in ``data/`` (each with its channel map), and the SINUMERIK
trace when it is beside the clone (``../shared/data/sinumerik/``; left out, and said, when it
is not); every whole robot's target is 30 s. ``--cases`` picks recordings by the start of
their names (``KUKA``, ``UR5 No8``). Each run gives its wall seconds, the CPU seconds of the
process (user + system) and its peak resident memory: on a machine shared with other work the
wall time is inflated by the load, the CPU time much less (the load average is printed before
and after). With ``--against DIR`` another checkout's ``src`` is timed as well, alternating
with this one (a copy of another commit: ``git worktree add DIR COMMIT``); the ratio columns
compare each code with this checkout. ``--every-interval`` adds this code drawing every pair's
intervals (``--intervals all``: minutes on UR5 No5). Each checkout's ``src`` is byte-compiled
first, as an installed package is: where ``PYTHONDONTWRITEBYTECODE`` is set, a source tree is
otherwise compiled again by every process (about a second of start-up).
"""

from __future__ import annotations

import argparse
import compileall
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import NamedTuple

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "data"  # the SINUMERIK trace (no licence: not shipped)
SHIPPED = ROOT / "data"
_UR5 = ["--channels", str(ROOT / "examples" / "ur5-channels.toml")]
_KUKA = ["--channels", str(ROOT / "examples" / "kuka-kr300-channels.toml")]
CASES = {
    "SINUMERIK trace": [str(SHARED / "sinumerik" / "axis7-braking-trace.xml")],
    "KUKA run A, whole robot": [str(SHIPPED / "kuka-kr300" / "kr300-run-A.mat"), *_KUKA],
    "KUKA run B, whole robot": [str(SHIPPED / "kuka-kr300" / "kr300-run-B.mat"), *_KUKA],
    "UR5 No8, whole robot": [str(SHIPPED / "ur5" / "Movement_No8_Singularity_Free_1"), *_UR5],
    "UR5 No9 without disturbance, whole robot": [
        str(SHIPPED / "ur5" / "Movement_No9_Singularity_Free_NoDist"), *_UR5],
    "UR5 No9 with the force sensor, whole robot": [
        str(SHIPPED / "ur5" / "Movement_No9_Singularity_Free_ForceSensor"), *_UR5],
    "UR5 No5 without disturbance, whole robot": [
        str(SHIPPED / "ur5" / "Movement_No5_Acc_slow_no_disturbance"), *_UR5],
    "UR5 No5 with disturbance, whole robot": [
        str(SHIPPED / "ur5" / "Movement_No5_Acc_slow_w_disturbance"), *_UR5],
    "MCS500, whole robot": [str(SHIPPED / "mecademic-mcs500" / "mcs500-two-cycles.csv"),
                            "--channels", str(ROOT / "examples" / "mecademic-channels.toml")],
}
#: Wall seconds on the quiet 2-core machine.
TARGETS = {name: 12.0 if name.startswith("KUKA") else 30.0 for name in CASES}


class Run(NamedTuple):
    """One process: wall and CPU seconds, peak resident memory in MiB."""

    wall: float
    cpu: float
    peak: float


def time_inspect(source: Path, arguments: list[str]) -> Run:
    """One `funcnet inspect` process importing ``source/src``: its wall, CPU and peak memory."""
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    command = [sys.executable, "-c", "from funcnet.cli import main; main()", "inspect",
               *arguments, "--quiet"]
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        process = subprocess.Popen([*command, "-o", out], cwd=ROOT, env=environment,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        # wait4, not the children's rusage: its peak memory is this process's alone
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
        stderr = process.stderr.read().decode() if process.stderr else ""
        if process.stderr:
            process.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"funcnet inspect {' '.join(arguments)} failed:\n{stderr}")
    return Run(wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024)


def _cases(names: list[str] | None) -> dict[str, list[str]]:
    """The recordings asked for (all by default) that are there; one line for each left out."""
    chosen = {}
    for name, arguments in CASES.items():
        if names is not None and not any(name.startswith(n) for n in names):
            continue
        if not Path(arguments[0]).exists():
            print(f"# {name}: {arguments[0]} is not there, left out")
            continue
        chosen[name] = arguments
    return chosen


def _row(case: str, name: str, runs: list[Run], mine: Run) -> str:
    """One table row: medians over the rounds, each round's wall time, ratios to this code."""
    wall = statistics.median(r.wall for r in runs)
    cpu = statistics.median(r.cpu for r in runs)
    peak = max(r.peak for r in runs)
    rounds = ", ".join(f"{r.wall:.1f}" for r in runs)
    target = TARGETS.get(case)
    return (f"| {case} | {name} | **{wall:.1f}** ({rounds}) | {cpu:.1f} | {peak:.0f} | "
            f"{wall / mine.wall:.2f} | {cpu / mine.cpu:.2f} | "
            f"{'' if target is None else f'{target:.0f}'} |")


def add_common_arguments(parser: argparse.ArgumentParser) -> None:
    """``--against``, ``--rounds``, ``--cases``: what this benchmark and bench_figures share."""
    parser.add_argument("--against", type=Path, default=None,
                        help="another checkout (its src/ is imported) to compare with")
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--cases", nargs="*", default=None,
                        help="recordings to run (the start of a name each: KUKA, UR5 No8)")


def checkouts(args: argparse.Namespace) -> dict[str, Path]:
    """This checkout, after the one ``--against`` names, each byte-compiled as installed (no
    process compiles the sources again)."""
    codes = {"this checkout": ROOT}
    if args.against is not None:
        codes = {"before (--against)": args.against.resolve(), **codes}
    for source in set(codes.values()):
        compileall.compile_dir(source / "src", quiet=1)
    return codes


def main(argv: list[str] | None = None) -> None:
    """Print the table: one row per recording and code."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    add_common_arguments(parser)
    parser.add_argument("--every-interval", action="store_true",
                        help="also this code drawing every pair's intervals (--intervals all)")
    args = parser.parse_args(argv)
    runs: dict[str, tuple[Path, list[str]]] = {"this checkout": (ROOT, [])}
    if args.against is not None:
        runs = {"before (--against)": (args.against.resolve(), []), **runs}
    if args.every_interval:
        runs["every interval (--intervals all)"] = (ROOT, ["--intervals", "all"])
    cases = _cases(args.cases)
    for source in {source for source, _ in runs.values()}:
        compileall.compile_dir(source / "src", quiet=1)
    print("## funcnet inspect, end to end (one process per run)\n")
    print(f"- {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, "
          f"load average before: {os.getloadavg()[0]:.2f} (1 min)\n")
    print("| recording | code | wall [s], median (rounds) | CPU [s] | peak [MiB] | wall / this "
          "| CPU / this | target [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for case, arguments in cases.items():
        found: dict[str, list[Run]] = {name: [] for name in runs}
        for _ in range(args.rounds):
            for name, (source, extra) in runs.items():
                found[name].append(time_inspect(source, [*arguments, *extra]))
        mine = Run(statistics.median(r.wall for r in found["this checkout"]),
                   statistics.median(r.cpu for r in found["this checkout"]), 0.0)
        for name in runs:
            print(_row(case, name, found[name], mine), flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
