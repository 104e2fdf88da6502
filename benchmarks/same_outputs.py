"""The same CLI calls on two code trees, and whether their outputs are the same.

A change that should leave results alone (a rename, a split, a faster kernel) is shown to by
running a fixed list of ``funcnet`` calls with the code before and with the code after, each into
a folder of its own, and comparing the folders::

    # the code before, e.g. a worktree of the base commit
    PYTHONPATH=src python -m benchmarks.same_outputs run /tmp/same-before --code /tmp/base/src
    # the code after
    PYTHONPATH=src python -m benchmarks.same_outputs run /tmp/same-after --code src
    python -m benchmarks.same_outputs compare /tmp/same-before /tmp/same-after

``run`` starts each call as its own process, ``python -m funcnet ...`` with ``PYTHONPATH`` set to
``--code`` (and ``OMP_WAIT_POLICY=PASSIVE``), in the folder ``OUT/<call>/``, writing its outputs
there; the inputs (the recordings of ``data/``, the channel maps of ``examples/``, the SINUMERIK
trace beside the clone) are read from ``--inputs`` (default: this repository), the same for both
sides. Each call's exit status, stdout, stderr, wall and CPU time are kept beside its outputs
(``call.json``, ``stdout.txt``, ``stderr.txt``).

``compare`` pairs the files of the two folders: JSON, CSV and every other file byte for byte;
where the bytes differ, JSON and CSV are read and compared value by value (the largest absolute
and relative difference of the numbers, and the values that differ otherwise), HTML as text
(the lines that differ), PNG and other files by their bytes alone. Before text is compared, the
folders' own paths, the inputs' root, the date a page was written and the seconds it took (its
provenance's "date (UTC)" and "computation time [s]") become placeholders: two runs of the same
code compare the same. Timings are shown, never compared. Exit status 0 when every file is the
same (byte for byte, or but for those placeholders), 1 otherwise.
"""

from __future__ import annotations

import argparse
import csv
import difflib
import io
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SINUMERIK = Path("..", "shared", "data", "sinumerik", "axis7-braking-trace.xml")
KUKA_MAP = "examples/kuka-kr300-channels.toml"
UR5_MAP = "examples/ur5-channels.toml"
KUKA_A = "data/kuka-kr300/kr300-run-A.mat"
UR5 = "data/ur5/"
# The KUKA axis of the one-axis calls: axis 2 (the shoulder) carries the arm's weight.
AXIS = "2"


def calls(inputs: Path) -> Iterator[tuple[str, list[str]]]:
    """(name, arguments after ``funcnet``) of every call; ``{in}`` stands for ``inputs``."""
    yield "inspect-kuka-A", ["inspect", f"{{in}}/{KUKA_A}", "--channels", f"{{in}}/{KUKA_MAP}",
                             "-q", "-o", "out"]
    yield "inspect-ur5-No8", ["inspect", f"{{in}}/{UR5}Movement_No8_Singularity_Free_1",
                              "--channels", f"{{in}}/{UR5_MAP}", "-q", "-o", "out"]
    yield "inspect-mcs500", ["inspect", "{in}/data/mecademic-mcs500/mcs500-two-cycles.csv",
                             "--channels", "{in}/examples/mecademic-channels.toml", "-q",
                             "-o", "out"]
    if (inputs / SINUMERIK).is_file():
        yield "inspect-sinumerik", ["inspect", f"{{in}}/{SINUMERIK.as_posix()}", "-q",
                                    "-o", "out"]
    else:
        print(f"# {inputs / SINUMERIK} is not there: its inspect left out", file=sys.stderr)
    axis = ["--channels", f"{{in}}/{KUKA_MAP}", "--axis", AXIS]
    yield "network-kuka-A-axis2", ["network", f"{{in}}/{KUKA_A}", *axis, "-o", "network.json"]
    yield "backlash-kuka-A-axis2", ["backlash", f"{{in}}/{KUKA_A}", *axis, "-o", "backlash.json"]
    yield "stability-kuka-A-axis2", ["stability", f"{{in}}/{KUKA_A}", *axis,
                                     "-o", "stability.csv"]
    yield "compare-ur5-No9-No8", ["compare", f"{{in}}/{UR5}Movement_No9_Singularity_Free_NoDist",
                                  "--against", f"{{in}}/{UR5}Movement_No8_Singularity_Free_1",
                                  "--channels", f"{{in}}/{UR5_MAP}", "-o", "out"]


