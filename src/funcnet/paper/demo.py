"""The demo report: the paper's analyses on a plan of simulated trials, as one HTML page.

:func:`build_demo_report` runs :func:`funcnet.paper.run_paper_analyses` and writes the paper's
Figures 1, 2, 5, 9, 10 and 11 (:mod:`funcnet.paper.figures`), an edge timeline and recurrence
plots beyond the paper, the table of the paper's findings (reproduced yes / partly / no / not
evaluable, with counts), every network's pairs table, the parameters and the provenance
(versions, SHA-256 of every input, command line, date).

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.
"""

from __future__ import annotations

import datetime as _dt
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, Unpack

import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.paper import Finding, PaperAnalyses, TrialAnalysis, run_paper_analyses
from funcnet.paper.analyses import AnalysisOptions
from funcnet.paper.coupling import CouplingEvidence, claims_coupling
from funcnet.report.html import (
    Progress,
    contents,
    escape,
    figure_html,
    mapping_table,
    page,
    pairs_table,
    provenance,
    step,
    table,
)

__all__ = ["build_demo_report"]


def _verdict_class(value: Any) -> str:
    classes = {"yes": "yes", "partly": "partly", "no": "no", "not evaluable": "ne"}
    return classes.get(str(value), "na")


def readable_evidence(finding: Finding, shown: int = 4) -> str:
    """A finding's evidence with its unevaluable claims grouped by reason, each counted.

    The counts of :attr:`Finding.evidence` stay; the list of claims that could not be
    evaluated (often the same reason many times) becomes one entry per reason with its count
    and the first few places.

    Examples
    --------
    >>> f = Finding("x", "4.1", "s", "partly", "0/1 networks show all claimed relations; 1/2 "
    ...             "relations hold; 2 of 3 claims could not be evaluated: [V1 · a] X->Y: no "
    ...             "network, [V1 · b] X->Y: no network", not_evaluable=(
    ...             "[V1 · a] X->Y: no network", "[V1 · b] X->Y: no network"))
    >>> for part in readable_evidence(f).split("; "):
    ...     print(part)
    0/1 networks show all claimed relations
    1/2 relations hold
    2 of 3 claims could not be evaluated — no network ×2: [V1 · a] X->Y, [V1 · b] X->Y
    """
    missing = finding.not_evaluable
    if not missing:
        return finding.evidence
    head = finding.evidence.partition(" claims could not be evaluated")[0]
    groups: dict[str, list[str]] = {}
    for item in missing:
        where, _, reason = item.partition(": ")
        groups.setdefault(reason or "not evaluable", []).append(where)
    parts = [f"{reason} ×{len(places)}: " + ", ".join(places[:shown])
             + (f", … ({len(places) - shown} more)" if len(places) > shown else "")
             for reason, places in groups.items()]
    return f"{head} claims could not be evaluated — " + "; ".join(parts)


def _findings_html(findings: Sequence[Finding],
                   coupling: Mapping[str, CouplingEvidence] | None = None) -> tuple[str, str]:
    """The findings' summary (counts of each verdict), and the table with the plain list; with
    ``coupling``, the table's column "coupling evidence" (:mod:`funcnet.paper.coupling`)."""
    coupling = coupling or {}
    frame = pd.DataFrame([{"finding": f.id, "section": f.section, "statement": f.statement,
                           "reproduced": f.reproduced, "evidence": readable_evidence(f),
                           "coupling evidence": coupling[f.id].text if f.id in coupling
                           else "—"}
                          for f in findings],
                         columns=["finding", "section", "statement", "reproduced", "evidence",
                                  "coupling evidence"])
    if not coupling:
        frame = frame.drop(columns="coupling evidence")
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
        f"<li><b>{escape(r.finding)}</b> — the paper: “{escape(r.statement)}” The simulation "
        f"{verdicts[r.reproduced]} ({escape(r.evidence)}).{escape(shown(seen[r.finding]))}</li>"
        for r in missed.itertuples(index=False))
    details = "".join(
        f"<details><summary>{escape(f.id)}: relations seen</summary><p><b>claimed:</b> "
        f"{escape('; '.join(f.expected)) or '—'}</p><p><b>seen:</b> "
        f"{escape('; '.join(f.edges_seen)) or '—'}</p></details>" for f in findings)
    shown = frame.rename(columns={"statement": "the paper says"})
    return (summary, table(shown, classes={"reproduced": _verdict_class})
            + (f"<h3>Where the simulation does not (or cannot) reproduce the paper</h3>"
               f"<ul>{plain}</ul>"
               if plain else "") + details)


