"""The trend page of a fleet's history (:func:`funcnet.track.robot_trends`).

``index.html``: per robot the alarms, then per program and axis each figure over time with the
band its healthy history gives it (mean +- 3 spreads), the learning runs in grey, the alarms
marked, every point linked to its run's page where one exists. ``alarms.json`` (robot, axis,
figure, time, run, size, why) and ``runs.json`` (robot, time, program, source, checksum, and
how the time was found). The charts are inline SVG: the page is one file. Every file is written
atomically.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable
from datetime import datetime
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.report.html import escape, mapping_table, page, provenance, table
from funcnet.track.add import REFERENCES
from funcnet.track.detect import DRIFT, LEARN, LEVEL, SPREAD_FLOOR
from funcnet.track.figures import FIGURES
from funcnet.track.trend import Trends, run_records

__all__ = ["write_trends"]

_W, _H, _L, _R, _T, _B = 200, 118, 60, 6, 20, 22
_STYLE = ("<style>body{max-width:1300px}.charts{display:flex;flex-wrap:wrap;gap:4px}"
          ".charts svg{border:1px solid #ddd;background:#fff}.alarm{color:#b00}"
          "h4{margin:.8em 0 .2em}</style>")
#: Points per chart beyond which the points are not drawn one by one (the line stays).
_DOTS = 400


def _seconds(times: pd.Series) -> np.ndarray:
    return np.array([datetime.fromisoformat(t).timestamp() for t in times], dtype=np.float64)


def _scale(lo: float, hi: float, a: float, b: float) -> Callable[[Any], Any]:
    if not hi > lo:  # one value: in the middle
        return lambda v: (a + b) / 2 + 0.0 * np.asarray(v, dtype=np.float64)
    return lambda v: a + (np.asarray(v, dtype=np.float64) - lo) / (hi - lo) * (b - a)


def _link(row: pd.Series, pages: Path | None, out: Path) -> str | None:
    if isinstance(row.get("page"), str) and row["page"]:
        return str(row["page"])
    if pages is not None:
        candidate = pages / Path(str(row["source"])).name / "index.html"
        if candidate.is_file():
            return os.path.relpath(candidate, out)
    return None


def _digits(top: float, bottom: float) -> int:
    """Significant digits that tell ``top`` from ``bottom`` (3 at least, 8 at most)."""
    if top == bottom or not math.isfinite(top - bottom):
        return 4
    return int(min(7, max(3, math.ceil(math.log10(max(abs(top), abs(bottom)) / (top - bottom)))
                          + 2)))


def _chart(series: pd.DataFrame, figure: str, links: dict[int, str | None], title: str) -> str:
    """One figure of one axis over time: an inline SVG (module notes)."""
    _, unit = FIGURES.get(figure, (figure, ""))
    label = title
    x = _seconds(series["time"])
    y = series["value"].to_numpy(dtype=np.float64)
    lo_band = series["low"].to_numpy(dtype=np.float64)
    hi_band = series["high"].to_numpy(dtype=np.float64)
    values = np.r_[y, lo_band[np.isfinite(lo_band)], hi_band[np.isfinite(hi_band)]]
    low, high = float(np.nanmin(values)), float(np.nanmax(values))
    # never narrower than the detector's spread floor: a figure the program fixes stays flat
    least = 6 * SPREAD_FLOOR * max(abs(low), abs(high))
    if high - low < least:
        low, high = (low + high - least) / 2, (low + high + least) / 2
    pad = (high - low) * 0.08 or abs(high) * 0.05 or 1.0
    sx = _scale(float(x.min()), float(x.max()), _L + 6, _W - _R - 6)
    sy = _scale(low - pad, high + pad, _H - _B, _T)
    parts = [f'<svg width="{_W}" height="{_H}" role="img"><title>{escape(label)}</title>',
             f'<text x="4" y="13" font-size="10" font-weight="bold">{escape(title)}</text>']
    judged = np.isfinite(lo_band)
    if judged.any():
        top = " ".join(f"{a:.1f},{b:.1f}" for a, b in zip(sx(x[judged]), sy(hi_band[judged]),
                                                          strict=True))
        bottom = " ".join(f"{a:.1f},{b:.1f}" for a, b in zip(sx(x[judged][::-1]),
                                                             sy(lo_band[judged][::-1]),
                                                             strict=True))
        parts.append(f'<polygon points="{top} {bottom}" fill="#cfe0f5" stroke="none"/>')
    line = " ".join(f"{a:.1f},{b:.1f}" for a, b in zip(sx(x), sy(y), strict=True))
    parts.append(f'<polyline points="{line}" fill="none" stroke="#555" stroke-width="1"/>')
    highest, lowest = float(np.nanmax(y)), float(np.nanmin(y))
    digits = _digits(highest, lowest)
    ticks = {highest, lowest}
    if abs(float(sy(highest)) - float(sy(lowest))) < 14:  # as good as flat: one label
        ticks, digits = {(highest + lowest) / 2}, 4
    for tick in ticks:
        parts.append(f'<line x1="{_L - 2}" x2="{_L + 2}" y1="{float(sy(tick)):.1f}" '
                     f'y2="{float(sy(tick)):.1f}" stroke="#333"/>'
                     f'<text x="{_L - 4}" y="{float(sy(tick)) + 3:.1f}" font-size="9" '
                     f'text-anchor="end">{tick:.{digits}g}</text>')
    ends = ((x.min(), "start"), (x.max(), "end")) if x.max() > x.min() else ((x.min(), "middle"),)
    for at, anchor in ends:
        day = datetime.fromtimestamp(float(at)).strftime("%Y-%m-%d")
        parts.append(f'<text x="{float(sx(at)):.1f}" y="{_H - 8}" font-size="9" '
                     f'text-anchor="{anchor}">{day}</text>')
    if len(series) <= _DOTS or series["alarm"].any():
        parts += _dots(series, sx(x), sy(y), links, unit, dense=len(series) > _DOTS)
    parts.append("</svg>")
    return "".join(parts)


def _dots(series: pd.DataFrame, xs: np.ndarray, ys: np.ndarray,
          links: dict[int, str | None], unit: str, *, dense: bool) -> list[str]:
    out = []
    columns = [series[c].tolist() for c in ("alarm", "centre", "time", "source", "value",
                                            "size", "run")]
    for a, b, alarm, centre, when, source, value, size, run in zip(xs, ys, *columns,
                                                                   strict=True):
        if dense and not alarm:
            continue
        colour = "#c00" if alarm else ("#999" if not math.isfinite(centre) else "#245")
        tip = (f"{when} {os.path.basename(str(source))}: {value:.4g} {unit}"
               + (f", {size:+.1f} spreads" if math.isfinite(size) else ", learning")
               + (" ALARM" if alarm else ""))
        dot = (f'<circle cx="{a:.1f}" cy="{b:.1f}" r="{4.5 if alarm else 2.5}" fill="{colour}">'
               f"<title>{escape(tip)}</title></circle>")
        if alarm:
            dot += (f'<circle cx="{a:.1f}" cy="{b:.1f}" r="8" fill="none" stroke="#c00" '
                    'stroke-width="1.5"/>')
        link = links.get(int(run))
        out.append(f'<a href="{escape(link)}">{dot}</a>' if link else dot)
    return out


_ORDER = ("departure", *(f for f in FIGURES if f != "departure"))


def _runs_table(of_program: pd.DataFrame, runs: pd.DataFrame) -> str:
    """The program's runs: time, file, largest departure and its axis, alarms."""
    departure = of_program[of_program["figure"] == "departure"]
    top = departure.loc[departure.groupby("run")["value"].idxmax()].set_index("run")
    alarms = of_program.groupby("run")["alarm"].sum()
    mine = runs[runs["id"].isin(alarms.index)].sort_values(["time", "id"])
    largest = [f"{top.at[i, 'value']:.1f} (axis {int(top.at[i, 'axis'])})" if i in top.index
               else "first run: none" for i in mine["id"]]
    frame = pd.DataFrame({"time": mine["time"].to_numpy(),
                          "run": [Path(str(s)).name for s in mine["source"]],
                          "time from": mine["time_from"].to_numpy(),
                          "largest departure [spreads]": largest,
                          "alarms": [int(alarms[i]) for i in mine["id"]]})
    shown = table(frame, classes={"alarms": lambda v: "no" if v else ""})
    if len(frame) <= 12:
        return shown
    return f"<details><summary>The program's {len(frame)} runs</summary>{shown}</details>"


