"""Benchmark of the reader of a run's folder of text files (a UR5 log) against one CSV.

Run from the repository root::

    python -m benchmarks.bench_ur5_reader [--repeat 5]

For each run of ``../shared/data/ur5`` (README there): ``read_trace(FOLDER,
channels="examples/ur5-channels.toml")`` -- seven files of one signal and six joints each, cut
lines dropped, ends trimmed, joined on their time stamps, every joint's columns named -- against
the competitor, the same data (the recording's 42 columns over the same ticks, written once by
pandas into one CSV with a time column) read by ``pandas.read_csv``. Both run in this process,
alternately, best of ``--repeat`` calls each after one warm-up call; the ratio is funcnet's time
over pandas'. Target: within 2x.
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
DATA = ROOT.parent / "shared" / "data" / "ur5"
CHANNELS = ROOT / "examples" / "ur5-channels.toml"


def _best(function, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    from funcnet.robot import read_trace

    def ours(folder: Path):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the cut lines and trimmed ends, said per run
            return read_trace(folder, channels=CHANNELS)

    print(f"load average {os.getloadavg()[0]:.2f}; best of {args.repeat} calls each")
    print("| run | rows x columns | funcnet folder [ms] | pandas one CSV [ms] | ratio |")
    print("|---|---|---|---|---|")
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for folder in sorted(p for p in DATA.iterdir() if p.is_dir()):
            recording = ours(folder)
            one = Path(tmp) / f"{folder.name}.csv"
            recording.data.to_csv(one, float_format="%.6f")
            ours(folder)
            pd.read_csv(one)
            funcnet_s = pandas_s = float("inf")
            for _ in range(args.repeat):  # alternate, so that load hits both alike
                funcnet_s = min(funcnet_s, _best(lambda f=folder: ours(f), 1))
                pandas_s = min(pandas_s, _best(lambda o=one: pd.read_csv(o), 1))
            ratio = funcnet_s / pandas_s
            ratios.append(ratio)
            rows, cols = recording.data.shape
            print(f"| {folder.name} | {rows} x {cols} | {funcnet_s * 1e3:.1f} | "
                  f"{pandas_s * 1e3:.1f} | {ratio:.2f}x |")
    print(f"worst ratio {max(ratios):.2f}x (target: within 2x)")


if __name__ == "__main__":
    main()
