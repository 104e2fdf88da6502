"""Benchmark: the coupling tests of a whole-recording robot network, the packed-row window kernel
against the scan of every listed pair it replaced, in the same process.

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks.bench_shift_lattice [--runs NAME ...]
                                                                     [--pairs P]

The data: each UR5 run of ``data/ur5`` as ``funcnet inspect`` takes its robot network (every
joint's RP, AP, RC, AC, V, constant ones left out; min-max normalized, default parameters; the
nodes of ``benchmarks.bench_large_resamples``), each node's recurrence thresholded by rate once
(:func:`funcnet.evidence.pairs.pairwise_evidence` does the same). For the first ``P`` pairs of
the network, the shift-lattice test (``K`` of :func:`~funcnet.evidence.default_surrogates` for the
network's pairs, spacing ``s0`` of the pair as the evidence takes it) is run twice, one thread:
by :func:`funcnet.evidence.dependence.dependence_test` (recurrent pairs listed by
:func:`~funcnet.evidence.dependence.recurrent_pairs`, windows counted by popcounts of packed rows)
and by the scan (``np.argwhere(np.triu(a, 1))``, every window visiting every listed pair). It
prints the CPU seconds of each (per test; the listing of every node's pairs once, as the
evidence does; both extrapolated to all the network's pairs), the peak memory of the process,
and whether every listing and every statistic is equal bit for bit.
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import warnings
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RUNS = ("Movement_No5_Acc_slow_no_disturbance", "Movement_No5_Acc_slow_w_disturbance",
        "Movement_No9_Singularity_Free_ForceSensor", "Movement_No9_Singularity_Free_NoDist",
        "Movement_No8_Singularity_Free_1")


def robot_values(run: str) -> np.ndarray:
    """The robot network's nodes over the whole run, min-max normalized: shape (N, nodes)."""
    from funcnet.core.normalization import normalize
    from funcnet.robot import read_trace
    from funcnet.robot.units import in_degrees
    from funcnet.robot.windows import paper_nodes

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        recording, _ = in_degrees(read_trace(ROOT / "data" / "ur5" / run, channels=ROOT /
                                             "examples" / "ur5-channels.toml", keep_setpoint=True))
    frame = recording.data[paper_nodes(recording.data.columns)]
    frame = frame.loc[:, frame.max() > frame.min()].dropna()
    return normalize(frame.to_numpy(dtype=np.float64), "minmax")


def one_run(run: str, n_pairs: int) -> str:
    """One table row for ``run``."""
    from funcnet.core.embedding import signal_states
    from funcnet.core.recurrence import auto_recurrence
    from funcnet.evidence import default_surrogates, shift_plan
    from funcnet.evidence._kernels import _window_counts
    from funcnet.evidence.dependence import decorrelation_time, dependence_test, recurrent_pairs
    from funcnet.parameters import NetworkParameters

    p = NetworkParameters()
    values = robot_values(run)
    states = [signal_states(values[:, k], parameters=p) for k in range(values.shape[1])]
    dense = [auto_recurrence(s, parameters=p).to_dense().astype(np.uint8) for s in states]
    s0 = [decorrelation_time(values[:, k]) for k in range(values.shape[1])]
    span = (p.dim - 1) * p.delay + 1
    n = len(states)
    everyone = [(i, j) for i in range(n) for j in range(i + 1, n)]
    pairs = everyone[:n_pairs]
    k = default_surrogates(len(everyone))
    # load both kernels (and the listing) from the cache before timing
    warm = recurrent_pairs(dense[0])
    _window_counts(dense[0], warm, warm, 0, 0, 100, 0)
    dependence_test(dense[0], dense[0], shift_plan(states[0].shape[0], 3, min_shift=span),
                    recurrent=(warm, warm))
    # each signal's recurrent pairs, once per network (as the evidence lists them)
    start = time.process_time()
    listed = [recurrent_pairs(a) for a in dense]
    list_new = time.process_time() - start
    start = time.process_time()
    scanned = [np.argwhere(np.triu(a, 1)).astype(np.int64) for a in dense]
    list_old = time.process_time() - start
    equal = all(np.array_equal(a, b) for a, b in zip(listed, scanned, strict=True))
    new_cpu = old_cpu = 0.0
    for i, j in pairs:
        plan = shift_plan(states[i].shape[0], k, min_shift=max(s0[i], s0[j], span))
        start = time.process_time()
        found = dependence_test(dense[i], dense[j], plan, recurrent=(listed[i], listed[j]))
        new_cpu += time.process_time() - start
        sx = np.concatenate([[plan.observed], plan.starts_x])
        sy = np.concatenate([[plan.observed], plan.starts_y])
        start = time.process_time()
        old = [_window_counts(dense[j], scanned[i], scanned[j], a, b, plan.length, 0)[0]
               for a, b in zip(sx, sy, strict=True)]
        old_cpu += time.process_time() - start
        got = np.concatenate([[found.statistic], found.null_statistics])
        equal &= bool(np.array_equal(got.view(np.int64), np.array(old).view(np.int64)))
    scale = len(everyone) / len(pairs)
    return (f"| {run} | {states[0].shape[0]:,} | {n} ({len(everyone)}) | {len(pairs)} | "
            f"{1e3 * new_cpu / len(pairs):.1f} | {1e3 * old_cpu / len(pairs):.1f} | "
            f"{old_cpu / new_cpu:.1f} | {list_new:.2f} | {list_old:.2f} | "
            f"{new_cpu * scale + list_new:.1f} | {old_cpu * scale + list_old:.1f} | "
            f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} | {equal} |")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--runs", nargs="*", default=list(RUNS))
    parser.add_argument("--pairs", type=int, default=60)
    args = parser.parse_args(argv)
    numba.set_num_threads(1)
    print(f"## Coupling tests of whole-run robot networks ({args.pairs} pairs per run, one "
          f"thread; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
          f"{os.getloadavg()[0]:.1f})\n")
    print("| run | states | nodes (pairs) | pairs timed | packed [ms/test] | scan [ms/test] | "
          "ratio | listing, new [CPU s] | listing, argwhere [CPU s] | all pairs, new [CPU s] | "
          "all pairs, before [CPU s] | peak [MiB] | equal |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for run in args.runs:
        print(one_run(run, args.pairs), flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
