"""Validation of the repetition coupling test on simulated repetitions with known truth.

Prints the table of docs/validation/evidence.md, section "Repetitions": per simulated system (speed
x phase) and number of repetitions R, the false-positive rate at alpha = 0.05 on pairs that share
the command and nothing else, and the power on the links the physics couples.

Runs: the simulated axis (:func:`funcnet.sim.simulate_trial`) with the real trace's
sensors, a forward-then-back move (``reverse=True``: spin-up, cruise, braking, the reversal),
logged every 4 ms (AP and MP are 4 ms signals: every other 2 ms tick is kept). A pool of runs
per speed, one seed each; a draw takes 2R distinct runs, sets A and B.

Null pairs: X of repetition i from run A_i, Y from run B_i (X, Y in AP, MP, RC, AC, the same
signal too): the command is shared, nothing else. RP is left out of both counts: the simulated
set-point is the same in every run, so its residual is zero and its test never rejects.
Coupled pairs: RC-AC, AC-MP and MP-AP within set A and within set B.

Each draw is one call of :func:`funcnet.evidence.repetitions.repetition_tests` on the 8
columns (A.AP ... B.AC), unadjusted p-values (each test at alpha on its own).

    PYTHONPATH=src python benchmarks/validate_repetitions.py [--draws 80] [--cache DIR] [--raw]
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet.evidence.repetitions import repetition_tests
from funcnet.robot import Recording, detect_phases
from funcnet.robot.signals import SignalInfo
from funcnet.sim import Trial, simulate_trial

SIGNALS = ("RP", "AP", "MP", "RC", "AC")
TESTED = ("AP", "MP", "RC", "AC")
LINKS = (("RC", "AC"), ("AC", "MP"), ("MP", "AP"))
#: Speed (deg/min) -> step (deg): every move has a cruise phase.
SYSTEMS = {35.0: 3.0, 175.0: 10.0, 350.0: 10.0}
PHASES = {"spin-up": ("early spin-up", "late spin-up"), "cruise": ("cruise",),
          "braking": ("braking",), "reversal": ("reversal",)}
LENGTH = 300  # samples (4 ms): the longest window
PERIOD = 0.004
ALPHA = 0.05


def simulated_run(speed: float, seed: int, cache: Path | None = None) -> np.ndarray:
    """One run, (time, RP AP MP RC AC) every 4 ms."""
    path = None if cache is None else cache / f"v{speed:g}-s{seed}.npy"
    if path is not None and path.exists():
        return np.load(path)
    trial = Trial(f"repeat-v{speed:g}", "repetitions", speed=speed, tcp=1.6,
                  step=SYSTEMS[speed], reverse=True, sensors="real")
    data = simulate_trial(trial, seed=seed).data[list(SIGNALS)].to_numpy()[::2]
    if path is not None:
        np.save(path, data)
    return data


def phase_spans(run: np.ndarray, length: int = LENGTH) -> dict[str, tuple[int, int]]:
    """Per phase the longest occurrence in samples, centred and cut to ``length``."""
    time_axis = pd.Index(np.arange(len(run)) * PERIOD, name="time")
    data = pd.DataFrame(run, columns=list(SIGNALS), index=time_axis)
    recording = Recording(data, {}, {c: SignalInfo(c, None, None, PERIOD) for c in SIGNALS},
                          sample_period=PERIOD)
    table = detect_phases(recording)
    spans: dict[str, tuple[int, int]] = {}
    for name, members in PHASES.items():
        runs: list[list[float]] = []
        for row in table.itertuples(index=False):
            if row.phase not in members:
                continue
            if runs and abs(runs[-1][1] - row.start) < 1e-9:
                runs[-1][1] = row.stop
            else:
                runs.append([row.start, row.stop])
        if not runs:
            continue
        start, stop = max(runs, key=lambda span: span[1] - span[0])
        a, b = round(start / PERIOD), round(stop / PERIOD)
        if b - a > length:
            a = (a + b) // 2 - length // 2
            b = a + length
        spans[name] = (a, b)
    return spans


def draw_tests(runs: Sequence[np.ndarray], span: tuple[int, int], r: int,
               rng: np.random.Generator, residuals: bool = True
               ) -> tuple[list[bool], dict[tuple[str, str], list[bool]], list[int]]:
    """One draw of 2R runs: the null decisions, the coupled links' decisions, the runs."""
    chosen = rng.choice(len(runs), size=2 * r, replace=False)
    columns = [SIGNALS.index(s) for s in TESTED]
    a, b = span
    stack = np.stack([
        np.hstack([runs[chosen[i]][a:b, columns], runs[chosen[r + i]][a:b, columns]])
        for i in range(r)
    ])
    names = [f"A.{s}" for s in TESTED] + [f"B.{s}" for s in TESTED]
    tests = repetition_tests(stack, signals=names, seed=int(rng.integers(2**31)),
                             residuals=residuals)
    rejected = dict(zip(zip(tests.x, tests.y, strict=True), tests.p_value <= ALPHA,
                        strict=True))
    null = [bool(v) for (x, y), v in rejected.items() if x[0] != y[0]]
    links: dict[tuple[str, str], list[bool]] = {}
    for u, v in LINKS:
        for side in "AB":
            key = tuple(sorted((f"{side}.{u}", f"{side}.{v}"), key=names.index))
            links.setdefault((u, v), []).append(bool(rejected[key]))
    return null, links, [int(c) for c in chosen]


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=80, help="draws per cell (R <= 20)")
    parser.add_argument("--draws-50", type=int, default=10, help="draws per cell at R = 50")
    parser.add_argument("--pool", type=int, default=150, help="runs per speed")
    parser.add_argument("--cache", type=Path, default=None, help="keep simulated runs here")
    parser.add_argument("--speeds", type=float, nargs="*", default=list(SYSTEMS))
    parser.add_argument("--repetitions", type=int, nargs="*", default=[5, 10, 20, 50])
    parser.add_argument("--raw", action="store_true",
                        help="test the raw signals instead of the residuals")
    args = parser.parse_args(argv)
    if args.cache is not None:
        args.cache.mkdir(parents=True, exist_ok=True)
    rows = []
    started = time.perf_counter()
    for speed in args.speeds:
        runs = [simulated_run(speed, seed, args.cache) for seed in range(1, args.pool + 1)]
        for phase, span in phase_spans(runs[0]).items():
            for r in args.repetitions:
                draws = args.draws_50 if r >= 50 else args.draws
                rng = np.random.default_rng([int(speed), r, len(phase)])
                null: list[bool] = []
                per_draw: list[float] = []
                links: dict[tuple[str, str], list[bool]] = {}
                used: set[int] = set()
                for _ in range(draws):
                    found, coupled, chosen = draw_tests(runs, span, r, rng, not args.raw)
                    used.update(chosen)
                    null += found
                    per_draw.append(float(np.mean(found)))
                    for key, values in coupled.items():
                        links.setdefault(key, []).extend(values)
                row = {"speed": speed, "phase": phase, "samples": span[1] - span[0], "R": r,
                       "null_tests": len(null), "fpr": float(np.mean(null)),
                       # Tests of one draw share their runs: the error between draws.
                       "fpr_se": float(np.std(per_draw, ddof=1) / np.sqrt(draws)),
                       "runs": len(used)}
                for (u, v), values in links.items():
                    row[f"power {u}-{v}"] = float(np.mean(values))
                row["link_tests"] = len(next(iter(links.values())))
                rows.append(row)
                print(pd.DataFrame([row]).to_string(index=False, header=len(rows) == 1),
                      flush=True)
    table = pd.DataFrame(rows)
    print()
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    for r in sorted(set(table.R)):
        cells = table[table.R == r]
        pooled = (cells.fpr * cells.null_tests).sum() / cells.null_tests.sum()
        print(f"R = {r}: pooled FPR {pooled:.4f} over {int(cells.null_tests.sum())} tests, "
              f"max cell {cells.fpr.max():.3f}")
    targeted = table[table.R <= 20]
    pooled = (targeted.fpr * targeted.null_tests).sum() / targeted.null_tests.sum()
    print(f"R in 5, 10, 20: pooled FPR {pooled:.4f} over {int(targeted.null_tests.sum())} tests")
    print(f"{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
