"""A robot's history read back: every figure's series per program and axis, judged.

:func:`robot_trends` reads a robot's runs and figures from the store and runs the detector
(:func:`funcnet.track.detect.detect_changes`) on each figure of each axis, within each
program, in time order. Its :class:`Trends` hold one row per run, axis and figure (value, the
healthy history's centre and spread, size in spreads, CUSUM, alarm) and the alarms as plain
records.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from funcnet.track import store as kept
from funcnet.track.add import REFERENCE_COUNT, REFERENCES
from funcnet.track.detect import LEVEL, detect_changes
from funcnet.track.figures import FIGURES

__all__ = ["Trends", "robot_trends", "run_records"]


@dataclass(frozen=True)
class Trends:
    """A robot's (or every robot's) runs, figures and alarms.

    Attributes
    ----------
    runs : DataFrame
        Every run kept: id, robot, time, time_from, program, source, checksum, page.
    points : DataFrame
        One row per run, axis and figure read: run, robot, program, axis, figure, time,
        value, centre, spread, size, cusum, low, high (the band: centre +- 3 spreads, on the
        figure's scale), alarm. A departure is judged on a log scale (its centre and spread
        are of its logarithm), and only where measured against all its references.
    alarms : tuple of dict
        ``robot, axis, figure, time, run, size, why``, in time order.
    """

    runs: pd.DataFrame = field(repr=False)
    points: pd.DataFrame = field(repr=False)
    alarms: tuple[dict[str, object], ...]


def _why(row: pd.Series, cusum: float) -> str:
    label, unit = FIGURES.get(str(row["figure"]), (str(row["figure"]), ""))
    side = "above" if row["size"] > 0 else "below"
    if row["figure"] == "departure":
        return (f"{label} {row['value']:.4g} {unit}, {abs(row['size']):.1f} spreads {side} the "
                f"healthy history on a log scale (its typical value {np.exp(row['centre']):.3g};"
                f" CUSUM {cusum:.1f} > {LEVEL:g})")
    return (f"{label} {row['value']:.4g} {unit}, {abs(row['size']):.1f} spreads {side} the "
            f"healthy mean {row['centre']:.4g} (spread {row['spread']:.3g}; CUSUM "
            f"{cusum:.1f} > {LEVEL:g})")


def _judged_values(points: pd.DataFrame, counts: pd.DataFrame) -> np.ndarray:
    """The values the detector reads: a departure on a log scale, and only where it was
    measured against all :data:`REFERENCES` (fewer references give another spread)."""
    values = points["value"].to_numpy(dtype=np.float64).copy()
    departure = (points["figure"] == "departure").to_numpy()
    if departure.any():
        full = points.merge(counts, on=["run", "axis"], how="left")["references"]
        usable = departure & (full.to_numpy(dtype=np.float64) >= REFERENCES) & (values > 0)
        values[departure] = np.where(usable[departure], np.log(np.where(
            usable[departure], values[departure], 1.0)), np.nan)
    return values


def _judge(points: pd.DataFrame, counts: pd.DataFrame) -> pd.DataFrame:
    """The detector over every series of ``points``: one sort, then each series a slice."""
    keys = ["robot", "program", "axis", "figure"]
    points = points.sort_values([*keys, "time", "run"], ignore_index=True)
    columns = {name: np.full(len(points), np.nan) for name in ("centre", "spread", "size",
                                                               "cusum")}
    alarm = np.zeros(len(points), dtype=bool)
    values = _judged_values(points, counts)
    codes = points.groupby(keys, sort=False).ngroup().to_numpy()
    edges = np.r_[0, np.flatnonzero(np.diff(codes)) + 1, len(points)]
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        found = detect_changes(values[a:b])
        for name, column in columns.items():
            column[a:b] = getattr(found, name)
        alarm[a:b] = found.alarm
    low, high = columns["centre"] - 3 * columns["spread"], columns["centre"] + 3 * columns["spread"]
    log = (points["figure"] == "departure").to_numpy()
    low[log], high[log] = np.exp(low[log]), np.exp(high[log])
    return points.assign(**columns, low=low, high=high, alarm=alarm)


def robot_trends(store: str | os.PathLike[str], robot: str | None = None) -> Trends:
    """The history of ``robot`` (every robot: None), judged (module notes).

    Raises
    ------
    ParameterError
        No such store, or no run of ``robot`` in it.
    """
    from funcnet.errors import ParameterError

    runs = kept.read_runs(store, robot)
    if robot is not None and runs.empty:
        raise ParameterError.of("robot", f"{robot!r}: no run of it in {os.fspath(store)}")
    figures = kept.read_figures(store, robot)
    columns = ["id", "robot", "program", "time", "source"]
    points = figures.merge(runs[columns], left_on="run", right_on="id").drop(columns="id")
    counts = points.loc[points["figure"] == REFERENCE_COUNT, ["run", "axis", "value"]].rename(
        columns={"value": "references"})
    points = points[points["figure"].isin(list(FIGURES))]
    points = _judge(points.dropna(subset=["value"]), counts)
    alarms = []
    for _, row in points[points["alarm"]].sort_values(["time", "axis"]).iterrows():
        alarms.append({"robot": str(row["robot"]), "axis": int(row["axis"]),
                       "figure": str(row["figure"]), "time": str(row["time"]),
                       "run": str(row["source"]), "size": round(float(row["size"]), 2),
                       "why": _why(row, float(row["cusum"]))})
    return Trends(runs, points, tuple(alarms))


def run_records(runs: pd.DataFrame) -> list[dict[str, object]]:
    """``runs.json``'s records: robot, time, program, source, checksum (and how the time was
    found)."""
    return [{"robot": str(r.robot), "time": str(r.time), "time_from": str(r.time_from),
             "program": str(r.program), "source": str(r.source), "checksum": str(r.checksum)}
            for r in runs.itertuples()]

