"""Node names of a recording of several axes: ``A1.RP``, ``A2.MP``, ...

A file that holds several axes (a MATLAB field with one row per axis) read without choosing one
is one recording whose columns are qualified by their axis: ``A<axis>.<role or name>``, with the
axis counted from 1 as controllers count. The same spelling is used everywhere -- columns, nodes
of a network, ``--signals`` -- and a signal common to all axes keeps its bare name.

Examples
--------
>>> qualified(2, "MP")
'A2.MP'
>>> split_qualified("A2.MP"), split_qualified("time_disc")
((2, 'MP'), (None, 'time_disc'))
>>> axes_of(["A1.RP", "A2.RP", "A1.MP", "time_disc"])
(1, 2)
"""

from __future__ import annotations

import re
from collections.abc import Iterable

__all__ = ["qualified", "split_qualified", "axes_of"]

_QUALIFIED = re.compile(r"^A(?P<axis>[1-9][0-9]*)\.(?P<name>.+)$")


def qualified(axis: int, name: str) -> str:
    """The column name of signal ``name`` of ``axis`` (1-based) in a multi-axis recording."""
    return f"A{axis}.{name}"


def split_qualified(column: str) -> tuple[int | None, str]:
    """``(axis, name)`` of a qualified column; ``(None, column)`` for any other."""
    match = _QUALIFIED.match(column)
    if match is None:
        return None, column
    return int(match["axis"]), match["name"]


def axes_of(columns: Iterable[str]) -> tuple[int, ...]:
    """The axes whose qualified columns are among ``columns``, in increasing order."""
    found = {split_qualified(c)[0] for c in columns}
    return tuple(sorted(a for a in found if a is not None))
