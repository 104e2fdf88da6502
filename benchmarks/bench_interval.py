"""Calibration of the asymmetry interval: prints the coverage table.

Usage::

    .venv/bin/python benchmarks/bench_interval.py                  # 200 pairs per cell
    .venv/bin/python benchmarks/bench_interval.py --quick          # 40 pairs, 140 and 300
    .venv/bin/python benchmarks/bench_interval.py --only noise,henon --lengths 140 --pairs 50

Every pair is what :func:`funcnet.functional_network` computes for two signals with the
library's defaults (min-max normalization of the window, ``dim = 3``, rr = cr = 0.05) and the
delays of ``benchmarks/bench_evidence.py`` (1 for maps and noise, 3 for Lorenz, 8 for Rossler);
the interval is :func:`funcnet.evidence.interval.asymmetry_intervals` with 200 resamples (100
keeping ``FRACTIONS[0]`` = 0.4 of the blocks, 100 keeping ``FRACTIONS[1]`` = 0.75) and level
0.95, seed = the pair's index.

Rows:

* pairs of independent realizations of the same process (true asymmetry 0 by symmetry): the
  fraction of pairs whose interval covers 0 (target 0.90-0.99), for ``C_diff`` and ``T_diff``;
* logistic maps r = 3.7 vs 4.0 (uncoupled, asymmetric): the fraction covering the mean
  ``C_diff`` (``T_diff``) of ``--truth`` independent realizations of the same length (seeds
  from 100000, disjoint from the pairs' seeds).

Columns also give the median estimated rate exponent ``beta`` and the median interval width.
Seeds start at ``--seed0`` (default 2000, the validation seeds of the fractions (0.4, 0.75);
they were chosen on seeds 5000-5199; the first version was validated on 1000-1199; the tests
use seeds below 100).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from funcnet.core.embedding import signal_states
from funcnet.core.measures import isrn_measures
from funcnet.core.normalization import normalize
from funcnet.core.recurrence import auto_recurrence, cross_recurrence
from funcnet.evidence.interval import (
    FRACTIONS,
    interval_from,
    resampled_differences,
    subsamples,
)
from funcnet.parameters import NetworkParameters
from funcnet.validation import systems

TRUTH_SEED0 = 100_000


@dataclass(frozen=True)
class Process:
    key: str
    name: str
    make: Callable[[int, list[int]], np.ndarray]
    delay: int
    symmetric: bool


PROCESSES = [
    Process("noise", "white noise", lambda n, s: systems.white_noise(n, seed=s), 1, True),
    Process("ar1", "AR(1) phi=0.95", lambda n, s: systems.ar1_pair(n, seed=s), 1, True),
    Process("henon", "Henon C=0 copies", lambda n, s: systems.henon_pair(n, 0.0, seed=s), 1,
            True),
    Process("lorenz", "Lorenz copies", lambda n, s: systems.lorenz_pair(n, seed=s), 3, True),
    Process("rossler", "Rossler equal w copies",
            lambda n, s: systems.rossler_pair(n, 0.0, 1.0, 1.0, seed=s), 8, True),
    Process("logistic", "logistic 3.7 vs 4.0",
            lambda n, s: systems.logistic_pair(n, 3.7, 4.0, seed=s), 1, False),
]


def pair_states(data: np.ndarray, p: NetworkParameters) -> list[np.ndarray]:
    values = normalize(data, p.normalize)
    return [signal_states(values[:, k], parameters=p) for k in (0, 1)]


def observed(states: list[np.ndarray], p: NetworkParameters) -> tuple[float, float]:
    a = auto_recurrence(states[0], parameters=p)
    b = auto_recurrence(states[1], parameters=p)
    c = cross_recurrence(states[0], states[1], parameters=p)
    m = isrn_measures(a, b, c)
    return m.c_diff, m.t_diff


def truth(proc: Process, n: int, count: int, p: NetworkParameters) -> tuple[float, float]:
    if proc.symmetric:
        return 0.0, 0.0
    batch = proc.make(n, list(range(TRUTH_SEED0, TRUTH_SEED0 + count)))
    diffs = np.array([observed(pair_states(batch[:, k], p), p) for k in range(count)])
    return float(diffs[:, 0].mean()), float(diffs[:, 1].mean())


def cell(proc: Process, n: int, pairs: int, resamples: int, seed0: int,
         truth_count: int) -> dict[str, float]:
    p = NetworkParameters(delay=proc.delay)
    target = truth(proc, n, truth_count, p)
    batch = proc.make(n, list(range(seed0, seed0 + pairs)))
    new_c, new_t, beta_c, width_c = [], [], [], []
    for k in range(pairs):
        states = pair_states(batch[:, k], p)
        c_diff, t_diff = observed(states, p)
        m = states[0].shape[0]
        # The draws of asymmetry_intervals(seed=k), unrolled to report the rate too.
        small = subsamples(m, resamples - resamples // 2, FRACTIONS[0], seed=k)
        large = subsamples(m, resamples // 2, FRACTIONS[1], seed=(k, 1))
        values = resampled_differences(states, [(0, 1)], small, parameters=p)[0]
        larger = resampled_differences(states, [(0, 1)], large, parameters=p)[0]
        iv = interval_from(c_diff, t_diff, values, rate_values=larger,
                           fractions=(small.shape[1] / m, large.shape[1] / m))
        new_c.append(iv.c_diff_low <= target[0] <= iv.c_diff_high)
        new_t.append(iv.t_diff_low <= target[1] <= iv.t_diff_high)
        beta_c.append(iv.c_rate)
        width_c.append(iv.c_diff_high - iv.c_diff_low)
    return {
        "c": float(np.mean(new_c)), "t": float(np.mean(new_t)),
        "beta": float(np.median(beta_c)), "width": float(np.median(width_c)),
        "target_c": target[0], "target_t": target[1],
    }


def mark(rate: float) -> str:
    return "" if 0.90 <= rate <= 0.99 else " *"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pairs", type=int, default=200)
    parser.add_argument("--lengths", default="140,300,1000")
    parser.add_argument("--only", default=",".join(p.key for p in PROCESSES),
                        help="comma-separated keys: " + ", ".join(p.key for p in PROCESSES))
    parser.add_argument("--resamples", type=int, default=200)
    parser.add_argument("--seed0", type=int, default=2000)
    parser.add_argument("--truth", type=int, default=1000,
                        help="realizations for the logistic mean")
    parser.add_argument("--quick", action="store_true",
                        help="40 pairs, lengths 140 and 300, truth from 300 realizations")
    args = parser.parse_args(argv)
    if args.quick:
        args.pairs, args.lengths, args.truth = 40, "140,300", 300
    lengths = [int(v) for v in args.lengths.split(",")]
    keys = args.only.split(",")
    by_key = {p.key: p for p in PROCESSES}
    if any(k not in by_key for k in keys):
        parser.error(f"--only: unknown key among {keys}")
    chosen = [by_key[k] for k in keys]  # in the order given
    print("$ .venv/bin/python benchmarks/bench_interval.py " + " ".join(sys.argv[1:]))
    print(f"pairs per cell {args.pairs}, seeds {args.seed0}-{args.seed0 + args.pairs - 1}, "
          f"{args.resamples} resamples (fractions {FRACTIONS[0]} / {FRACTIONS[1]} of the blocks), "
          f"level 0.95; logistic mean over "
          f"{args.truth} realizations, seeds {TRUTH_SEED0}-{TRUTH_SEED0 + args.truth - 1}")
    se = math.sqrt(0.95 * 0.05 / args.pairs)
    print(f"binomial SE at 0.95: {se:.3f}; * = outside 0.90-0.99\n")
    print("| process | N | covers | C_diff | T_diff | median beta (C) "
          "| median width (C) | time |")
    print("|---|---|---|---|---|---|---|---|")
    start_all = time.perf_counter()
    for proc in chosen:
        for n in lengths:
            start = time.perf_counter()
            r = cell(proc, n, args.pairs, args.resamples, args.seed0, args.truth)
            what = "0" if proc.symmetric else f"mean {r['target_c']:.4f} / {r['target_t']:.4f}"
            print(f"| {proc.name} | {n} | {what} | {r['c']:.3f}{mark(r['c'])} | "
                  f"{r['t']:.3f}{mark(r['t'])} | {r['beta']:.2f} | {r['width']:.4f} | "
                  f"{time.perf_counter() - start:.0f} s |",
                  flush=True)
    print(f"\ntotal {time.perf_counter() - start_all:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
