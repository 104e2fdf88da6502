"""The study report: a study's Parquet rows as a summary, consensus figures and tables in HTML.

:func:`write_report` reads a results folder (:func:`funcnet.study.load_results`) and writes one
page that reads from the top: what was run and what failed (grouped by cause), how to read the
figures, a table of contents, then per parameter set the consensus of the recordings (for each
pair and window label, the edge most recordings show and in how many), one recording's
networks and edge timeline as an example; the problems the pairs tables flag, counted with the
trials and windows named; every pairs table (collapsed); the study and its provenance.

The figures are few and of fixed number per parameter set, so that the report of a study of
hundreds of networks is written in seconds.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 3.4
   and 4.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.report.html import (
    Progress,
    contents,
    escape,
    figure_html,
    mapping_table,
    page,
    pairs_table,
    provenance,
    setpoint_html,
    step,
    table,
)
from funcnet.study import PARAMETER_COLUMNS, load_results, network_from_rows

__all__ = ["write_report", "consensus", "problem_counts", "evidence_counts"]

_WINDOW_KEYS = ["recording", "window", "start", "stop"]
_GRID = 24  # networks in the example figure
_ARROWS = {"x->y": "→", "y->x": "←", "bidirectional": "↔", "conflict": "×",
           "degenerate": "?", "": ""}
_SHOWN = 8  # trials x windows named per problem before "and N more"

#: What each flagged problem of a pairs table means, for the reader.
PROBLEMS = {
    "eps_order": "ε_XY is not below ε_X and ε_Y (section 2.2 asks it for a modular ISRN)",
    "rate_exceeded": "ties at a threshold pushed an achieved rate above its target",
    "degenerate": "too few distinct states: the arrow is meaningless (no edge drawn)",
}


def _slug(text: str) -> str:
    keep = "".join(ch if ch.isalnum() else "-" for ch in text)
    return "-".join(part for part in keep.split("-") if part)[:60] or "x"


def _names(rows: pd.DataFrame) -> pd.Series:
    """A short name per row's recording: its trial, else its file name (never a full path)."""
    if "trial" in rows.columns:
        trial = rows["trial"].astype("string")
        named = trial.notna() & (trial != "")
        return trial.where(named, rows["recording"].map(lambda p: Path(str(p)).name)).astype(str)
    return rows["recording"].map(lambda p: Path(str(p)).name)


def problem_counts(rows: pd.DataFrame, networks: Sequence[str] = _WINDOW_KEYS
                   ) -> pd.DataFrame:
    """The problems the pairs tables flag, once each: how many networks, which ones.

    Parameters
    ----------
    rows : pandas.DataFrame
        A study's rows (:func:`funcnet.study.load_results`), with a ``name`` column naming the
        recording for the reader.
    networks : sequence of str
        The columns that identify one network (with the parameter columns).

    Returns
    -------
    pandas.DataFrame
        ``problem, meaning, networks, of, where`` (``where``: trial · window, the first few,
        then how many more).

    Examples
    --------
    >>> rows = pd.DataFrame({"name": ["t1", "t1", "t2"], "recording": ["a", "a", "b"],
    ...                      "window": ["cruise"] * 3, "start": [0.0] * 3, "stop": [1.0] * 3,
    ...                      "eps_ordered": [False, True, True], "rate_exceeded": [False] * 3,
    ...                      "degenerate": [False] * 3})
    >>> problem_counts(rows)[["problem", "networks", "of", "where"]].to_dict("records")
    [{'problem': 'eps_order', 'networks': 1, 'of': 2, 'where': 't1 · cruise'}]
    """
    keys = [c for c in networks if c in rows.columns]
    flags = pd.DataFrame({
        "eps_order": ~rows["eps_ordered"].astype(bool),
        "rate_exceeded": rows["rate_exceeded"].astype(bool) & ~rows["degenerate"].astype(bool),
        "degenerate": rows["degenerate"].astype(bool),
    })
    frame = pd.concat([rows[keys + ["name"]], flags], axis=1)
    per_network = frame.groupby(keys, sort=False, dropna=False).agg(
        {"name": "first", **dict.fromkeys(PROBLEMS, "any")})
    total = len(per_network)
    out = []
    for problem, meaning in PROBLEMS.items():
        hit = per_network[per_network[problem]]
        if hit.empty:
            continue
        labels = list(dict.fromkeys(
            f"{name} · {window}" for name, window in
            zip(hit["name"], hit.index.get_level_values("window"), strict=True)))
        where = ", ".join(labels[:_SHOWN]) + (f", and {len(labels) - _SHOWN} more"
                                               if len(labels) > _SHOWN else "")
        out.append({"problem": problem, "meaning": meaning, "networks": len(hit), "of": total,
                    "where": where})
    return pd.DataFrame(out, columns=["problem", "meaning", "networks", "of", "where"])


