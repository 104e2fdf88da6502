"""Every per-recording command, with its defaults, on every axis of every real recording.

Run from the repository root::

    PYTHONPATH=src python -m benchmarks.every_recording [--only COMMAND ...] [--match TEXT]
        [--json FILE]

The recordings: the KUKA KR 300 runs and the UR5 runs shipped in ``data/`` (read with their
channel maps in ``examples/``), and the SINUMERIK trace when it is beside the clone
(``../shared/data/sinumerik/axis7-braking-trace.xml``; left out, and said, when it is not).
The commands, each in a process of its own, as a user types them (options only to name the
channel map, the axis, and a temporary output folder):

* ``funcnet network RUN --axis N`` and ``funcnet stability RUN --axis N``: every axis;
* ``funcnet backlash RUN`` and ``funcnet inspect RUN``: the whole recording (every axis);
* ``funcnet compare RUN --against REF ...``: each UR5 run against the other runs of its program.

Printed: one row per call with its exit status, its wall time and what it said on stderr (its
error line, or how many warning lines and the first words of each), then the count of calls per
exit status. ``--json`` keeps every call's full stderr. Every call is expected to exit 0.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SINUMERIK = ROOT.parent / "shared" / "data" / "sinumerik" / "axis7-braking-trace.xml"
# The UR5 runs of one motion program each (data/ur5/README.md).
UR5_PROGRAMS = (("Movement_No8_Singularity_Free_1", "Movement_No9_Singularity_Free_NoDist",
                 "Movement_No9_Singularity_Free_ForceSensor"),
                ("Movement_No5_Acc_slow_no_disturbance", "Movement_No5_Acc_slow_w_disturbance"))
COMMANDS = ("network", "stability", "backlash", "inspect", "compare")


def recordings() -> Iterator[tuple[str, Path, list[str], list[int | None]]]:
    """(name, path relative to the repository, channel options, axes) of every real recording
    there is."""
    if SINUMERIK.is_file():
        yield "SINUMERIK axis 7", Path(os.path.relpath(SINUMERIK, ROOT)), [], [None]
    else:
        print(f"# the SINUMERIK trace is not at {SINUMERIK}: left out")
    for run in "AB":
        yield (f"KUKA run {run}", Path("data", "kuka-kr300", f"kr300-run-{run}.mat"),
               ["--channels", "examples/kuka-kr300-channels.toml"], list(range(1, 7)))
    for program in UR5_PROGRAMS:
        for folder in program:
            yield (f"UR5 {folder}", Path("data", "ur5", folder),
                   ["--channels", "examples/ur5-channels.toml"], list(range(1, 7)))


def calls(only: set[str], out: Path, match: str = "") -> Iterator[tuple[str, str, str, list[str]]]:
    """(recording, command, axis, arguments after ``funcnet``) of every call to make, on the
    recordings whose name holds ``match``."""
    for name, path, channels, axes in recordings():
        if match not in name:
            continue
        for command in ("network", "stability"):
            if command in only:
                for axis in axes:
                    where = [] if axis is None else ["--axis", str(axis)]
                    yield name, command, str(axis or "-"), [command, str(path), *channels,
                                                             *where]
        if "backlash" in only:
            yield name, "backlash", "all", ["backlash", str(path), *channels]
        if "inspect" in only:
            yield name, "inspect", "all", ["inspect", str(path), *channels, "-q",
                                           "-o", str(out / "inspect")]
        program = next((p for p in UR5_PROGRAMS if path.name in p), None)
        if "compare" in only and program is not None:
            against = [a for ref in program if ref != path.name
                       for a in ("--against", str(path.parent / ref))]
            yield name, "compare", "all", ["compare", str(path), *against, *channels,
                                           "-o", str(out / "compare")]


def said(stderr: str, path: str) -> str:
    """What a call said, shortened for the table (the recording's path as RUN): its error, or
    the first words of each warning line."""
    lines = [line.replace(path, "RUN") for line in stderr.splitlines()
             if line.startswith("funcnet: ")]
    errors = [line for line in lines if line.startswith("funcnet: error")]
    if errors:
        return errors[0][:200]
    heads = [line.removeprefix("funcnet: warning: ").removeprefix("RUN: ")[:44] + "..."
             for line in lines]
    return "; ".join(heads) if heads else "nothing"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", choices=COMMANDS, default=list(COMMANDS))
    parser.add_argument("--match", default="", help="Only the recordings whose name holds it.")
    parser.add_argument("--json", type=Path, help="Write every call's full stderr here.")
    args = parser.parse_args(argv)
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    rows = []
    print(f"load average before: {os.getloadavg()}")
    print("| recording | command | axis | exit | wall [s] | said on stderr |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for name, command, axis, arguments in calls(set(args.only), Path(folder), args.match):
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-m", "funcnet", *arguments], env=env,
                                  cwd=ROOT, capture_output=True, text=True, timeout=3600)
            wall = time.perf_counter() - start
            short = said(done.stderr, arguments[1]).replace("|", "/")
            print(f"| {name} | {command} | {axis} | {done.returncode} | {wall:.1f} | {short} |",
                  flush=True)
            rows.append({"recording": name, "command": command, "axis": axis,
                         "arguments": arguments, "exit": done.returncode, "wall": wall,
                         "stderr": done.stderr})
    print(f"load average after: {os.getloadavg()}")
    counts = Counter(row["exit"] for row in rows)
    print("exit statuses: " + ", ".join(f"{code}: {n}" for code, n in sorted(counts.items())))
    if args.json is not None:
        args.json.write_text(json.dumps(rows, indent=1), encoding="utf-8")
    return 0 if set(counts) <= {0} else 1


if __name__ == "__main__":
    raise SystemExit(main())
