"""Every pairs table of a robot page as JSON, and the cell-by-cell comparison of two such files.

Run from the repository root (``PYTHONPATH`` at the checkout whose code is to be read)::

    python -m benchmarks.robot_pairs dump RECORDING --channels MAP --out FILE.json
    python -m benchmarks.robot_pairs compare BEFORE.json AFTER.json

``dump`` computes what `funcnet inspect RECORDING --channels MAP` computes (the robot network
of each window with its evidence, and each axis's networks per phase, default settings) and
writes every pairs table, keyed by the robot window's label or ``axis N / window label``.
``compare`` joins two dumps on their keys and says, for the keys both hold, whether every cell
is equal (floats bit for bit, NaN equal to NaN), and lists the keys only one holds.
"""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path

import numpy as np


def dump(recording_path: str, channels: str | None, out: Path) -> None:
    """Write the pairs tables of the robot page of ``recording_path`` to ``out``."""
    from funcnet.inspection import inspect_file

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        found = inspect_file(recording_path, channels=channels)
    tables = {f"robot / {label}": net.pairs for label, net in found.networks.items()}
    for axis, one in getattr(found, "axes", {}).items():
        tables.update({f"axis {axis} / {label}": net.pairs for label, net in one.networks.items()})
    # json writes floats by repr, which round-trips every float64 bit for bit (NaN as null)
    payload = {key: table.astype(object).where(table.notna(), None).to_dict(orient="split")
               for key, table in tables.items()}
    out.write_text(json.dumps(payload, default=str))
    print(f"{out}: {len(payload)} pairs tables")


def _same(a: object, b: object) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return (np.isnan(a) and np.isnan(b)) or a == b
    return a == b


def compare(before: Path, after: Path) -> None:
    """Print how the pairs tables of two dumps compare, cell by cell."""
    old, new = json.loads(before.read_text()), json.loads(after.read_text())
    cells = differing = 0
    for key in sorted(old.keys() & new.keys()):
        a, b = old[key], new[key]
        if a["columns"] != b["columns"] or len(a["data"]) != len(b["data"]):
            print(f"{key}: different shape or columns")
            differing += 1
            continue
        for row_a, row_b in zip(a["data"], b["data"], strict=True):
            for x, y in zip(row_a, row_b, strict=True):
                cells += 1
                differing += not _same(x, y)
    print(f"{len(old.keys() & new.keys())} tables in both, {cells} cells compared, "
          f"{differing} differ")
    for key in sorted(old.keys() - new.keys()):
        print(f"only before: {key}")
    for key in sorted(new.keys() - old.keys()):
        print(f"only after: {key}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    one = sub.add_parser("dump")
    one.add_argument("recording")
    one.add_argument("--channels", default=None)
    one.add_argument("--out", type=Path, required=True)
    two = sub.add_parser("compare")
    two.add_argument("before", type=Path)
    two.add_argument("after", type=Path)
    args = parser.parse_args(argv)
    if args.command == "dump":
        dump(args.recording, args.channels, args.out)
    else:
        compare(args.before, args.after)


if __name__ == "__main__":
    main()
