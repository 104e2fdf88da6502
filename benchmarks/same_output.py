"""The same pages, JSON and figures before and after a change that should not change them.

Run from the repository root, once with the code before the change and once with it after::

    PYTHONPATH=/path/to/old/src python -m benchmarks.same_output run /tmp/before
    PYTHONPATH=src python -m benchmarks.same_output run /tmp/after
    python -m benchmarks.same_output compare /tmp/before /tmp/after

``run`` calls a fixed set of commands on the shipped recordings, each in a process of its own
(``funcnet inspect`` of the KUKA KR 300's run A, the UR5's Movement_No8 and the MCS500's log,
every axis; ``funcnet network`` and ``funcnet backlash`` of the KUKA's axis 1; ``funcnet
backlash`` of the UR5 run) and keeps what each wrote and printed. ``compare`` says every file
that differs: JSON, CSV and PNG byte for byte; HTML and the printed lines with what a run cannot
repeat masked (the date, the output folder, the computation time); the timing line on stderr
left out. Exit status 0 when all are the same. The commands take about 10 minutes on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KUKA = ("data/kuka-kr300/kr300-run-A.mat", "--channels", "examples/kuka-kr300-channels.toml")
UR5 = ("data/ur5/Movement_No8_Singularity_Free_1", "--channels", "examples/ur5-channels.toml")
MCS = ("data/mecademic-mcs500/mcs500-two-cycles.csv", "--channels",
       "examples/mecademic-channels.toml")
# name -> (arguments, the output it writes, relative to the run's folder)
COMMANDS = {
    "kuka": (("inspect", *KUKA), "kuka"),
    "ur5": (("inspect", *UR5), "ur5"),
    "mcs": (("inspect", *MCS), "mcs500"),
    "kuka-net": (("network", *KUKA, "--axis", "1", "--window", "all"), "kuka-a1.json"),
    "kuka-backlash": (("backlash", *KUKA, "--axis", "1"), "kuka-backlash.json"),
    "ur5-backlash": (("backlash", *UR5), "ur5-backlash.json"),
}
_DATE = re.compile(rb"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00")
_ELAPSED = re.compile(rb"(computation time \[s\]</t[dh]>\s*<td>)[0-9.]+")


def run(out: Path) -> None:
    """Every command of :data:`COMMANDS`, its output and printed lines kept in ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE", "MPLBACKEND": "Agg"}
    for name, (arguments, written) in COMMANDS.items():
        start = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "funcnet", *arguments, "--quiet", "-o",
                               str(out / written)], cwd=ROOT, env=env, capture_output=True)
        (out / f"{name}.stdout").write_bytes(done.stdout)
        (out / f"{name}.stderr").write_bytes(done.stderr)
        print(f"{name}: exit {done.returncode}, {time.perf_counter() - start:.0f} s", flush=True)


def _masked(data: bytes, folder: Path) -> bytes:
    data = data.replace(str(folder).encode(), b"OUT")
    return _ELAPSED.sub(rb"\1T", _DATE.sub(b"DATE", data))


def compare(before: Path, after: Path) -> list[str]:
    """The files that differ between two ``run`` folders, and why; empty when none does."""
    files = {p.relative_to(before) for p in before.rglob("*") if p.is_file()}
    others = {p.relative_to(after) for p in after.rglob("*") if p.is_file()}
    found = [f"only in one folder: {path}" for path in sorted(files ^ others)]
    for path in sorted(files & others):
        old, new = (before / path).read_bytes(), (after / path).read_bytes()
        if path.suffix in (".html", ".stdout", ".stderr"):
            old, new = _masked(old, before), _masked(new, after)
        if old != new:
            found.append(f"differs: {path}")
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("run").add_argument("out", type=Path)
    pair = commands.add_parser("compare")
    pair.add_argument("before", type=Path)
    pair.add_argument("after", type=Path)
    options = parser.parse_args()
    if options.command == "run":
        run(options.out)
        return 0
    found = compare(options.before, options.after)
    count = sum(1 for p in options.before.rglob("*") if p.is_file())
    print("\n".join(found) or f"the same: {count} files")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