# --------------------------------------------------------------------------------------------
# run


def run_all(out: Path, code: Path, inputs: Path, only: list[str] | None = None) -> int:
    """Every call (or those named in ``only``) into ``out``; the number that did not exit 0."""
    out.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONPATH": str(code.resolve()), "OMP_WAIT_POLICY": "PASSIVE"}
    failed = 0
    for name, arguments in calls(inputs):
        if only and name not in only:
            continue
        folder = out / name
        shutil.rmtree(folder, ignore_errors=True)  # nothing of an earlier run left to compare
        folder.mkdir()
        args = [a.replace("{in}", str(inputs.resolve())) for a in arguments]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        began = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "funcnet", *args], cwd=folder, env=env,
                              capture_output=True, text=True)
        wall = time.perf_counter() - began
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        (folder / "stdout.txt").write_text(done.stdout, encoding="utf-8")
        (folder / "stderr.txt").write_text(done.stderr, encoding="utf-8")
        record = {"arguments": arguments, "returncode": done.returncode, "code": str(code),
                  "inputs": str(inputs.resolve()), "folder": str(folder.resolve()),
                  "wall_s": round(wall, 2), "cpu_s": round(cpu, 2),
                  "load": os.getloadavg()[0]}
        (folder / "call.json").write_text(json.dumps(record, indent=1), encoding="utf-8")
        failed += done.returncode != 0
        print(f"{name}: exit {done.returncode}, {wall:.1f} s wall, {cpu:.1f} s CPU", flush=True)
    return failed


# --------------------------------------------------------------------------------------------
# compare

# Files of the run itself, not outputs: timings and places differ by nature.
_OWN = {"call.json"}


def _places(folder: Path) -> list[tuple[str, str]]:
    """(text, placeholder) of the places a call's text may name: its folder and the inputs."""
    record = json.loads((folder / "call.json").read_text(encoding="utf-8"))
    found = [(record["folder"], "<OUT>"), (record["inputs"], "<INPUTS>")]
    return sorted(found, key=lambda pair: -len(pair[0]))


# When a page was written and how long it took: the values two runs of the same code never
# share (a page's provenance rows; a document's fields of that name).
_DATES = (re.compile(r"((?:date \(UTC\)|computation time \[s\])</td><td>(?:<span[^>]*>)?)"
                     r"[^<]+"),
          re.compile(r'("(?:date|created|written)"\s*:\s*")[^"]+'),
          re.compile(r'("(?:computation_time|elapsed|seconds)"\s*:\s*)[0-9.eE+-]+'))


def _text(path: Path, places: list[tuple[str, str]]) -> str:
    """The file's text with its places and its writing date as placeholders."""
    text = path.read_text(encoding="utf-8", errors="replace")
    for place, mark in places:
        text = text.replace(place, mark)
    for pattern in _DATES:
        text = pattern.sub(r"\1<DATE>", text)
    return text


def _number(value: object) -> float | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return None
    return None