def _program_section(program: str, of_program: pd.DataFrame, runs: pd.DataFrame,
                     links: dict[int, str | None]) -> list[str]:
    count = int(runs["program"].eq(program).sum())
    parts = [f"<h3>Program {escape(program)} ({count} run(s))</h3>",
             _runs_table(of_program, runs)]
    if count <= LEARN:
        parts.append(f'<p class="note">The first {LEARN} runs of a program only learn: no '
                     f"alarm can be raised yet ({count} so far); the charts show the values "
                     "alone, without a band.</p>")
    units: dict[str, str] = {}
    for text in runs.loc[runs["program"] == program, "units"].dropna():
        units.update(json.loads(text))
    axes = sorted(of_program["axis"].unique())
    one: list[str] = []  # one axis: every figure side by side
    for figure in _ORDER:
        of_figure = of_program[of_program["figure"] == figure]
        if of_figure.empty:
            continue
        label, unit = FIGURES[figure]
        unit = units.get(figure, unit)
        if len(axes) == 1:
            one.append(_chart(of_figure, figure, links, f"{figure} [{unit}]"))
            continue
        charts = [_chart(of_axis, figure, links, f"axis {int(axis)} [{unit}]")
                  for axis, of_axis in of_figure.groupby("axis")]  # in time order (_judge)
        parts.append(f"<h4>{escape(label)}</h4><div class=\"charts\">{''.join(charts)}</div>")
    if one:
        parts.append(f"<h4>Axis {int(axes[0])}</h4><div class=\"charts\">{''.join(one)}</div>")
    return parts


