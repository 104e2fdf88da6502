"""Benchmark of one robot-wide functional network: all six axes of a KUKA KR 300 run at once.

Run from the repository root::

    python -m benchmarks.bench_robot_network [--against DIR] [--rounds N] [--run A|B]

The 21 nodes are RP, MP and the motor torque of each of the six axes and AP of axes 1-3
(``data/kuka-kr300/kr300-run-A.mat``: 2,501 samples at 250 Hz, read with
``scipy.io.loadmat``), named ``A1.RP`` ...; ``funcnet.functional_network`` with the default
parameters (M = 2,481 states, 210 pairs). Target: at most 2 s on the 2-core machine.

Each round times the network (median of three calls after a warm-up call) in a fresh
interpreter importing this checkout's ``src``; with ``--against DIR`` another one imports
``DIR/src`` (e.g. the code before a change), the two alternating, and their pairs tables are
compared. Wall seconds and the CPU seconds of all threads are printed; the machine may be
shared (the load average is printed before and after).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
import warnings
from pathlib import Path
from typing import Any

from benchmarks.bench_core import Run

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "kuka-kr300"


def robot_frame(run: str) -> Any:
    """The 21 signals of a run as a DataFrame (time on the rows)."""
    import pandas as pd
    import scipy.io

    record = scipy.io.loadmat(DATA / f"kr300-run-{run}.mat", squeeze_me=True,
                              struct_as_record=False)["rec"]
    columns = {}
    for axis in range(6):
        columns[f"A{axis + 1}.RP"] = record.ref_pos_deg[axis]
        columns[f"A{axis + 1}.MP"] = record.act_pos_mot_deg[axis]
        columns[f"A{axis + 1}.AC"] = record.act_torque_abs_nm[axis]
        if axis < 3:
            columns[f"A{axis + 1}.AP"] = record.act_pos_se_deg[axis]
    return pd.DataFrame(columns)


def child(run: str) -> None:
    """Time the network in this interpreter (whatever ``funcnet`` it imports); print JSON."""
    warnings.simplefilter("ignore")
    import funcnet

    frame = robot_frame(run)
    network = funcnet.functional_network(frame)  # warm-up: compiled kernels loaded
    walls, cpus = [], []
    for _ in range(3):
        wall, cpu = time.perf_counter(), time.process_time()
        network = funcnet.functional_network(frame)
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    pairs = network.pairs
    values = {name: pairs[name].tolist() for name in ("c_xy", "c_yx", "t_xy", "t_yx",
                                                      "eps_x", "eps_y", "eps_xy")}
    print(json.dumps({"wall": statistics.median(walls), "cpu": statistics.median(cpus),
                      "n_pairs": len(pairs), "n_edges": len(network.edges), "values": values}))


def run_child(source: Path, run: str) -> dict[str, Any]:
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    command = [sys.executable, "-m", "benchmarks.bench_robot_network", "--child", run]
    output = subprocess.run(command, check=True, capture_output=True, text=True, cwd=ROOT,
                            env=environment).stdout
    return json.loads(output.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--against", type=Path, default=None,
                        help="another checkout (its src/ is imported) to compare with")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--run", choices=("A", "B"), default="A")
    parser.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child is not None:
        child(args.child)
        return
    run = Run()
    run.header("One robot-wide network: 21 signals of a KUKA KR 300 run")
    checkouts = {"this checkout": ROOT}
    if args.against is not None:
        checkouts = {"before": args.against.resolve(), "after": ROOT}
    results: dict[str, list[dict[str, Any]]] = {name: [] for name in checkouts}
    for _ in range(args.rounds):
        for name, source in checkouts.items():
            results[name].append(run_child(source, args.run))
    print(f"\nrun {args.run}, {results[next(iter(checkouts))][0]['n_pairs']} pairs; each round "
          "the median of 3 calls in a fresh interpreter\n")
    print("| code | wall [s], median of rounds (each round) | CPU [s] | edges |")
    print("|---|---|---|---|")
    for name, rounds in results.items():
        walls = [r["wall"] for r in rounds]
        cpus = [r["cpu"] for r in rounds]
        print(f"| {name} | **{statistics.median(walls):.2f}** "
              f"({', '.join(f'{w:.2f}' for w in walls)}) | {statistics.median(cpus):.2f} | "
              f"{rounds[0]['n_edges']} |")
    if args.against is not None:
        before, after = results["before"], results["after"]
        same = all(b["values"] == a["values"] for b in before for a in after)
        ratio = (statistics.median(r["wall"] for r in before)
                 / statistics.median(r["wall"] for r in after))
        print(f"\nbefore / after: {ratio:.2f}x wall; pairs tables (C, T, eps of every pair) "
              f"{'identical' if same else 'DIFFERENT'}")
    run.footer("python -m benchmarks.bench_robot_network"
               + (f" --against {args.against}" if args.against else ""))


if __name__ == "__main__":
    main()
