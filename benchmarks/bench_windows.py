"""Benchmark of the paper's workload: many short windows, against pyunicorn in the same run.

Run from the repository root::

    python -m benchmarks.bench_windows [--skip-pyunicorn] [--quick] [--sample N] [--paper DIR]

1. One pair at 150, 300, 600, 1000, 2000 samples (m = 3, tau = 10, rates 0.05, supremum,
   ``rule="pyunicorn"``): ``funcnet.cross_measures`` (median of single calls), the batched
   engine on the same pair (:func:`funcnet.core.batch.batch_pairs`, one window of two signals,
   ``normalize=None``) and pyunicorn 1.0.0's ``InterSystemRecurrenceNetwork`` plus its four
   measures on the same embedded input; the values must agree (max difference printed).
2. A 6-signal network at 150 and 300 samples: ``functional_network`` (single call), the
   batched engine on that window, and amortized over a batch of windows.
3. The sliding timeline over the real trace ``../shared/data/sinumerik/axis7-braking-trace.xml``
   (RP, AP, MP, V, AC; 0.3 s windows every 2 ms from 0.05 s before each move's early spin-up to
   0.05 s after its braking): one :func:`funcnet.window_networks` call (batched) after a
   warm-up call on two windows, against the same function on the per-window path and pyunicorn
   (10 pairs per window), both timed on an evenly spread sample of the windows; both rules.
   Three rounds, each the batched call then pyunicorn on a third of its sample: the batched
   times and the ratio are the rounds' medians (the machine's speed drifts within a minute).
   The sample's networks are asserted equal (``==``) to the per-window path's. The batched call
   is timed again with the direction reading replaced by a constant (its share of the time),
   and pyunicorn's CPU time is measured beside its wall time (a loaded machine inflates wall).
4. With ``--paper DIR`` (a plan from ``funcnet simulate --plan paper --out DIR``): the paper's
   analyses (:func:`funcnet.paper.analyses.run_paper_analyses`) batched and per-window.

Times are wall-clock seconds (CPU seconds of all threads next to them) on a machine that may be
shared: the load average is printed before and after; only ratios measured in this run mean
something.
"""

from __future__ import annotations

import argparse
import statistics
import time
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from benchmarks.bench_core import Run, six_signals, timed

DIM, DELAY, RATE = 3, 10, 0.05
PAIR_SAMPLES = (150, 300, 600, 1000, 2000)
TRACE = Path(__file__).resolve().parents[2] / "shared/data/sinumerik/axis7-braking-trace.xml"
NODES = ["RP", "AP", "MP", "V", "AC"]
ROUNDS = 3  # of the timeline: batched call and a third of the pyunicorn sample


@contextmanager
def per_window_path() -> Iterator[None]:
    """``window_networks`` without the batched engine (what it did before it)."""
    import funcnet.pipeline

    original = funcnet.pipeline._batched_networks
    funcnet.pipeline._batched_networks = lambda *args, **kwargs: ({}, [])  # type: ignore[assignment]
    try:
        yield
    finally:
        funcnet.pipeline._batched_networks = original  # type: ignore[assignment]


@contextmanager
def without_direction() -> Iterator[None]:
    """``window_networks`` with the direction reading replaced by a constant (its share)."""
    import funcnet.pipeline

    # the stacked reading, or the per-window one of earlier versions (for a before/after)
    name = ("window_directions" if hasattr(funcnet.pipeline, "window_directions")
            else "direction_columns")
    original = getattr(funcnet.pipeline, name)

    def constant(windows: Any, names: Any, pairs: Any = None, *args: Any, **kwargs: Any) -> Any:
        rows = len(windows) * len(pairs) if name == "window_directions" else len(windows)
        return {"direction": ["none"] * rows, "direction_reason": [""] * rows}

    setattr(funcnet.pipeline, name, constant)
    # the p-values read apart (while the kernels run), where the pipeline does so
    apart = getattr(funcnet.pipeline, "window_p_values", None)
    if apart is not None:
        funcnet.pipeline.window_p_values = lambda *args, **kwargs: None  # type: ignore
    try:
        yield
    finally:
        setattr(funcnet.pipeline, name, original)
        if apart is not None:
            funcnet.pipeline.window_p_values = apart  # type: ignore[attr-defined]


#: CPU seconds of the last :func:`pyunicorn_measures` call.
PYUNICORN_CPU = [0.0]


