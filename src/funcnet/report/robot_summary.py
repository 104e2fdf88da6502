"""The findings of a robot's page, first: one compact row per axis and the notes they share.

What an engineer asks of each axis of a :class:`~funcnet.inspection.robot.RobotInspection`:
how often it moves and turns, its peak speed, torque (or current) and following error, its lost
motion (or the bound below which the data cannot resolve it), the gear's parts where they are
measured, and anything unusual. Every sentence that explains a cell is a numbered note said
once, with the axes it applies to: a reason shared by several axes is not repeated per row.
No cell holds a file path or "None". Below the robot network, :func:`scope_counts` and
:func:`evidence_sentence` say its edges and their evidence in a sentence.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from funcnet.inspection import TraceInspection
from funcnet.inspection.robot import BETWEEN_AXES, WITHIN_AXIS
from funcnet.report.html import escape
from funcnet.report.inspect_text import lost_motion_cell

__all__ = ["AxisFindings", "axis_findings", "scope_counts", "evidence_sentence"]


@dataclass(frozen=True)
class AxisFindings:
    """The per-axis table and its notes.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per axis; every cell a short string.
    notes : tuple of (str, tuple of int)
        Each note's text and the axes it applies to, in the order the table cites them
        (``notes`` column: their numbers, from 1).
    """

    table: pd.DataFrame
    notes: tuple[tuple[str, tuple[int, ...]], ...]


def _number(value: Any, digits: int = 3) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    return f"{float(value):.{digits}g}"


def _without_paths(text: str, source: str) -> str:
    """A message without the recording's file (as given, and its name alone)."""
    for where in (f"{source}: ", source, Path(source).name):
        if where:
            text = text.replace(where, "the recording")
    return text.replace("the recording the recording", "the recording").strip()


def _general(message: str) -> str:
    """A diagnosis's message as a note several axes can share: the counts the table holds
    left out (``"no reversal (...): 3 in continuous motion ..."`` is the same finding on
    every axis whatever the 3)."""
    found = re.match(r"no reversal \(([^)]*)\)", message)
    if found:
        return (f"no reversal ({found.group(1)}): no motor-side backlash score, which is "
                "calibrated on reversals only")
    if message.startswith("one measured position per joint"):
        # what it measures at each turn is on the axis's page
        return message.split("; ")[0] + "; what each turn shows is on the axis's page"
    return message


def _peak(moves: pd.DataFrame, column: str, scale: float = 1.0) -> str:
    if column not in moves or not len(moves):
        return "—"
    return _number(float(moves[column].max()) * scale)


def _torque_cell(one: TraceInspection) -> str:
    if "peak |AC|" not in one.moves or not len(one.moves):
        return "—"
    info = one.recording.signals.get("AC")
    unit = info.unit if info is not None and info.unit else "A"
    return f"{_peak(one.moves, 'peak |AC|')} {unit}"


def _gear_cell(result: Any, cite: Any, scale: float = 60.0) -> str:
    parts = None if result is None else result.gear_parts
    if parts is None:
        return "—"
    if parts.dead_zone is None:
        if parts.reason:
            cite(f"gear parts not told apart: {parts.reason}")
        return "—"
    return (f"dead zone {_part(parts.dead_zone, parts.dead_zone_low, parts.dead_zone_high, scale)}"
            f", friction {_part(parts.friction, parts.friction_low, parts.friction_high, scale)}")


#: The robot table's columns of lengths: (column without unit, its unit on a rotary axis).
_UNIT_COLUMNS = {"peak speed": "°/s", "peak following error": "arcmin", "lost motion": "arcmin",
                 "gear dead zone, friction": "arcmin"}


def _with_units(rows: list[dict[str, str]], linear: dict[str, bool]) -> pd.DataFrame:
    """The rows as a table: the units in the headers where every axis turns; else each cell
    with its axis's unit (a linear axis's in mm/s and um) and the headers without one."""
    if not any(linear.values()):
        return pd.DataFrame([{(f"{k} [{_UNIT_COLUMNS[k]}]" if k in _UNIT_COLUMNS else k): v
                              for k, v in row.items()} for row in rows])
    shown = []
    for row in rows:
        units = ({"peak speed": "mm/s"} | dict.fromkeys(list(_UNIT_COLUMNS)[1:], "um")
                 if linear.get(row["axis"]) else _UNIT_COLUMNS)
        shown.append({k: (f"{v} {units[k]}" if k in units and v != "—" else v)
                      for k, v in row.items()})
    return pd.DataFrame(shown)


def _part(value: float | None, low: float | None, high: float | None,
          scale: float = 60.0) -> str:
    """A gear part in arcmin (``scale`` 60; um: 1000 on a linear axis): its value, or ``≤`` its
    bound where the interval reaches 0 (a part of a lost motion is never negative)."""
    if value is None:
        return "—"
    if low is not None and high is not None and low <= 0:
        return f"≤ {scale * max(high, 0.0):.2g}"
    return f"{scale * value:.2g}"


