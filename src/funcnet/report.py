"""Static HTML reports: the paper's analyses on the simulated plan, and a study's results.

Both reports are one ``index.html`` with PNG figures beside it in ``figures/`` and nothing
loaded from elsewhere (no CDN, no script, no web font), so the folder can be archived, mailed or
opened offline. Every file is written atomically (:mod:`funcnet._io`): a report folder never
holds a half-written figure or page.

- :func:`build_demo_report` runs :func:`funcnet.findings.run_paper_analyses` on a plan of
  simulated trials and writes the paper's Figures 1, 2, 5, 9, 10 and 11 (from funcnet's own
  computations), an edge timeline and recurrence plots beyond the paper, the table of the
  paper's findings (reproduced yes / partly / no / not evaluable, with counts), every network's
  pairs table, the parameters and the provenance (versions, SHA-256 of every input, command
  line, date).
- :func:`write_report` does the same for the Parquet rows of a study (:mod:`funcnet.study`):
  networks per window, an edge timeline per recording, tables and provenance.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.
"""

from __future__ import annotations

import datetime as _dt
import html
import json
import os
import sys
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from funcnet._io import atomic_path, write_text_atomic
from funcnet.study import package_versions

__all__ = ["build_demo_report", "write_report", "save_figure"]

Progress = Callable[..., None] | None

# Columns of a pairs table shown in the report, in this order (those present).
_PAIR_COLUMNS = ("x", "y", "kind", "weight", "c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff",
                 "eps_x", "eps_y", "eps_xy", "rr_x", "rr_y", "cr", "eps_ordered",
                 "rate_exceeded")
_PACKAGES = ("numpy", "numba", "scipy", "pandas", "pyarrow", "networkx", "matplotlib")

