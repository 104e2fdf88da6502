"""Benchmark of the track store at fleet scale: 10,000 runs of 100 robots.

Builds a synthetic store (every robot 100 runs of one program, one a day, six axes, every figure
of :data:`funcnet.track.FIGURES` drawn around a level of its own; no kept traces, which only a
run's departure reads), one transaction per run as ``track add`` writes them, then times
``track show`` for one robot: reading its runs and figures, judging every series, writing the
page and the JSON. Also the same for the whole fleet's runs list (``read_runs``). With
``--add N``: ``track add`` of N simulated runs (:func:`funcnet.validation.histories.
write_history`) in one call onto the first robot's history, CPU seconds (a robot with many runs:
``--robots 1 --runs 20000``).

    PYTHONPATH=src python benchmarks/bench_track.py [--robots 100] [--runs 100] [--repeat 5]
        [--add N]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from datetime import UTC, datetime, timedelta
from pathlib import Path

import numpy as np

from funcnet.report.track_page import write_trends
from funcnet.track import FIGURES, robot_trends, store as kept


def build(path: Path, robots: int, runs: int, seed: int = 0) -> float:
    """Write the synthetic store; seconds taken."""
    rng = np.random.default_rng(seed)
    start = datetime(2026, 1, 1, tzinfo=UTC)
    began = time.perf_counter()
    with kept.open_store(path) as db:
        for r in range(robots):
            level = rng.uniform(0.5, 2.0, (6, len(FIGURES)))
            for k in range(runs):
                values = level * (1 + rng.normal(0, 0.03, level.shape))
                row = kept.RunRow(f"robot-{r:03d}", (start + timedelta(days=k)).isoformat(),
                                  "given", "P-1", f"/data/robot-{r:03d}/run-{k:04d}.xml",
                                  f"{r:03d}-{k:04d}")
                kept.add_run(db, row, {(a + 1, f): float(values[a, j])
                                       for a in range(6) for j, f in enumerate(FIGURES)})
    return time.perf_counter() - began


def time_add(path: Path, folder: Path, n: int) -> None:
    """``track add`` of ``n`` simulated runs in one call onto robot-000's history."""
    from funcnet.track import add_runs
    from funcnet.validation.histories import write_history

    runs = write_history(folder, 0, healthy=n, worn=())
    held = len(kept.read_runs(path, "robot-000"))
    wall, cpu = time.perf_counter(), time.process_time()
    added = add_runs(runs, path, "robot-000")
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    print(f"track add of {sum(a.added for a in added)} runs in one call onto a robot holding "
          f"{held} runs: {wall:.2f} s wall, {cpu:.2f} s CPU")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, default=100)
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--add", type=int, default=0, help="time track add of N runs")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fleet.sqlite"
        built = build(path, args.robots, args.runs)
        total = args.robots * args.runs
        size = sum(p.stat().st_size for p in Path(tmp).glob("fleet.sqlite*"))
        print(f"store: {total} runs of {args.robots} robots, {total * 6 * len(FIGURES)} "
              f"figures, built in {built:.1f} s ({total / built:.0f} runs/s, one transaction "
              f"each), {size / 2**20:.1f} MiB")
        times, judged = [], []
        for k in range(args.repeat):
            robot = f"robot-{(37 * k) % args.robots:03d}"
            began = time.perf_counter()
            trends = robot_trends(path, robot)
            middle = time.perf_counter()
            write_trends(trends, Path(tmp) / f"show-{k}")
            times.append((time.perf_counter() - began, middle - began))
            judged.append(len(trends.points))
        show = np.array(times)
        print(f"track show, one robot ({judged[0]} points judged): median "
              f"{np.median(show[:, 0]):.2f} s (best {show[:, 0].min():.2f} s) of {args.repeat}; "
              f"reading and judging {np.median(show[:, 1]):.2f} s, the page the rest")
        began = time.perf_counter()
        listed = kept.read_runs(path)
        print(f"every run listed ({len(listed)}): {time.perf_counter() - began:.2f} s")
        if args.add:
            time_add(path, Path(tmp) / "new", args.add)
        print(f"load average: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
