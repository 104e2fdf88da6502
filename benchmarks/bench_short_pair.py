"""Benchmark of one short pair against pyunicorn, and of this checkout against another one.

Run from the repository root::

    python -m benchmarks.bench_short_pair [--against DIR] [--repeats N] [--skip-timeline]

1. One pair at 150 samples, as the method guide (docs/guide/method.md) calls it:
   ``funcnet.cross_measures(x, y, dim=3, delay=10, metric="supremum", rule="pyunicorn")``
   (warnings on, as by default; this process ignores them), and pyunicorn 1.0.0's
   ``InterSystemRecurrenceNetwork`` with its four measures on the same embedded signals, in
   this process, the two calls alternating so that both meet the same load. Prints the median
   of single calls of each and their ratio (target: at least 30x), the same of the calling
   thread's CPU time (on a loaded machine a call of milliseconds is preempted more often than
   one of 0.1 ms, which favours the shorter in wall time), and the largest difference of the
   four values (must be 0). The same at 100-2000 samples.
2. With ``--against DIR`` (another checkout, e.g. the code before a change): the same
   ``cross_measures`` calls at 150 and 2000 samples, and the sliding timeline over the real
   trace (``window_networks``, as in :mod:`benchmarks.bench_windows`, both rules), each in a
   fresh interpreter importing ``DIR/src`` and one importing this checkout's ``src``,
   alternating; their values are compared.

Times are wall-clock seconds on a machine that may be shared: the load average is printed before
and after; quote the ratios measured in the same run.
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
from benchmarks.bench_windows import NODES, pyunicorn_measures, signal_pair, timeline_windows

OPTIONS: dict[str, Any] = {"dim": 3, "delay": 10, "metric": "supremum", "rule": "pyunicorn"}
SIZES = (100, 150, 200, 300, 600, 800, 1000, 2000)
ROOT = Path(__file__).resolve().parents[1]


def _values(result: Any) -> list[float]:
    return [result.c_xy, result.c_yx, result.t_xy, result.t_yx, result.eps_x, result.eps_y,
            result.eps_xy]


def against_pyunicorn(sizes: tuple[int, ...], repeats: int) -> None:
    """Section 1: cross_measures and pyunicorn alternating, in this process."""
    from funcnet import cross_measures

    print("\n### One pair against pyunicorn (rule=pyunicorn, supremum, same process)\n")
    print("| samples | cross_measures [ms] (best) | pyunicorn [ms] (best) | ratio | "
          "CPU: cross_measures, pyunicorn [ms] | CPU ratio | max abs diff |")
    print("|---|---|---|---|---|---|---|")
    for n in sizes:
        x, y = signal_pair(n)
        ours: list[float] = []
        theirs: list[float] = []
        our_cpu: list[float] = []
        their_cpu: list[float] = []
        count = repeats if n <= 300 else max(3, repeats // 20)
        result = cross_measures(x, y, **OPTIONS)
        pyunicorn_measures(x, y)
        reference: tuple[float, ...] = ()
        for _ in range(count):
            cpu, start = time.thread_time(), time.perf_counter()
            result = cross_measures(x, y, **OPTIONS)
            ours.append(time.perf_counter() - start)
            our_cpu.append(time.thread_time() - cpu)
            cpu = time.thread_time()
            seconds, reference = pyunicorn_measures(x, y)
            their_cpu.append(time.thread_time() - cpu)
            theirs.append(seconds)
        difference = max(abs(a - b) for a, b in zip(_values(result)[:4], reference, strict=True))
        assert difference == 0.0, difference
        mine, other = statistics.median(ours), statistics.median(theirs)
        mine_cpu, other_cpu = statistics.median(our_cpu), statistics.median(their_cpu)
        print(f"| {n} | {mine * 1e3:.3f} ({min(ours) * 1e3:.3f}) | {other * 1e3:.2f} "
              f"({min(theirs) * 1e3:.2f}) | **{other / mine:.0f}x** | {mine_cpu * 1e3:.3f}, "
              f"{other_cpu * 1e3:.2f} | {other_cpu / mine_cpu:.0f}x | {difference:.1e} |")


# --------------------------------------------------------------------------------------------
# this checkout against another, each measurement in a fresh interpreter


def child(kind: str, repeats: int) -> None:
    """Time one case in this interpreter (whatever ``funcnet`` it imports); print JSON."""
    warnings.simplefilter("ignore")
    if kind.startswith("pair"):
        from funcnet import cross_measures

        x, y = signal_pair(int(kind[4:]))
        result = cross_measures(x, y, **OPTIONS)
        walls, cpus = [], []
        for _ in range(repeats):
            cpu, start = time.process_time(), time.perf_counter()
            result = cross_measures(x, y, **OPTIONS)
            walls.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
        values: Any = _values(result)
    else:
        from funcnet import window_networks

        options = {} if kind == "timeline-funcnet" else {"rule": "pyunicorn",
                                                         "metric": "supremum"}
        recording, windows, _ = timeline_windows()
        window_networks(recording, windows[:2], signals=NODES, **options)  # warm-up
        walls, cpus = [], []
        for _ in range(repeats):
            cpu, start = time.process_time(), time.perf_counter()
            networks = window_networks(recording, windows, signals=NODES, **options)
            walls.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
        values = [network.pairs["c_diff"].tolist() + network.pairs["t_diff"].tolist()
                  for network in networks.values()]
    print(json.dumps({"walls": walls, "cpus": cpus, "values": values}))


def run_child(source: Path, kind: str, repeats: int) -> dict[str, Any]:
    environment = dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")
    command = [sys.executable, "-m", "benchmarks.bench_short_pair", "--child", kind,
               "--repeats", str(repeats)]
    output = subprocess.run(command, check=True, capture_output=True, text=True, cwd=ROOT,
                            env=environment).stdout
    return json.loads(output.strip().splitlines()[-1])


def against_checkout(other: Path, repeats: int, timeline: bool, rounds: int) -> None:
    """Section 2: this checkout and ``other``, alternating fresh interpreters."""
    cases = [("pair150", repeats, "one pair, 150 samples [ms]", 1e3),
             ("pair2000", max(5, repeats // 20), "one pair, 2000 samples [ms]", 1e3)]
    if timeline:
        cases += [("timeline-funcnet", 1, "timeline, rule funcnet [s]", 1.0),
                  ("timeline-pyunicorn", 1, "timeline, rule pyunicorn, supremum [s]", 1.0)]
    print(f"\n### This checkout against {other} (fresh interpreters, alternating, {rounds} "
          "rounds)\n")
    print("| case | before (median of rounds) | after | before / after | CPU before, after "
          "(all threads) | CPU before / after | values |")
    print("|---|---|---|---|---|---|---|")
    for kind, count, label, scale in cases:
        before: list[float] = []
        after: list[float] = []
        cpu_before: list[float] = []
        cpu_after: list[float] = []
        same = True
        for _ in range(rounds):
            old = run_child(other, kind, count)
            new = run_child(ROOT, kind, count)
            before.append(statistics.median(old["walls"]))
            after.append(statistics.median(new["walls"]))
            cpu_before.append(statistics.median(old["cpus"]))
            cpu_after.append(statistics.median(new["cpus"]))
            same = same and old["values"] == new["values"]
        b, a = statistics.median(before), statistics.median(after)
        cb, ca = statistics.median(cpu_before), statistics.median(cpu_after)
        print(f"| {label} | {b * scale:.3f} | {a * scale:.3f} | {b / a:.2f}x | "
              f"{cb * scale:.3f}, {ca * scale:.3f} | {cb / ca:.2f}x | "
              f"{'identical' if same else 'DIFFERENT'} |")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--against", type=Path, default=None,
                        help="another checkout (its src/ is imported) to compare with")
    parser.add_argument("--repeats", type=int, default=200)
    parser.add_argument("--sizes", type=int, nargs="*", default=list(SIZES))
    parser.add_argument("--skip-timeline", action="store_true")
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds of fresh interpreters with --against")
    parser.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child is not None:
        child(args.child, args.repeats)
        return
    warnings.simplefilter("ignore")
    run = Run()
    run.header("One short pair")
    against_pyunicorn(tuple(args.sizes), args.repeats)
    if args.against is not None:
        against_checkout(args.against.resolve(), args.repeats, not args.skip_timeline,
                         args.rounds)
    run.footer("python -m benchmarks.bench_short_pair"
               + (f" --against {args.against}" if args.against else ""))


if __name__ == "__main__":
    main()
