"""Benchmark of the edge evidence on systems with known coupling (issue 10): prints the tables.

Usage::

    .venv/bin/python benchmarks/bench_evidence.py            # quick: 40 pairs per cell
    .venv/bin/python benchmarks/bench_evidence.py --full     # 500 pairs per uncoupled cell
    .venv/bin/python benchmarks/bench_evidence.py --pairs 100 --only timing

Every pair is a two-node :func:`funcnet.functional_network` with the library's defaults
(``dim = 3``, rr = cr = mu = 0.05, min-max) and ``evidence=True`` (99 surrogates, alpha = 0.05,
200 half-samples); delays: 1 for maps, noise and filtered maps, 3 for Lorenz (sampled every
0.05), 8 for Rossler (sampled every 0.2). Seeds start at 1000 (the tests use lower seeds).

Tables:

1. false positives on uncoupled pairs, per system and length: the paper's rule (an arrow at mu),
   mu with the interval (an arrow under ``edge_rule="interval"``), the dependence test
   (``coupled``), the direction measure (``coupled`` with a direction), with the binomial
   standard error of the test's rate;
2. power on coupled pairs (arrow drawn / coupled / coupled with a direction) and direction
   accuracy (the right arrow; for the common driver "no direction" is right);
3. interval coverage: on pairs of independent realizations of one process the 95 % intervals
   should cover 0, and for logistic maps r = 3.7 vs 4.0 the mean ``C_diff`` of the cell;
4. timing of a 6-signal network over 300 samples, plain and with evidence.

pyEDM (convergent cross mapping) and tigramite (PCMCI) are not dependencies of funcnet and are
not installed here; their columns are left out.
"""

from __future__ import annotations

import argparse
import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from funcnet import systems
from funcnet.evidence import interval_kind
from funcnet.network import functional_network
from funcnet.network.rule import combine_kinds

SEED0 = 1000


@dataclass(frozen=True)
class Case:
    name: str
    make: Callable[[int, list[int]], np.ndarray]
    delay: int
    truth: str  # "none", "x->y", "dependent" (common driver: no direction)


UNCOUPLED = [
    Case("white noise", lambda n, s: systems.white_noise(n, seed=s), 1, "none"),
    Case("AR(1) phi=0.95", lambda n, s: systems.ar1_pair(n, seed=s), 1, "none"),
    Case("Henon C=0", lambda n, s: systems.henon_pair(n, 0.0, seed=s), 1, "none"),
    Case("logistic 3.7/4.0", lambda n, s: systems.logistic_pair(n, 3.7, 4.0, seed=s), 1, "none"),
    Case("Lorenz copies", lambda n, s: systems.lorenz_pair(n, seed=s), 3, "none"),
    Case("Rossler equal w", lambda n, s: systems.rossler_pair(n, 0.0, 1.0, 1.0, seed=s), 8,
         "none"),
    Case("Rossler w 1.015/0.985", lambda n, s: systems.rossler_pair(n, 0.0, seed=s), 8, "none"),
    Case("low-pass of unrelated", lambda n, s: systems.unrelated_low_pass(n, seed=s), 1, "none"),
]


def coupled_cases() -> list[tuple[Case, int]]:
    cases: list[tuple[Case, int]] = []
    for c in (0.2, 0.4, 0.6):
        cases.append((Case(f"Henon C={c}", lambda n, s, c=c: systems.henon_pair(n, c, seed=s),
                           1, "x->y"), 500))
    for kappa in (0.05, 0.1, 0.2):
        for n in (500, 2000):
            cases.append((Case(f"Rossler faster drives k={kappa}",
                               lambda n, s, k=kappa: systems.rossler_pair(n, k, seed=s),
                               8, "x->y"), n))
            cases.append((Case(f"Rossler slower drives k={kappa}",
                               lambda n, s, k=kappa: systems.rossler_pair(
                                   n, k, 0.985, 1.015, seed=s), 8, "x->y"), n))
    cases.append((Case("logistic 3.7->4.0 c=0.2",
                       lambda n, s: systems.logistic_pair(n, 3.7, 4.0, 0.2, seed=s), 1, "x->y"),
                  500))
    cases.append((Case("rough driver -> low-pass",
                       lambda n, s: systems.rough_driver_response(n, seed=s), 1, "x->y"), 500))
    cases.append((Case("common driver (C=0.4)",
                       lambda n, s: systems.common_driver(n, 0.4, seed=s), 1, "dependent"),
                  500))
    return cases