def consensus(rows: pd.DataFrame) -> pd.DataFrame:
    """Per pair and window label: the kind most recordings show, and in how many.

    Parameters
    ----------
    rows : pandas.DataFrame
        The rows of one parameter set.

    Returns
    -------
    pandas.DataFrame
        ``window, pair, kind, count, of`` (degenerate pairs count as ``"degenerate"``), windows
        in order of their first start.

    Examples
    --------
    >>> rows = pd.DataFrame({"recording": ["a", "b", "c"], "window": ["cruise"] * 3,
    ...                      "start": [1.0, 1.0, 1.2], "x": ["RP"] * 3, "y": ["AC"] * 3,
    ...                      "kind": ["y->x", "y->x", "x->y"], "degenerate": [False] * 3})
    >>> consensus(rows).to_dict("records")
    [{'window': 'cruise', 'pair': 'RP–AC', 'kind': 'y->x', 'count': 2, 'of': 3}]
    """
    kind = rows["kind"].astype(str).where(~rows["degenerate"].astype(bool), "degenerate")
    frame = pd.DataFrame({"window": rows["window"].astype(str),
                          "pair": rows["x"].astype(str) + "–" + rows["y"].astype(str),
                          "kind": kind, "recording": rows["recording"]})
    counts = frame.groupby(["window", "pair", "kind"], sort=False).size().rename("count")
    totals = frame.groupby(["window", "pair"], sort=False).size().rename("of")
    top = counts.reset_index().sort_values("count", ascending=False, kind="stable")
    top = top.drop_duplicates(["window", "pair"]).merge(totals.reset_index(),
                                                         on=["window", "pair"])
    order = {w: k for k, w in enumerate(
        rows.assign(w=rows["window"].astype(str)).sort_values("start")["w"].drop_duplicates())}
    top = top.assign(_o=top["window"].map(order)).sort_values(["_o"], kind="stable")
    return top.drop(columns="_o").reset_index(drop=True)[["window", "pair", "kind", "count",
                                                         "of"]]


def has_evidence(rows: pd.DataFrame) -> bool:
    """Whether a study's rows carry evidence (its ``[evidence]`` was enabled for some)."""
    return "evidence" in rows.columns and bool(rows["evidence"].notna().any())


