"""Speed of the repetition evidence: 5 nodes, 300 samples, R = 20 repetitions (target <= 2 s).

Twenty simulated runs of one move (175 deg/min, the real trace's sensors, logged every 4 ms),
a 300-sample cruise window of RP, AP, MP, RC, AC in each. Timed: :func:`funcnet.repetition_evidence`
on the 20 windows (median and best of 5 calls after a warm-up), and in the same process the
single-window coupling test of the same 20 windows (:func:`funcnet.functional_network` with
``evidence=True, resamples=0``, one call per window): what testing each repetition on its own
costs (without the intervals, which take seconds per window).

    PYTHONPATH=src python -m benchmarks.bench_repetitions
"""

from __future__ import annotations

import os
import platform
import warnings

import pandas as pd

import funcnet
from benchmarks.bench_core import timed
from funcnet.sim import Trial, simulate_trial

SIGNALS = ["RP", "AP", "MP", "RC", "AC"]
R = 20
START, LENGTH = 445, 300  # samples of the 4 ms log: inside the cruise


def windows() -> list[pd.DataFrame]:
    trial = Trial("bench-repeat", "repetitions", speed=175, tcp=1.6, step=10.0, sensors="real")
    return [simulate_trial(trial, seed=seed).data[SIGNALS].iloc[::2].iloc[START:START + LENGTH]
            .reset_index(drop=True) for seed in range(1, R + 1)]



def main() -> None:
    data = windows()
    funcnet.repetition_evidence(data[:5])  # compile
    for window in data[:2]:
        funcnet.functional_network(window, evidence=True, resamples=0)
    median, best, _, _ = timed(lambda: funcnet.repetition_evidence(data), 5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", funcnet.FuncnetWarning)
        single, single_best, _, _ = timed(
            lambda: [funcnet.functional_network(w, evidence=True, resamples=0) for w in data], 3)
    table = funcnet.repetition_evidence(data)
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load {os.getloadavg()[0]:.1f}")
    print(f"repetition_evidence, 5 nodes x 300 samples x R = {R}: median {median:.3f} s "
          f"(best {best:.3f} s); target <= 2 s: {'met' if median <= 2 else 'NOT met'}")
    print(f"single-window coupling tests of the same {R} windows: median {single:.3f} s "
          f"(best {single_best:.3f} s); ratio {single / median:.1f}x")
    print(table[["x", "y", "coupling_statistic", "coupling_p", "evidence"]].to_string(index=False))


if __name__ == "__main__":
    main()
