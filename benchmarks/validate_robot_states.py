"""What a robot network on a bounded number of states changes, on every shipped robot recording.

Run from the repository root::

    python -m benchmarks.validate_robot_states [--bounds 2000 1000] [--cases KUKA ...]

For each recording, the robot network of the whole recording (the page's nodes, default
parameters and evidence) is computed on every state and on at most ``B`` states per bound
(:func:`funcnet.network.functional_network`'s ``max_states``: every ``d``-th state). Printed per
bound: the thinning, CPU seconds, the share of pairs of the same kind (all pairs, and those whose
differences both stand at least ``2 mu`` from 0 in the full network), the correlation of
``c_diff`` and ``t_diff``, the pairs coupled, and two truths a recording fixes: asymmetry arrows
and direction readings into a set-point (nothing drives a set-point).
"""

from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "KUKA A": ("data/kuka-kr300/kr300-run-A.mat", "examples/kuka-kr300-channels.toml"),
    "KUKA B": ("data/kuka-kr300/kr300-run-B.mat", "examples/kuka-kr300-channels.toml"),
    "UR5 No8": ("data/ur5/Movement_No8_Singularity_Free_1", "examples/ur5-channels.toml"),
    "UR5 No9 ND": ("data/ur5/Movement_No9_Singularity_Free_NoDist", "examples/ur5-channels.toml"),
    "UR5 No9 FS": ("data/ur5/Movement_No9_Singularity_Free_ForceSensor",
                   "examples/ur5-channels.toml"),
    "UR5 No5 nd": ("data/ur5/Movement_No5_Acc_slow_no_disturbance", "examples/ur5-channels.toml"),
    "UR5 No5 wd": ("data/ur5/Movement_No5_Acc_slow_w_disturbance", "examples/ur5-channels.toml"),
    "MCS500": ("data/mecademic-mcs500/mcs500-two-cycles.csv", "examples/mecademic-channels.toml"),
}


def _network(recording, nodes, max_states):  # type: ignore[no-untyped-def]
    from funcnet.inspection.robot import robot_windows
    from funcnet.pipeline import window_evidence, window_networks

    windows, _ = robot_windows(recording)
    started = time.process_time()
    networks = window_networks(recording, windows, signals=nodes, max_states=max_states)
    networks = window_evidence(recording, networks, windows)
    return next(iter(networks.values())), time.process_time() - started


def _into_setpoint(pairs: pd.DataFrame) -> tuple[int, int]:
    """Asymmetry arrows, and direction readings, whose target is a set-point (``.RP``)."""
    def target(frame: pd.DataFrame, column: str) -> pd.Series:
        return np.where(frame[column] == "x->y", frame["y"],
                        np.where(frame[column] == "y->x", frame["x"], ""))
    arrows = pd.Series(target(pairs, "kind")).str.endswith(".RP").sum()
    readings = pd.Series(target(pairs, "direction")).str.endswith(".RP").sum()
    return int(arrows), int(readings)


def compare(name: str, bounds: list[int]) -> None:
    from funcnet.robot import paper_nodes, read_trace
    from funcnet.robot.units import in_axis_units

    path, channels = CASES[name]
    recording, _ = in_axis_units(read_trace(ROOT / path, channels=ROOT / channels,
                                            keep_setpoint=True), warn=False)
    nodes = paper_nodes(recording.data.columns)
    full, seconds = _network(recording, nodes, None)
    a = full.pairs.set_index(["x", "y"])
    mu = full.parameters.mu
    clear = (a["c_diff"].abs() >= 2 * mu) & (a["t_diff"].abs() >= 2 * mu)
    arrows, readings = _into_setpoint(full.pairs)
    print(f"{name}: {len(a)} pairs, {full.n_samples} samples; every state: {seconds:.1f} CPU s, "
          f"coupled {int(a['coupled'].sum())}, into a set-point: {arrows} arrows, "
          f"{readings} readings")
    for bound in bounds:
        thinned, seconds = _network(recording, nodes, bound)
        b = thinned.pairs.set_index(["x", "y"])
        same = a["kind"] == b["kind"]
        decided = (a["coupled"] == b["coupled"]).mean()
        arrows, readings = _into_setpoint(thinned.pairs)
        print(f"  at most {bound:,} states (one in {thinned.state_step}): {seconds:.1f} CPU s; "
              f"same kind {same.mean():.3f} (clear pairs {same[clear].mean():.3f} of "
              f"{int(clear.sum())}); corr c_diff {np.corrcoef(a['c_diff'], b['c_diff'])[0, 1]:.4f}"
              f" t_diff {np.corrcoef(a['t_diff'], b['t_diff'])[0, 1]:.4f}; median |change| "
              f"c_diff {(a['c_diff'] - b['c_diff']).abs().median():.4f}; coupled "
              f"{int(b['coupled'].sum())} (same decision {decided:.3f})"
              f"; into a set-point: {arrows} arrows, {readings} readings")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bounds", type=int, nargs="+", default=[2000, 1000])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    args = parser.parse_args()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in args.cases:
            compare(name, args.bounds)


if __name__ == "__main__":
    main()
