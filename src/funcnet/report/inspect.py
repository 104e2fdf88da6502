"""The engineer's report of a controller trace: "here is a trace of my axis: what is it doing?".

:func:`write_inspections` writes, for each trace :func:`funcnet.inspection.inspect_files` read
and inspected, one HTML page that reads from the top: a plain summary of the motion (moves,
phases with their times, speeds, peak currents, following error, lost motion at the direction
changes where both encoders exist), then the functional network of every phase of every move
with its evidence, the edge timeline, the backlash diagnosis, and what an arrow does and does
not say. Several traces get an index page. This module only draws: the computation is
:func:`funcnet.inspection.inspect_recording` (a :class:`~funcnet.inspection.TraceInspection`);
:func:`write_inspection` renders it. A file of several axes read without ``axis`` is
:func:`funcnet.inspection.inspect_robot`'s, rendered by :func:`write_robot_inspection`: the
robot's page (a summary per axis, the robot network with its nodes grouped per axis and its
pairs told apart within and between axes) and each axis's own page in ``axis-N/``.
:func:`inspect_trace` is the two steps in one call.

The figures are in :mod:`funcnet.report.inspect_figures`, the summary's words in
:mod:`funcnet.report.inspect_text`. A recording with gaps (missing values) is said to have them
where the summary says how long it is, on the trace's page and the robot's.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2.4
   (reading an edge), 3.3-3.4 (preprocessing, parameters) and 4 (phases).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Unpack

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.inspection import TraceInspection
from funcnet.inspection.robot import RobotInspection
from funcnet.inspection.run import FileInspections, inspect_files
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides
from funcnet.report.html import (
    Progress,
    contents,
    escape,
    figure_html,
    mapping_table,
    page,
    page_processes,
    pairs_table,
    provenance,
    setpoint_html,
    step,
    table,
)
from funcnet.report.inspect_figures import (
    ARROWS,
    evidence_informs,
    figure_evidence,
    figure_lost_motion,
    figure_motion,
    figure_networks,
    figure_timeline,
)
from funcnet.report.inspect_text import (
    clock_items,
    converted_sentence,
    failed_windows,
    gaps_sentence,
    lost_motion_cell,
    moves_shown,
    partial_evidence,
    scale_of,
    summary_html,
    time_sentence,
)
from funcnet.report.repetitions_page import write_repetitions
from funcnet.report.robot_figures import figure_robot_matrix
from funcnet.report.robot_summary import axis_findings, evidence_sentence, scope_counts
from funcnet.robot.grid import format_spans

__all__ = ["inspect_trace", "write_inspections", "write_inspection", "write_robot_inspection",
           "READING_AN_ARROW"]

#: What the report says about reading an arrow (paper section 2.4; docs/guide/direction.md).
READING_AN_ARROW = (
    "An arrow X → Y says that the recurrences of X are more often shared by Y than the other "
    "way round (C_diff, T_diff of Eq. 10 at or above μ). It follows the relative complexity of "
    "the two signals as well as their coupling: a smooth signal (a position set-point) tends "
    "to look driven by a rough one (a measured current) even where physics says the opposite. "
    "Read an arrow as 'these two signals share structure, asymmetrically', not as cause. A red "
    "(bidirectional) edge means |diff| < μ: mutual coupling or no coupling at all. Where the "
    "evidence columns are shown, 'coupled' means the joint-recurrence test rejected "
    "independence (time-shift surrogates, Benjamini-Hochberg across the pairs), "
    "'coupled-directed' that the direction index agrees, 'asymmetry-only' that the arrow "
    "stands on an asymmetry the dependence test could not tell from chance, 'not-coupled' "
    "that the test found nothing, and 'untestable' that the window left the test too few "
    "surrogates to reject whatever the data (evidence_reason says how few): an untestable "
    "pair is neither coupled nor uncoupled, only unread. Compare arrows between phases of the "
    "same trace, not between traces with other signals or parameters."
)

# --------------------------------------------------------------------------------------------
# the page


def _fmt(value: Any, digits: int = 3) -> str:
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def _backlash_html(ins: TraceInspection) -> str:
    result = ins.backlash
    if result is None:
        return f"<p>No diagnosis: {escape(ins.backlash_error or 'not asked for')}.</p>"
    from funcnet.diagnosis.diagnose import MODEL_NOTE

    scale = scale_of(ins)
    rows = [{"change": r.change.kind, "stop [s]": r.change.stop, "start [s]": r.change.start,
             "dwell [s]": r.change.dwell, "direction": "+" if r.change.direction > 0 else "−",
             f"lost motion [{scale.fine}]": lost_motion_cell(r.lost_motion, r.lost_motion_high,
                                                             scale.fine_factor),
             "backlash score": _fmt(r.backlash_score)} for r in result.reversals]
    reading = result.reading.get("text", "") if result.reading else ""
    return (f"<p>{escape(result.message)}.{' ' + escape(reading) if reading else ''}</p>"
            f"<p class=\"note\">The score is {escape(MODEL_NOTE)}.</p>"
            + (table(pd.DataFrame(rows)) if rows else ""))


#: A reason longer than this, given for more than one pair, is said once below the tables.
_LONG_REASON = 60


def _shared_reasons(ins: TraceInspection) -> dict[str, int]:
    """The long evidence reasons the page's pairs share, numbered in order of appearance."""
    seen: dict[str, int] = {}
    for net in ins.networks.values():
        if "evidence_reason" in net.pairs.columns:
            for reason in net.pairs["evidence_reason"].dropna().astype(str):
                if len(reason) > _LONG_REASON:
                    seen[reason] = seen.get(reason, 0) + 1
    return {reason: k + 1 for k, reason in enumerate(r for r, n in seen.items() if n > 1)}


