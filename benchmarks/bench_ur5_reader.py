"""Benchmark of the reader of a run's folder of text files (a UR5 log) against one CSV.

Run from the repository root::

    python -m benchmarks.bench_ur5_reader [--repeat 5]

For each run of ``data/ur5`` (README there): ``read_trace(FOLDER,
channels="examples/ur5-channels.toml")`` -- seven files of one signal and six joints each, cut
lines dropped, ends trimmed, joined on their time stamps, every joint's columns named -- against
the competitor, the same data (the recording's 42 columns over the same ticks, written once by
pandas into one CSV with a time column) read by ``pandas.read_csv``. Both run in this process,
alternately, best of ``--repeat`` calls each after one warm-up call; the ratio is funcnet's time
over pandas'. Wall and CPU time are both given: the machine is shared, and CPU time (both
readers run on one thread) is the less disturbed by other processes. Target: within 2x.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "ur5"
CHANNELS = ROOT / "examples" / "ur5-channels.toml"


def _timed(function) -> tuple[float, float]:
    """Wall and CPU seconds of one call (both readers run on one thread)."""
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    from funcnet.robot import read_trace

    def ours(folder: Path):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the cut lines and trimmed ends, said per run
            return read_trace(folder, channels=CHANNELS)

    print(f"load average {os.getloadavg()[0]:.2f}; best of {args.repeat} calls each, "
          "alternating")
    print("| run | rows x columns | funcnet folder wall / CPU [ms] | pandas one CSV wall / CPU "
          "[ms] | ratio wall / CPU |")
    print("|---|---|---|---|---|")
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for folder in sorted(p for p in DATA.iterdir() if p.is_dir()):
            recording = ours(folder)
            one = Path(tmp) / f"{folder.name}.csv"
            recording.data.to_csv(one, float_format="%.6f")
            ours(folder)
            pd.read_csv(one)
            mine = [float("inf")] * 2
            theirs = [float("inf")] * 2
            for _ in range(args.repeat):  # alternate, so that load hits both alike
                mine = [min(a, b) for a, b in zip(mine, _timed(lambda f=folder: ours(f)),
                                                  strict=True)]
                theirs = [min(a, b) for a, b in zip(theirs, _timed(lambda o=one: pd.read_csv(o)),
                                                    strict=True)]
            ratio = (mine[0] / theirs[0], mine[1] / theirs[1])
            ratios.append(ratio)
            rows, cols = recording.data.shape
            print(f"| {folder.name} | {rows} x {cols} | {mine[0] * 1e3:.1f} / {mine[1] * 1e3:.1f} "
                  f"| {theirs[0] * 1e3:.1f} / {theirs[1] * 1e3:.1f} | {ratio[0]:.2f}x / "
                  f"{ratio[1]:.2f}x |")
    print(f"worst ratio: wall {max(r[0] for r in ratios):.2f}x, CPU "
          f"{max(r[1] for r in ratios):.2f}x (target: within 2x)")


if __name__ == "__main__":
    main()
