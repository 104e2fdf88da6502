"""The study report: a study's Parquet rows as networks, timelines and tables in HTML.

:func:`write_report` reads a results folder (:func:`funcnet.study.load_results`) and draws, for
each recording and parameter set, the network of every window (:func:`funcnet.plot.plot_network`
on the window's rows) and an edge timeline; then every pairs table, the study, its run and the
provenance.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 3.4
   and 4.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import sys
from pathlib import Path

import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.report.html import (
    PACKAGES,
    Progress,
    escape,
    figure_html,
    mapping_table,
    page,
    pairs_table,
    step,
    table,
)
from funcnet.study import PARAMETER_COLUMNS, load_results, package_versions

__all__ = ["write_report"]

_WINDOW_KEYS = ["recording", "window", "start", "stop"]
_GRID = 24  # networks per figure of a recording


def _slug(text: str) -> str:
    keep = "".join(ch if ch.isalnum() else "-" for ch in text)
    return "-".join(part for part in keep.split("-") if part)[:80] or "x"


def write_report(
    results_dir: str | os.PathLike[str],
    out_dir: str | os.PathLike[str] | None = None,
    *,
    progress: Progress = None,
) -> Path:
    """Write the HTML report of a study's results folder.

    For each recording and parameter set: the networks of its windows (drawn from the rows,
    :func:`funcnet.plot.plot_network` on each window's pairs), an edge timeline when it has
    three windows or more (:func:`funcnet.plot.plot_edge_timeline`), and every window's pairs
    table; then the study, its run counts and failures, and the provenance (versions, input
    hashes, commands, date).

    Parameters
    ----------
    results_dir : path-like
        A folder written by :func:`funcnet.study.run_study` (``rows/*.parquet``,
        ``study.json``).
    out_dir : path-like, optional
        Report folder; ``results_dir/report`` by default.
    progress : callable, optional
        ``progress(done, total, description)``.

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.

    Raises
    ------
    funcnet.errors.StudyError
        When the folder holds no results.
    """
    from matplotlib.figure import Figure

    from funcnet import plot

    results = Path(results_dir)
    out = Path(out_dir) if out_dir is not None else results / "report"
    rows = load_results(results)
    document_path = results / "study.json"
    document = json.loads(document_path.read_text()) if document_path.is_file() else {}
    parameters = [c for c in PARAMETER_COLUMNS.values() if c in rows.columns]
    body = [f"<h1>funcnet study report — {escape(results.resolve().name)}</h1>"]
    groups = list(rows.groupby(["recording", *parameters], sort=False, dropna=False))
    index_rows = []
    sections = []
    for k, (key, group) in enumerate(groups):
        recording = key[0]
        step(progress, k, len(groups), f"report: {recording}")
        setting = dict(zip(parameters, key[1:], strict=True))
        # Degenerate pairs are drawn as edges only where the study kept them.
        policy = setting.get(PARAMETER_COLUMNS.get("degenerate", "degenerate_policy"))
        policy = policy if policy in ("drop", "keep") else "drop"
        windows = list(group.groupby(_WINDOW_KEYS[1:], sort=False))
        windows.sort(key=lambda item: (item[0][1], item[0][2]))
        slug = _slug(f"{k}-{recording}")
        parts = [f'<h2 id="{slug}">{escape(recording)}</h2>',
                 f"<p>parameters: {escape(', '.join(f'{n}={v}' for n, v in setting.items()))}</p>"]
        for start in range(0, len(windows), _GRID):
            chunk = windows[start:start + _GRID]
            cols = min(6, len(chunk))
            fig = Figure(figsize=(2.3 * cols, 2.5 * -(-len(chunk) // cols)), layout="constrained")
            degenerate = False
            for j, ((label, t0, t1), pairs) in enumerate(chunk):
                ax = fig.add_subplot(-(-len(chunk) // cols), cols, j + 1)
                # sliding windows are labelled by their span already
                title = label if str(label).endswith(" s") else f"{label}\n{t0:.2f}–{t1:.2f} s"
                plot.plot_network(pairs, ax, title=title, fontsize=7, legend=False,
                                  degenerate=policy)
                degenerate |= bool(plot.network_edges(pairs, degenerate=policy)
                                   ["degenerate"].any())
            plot.add_network_legend(fig, degenerate=degenerate)
            parts.append(figure_html(out, f"{slug}-networks-{start // _GRID}", fig,
                                      f"{recording}: networks of windows {start + 1}–"
                                      f"{start + len(chunk)} of {len(windows)}"))
        if len(windows) >= 3:
            centred = group.assign(time=(group["start"] + group["stop"]) / 2)
            timeline = plot.plot_edge_timeline(centred)
            parts.append(figure_html(out, f"{slug}-timeline", timeline.figure,
                                      f"{recording}: edge kind and weight per window centre"))
        for (label, t0, t1), pairs in windows:
            parts.append(f"<details><summary>{escape(label)} ({t0:.3f}–{t1:.3f} s)</summary>"
                         f"{pairs_table(pairs)}</details>")
        sections.append("".join(parts))
        index_rows.append({"recording": recording, **setting, "windows": len(windows),
                           "source sha256": group["source_sha256"].iloc[0]
                           if "source_sha256" in group else ""})
    body += ["<h2>Recordings</h2>", table(pd.DataFrame(index_rows)), *sections]
    run = document.get("run", {})
    if run:
        body += ["<h2>Run</h2>", mapping_table({k: v for k, v in run.items()
                                                 if k != "failures"}, "item")]
        if run.get("failures"):
            body += ["<h3>Failed tasks</h3>", table(pd.DataFrame(run["failures"]))]
    if document.get("study"):
        body += ["<h2>Study</h2>",
                 f"<pre>{escape(json.dumps(document['study'], indent=2, default=str))}</pre>"]
    study_provenance = document.get("provenance", {})
    provenance = {
        "report date (UTC)": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "report command": " ".join(sys.argv),
        "study command": " ".join(study_provenance.get("command", [])),
        **{f"version of {k} (study)": v
           for k, v in study_provenance.get("versions", {}).items()},
        **{f"version of {k} (report)": v for k, v in package_versions(PACKAGES).items()},
    }
    inputs = study_provenance.get("inputs") or dict(
        zip(rows["recording"], rows.get("source_sha256", ""), strict=False))
    body += ["<h2>Provenance</h2>", mapping_table(provenance, "item"),
             "<h3>Inputs (SHA-256)</h3>", mapping_table(inputs, "file", "sha256")]
    index = write_text_atomic(out / "index.html", page("funcnet study report", body))
    step(progress, len(groups), len(groups), "report written")
    return index