def _network_tables(ins: TraceInspection) -> str:
    parts = []
    notes = _shared_reasons(ins)
    where: dict[str, list[str]] = {reason: [] for reason in notes}
    errors = failed_windows(ins, "network")
    partial = {f.window: f.part for f in ins.failures if f.part != "network"}
    for w in ins.windows:
        net = ins.networks.get(w.label)
        span = f"{w.start:.3f}–{w.stop:.3f} s"
        if net is None:
            parts.append(f"<p><b>{escape(w.label)}</b> ({span}): no network — "
                         f"{escape(errors.get(w.label, ''))}</p>")
            continue
        dropped = net.window.get("dropped") if net.window else ()
        note = f"; left out (constant): {', '.join(dropped)}" if dropped else ""
        if w.label in partial:
            note += f"; without its {partial[w.label]} (too short: see problems)"
        columns = [c for c in ("x", "y", "kind", "direction", "weight", "c_diff", "t_diff",
                               "degenerate", "evidence", "coupling_p", "surrogates",
                               "c_diff_low", "c_diff_high", "evidence_reason")
                   if c in net.pairs.columns]  # direction_reason stays in the files
        frame = net.pairs[columns].assign(kind=net.pairs["kind"].map(
            lambda k: f"{ARROWS.get(k, '')} {k}"))
        if notes and "evidence_reason" in frame.columns:
            for x, y, reason in zip(frame["x"], frame["y"], frame["evidence_reason"],
                                    strict=True):
                if reason in notes:
                    where[reason].append(f"{w.label} {x}–{y}")
            frame["evidence_reason"] = frame["evidence_reason"].map(
                lambda r: f"note {notes[r]} below" if r in notes else r)
        parts.append(f"<details><summary>{escape(w.label)} ({span}, {net.n_samples} samples"
                     f"{escape(note)})</summary>{table(frame)}</details>")
    if notes:  # a long reason several pairs share: said once, with the pairs it is for
        items = "".join(f"<li>{escape(reason)} ({escape(', '.join(where[reason]))}).</li>"
                        for reason in notes)
        parts.append("<p>The evidence_reason several pairs share, said once:</p>"
                     f"<ol class=\"notes\">{items}</ol>")
    return "".join(parts)


