"""The words of the inspect pages (:mod:`funcnet.report.inspect`): the summary of a trace.

What the page says first, from a :class:`~funcnet.inspection.TraceInspection`: how long the
trace is, where values are missing (its gaps and segments), how the axis moves and turns, the
peak speed, current and following error, the lost motion, how many phase windows have their
network and evidence, and which windows lack one or a part of it. The figures are in
:mod:`funcnet.report.inspect_figures`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from funcnet.inspection import TraceInspection
from funcnet.report.html import escape
from funcnet.robot.grid import format_spans

__all__ = ["summary_html", "gaps_sentence", "converted_sentence", "failed_windows",
           "partial_evidence", "lost_motion_cell", "time_sentence", "scale_of", "moves_shown",
           "clock_items"]


def scale_of(ins: TraceInspection) -> Any:
    """The :class:`~funcnet.robot.units.AxisScale` of the inspected axis (deg or mm)."""
    from funcnet.robot.units import axis_scale, position_unit

    return axis_scale(position_unit(ins.recording.signals))


def time_sentence(recording: Any) -> str:
    """How long a recording is and how often it samples, with the file's clock where its time
    was read from the recording's start.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> import pandas as pd
    >>> rec = S(data=pd.DataFrame(index=[0.0, 0.001, 0.002]), sample_period=0.001,
    ...         time_origin=107742.743, time_unit="us", start_time=None)
    >>> print(time_sentence(rec))
    0.002 s sampled every 1 ms (time from the log's start; its clock, in us, read 107742.743 s there)
    """  # noqa: E501
    index = recording.data.index
    span = float(index[-1] - index[0]) if len(index) else 0.0
    text = f"{span:.4g} s sampled every {recording.sample_period * 1e3:g} ms"
    if recording.time_origin:
        unit = f", in {recording.time_unit}," if recording.time_unit else ""
        at = recording.start_time or f"{recording.time_origin:.9g} s"
        text += f" (time from the log's start; its clock{unit} read {at} there)"
    return text


def gaps_sentence(gaps: Sequence[tuple[float, float]], segments: Sequence[tuple[float, float]],
                  spanned: str = "no window") -> str:
    """Where values are missing: each gap (start-end, its length) and the segments between.

    Parameters
    ----------
    gaps, segments : sequence of (float, float)
        Spans in seconds (:attr:`funcnet.robot.Recording.gaps`, ``.segments``).
    spanned : str
        What never spans a gap, as the sentence names it.

    Returns
    -------
    str
        One sentence; "" without gaps.

    Examples
    --------
    >>> gaps_sentence([(3.5, 3.8)], [(0.0, 3.5), (3.8, 8.0)])
    'Values are missing in 1 gap, 3.5-3.8 s (0.3 s): the recording is read as 2 segments, 0-3.5 s and 3.8-8 s, and no window spans a gap.'
    >>> gaps_sentence([], [(0.0, 8.0)])
    ''
    """  # noqa: E501
    if not gaps:
        return ""
    listed = ", ".join(f"{format_spans([gap])} ({round(gap[1] - gap[0], 9):g} s)"
                       for gap in gaps)
    parts = [format_spans([segment]) for segment in segments]
    between = ", ".join(parts[:-1]) + " and " + parts[-1] if len(parts) > 1 else "".join(parts)
    return (f"Values are missing in {len(gaps)} gap{'s' if len(gaps) > 1 else ''}, {listed}: "
            f"the recording is read as {len(segments)} segment{'s' if len(parts) > 1 else ''}, "
            f"{between}, and {spanned} spans a gap.")


def _cut_moves_sentence(ins: TraceInspection) -> str:
    """The moves a gap cuts: only the part recorded is summarized."""
    if "cut by a gap" not in ins.moves:
        return ""
    cut = ins.moves[ins.moves["cut by a gap"] != ""]
    if not len(cut):
        return ""
    listed = ", ".join(f"move {move} ({gap})"
                       for move, gap in zip(cut["move"], cut["cut by a gap"], strict=True))
    return f"A gap cuts {listed}: distance and peaks are those of the part recorded."


def _turns_sentence(ins: TraceInspection) -> str:
    """How often the set-point changes direction, and where."""
    across = ins.turns_across_gaps
    if not ins.turns and not across:
        return "It never changes direction." if len(ins.moves) else ""
    within = int(ins.moves["direction changes"].sum()) if len(ins.moves) else 0
    times = ", ".join(f"{turn.time:.2f}" for turn in ins.turns)
    # where the set-point turns across a gap is not recorded: only the gaps it turns across
    spanned = [[g for g in ins.gaps if stop <= g[0] and g[1] <= start] for stop, start in across]
    gaps = "; ".join(f"the gap{'s' if len(g) > 1 else ''} {format_spans(g)}" for g in spanned)
    parts = [f"{within} within a move (no rest at the turn)" if within else "",
             f"{len(ins.turns) - within} after a rest" if len(ins.turns) > within else "",
             f"{len(across)} across a gap (it turns across {gaps})" if across else ""]
    return (f"It changes direction {len(ins.turns) + len(across)} time(s)"
            + (f", at {times} s" if times else "") + ": " + ", ".join(p for p in parts if p)
            + ".")


def _position_unit(ins: TraceInspection) -> str:
    """``"deg"``, ``"mm"`` (a linear axis), or ``"unknown"`` where no unit is stated."""
    return str(scale_of(ins).position)


def _units_facts(ins: TraceInspection) -> list[str]:
    """One line for signals converted to degrees, one for positions of unknown unit."""
    from funcnet.robot.units import UNKNOWN, unit_of

    signals = ins.recording.signals
    converted = [f"{c} ({i.converted_from})" for c, i in signals.items() if i.converted_from]
    unknown = [c for c in ("RP", "AP", "MP") if c in signals and unit_of(signals[c]) == UNKNOWN]
    facts = []
    if converted:
        facts.append(f"converted to {_targets(signals)} from the unit the file holds: "
                     + ", ".join(converted))
    if unknown:
        facts.append(f"no unit stated for {', '.join(unknown)}: computed as if degrees "
                     "(thresholds of 1 deg/s), shown without a unit")
    return facts


def converted_sentence(signals: Mapping[str, Any]) -> str:
    """The signals of a robot's recording converted to degrees, said once for all its axes.

    Parameters
    ----------
    signals : mapping of str to SignalInfo
        The recording's signals by column (``A1.RP``, ...), each with ``converted_from``.

    Returns
    -------
    str
        ``""`` when nothing was converted; else one sentence naming each converted signal with
        the unit the file holds and the axes it was converted on.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> converted_sentence({"A1.RP": S(converted_from="rad"), "A2.RP": S(converted_from="rad"),
    ...                     "A1.V": S(converted_from="rad/s"), "A1.AC": S(converted_from=None)})
    ... # doctest: +NORMALIZE_WHITESPACE
    'Converted to degrees (deg/s) from the unit the file holds: RP (rad) on axes 1, 2;
     V (rad/s) on axis 1.'
    >>> converted_sentence({"A1.RP": S(converted_from=None)})
    ''
    """
    from funcnet.robot.axes import split_qualified

    axes_of: dict[tuple[str, str], list[int | None]] = {}
    for column, info in signals.items():
        if info.converted_from:
            axis, role = split_qualified(column)
            axes_of.setdefault((role, info.converted_from), []).append(axis)
    if not axes_of:
        return ""
    every = {tuple(a) for a in axes_of.values()}

    def where(axes: list[Any]) -> str:
        numbered = [str(a) for a in axes if a is not None]
        if not numbered:
            return ""
        return f" on axis {numbered[0]}" if len(numbered) == 1 else (
            f" on axes {', '.join(numbered)}")

    target = _targets(signals)
    if len(every) == 1:  # the same on every axis: the list once, then the axes
        listed = ", ".join(f"{role} ({unit})" for role, unit in axes_of)
        return (f"Converted to {target} from the unit the file holds: "
                f"{listed}{where(next(iter(axes_of.values())))}.")
    listed = "; ".join(f"{role} ({unit}){where(axes)}" for (role, unit), axes in axes_of.items())
    return f"Converted to {target} from the unit the file holds: {listed}."


def _targets(signals: Mapping[str, Any]) -> str:
    """``"degrees (deg/s)"``, ``"mm (mm/s)"`` or both: the units converted signals now hold."""
    units = {str(getattr(i, "unit", None) or "deg") for i in signals.values()
             if getattr(i, "converted_from", None)}
    lengths = any(u.startswith("mm") for u in units)
    angles = any(not u.startswith("mm") for u in units)
    return " and ".join((["degrees (deg/s)"] if angles else []) + (["mm (mm/s)"] if lengths
                                                                    else []))


def _rest_facts(ins: TraceInspection) -> list[str]:
    """What a recording whose set-point never moves measured at rest."""
    from funcnet.robot.units import UNKNOWN, unit_of

    data, signals = ins.recording.data, ins.recording.signals
    scale = scale_of(ins)
    facts = ["the set-point never moves: the axis rests over the whole recording, so it has no "
             "phase, network or direction change to read; what it measured at rest:"]
    if "AP" in data and "RP" in data:
        error = (data["RP"] - data["AP"]).abs()
        spread = float(data["AP"].max() - data["AP"].min())
        k, unit = scale.fine_factor, scale.fine
        facts.append(
            f"|RP − AP| {error.mean() * k:.3g} {unit} on average, at most "
            f"{error.max() * k:.3g} {unit}; AP spans {spread * k:.3g} {unit}"
            if scale.position != UNKNOWN
            else f"|RP − AP| {error.mean():.3g} on average, at most {error.max():.3g}; AP "
            f"spans {spread:.3g} (the position's unit is unknown)")
    for column in ("RC", "AC"):
        if column in data:
            unit = unit_of(signals[column])
            unit = "" if unit == UNKNOWN else f" {unit}"
            facts.append(f"{column} {data[column].mean():.3g}{unit} on average, standard "
                         f"deviation {data[column].std():.3g}{unit}")
    return facts


def summary_html(ins: TraceInspection) -> str:
    """The page's summary: the trace, its gaps, the moves and their peaks, the windows.

    Parameters
    ----------
    ins : TraceInspection

    Returns
    -------
    str
        HTML paragraphs and a list.
    """
    moves = ins.moves
    moving = float(moves["duration"].sum()) if len(moves) else 0.0
    missing = sum(b - a for a, b in ins.gaps)
    gaps = gaps_sentence(ins.gaps, ins.segments, "no phase, move or window")
    kinds = ins.phases[ins.phases["move"] > 0]["phase"].value_counts()
    lines = [f"<p><b>{escape(Path(ins.source).name)}</b>: "
             f"{escape(time_sentence(ins.recording))}; signals used as nodes: "
             f"{escape(', '.join(ins.signals))}. {escape(gaps + ' ' if gaps else '')}The axis "
             f"moves {len(moves)} time(s), {moving:.1f} s in all, and stands still the other "
             f"{max(ins.duration - moving - missing, 0.0):.1f} s. "
             f"{escape(_turns_sentence(ins))}"
             + (f" {escape(_cut_moves_sentence(ins))}" if _cut_moves_sentence(ins) else "")
             + "</p>"]
    position = _position_unit(ins)
    if len(moves):
        facts = []
        if position == "deg":
            facts.append(f"peak set-point speed {moves['peak speed'].max():.4g} °/s "
                         f"({moves['peak speed'].max() * 60:.4g} °/min)")
        elif position == "mm":
            facts.append(f"peak set-point speed {moves['peak speed'].max():.4g} mm/s "
                         f"({moves['peak speed'].max() * 60:.4g} mm/min)")
        else:
            facts.append(f"peak set-point speed {moves['peak speed'].max():.4g} per s "
                         "(the position's unit is unknown)")
        if "peak |AC|" in moves:
            from funcnet.robot.units import UNKNOWN, unit_of

            info = ins.recording.signals.get("AC")
            unit = unit_of(info) if info is not None else UNKNOWN
            if unit == UNKNOWN:
                facts.append(f"peak |AC| {moves['peak |AC|'].max():.3g} (no unit stated)")
            else:
                what = ("current" if unit.endswith("A") else "force" if unit.strip() == "N"
                        else "torque" if "N" in unit else "value")
                facts.append(f"peak {what} |AC| {moves['peak |AC|'].max():.3g} {unit}")
        if "peak |FE|" in moves and position == "mm":
            facts.append(f"peak following error |RP − AP| {moves['peak |FE|'].max() * 1e3:.3g} "
                         f"um, {moves['final |FE|'].max() * 1e3:.3g} um at the end of a move")
        elif "peak |FE|" in moves and position != "deg":
            facts.append(f"peak following error |RP − AP| {moves['peak |FE|'].max():.3g} "
                         "(the position's unit is unknown)")
        elif "peak |FE|" in moves:
            facts.append(f"peak following error |RP − AP| {moves['peak |FE|'].max():.3g}° "
                         f"({moves['peak |FE|'].max() * 60:.3g} arcmin), "
                         f"{moves['final |FE|'].max() * 3600:.3g} arcsec at the end of a move")
        facts += _units_facts(ins)
        lines.append("<ul>" + "".join(f"<li>{escape(f)}</li>" for f in facts)
                     + "<li>phases within the moves: "
                     + escape(", ".join(f"{k} ×{n}" for k, n in kinds.items())) + "</li>"
                     + _lost_motion_item(ins) + "</ul>")
    if not len(moves):
        lines.append("<ul>" + "".join(f"<li>{escape(f)}</li>"
                                      for f in _rest_facts(ins) + _units_facts(ins)) + "</ul>")
    n_net = len(ins.networks)
    errors, partial = failed_windows(ins, "network"), partial_evidence(ins)
    lines.append(f"<p>{n_net} of {len(ins.windows)} phase windows have a network"
                 + (f" ({len(errors)} could not be computed: see "
                    "<a href=\"#problems\">problems</a>)" if errors else "")
                 + (", each with its evidence columns" if ins.evidence and n_net else "")
                 + _evidence_count(ins)
                 + (f" ({len(partial)} without part of them, too short for it: see "
                    "<a href=\"#problems\">problems</a>)" if len(partial) else "")
                 + (f"; {escape(', '.join(ins.resampled))} were interpolated onto the "
                    f"{ins.sample_period * 1e3:g} ms grid (recorded coarser)" if ins.resampled
                    else "") + ".</p>")
    return "".join(lines)


def _evidence_count(ins: TraceInspection) -> str:
    """``" (pairs: 3 coupled, 117 untestable ...)"``: the evidence labels over all windows."""
    labels = [label for net in ins.networks.values() if "evidence" in net.pairs.columns
              for label in net.pairs["evidence"]]
    if not labels:
        return ""
    counts = pd.Series(labels).value_counts()
    text = ", ".join(f"{n} {label}" for label, n in counts.items())
    blind = [net.pairs.loc[net.pairs["evidence"] == "untestable", "surrogates"]
             for net in ins.networks.values() if "evidence" in net.pairs.columns]
    k = pd.concat(blind) if blind else pd.Series(dtype=float)
    span = "" if not len(k) else str(k.min()) if k.min() == k.max() else f"{k.min()}–{k.max()}"
    undrawn = any(net.pairs.loc[net.pairs["evidence"] == "untestable", "c_diff_low"].isna().all()
                  and (net.pairs["evidence"] == "untestable").any()
                  for net in ins.networks.values() if "evidence" in net.pairs.columns)
    note = (f"; untestable: the windows leave the test {span} surrogates, too few to reject "
            "whatever the data" + ("; their asymmetry intervals are not drawn" if undrawn
                                   else "") if span else "")
    return f" (pairs over the windows: {text}{note})"


def _moves_scaled(ins: TraceInspection) -> pd.DataFrame:
    """The moves table as the page shows it: a linear axis's following error in um."""
    if not scale_of(ins).linear:
        return ins.moves
    fe = [c for c in ("peak |FE|", "final |FE|") if c in ins.moves]
    return ins.moves.assign(**{c: ins.moves[c] * 1e3 for c in fe})


def _move_units(ins: TraceInspection) -> dict[str, str]:
    """The moves table's columns with the unit each holds (positions in degrees or mm, or of
    unknown unit; the current's as the recording states it)."""
    from funcnet.robot.units import UNKNOWN, unit_of

    signals = ins.recording.signals
    scale = scale_of(ins)
    position, speed = {"deg": ("°", "°/s"), "mm": ("mm", "mm/s")}.get(
        scale.position, ("unit unknown", "unit unknown per s"))
    ac = signals.get("AC")
    current = unit_of(ac) if ac is not None else UNKNOWN
    units = {"start": "s", "stop": "s", "duration": "s", "distance": position,
             "peak speed": speed, "peak V": speed,
             "peak |FE|": "um" if scale.linear else position,
             "final |FE|": "um" if scale.linear else position,
             "peak |AC|": "unit unknown" if current == UNKNOWN else current}
    return {column: f"{column} [{unit}]" for column, unit in units.items()}


def moves_shown(ins: TraceInspection) -> pd.DataFrame:
    """The moves table as the page shows it: rounded, each column's unit in its name, a linear
    axis's following error in um."""
    return _moves_scaled(ins).round(4).rename(columns=_move_units(ins))


def clock_items(recording: Any) -> dict[str, str]:
    """The file's own clock for the provenance table, where the time was read from it."""
    items = {}
    if recording.time_unit or recording.time_origin:
        items["time read in"] = recording.time_unit or "s"
    if recording.time_origin:
        items["file's clock at time 0 [s]"] = f"{recording.time_origin:.9g}"
    if recording.start_time:
        items["start time"] = recording.start_time
    return items


def failed_windows(ins: TraceInspection, part: str) -> dict[str, str]:
    """Window label -> why it lacks ``part``, the trace's file left out of the message."""
    return {label: message.removeprefix(f"{ins.source}: ")
            for label, message in ins.failed(part).items()}


def partial_evidence(ins: TraceInspection) -> pd.DataFrame:
    """The windows whose network lacks its evidence or part of it: window, left out, why."""
    rows = [{"window": f.window, "left out": f.part,
             "why": f.message.removeprefix(f"{ins.source}: ")}
            for f in ins.failures if f.part != "network"]
    return pd.DataFrame(rows, columns=["window", "left out", "why"])


def lost_motion_cell(lost: float | None, high: float | None, scale: float) -> str:
    """A lost motion as a cell: the value, its bound where the data do not resolve it
    (``"≤ 12"``), or a dash; ``scale`` turns degrees into the cell's unit.

    Examples
    --------
    >>> lost_motion_cell(0.01, 0.012, 60), lost_motion_cell(None, 0.003, 60)
    ('0.6', '≤ 0.18')
    >>> lost_motion_cell(None, None, 60)
    '—'
    """
    if lost is not None:
        return f"{lost * scale:.3g}"
    return "—" if high is None else f"≤ {high * scale:.2g}"


def _lost_motion_item(ins: TraceInspection) -> str:
    result = ins.backlash
    if result is None:
        return ""
    measured = [r for r in result.reversals
                if r.lost_motion is not None or r.lost_motion_high is not None]
    if not measured:
        return f"<li>backlash: {escape(result.message)}</li>"
    scale = scale_of(ins)
    k, unit = scale.fine_factor, scale.fine
    listed = ", ".join(lost_motion_cell(r.lost_motion, r.lost_motion_high, k)
                       for r in measured)
    whole = (f"mean {result.lost_motion * k:.3g} {unit}" if result.lost_motion is not None
             else f"as a whole {result.lost_motion_reason}")
    unresolved = ("; ≤: below what the estimate resolves (its noise and the motor friction's "
                  "bias)" if any(r.lost_motion is None for r in measured) else "")
    return (f"<li>lost motion at the {len(measured)} direction change(s), from both encoders: "
            f"{escape(listed)} {escape(unit)} ({escape(whole)}{escape(unresolved)})</li>")