def readings(case: Case, n: int, pairs: int) -> list[dict[str, object]]:
    """One dict per pair: the paper's kind, the interval kind, coupled, direction, diffs."""
    seeds = list(range(SEED0, SEED0 + pairs))
    batch = case.make(n, seeds)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(pairs):
            network = functional_network(batch[:, k], names=["x", "y"], delay=case.delay,
                                         evidence=True, surrogates=99, seed=k)
            row = network.pairs.iloc[0]
            mu = network.parameters.mu
            c = interval_kind(row["c_diff"], row["c_diff_low"], row["c_diff_high"], mu)
            t = interval_kind(row["t_diff"], row["t_diff_low"], row["t_diff_high"], mu)
            rows.append({
                "kind": row["kind"], "interval": combine_kinds(c, t),
                "coupled": bool(row["coupled"]), "direction": row["direction"],
                "label": row["evidence"],
                "surrogates": int(row["surrogates"]),
                "c_diff": row["c_diff"], "t_diff": row["t_diff"],
                "c_cover0": row["c_diff_low"] <= 0 <= row["c_diff_high"],
                "t_cover0": row["t_diff_low"] <= 0 <= row["t_diff_high"],
                "c_low": row["c_diff_low"], "c_high": row["c_diff_high"],
            })
    return rows


def arrow(kind: object) -> bool:
    return kind in ("x->y", "y->x")


def rate(flags: list[bool]) -> float:
    return float(np.mean(flags)) if flags else float("nan")


def table_false_positives(pairs: int, lengths: tuple[int, ...]) -> dict[tuple[str, int], list]:
    print(f"\n## 1. False positives on uncoupled pairs ({pairs} pairs per cell, alpha = 0.05)\n")
    print("| system | N | paper mu rule | mu + interval | dependence test (SE) | direction "
          "measure | surrogates |")
    print("|---|---|---|---|---|---|---|")
    found: dict[tuple[str, int], list] = {}
    pooled: list[bool] = []
    for case in UNCOUPLED:
        for n in lengths:
            start = time.perf_counter()
            rows = readings(case, n, pairs)
            found[(case.name, n)] = rows
            test = [r["coupled"] for r in rows]
            pooled += test
            fp = rate(test)
            se = math.sqrt(0.05 * 0.95 / len(rows))
            flag = "" if fp <= 0.05 + 3 * se else " **over 3 SE**"
            print(f"| {case.name} | {n} | {rate([arrow(r['kind']) for r in rows]):.3f} | "
                  f"{rate([arrow(r['interval']) for r in rows]):.3f} | {fp:.3f} ({se:.3f})"
                  f"{flag} | {rate([bool(r['direction']) for r in rows]):.3f} | "
                  f"{int(np.median([r['surrogates'] for r in rows]))} |", flush=True)
            del start
    se = math.sqrt(0.05 * 0.95 / len(pooled))
    print(f"\npooled dependence-test false-positive rate: {rate(pooled):.4f} over {len(pooled)} "
          f"pairs (0.05 + 2 SE = {0.05 + 2 * se:.4f})")
    return found