def _trace_sections(ins: TraceInspection, out: Path, progress: Progress) -> list[str]:
    """The body of one trace's page (figures written to ``out/figures``)."""
    steps = 6
    figures: list[tuple[str, str, str]] = []  # (section id, title, html)

    def add(k: int, name: str, make: Any, caption: str) -> None:
        step(progress, k, steps, f"figure: {name}")
        if not ins.networks and name in ("networks", "timeline", "evidence"):
            return  # no network (an axis at rest): the summary says why
        fig = make(ins)
        if fig is not None:
            figures.append((name, caption, figure_html(out, name, fig, caption)))

    add(0, "motion", figure_motion,
        "Figure 1 — the motion. Top: the set-point RP over the whole trace, the moves named. "
        + ("Below, each move zoomed: positions, " if len(ins.moves)
           else "Below, the whole trace (the axis never moves): positions, ")
        + ("measured speed V" if "V" in ins.recording.roles
           else "arm-side speed V (Eq. 11–12 on AP)") + ", current AC "
        "and following error RP − AP. Shading: the detected phase (same colour for the same "
        "kind of phase in every figure)" + ("; dark grey: a gap, where values are missing."
                                            if ins.gaps else "."))
    add(1, "networks", figure_networks,
        "Figure 2 — the functional network of every phase window (rows: moves; columns: "
        "phases; where a move repeats a phase, every window its own panel in time order), "
        "each node at the same place in every panel. Black arrow: the direction "
        "reading X → Y (X's past improves Y's prediction, Y's does not improve X's); pale "
        "line: undecided (the pairs table's direction_reason says why); width ∝ weight "
        "(Eq. 13); no line: a degenerate pair. The rule's arrows (kind) are in the pairs "
        "tables and Figures 3–4.")
    add(2, "timeline", figure_timeline,
        "Figure 3 — edge timeline: every pair's edge kind (marker) and weight (area) in each "
        "window, windows in time order and equally spaced, shaded by phase. A pair that keeps "
        "its arrow across the moves is a property of the axis; one that flips between moves "
        "of the same kind is not to be read.")
    if not ins.networks or evidence_informs(ins):
        add(3, "evidence", figure_evidence,
            "Figure 4 — pairs × windows: the arrow of each pair (→ X → Y, ← Y → X, ↔ "
            "bidirectional, × conflict, – left out), the cell coloured by what the evidence says "
            "about it" + (" (coupling test and direction index of funcnet.evidence). A "
                          "near-white cell with a grey arrow is untestable: its window left the "
                          "test too few surrogates to reject at α whatever the data; the arrow "
                          "is the rule's, not a finding." if ins.evidence
                          else " (evidence not computed: coloured by kind)."))
    else:  # every cell untestable: the figure would repeat Figure 3's arrows in grey
        step(progress, 3, steps, "figure: evidence")
        figures.append(("evidence", "", "<figure><figcaption>Figure 4 (pairs × windows, each "
                        "cell coloured by its evidence) is not drawn: every pair of every window "
                        "is untestable, its window leaving the test too few surrogates to reject "
                        "at α whatever the data. Its arrows would be the rule's of Figure 3, not "
                        "findings.</figcaption></figure>"))
    add(4, "lost-motion", figure_lost_motion,
        f"Figure 5 — motor minus arm position (MP − AP, {scale_of(ins).fine}) around the start "
        "of the move "
        "after each direction change; the dotted line is where the set-point starts it. The "
        "jump in MP − AP while the motor turns and the arm waits is the lost motion (backlash "
        "plus elastic windup) the table below lists. At a direction change in continuous motion "
        "(the arm never waits) the panel shows MP − AP less the gear's fitted wind-up and the "
        "encoders' skew, the dotted line at the set-point's turn; the black bars are its means "
        "over the stretches before and after the turn, and their difference is the reversal "
        "error listed.")
    step(progress, steps, steps, "figures done")
    return [f"<section id=\"{name}\">{html}</section>" for name, _, html in figures]


