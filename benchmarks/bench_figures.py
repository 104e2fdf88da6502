"""Benchmark of the drawing step of `funcnet inspect`: the pages of inspections computed once.

Run from the repository root::

    python -m benchmarks.bench_figures [--against DIR] [--rounds N] [--cases NAME ...]
        [--per-figure]

The end-to-end benchmark (:mod:`benchmarks.bench_inspect`) times the computation and the drawing
together; on a machine shared with other work the computation's CPU time varies by more than the
drawing costs. Here each recording (the cases of :mod:`benchmarks.bench_inspect`; ``--cases``
picks them by the start of their names) is inspected once, by this checkout, and kept in a
pickle; then each code (this checkout, and with ``--against DIR`` another checkout's ``src``,
alternating) writes its pages from that pickle in a process of its own: the seconds to start
(importing the report and the inspection) and to write the pages (every figure, table and
page), wall and CPU, the CPU of the processes that drew pages beside it included.

With ``--per-figure`` each code instead draws every axis page's figures one by one in a single
process (no pages, no processes beside it): each figure built and saved as the page does
(:func:`funcnet.report.html.figure_html`), twice, the second time timed (warm), in CPU
seconds, summed over the axes per kind of figure; the codes alternate over ``--rounds``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.bench_inspect import CASES, ROOT, _cases, add_common_arguments, checkouts

# One process: load the pickle, write the pages, print the seconds as JSON.
_DRAW = """
import json, pickle, resource, sys, time
wall, cpu = time.perf_counter(), time.process_time()
from funcnet.inspection.run import inspect_file  # noqa: F401  (what `inspect` imports)
from funcnet.report.inspect import write_inspection, write_robot_inspection
from funcnet.inspection.robot import RobotInspection
with open(sys.argv[1], "rb") as f:
    found, names = pickle.load(f)
start = (time.perf_counter() - wall, time.process_time() - cpu)
wall, cpu = time.perf_counter(), time.process_time()
if isinstance(found, RobotInspection):
    write_robot_inspection(found, sys.argv[2], axis_names=names)
else:
    write_inspection(found, sys.argv[2])
children = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"start_wall": start[0], "start_cpu": start[1],
                  "draw_wall": time.perf_counter() - wall,
                  "draw_cpu": time.process_time() - cpu + children.ru_utime
                  + children.ru_stime}))
"""

# One process: load the pickle, build and save each axis page's figures twice, print the CPU
# seconds of the second time (build, save) per figure as JSON.
_FIGURES = """
import json, pickle, sys, tempfile, time, warnings
from pathlib import Path
warnings.simplefilter("ignore")
from funcnet.report import inspect_figures
from funcnet.report.html import figure_html
from funcnet.inspection.robot import RobotInspection
with open(sys.argv[1], "rb") as f:
    found, names = pickle.load(f)
axes = found.axes if isinstance(found, RobotInspection) else {0: found}
seconds = {}
with tempfile.TemporaryDirectory() as out:
    for k, ins in axes.items():
        for name in sys.argv[2:]:
            for _ in range(2):
                cpu = time.process_time()
                fig = getattr(inspect_figures, "figure_" + name)(ins)
                built = time.process_time() - cpu
                if fig is None:
                    break
                cpu = time.process_time()
                figure_html(Path(out), f"{k}-{name}", fig, "x")
                saved = time.process_time() - cpu
            if fig is not None:
                total = seconds.setdefault(name, [0.0, 0.0])
                total[0] += built
                total[1] += saved
print(json.dumps(seconds))
"""
FIGURES = ("motion", "networks", "timeline", "evidence", "lost_motion")

_INSPECT = """
import pickle, sys
from funcnet.inspection.run import inspect_file
from funcnet.robot.io.channels import channel_map
arguments = sys.argv[2:]
channels = arguments[arguments.index("--channels") + 1] if "--channels" in arguments else None
found = inspect_file(arguments[0], channels=channels)
with open(sys.argv[1], "wb") as f:
    pickle.dump((found, channel_map(channels).axis_names if channels else ()), f)
