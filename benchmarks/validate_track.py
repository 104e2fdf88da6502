"""Validation of ``funcnet track`` on simulated histories with known truth.

Prints the tables of docs/validation/track.md:

1. **The detector alone** on steady normal figures (no simulator): how often a figure of a
   healthy axis raises a false alarm, per judged run (the reciprocal of the average run length),
   over ``--null-series`` series of ``--null-runs`` runs, against the textbook CUSUM that knows
   the level and spread.
2. **Histories**: per seed, 24 healthy runs of one program with day-to-day nuisance (friction
   and gear stiffness scales, 5 % spread each; program speed, 3 %), then backlash 0.57, 1.5 and
   3 arcmin (:mod:`funcnet.validation.histories`), each written as a SINUMERIK trace, added with
   :func:`funcnet.track.add_runs` (departure included) and judged by
   :func:`funcnet.track.robot_trends`: false alarms on the healthy runs (any figure of the
   axis), and the worn run that raises the first alarm.
3. **Long healthy histories** (``--long-runs`` healthy runs, no wear) for the false-alarm rate of
   the whole chain on the simulator's figures.

    PYTHONPATH=src python benchmarks/validate_track.py [--seeds 12] [--long-seeds 2]
        [--long-runs 80] [--workers 2]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet.track import add_runs, robot_trends
from funcnet.track.detect import DRIFT, LEARN, LEVEL, detect_changes
from funcnet.validation.histories import WORN_ARCMIN, write_history

HEALTHY = 24


def markdown(frame: pd.DataFrame) -> str:
    """A Markdown table of ``frame``."""
    lines = ["| " + " | ".join(map(str, frame.columns)) + " |",
             "|" + "---|" * len(frame.columns)]
    lines += ["| " + " | ".join(map(str, row)) + " |" for row in frame.itertuples(index=False)]
    return "\n".join(lines)


def _textbook(u: np.ndarray) -> int:
    """Alarms of the two-sided CUSUM on known N(0, 1) scores, restarted after each."""
    high = low = 0.0
    alarms = 0
    for score in u:
        high, low = max(0.0, high + score - DRIFT), max(0.0, low - score - DRIFT)
        if max(high, low) > LEVEL:
            alarms += 1
            high = low = 0.0
    return alarms


def null_rates(series: int, runs: int, seed: int = 0) -> dict[str, float]:
    """False alarms per judged run: the self-starting detector and the textbook CUSUM."""
    rng = np.random.default_rng(seed)
    own = first = judged = 0
    for _ in range(series):
        found = detect_changes(rng.normal(3.0, 0.2, runs))
        alarms = np.flatnonzero(found.alarm)
        # until its first alarm (after it the history is frozen): runs judged, alarms raised
        stop = int(alarms[0]) + 1 if alarms.size else runs
        judged += stop - LEARN
        own += int(alarms.size > 0)
        first += 1
    known = sum(_textbook(rng.normal(0.0, 1.0, runs - LEARN)) for _ in range(series))
    return {"self-starting, per run": own / judged,
            "textbook (known level and spread), per run": known / (series * (runs - LEARN))}


def history(seed: int, folder: Path, store: Path, workers: int, **options: object
            ) -> pd.DataFrame:
    """One history through the whole chain: per run its index, alarms and alarmed figures."""
    paths = write_history(folder / f"seed{seed}", seed, **options)
    robot = f"sim-{seed}"
    add_runs(paths, store, robot, workers=workers)
    trends = robot_trends(store, robot)
    runs = trends.runs.reset_index(drop=True)
    index = {int(r): k for k, r in enumerate(runs["id"])}
    points = trends.points.assign(index=trends.points["run"].map(index))
    alarmed = points[points["alarm"]].groupby("index")["figure"].apply(
        lambda f: ", ".join(sorted(f)))
    return pd.DataFrame({"index": range(len(runs))}).assign(
        figures=lambda d: d["index"].map(alarmed).astype(object).fillna(""))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=12)
    parser.add_argument("--long-seeds", type=int, default=2)
    parser.add_argument("--long-runs", type=int, default=80)
    parser.add_argument("--null-series", type=int, default=400)
    parser.add_argument("--null-runs", type=int, default=500)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    started = time.perf_counter()
    print("## The detector alone (steady normal figures)\n")
    for name, rate in null_rates(args.null_series, args.null_runs).items():
        print(f"* {name}: {rate:.4f} (one in {1 / rate:.0f} runs)")
    rows, false_alarms = [], []
    with tempfile.TemporaryDirectory() as tmp:
        folder, store = Path(tmp), Path(tmp) / "histories.sqlite"
        for seed in range(args.seeds):
            found = history(seed, folder, store, args.workers)
            healthy = found[(found["index"] >= LEARN) & (found["index"] < HEALTHY)]
            worn = found[found["index"] >= HEALTHY]
            first = worn[worn["figures"] != ""]
            delay = int(first["index"].iloc[0]) - HEALTHY + 1 if len(first) else None
            rows.append({"seed": seed, "healthy runs judged": len(healthy),
                         "false alarms": int((healthy["figures"] != "").sum()),
                         "first alarm on worn run": delay if delay else "missed",
                         "its backlash [arcmin]": WORN_ARCMIN[delay - 1] if delay else "",
                         "figures": first["figures"].iloc[0] if len(first) else ""})
            false_alarms += [f for f in healthy["figures"] if f]
            print(f"seed {seed}: {rows[-1]}", flush=True)
        print("\n## Histories: 24 healthy runs, then 0.57, 1.5, 3 arcmin\n")
        print(markdown(pd.DataFrame(rows)))
        print(f"\nfalse alarms on healthy runs: {false_alarms}")
        long_rows = []
        for seed in range(100, 100 + args.long_seeds):
            found = history(seed, folder, store, args.workers, healthy=args.long_runs, worn=())
            judged = found[found["index"] >= LEARN]
            long_rows.append({"seed": seed, "runs judged": len(judged),
                              "runs with an alarm": int((judged["figures"] != "").sum()),
                              "figures": "; ".join(f for f in judged["figures"] if f)})
        print(f"\n## Long healthy histories ({args.long_runs} runs)\n")
        print(markdown(pd.DataFrame(long_rows)))
    print(f"\n{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