def table_power(pairs: int) -> None:
    print(f"\n## 2. Power and direction on coupled pairs ({pairs} pairs per cell)\n")
    print("| system | N | arrow (paper) | right arrow (paper) | right arrow (mu + interval) | "
          "coupled (test) | coupled + right direction (measure) | wrong direction (measure) | "
          "coupled-directed right (label) | coupled-directed wrong (label) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for case, n in coupled_cases():
        rows = readings(case, n, pairs)
        if case.truth == "dependent":
            right_paper = rate([not arrow(r["kind"]) for r in rows])
            right_interval = rate([not arrow(r["interval"]) for r in rows])
            right_measure = rate([r["coupled"] and not r["direction"] for r in rows])
            wrong = rate([bool(r["direction"]) for r in rows])
            label_right = rate([r["label"] == "coupled" for r in rows])
            label_wrong = rate([r["label"] == "coupled-directed" for r in rows])
        else:
            right_paper = rate([r["kind"] == case.truth for r in rows])
            right_interval = rate([r["interval"] == case.truth for r in rows])
            right_measure = rate([r["coupled"] and r["direction"] == case.truth for r in rows])
            wrong = rate([bool(r["direction"]) and r["direction"] != case.truth for r in rows])
            label_right = rate([r["label"] == "coupled-directed" and r["kind"] == case.truth
                                for r in rows])
            label_wrong = rate([r["label"] == "coupled-directed" and r["kind"] != case.truth
                                for r in rows])
        print(f"| {case.name} | {n} | {rate([arrow(r['kind']) for r in rows]):.2f} | "
              f"{right_paper:.2f} | {right_interval:.2f} | {rate([r['coupled'] for r in rows]):.2f}"
              f" | {right_measure:.2f} | {wrong:.2f} | {label_right:.2f} | {label_wrong:.2f} |",
              flush=True)
    print("\nFor the common driver the right answer is 'no direction': its 'right' columns count "
          "pairs without an arrow (paper, interval), coupled without a direction (measure), "
          "labelled 'coupled' (label); 'wrong' counts a direction or 'coupled-directed'.")


def table_coverage(found: dict[tuple[str, int], list], lengths: tuple[int, ...]) -> None:
    print("\n## 3. Interval coverage (nominal 95 %; target 90-99 %)\n")
    print("| system | N | pairs | C_diff interval covers 0 | T_diff interval covers 0 |")
    print("|---|---|---|---|---|")
    for name in ("white noise", "Henon C=0", "Lorenz copies", "Rossler equal w"):
        for n in lengths:
            rows = found[(name, n)]
            print(f"| {name} | {n} | {len(rows)} | {rate([r['c_cover0'] for r in rows]):.3f} | "
                  f"{rate([r['t_cover0'] for r in rows]):.3f} |")
    print("\n| logistic 3.7 vs 4.0 | N | pairs | mean C_diff | interval covers the mean |")
    print("|---|---|---|---|---|")
    for n in lengths:
        rows = found[("logistic 3.7/4.0", n)]
        mean = float(np.mean([r["c_diff"] for r in rows]))
        cover = rate([r["c_low"] <= mean <= r["c_high"] for r in rows])
        print(f"| logistic | {n} | {len(rows)} | {mean:.4f} | {cover:.3f} |")


def table_timing(repeat: int = 3) -> None:
    print("\n## 4. Timing: 6 signals, 300 samples, 99 surrogates, 200 half-samples\n")
    data = np.column_stack([
        systems.henon_pair(300, 0.6, seed=1), systems.white_noise(300, seed=2),
        systems.logistic_pair(300, seed=3),
    ])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        functional_network(data, delay=1, evidence=True, surrogates=99)  # compile
        plain, full = [], []
        for _ in range(repeat):
            start = time.perf_counter()
            functional_network(data, delay=1)
            plain.append(time.perf_counter() - start)
            start = time.perf_counter()
            functional_network(data, delay=1, evidence=True, surrogates=99, resamples=200)
            full.append(time.perf_counter() - start)
    print(f"plain network {min(plain):.3f} s, with evidence {min(full):.3f} s "
          f"(best of {repeat}); ratio {min(full) / min(plain):.1f}; target <= 5 s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="500 pairs per uncoupled cell")
    parser.add_argument("--pairs", type=int, default=None, help="pairs per cell")
    parser.add_argument("--only", choices=("fp", "power", "timing"), default=None)
    args = parser.parse_args()
    pairs = args.pairs or (500 if args.full else 40)
    lengths = (140, 300, 1000)
    if args.only in (None, "timing"):
        table_timing()
    if args.only in (None, "fp"):
        found = table_false_positives(pairs, lengths)
        table_coverage(found, lengths)
    if args.only in (None, "power"):
        table_power(min(pairs, 100) if args.full else pairs)


if __name__ == "__main__":
    main()