def _provenance(ins: TraceInspection | RobotInspection, **items: str) -> dict[str, Any]:
    clock = clock_items(ins.recording)
    return {"trace": Path(ins.source).name,
            **provenance({**clock, "computation time [s]": f"{ins.elapsed:.1f}", **items})}


def write_inspection(
    inspection: TraceInspection,
    out_dir: str | os.PathLike[str],
    *,
    progress: Progress = None,
    axis_label: str | None = None,
) -> Path:
    """Write the HTML page of one inspected trace (``index.html``, ``figures/*.png``).

    Parameters
    ----------
    inspection : TraceInspection
    out_dir : path-like
        The page's folder.
    progress : callable, optional
        ``progress(done, total, description)``.
    axis_label : str, optional
        The axis as the channel map names it (``"axis 2 (shoulder)"``), in the title.

    Returns
    -------
    pathlib.Path
        The path of ``index.html``.
    """
    ins = inspection
    out = Path(out_dir)
    figures = _trace_sections(ins, out, progress)
    name = Path(ins.source).name
    sections = [("summary", "Summary"), ("figures", "Figures"), ("arrows", "Reading an arrow"),
                ("backlash", "Backlash and lost motion"), ("phases", "Moves and phases"),
                ("problems", "Problems flagged"), ("networks", "Pairs tables"),
                ("parameters", "Parameters and provenance")]
    problems = ins.problems
    problem_html = ("<p>None: every pair of every window has ordered thresholds, its target "
                    "rates and a non-degenerate structure.</p>") if problems.empty else (
        "<p>Each problem once, with the windows that have it (flags of the pairs tables; "
        "<code>eps_order</code>: ε_XY is not below ε_X and ε_Y, section 2.2; "
        "<code>rate_exceeded</code>: ties pushed a rate above its target; "
        "<code>degenerate</code>: too few distinct states, no edge drawn).</p>"
        + table(problems))
    errors, partial = failed_windows(ins, "network"), partial_evidence(ins)
    if errors:
        problem_html += table(pd.DataFrame({"window": list(errors),
                                            "why no network": list(errors.values())}))
    if len(partial):
        problem_html += ("<p>Windows too short for part of their evidence, which is left out "
                         "of their pairs tables (<code>intervals</code>: the asymmetry "
                         "intervals, whose subsamples are shorter than the window; "
                         "<code>evidence</code>: all of it).</p>" + table(partial))
    body = [
        f"<h1>What {escape(axis_label or 'the axis')} does — {escape(name)}</h1>",
        setpoint_html(ins.networks),
        f"<section id=\"summary\"><h2>Summary</h2>{summary_html(ins)}</section>",
        contents(sections),
        "<h2 id=\"figures\">Figures</h2>", *figures,
        f"<section id=\"arrows\"><h2>Reading an arrow</h2><p>{escape(READING_AN_ARROW)}</p>"
        "</section>",
        f"<section id=\"backlash\"><h2>Backlash and lost motion</h2>{_backlash_html(ins)}"
        "</section>",
        "<section id=\"phases\"><h2>Moves and phases</h2>",
        table(moves_shown(ins)) if len(ins.moves)
        else "<p>No move.</p>",
        "<details><summary>every phase</summary>",
        table(ins.phases[["phase", "move", "start", "stop", "duration"]].rename(
            columns={c: f"{c} [s]" for c in ("start", "stop", "duration")})),
        "</details></section>",
        f"<section id=\"problems\"><h2>Problems flagged</h2>{problem_html}</section>",
        f"<section id=\"networks\"><h2>Pairs tables</h2>{_network_tables(ins)}</section>",
        "<section id=\"parameters\"><h2>Parameters and provenance</h2>",
        mapping_table(ins.parameters.to_dict(), "parameter"),
        mapping_table(_provenance(ins), "item"), "</section>",
    ]
    return write_text_atomic(out / "index.html", page(f"funcnet inspect — {name}", body))