def pyunicorn_measures(x: np.ndarray, y: np.ndarray,
                       metric: str = "supremum") -> tuple[float, tuple[float, ...]]:
    """Seconds and (C_xy, C_yx, T_xy, T_yx) of pyunicorn's ISRN on the embedded signals."""
    from pyunicorn.timeseries import InterSystemRecurrenceNetwork

    from funcnet.core.embedding import embed

    cpu = time.process_time()
    start = time.perf_counter()
    network = InterSystemRecurrenceNetwork(
        embed(x, DIM, DELAY), embed(y, DIM, DELAY), metric=metric,
        recurrence_rate=(RATE, RATE, RATE), silence_level=3,
    )
    values = (
        network.cross_global_clustering_xy(),
        network.cross_global_clustering_yx(),
        network.cross_transitivity_xy(),
        network.cross_transitivity_yx(),
    )
    PYUNICORN_CPU[0] = time.process_time() - cpu
    return time.perf_counter() - start, values


def signal_pair(n_samples: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Two noisy oscillators in [0, 1], Y driven by X."""
    rng = np.random.default_rng(seed)
    t = np.arange(n_samples)
    x = np.sin(0.05 * t) + 0.1 * rng.normal(size=t.size)
    y = np.sin(0.065 * t + 0.5) + 0.3 * x + 0.1 * rng.normal(size=t.size)
    return (x - x.min()) / np.ptp(x), (y - y.min()) / np.ptp(y)


def one_pair(skip_pyunicorn: bool, sizes: tuple[int, ...]) -> None:
    from funcnet.core.batch import batch_pairs
    from funcnet.core.measures import cross_measures

    options: dict[str, Any] = {"dim": DIM, "delay": DELAY, "metric": "supremum",
                               "rule": "pyunicorn"}
    print("\n### One pair (rule=pyunicorn, supremum)\n")
    print("| samples | cross_measures [ms] (best) | batch_pairs, 1 window [ms] (best) | "
          "pyunicorn [ms] | pyunicorn / cross_measures | pyunicorn / batch_pairs | "
          "max abs diff |")
    print("|---|---|---|---|---|---|---|")
    for n in sizes:
        x, y = signal_pair(n)
        repeats = 21 if n <= 300 else (7 if n <= 1000 else 3)
        wall, best, _, result = timed(
            lambda x=x, y=y: cross_measures(x, y, warn=False, **options), repeats)
        stack = np.column_stack([x, y])[np.newaxis]
        b_wall, b_best, _, batched = timed(
            lambda stack=stack: batch_pairs(stack, normalize=None, **options), repeats)
        assert batched.measures(0)[("0", "1")].c_xy == result.c_xy  # type: ignore[union-attr]
        mine = (result.c_xy, result.c_yx, result.t_xy, result.t_yx)  # type: ignore[union-attr]
        row = (f"| {n} | {wall * 1e3:.2f} ({best * 1e3:.2f}) | {b_wall * 1e3:.2f} "
               f"({b_best * 1e3:.2f}) |")
        if skip_pyunicorn:
            print(f"{row} skipped | | | |")
            continue
        runs = [pyunicorn_measures(x, y) for _ in range(5 if n <= 300 else 1)]
        reference = statistics.median(seconds for seconds, _ in runs)
        difference = max(abs(a - b) for a, b in zip(mine, runs[0][1], strict=True))
        assert difference <= 1e-9, difference
        print(f"{row} {reference * 1e3:.1f} | {reference / wall:.0f}x | "
              f"{reference / b_wall:.0f}x | {difference:.1e} |")


def six_signal_network(skip_pyunicorn: bool, batch_size: int) -> None:
    from funcnet.core.batch import batch_pairs
    from funcnet.network import functional_network

    print("\n### A 6-signal network (15 pairs; defaults: rule=funcnet, Euclidean, min-max)\n")
    print("| samples | functional_network [ms] | batch_pairs, 1 window [ms] | batch_pairs, "
          f"amortized over {batch_size} windows [ms/window] (CPU) | per-window / amortized | "
          "pyunicorn, 15 pairs [ms] | pyunicorn / amortized |")
    print("|---|---|---|---|---|---|---|")
    for n in (150, 300):
        rng = np.random.default_rng(n)
        windows = []
        for w in range(batch_size):
            signals = six_signals(n + 7 * w, seed=w)
            windows.append(np.column_stack(signals)[-n:] + 1e-3 * rng.normal(size=(n, 6)))
        stack = np.stack(windows)
        batch_pairs(stack[:2])
        wall, _, _, network = timed(lambda stack=stack: functional_network(stack[0], warn=False),
                                    7)
        single, _, _, _ = timed(lambda stack=stack: batch_pairs(stack[:1]), 7)
        amortized, _, cpu, result = timed(lambda stack=stack: batch_pairs(stack), 3)
        assert result["c_diff"][0].tolist() == network.pairs["c_diff"].tolist()  # type: ignore
        amortized, cpu = amortized / batch_size, cpu / batch_size
        row = (f"| {n} | {wall * 1e3:.2f} | {single * 1e3:.2f} | {amortized * 1e3:.3f} "
               f"({cpu * 1e3:.3f}) | {wall / amortized:.0f}x |")
        if skip_pyunicorn:
            print(f"{row} skipped | |")
            continue
        values = np.column_stack(six_signals(n, seed=0))[-n:]
        values = (values - values.min(axis=0)) / np.ptp(values, axis=0)
        seconds = sum(pyunicorn_measures(values[:, i], values[:, j], "euclidean")[0]
                      for i in range(6) for j in range(i + 1, 6))
        print(f"{row} {seconds * 1e3:.0f} | {seconds / amortized:.0f}x |")


def timeline_windows() -> tuple[Any, list[Any], int]:
    """The recording, the timeline's windows over its moves, and the number of moves."""
    from funcnet.robot import add_derived_signals, detect_phases, read_trace, sliding_windows

    recording = add_derived_signals(read_trace(TRACE), ["V"])
    phases = detect_phases(recording)
    windows: list[Any] = []
    begin = 0.0
    for row in phases.itertuples():
        if row.phase == "early spin-up":
            begin = row.start - 0.05
        if row.phase == "braking":
            windows += sliding_windows(recording, 0.3, 0.002, start=begin, stop=row.stop + 0.05)
    return recording, windows, int(sum(phases["phase"] == "braking"))


def timeline(skip_pyunicorn: bool, n_sample: int) -> None:
    from funcnet import window_networks

    recording, windows, moves = timeline_windows()
    sample = [windows[i] for i in np.linspace(0, len(windows) - 1, n_sample).astype(int)]
    print(f"\n### Sliding timeline over the real trace ({TRACE.name}: {moves} moves, "
          f"{len(windows)} windows of 0.3 s every 2 ms, {len(NODES)} signals = 10 pairs per "
          "window), `window_networks`\n")
    print(f"| rule, metric | batched, all windows [s] (CPU) | without the direction [s] (CPU) "
          f"| batched [ms/window] | per-window path [ms/window] ({n_sample} windows) | "
          f"pyunicorn [ms/window] (CPU) ({min(30, n_sample)} windows) | "
          "per-window / batched | pyunicorn / batched, wall (CPU) |")
    print("|---|---|---|---|---|---|---|---|")
    for options in ({}, {"rule": "pyunicorn", "metric": "supremum"}):
        def batched(chosen: list[Any], options: dict[str, Any] = options) -> Any:
            return window_networks(recording, chosen, signals=NODES, **options)

        batched(windows[:2])  # warm-up
        with without_direction():
            bare, _, bare_cpu, _ = timed(lambda: batched(windows), 1)
        with per_window_path():
            batched(sample[:2])
            path_wall, _, _, singles = timed(lambda: batched(sample), 1)
        # Rounds: the batched call, then pyunicorn on every ROUNDS-th window of its sample; the
        # ratio is the median of the rounds' (this machine's speed drifts within a minute).
        metric = options.get("metric", "euclidean")
        chosen = sample[: min(30, len(sample))]
        walls, cpus, references, reference_cpus, ratios, cpu_ratios = ([] for _ in range(6))
        for start in range(ROUNDS):
            wall, _, cpu, networks = timed(lambda: batched(windows), 1)
            seconds = cpu_seconds = 0.0
            for window in chosen[start::ROUNDS]:
                part = recording.window(window.start, window.stop).data[NODES].to_numpy()
                part = (part - part.min(axis=0)) / np.ptp(part, axis=0)
                for i, j in zip(*np.triu_indices(5, k=1), strict=True):
                    seconds += pyunicorn_measures(part[:, i], part[:, j], metric)[0]
                    cpu_seconds += PYUNICORN_CPU[0]
            count = len(chosen[start::ROUNDS])
            walls.append(wall)
            cpus.append(cpu)
            references.append(seconds / count)
            reference_cpus.append(cpu_seconds / count)
            ratios.append(references[-1] * len(windows) / wall)
            cpu_ratios.append(reference_cpus[-1] * len(windows) / cpu)
            if skip_pyunicorn:
                break
        wall, cpu = statistics.median(walls), statistics.median(cpus)
        per_window = wall / len(windows)
        path = path_wall / len(sample)
        reasons = 0
        for window in sample:
            # equal but where a reason prints a p-value the inputs' rounding sets (the sliding
            # reading is read from the recording's rows, the per-window one from the window's)
            mine, alone = networks[window.label], singles[window.label]  # type: ignore
            if mine != alone:
                assert mine.pairs.drop(columns="direction_reason").equals(
                    alone.pairs.drop(columns="direction_reason")), window.label
                reasons += int((mine.pairs["direction_reason"]
                                != alone.pairs["direction_reason"]).sum())
        label = f"{options.get('rule', 'funcnet')}, {options.get('metric', 'euclidean')}"
        print(f"({label}: direction {cpu - bare_cpu:.2f} CPU s; {reasons} reasons of the "
              f"sample print another p-value than the per-window path; pyunicorn / batched "
              f"in each round: {', '.join(f'{r:.0f}x' for r in ratios)})")
        row = (f"| {label} | {wall:.2f} ({cpu:.2f}) | {bare:.2f} ({bare_cpu:.2f}) | "
               f"{per_window * 1e3:.2f} | {path * 1e3:.1f} |")
        if skip_pyunicorn:
            print(f"{row} skipped | {path / per_window:.0f}x | |")
            continue
        print(f"{row} {statistics.median(references) * 1e3:.0f} "
              f"({statistics.median(reference_cpus) * 1e3:.0f}) | "
              f"{path / per_window:.0f}x | {statistics.median(ratios):.0f}x "
              f"({statistics.median(cpu_ratios):.0f}x) |")


def paper(plan: Path) -> None:
    from funcnet.paper.analyses import run_paper_analyses

    def run() -> Any:
        return run_paper_analyses(plan)

    print(f"\n### The paper's analyses (`run_paper_analyses` on {plan})\n")
    print("| path | wall [s] | CPU [s] |\n|---|---|---|")
    run()  # warm-up: compiled kernels loaded, files cached
    results: dict[str, Callable[[], Any]] = {"batched": run}
    for name, function in results.items():
        wall, _, cpu, _ = timed(function, 1)
        print(f"| {name} | {wall:.1f} | {cpu:.1f} |")
    with per_window_path():
        wall, _, cpu, _ = timed(run, 1)
    print(f"| per-window | {wall:.1f} | {cpu:.1f} |")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--skip-pyunicorn", action="store_true")
    parser.add_argument("--quick", action="store_true", help="smaller sizes and samples")
    parser.add_argument("--sample", type=int, default=None,
                        help="timeline windows timed on the per-window path (default 100)")
    parser.add_argument("--paper", type=Path, default=None, help="a paper plan directory")
    parser.add_argument("--only", choices=("pair", "six", "timeline", "paper"), default=None)
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    run = Run()

    from funcnet.core.batch import batch_pairs
    from funcnet.core.measures import cross_measures

    x, y = signal_pair(300)
    cross_measures(x, y, rule="pyunicorn", metric="supremum", warn=False)  # load the kernels
    batch_pairs(np.column_stack([x, y])[np.newaxis])

    run.header("Many short windows: batched engine")
    sizes = PAIR_SAMPLES[:3] if args.quick else PAIR_SAMPLES
    if args.only in (None, "pair"):
        one_pair(args.skip_pyunicorn, sizes)
    if args.only in (None, "six"):
        six_signal_network(args.skip_pyunicorn, 50 if args.quick else 300)
    if args.only in (None, "timeline"):
        timeline(args.skip_pyunicorn, args.sample or (10 if args.quick else 100))
    if args.paper is not None and args.only in (None, "paper"):
        paper(args.paper)
    run.footer("python -m benchmarks.bench_windows")


if __name__ == "__main__":
    main()