class _Differences:
    """The largest numeric differences and the first other differences of two documents."""

    def __init__(self) -> None:
        self.abs = 0.0
        self.rel = 0.0
        self.numbers = 0
        self.others: list[str] = []
        self.nan_mismatch = 0

    def value(self, where: str, a: object, b: object) -> None:
        x, y = _number(a), _number(b)
        if x is not None and y is not None:
            if x == y or (math.isnan(x) and math.isnan(y)):
                return
            if math.isnan(x) or math.isnan(y) or math.isinf(x) or math.isinf(y):
                self.nan_mismatch += 1
                self.others.append(f"{where}: {a!r} != {b!r}")
                return
            self.numbers += 1
            self.abs = max(self.abs, abs(x - y))
            self.rel = max(self.rel, abs(x - y) / max(abs(x), abs(y)))
        elif a != b:
            self.others.append(f"{where}: {str(a)[:80]!r} != {str(b)[:80]!r}")

    def tree(self, where: str, a: object, b: object) -> None:
        if isinstance(a, dict) and isinstance(b, dict):
            for key in sorted(set(a) | set(b), key=str):
                if key not in a or key not in b:
                    self.others.append(f"{where}/{key}: only on one side")
                else:
                    self.tree(f"{where}/{key}", a[key], b[key])
        elif isinstance(a, list) and isinstance(b, list):
            if len(a) != len(b):
                self.others.append(f"{where}: {len(a)} items != {len(b)}")
            for k, (x, y) in enumerate(zip(a, b, strict=False)):
                self.tree(f"{where}[{k}]", x, y)
        else:
            self.value(where, a, b)

    def summary(self) -> str:
        parts = []
        if self.numbers:
            parts.append(f"{self.numbers} numbers differ, max abs {self.abs:.3g}, "
                         f"max rel {self.rel:.3g}")
        if self.others:
            shown = "; ".join(self.others[:5])
            more = f" (and {len(self.others) - 5} more)" if len(self.others) > 5 else ""
            parts.append(f"{len(self.others)} other differences: {shown}{more}")
        return "; ".join(parts) or "the same values (formatting differs)"


def _json_differences(a: str, b: str) -> str:
    found = _Differences()
    try:
        found.tree("", json.loads(a), json.loads(b))
    except json.JSONDecodeError as error:
        return f"not JSON: {error}"
    return found.summary()


def _csv_differences(a: str, b: str) -> str:
    rows_a, rows_b = list(csv.reader(io.StringIO(a))), list(csv.reader(io.StringIO(b)))
    found = _Differences()
    if len(rows_a) != len(rows_b):
        found.others.append(f"{len(rows_a)} rows != {len(rows_b)}")
    for k, (x, y) in enumerate(zip(rows_a, rows_b, strict=False)):
        found.tree(f"row {k}", x, y)
    return found.summary()


def _first_difference(a: str, b: str, width: int = 50) -> str:
    """Both lines around their first differing character."""
    k = next((i for i, (x, y) in enumerate(zip(a, b, strict=False)) if x != y), min(len(a),
                                                                                  len(b)))
    lo = max(0, k - width)
    return f"at char {k}: {a[lo:k + width]!r} / {b[lo:k + width]!r}"


def _text_differences(a: str, b: str) -> str:
    """How many lines differ, and the first few, each at its first differing character."""
    lines_a, lines_b = a.splitlines(), b.splitlines()
    shown: list[str] = []
    n = 0
    matcher = difflib.SequenceMatcher(None, lines_a, lines_b, autojunk=False)
    for tag, i0, i1, j0, j1 in matcher.get_opcodes():
        if tag == "equal":
            continue
        n += max(i1 - i0, j1 - j0)
        for x, y in zip(lines_a[i0:i1] or [""], lines_b[j0:j1] or [""], strict=False):
            if len(shown) < 6:
                shown.append(f"      line {i0 + 1}: {_first_difference(x, y)}")
    return f"{n} line(s) differ:\n" + "\n".join(shown)


