"""Benchmark of the engineer's report: `funcnet inspect` end to end on the real recordings.

Run from the repository root::

    python -m benchmarks.bench_inspect [--against DIR] [--rounds N] [--no-kuka]

Times the whole command as a process (start-up, reading, phases, networks, evidence, figures,
page) on the SINUMERIK trace (``../shared/data/sinumerik/axis7-braking-trace.xml``; budget
120 s on the 2-core machine) and on the whole KUKA KR 300 run A with its channel map (all six
axes and the robot-wide network with evidence; budget 3 min). With ``--against DIR`` another
checkout's ``src`` is timed the same way, the two alternating. The machine may be shared: the
load average is printed before and after.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "data"
CASES = {
    "SINUMERIK trace": ([str(SHARED / "sinumerik" / "axis7-braking-trace.xml")], 120.0),
    "KUKA run A, whole robot": ([str(SHARED / "kuka-kr300" / "kr300-run-A.mat"), "--channels",
                                 str(ROOT / "examples" / "kuka-kr300-channels.toml")], 180.0),
}


def time_inspect(source: Path, arguments: list[str]) -> float:
    """Wall seconds of one `funcnet inspect` process importing ``source/src``."""
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    command = [sys.executable, "-c", "from funcnet.cli import main; main()", "inspect",
               *arguments, "--quiet"]
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([*command, "-o", out], check=True, capture_output=True, cwd=ROOT,
                       env=environment)
        return time.perf_counter() - start


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--against", type=Path, default=None,
                        help="another checkout (its src/ is imported) to compare with")
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--no-kuka", action="store_true", help="the SINUMERIK trace only")
    args = parser.parse_args(argv)
    checkouts = {"this checkout": ROOT}
    if args.against is not None:
        checkouts = {"before": args.against.resolve(), "after": ROOT}
    cases = {name: case for name, case in CASES.items()
             if not (args.no_kuka and name.startswith("KUKA"))}
    print("## funcnet inspect, end to end (one process)\n")
    print(f"- load average before: {os.getloadavg()[0]:.2f} (1 min)\n")
    print("| recording | code | wall [s], median (rounds) | budget [s] |")
    print("|---|---|---|---|")
    for case, (arguments, budget) in cases.items():
        times: dict[str, list[float]] = {name: [] for name in checkouts}
        for _ in range(args.rounds):
            for name, source in checkouts.items():
                times[name].append(time_inspect(source, arguments))
        for name, walls in times.items():
            print(f"| {case} | {name} | **{statistics.median(walls):.0f}** "
                  f"({', '.join(f'{w:.0f}' for w in walls)}) | {budget:.0f} |")
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
