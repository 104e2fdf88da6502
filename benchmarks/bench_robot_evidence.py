"""Benchmark: evidence for the 21-node six-axis network of a real robot, against another checkout.

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks.bench_robot_evidence [--against DIR] [--repeats N]

The data: run A of the KUKA KR 300 in ``data/kuka-kr300/`` (MAT 5, the struct ``rec``,
6 axes x 2,501 samples at 250 Hz): per axis the set-point RP (``ref_pos_deg``), the motor
position MP (``act_pos_mot_deg``) and the motor torque AC (``act_torque_abs_nm``), and the
arm-side position AP (``act_pos_se_deg``) of axes 1-3: 21 nodes (``A1.RP`` ...), over the
750 samples from 4.0 s. One call, as a user makes it: ``functional_network(frame,
evidence=True)`` with the default parameters and evidence settings (200 resamples for the
intervals; as many shift surrogates as the window holds).

Each timed call runs in a fresh interpreter (this checkout's ``src`` or ``DIR/src`` first on
``PYTHONPATH``), after one warm-up call that loads the compiled kernels, the two checkouts
alternating so that both meet the same load; wall and CPU seconds (all threads) are printed per
call and as medians, with their ratio. The pairs tables are compared: every number and kind must be
equal bit for bit; the ``evidence`` labels may differ only where this checkout reads
``untestable``.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RUN = ROOT / "data" / "kuka-kr300" / "kr300-run-A.mat"
START, SAMPLES = 1000, 750  # 4.0-7.0 s at 250 Hz


def robot_frame(path: Path = RUN, start: int = START, samples: int = SAMPLES) -> Any:
    """The 21 nodes of the six axes over ``samples`` samples from ``start``."""
    import pandas as pd
    import scipy.io

    rec = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["rec"]
    columns = {}
    for axis in range(6):
        columns[f"A{axis + 1}.RP"] = rec.ref_pos_deg[axis]
        columns[f"A{axis + 1}.MP"] = rec.act_pos_mot_deg[axis]
        if axis < 3:  # the arm-side encoder is fitted on axes 1-3 only
            columns[f"A{axis + 1}.AP"] = rec.act_pos_se_deg[axis]
        columns[f"A{axis + 1}.AC"] = rec.act_torque_abs_nm[axis]
    frame = pd.DataFrame(columns)
    return frame.iloc[start:start + samples].reset_index(drop=True)


def child(out: str) -> None:
    """One warm-up and one timed call in this interpreter; the result pickled to ``out``."""
    import time
    import warnings

    import funcnet
    from funcnet import functional_network

    warnings.simplefilter("ignore")
    frame = robot_frame()
    functional_network(frame.iloc[:300, :4], evidence=True, warn=False, resamples=10)
    wall, cpu = time.perf_counter(), time.process_time()
    network = functional_network(frame, evidence=True, warn=False)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    with open(out, "wb") as fh:
        pickle.dump({"wall": wall, "cpu": cpu, "pairs": network.pairs,
                     "source": str(Path(funcnet.__file__).parents[1])}, fh)


def run(src: Path) -> dict[str, Any]:
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "result.pkl")
        env = {**os.environ, "PYTHONPATH": str(src)}
        subprocess.run([sys.executable, "-m", "benchmarks.bench_robot_evidence", "--child", out],
                       cwd=ROOT, env=env, check=True)
        with open(out, "rb") as fh:
            result: dict[str, Any] = pickle.load(fh)
    if Path(result["source"]).resolve() != src.resolve():
        raise SystemExit(f"the child imported {result['source']}, not {src}")
    return result


def compare(old: Any, new: Any) -> list[str]:
    """Differences between two pairs tables beyond the labels (must be none)."""
    import numpy as np

    problems = []
    for name in old.columns:
        if name == "evidence":
            continue
        if name not in new.columns:
            problems.append(f"column {name} missing")
        elif old[name].dtype.kind == "f":
            a, b = old[name].to_numpy(), new[name].to_numpy()
            if not np.array_equal(a.view(np.int64), b.view(np.int64)):
                problems.append(f"column {name} differs")
        elif not old[name].equals(new[name]):
            problems.append(f"column {name} differs")
    changed = old["evidence"] != new["evidence"]
    if (new.loc[changed, "evidence"] != "untestable").any():
        problems.append("a label changed to something other than 'untestable'")
    return problems


def load() -> str:
    return "/".join(f"{v:.1f}" for v in os.getloadavg())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--against", type=Path, help="another checkout (its src is used)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.child)
        return
    from benchmarks.bench_core import machine

    print(f"machine: {machine()}; load before {load()}")
    sides = {"this checkout": ROOT / "src"}
    if args.against is not None:
        sides = {"other": args.against / "src", **sides}
    results: dict[str, list[dict[str, Any]]] = {name: [] for name in sides}
    for k in range(args.repeats):
        for name, src in sides.items():
            result = run(src)
            results[name].append(result)
            print(f"run {k + 1} {name}: wall {result['wall']:.2f} s, CPU {result['cpu']:.2f} s "
                  f"(load {load()})", flush=True)
    print(f"\nload after {load()}\n")
    print("| code | wall median [s] (min-max) | CPU median [s] |")
    print("|---|---|---|")
    medians = {}
    for name, found in results.items():
        walls = [r["wall"] for r in found]
        cpus = [r["cpu"] for r in found]
        medians[name] = (statistics.median(walls), statistics.median(cpus))
        print(f"| {name} | {medians[name][0]:.2f} ({min(walls):.2f}-{max(walls):.2f}) | "
              f"{medians[name][1]:.2f} |")
    new = results["this checkout"][0]["pairs"]
    print(f"\npairs: {len(new)}; surrogates {new['surrogates'].min()}-"
          f"{new['surrogates'].max()}; labels here: "
          f"{json.dumps(new['evidence'].value_counts().to_dict())}")
    if args.against is not None:
        old = results["other"][0]["pairs"]
        print(f"labels there: {json.dumps(old['evidence'].value_counts().to_dict())}")
        wall_ratio = medians["other"][0] / medians["this checkout"][0]
        cpu_ratio = medians["other"][1] / medians["this checkout"][1]
        print(f"ratio (other / this checkout): wall {wall_ratio:.1f}x, CPU {cpu_ratio:.1f}x")
        problems = [problem for found in results["this checkout"]
                    for problem in compare(old, found["pairs"])]
        print("numbers and kinds bit for bit: " + ("yes" if not problems
                                                   else "NO: " + "; ".join(problems)))


if __name__ == "__main__":
    main()
