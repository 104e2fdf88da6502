"""Benchmark of the core: cross measures against pyunicorn, a 6-signal network, cost versus M.

Run from the repository root::

    python -m benchmarks.bench_core [--skip-pyunicorn] [--sizes 500 1000 ...]

1. One pair at M = 2000 embedded states (m = 3, tau = 10, RR = CR = 0.05, Euclidean):
   pyunicorn 1.0.0's ``InterSystemRecurrenceNetwork`` (the four measures, run once: it takes
   seconds) and ``funcnet.cross_measures(..., rule="pyunicorn")`` (median of 7 calls,
   alternating with ``rule="funcnet"``) in the same run; their ratio, and the largest difference
   of the four values (must be <= 1e-9). Target: at least 100x.
2. A 6-signal functional network on a 2000-sample window (``pairwise_cross_measures``, each
   signal's recurrence computed once; median of 5). Target: under 0.5 s.
3. One pair (``cross_measures``, rule "funcnet") for each M, each in a fresh interpreter that
   reports the time of the call (after a small warm-up call, so compilation is excluded) and its
   peak resident memory (``VmHWM`` of /proc/self/status, and ``resource.getrusage``'s
   ``ru_maxrss``, which on Linux also covers the parent's size at fork: these children are
   started first, from a small parent). Target at M = 20000: peak RSS under 1.5 GB.

Times are wall-clock seconds on whatever machine runs this; the load average before and after is
printed because the machine may be shared (CPU seconds are shown next to wall seconds for that
reason). Compiled kernels are cached on disk (Numba ``cache=True``): the first run after an edit
compiles them once, which the warm-up absorbs.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
import warnings

import numpy as np

DIM, DELAY, RATE = 3, 10, 0.05
SIZES = (500, 1000, 2000, 5000, 10000, 20000)


def coupled_pair(n_states: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Two noisy oscillators, Y driven by X, with ``n_states`` embedded states each."""
    rng = np.random.default_rng(seed)
    t = np.arange(n_states + (DIM - 1) * DELAY)
    x = np.sin(0.05 * t) + 0.1 * rng.normal(size=t.size)
    y = np.sin(0.065 * t + 0.5) + 0.3 * x + 0.1 * rng.normal(size=t.size)
    return x, y


def six_signals(n_samples: int, seed: int = 1) -> list[np.ndarray]:
    """Six signals of different character (smooth, rough, quantized), as a robot window has."""
    rng = np.random.default_rng(seed)
    t = np.arange(n_samples) / 500.0
    position = np.sin(2 * np.pi * 0.7 * t)
    velocity = np.gradient(position)
    current = 0.5 * velocity / velocity.std() + 0.3 * rng.normal(size=t.size)
    return [
        position,
        np.round(position * 2000) / 2000,  # encoder quantization
        velocity,
        current,
        np.cumsum(rng.normal(size=t.size)) / 30,
        np.sin(2 * np.pi * 3.1 * t) + 0.2 * position,
    ]


def timed(function, repeats: int) -> tuple[float, float, float, object]:
    """Median and best wall seconds, median CPU seconds of ``repeats`` calls, last result."""
    walls, cpus = [], []
    result = None
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        result = function()
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), min(walls), statistics.median(cpus), result


def pyunicorn_pair(x: np.ndarray, y: np.ndarray) -> tuple[float, tuple[float, ...]]:
    from pyunicorn.timeseries import InterSystemRecurrenceNetwork

    from funcnet.core.embedding import embed

    start = time.perf_counter()
    network = InterSystemRecurrenceNetwork(
        embed(x, DIM, DELAY),
        embed(y, DIM, DELAY),
        metric="euclidean",
        recurrence_rate=(RATE, RATE, RATE),
        silence_level=3,
    )
    values = (
        network.cross_global_clustering_xy(),
        network.cross_global_clustering_yx(),
        network.cross_transitivity_xy(),
        network.cross_transitivity_yx(),
    )
    return time.perf_counter() - start, values


def one_pair_in_child(n_states: int) -> dict[str, float]:
    """Time one pair and take the peak RSS of a fresh interpreter (``--child``)."""
    command = [sys.executable, "-m", "benchmarks.bench_core", "--child", str(n_states)]
    output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return json.loads(output.strip().splitlines()[-1])


def peak_rss_of_this_process_mib() -> float:
    """Peak RSS of this process image from /proc (VmHWM), else from getrusage."""
    import resource

    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def child(n_states: int) -> None:
    import resource

    from funcnet.core.measures import cross_measures

    warnings.simplefilter("ignore")
    # Load the compiled kernels; 900 states take the sampled-bracket path as large M do.
    small_x, small_y = coupled_pair(900)
    cross_measures(small_x, small_y)
    baseline = peak_rss_of_this_process_mib()
    x, y = coupled_pair(n_states)
    wall, cpu = time.perf_counter(), time.process_time()
    result = cross_measures(x, y, dim=DIM, delay=DELAY, rr=RATE, cr=RATE)
    report = {
        "m": n_states,
        "seconds": time.perf_counter() - wall,
        "cpu": time.process_time() - cpu,
        # getrusage's ru_maxrss survives exec (Linux keeps the parent's peak at fork): the
        # parent therefore launches these children while it is still small.
        "ru_maxrss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "vm_hwm_mib": peak_rss_of_this_process_mib(),
        "baseline_mib": baseline,
        "c_diff": result.c_diff,
        "t_diff": result.t_diff,
    }
    print(json.dumps(report))