"""


def _environment(source: Path) -> dict[str, str]:
    return dict(os.environ, PYTHONPATH=str(source / "src"), OMP_WAIT_POLICY="PASSIVE")


def draw(source: Path, pickled: Path) -> dict[str, float]:
    """One process of ``source``'s code writing the pages of ``pickled``: its seconds."""
    with tempfile.TemporaryDirectory() as out:
        done = subprocess.run([sys.executable, "-c", _DRAW, str(pickled), out], cwd=ROOT,
                              env=_environment(source), capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"drawing {pickled} with {source} failed:\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def per_figure(source: Path, pickled: Path) -> dict[str, list[float]]:
    """One process of ``source``'s code drawing each axis page's figures of ``pickled``: the
    warm CPU seconds (build, save) of each kind of figure, summed over the axes."""
    done = subprocess.run([sys.executable, "-c", _FIGURES, str(pickled), *FIGURES], cwd=ROOT,
                          env=_environment(source), capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"drawing {pickled} with {source} failed:\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def _inspected(arguments: list[str], pickled: Path) -> None:
    subprocess.run([sys.executable, "-c", _INSPECT, str(pickled), *arguments], cwd=ROOT,
                   env=_environment(ROOT), check=True, stderr=subprocess.DEVNULL)


def main_per_figure(args: argparse.Namespace, codes: dict[str, Path]) -> None:
    """Print the table of ``--per-figure``: one row per recording and code, a column per
    kind of figure (build + save, CPU seconds, the best of the rounds)."""
    print("## funcnet inspect, the axis pages' figures one by one (warm CPU seconds, "
          "build + save, summed over the axes, best of the rounds)\n")
    print(f"- {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, "
          f"load average before: {os.getloadavg()[0]:.2f} (1 min)\n")
    print("| recording | code | " + " | ".join(FIGURES) + " | all [s] | CPU / this |")
    print("|---|---|" + "---|" * (len(FIGURES) + 2))
    with tempfile.TemporaryDirectory() as scratch:
        for case, arguments in _cases(args.cases).items():
            pickled = Path(scratch) / "inspection.pickle"
            _inspected(arguments, pickled)
            found: dict[str, list[dict[str, list[float]]]] = {name: [] for name in codes}
            for _ in range(args.rounds):
                for name, source in codes.items():
                    found[name].append(per_figure(source, pickled))
            best = {name: {f: min((r[f] for r in runs if f in r), key=sum, default=[0.0, 0.0])
                           for f in FIGURES} for name, runs in found.items()}
            mine = sum(sum(v) for v in best["this checkout"].values())
            for name, figures in best.items():
                cells = " | ".join(f"{figures[f][0]:.2f} + {figures[f][1]:.2f}" for f in FIGURES)
                total = sum(sum(v) for v in figures.values())
                print(f"| {case} | {name} | {cells} | **{total:.2f}** | {total / mine:.2f} |",
                      flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


def main(argv: list[str] | None = None) -> None:
    """Print the table: one row per recording and code."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    add_common_arguments(parser)
    parser.add_argument("--per-figure", action="store_true",
                        help="time each axis page's figures one by one instead of the pages")
    args = parser.parse_args(argv)
    codes = checkouts(args)
    if args.per_figure:
        main_per_figure(args, codes)
        return
    print("## funcnet inspect, the pages drawn from a computed inspection\n")
    print(f"- {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, "
          f"load average before: {os.getloadavg()[0]:.2f} (1 min)\n")
    print("| recording | code | start wall / CPU [s] | pages wall [s], median (rounds) | "
          "pages CPU [s] | CPU / this |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        for case, arguments in _cases(args.cases).items():
            pickled = Path(scratch) / "inspection.pickle"
            _inspected(arguments, pickled)
            found: dict[str, list[dict[str, float]]] = {name: [] for name in codes}
            for _ in range(args.rounds):
                for name, source in codes.items():
                    found[name].append(draw(source, pickled))
            mine = statistics.median(r["draw_cpu"] for r in found["this checkout"])
            for name, runs in found.items():
                def median(key: str, runs: list[dict[str, float]] = runs) -> float:
                    return statistics.median(r[key] for r in runs)
                rounds = ", ".join(f"{r['draw_wall']:.1f}" for r in runs)
                print(f"| {case} | {name} | {median('start_wall'):.1f} / "
                      f"{median('start_cpu'):.1f} | **{median('draw_wall'):.1f}** ({rounds}) | "
                      f"{median('draw_cpu'):.1f} | {median('draw_cpu') / mine:.2f} |",
                      flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    assert CASES  # the recordings are bench_inspect's
    main()
