"""Benchmark: the intervals' resamples of a long window, batched kernel against the per-resample
path, in the same process.

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks.bench_large_resamples [--nodes K] [--resamples R]

The data: the whole UR5 run ``Movement_No5_Acc_slow_no_disturbance`` (``data/ur5``,
26 s at 125 Hz), its robot network's nodes as ``funcnet inspect`` takes them (every joint's
RP, AP, RC, AC, V, constant ones left out), min-max normalized and embedded with the default
parameters (3,223 states). The intervals resample these states (kept fractions 0.4 and 0.75 of
the blocks: about 1,250 and 2,400 states); other fractions give the sizes in between. For each
size, ``R`` resamples of every pair of the first ``K`` nodes are computed by
:func:`funcnet.evidence.interval.resampled_differences` (the batched kernel up to
``RESAMPLE_MAX_STATES`` kept states) and by the per-resample path it replaced there
(``_fill``: each resample's recurrences one pair at a time), both in one thread, alternating;
the CPU seconds of each, their ratio, and whether the numbers are equal bit for bit.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RUN = ROOT / "data" / "ur5" / "Movement_No5_Acc_slow_no_disturbance"
FRACTIONS = (0.27, 0.33, 0.4, 0.5, 0.6, 0.75)


def robot_states() -> list[np.ndarray]:
    """The embedded states of the robot network's nodes over the whole run."""
    from funcnet.core.embedding import signal_states
    from funcnet.core.normalization import normalize
    from funcnet.robot import read_trace
    from funcnet.robot.units import in_degrees
    from funcnet.robot.windows import paper_nodes

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        recording, _ = in_degrees(read_trace(RUN, channels=ROOT / "examples" /
                                             "ur5-channels.toml", keep_setpoint=True))
    frame = recording.data[paper_nodes(recording.data.columns)]
    frame = frame.loc[:, frame.max() > frame.min()].dropna()
    values = normalize(frame.to_numpy(dtype=np.float64), "minmax")
    return [signal_states(values[:, k]) for k in range(values.shape[1])]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--nodes", type=int, default=18)
    parser.add_argument("--resamples", type=int, default=2)
    args = parser.parse_args(argv)

    from funcnet.core.thresholds import signal_thresholds
    from funcnet.evidence import interval
    from funcnet.parameters import NetworkParameters

    p = NetworkParameters()
    states = robot_states()[:args.nodes]
    n = states[0].shape[0]
    pairs = [(i, j) for i in range(len(states)) for j in range(i + 1, len(states))]
    thresholds, (cr, cross_eps) = signal_thresholds(p, len(states))
    numba.set_num_threads(1)
    warm = interval.subsamples(n, 1, 0.1, seed=9)
    interval.resampled_differences(states, pairs[:2], warm, parameters=p)  # load the kernels
    print(f"## Resamples of a long window ({len(states)} nodes, {n} states, {len(pairs)} pairs, "
          f"{args.resamples} resamples per size, one thread; load "
          f"{os.getloadavg()[0]:.1f})\n")
    print("| kept states | path now | now CPU [s] | per-resample path CPU [s] | ratio | equal |")
    print("|---|---|---|---|---|---|")
    for fraction in FRACTIONS:
        chosen = interval.subsamples(n, args.resamples, fraction, seed=0)
        kept = chosen.shape[1]
        start = time.process_time()
        now = interval.resampled_differences(states, pairs, chosen, parameters=p)
        now_cpu = time.process_time() - start
        old = np.empty_like(now)
        start = time.process_time()
        interval._fill(old, states, pairs, chosen, p, thresholds, cr, cross_eps)
        old_cpu = time.process_time() - start
        path = "batched" if kept <= interval.RESAMPLE_MAX_STATES else "per resample"
        same = np.array_equal(now.view(np.int64), old.view(np.int64))
        print(f"| {kept} | {path} | {now_cpu:.2f} | {old_cpu:.2f} | {old_cpu / now_cpu:.2f} | "
              f"{same} |", flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