class Run:
    """A benchmark run's record: the load average and the clock at its start, printed in its
    header (title, machine, load before) and its footer (load after, total time, command)."""

    def __init__(self) -> None:
        self.load_before = os.getloadavg()
        self.start = time.perf_counter()

    def header(self, title: str) -> None:
        print(f"## {title}\n")
        print(f"- machine: {machine()}")
        print(f"- load average before: {self.load_before[0]:.2f} (1 min), "
              f"{self.load_before[1]:.2f} (5 min)")

    def footer(self, command: str) -> None:
        print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min); total "
              f"{time.perf_counter() - self.start:.0f} s; command: {command}")


def machine() -> str:
    import numba

    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            model = next(line.split(":", 1)[1].strip() for line in cpuinfo if "model name" in line)
    except (OSError, StopIteration):
        pass
    return (
        f"{model}, {os.cpu_count()} logical CPUs, Numba threads {numba.get_num_threads()} "
        f"({numba.threading_layer() if hasattr(numba, 'threading_layer') else '?'}), "
        f"Python {platform.python_version()}, NumPy {np.__version__}, Numba {numba.__version__}"
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-pyunicorn", action="store_true")
    parser.add_argument("--sizes", type=int, nargs="*", default=list(SIZES))
    parser.add_argument("--child", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child is not None:
        child(args.child)
        return

    run = Run()
    # The size sweep runs first, while this process is small: a child's getrusage peak starts
    # from its parent's size at fork.
    sweep = [one_pair_in_child(n_states) for n_states in args.sizes]

    from funcnet.core.measures import cross_measures, pairwise_cross_measures

    warnings.simplefilter("ignore")
    x, y = coupled_pair(2000)
    cross_measures(x[:900], y[:900], rule="pyunicorn")  # load the compiled kernels
    cross_measures(x[:900], y[:900])

    run.header("funcnet core benchmark")
    print(
        f"- signals: coupled noisy oscillators, m = {DIM}, tau = {DELAY}, RR = CR = {RATE}, "
        "Euclidean; wall = median (best) of 7 calls (5 for the network), CPU = median CPU "
        "seconds of all threads\n"
    )
    print(
        "| case | M | funcnet wall [s] | funcnet CPU [s] | pyunicorn [s] | ratio | max abs diff |"
    )
    print("|---|---|---|---|---|---|---|")
    # The two rules alternate call by call, so that both meet the same machine load.
    rules = {"pyunicorn": ([], [], None), "funcnet": ([], [], None)}
    for _ in range(7):
        for rule, (walls, cpus, _) in rules.items():
            wall, _, cpu, result = timed(lambda rule=rule: cross_measures(x, y, rule=rule), 1)
            walls.append(wall)
            cpus.append(cpu)
            rules[rule] = (walls, cpus, result)
    for rule, (walls, cpus, result) in rules.items():
        wall, best, cpu = statistics.median(walls), min(walls), statistics.median(cpus)
        row = f"| one pair, rule={rule} | 2000 | {wall:.4f} ({best:.4f}) | {cpu:.4f} |"
        if rule == "funcnet":
            print(f"{row} | | |")
        elif args.skip_pyunicorn:
            print(f"{row} skipped | | |")
        else:
            reference_seconds, reference = pyunicorn_pair(x, y)
            values = (result.c_xy, result.c_yx, result.t_xy, result.t_yx)
            difference = max(abs(a - b) for a, b in zip(values, reference, strict=True))
            print(
                f"{row} {reference_seconds:.2f} | {reference_seconds / wall:.0f}x "
                f"({reference_seconds / best:.0f}x) | {difference:.1e} |"
            )
    signals = six_signals(2000)
    pairwise_cross_measures(signals[:2])
    wall, best, cpu, _ = timed(lambda: pairwise_cross_measures(signals), 5)
    print(
        f"| 6-signal network, 15 pairs, 2000 samples | {2000 - (DIM - 1) * DELAY} | "
        f"{wall:.4f} ({best:.4f}) | {cpu:.4f} | | | |"
    )

    print("\nOne pair (rule=funcnet) per M, each in a fresh interpreter (one call each):\n")
    print("| M | wall [s] | CPU [s] | peak RSS [MiB] | ru_maxrss [MiB] | RSS after warm-up [MiB] |")
    print("|---|---|---|---|---|---|")
    for report in sweep:
        print(
            f"| {report['m']} | {report['seconds']:.3f} | {report['cpu']:.3f} | "
            f"{report['vm_hwm_mib']:.0f} | {report['ru_maxrss_mib']:.0f} | "
            f"{report['baseline_mib']:.0f} |"
        )
    run.footer("python -m benchmarks.bench_core")


if __name__ == "__main__":
    main()