def _problems_html(analyses: PaperAnalyses, shown: int = 8) -> str:
    """The problems the networks' pairs tables flag, once each, with trial · window named."""
    from funcnet.pipeline import window_warnings

    places: dict[str, list[str]] = {}
    for group in analyses.groups().values():
        for trial in group.values():
            if trial is None:
                continue
            computed = {key: net for key, net in trial.networks.items() if net is not None}
            labels = {str(key): (trial.windows[key].label if key in trial.windows else str(key))
                      for key in computed}
            for warning in window_warnings({str(k): n for k, n in computed.items()}):
                places.setdefault(str(warning.problem), []).append(
                    f"{trial.trial} · {labels.get(str(warning.window), warning.window)}")
    if not places:
        return "<p>None.</p>"
    meaning = {"eps_order": "ε_XY is not below ε_X and ε_Y (section 2.2 asks it)",
               "rate_exceeded": "ties at a threshold pushed an achieved rate above its target",
               "degenerate": "too few distinct states: the arrow is meaningless (no edge)"}
    rows = [{"problem": problem, "meaning": meaning.get(problem, ""), "networks": len(where),
             "where": ", ".join(dict.fromkeys(where[:shown]))
             + (f", and {len(where) - shown} more" if len(where) > shown else "")}
            for problem, where in places.items()]
    return ("<p>Each problem once, with the networks (trial · window) whose pairs table flags "
            "it.</p>" + table(pd.DataFrame(rows)))


def _network_tables(title: str, analyses: Mapping[str, TrialAnalysis]) -> str:
    parts = [f"<h3>{escape(title)}</h3>"]
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
                inner.append(f"<p><b>{escape(name)}</b>{escape(span)}: not computed — "
                             f"{escape(trial.errors.get(key, ''))}</p>")
            else:
                inner.append(f"<details><summary>{escape(name)}{escape(span)}</summary>"
                             f"{pairs_table(net.pairs)}</details>")
        if "windows" in trial.errors:
            inner.append(f"<p>no windows: {escape(trial.errors['windows'])}</p>")
        parts.append(f"<details><summary><b>{escape(trial.trial)}</b> — {len(trial.networks)} "
                     f"windows</summary>{''.join(inner)}</details>")
    return "".join(parts)