# --- a recording of several axes: the robot's page and one page per axis


def _findings_html(ins: RobotInspection, axis_names: tuple[str, ...] = ()) -> str:
    """The per-axis table, each axis linked to its page, and its notes said once."""
    found = axis_findings(ins.axes, ins.axis_errors, tuple(ins.recording.axes), ins.source)
    frame = found.table.copy()
    if axis_names:
        frame.insert(1, "name", [axis_names[int(a) - 1] if int(a) <= len(axis_names) else ""
                                 for a in frame["axis"]])
    html_table = table(frame)
    for axis in ins.axes:  # the axis's number links to its own page
        html_table = html_table.replace(
            f"<tr><td>{axis}</td>", f'<tr><td><a href="axis-{axis}/index.html">{axis}</a></td>',
            1)
    items = "".join(
        f"<li>{escape(text)} ({'axis' if len(axes) == 1 else 'axes'} "
        f"{', '.join(map(str, axes))}).</li>" for text, axes in found.notes)
    return html_table + (f"<ol class=\"notes\">{items}</ol>" if items else "")


def _figure(ins: RobotInspection, label: str) -> Any:
    net = ins.networks[label]
    return figure_robot_matrix(net, label, arrows="direction" if "direction" in net.pairs.columns
                               else "rule")


def write_robot_inspection(
    inspection: RobotInspection,
    out_dir: str | os.PathLike[str],
    *,
    progress: Progress = None,
    axis_names: tuple[str, ...] = (),
) -> Path:
    """Write the robot's page (``index.html``) and each axis's page (``axis-N/index.html``).

    Parameters
    ----------
    inspection : RobotInspection
    out_dir : path-like
    progress : callable, optional
        ``progress(done, total, description)``.
    axis_names : tuple of str, optional
        The axes' names, axis 1 first (the channel map's ``axis_names``), on the pages.

    Returns
    -------
    pathlib.Path
        The robot's ``index.html``.
    """
    ins = inspection
    out = Path(out_dir)

    def axis_label(axis: int) -> str:
        return f"axis {axis}" + (f" ({axis_names[axis - 1]})" if axis <= len(axis_names) else "")

    pages = [(one, out / f"axis-{axis}", axis_label(axis) if axis_names else None)
             for axis, one in ins.axes.items()]
    with page_processes(len(pages)) as pool:
        # the axes' pages drawn beside this one (each page's figures are its own), the most
        # windows first: the last page to start is a short one
        written = [pool.submit(write_inspection, one, folder, axis_label=label)
                   for one, folder, label in sorted(pages, key=lambda page: -len(page[0].networks))
                   ] if pool is not None else []
        robot = _write_robot_page(ins, out, axis_names)
        if pool is None:
            for one, folder, label in pages:
                write_inspection(one, folder, progress=progress, axis_label=label)
        for k, page in enumerate(written):
            page.result()
            step(progress, k + 1, len(written), "axis pages")
    return robot


