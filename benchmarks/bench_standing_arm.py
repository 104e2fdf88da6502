"""Benchmark: `funcnet inspect` on an arm at rest, pushed by hand (the worst shape of a run).

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks.bench_standing_arm [--keep DIR] [--profile OUT]

The standing arm is built from a real run's signals, the UR5 run
``Movement_No9_Singularity_Free_ForceSensor`` (``../shared/data/ur5``: the arm moves while a
person pushes it, 34.4 s at 125 Hz). Each logged signal of each joint is held at its first
value plus the run's own fast part: the signal minus its centred 1 s moving average (sensor
noise, current ripple, the pushes' transients, what is left of the motion's curvature). The
4,296 rows of that fast part are tiled to 5,326 rows (42.6 s, the length of the pushed
standing run this stands for) and written in the UR5 log format (one headerless CSV per
signal, six decimals as the robot logs them, so small signals are quantized and tie as in a
real log). Nothing moves: the set-points wander by micro-radians. The page is then
`funcnet inspect DIR --channels examples/ur5-channels.toml`, timed as a child process with
its CPU seconds and peak RSS (``ru_maxrss`` of the child; ``/usr/bin/time -v`` agrees).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT.parent / "shared" / "data" / "ur5" / "Movement_No9_Singularity_Free_ForceSensor"
FILES = ("log_q_target.csv", "log_q_actual.csv", "log_qd_target.csv", "log_qd_actual.csv",
         "log_i_target.csv", "log_i_actual.csv", "log_m_target.csv")
#: Rows of the standing run: 42.6 s at 8 ms.
ROWS = 5326
#: The moving average that separates the motion from its fast part: 1 s at 125 Hz.
SMOOTH = 125


def _read_rows(path: Path) -> np.ndarray:
    """The log's rows of seven fields (time and six joints); a malformed row is left out."""
    rows = []
    for line in path.read_text().splitlines():
        fields = line.split(",")
        if len(fields) == 7:
            rows.append([float(f) for f in fields])
    return np.asarray(rows)


def standing_signal(values: np.ndarray, rows: int = ROWS) -> np.ndarray:
    """One joint's signal held at its first value plus its fast part, tiled to ``rows``.

    >>> standing_signal(np.arange(400.0), 5)[:3]   # a ramp has no fast part inside the average
    array([0., 0., 0.])
    """
    kernel = np.ones(SMOOTH) / SMOOTH
    padded = np.pad(values, SMOOTH // 2, mode="edge")
    smooth = np.convolve(padded, kernel, mode="valid")[: values.size]
    fast = values - smooth
    return values[0] + np.resize(fast, rows)


def write_standing_arm(folder: Path, source: Path = SOURCE, rows: int = ROWS) -> Path:
    """Write the standing arm in the UR5 log format into ``folder``; returns it."""
    folder.mkdir(parents=True, exist_ok=True)
    time_column = np.arange(rows) * 0.008
    for name in FILES:
        data = _read_rows(source / name)
        joints = [standing_signal(data[:, k]) for k in range(1, 7)]
        table = np.column_stack([time_column, *joints])
        np.savetxt(folder / name, table, fmt="%.6f", delimiter=", ")
    return folder


def run_inspect(folder: Path, out: Path, extra: list[str], profile: Path | None) -> dict:
    """Wall, CPU seconds and peak RSS of one `funcnet inspect` process on ``folder``."""
    environment = dict(os.environ, PYTHONPATH=str(ROOT / "src"), OMP_WAIT_POLICY="PASSIVE")
    prefix = [sys.executable]
    if profile is not None:
        prefix += ["-m", "cProfile", "-o", str(profile)]
    command = [*prefix, "-m", "funcnet", "inspect", str(folder), "--channels",
               str(ROOT / "examples" / "ur5-channels.toml"), "--quiet", "-o", str(out), *extra]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, cwd=ROOT, env=environment)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall": wall, "cpu": cpu, "peak_mib": after.ru_maxrss / 1024}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--keep", type=Path, default=None,
                        help="write the standing run here (and keep it) instead of a temp folder")
    parser.add_argument("--profile", type=Path, default=None, help="cProfile output file")
    parser.add_argument("--no-evidence", action="store_true")
    args = parser.parse_args(argv)
    extra = ["--no-evidence"] if args.no_evidence else []
    with tempfile.TemporaryDirectory() as scratch:
        folder = write_standing_arm(args.keep or Path(scratch) / "standing-arm")
        result = run_inspect(folder, Path(scratch) / "page", extra, args.profile)
    print(f"standing arm ({ROWS} rows, 42.6 s at 125 Hz): wall {result['wall']:.1f} s, "
          f"CPU {result['cpu']:.1f} s, peak RSS {result['peak_mib']:.0f} MiB "
          f"(load {os.getloadavg()[0]:.1f})")


if __name__ == "__main__":
    main()