def _robot_section(trends: Trends, robot: str, pages: Path | None, out: Path) -> str:
    runs = trends.runs[trends.runs["robot"] == robot]
    links = {int(r["id"]): _link(r, pages, out) for _, r in runs.iterrows()} \
        if pages is not None or runs["page"].notna().any() else {}
    points = trends.points[trends.points["robot"] == robot]
    alarms = [a for a in trends.alarms if a["robot"] == robot]
    parts = [f'<h2 id="{escape(robot)}">Robot {escape(robot)}</h2>',
             f"<p>{len(runs)} run(s), {runs['program'].nunique()} program(s), "
             f"<b class=\"{'alarm' if alarms else ''}\">{len(alarms)} alarm(s)</b>.</p>"]
    if alarms:
        frame = pd.DataFrame(alarms)[["time", "axis", "figure", "size", "why", "run"]]
        parts.append(table(frame))
    for program, of_program in points.groupby("program", sort=False):
        parts += _program_section(str(program), of_program, runs, links)
    return "\n".join(parts)


def write_trends(trends: Trends, out_dir: str | os.PathLike[str], *,
                 pages: str | os.PathLike[str] | None = None) -> Path:
    """Write ``index.html``, ``alarms.json`` and ``runs.json`` (module notes).

    Parameters
    ----------
    trends : Trends
    out_dir : path-like
    pages : path-like, optional
        A folder of run pages: a run links to ``PAGES/<its file name>/index.html`` when that
        exists (as ``funcnet inspect RUN -o PAGES/<name>`` writes it), unless the store names
        its page.

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    write_text_atomic(out / "alarms.json", json.dumps(list(trends.alarms), indent=2) + "\n")
    write_text_atomic(out / "runs.json", json.dumps(run_records(trends.runs), indent=2) + "\n")
    folder = Path(pages) if pages is not None else None
    robots = sorted(trends.runs["robot"].astype(str).unique())
    how = ("Each figure is judged within its program, run after run, by a self-starting CUSUM "
           f"(k = {DRIFT:g}, h = {LEVEL:g}) against the healthy history of the same figure: "
           f"the first {LEARN} runs of a program only learn; the band is the healthy mean "
           "+- 3 spreads; an alarm (red ring) stops the history from growing. About one false "
           "alarm in 500 runs per steady normal figure (docs/validation/track.md). The "
           f"departure is measured against the program's first {REFERENCES} runs, and judged on "
           f"a log scale once it has all {REFERENCES}: from the program's {REFERENCES + 1}th run "
           f"on, so its first alarm can come on the {REFERENCES + LEARN + 1}th.")
    times = trends.runs["time_from"].value_counts().to_dict()
    body = [f"<h1>Health over time: {', '.join(map(escape, robots))}</h1>",
            _STYLE, f"<p>{escape(how)}</p>",
            f"<p>Run times: {escape(', '.join(f'{n} {k}' for k, n in times.items()))} "
            "(given: --time; file: the file's own start time; mtime: the file's modification "
            "time).</p>"]
    body += [_robot_section(trends, robot, folder, out) for robot in robots]
    body.append("<h2>Provenance</h2>" + mapping_table(provenance()))
    write_text_atomic(out / "index.html", page("funcnet track", body))
    return out / "index.html"