def _write_robot_page(ins: RobotInspection, out: Path, axis_names: tuple[str, ...]) -> Path:
    """The robot's own page (``out/index.html``): its axes' findings and its network."""
    findings = _findings_html(ins, axis_names)
    gaps = gaps_sentence(ins.recording.gaps, ins.recording.segments)
    gaps += " The robot network is one per segment." if gaps else ""
    units = converted_sentence(ins.recording.signals)
    name = Path(ins.source).name
    network_parts = [f"<p>{escape(ins.windows_note)}</p>"] if ins.windows_note else []
    for k, window in enumerate(ins.windows):
        label = window.label
        if label not in ins.networks:
            why = [f.message for f in ins.failures if f.window == label and f.part == "network"]
            network_parts.append(f"<p>{escape(label)}: no network ({escape('; '.join(why))})"
                                 "</p>")
            continue
        pairs = ins.pairs[label]
        caption = (f"The robot network of {label} as a matrix: row X, column Y, the axes in "
                   "blocks (on the diagonal: within an axis; off it: between two axes), each "
                   "block's signals in the same order. Blue: the direction reading X → Y "
                   "(X's past improves Y's prediction; row → column), an undecided pair "
                   "empty; darker: heavier (Eq. 13); a dot: the coupling test rejects "
                   "independence. The rule's kinds are in the pairs tables.")
        network_parts.append(figure_html(out, f"robot-network-{k + 1}", _figure(ins, label),
                                         caption))
        drawn = (ins.networks[label].evidence or {}).get("resamples", 1) != 0
        network_parts.append(f"<p>{escape(scope_counts(pairs))}."
                             f"{evidence_sentence(pairs, intervals=drawn)}</p>")
        shown = pairs_table(pairs)
        scope = table(pairs[["x", "y", "axis_x", "axis_y", "scope", "kind", "weight"]])
        network_parts.append("<details><summary>pairs with their scope</summary>" + scope
                             + "</details><details><summary>every column</summary>" + shown
                             + "</details>")
    body = [
        f"<h1>What the robot does — {escape(name)}</h1>",
        setpoint_html(ins.networks),
        f"<section id=\"axes\"><h2>Each axis</h2><p>{len(ins.recording.axes)} axes, "
        f"{escape(time_sentence(ins.recording))}. "
        f"{escape(gaps + ' ' if gaps else '')}{escape(units + ' ' if units else '')}"
        "An axis's number opens its own report "
        "(moves, a network per phase, evidence, backlash). Peaks are over the moves; the lost "
        "motion is the mean over the direction changes, ≤ a bound where the data do not "
        "resolve it.</p>"
        f"{findings}</section>",
        "<section id=\"robot\"><h2>The robot as one network</h2>",
        f"<p>Nodes: {escape(', '.join(ins.signals))}.</p>", *network_parts, "</section>",
        f"<section id=\"arrows\"><h2>Reading an arrow</h2><p>{escape(READING_AN_ARROW)}</p>"
        "</section>",
        "<section id=\"parameters\"><h2>Parameters and provenance</h2>",
        mapping_table(ins.parameters.to_dict(), "parameter"),
        mapping_table(_provenance(ins, segments=format_spans(
            ins.recording.segments)), "item"), "</section>",
    ]
    return write_text_atomic(out / "index.html", page(f"funcnet inspect — {name}", body))


def _slug(path: Path, taken: set[str]) -> str:
    base = "".join(ch if ch.isalnum() or ch in "-_" else "-" for ch in path.stem) or "trace"
    slug, k = base, 1
    while slug in taken:
        k += 1
        slug = f"{base}-{k}"
    taken.add(slug)
    return slug