def evidence_counts(rows: pd.DataFrame, alpha: float = 0.05) -> pd.DataFrame:
    """Per window label: how many pairs the coupling test shows coupled, and how many it could
    not test.

    Parameters
    ----------
    rows : pandas.DataFrame
        The rows of one parameter set, with the evidence columns.
    alpha : float
        The study's ``[evidence] alpha`` (for :func:`funcnet.evidence.untestable`).

    Returns
    -------
    pandas.DataFrame
        ``window, pairs, coupled`` (``coupled`` and ``coupled-directed``),
        ``coupled-directed, asymmetry-only`` (tested, the paper's arrow, nothing supports
        coupling), ``not-coupled`` (tested, no arrow), ``untestable`` (the test could not have
        rejected at ``alpha``: too few surrogates), ``surrogates`` (their range), windows in
        order of first start. Rows written before the ``untestable`` label are read as a new
        network's: ``untestable`` from each network's surrogates.

    Examples
    --------
    >>> rows = pd.DataFrame({"window": ["cruise"] * 3, "start": [1.0] * 3,
    ...                      "evidence": ["coupled", "asymmetry-only", "untestable"],
    ...                      "coupled": [True, False, False], "coupling_p": [0.01, 0.3, 0.5],
    ...                      "surrogates": [299, 299, 12]})
    >>> evidence_counts(rows).iloc[0].to_dict()  # doctest: +NORMALIZE_WHITESPACE
    {'window': 'cruise', 'pairs': 3, 'coupled': 1, 'coupled-directed': 0,
     'asymmetry-only': 1, 'not-coupled': 0, 'untestable': 1, 'surrogates': '12–299'}
    """
    from funcnet.evidence import untestable

    rows = rows[rows["evidence"].notna()]
    # Whether a pair was untestable depends on its network's other pairs (the adjustment).
    networks = [c for c in _WINDOW_KEYS if c in rows.columns]
    blind = pd.Series(False, index=rows.index)
    for _, network in rows.groupby(networks, sort=False, dropna=False):
        blind[network.index] = untestable(network["surrogates"].to_numpy(dtype=float), alpha) \
            & ~network["coupled"].astype(bool).to_numpy()
    out = []
    for window, group in rows.sort_values("start", kind="stable").groupby("window", sort=False):
        label = group["evidence"].astype(str)
        tested = ~blind[group.index]
        k = group["surrogates"].astype(float)
        out.append({"window": str(window), "pairs": len(group),
                    "coupled": int(label.isin(["coupled", "coupled-directed"]).sum()),
                    "coupled-directed": int((label == "coupled-directed").sum()),
                    "asymmetry-only": int(((label == "asymmetry-only") & tested).sum()),
                    "not-coupled": int(((label == "not-coupled") & tested).sum()),
                    "untestable": int(blind[group.index].sum()),
                    "surrogates": f"{k.min():g}–{k.max():g}" if k.min() != k.max()
                    else f"{k.min():g}"})
    return pd.DataFrame(out, columns=["window", "pairs", "coupled", "coupled-directed",
                                      "asymmetry-only", "not-coupled", "untestable",
                                      "surrogates"])


def _read_labels(rows: pd.DataFrame, alpha: float, networks: Sequence[str]) -> pd.DataFrame:
    """Rows with evidence written before the ``untestable`` label, labelled as a network with
    evidence is now (:func:`funcnet.network.edge_evidence.with_readings`, per network)."""
    if not has_evidence(rows):
        return rows
    stale = rows["evidence"].notna()
    if "evidence_reason" in rows.columns:
        stale &= rows["evidence_reason"].isna()
    if not stale.any():
        return rows
    from funcnet.network.edge_evidence import with_readings

    rows = rows.copy()
    if "evidence_reason" not in rows.columns:
        rows.insert(rows.columns.get_loc("evidence") + 1, "evidence_reason",
                    pd.Series(pd.NA, index=rows.index, dtype="object"))
    keys = [c for c in networks if c in rows.columns]
    for _, network in rows[stale].groupby(keys, sort=False, dropna=False):
        read = with_readings(network, alpha)
        rows.loc[network.index, "evidence"] = read["evidence"].to_numpy(dtype=object)
        rows.loc[network.index, "evidence_reason"] = read["evidence_reason"].to_numpy(
            dtype=object)
    return rows