_STYLE = """
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;max-width:1200px;margin:2em auto;
padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;font-size:.82em;margin:.5em 0;max-width:100%}
th,td{border:1px solid #ccc;padding:2px 6px;text-align:left;vertical-align:top;
overflow-wrap:anywhere}
td.hash{font-family:ui-monospace,monospace;word-break:break-all;min-width:12ch}
pre{white-space:pre-wrap;overflow-wrap:anywhere}
th{background:#f3f3f3}td.num{text-align:right;font-variant-numeric:tabular-nums}
figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #eee}
figcaption{font-size:.88em;color:#444}
.yes{background:#d9f2d9}.partly{background:#fff2c2}.no{background:#f8d4d4}.na{background:#e8e8f4}
.ne{background:#e6e6e6;font-style:italic}
details{margin:.3em 0}summary{cursor:pointer}code{font-size:.9em}
.note{background:#f6f6f6;border-left:4px solid #999;padding:.5em 1em}
"""


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: int = 100) -> Path:
    """Save a matplotlib figure as PNG, atomically.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        Target file (``.png``).
    dpi : int
        Resolution.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return Path(path)


def _esc(value: Any) -> str:
    return html.escape(str(value), quote=True)


def _format(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _table(frame: pd.DataFrame, *, classes: Mapping[str, Callable[[Any], str]] | None = None
           ) -> str:
    """A small HTML table (escaped), numbers right-aligned, hashes (``*sha256*``) wrapped."""
    classes = classes or {}
    head = "".join(f"<th>{_esc(c)}</th>" for c in frame.columns)
    rows = []
    for record in frame.itertuples(index=False):
        cells = []
        for column, value in zip(frame.columns, record, strict=True):
            if column in classes:
                css = classes[column](value)
            elif "sha256" in str(column):  # a long hash wraps instead of widening the page
                css = "hash"
            else:
                css = ("num" if isinstance(value, int | float) and not isinstance(value, bool)
                       else "")
            cells.append(f'<td class="{css}">{_esc(_format(value))}</td>' if css
                         else f"<td>{_esc(_format(value))}</td>")
        rows.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>"


def _mapping_table(mapping: Mapping[str, Any], key: str = "name", value: str = "value") -> str:
    return _table(pd.DataFrame({key: list(mapping), value: [str(v) for v in mapping.values()]}))


def _pairs_table(pairs: pd.DataFrame) -> str:
    return _table(pairs[[c for c in _PAIR_COLUMNS if c in pairs.columns]])


def _figure_html(out_dir: Path, name: str, fig: Any, caption: str) -> str:
    save_figure(fig, out_dir / "figures" / f"{name}.png")
    return (f'<figure id="{_esc(name)}"><img src="figures/{_esc(name)}.png" '
            f'alt="{_esc(caption)}"><figcaption>{_esc(caption)}</figcaption></figure>')


def _page(title: str, body: Iterable[str]) -> str:
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{_esc(title)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(body) + "</body></html>\n")


def _step(progress: Progress, done: int, total: int, description: str) -> None:
    if progress is not None:
        progress(done, total, description)


# --------------------------------------------------------------------------------------------
# the demo report


def _verdict_class(value: Any) -> str:
    classes = {"yes": "yes", "partly": "partly", "no": "no", "not evaluable": "ne"}
    return classes.get(str(value), "na")


def _findings_html(findings: Sequence[Any]) -> str:
    frame = pd.DataFrame([{"finding": f.id, "section": f.section, "statement": f.statement,
                           "reproduced": f.reproduced, "evidence": f.evidence}
                          for f in findings],
                         columns=["finding", "section", "statement", "reproduced", "evidence"])
    counts = frame["reproduced"].value_counts() if len(frame) else pd.Series(dtype=int)
    paper = frame[frame["reproduced"] != "n/a"] if len(frame) else frame
    summary = (f"<p>Of the paper's {len(paper)} findings checked here, the simulated plan "
               f"reproduces <b>{counts.get('yes', 0)}</b> fully, <b>{counts.get('partly', 0)}"
               f"</b> partly, <b>{counts.get('no', 0)}</b> not at all, <b>"
               f"{counts.get('not evaluable', 0)}</b> not evaluable (none of their claimed "
               "relations could be measured).</p>")
    missed = paper[paper["reproduced"] != "yes"] if len(paper) else paper
    verdicts = {"partly": "reproduces this only in part",
                "no": "does not reproduce this",
                "not evaluable": "cannot test this: nothing could be measured"}
    seen = {f.id: f.edges_seen for f in findings}

    def shown(edges: Sequence[str], limit: int = 12) -> str:
        text = "; ".join(edges[:limit]) + ("; …" if len(edges) > limit else "")
        return f" What the simulated networks show: {text}." if edges else ""

    plain = "".join(
        f"<li><b>{_esc(r.finding)}</b> — the paper: “{_esc(r.statement)}” The simulation "
        f"{verdicts[r.reproduced]} ({_esc(r.evidence)}).{_esc(shown(seen[r.finding]))}</li>"
        for r in missed.itertuples(index=False))
    details = "".join(
        f"<details><summary>{_esc(f.id)}: relations seen</summary><p><b>claimed:</b> "
        f"{_esc('; '.join(f.expected)) or '—'}</p><p><b>seen:</b> "
        f"{_esc('; '.join(f.edges_seen)) or '—'}</p></details>" for f in findings)
    shown = frame.rename(columns={"statement": "the paper says"})
    return (summary + _table(shown, classes={"reproduced": _verdict_class})
            + (f"<h3>Where the simulation does not (or cannot) reproduce the paper</h3>"
               f"<ul>{plain}</ul>"
               if plain else "") + details)


def _network_tables(title: str, analyses: Mapping[str, Any]) -> str:
    parts = [f"<h3>{_esc(title)}</h3>"]
    for trial in analyses.values():
        inner = []
        for key, net in trial.networks.items():
            window = trial.windows.get(key)
            name = window.label if window is not None else key
            span = (f" ({float(window.start):.3f}–{float(window.stop):.3f} s)"
                    if window is not None else "")
            if key in trial.dropped:
                span += f" — constant, left out: {', '.join(trial.dropped[key])}"
            if net is None:
                inner.append(f"<p><b>{_esc(name)}</b>{_esc(span)}: not computed — "
                             f"{_esc(trial.errors.get(key, ''))}</p>")
            else:
                inner.append(f"<details><summary>{_esc(name)}{_esc(span)}</summary>"
                             f"{_pairs_table(net.pairs)}</details>")
        if "windows" in trial.errors:
            inner.append(f"<p>no windows: {_esc(trial.errors['windows'])}</p>")
        parts.append(f"<details><summary><b>{_esc(trial.trial)}</b> — {len(trial.networks)} "
                     f"windows</summary>{''.join(inner)}</details>")
    return "".join(parts)


def _demo_figures(analyses: Any, out_dir: Path, progress: Progress) -> list[str]:
    from matplotlib.figure import Figure

    from funcnet import plot
    from funcnet.preprocess import normalize

    parts: list[str] = []
    steps = 9

    def add(k: int, name: str, make: Callable[[], Any], caption: str) -> None:
        _step(progress, k, steps, f"figure: {name}")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            made = make()
        fig = made if isinstance(made, Figure) else made.figure
        # The computation's warnings belong to the figure they concern, not to the console.
        notes = sorted({f"{w.category.__name__}: {w.message}" for w in caught})
        parts.append(_figure_html(out_dir, name, fig, " ".join([caption, *notes])))

    add(0, "fig1-embedding-network", plot.figure_embedding_network,
        "Fig. 1 — sine (N = 251), its embedding (m = 3, τ = 10), recurrence matrix (ε = 0.15) "
        "and recurrence network (spring layout).")
    add(1, "fig2-isrn", plot.figure_isrn,
        "Fig. 2 — inter-system recurrence network of x = sin t, y = sin 1.5t + 0.3x "
        "(ε_X = ε_Y = 0.15, ε_XY = 0.05).")
    add(2, "fig5-pair-network", plot.figure_pair_network,
        "Fig. 5 — functional network of the Fig. 2 pair from C_diff alone (RR = CR = 0.05, "
        "μ = 0.05).")
    base = analyses.baseline
    if base is not None and base.networks:
        add(3, "fig9-baseline-phases",
            lambda: plot.figure_phases(base.data, list(base.windows.values()), base.networks,
                                       title=f"baseline trial {base.trial}"),
            f"Fig. 9 — baseline trial {base.trial}: normalized and raw signals with the "
            "detected phases, and a functional network per phase.")
    cells = {}
    for label, trial in analyses.velocity.items():
        for phase, net in trial.networks.items():
            cells[(label, phase)] = (trial.window_data(phase), net)
    if cells:
        add(4, "fig10-velocity-grid", lambda: plot.figure_velocity_grid(cells),
            "Fig. 10 — velocities (V1, V35, V175, V350; TCP 1.6 m) × phases (fixed windows "
            "of 280 / 600 / 600 ms): normalized series over each network.")
    if analyses.reversal:
        # The backlash trial closest to the baseline (35 °/min, TCP 1.6 m) if the plan has it.
        trials = analyses.trials.set_index("name")
        rev = min(analyses.reversal.values(),
                  key=lambda a: (abs(float(trials.loc[a.trial, "speed"]) - 35),
                                 abs(float(trials.loc[a.trial, "tcp"]) - 1.6)))
        add(5, "fig11-reversal",
            lambda: plot.figure_reversal(rev.data, list(rev.windows.values()),
                                         {f"{k:+d} ms": v for k, v in rev.networks.items()},
                                         phases=rev.phases, title=f"backlash trial {rev.trial}"),
            f"Fig. 11 — backlash trial {rev.trial}: full motion, the reversal with windows at "
            "−40, −20, 0, +20, +40 ms, and their networks.")
    timeline = analyses.timeline
    if timeline is not None and any(n is not None for n in timeline.networks.values()):
        add(6, "edge-timeline",
            lambda: plot.plot_edge_timeline(
                {t: n for t, n in timeline.networks.items() if n is not None}),
            f"Beyond the paper — every pair's edge kind and weight (marker area) over the "
            f"baseline trial {timeline.trial}, from sliding windows.")
    if base is not None and "cruise" in base.windows:
        data = base.window_data("cruise")
        parameters = analyses.parameters
        # A signal constant in the window was left out of its network: left out here too.
        shown = [c for c in ("AP", "V", "AC")
                 if c in data and c not in base.dropped.get("cruise", ())]

        def recurrence_plots() -> Any:
            fig = Figure(figsize=(9.0, 3.2), layout="constrained")
            for ax, column in zip(fig.subplots(1, 3), ("AP", "V", "AC"), strict=True):
                if column in shown:
                    values = normalize(data[column].to_numpy(dtype=float),
                                       parameters["normalize"], names=column)
                    plot.plot_recurrence(values, dim=parameters["dim"], delay=parameters["delay"],
                                         rr=parameters["rr"], metric=parameters["metric"],
                                         theiler=parameters["theiler"], ax=ax, title=column)
            return fig

        add(7, "recurrence-cruise", recurrence_plots,
            f"Beyond the paper — recurrence plots (RR = {parameters['rr']}) of AP, V and AC in "
            f"the baseline cruise window, normalized ({parameters['normalize']}) as for the "
            "networks.")
    _step(progress, steps, steps, "figures done")
    return parts


def build_demo_report(
    plan_dir: str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    progress: Progress = None,
    **parameters: Any,
) -> Path:
    """Run the paper's analyses on a plan of simulated trials and write the HTML report.

    Parameters
    ----------
    plan_dir : path-like
        A folder written by :func:`funcnet.robot.write_plan` (traces and ``manifest.csv``).
    out_dir : path-like
        Report folder: ``index.html`` and ``figures/*.png`` are written there.
    progress : callable, optional
        ``progress(done, total, description)``, called as the work advances.
    **parameters
        Passed to :func:`funcnet.findings.run_paper_analyses` (network parameters, window
        lengths).

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.

    References
    ----------
    Paper sections 2-4, Figures 1, 2, 5, 9, 10 and 11.
    """
    from funcnet.findings import run_paper_analyses

    out = Path(out_dir)
    started = _dt.datetime.now(_dt.UTC)
    analyses = run_paper_analyses(plan_dir, progress=progress, **parameters)
    figures = _demo_figures(analyses, out, progress)
    failures = [(t.trial, k, msg) for group in analyses.groups().values()
                for t in group.values() if t is not None for k, msg in t.errors.items()]
    provenance = {
        "date (UTC)": started.isoformat(timespec="seconds"),
        "command": " ".join(sys.argv),
        "plan folder": str(Path(plan_dir).resolve()),
        "analysis time [s]": f"{analyses.elapsed:.1f}",
        **{f"version of {k}": v for k, v in package_versions(_PACKAGES).items()},
    }
    body = [
        "<h1>funcnet — the paper's analyses on the simulated axis</h1>",
        "<p class=\"note\">All data here are simulated (funcnet's two-mass axis model, the "
        "paper's Table 1 plan), not the paper's robot recordings. Every verdict below is "
        "measured on the networks computed from these traces with the parameters listed; "
        "nothing was tuned towards the paper's results. Read an arrow with care: the asymmetry "
        "of cross-clustering and cross-transitivity follows the relative complexity of two "
        "signals as well as their coupling, and the positions here are smooth while the "
        "currents are noisy (paper section 2.4; funcnet README, 'Direction').</p>",
        "<h2>Findings of the paper's section 4</h2>",
        _findings_html(analyses.findings),
        "<p>Decision rule (fixed before any result, the same for every finding): a claimed "
        "relation is <i>not evaluable</i> when its network is missing or lacks one of its "
        "signals (a signal constant in a window is left out of that window's network), or when "
        "the pair of its signals has a degenerate recurrence structure (a signal barely moves "
        "in the window, so the arrow is meaningless). "
        "<i>yes</i> — every claimed relation was evaluated and holds; <i>partly</i> — not "
        "<i>yes</i>, but at least one network (or trial) shows all its claimed relations, or at "
        "least half of the evaluated relations hold (this includes findings whose evaluated "
        "relations all hold while others could not be evaluated: the evidence then says how "
        "many of the claims could not be evaluated); <i>no</i> — relations were evaluated and "
        "neither holds; <i>not evaluable</i> — no claimed relation could be evaluated, so "
        "nothing was measured; <i>n/a</i> — not reported by the paper, measured here. "
        "Bidirectional edges (|diff| &lt; μ) mean mutual coupling <i>or no coupling</i> (paper "
        "section 2.4).</p>",
        "<h2>Figures</h2>", *figures,
        "<h2>Parameters</h2>", _mapping_table(analyses.parameters, "parameter"),
        "<h2>Trials</h2>", _table(analyses.trials),
        "<h2>Networks (pairs tables)</h2>",
        *(_network_tables(title, group) for title, group in analyses.groups().items()),
    ]
    dropped = [(t.trial, t.windows[k].label if k in t.windows else k, ", ".join(signals))
               for group in analyses.groups().values() for t in group.values()
               for k, signals in t.dropped.items()]
    if failures:
        body += ["<h2>Windows without a network</h2>",
                 _table(pd.DataFrame(failures, columns=["trial", "window", "reason"]))]
    if dropped:
        body += ["<h2>Signals left out of a window (constant there)</h2>",
                 "<p>Min–max normalization needs a range; claims about these signals in these "
                 "windows are counted as not evaluable.</p>",
                 _table(pd.DataFrame(dropped, columns=["trial", "window", "signals"]))]
    if analyses.warnings:
        body += ["<h2>Warnings while computing the networks</h2>",
                 _mapping_table(analyses.warnings, "warning", "networks")]
    body += ["<h2>Provenance</h2>", _mapping_table(provenance, "item"),
             "<h3>Inputs (SHA-256)</h3>", _mapping_table(analyses.inputs, "file", "sha256")]
    index = write_text_atomic(out / "index.html", _page("funcnet demo report", body))
    _step(progress, 1, 1, "report written")
    return index


# --------------------------------------------------------------------------------------------
# the report of a study's results

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
    from funcnet.study import PARAMETER_COLUMNS, load_results

    results = Path(results_dir)
    out = Path(out_dir) if out_dir is not None else results / "report"
    rows = load_results(results)
    document_path = results / "study.json"
    document = json.loads(document_path.read_text()) if document_path.is_file() else {}
    parameters = [c for c in PARAMETER_COLUMNS.values() if c in rows.columns]
    body = [f"<h1>funcnet study report — {_esc(results.resolve().name)}</h1>"]
    groups = list(rows.groupby(["recording", *parameters], sort=False, dropna=False))
    index_rows = []
    sections = []
    for k, (key, group) in enumerate(groups):
        recording = key[0]
        _step(progress, k, len(groups), f"report: {recording}")
        setting = dict(zip(parameters, key[1:], strict=True))
        windows = list(group.groupby(_WINDOW_KEYS[1:], sort=False))
        windows.sort(key=lambda item: (item[0][1], item[0][2]))
        slug = _slug(f"{k}-{recording}")
        parts = [f'<h2 id="{slug}">{_esc(recording)}</h2>',
                 f"<p>parameters: {_esc(', '.join(f'{n}={v}' for n, v in setting.items()))}</p>"]
        for start in range(0, len(windows), _GRID):
            chunk = windows[start:start + _GRID]
            cols = min(6, len(chunk))
            fig = Figure(figsize=(2.3 * cols, 2.5 * -(-len(chunk) // cols)), layout="constrained")
            for j, ((label, t0, t1), pairs) in enumerate(chunk):
                ax = fig.add_subplot(-(-len(chunk) // cols), cols, j + 1)
                # sliding windows are labelled by their span already
                title = label if str(label).endswith(" s") else f"{label}\n{t0:.2f}–{t1:.2f} s"
                plot.plot_network(pairs, ax, title=title, fontsize=7, legend=False)
            plot.add_network_legend(fig)
            parts.append(_figure_html(out, f"{slug}-networks-{start // _GRID}", fig,
                                      f"{recording}: networks of windows {start + 1}–"
                                      f"{start + len(chunk)} of {len(windows)}"))
        if len(windows) >= 3:
            table = group.assign(time=(group["start"] + group["stop"]) / 2)
            timeline = plot.plot_edge_timeline(table)
            parts.append(_figure_html(out, f"{slug}-timeline", timeline.figure,
                                      f"{recording}: edge kind and weight per window centre"))
        for (label, t0, t1), pairs in windows:
            parts.append(f"<details><summary>{_esc(label)} ({t0:.3f}–{t1:.3f} s)</summary>"
                         f"{_pairs_table(pairs)}</details>")
        sections.append("".join(parts))
        index_rows.append({"recording": recording, **setting, "windows": len(windows),
                           "source sha256": group["source_sha256"].iloc[0]
                           if "source_sha256" in group else ""})
    body += ["<h2>Recordings</h2>", _table(pd.DataFrame(index_rows)), *sections]
    run = document.get("run", {})
    if run:
        body += ["<h2>Run</h2>", _mapping_table({k: v for k, v in run.items()
                                                 if k != "failures"}, "item")]
        if run.get("failures"):
            body += ["<h3>Failed tasks</h3>", _table(pd.DataFrame(run["failures"]))]
    if document.get("study"):
        body += ["<h2>Study</h2>",
                 f"<pre>{_esc(json.dumps(document['study'], indent=2, default=str))}</pre>"]
    study_provenance = document.get("provenance", {})
    provenance = {
        "report date (UTC)": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "report command": " ".join(sys.argv),
        "study command": " ".join(study_provenance.get("command", [])),
        **{f"version of {k} (study)": v
           for k, v in study_provenance.get("versions", {}).items()},
        **{f"version of {k} (report)": v for k, v in package_versions(_PACKAGES).items()},
    }
    inputs = study_provenance.get("inputs") or dict(
        zip(rows["recording"], rows.get("source_sha256", ""), strict=False))
    body += ["<h2>Provenance</h2>", _mapping_table(provenance, "item"),
             "<h3>Inputs (SHA-256)</h3>", _mapping_table(inputs, "file", "sha256")]
    index = write_text_atomic(out / "index.html", _page("funcnet study report", body))
    _step(progress, len(groups), len(groups), "report written")
    return index