def write_inspections(
    inspections: FileInspections,
    out_dir: str | os.PathLike[str] = "inspect",
    *,
    progress: Progress = None,
) -> Path:
    """Write the engineer's report of each inspected trace (and an index for several).

    Parameters
    ----------
    inspections : FileInspections
        :func:`funcnet.inspection.inspect_files`' (each page is written before the next file
        is read).
    out_dir : path-like
        One trace: ``out_dir/index.html``; several: a folder per trace (named after the file)
        and an ``index.html`` linking them; a robot: its page and one per axis
        (:func:`write_robot_inspection`); ``repeated``: also ``repeated.html``.
    progress : callable, optional
        ``progress(done, total, description)``.

    Returns
    -------
    pathlib.Path
        The page to open first.
    """
    out = Path(out_dir)
    cmap, axis = inspections.channels, inspections.axis

    def write(found: TraceInspection | RobotInspection, folder: Path) -> None:
        if isinstance(found, RobotInspection):
            write_robot_inspection(found, folder, progress=progress, axis_names=cmap.axis_names)
        else:
            write_inspection(found, folder, progress=progress,
                             axis_label=cmap.axis_label(axis)
                             if axis is not None and cmap.axis_names else None)

    if len(inspections.paths) == 1:
        for _, single in inspections:
            write(single, out)
        if inspections.repeated:
            write_repetitions(inspections.repetitions(), out)
        return out / "index.html"
    taken: set[str] = set()
    rows = []
    for path, ins in inspections:
        slug = _slug(path, taken)
        write(ins, out / slug)
        if isinstance(ins, RobotInspection):  # the axes' moves and diagnoses are on its page
            duration, moves = f"{ins.recording.duration:.1f}", ""
            networks, backlash = len(ins.networks), f"{len(ins.axes)} axes: see its page"
        else:
            duration, moves = f"{ins.duration:.1f}", str(len(ins.moves))
            networks = len(ins.networks)
            backlash = ins.backlash.message if ins.backlash else ins.backlash_error
        rows.append(f"<tr><td><a href=\"{escape(slug)}/index.html\">{escape(path.name)}</a>"
                    f"</td><td class=\"num\">{duration}</td><td class=\"num\">"
                    f"{moves}</td><td class=\"num\">{networks}</td><td>"
                    f"{escape(backlash)}</td></tr>")
    index = ("<h1>funcnet inspect — traces</h1><table><thead><tr><th>trace</th>"
             "<th>duration [s]</th><th>moves</th><th>networks</th><th>backlash</th></tr>"
             f"</thead><tbody>{''.join(rows)}</tbody></table>")
    if inspections.repeated:
        write_repetitions(inspections.repetitions(), out)
        index += "<p><a href=\"repeated.html\">The repetitions of the traces together</a></p>"
    return write_text_atomic(out / "index.html", page("funcnet inspect", [index]))


def inspect_trace(
    *paths: str | os.PathLike[str],
    out_dir: str | os.PathLike[str] = "inspect",
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    channels: Any = None,
    axis: int | None = None,
    progress: Progress = None,
    evidence_options: EvidenceSettings | None = None,
    repeated: bool = False,
    **overrides: Unpack[ParameterOverrides],
) -> Path:
    """Read traces and write the engineer's report of each (and an index for several).

    The two steps of ``funcnet inspect`` in one call: :func:`funcnet.inspection.inspect_files`
    reads and inspects, :func:`write_inspections` draws.

    Parameters
    ----------
    *paths : path-like
        Trace files (SINUMERIK XML, CSV, Parquet, MATLAB, HDF5:
        :func:`funcnet.robot.read_trace`).
    out_dir : path-like
        The report folder (:func:`write_inspections`).
    signals, parameters, evidence, channels, axis, progress, evidence_options, repeated
        As :func:`funcnet.inspection.inspect_files`. A file of several axes without ``axis``
        gets the robot's page and one page per axis; ``signals`` then names the robot
        network's nodes (``A1.RP``, ...). ``repeated`` adds ``out_dir/repeated.html``: per
        phase the repetition evidence, or how many repetitions a decision needs.
    **overrides
        Network parameters by name.

    Returns
    -------
    pathlib.Path
        The page to open first.

    Raises
    ------
    ParameterError
        No trace, or a bad parameter (before any file is read).
    TraceError
        A file cannot be read.

    Examples
    --------
    >>> inspect_trace(out_dir="x")
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: paths must name at least one trace file
    """
    inspections = inspect_files(*paths, channels=channels, axis=axis, signals=signals,
                                parameters=parameters, evidence=evidence, progress=progress,
                                evidence_options=evidence_options, repeated=repeated,
                                **overrides)
    return write_inspections(inspections, out_dir, progress=progress)