def _consensus_figure(table_: pd.DataFrame) -> Any:
    from matplotlib.colors import to_rgb
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    from funcnet import plot

    windows = list(dict.fromkeys(table_["window"]))
    pairs = list(dict.fromkeys(table_["pair"]))
    fig = Figure(figsize=(max(7.0, 0.9 * len(windows) + 3.5), 0.38 * len(pairs) + 2.4),
                 layout="constrained")
    ax = fig.add_subplot()
    image = np.ones((len(pairs), len(windows), 3))
    for row in table_.itertuples(index=False):
        r, c = pairs.index(row.pair), windows.index(row.window)
        share = row.count / row.of if row.of else 0.0
        colour = np.array(to_rgb(plot.KIND_COLORS.get(row.kind, "0.5")))
        image[r, c] = 1 - share * (1 - colour) * 0.75  # paler where fewer recordings agree
        ax.text(c, r, f"{_ARROWS.get(row.kind, row.kind)} {row.count}/{row.of}", ha="center",
                va="center", fontsize=9)
    ax.imshow(image, aspect="auto", interpolation="nearest")
    ax.set_xticks(range(len(windows)), windows, rotation=45, ha="right", fontsize=9)
    ax.set_yticks(range(len(pairs)), pairs, fontsize=9)
    ax.set_ylabel("pair X–Y", fontsize=9)
    handles = [Patch(facecolor=plot.KIND_COLORS[k], label=f"{_ARROWS[k]} {k}")
               for k in ("x->y", "y->x", "bidirectional", "conflict", "degenerate")]
    fig.legend(handles=handles, loc="outside right upper", fontsize=9, frameon=False,
               title="most common kind\n(paler: fewer agree)", title_fontsize=9)
    return fig