def compare_files(a: Path, b: Path, places_a: list[tuple[str, str]],
                  places_b: list[tuple[str, str]]) -> tuple[str, str]:
    """(verdict, detail) of two files: ``same`` (bytes), ``same text`` (bytes differ only in
    the places named), ``differs``."""
    if a.read_bytes() == b.read_bytes():
        return "same", ""
    suffix = a.suffix.lower()
    if suffix in (".json", ".csv", ".html", ".txt", ".svg", ".md", ".toml"):
        ta, tb = _text(a, places_a), _text(b, places_b)
        if ta == tb:
            return "same text", ("the bytes differ only in the folders' or the inputs' places "
                                 "or the date and time taken")
        if suffix == ".json":
            return "differs", _json_differences(ta, tb)
        if suffix == ".csv":
            return "differs", _csv_differences(ta, tb)
        return "differs", _text_differences(ta, tb)
    if suffix == ".parquet":
        import pandas as pd

        fa, fb = pd.read_parquet(a), pd.read_parquet(b)
        if fa.equals(fb):
            return "same text", "the same table (the file's bytes differ)"
        return "differs", _csv_differences(fa.to_csv(index=False), fb.to_csv(index=False))
    return "differs", f"bytes differ ({a.stat().st_size} and {b.stat().st_size} bytes)"


def _files(folder: Path) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}


def compare_all(before: Path, after: Path) -> int:
    """Print the comparison of two ``run`` folders; 0 when every file is the same."""
    differing = 0
    for name in sorted({p.name for p in before.iterdir() if p.is_dir()}
                       | {p.name for p in after.iterdir() if p.is_dir()}):
        a, b = before / name, after / name
        if not (a / "call.json").is_file() or not (b / "call.json").is_file():
            print(f"{name}: run on one side only")
            differing += 1
            continue
        places_a, places_b = _places(a), _places(b)
        ra = json.loads((a / "call.json").read_text(encoding="utf-8"))
        rb = json.loads((b / "call.json").read_text(encoding="utf-8"))
        print(f"{name}: exit {ra['returncode']} / {rb['returncode']}; CPU {ra['cpu_s']} s / "
              f"{rb['cpu_s']} s; wall {ra['wall_s']} s / {rb['wall_s']} s "
              f"(load {ra['load']:.1f} / {rb['load']:.1f})")
        if ra["inputs"] != rb["inputs"]:
            print(f"  inputs read from two places: {ra['inputs']} and {rb['inputs']}")
        differing += ra["returncode"] != rb["returncode"]
        files_a, files_b = _files(a) - _OWN, _files(b) - _OWN
        for only, side in ((files_a - files_b, "before"), (files_b - files_a, "after")):
            for path in sorted(only):
                print(f"  {path}: only {side}")
                differing += 1
        counts = {"same": 0, "same text": 0}
        for path in sorted(files_a & files_b):
            verdict, detail = compare_files(a / path, b / path, places_a, places_b)
            if verdict in counts:
                counts[verdict] += 1
                continue
            differing += 1
            print(f"  {path}: DIFFERS: {detail}")
        print(f"  {counts['same']} file(s) the same byte for byte, {counts['same text']} the "
              "same but for places")
    print(f"{differing} difference(s)" if differing else
          "every file the same (byte for byte, or but for places, dates and times taken)")
    return 1 if differing else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="run every call into a folder")
    run.add_argument("out", type=Path)
    run.add_argument("--code", type=Path, default=ROOT / "src",
                     help="PYTHONPATH of the calls (the tree whose code runs)")
    run.add_argument("--inputs", type=Path, default=ROOT,
                     help="where data/ and examples/ are read (default: this repository)")
    run.add_argument("--only", nargs="*", help="names of the calls to run")
    compare = commands.add_parser("compare", help="compare two folders of run")
    compare.add_argument("before", type=Path)
    compare.add_argument("after", type=Path)
    options = parser.parse_args()
    if options.command == "run":
        return 1 if run_all(options.out, options.code, options.inputs, options.only) else 0
    return compare_all(options.before, options.after)


if __name__ == "__main__":
    sys.exit(main())
