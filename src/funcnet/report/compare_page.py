"""The page and the JSON of a comparison (:func:`funcnet.comparison.compare_runs`).

``index.html``: what was compared, the intervals where RUN changed (the reading that carries
them said), per axis RUN's residuals over the references' band with the intervals shaded, and
per phase of the program the networks' measures of the references and of RUN side by side,
the pairs beyond the references' spread marked. ``changes.json``: the same numbers. Every file
is written atomically (:mod:`funcnet.report.html`).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.comparison.compare import RESIDUAL_NAMES, Comparison
from funcnet.comparison.intervals import Interval
from funcnet.comparison.networks import phase_summary
from funcnet.report.html import (
    contents,
    escape,
    figure_html,
    mapping_table,
    page,
    provenance,
    table as html_table,
)

__all__ = ["write_comparison", "changes", "CARRIED_BY"]

#: What the page says of the readings (docs/guide/compare.md has the comparison with the sensor).
CARRIED_BY = {
    "residuals": "The intervals come from the residuals (current residual AC - RC and "
                 "following error RP - AP) against the references' band: measured against a "
                 "force sensor's record of nine pushes on a UR5 (docs/guide/compare.md) they "
                 "found all nine, with two false intervals in the run's once-only first move.",
    "networks": "The intervals come from the functional networks' measures over sliding "
                "windows.",
}
_NETWORKS_NOTE = ("The networks' reading (C/T differences and coupling over sliding windows) is "
                  "shown beside it, not used for the intervals: against the force sensor it "
                  "found the same pushes and nothing the residuals missed, and its 1 s windows "
                  "marked half of the run as changed (docs/guide/compare.md).")


def _interval_rows(intervals: tuple[Interval, ...]) -> pd.DataFrame:
    rows = []
    for i in intervals:
        top = i.differences[0]
        rows.append({"start [s]": i.start, "stop [s]": i.stop,
                     "axes": ", ".join(map(str, i.axes)), "signals": ", ".join(i.signals),
                     "size [spreads]": i.size,
                     "largest difference": f"{top.signal} axis {top.axis}: {top.value:+.4g} "
                                           f"{top.unit or '(unit unknown)'}"})
    return pd.DataFrame(rows)


def changes(comparison: Comparison) -> dict[str, Any]:
    """The comparison as the JSON document ``changes.json`` holds."""
    c = comparison
    return {
        "run": c.run,
        "references": list(c.references),
        "compared": {"fraction": round(c.compared, 4), "seconds": c.compared_seconds,
                     "duration": round(float(c.times.size * (c.times[1] - c.times[0])), 6)
                     if c.times.size > 1 else 0.0},
        "coverage": {ref: round(share, 4) for ref, share in
                     zip(c.references, c.coverage, strict=True)},
        "threshold": c.threshold,
        "spread": "within one run (one reference: across its cycles)" if c.within_run
        else "across the references' runs and cycles",
        "readings": list(c.readings),
        "carried_by": " ".join(CARRIED_BY[r] for r in c.readings),
        "units": c.units,
        "intervals": [i.as_dict() for i in c.intervals],
        "residual_intervals": [i.as_dict() for i in c.residual_intervals],
        "network_intervals": [i.as_dict() for i in c.network_intervals],
        "changed_seconds": c.changed_seconds,
        "notes": list(c.notes),
    }


def _shade(ax: Any, intervals: tuple[Interval, ...], axis: int | None) -> None:
    for i in intervals:
        if axis is None or axis in i.axes:
            ax.axvspan(i.start, i.stop, color="#d62728", alpha=0.18, lw=0)


def _axis_figure(c: Comparison, axis: int, label: str) -> Any:
    from matplotlib.figure import Figure

    names = [s for s in RESIDUAL_NAMES if (s, axis) in c.bands]
    fig = Figure(figsize=(11.0, 1.2 + 2.0 * len(names)), layout="constrained")
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name in zip(axes, names, strict=True):
        b = c.bands[(name, axis)]
        low, high = b.centre - c.threshold * b.spread, b.centre + c.threshold * b.spread
        ax.fill_between(c.times, low, high, color="0.82", lw=0,
                        label=f"references' band (centre ± {c.threshold:g} spreads)")
        ax.plot(c.times, b.centre, color="0.45", lw=0.8, label="references' centre")
        ax.plot(c.times, b.run, color="#1f77b4", lw=0.8, label="RUN")
        _shade(ax, c.intervals, axis)
        unit = c.units.get(name) or "unit unknown"
        ax.set_ylabel(f"{name} [{unit}]", fontsize=9)
        ax.set_title(f"{label}: {RESIDUAL_NAMES[name]}", fontsize=10, loc="left")
        ax.tick_params(labelsize=9)
    axes[0].legend(fontsize=9, loc="upper right", ncol=3)
    axes[-1].set_xlabel("RUN's time [s] (red: intervals that name this axis)", fontsize=9)
    return fig


def _phase_table(c: Comparison, axis: int) -> str:
    if c.networks is None or c.networks.starts.size == 0:
        return "<p>No network windows.</p>"
    frame = phase_summary(c.networks, c.phases, threshold=c.threshold)
    if frame.empty or not (frame["axis"] == axis).any():
        return "<p>No network window lies in a move.</p>"
    frame = frame[frame["axis"] == axis].drop(columns="axis").rename(
        columns={"start": "start [s]", "stop": "stop [s]", "beyond": "beyond the spread"})
    frame["beyond the spread"] = frame["beyond the spread"].replace("", "-")
    return html_table(frame, classes={"beyond the spread": lambda v: "no" if v != "-" else ""})


def write_comparison(
    comparison: Comparison,
    out_dir: str | os.PathLike[str],
    *,
    axis_label: Callable[[int], str] | None = None,
) -> Path:
    """Write ``index.html`` (with ``figures/``) and ``changes.json`` of a comparison.

    Parameters
    ----------
    comparison : Comparison
    out_dir : path-like
    axis_label : callable, optional
        ``axis -> "axis 2 (shoulder)"``; default ``"axis N"``.

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.
    """
    c = comparison
    out = Path(out_dir)
    label = axis_label or (lambda a: f"axis {a}")
    document = changes(c)
    write_text_atomic(out / "changes.json", json.dumps(document, indent=2) + "\n")
    axes = sorted({a for _, a in c.bands})
    n_refs = len(c.references)
    spread = ("<p class=\"note\"><b>The band is estimated with one reference</b>: its spread is "
              "that of the reference's cycles, within one run. What differs between runs "
              "(another day, warm-up, payload) is not in it, so the band is narrower than "
              "that of several runs and more of RUN reads as changed; give a second reference "
              "to learn how runs differ.</p>") if c.within_run else (
        f"<p>The band's spread is learnt from {n_refs} references, across their runs and "
        "cycles, per signal, per axis and along the program.</p>")
    summary = (
        f"<p>RUN <code>{escape(c.run)}</code> against {n_refs} reference(s): "
        + ", ".join(f"<code>{escape(r)}</code> ({s:.0%} of RUN matched)"
                    for r, s in zip(c.references, c.coverage, strict=True))
        + f". Aligned on the position set-points of every axis, cycle by cycle: "
        f"<b>{c.compared_seconds:g} s of RUN's {document['compared']['duration']:g} s "
        f"({c.compared:.0%}) compared</b>; no interval lies where no reference covers RUN.</p>"
        f"<p class=\"verdict\"><b>{len(c.intervals)} interval(s)</b> where RUN departs beyond "
        f"{c.threshold:g} times the references' spread, {c.changed_seconds:g} s in all. "
        f"{escape(' '.join(CARRIED_BY[r] for r in c.readings))}</p>"
        + spread
        + ("<ul>" + "".join(f"<li>{escape(n)}</li>" for n in c.notes) + "</ul>"
           if c.notes else ""))
    intervals_html = (html_table(_interval_rows(c.intervals)) if c.intervals
                      else "<p>None: RUN stays within the references' band.</p>")
    figures = [figure_html(out, f"axis{a}", _axis_figure(c, a, label(a)),
                           f"{label(a)}: RUN's residuals over the references' band; intervals "
                           "shaded") for a in axes]
    network_html = ""
    if c.networks is not None:
        other = "networks" not in c.readings
        network_html = (
            (f"<p>{escape(_NETWORKS_NOTE)}</p>" if other else "")
            + f"<p>Windows of {c.networks.window:g} s every {c.networks.step:g} s, nodes RC, "
            "AC and FE = RP - AP per axis; per phase of the program the references' mean and "
            "RUN's, and the measures of a pair that move beyond the references' spread "
            f"(largest departure in spreads). {c.networks.missing} window(s) without a "
            "network (a constant node, or no reference window).</p>"
            + (f"<h3>The networks' own intervals ({len(c.network_intervals)})</h3>"
               + (html_table(_interval_rows(c.network_intervals)) if c.network_intervals
                  else "<p>None.</p>") if other else "")
            + "".join(f"<h3>{escape(label(a))}</h3>{_phase_table(c, a)}"
                      for a in axes))
    sections = [("summary", "Summary"), ("intervals", "Intervals"), ("axes", "Per axis"),
                ("networks", "Networks per phase"), ("provenance", "Provenance")]
    body = [
        f"<h1>What changed, and when — {escape(Path(c.run).name)}</h1>",
        f"<section id=\"summary\"><h2>Summary</h2>{summary}</section>",
        contents(sections),
        f"<section id=\"intervals\"><h2>Intervals</h2>{intervals_html}</section>",
        "<section id=\"axes\"><h2>Per axis</h2>", *figures, "</section>",
        f"<section id=\"networks\"><h2>Networks per phase</h2>{network_html}</section>",
        "<section id=\"provenance\"><h2>Provenance</h2>",
        mapping_table(provenance({"run": c.run, "references": ", ".join(c.references)}),
                      "item"), "</section>",
    ]
    return write_text_atomic(out / "index.html",
                             page(f"funcnet compare — {Path(c.run).name}", body))
