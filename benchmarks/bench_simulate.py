"""Benchmark of the simulated axis: the paper's whole plan (36 trials of Table 1) as traces.

Run from the repository root::

    python -m benchmarks.bench_simulate

1. ``write_plan(paper_plan(), out)`` in a fresh interpreter (imports, loading -- or, after a
   change of the kernel, compiling -- the Numba kernel): what ``funcnet simulate --plan paper``
   costs. Target: under 60 s on 2 cores.
2. In one process, warm: the simulation alone (all 36 trials), the whole plan written with one
   process and with two, and a re-run over the finished directory (every trial skipped).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

_CHILD = """
import json, sys, time
start = time.perf_counter()
from funcnet.sim import paper_plan, write_plan
write_plan(paper_plan(), sys.argv[1])
print(json.dumps({"seconds": time.perf_counter() - start}))
"""


def _timed(function, *args, **kwargs) -> float:
    start = time.perf_counter()
    function(*args, **kwargs)
    return time.perf_counter() - start


def main() -> dict[str, float]:
    """Run the benchmark, print and return its timings (s) and the output size (MB)."""
    from funcnet.sim import paper_plan, simulate_trial, write_plan

    plan = paper_plan()
    results: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        cold = Path(tmp) / "cold"
        child = subprocess.run(
            [sys.executable, "-c", _CHILD, str(cold)], capture_output=True, text=True, check=True
        )
        results["fresh_interpreter_s"] = json.loads(child.stdout)["seconds"]
        results["output_mb"] = sum(p.stat().st_size for p in cold.iterdir()) / 1e6
        simulate_trial(plan[0])  # load the kernel before timing the warm runs
        results["simulate_only_s"] = _timed(lambda: [simulate_trial(t) for t in plan])
        results["write_plan_1_worker_s"] = _timed(write_plan, plan, Path(tmp) / "one", workers=1)
        results["write_plan_2_workers_s"] = _timed(write_plan, plan, Path(tmp) / "two", workers=2)
        results["rerun_all_skipped_s"] = _timed(write_plan, plan, Path(tmp) / "two")
        simulated = sum(len(simulate_trial(t).data) for t in plan) * 0.002
        results["simulated_seconds"] = simulated
    for key, value in results.items():
        print(f"{key:32s} {value:10.2f}")
    target = results["fresh_interpreter_s"]
    print(f"paper plan from scratch: {target:.1f} s ({'within' if target < 60 else 'ABOVE'} 60 s)")
    return results


if __name__ == "__main__":
    main()
