"""Validation of the coupling test of a long segment on thinned states: false positives, power.

Run from the repository root::

    NUMBA_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE python -m benchmarks.validate_segment_test \
        [--pairs 200] [--power-pairs 100] [--reference] \
        [--only false-positives|power]

:func:`funcnet.evidence.segment.segment_tests` runs the shift-lattice test
(:mod:`funcnet.evidence.dependence`) on every ``d``-th embedded state of a long segment, at
most ``SEGMENT_MAX_STATES`` = 1,500 kept states and ``SEGMENT_MAX_SURROGATES`` = 199
surrogates. On the systems of the evidence plan (``benchmarks/bench_evidence.py``: the same
uncoupled and coupled pairs, delays and seeds from 1000), one pair per test, K = 99 asked
(a pair alone), alpha = 0.05:

* **false positives** on the eight uncoupled systems at N = 3,000 and 12,000 samples (thinned
  by 2 and 8) (``--reference``: beside the same test unthinned at N = 3,000);
* **power** on coupled systems at the same lengths, beside the test unthinned on the whole
  3,000 samples and on one part of 1,500 samples (what a cut segment's part held before).

Each row prints the rate, its binomial standard error and the median ``K``.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from benchmarks.bench_evidence import UNCOUPLED, Case
from funcnet.evidence.segment import segment_tests
from funcnet.parameters import NetworkParameters
from funcnet.validation import systems

SEED0 = 1000
ALPHA = 0.05

COUPLED = [
    Case("Henon C=0.2", lambda n, s: systems.henon_pair(n, 0.2, seed=s), 1, "x->y"),
    Case("logistic 3.7->4.0 c=0.2",
         lambda n, s: systems.logistic_pair(n, 3.7, 4.0, 0.2, seed=s), 1, "x->y"),
    Case("Rossler faster drives k=0.1", lambda n, s: systems.rossler_pair(n, 0.1, seed=s), 8,
         "x->y"),
    Case("rough driver -> low-pass", lambda n, s: systems.rough_driver_response(n, seed=s), 1,
         "x->y"),
    Case("common driver (C=0.4)", lambda n, s: systems.common_driver(n, 0.4, seed=s), 1,
         "dependent"),
]


def rejections(case: Case, n: int, pairs: int, max_states: int, part: int | None = None,
               ) -> tuple[list[bool], list[int]]:
    """Per pair, whether the test rejects at ALPHA, and its K (``part``: the first ``part``
    samples only)."""
    batch = case.make(n, list(range(SEED0, SEED0 + pairs)))
    p = NetworkParameters(delay=case.delay)
    found, ks = [], []
    for k in range(pairs):
        data = batch[:, k] if part is None else batch[:part, k]
        tests, _ = segment_tests([data[:, 0], data[:, 1]], names=["x", "y"], parameters=p,
                                 surrogates=99, max_states=max_states)
        test = tests[("x", "y")]
        found.append(test is not None and test.p_value <= ALPHA)
        ks.append(0 if test is None else test.surrogates)
    return found, ks


def row(name: str, design: str, n: int, found: list[bool], ks: list[int]) -> str:
    rate = float(np.mean(found))
    se = math.sqrt(rate * (1 - rate) / len(found)) if found else float("nan")
    return (f"| {name} | {n:,} | {design} | {rate:.3f} | {se:.3f} | {int(np.median(ks))} | "
            f"{len(found)} |")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--pairs", type=int, default=200)
    parser.add_argument("--power-pairs", type=int, default=100)
    parser.add_argument("--only", choices=("false-positives", "power"), default=None)
    parser.add_argument("--reference", action="store_true",
                        help="also the false positives of the unthinned test")
    parser.add_argument("--lengths", type=int, nargs="+", default=[3000, 12000])
    args = parser.parse_args(argv)
    started = time.perf_counter()
    header = "| system | N | design | rate | SE | median K | pairs |\n|---|---|---|---|---|---|---|"
    print(f"False positives at alpha = {ALPHA} (bound 0.05 + 3 SE = "
          f"{0.05 + 3 * math.sqrt(0.05 * 0.95 / args.pairs):.3f})\n\n{header}")
    for case in UNCOUPLED if args.only != "power" else []:
        for n in args.lengths:
            print(row(case.name, "thinned to 1,500", n, *rejections(case, n, args.pairs, 1500)),
                  flush=True)
        if args.reference:
            print(row(case.name, "unthinned", args.lengths[0],
                      *rejections(case, args.lengths[0], args.pairs, 10**7)), flush=True)
    print(f"\nPower at alpha = {ALPHA}\n\n{header}")
    for case in COUPLED if args.only != "false-positives" else []:
        for n in args.lengths:
            print(row(case.name, "thinned to 1,500", n,
                      *rejections(case, n, args.power_pairs, 1500)), flush=True)
        first = args.lengths[0]
        print(row(case.name, "unthinned", first,
                  *rejections(case, first, args.power_pairs, 10**7)), flush=True)
        print(row(case.name, "one part of half", first // 2,
                  *rejections(case, first, args.power_pairs, 10**7, part=first // 2)),
              flush=True)
    print(f"\n{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