def axis_findings(axes: dict[int, TraceInspection], errors: dict[int, str],
                  order: tuple[int, ...], source: str) -> AxisFindings:
    """The per-axis table of a robot's page and its notes (module notes).

    Parameters
    ----------
    axes : dict
        Axis -> its :class:`~funcnet.inspection.TraceInspection`.
    errors : dict
        Axis -> why it could not be inspected.
    order : tuple of int
        The recording's axes, in order.
    source : str
        The recording's file: left out of every message.

    Returns
    -------
    AxisFindings
        Columns: ``axis``, ``moves``, ``direction changes``, ``peak speed [°/s]``,
        ``peak torque or current``, ``peak following error [arcmin]``,
        ``lost motion [arcmin]`` (a value, ``≤`` a bound where not resolved, or —),
        ``gear dead zone, friction [arcmin]``, ``notes``. A robot with a linear axis (positions
        in mm) has these columns without a unit, and each cell states its axis's: a rotary
        axis's as above, a linear one's in mm/s and um.
    """
    from funcnet.robot.units import axis_scale, position_unit

    notes: dict[str, list[int]] = {}
    rows = []
    linear: dict[str, bool] = {}
    for axis in order:
        cited: list[int] = []

        def cite(text: str, axis: int = axis, cited: list[int] = cited) -> None:
            text = _without_paths(text, source).rstrip(".")
            notes.setdefault(text, [])
            if axis not in notes[text]:
                notes[text].append(axis)
            number = list(notes).index(text) + 1
            if number not in cited:
                cited.append(number)

        one = axes.get(axis)
        if one is None:
            cite(f"not inspected: {errors.get(axis, 'no reason given')}")
            rows.append({"axis": str(axis), "moves": "—", "direction changes": "—",
                         "peak speed": "—", "peak torque or current": "—",
                         "peak following error": "—", "lost motion": "—",
                         "gear dead zone, friction": "—",
                         "notes": ", ".join(map(str, sorted(cited)))})
            continue
        scale = axis_scale(position_unit(one.recording.signals))
        linear[str(axis)] = scale.linear
        result = one.backlash
        if result is None:
            cite(f"no backlash diagnosis: {one.backlash_error or 'not asked for'}")
            lost = "—"
        else:
            lost = lost_motion_cell(result.lost_motion, result.lost_motion_high,
                                    scale.coarse_factor)
            if result.lost_motion is None and result.lost_motion_high is not None:
                terms = " and ".join(result.lost_motion_terms) or "error"
                cite(f"lost motion ≤ a bound: below what the estimate resolves (its "
                     f"{terms}); the interval reaches 0")
            elif result.lost_motion is None:
                cite(f"no lost motion: {result.lost_motion_reason or 'not measured'}")
            if result.backlash_score is None:
                cite(_general(result.message))
        gear = _gear_cell(result, cite, scale.coarse_factor)
        networks = len(one.networks)
        if networks < len(one.windows):
            cite(f"{len(one.windows) - networks} of {len(one.windows)} phase windows without "
                 "a network (too short or constant: see the axis's page)")
        if not len(one.moves):
            cite("the axis never moves")
        rows.append({
            "axis": str(axis), "moves": str(len(one.moves)),
            "direction changes": str(len(one.turns) + len(one.turns_across_gaps)),
            "peak speed": _peak(one.moves, "peak speed"),
            "peak torque or current": _torque_cell(one),
            "peak following error": _peak(one.moves, "peak |FE|", scale.coarse_factor),
            "lost motion": lost,
            "gear dead zone, friction": gear,
            "notes": ", ".join(map(str, sorted(cited))),
        })
    return AxisFindings(table=_with_units(rows, linear),
                        notes=tuple((text, tuple(axes_)) for text, axes_ in notes.items()))


def scope_counts(pairs: pd.DataFrame) -> str:
    """How many edges a robot network has, within an axis and between axes, in words."""
    edges = pairs[pairs["kind"].isin(["x->y", "y->x", "bidirectional"])]
    if "degenerate" in edges:
        edges = edges[~edges["degenerate"].astype(bool)]
    within = int((edges["scope"] == WITHIN_AXIS).sum())
    between = int((edges["scope"] == BETWEEN_AXES).sum())
    return (f"{len(edges)} edges of {len(pairs)} pairs: {within} within an axis, {between} "
            "between axes")


def evidence_sentence(pairs: pd.DataFrame, *, intervals: bool = True) -> str:
    """What the evidence says of a robot network's pairs, in one sentence ("" without it);
    ``intervals=False``: the network computed none (the part of a cut segment), so no option
    of the page draws them."""
    if "evidence" not in pairs.columns:
        return ""
    counts = pairs["evidence"].value_counts()
    said = ", ".join(f"{n} {label}" for label, n in counts.items())
    blind = pairs[pairs["evidence"] == "untestable"]
    why = ""
    if len(blind):
        reasons = blind["evidence_reason"].value_counts()
        drawn = "c_diff_low" in blind and not blind["c_diff_low"].isna().all()
        why = (f" Untestable: {reasons.index[0]}" + (" (the most common reason)"
                                                     if len(reasons) > 1 else "")
               + ("." if drawn or not intervals else "; their asymmetry intervals are not "
                  "drawn (--intervals all draws them)."))
    tested = pairs[pairs["evidence"] != "untestable"]  # their own sentence: above
    undrawn = int((tested["c_diff_low"].isna() & ~tested["coupled"].astype(bool)).sum())
    if undrawn and intervals:
        why += (f" The asymmetry intervals of the {undrawn} tested pairs without coupling are "
                "not drawn (--intervals all draws them).")
    return escape(f" Evidence: {said} of {len(pairs)} pairs.{why}")
