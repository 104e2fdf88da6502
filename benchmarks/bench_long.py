"""Benchmark of long windows: the whole 45 s trace as one network, and the triangle kernels.

Run from the repository root::

    python -m benchmarks.bench_long [--sizes 2000 5000 10000 22686] [--repeats 3]
                                    [--skip-whole] [--skip-kernels]

1. One ``funcnet.functional_network`` over the whole real trace
   (``../shared/data/sinumerik/axis7-braking-trace.xml``: RP, AP, MP, V, AC, 22,706 complete
   rows, defaults) in a fresh interpreter: wall and CPU seconds of the call, peak resident
   memory of the process (``VmHWM`` and ``ru_maxrss``), next to
   :func:`funcnet.core.recurrence.estimate_cost`'s forecast. Targets: <= 30 s and <= 1 GiB.
2. The triangle counts of Eq. 6-7 for both directions of a pair, on prefixes of the same
   trace (M states): the row-wise kernel (one cross row at a time, ``_cross_triangles`` twice)
   against the blocked kernel (``_cross_triangles_both``: blocks of 64 * b cross rows, each auto
   row read once per block, both directions in one parallel pass) for b = 1, 4, 8, alternating
   call by call in one process; the counts must be identical.

The machine is shared: the load average is printed, wall and CPU seconds are shown side by side,
and the kernel comparison is a ratio within one run. ``OMP_WAIT_POLICY=PASSIVE`` is set here (an
application may; the library never touches the environment): idle OpenMP threads that spin
make the short parallel loops several times slower on a busy machine.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import argparse  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

TRACE = Path(__file__).resolve().parents[2] / "shared" / "data" / "sinumerik" / (
    "axis7-braking-trace.xml"
)
SIGNALS = ["RP", "AP", "MP", "V", "AC"]
SIZES = (2000, 5000, 10000, 22686)
BLOCKS = (1, 4, 8)
# Pairs of the kernel table: a rough/smooth pair and two smooth positions.
KERNEL_PAIRS = (("V", "AC"), ("AP", "MP"))


def load() -> str:
    return " ".join(f"{value:.2f}" for value in os.getloadavg())


def trace_frame() -> Any:
    import funcnet.robot as robot

    recording = robot.add_derived_signals(robot.read_trace(TRACE), ["V"])
    return recording.data[SIGNALS].dropna()


def peak_rss_mib() -> tuple[float, float]:
    """``(VmHWM, ru_maxrss)`` of this process, MiB."""
    import resource

    hwm = float("nan")
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                hwm = int(line.split()[1]) / 1024
    return hwm, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def whole_child() -> None:
    """``--child-whole``: one network over the whole trace, in this fresh interpreter."""
    import funcnet
    from funcnet.core.recurrence import estimate_cost

    warnings.simplefilter("ignore")
    frame = trace_frame()
    before = peak_rss_mib()[0]
    wall, cpu = time.perf_counter(), time.process_time()
    network = funcnet.functional_network(frame, warn=False)
    report = {
        "rows": len(frame),
        "seconds": time.perf_counter() - wall,
        "cpu": time.process_time() - cpu,
        "rss_before_mib": before,
        "vmhwm_mib": peak_rss_mib()[0],
        "maxrss_mib": peak_rss_mib()[1],
        "degenerate": int(network.pairs["degenerate"].sum()),
        "pairs": network.pairs[["x", "y", "c_xy", "c_yx", "t_xy", "t_yx"]].to_numpy().tolist(),
        "estimate": estimate_cost(len(frame), len(SIGNALS)).__dict__,
    }
    print(json.dumps(report))


def whole_network() -> dict[str, Any]:
    """Run the whole-trace network twice in fresh interpreters (the first also compiles any
    kernel whose cache is stale); report the second."""
    command = [sys.executable, "-m", "benchmarks.bench_long", "--child-whole"]
    runs = []
    for _ in range(2):
        output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
        runs.append(json.loads(output.strip().splitlines()[-1]))
    assert runs[0]["pairs"] == runs[1]["pairs"]
    return runs[-1]


def triangles(cross: Any, auto_x: Any, auto_y: Any, threads: int,
              block_words: int | None = None) -> tuple[Any, ...]:
    """``(k_xy, tri_xy, k_yx, tri_yx)``: row-wise kernel twice, or the blocked one; both
    transpose ``CR_XY`` first."""
    from funcnet.core._isrn_kernels import (
        _cross_triangles,
        _cross_triangles_both,
        _transpose_packed,
    )

    transposed = _transpose_packed(cross, auto_y.shape[0])
    if block_words is None:
        return (*_cross_triangles(cross, auto_y), *_cross_triangles(transposed, auto_x))
    return _cross_triangles_both(cross, transposed, auto_x, auto_y, block_words, threads)


def kernel_table(sizes: tuple[int, ...], repeats: int) -> list[dict[str, Any]]:
    import numba
    import numpy as np

    from funcnet.core.embedding import embed
    from funcnet.core.normalization import normalize
    from funcnet.core.recurrence import auto_recurrence, cross_recurrence

    frame = trace_frame()
    values = normalize(frame.to_numpy(), "minmax", names=SIGNALS)
    threads = numba.get_num_threads()
    rows = []
    for n_states in sizes:
        for x_name, y_name in KERNEL_PAIRS:
            n = n_states + 20  # dim 3, delay 10
            xs = embed(values[:n, SIGNALS.index(x_name)], 3, 10)
            ys = embed(values[:n, SIGNALS.index(y_name)], 3, 10)
            a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
            cr_xy = cross_recurrence(xs, ys, cr=0.05)

            blocks = (cr_xy.rows, a_x.rows, a_y.rows, threads)
            candidates: dict[str, tuple[int, ...]] = {"row-wise": ()}
            candidates.update({f"blocked b={b}": (b,) for b in BLOCKS})
            reference = triangles(*blocks)
            walls: dict[str, list[float]] = {name: [] for name in candidates}
            cpus: dict[str, list[float]] = {name: [] for name in candidates}
            for _ in range(repeats):
                for name, words in candidates.items():
                    wall, cpu = time.perf_counter(), time.process_time()
                    counts = triangles(*blocks, *words)
                    walls[name].append(time.perf_counter() - wall)
                    cpus[name].append(time.process_time() - cpu)
                    assert all(np.array_equal(c, r) for c, r in zip(counts, reference,
                                                                    strict=True)), name
            base_wall = statistics.median(walls["row-wise"])
            base_cpu = statistics.median(cpus["row-wise"])
            for name in candidates:
                rows.append({
                    "m": xs.shape[0], "pair": f"{x_name}-{y_name}", "kernel": name,
                    "wall": statistics.median(walls[name]), "cpu": statistics.median(cpus[name]),
                    "ratio_wall": base_wall / statistics.median(walls[name]),
                    "ratio_cpu": base_cpu / statistics.median(cpus[name]),
                })
                r = rows[-1]
                print(f"| {r['m']} | {r['pair']} | {name} | {r['wall']:.3f} | {r['cpu']:.3f} | "
                      f"{r['ratio_wall']:.2f}x | {r['ratio_cpu']:.2f}x |", flush=True)
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=list(SIZES))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--skip-whole", action="store_true")
    parser.add_argument("--skip-kernels", action="store_true")
    parser.add_argument("--child-whole", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child_whole:
        whole_child()
        return
    cpu_model = next(
        (line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
         if line.startswith("model name")), platform.processor(),
    )
    print(f"# machine: {os.cpu_count()} CPUs, {cpu_model}, Python {platform.python_version()}")
    print(f"# load average at start: {load()}")
    if not args.skip_whole:
        report = whole_network()
        estimate = report["estimate"]
        print("\n## Whole trace, one 5-signal network (fresh interpreter)\n")
        print(f"rows {report['rows']}: wall {report['seconds']:.1f} s, CPU {report['cpu']:.1f} s, "
              f"peak RSS {report['vmhwm_mib']:.0f} MiB (ru_maxrss {report['maxrss_mib']:.0f}, "
              f"{report['rss_before_mib']:.0f} before the call), "
              f"{report['degenerate']} degenerate pair(s)")
        print(f"estimate_cost: {estimate['seconds']:.1f} s on {estimate['threads']} threads "
              f"({estimate['cpu_seconds']:.1f} CPU s), {estimate['bytes'] / 2**20:.0f} MiB")
        print(f"# load average after the network: {load()}")
    if not args.skip_kernels:
        print("\n## Triangle kernels, both directions (median of "
              f"{args.repeats}; ratio = row-wise / this)\n")
        print("| M | pair | kernel | wall [s] | CPU [s] | ratio wall | ratio CPU |")
        print("|---|---|---|---|---|---|---|")
        kernel_table(tuple(args.sizes), args.repeats)
    print(f"\n# load average at the end: {load()}")


if __name__ == "__main__":
    main()