def _network_grid(windows: Sequence[tuple[tuple[Any, ...], pd.DataFrame]], name: str) -> Any:
    from matplotlib.figure import Figure

    from funcnet import plot

    chunk = list(windows)[:_GRID]
    cols = min(6, len(chunk))
    fig = Figure(figsize=(2.4 * cols, 2.7 * -(-len(chunk) // cols) + 0.6), layout="constrained")
    degenerate = evidence = False
    for j, ((label, t0, t1), pairs) in enumerate(chunk):
        ax = fig.add_subplot(-(-len(chunk) // cols), cols, j + 1)
        # sliding windows are labelled by their span already
        title = label if str(label).endswith(" s") else f"{label}\n{t0:.2f}–{t1:.2f} s"
        net = network_from_rows(pairs)  # its edges under its own degenerate policy
        plot.plot_network(net, ax, title=title, fontsize=9, legend=False,
                          arrows="direction" if "direction" in net.pairs.columns else "rule")
        ax.set_facecolor(plot.phase_color(label, 99))
        edges = plot.network_edges(net)
        degenerate |= bool(edges["degenerate"].any())
        evidence |= plot.edge_evidence(net, edges) is not None
    plot.add_network_legend(fig, degenerate=degenerate, evidence=evidence)
    fig.suptitle(name, fontsize=10)
    return fig


def _failures_html(failures: Sequence[Mapping[str, Any]]) -> str:
    """Failed tasks grouped by cause: one row per distinct error, its tasks counted and named."""
    groups: dict[str, list[str]] = {}
    for failure in failures:
        error = str(failure.get("message", failure.get("error", failure)))
        source = Path(str(failure.get("recording", failure.get("source", "")))).name
        window = failure.get("window", "")
        if isinstance(window, Mapping):
            window = window.get("label", window.get("kind", ""))
        groups.setdefault(error, []).append(" · ".join(str(p) for p in (source, window) if p))
    rows = [{"tasks": len(where), "error": error,
             "where": ", ".join(where[:_SHOWN]) + (f", and {len(where) - _SHOWN} more"
                                                   if len(where) > _SHOWN else "")}
            for error, where in groups.items()]
    return table(pd.DataFrame(rows))


def _parameter_section(out: Path, k: int, setting: dict[str, Any], group: pd.DataFrame,
                       alpha: float, steps: int, progress: Progress) -> str:
    """One parameter set's part of the figures: consensus, example networks, timeline, evidence."""
    from funcnet import plot

    label = ", ".join(f"{n} = {v}" for n, v in setting.items()) or "one parameter set"
    slug = _slug(f"set{k + 1}-" + "-".join(f"{n}{v}" for n, v in setting.items()))
    step(progress, 3 * k, steps, f"report: {label}")
    table_ = consensus(group)
    parts = [f'<h3 id="{slug}">Parameter set {k + 1}: {escape(label)}</h3>',
             figure_html(out, f"{slug}-consensus", _consensus_figure(table_),
                         f"Consensus over {group['name'].nunique()} recordings ({label}): "
                         "for each pair (rows) and window label (columns), the edge kind "
                         "most recordings show and in how many of them (→ X → Y, ← Y → X, "
                         "↔ bidirectional, × conflict = no edge, ? degenerate). A kind "
                         "shown by about half the recordings is not a property of the "
                         "plan.")]
    first = group["name"].iloc[0]
    mine = group[group["name"] == first]
    windows = sorted(mine.groupby(_WINDOW_KEYS[1:], sort=False),
                     key=lambda item: (item[0][1], item[0][2]))
    step(progress, 3 * k + 1, steps, f"report: {label}: example networks")
    parts.append(figure_html(out, f"{slug}-networks-0",
                             _network_grid(windows, f"{first} ({label})"),
                             f"Example: the networks of recording {first} ({label}), "
                             f"{min(len(windows), _GRID)} of its {len(windows)} windows. "
                             "Black arrow: the direction reading (the source's past "
                             "improves the target's prediction); pale line: undecided "
                             "(rows without a direction column: the rule's arrows, red "
                             "bidirectional); width ∝ weight (Eq. 13)."
                             + (" Dotted, pale: the coupling test does not show the pair "
                                "coupled (asymmetry-only or not-coupled); dash-dotted, "
                                "paler: untestable (the test could not have rejected)."
                                if has_evidence(mine) else "")))
    if len(windows) >= 3:
        step(progress, 3 * k + 2, steps, f"report: {label}: timeline")
        # keyed by window: each network placed at its window's centre
        timeline = plot.plot_edge_timeline(
            {key: network_from_rows(part)
             for key, part in mine.groupby(_WINDOW_KEYS[1:], sort=False)})
        parts.append(figure_html(out, f"{slug}-timeline", timeline.figure,
                                 f"Example: edge kind and weight per window centre, "
                                 f"recording {first} ({label})."))
    if has_evidence(group):
        parts += ["<h4>Coupling evidence</h4>",
                  "<p>Per window label, over the recordings: pairs the joint-recurrence "
                  f"test shows coupled (α = {alpha:g}, Benjamini–Hochberg over each "
                  "network's pairs), tested arrows without coupling evidence "
                  "(asymmetry-only), tested pairs without an arrow (not-coupled), and pairs "
                  "the test could not have shown coupled whatever the data (untestable: "
                  "with K surrogates no p-value is below 1/(K+1), and the adjustment over "
                  "the network's pairs never lowers it; short windows hold few). "
                  "Untestable is not uncoupled. The pairs tables below have every "
                  "evidence column.</p>", table(evidence_counts(group, alpha))]
    return "".join(parts)


def _summary_html(results: Path, rows: pd.DataFrame, run: Mapping[str, Any], n_networks: int,
                  n_settings: int, varying: list[str]) -> list[str]:
    """The page's head: the counts, the run's tasks, how to read it, the failures by cause."""
    recordings = list(dict.fromkeys(rows["name"]))
    failures = run.get("failures") or []
    kinds = rows["kind"].astype(str).where(~rows["degenerate"].astype(bool), "degenerate")
    kind_text = ", ".join(f"{n} {k}" for k, n in kinds.value_counts().items())
    summary = [
        f"<h1>funcnet study report — {escape(results.resolve().name)}</h1>",
        setpoint_html([part for _, part in rows.groupby(_WINDOW_KEYS, sort=False)]),
        '<section id="summary"><h2>Summary</h2>',
        f"<p>{len(recordings)} recording(s), {n_networks} networks ({len(rows)} pairs: "
        f"{escape(kind_text)}) over {n_settings} parameter set(s)"
        + (f" varying {escape(', '.join(varying))}" if varying else "") + "."
        + (f" {run.get('tasks', 0)} tasks: {run.get('computed', 0)} computed, "
           f"{run.get('cached', 0)} reused from an earlier run, {len(failures)} failed."
           if run else "") + "</p>",
        '<p class="verdict">How to read it: a study says what is <i>common</i> to its '
        "recordings. For each pair and window label, the consensus figure gives the edge "
        "kind most recordings show and in how many (→ 30/36). Read an arrow shared by most "
        "recordings as a property of the plan and its parameters; one shared by about half "
        "as no finding. An arrow follows the relative complexity of two signals as well as "
        "their coupling (paper section 2.4): it is not a cause. Pairs flagged degenerate "
        "have no edge.</p>",
    ]
    if failures:
        summary += ["<h3>Failed tasks, by cause</h3>", _failures_html(failures)]
    summary.append("</section>")
    return summary


def _problems_html(rows: pd.DataFrame, run: Mapping[str, Any], parameters: list[str]) -> list[str]:
    """The problems the pairs tables flag, then those the run counted beyond them."""
    problems = problem_counts(rows, [*_WINDOW_KEYS, *parameters])
    body = ['<section id="problems"><h2>Problems flagged</h2>',
            "<p>Each problem once: the networks whose pairs table flags it (trial · window; "
            "the flags are columns of the rows).</p>" + table(problems)
            if len(problems) else "<p>None in the pairs tables.</p>"]
    # what the run flagged beyond the pairs tables (windows, staircases), counted by the run
    others = {k: v for k, v in (run.get("warnings") or {}).items() if k not in PROBLEMS}
    if others:
        body += ["<p>Flagged by the run (counted over the networks it computed):</p>",
                 table(pd.DataFrame([{"problem": k, "networks": v.get("tasks"),
                                      "example": v.get("example", "")}
                                     for k, v in others.items()]))]
    body.append("</section>")
    return body


def _tables_html(rows: pd.DataFrame, parameters: list[str], varying: list[str]) -> list[str]:
    """Every window's pairs table (collapsed, per recording and parameter set), the recordings."""
    details = []
    for (name, *rest), group in rows.groupby(["name", *parameters], sort=False, dropna=False):
        values_shown = ", ".join(f"{n}={v}" for n, v in zip(parameters, rest, strict=True)
                                 if n in varying)
        inner = "".join(
            f"<details><summary>{escape(w)} ({t0:.3f}–{t1:.3f} s)</summary>"
            f"{pairs_table(pairs)}</details>"
            for (w, t0, t1), pairs in group.groupby(["window", "start", "stop"], sort=False))
        details.append(f"<details><summary><b>{escape(name)}</b>"
                       f"{' — ' + escape(values_shown) if values_shown else ''}</summary>{inner}"
                       "</details>")
    index_rows = (rows.groupby("name", sort=False)
                  .agg(file=("recording", lambda s: Path(str(s.iloc[0])).name),
                       windows=("window", "nunique"),
                       sha256=("source_sha256", "first") if "source_sha256" in rows
                       else ("recording", "size"))
                  .reset_index().rename(columns={"name": "recording"}))
    return ['<section id="networks"><h2>Pairs tables</h2>', *details, "</section>",
            '<section id="recordings"><h2>Recordings</h2>',
            f"<details><summary>{len(index_rows)} recordings</summary>{table(index_rows)}"
            "</details></section>"]


def _provenance_html(rows: pd.DataFrame, document: Mapping[str, Any]) -> list[str]:
    """The study's run record, the study as read, the provenance and the inputs' hashes."""
    run = document.get("run", {})
    study_provenance = document.get("provenance", {})
    report_provenance = provenance({
        "study command": " ".join(study_provenance.get("command", [])),
        **{f"version of {k} (study)": v
           for k, v in study_provenance.get("versions", {}).items()},
    }, qualifier="report")
    inputs = study_provenance.get("inputs") or dict(
        zip(rows["recording"], rows.get("source_sha256", ""), strict=False))
    inputs = {Path(str(k)).name: v for k, v in inputs.items()}
    body = ['<section id="study"><h2>Study and provenance</h2>']
    if run:
        body.append(mapping_table({k: v for k, v in run.items()
                                   if k not in ("failures", "warnings")}, "run"))
    if document.get("study"):
        body.append("<details><summary>the study as read</summary><pre>"
                    f"{escape(json.dumps(document['study'], indent=2, default=str))}</pre>"
                    "</details>")
    return [*body, mapping_table(report_provenance, "item"),
            "<details><summary>inputs (SHA-256)</summary>"
            f"{mapping_table(inputs, 'file', 'sha256')}</details></section>"]


def write_report(
    results_dir: str | os.PathLike[str],
    out_dir: str | os.PathLike[str] | None = None,
    *,
    progress: Progress = None,
) -> Path:
    """Write the HTML report of a study's results folder.

    Summary and failures (grouped by cause) first, then a table of contents and, per parameter
    set, the consensus figure (:func:`consensus`), the first recording's networks
    (:func:`funcnet.plot.plot_network` on each window's rows) and its edge timeline when it has
    three windows or more (:func:`funcnet.plot.plot_edge_timeline`); then the flagged problems
    counted (:func:`problem_counts`), every window's pairs table (collapsed), the study and
    the provenance (versions, input hashes, commands, date).

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
    results = Path(results_dir)
    out = Path(out_dir) if out_dir is not None else results / "report"
    rows = load_results(results)
    rows = rows.assign(name=_names(rows))
    document_path = results / "study.json"
    document = json.loads(document_path.read_text()) if document_path.is_file() else {}
    run = document.get("run", {})
    alpha = float(((document.get("study") or {}).get("evidence") or {}).get("alpha", 0.05))
    parameters = [c for c in PARAMETER_COLUMNS.values() if c in rows.columns]
    rows = _read_labels(rows, alpha, [*_WINDOW_KEYS, "signals", *parameters])
    varying = [c for c in parameters if rows[c].astype(str).nunique() > 1]
    settings = list(rows.groupby(varying, sort=False, dropna=False)) if varying else [((), rows)]
    n_networks = rows.groupby([*_WINDOW_KEYS, *parameters], dropna=False).ngroups
    steps = 3 * len(settings) + 2
    sections = []
    for k, (key, group) in enumerate(settings):
        values = key if isinstance(key, tuple) else (key,)
        setting = dict(zip(varying, values, strict=True))
        sections.append(_parameter_section(out, k, setting, group, alpha, steps, progress))
    toc = [("summary", "Summary"), ("figures", "Figures"), ("problems", "Problems flagged"),
           ("networks", "Pairs tables"), ("recordings", "Recordings"),
           ("study", "Study and provenance")]
    body = [*_summary_html(results, rows, run, n_networks, len(settings), varying),
            contents(toc), '<h2 id="figures">Figures</h2>', *sections]
    step(progress, steps - 2, steps, "report: tables")
    body += [*_problems_html(rows, run, parameters), *_tables_html(rows, parameters, varying),
             *_provenance_html(rows, document)]
    index = write_text_atomic(out / "index.html", page("funcnet study report", body))
    step(progress, steps, steps, "report written")
    return index