def _demo_figures(analyses: PaperAnalyses, out_dir: Path, progress: Progress) -> list[str]:
    from matplotlib.figure import Figure

    from funcnet import plot
    from funcnet.paper import figures as paper_figures

    parts: list[str] = []
    steps = 9

    def add(k: int, name: str, make: Callable[[], Any], caption: str,
            networks: Mapping[Any, Any] | None = None) -> None:
        step(progress, k, steps, f"figure: {name}")
        made = make()
        fig = made if isinstance(made, Figure) else made.figure
        # What the drawn networks flag belongs to the figure's caption.
        notes = paper_figures.figure_notes(networks or {})
        parts.append(figure_html(out_dir, name, fig, " ".join([caption, *notes])))

    add(0, "fig1-embedding-network", paper_figures.figure_embedding_network,
        "Fig. 1 — sine (N = 251), its embedding (m = 3, τ = 10), recurrence matrix (ε = 0.15) "
        "and recurrence network (spring layout).")
    cross = paper_figures.isrn_cross_links()
    add(1, "fig2-isrn", paper_figures.figure_isrn,
        "Fig. 2 — inter-system recurrence network of x = sin t, y = sin 1.5t + 0.3x "
        "(ε_X = ε_Y = 0.15, ε_XY = 0.05)."
        + (" The cross blocks CR_XY, CR_YX of panel (c) are empty and the network of panel (d) "
           "falls into two parts: at ε_XY = 0.05 no state of x lies that close to a state of "
           "y (0 cross links; 64 at ε_XY = 0.15). That is the data, not a drawing error."
           if cross == 0 else f" {cross} cross links."))
    pair = paper_figures.pair_network(warn=False)
    add(2, "fig5-pair-network", lambda: paper_figures.figure_pair_network(network=pair),
        "Fig. 5 — functional network of the Fig. 2 pair from C_diff alone (min-max "
        "normalized, RR = CR = 0.05, μ = 0.05). "
        + (f"The arrow points y → x although x drives y (y = sin 1.5t + 0.3x): C_diff = "
           f"{float(pair.pairs['c_diff'].iloc[0]):+.3f} puts it there by the rule of section "
           "2.4. The more complex signal looks like the driver — an arrow is an asymmetry of "
           "recurrence structure, not a cause (docs/guide/direction.md)."
           if str(pair.pairs['kind'].iloc[0]) == "y->x" else ""), {"Fig. 5": pair})
    base = analyses.baseline
    if base is not None and base.networks:
        add(3, "fig9-baseline-phases",
            lambda: paper_figures.figure_phases(base.data, list(base.windows.values()),
                                                base.networks,
                                                title=f"baseline trial {base.trial}"),
            f"Fig. 9 — baseline trial {base.trial}: normalized and raw signals with the "
            "detected phases, and a functional network per phase.")
    cells = analyses.velocity_cells()
    if cells:
        add(4, "fig10-velocity-grid", lambda: paper_figures.figure_velocity_grid(cells),
            "Fig. 10 — velocities (V1, V35, V175, V350; TCP 1.6 m) × phases (fixed windows "
            "of 280 / 600 / 600 ms): normalized series over each network.")
    rev = analyses.example_reversal()
    if rev is not None:
        add(5, "fig11-reversal",
            lambda: paper_figures.figure_reversal(
                rev.data, list(rev.windows.values()),
                {f"{k:+d} ms": v for k, v in rev.networks.items()}, phases=rev.phases,
                title=f"backlash trial {rev.trial}"),
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
        parameters = analyses.parameters
        add(7, "recurrence-cruise",
            lambda: paper_figures.figure_recurrence_plots(
                base.window_data("cruise"), parameters,
                left_out=base.dropped.get("cruise", ())),
            f"Beyond the paper — recurrence plots (RR = {parameters.rr}) of AP, V and AC in "
            f"the baseline cruise window, normalized ({parameters.normalize}) as for the "
            "networks.")
    step(progress, steps, steps, "figures done")
    return parts


#: How each finding is decided, and what the coupling evidence adds, as the page says it.
_RULE_HTML = (
    "<p class=\"verdict\"><b>How each finding is decided</b> (fixed before any result, "
    "the same for every finding): a claimed relation is <i>not evaluable</i> when its "
    "network is missing or lacks one of its signals (a signal constant in a window is left "
    "out of that window's network), or when the pair of its signals has a degenerate "
    "recurrence structure (a signal barely moves in the window, so the arrow is "
    "meaningless). <i>yes</i> — every claimed relation was evaluated and holds; "
    "<i>partly</i> — not <i>yes</i>, but at least one network (or trial) shows all its "
    "claimed relations, or at least half of the evaluated relations hold (this includes "
    "findings whose evaluated relations all hold while others could not be evaluated: the "
    "evidence then says how many of the claims could not be evaluated); <i>no</i> — "
    "relations were evaluated and neither holds; <i>not evaluable</i> — no claimed relation "
    "could be evaluated, so nothing was measured; <i>n/a</i> — not reported by the paper, "
    "measured here. Bidirectional edges (|diff| &lt; μ) mean mutual coupling <i>or no "
    "coupling</i> (paper section 2.4).</p>"
    "<p class=\"note\"><b>Coupling evidence</b> (beyond the paper, funcnet.evidence): for "
    "each claimed relation, the joint-recurrence dependence test on its window (time-shift "
    "surrogates, Benjamini–Hochberg over the window's pairs, α = 0.05) says whether the "
    "two signals are coupled at all, which the paper's arrows cannot. <i>Untestable</i> "
    "is not <i>uncoupled</i>: a shift must exceed the signals' decorrelation time, so the "
    "paper's short robot windows (140–300 samples, 100 around a reversal) hold only a few "
    "surrogates, and with K surrogates no p-value is below 1/(K+1) — above α, the test "
    "cannot reject whatever the data (docs/guide/evidence.md).</p>")

def build_demo_report(
    plan_dir: str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    progress: Progress = None,
    **options: Unpack[AnalysisOptions],
) -> Path:
    """Run the paper's analyses on a plan of simulated trials and write the HTML report.

    Parameters
    ----------
    plan_dir : path-like
        A folder written by :func:`funcnet.sim.write_plan` (traces and ``manifest.csv``).
    out_dir : path-like
        Report folder: ``index.html`` and ``figures/*.png`` are written there.
    progress : callable, optional
        ``progress(done, total, description)``, called as the work advances.
    **options
        Passed to :func:`funcnet.paper.run_paper_analyses`: ``parameters=`` (a
        :class:`~funcnet.parameters.NetworkParameters`), network parameters by name, window
        lengths.

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.

    References
    ----------
    Paper sections 2-4, Figures 1, 2, 5, 9, 10 and 11.
    """
    out = Path(out_dir)
    started = _dt.datetime.now(_dt.UTC)
    analyses = run_paper_analyses(plan_dir, progress=progress, **options)
    # The coupling test on the windows the claims are evaluated on (the test only: ~5 s).
    coupling = claims_coupling(
        analyses, progress=lambda k, n: step(progress, k, n, "coupling evidence"))
    figures = _demo_figures(analyses, out, progress)
    failures = [(t.trial, k, msg) for group in analyses.groups().values()
                for t in group.values() if t is not None for k, msg in t.errors.items()]
    run = provenance({
        "plan folder (from the report)": os.path.relpath(Path(plan_dir).resolve(), out.resolve()),
        "analysis time [s]": f"{analyses.elapsed:.1f}",
    }, date=started)
    toc = [("findings", "Findings: summary and rule"), ("figures", "Figures"),
           ("findings-table", "Findings, one by one"), ("problems", "Problems flagged"),
           ("parameters", "Parameters"), ("trials", "Trials"),
           ("networks", "Networks (pairs tables)"), ("provenance", "Provenance")]
    summary, details = _findings_html(analyses.findings, coupling)
    body = [
        "<h1>funcnet — the paper's analyses on the simulated axis</h1>",
        "<section id=\"findings\"><h2>Findings of the paper's section 4: summary</h2>",
        summary, _RULE_HTML,
        "<p class=\"note\">All data here are simulated (funcnet's two-mass axis model, the "
        "paper's Table 1 plan), not the paper's robot recordings. Every verdict is measured on "
        "the networks computed from these traces with the parameters listed; nothing was tuned "
        "towards the paper's results. Read an arrow with care: the asymmetry of "
        "cross-clustering and cross-transitivity follows the relative complexity of two "
        "signals as well as their coupling, and the positions here are smooth while the "
        "currents are noisy (paper section 2.4; docs/guide/direction.md).</p></section>",
        contents(toc),
        "<h2 id=\"figures\">Figures</h2>", *figures,
        "<section id=\"findings-table\"><h2>Findings, one by one</h2>", details, "</section>",
        "<section id=\"problems\"><h2>Problems flagged</h2>", _problems_html(analyses),
        "</section>",
        "<section id=\"parameters\"><h2>Parameters</h2>",
        mapping_table(analyses.parameters.to_dict(), "parameter"),
        mapping_table(analyses.settings, "choice"), "</section>",
        "<section id=\"trials\"><h2>Trials</h2>", table(analyses.trials), "</section>",
        "<section id=\"networks\"><h2>Networks (pairs tables)</h2>",
        *(_network_tables(title, group) for title, group in analyses.groups().items()),
        "</section>",
    ]
    dropped = [(t.trial, t.windows[k].label if k in t.windows else k, ", ".join(signals))
               for group in analyses.groups().values() for t in group.values()
               for k, signals in t.dropped.items()]
    if failures:
        body += ["<h2>Windows without a network</h2>",
                 table(pd.DataFrame(failures, columns=["trial", "window", "reason"]))]
    if dropped:
        body += ["<h2>Signals left out of a window (constant there)</h2>",
                 "<p>Min–max normalization needs a range; claims about these signals in these "
                 "windows are counted as not evaluable.</p>",
                 table(pd.DataFrame(dropped, columns=["trial", "window", "signals"]))]
    body += ["<section id=\"provenance\"><h2>Provenance</h2>", mapping_table(run, "item"),
             "<details><summary>Inputs (SHA-256)</summary>",
             mapping_table(analyses.inputs, "file", "sha256"), "</details></section>"]
    index = write_text_atomic(out / "index.html", page("funcnet demo report", body))
    step(progress, 1, 1, "report written")
    return index
