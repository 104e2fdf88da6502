"""The figures of the inspect report (:mod:`funcnet.report.inspect`): motion, networks per
phase, edge timeline, evidence, lost motion.

Each takes a :class:`~funcnet.inspection.TraceInspection` and returns a matplotlib figure
(or None when the trace lacks what it draws); phases are shaded in
:data:`funcnet.plot.PHASE_COLORS`, the same colour for the same kind of phase everywhere; every
text is at least 9 pt at the figure's native size (100 dpi), the size the report shows.

Length: just over 600 lines; the five figures of a page and the placing of their texts belong
together.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from funcnet.inspection import TraceInspection
from funcnet.report.figure_geometry import (
    PT,
    axis_ticks,
    extent,
    fix_ticks,
    legend_extent,
    put,
    renderer_of,
)
from funcnet.robot import Window

__all__ = ["figure_motion", "figure_networks", "figure_timeline", "figure_evidence",
           "figure_lost_motion", "ARROWS"]

#: The arrow shown for each pair kind.
ARROWS = {"x->y": "→", "y->x": "←", "bidirectional": "↔", "conflict": "×"}
_EVIDENCE_COLORS = {"coupled-directed": "#1b7837", "coupled": "#7fbf7b",
                    "asymmetry-only": "#f1a340", "not-coupled": "#d9d9d9",
                    "untestable": "#f7f7f7", "degenerate": "#9e9e9e", "left out": "#ffffff"}
#: The legend's words for the evidence readings (what each colour says).
_EVIDENCE_LEGEND = {"asymmetry-only": "asymmetry-only (tested, not coupled)",
                    "not-coupled": "not-coupled (tested)",
                    "untestable": "untestable (too few surrogates)"}
_MAX_MOVE_COLUMNS = 6  # the motion figure zooms into at most this many moves
_MAX_NETWORK_COLUMNS = 6  # networks per row where a move holds several cycles


def _fine_scale(inspection: Any) -> tuple[float, str]:
    """The factor and unit of a small position difference: arcsec, or um on a linear axis."""
    from funcnet.robot.units import axis_scale, position_unit

    scale = axis_scale(position_unit(inspection.recording.signals))
    return scale.fine_factor, scale.fine


def _shown_unit(signals: dict, column: str, default: str) -> str:
    """A column's unit for an axis label: deg as °, any other stated unit as stated,
    "unit unknown" where nothing states it; ``default`` for a column the recording lacks."""
    from funcnet.robot.units import UNKNOWN, unit_of

    info = signals.get(column)
    if info is None:
        return default
    unit = unit_of(info)
    if unit == UNKNOWN:
        return "unit unknown"
    return {"deg": "°"}.get(unit, unit)

def _phase_legend(fig: Any, kinds: Sequence[str], gaps: bool = False) -> Any:
    from matplotlib.patches import Patch

    from funcnet import plot

    handles = [Patch(facecolor=plot.phase_color(k), edgecolor="0.6", label=k) for k in kinds]
    if gaps:
        handles.append(Patch(facecolor=plot.GAP_COLOR, edgecolor="0.6", alpha=0.8,
                             label="gap (values missing)"))
    legend = fig.legend(handles=handles, loc="upper center", ncol=len(handles),
                        fontsize=9, frameon=False, title="phase (shading)", title_fontsize=9,
                        borderaxespad=0.0)
    legend.set_gid("legend:phases")
    return legend


def figure_motion(inspection: TraceInspection) -> Any:
    """The motion: the whole trace, then each move zoomed (positions, speed, current, error).

    Parameters
    ----------
    inspection : TraceInspection

    Returns
    -------
    matplotlib.figure.Figure
        Row 0 the set-point over the whole trace; below, one column per move (at most six;
        an axis that never moves: one column, the whole trace at rest): positions, V, AC and
        the following error RP - AP, the phases shaded in the colours of
        :data:`funcnet.plot.PHASE_COLORS` and the gaps (values missing) in
        :data:`funcnet.plot.GAP_COLOR`. The rows of a column share its time axis, labelled
        below the last. The axes are placed by :func:`_place_motion` (no layout engine).
    """
    from matplotlib.figure import Figure

    from funcnet import plot

    data = inspection.recording.data
    phases = inspection.phases
    moves = inspection.moves.head(_MAX_MOVE_COLUMNS)
    deg = _shown_unit(inspection.recording.signals, "RP", "°")
    panels = _motion_panels(inspection, deg)
    fig = Figure(figsize=(11.0, 2.2 + 1.9 * len(panels)))
    top = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    t = data.index.to_numpy(dtype=float)
    plot.shade_spans(top, phases, alpha=0.8, within=(t[0], t[-1]))
    _shade_gaps(top, inspection, (t[0], t[-1]))
    top.plot(t, data["RP"].to_numpy(dtype=float), color=plot.signal_color("RP"), linewidth=1)
    top.set_ylabel(f"RP [{deg}]", fontsize=9)
    top.set_xlabel("time [s]", fontsize=9)
    top.set_title("(a) the whole trace: set-point RP", fontsize=10, loc="left", pad=16)
    for move in moves.itertuples():
        top.annotate(f"move {move.move}", ((move.start + move.stop) / 2, 1.0),
                     xycoords=top.get_xaxis_transform(), ha="center", va="bottom", fontsize=9)
    fe = (data["RP"] - data["AP"]) * (1e3 if deg == "mm" else 1.0) if "AP" in data else None
    # each move zoomed; an axis that never moves: the whole trace, what it measured at rest
    spans = [(f"(b) move {move.move}: {move.start:.2f}–{move.stop:.2f} s",
              move.start - 0.15 * (move.stop - move.start),
              move.stop + 0.15 * (move.stop - move.start)) for move in moves.itertuples()]
    if not spans:
        spans = [(f"(b) no move: at rest over {t[0]:.2f}–{t[-1]:.2f} s", t[0], t[-1])]
    grid = [[_motion_panel(fig, inspection, panels, fe, span, k, row, bool(len(moves)))
             for row in range(len(panels))] for k, span in enumerate(spans)]
    top.tick_params(labelsize=9)
    legend = _phase_legend(fig, [k for k in plot.PHASE_COLORS if k in set(phases["phase"])],
                           gaps=bool(inspection.gaps))
    _place_motion(fig, top, grid, legend)
    return fig


def _motion_panels(inspection: TraceInspection, deg: str) -> list[tuple[str, list[str]]]:
    """The rows of the zoomed moves: (y label, columns drawn), those the recording has."""
    data = inspection.recording.data
    panels = [(f"position [{deg}]", [c for c in ("RP", "AP", "MP") if c in data])]
    if "V" in data:
        panels.append((f"V [{deg}/s]" if deg != "unit unknown" else "V [unit unknown]", ["V"]))
    if "AC" in data:
        panels.append((f"AC [{_shown_unit(inspection.recording.signals, 'AC', 'A')}]",
                       ["AC"]))
    if "AP" in data:  # a linear axis's following error in um, as the page states it
        panels.append(("RP − AP [um]" if deg == "mm" else f"RP − AP [{deg}]", ["FE"]))
    return panels


def _motion_panel(fig: Any, inspection: TraceInspection, panels: list[tuple[str, list[str]]],
                  fe: Any, span: tuple[str, float, float], k: int, row: int,
                  moving: bool) -> Any:
    """One zoomed panel: move (column) ``k``, signal row ``row`` (1 the first below the top)."""
    from funcnet import plot

    title, lo, hi = span
    data = inspection.recording.data
    part = data.loc[(data.index >= lo) & (data.index <= hi)]
    tt = part.index.to_numpy(dtype=float)
    ylabel, columns = panels[row]
    above = fig.axes[-1] if row else None  # the column's rows share its time axis
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0), sharex=above)
    plot.shade_spans(ax, inspection.phases, alpha=0.8, within=(lo, hi))
    _shade_gaps(ax, inspection, (lo, hi))
    for column in columns:
        values = (fe.loc[part.index] if column == "FE" and fe is not None
                  else part[column]).to_numpy(dtype=float)
        ax.plot(tt, values, color=plot.signal_color(column), linewidth=1, label=column)
    ax.tick_params(labelsize=9)
    if not moving:  # jitter at rest: the values themselves, not "+3.437e1" above
        ax.ticklabel_format(axis="y", useOffset=False)
    if k == 0:
        ax.set_ylabel(ylabel, fontsize=9)
    if row == 0:
        ax.set_title(title, fontsize=10, loc="left")
        if k == 0 and len(columns) > 1:
            ax.legend(fontsize=9, frameon=False, loc="best")
    if row == len(panels) - 1:
        ax.set_xlabel("time [s]", fontsize=9)
    else:  # the time is read below the column's last row
        ax.tick_params(labelbottom=False)
    return ax


def _place_motion(fig: Any, top: Any, grid: list[list[Any]], legend: Any) -> None:
    """Put the motion figure's axes where its texts leave room: the phase legend at the top,
    the whole trace below it, the zoomed columns under that (:mod:`.figure_geometry`).

    The heights first (they depend on no tick label's width), then the widths from the y tick
    labels, which are measured at the axes' final heights: an axis's ticks depend on its length.
    """

    renderer = renderer_of(fig)
    width, height = fig.get_size_inches()
    rows, cols = len(grid[0]), len(grid)
    text = extent([top.xaxis.label, top.title], renderer)[1]  # one line of 9-10 pt
    title, last_title = _motion_titles(fig, grid, renderer)
    title = max(title, text)
    xtick = extent([fig.text(0, 0, "0123456789−.", fontsize=9, visible=True)], renderer)[1]
    fig.texts.pop()
    head = 4 * PT + legend_extent(legend, renderer)[1] + 4 * PT + text + 16 * PT
    below_top = 7 * PT + xtick + 4 * PT + text + 10 * PT + title + 6 * PT + text
    between = 8 * PT + text  # room for an offset ("1e-5") above a panel
    size = (height - head - below_top - (rows - 1) * between
            - (7 * PT + xtick + 4 * PT + text + 4 * PT)) / (rows + 1)
    tops = [height - head - size] + [height - head - below_top - size - r * (size + between)
                                     - size for r in range(rows)]
    every = [top, *(ax for column in grid for ax in column)]
    for k, ax in enumerate(every):
        put(ax, 0.0, tops[0 if k == 0 else 1 + (k - 1) % rows], width, size)
    yticks = {ax: axis_ticks(ax, "y") for ax in every}  # at the final heights, as drawn
    ticks = {ax: extent(yticks[ax].labels, renderer)[0] for ax in every}
    left = 4 * PT + text + 4 * PT + 7 * PT + max(ticks[ax] for ax in [top, *grid[0]])
    gap = 17 * PT + max((ticks[ax] for column in grid[1:] for ax in column), default=0.0)
    right = _motion_right(width - left - (cols - 1) * gap, cols, last_title)
    put(top, left, tops[0], width - left - right, size)
    column = (width - left - right - (cols - 1) * gap) / cols
    for k in range(cols):
        for r in range(rows):
            put(grid[k][r], left + k * (column + gap), tops[1 + r], column, size)
    legend.set_bbox_to_anchor((0.5, 1.0 - 4 * PT / height), transform=fig.transFigure)
    # the time ticks at the final widths, every axis's before any is fixed (a column's rows
    # share their ticker); labelled under the whole trace and each column's last row
    xticks = {ax: axis_ticks(ax, "x", labels=ax is top or ax is rows_of[-1])
              for rows_of in [[top], *grid] for ax in rows_of}
    for ax in every:
        fix_ticks(ax, xticks[ax], yticks[ax], renderer)


def _motion_titles(fig: Any, grid: list[list[Any]], renderer: Any) -> tuple[float, float]:
    """The zoomed columns' titles, on two lines ("(b) move 5:" above its times) where one line
    is wider than a column leaves them; their height and the last one's width (inches).

    A column and its gap take about a ``cols``-th of the figure's width less its margins
    (an inch); titles wider than that ran into the next column's.
    """
    cols = len(grid)
    titles = [column[0].get_title(loc="left") for column in grid]
    probe = fig.text(0, 0, "\n".join(titles), fontsize=10)  # measured only: the widest line
    widest = extent([probe], renderer)[0]
    if widest + 6 * PT > (fig.get_figwidth() - 1.0) / cols:
        titles = [t.replace(": ", ":\n", 1) for t in titles]
        for column, t in zip(grid, titles, strict=True):
            column[0].set_title(t, fontsize=10, loc="left")
    probe.set_text(titles[-1])
    last = extent([probe], renderer)
    probe.remove()
    return last[1], last[0]


def _motion_right(room: float, cols: int, title: float) -> float:
    """The margin right of the zoomed columns (inches): half a time label past the end of the
    axis, or what the last column's title (``title`` wide, from its left end) needs beyond it.

    ``room`` is the width of the columns and the margin together. A column is
    ``(room - right) / cols`` wide, so its title ends inside the canvas when
    ``(room - right) / cols + right >= title`` (with 2 pt to spare).
    """
    if cols < 2:
        return 0.2
    return max(0.2, (title + 2 * PT - room / cols) / (1.0 - 1.0 / cols))


def _shade_gaps(ax: Any, inspection: TraceInspection, within: tuple[float, float]) -> None:
    """The recording's gaps (values missing), shaded over the phases."""
    from funcnet import plot

    plot.shade_spans(ax, [("gap", a, b) for a, b in inspection.gaps], prefix="gap", alpha=0.8,
                     within=within, color=plot.GAP_COLOR)


def _kinds_present(windows: Sequence[Window]) -> list[str]:
    from funcnet.robot import PHASES

    present = {w.phase for w in windows}
    return [k for k in PHASES if k in present]


#: A network panel's cell (inches: its title above a square of the circle's ±1.3 units).
_CELL_WIDTH, _CELL_HEIGHT, _TITLE_ROOM = 2.6, 2.7, 0.45
_SQUARE = min(_CELL_WIDTH - 0.2, _CELL_HEIGHT - _TITLE_ROOM - 0.03)


def figure_networks(inspection: TraceInspection) -> Any:
    """One network per phase (columns, in the order of a move) and move (rows).

    Parameters
    ----------
    inspection : TraceInspection

    Returns
    -------
    matplotlib.figure.Figure
        Every node at the same place in every panel; a node left out of a window (constant
        there) dashed; each panel's square the colour of its phase (a rectangle of gid
        ``panel:LABEL``, its title a text of gid ``title:LABEL``). The panels share one axes
        (an axes each cost more than the networks): in its data units each network is a
        circle of radius 1 around its panel's centre.
    """
    from matplotlib.lines import Line2D
    from matplotlib.transforms import ScaledTranslation

    from funcnet import plot

    cells, rows, cols = _panels(inspection)
    fig, ax, scale = _network_canvas(rows, cols)
    degenerate = dropped = with_evidence = False
    names: dict[tuple[str, float, str], list[Any]] = {}  # every panel's node names, drawn once
    pieces = plot.NetworkPieces()  # and its nodes and undecided lines
    # 4 pt above the square: a text in data units shifted, cheaper to draw than an annotation
    above = ax.transData + ScaledTranslation(0.0, 4 * PT, fig.dpi_scale_trans)
    for w, (r, c) in zip(inspection.windows, cells, strict=True):
        centre = ((c + 0.5) * _CELL_WIDTH / scale,
                  ((rows - r) * _CELL_HEIGHT - _TITLE_ROOM - _SQUARE / 2) / scale)
        ax.text(centre[0], centre[1] + 1.3, f"{w.label}\n{w.start:.2f}–{w.stop:.2f} s",
                transform=above, ha="center", va="bottom", fontsize=11, gid=f"title:{w.label}")
        net = inspection.networks.get(w.label)
        if net is None:
            names.setdefault(("no network", 10.0, "black"), []).append(centre)
            continue
        ax.add_patch(_panel_square(centre, plot.phase_color(w.phase), w.label))
        plot.plot_network(net, ax, nodes=list(inspection.signals), legend=False,
                          arrows="direction", at=centre, names=names, pieces=pieces)
        degenerate |= bool(plot.network_edges(net)["degenerate"].any())
        dropped |= bool(net.window and net.window.get("dropped"))
        with_evidence |= "evidence" in net.pairs.columns
    pieces.draw(ax)
    plot.glyph_markers(ax, names, prefix="name")
    handles = plot.network_legend_handles(degenerate=degenerate, evidence=with_evidence)
    if dropped:
        handles.append(Line2D([], [], color="0.2", linestyle="none", marker="o", markersize=9,
                              markerfacecolor="white",
                              label="dashed node: left out (constant in the window)"))
    legend = fig.legend(handles=handles, loc="upper center", ncol=3, fontsize=9,
                        frameon=False, handlelength=2.5, borderaxespad=0.0)
    legend.set_gid("legend:network")
    _fit_networks(fig, ax, legend, rows, cols)
    return fig


def _network_canvas(rows: int, cols: int) -> tuple[Any, Any, float]:
    """The networks' figure and its one axes over the panels' cells; the axes' data units are
    ``scale`` inches each way."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(_CELL_WIDTH * cols + 0.6, _CELL_HEIGHT * rows + 1.0))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    scale = _SQUARE / 2.6  # inches per unit: the square holds the circle's ±1.3
    ax.set_xlim(0.0, _CELL_WIDTH * cols / scale)
    ax.set_ylim(0.0, _CELL_HEIGHT * rows / scale)
    ax.set_axis_off()
    return fig, ax, scale


def _fit_networks(fig: Any, ax: Any, legend: Any, rows: int, cols: int) -> None:
    """The figure as tall as the cells and the legend below them; the axes and the legend
    placed (inches)."""

    below = legend_extent(legend, renderer_of(fig))[1] + 0.15
    height = _CELL_HEIGHT * rows + 0.05 + below
    fig.set_size_inches(_CELL_WIDTH * cols + 0.6, height)
    put(ax, 0.3, below, _CELL_WIDTH * cols, _CELL_HEIGHT * rows)
    legend.set_bbox_to_anchor((0.5, (below - 0.05) / height), transform=fig.transFigure)


def _panel_square(centre: tuple[float, float], colour: str, label: str) -> Any:
    """A network panel's square in its phase's colour, framed."""
    from matplotlib.patches import Rectangle

    square = Rectangle((centre[0] - 1.3, centre[1] - 1.3), 2.6, 2.6, facecolor=colour,
                       edgecolor="black", linewidth=0.8, zorder=0)
    square.set_gid(f"panel:{label}")
    return square


def _panels(inspection: TraceInspection) -> tuple[list[tuple[int, int]], int, int]:
    """Each window's panel (row, column), the rows and the columns.

    One row per move and one column per kind of phase, where no move holds two windows of one
    kind; else (cycles within a move) every window a panel of its own, in time order, a move's
    windows wrapped at :data:`_MAX_NETWORK_COLUMNS` columns: never two networks in one panel.
    """
    windows = inspection.windows
    moves = _moves_of(inspection, windows)
    kinds = _kinds_present(windows)
    if len(set(zip(moves, (str(w.phase) for w in windows), strict=True))) == len(windows):
        order = sorted(set(moves)) or [0]
        cells = [(order.index(m), kinds.index(str(w.phase)))
                 for m, w in zip(moves, windows, strict=True)]
        return cells, len(order), max(len(kinds), 1)
    per_move: dict[int, int] = {}
    for m in moves:
        per_move[m] = per_move.get(m, 0) + 1
    cols = min(max(per_move.values()), _MAX_NETWORK_COLUMNS)
    first_row, row = {}, 0
    for m in sorted(per_move):
        first_row[m] = row
        row += -(-per_move[m] // cols)
    seen: dict[int, int] = {}
    cells = []
    for m in moves:
        k = seen.get(m, 0)
        seen[m] = k + 1
        cells.append((first_row[m] + k // cols, k % cols))
    return cells, row, cols


def _moves_of(inspection: TraceInspection, windows: Sequence[Window]) -> list[int]:
    """Each window's move: that of the first phase holding its start (0 where none does);
    the phase table read once as arrays, not filtered per window."""
    phases = inspection.phases
    start, stop = (phases[c].to_numpy(dtype=float) for c in ("start", "stop"))
    moves = phases["move"].to_numpy()
    found = []
    for window in windows:
        holding = np.flatnonzero((start <= window.start) & (stop > window.start))
        found.append(int(moves[holding[0]]) if len(holding) else 0)
    return found


def figure_timeline(inspection: TraceInspection) -> Any:
    """Every pair's edge over the windows, in time order (one column per window).

    Parameters
    ----------
    inspection : TraceInspection

    Returns
    -------
    matplotlib.figure.Figure
        :func:`funcnet.plot.plot_edge_timeline` with the windows as equally spaced columns
        (labelled, the phases shaded) instead of their times: the moves are seconds long and
        the standstills between them minutes.
    """
    from matplotlib.figure import Figure

    from funcnet import plot
    from funcnet.plot.style import _category_ticks

    labels = [w.label for w in inspection.windows if w.label in inspection.networks]
    fig = Figure(figsize=(max(8.0, 0.55 * len(labels) + 4.5), 4.6))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    by_label = {w.label: w for w in inspection.windows}
    plot.shade_spans(ax, [(str(by_label[label].phase), k - 0.5, k + 0.5)
                          for k, label in enumerate(labels)], alpha=0.8)
    plot.plot_edge_timeline({float(k): inspection.networks[label]
                             for k, label in enumerate(labels)}, ax=ax)
    _category_ticks(ax.xaxis, labels)
    ax.set_xlim(-0.5, len(labels) - 0.5)
    ax.set_xlabel("window (time order)", fontsize=9)

    from matplotlib.legend import Legend

    renderer = renderer_of(fig)  # the two legends beside the axes, at its right
    widest = max(legend_extent(legend, renderer)[0] for legend in ax.get_children()
                 if isinstance(legend, Legend))
    _place_single(fig, ax, right=4.5 * PT + widest + 4 * PT)
    return fig


def _place_single(fig: Any, ax: Any, *, right: float, top: float = 8 * PT) -> None:
    """Put a figure's one axes where its texts leave room (inches): the y label and tick
    labels at its left, the x label and (rotated) tick labels below, ``right`` and ``top``
    given. The first x tick label, rotated, may reach left of the axes: room for it too.

    The ticks are drawn by :func:`.fix_ticks`: the axes' locators name fixed places (columns
    and rows), which its size does not change; 9 pt labels, those below slanted.
    """

    renderer = renderer_of(fig)
    width, height = fig.get_size_inches()
    xticks = axis_ticks(ax, "x", rotation=60, ha="right")
    yticks = axis_ticks(ax, "y")
    xtick = extent(xticks.labels, renderer)[1]
    left = (6 * PT + extent([ax.yaxis.label], renderer)[0] + 4 * PT
            + extent(yticks.labels, renderer)[0] + 7 * PT)
    bottom = (4 * PT + extent([ax.xaxis.label], renderer)[1] + 4 * PT + xtick + 7 * PT)
    if xticks.labels:  # the first label ends at its tick, half a column in (rotated)
        lo, hi = ax.get_xlim()
        first = extent(xticks.labels[:1], renderer)[0]
        for _ in range(2):  # the column's width depends on the axes' width
            half = (width - left - right) * 0.5 / max(abs(hi - lo), 1.0)
            left = max(left, first - half + 6 * PT)
    put(ax, left, bottom, width - left - right, height - bottom - top)
    fix_ticks(ax, xticks, yticks, renderer)


def figure_evidence(inspection: TraceInspection) -> Any:
    """Pairs × windows: each cell the pair's arrow, coloured by its evidence reading.

    Parameters
    ----------
    inspection : TraceInspection

    Returns
    -------
    matplotlib.figure.Figure
        Without evidence columns, cells are coloured by edge kind instead. An untestable pair
        (its test could not have rejected) is near white, its arrow grey: the arrow is the
        rule's, not a finding.
    """
    from matplotlib.colors import to_rgb
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    from funcnet import plot
    from funcnet.plot.style import _category_ticks

    labels = [w.label for w in inspection.windows if w.label in inspection.networks]
    signals = list(inspection.signals)
    pairs = [(a, b) for i, a in enumerate(signals) for b in signals[i + 1:]]
    image = np.ones((len(pairs), len(labels), 3))
    fig = Figure(figsize=(max(8.0, 0.55 * len(labels) + 4.0), 0.36 * len(pairs) + 2.8))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    used: dict[str, str] = {}
    cells: dict[tuple[str, float, str], list[tuple[int, int]]] = {}  # (glyph, size, colour)
    for c, label in enumerate(labels):
        readings = _cell_readings(inspection.networks[label].pairs)
        for r, (a, b) in enumerate(pairs):
            if (a, b) not in readings:
                used["left out"] = _EVIDENCE_COLORS["left out"]
                cells.setdefault(("–", 9.0, "0.4"), []).append((c, r))
                continue
            key, kind = readings[(a, b)]
            colour = _EVIDENCE_COLORS.get(key, plot.KIND_COLORS.get(key, "0.8"))
            used[key] = colour
            image[r, c] = to_rgb(colour)
            cells.setdefault((ARROWS.get(kind, "?"), 10.0,
                              "0.55" if key == "untestable" else "black"), []).append((c, r))
    plot.glyph_markers(ax, cells)
    ax.imshow(image, aspect="auto", interpolation="nearest")
    _category_ticks(ax.xaxis, labels)
    _category_ticks(ax.yaxis, [f"{a}–{b}" for a, b in pairs])
    ax.set_ylabel("pair X–Y\n(arrow: → X drives Y in the rule's sense)", fontsize=9)
    handles = [Patch(facecolor=colour, edgecolor="0.5", label=_EVIDENCE_LEGEND.get(key, key))
               for key, colour in used.items()]
    legend = fig.legend(handles=handles, loc="upper left", fontsize=9, frameon=False,
                        title="evidence" if inspection.evidence else "edge kind",
                        title_fontsize=9, borderaxespad=0.0)

    right = 8 * PT + legend_extent(legend, renderer_of(fig))[0] + 4 * PT
    _place_single(fig, ax, right=right)
    width, height = fig.get_size_inches()
    legend.set_bbox_to_anchor((1.0 - (right - 8 * PT) / width, 1.0 - 8 * PT / height),
                              transform=fig.transFigure)
    return fig


def evidence_informs(inspection: TraceInspection) -> bool:
    """Whether :func:`figure_evidence` shows more than the edge timeline: not when no cell has a
    reading but untestable (or degenerate, or left out), the rule's arrows in grey.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["RP"], "y": ["AP"], "degenerate": [False],
    ...                       "evidence": ["untestable"], "kind": ["X->Y"]})
    >>> evidence_informs(SimpleNamespace(networks={"cruise": SimpleNamespace(pairs=pairs)}))
    False
    """
    keys = {key for net in inspection.networks.values()
            for key, _ in _cell_readings(net.pairs).values()}
    return "untestable" not in keys or bool(keys - {"untestable", "degenerate"})


def _cell_readings(pairs: Any) -> dict[tuple[str, str], tuple[str, str]]:
    """Each pair's cell in the evidence figure: (its colour's key, its kind), by (x, y).

    The key is ``degenerate`` for a degenerate pair, else its evidence reading, else (no
    evidence columns) its kind. Read column by column: a table lookup per cell cost more than
    drawing the cell.
    """
    keys = (pairs["evidence"] if "evidence" in pairs.columns else pairs["kind"]).astype(str)
    return {(str(x), str(y)): ("degenerate" if bool(degenerate) else key, str(kind))
            for x, y, degenerate, key, kind in zip(
                pairs["x"].tolist(), pairs["y"].tolist(), pairs["degenerate"].tolist(),
                keys.tolist(), pairs["kind"].tolist(), strict=True)}


def figure_lost_motion(inspection: TraceInspection) -> Any | None:
    """Motor minus arm position (MP − AP) around each direction change, its lost motion marked.

    After a rest, MP − AP itself; at a direction change in continuous motion, the part of it the
    gear's wind-up and the encoders' skew do not explain
    (:attr:`~funcnet.inspection.TraceInspection.reversal_residual`), with the two stretches whose
    means differ by the reversal error.

    Parameters
    ----------
    inspection : TraceInspection

    Returns
    -------
    matplotlib.figure.Figure or None
        None without both encoders or without a direction change.
    """
    from matplotlib.figure import Figure

    from funcnet import plot
    from funcnet.diagnosis.reversal_error import WINDOW

    data = inspection.recording.data
    result = inspection.backlash
    if result is None or not result.reversals or not {"AP", "MP"} <= set(data.columns):
        return None
    changes = result.reversals[:_MAX_MOVE_COLUMNS]
    rest = inspection.reversal_residual
    scale = _fine_scale(inspection)
    fig = Figure(figsize=(max(6.0, 3.6 * len(changes)), 3.6))
    t_all = data.index.to_numpy(dtype=float)
    for k, reversal in enumerate(changes):
        change = reversal.change
        continuous = change.kind == "continuous" and rest is not None
        # around the restart: the turn itself when the axis reverses, else the new start
        lo = (change.stop - WINDOW - 0.1 if continuous else
              (change.stop if change.kind == "reversal" else change.start) - 0.15)  # fmt: skip
        hi = change.start + (WINDOW + 0.1 if continuous else 0.3)
        inside = (t_all >= lo) & (t_all <= hi)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        plot.shade_spans(ax, inspection.phases, alpha=0.8, within=(lo, hi))
        if continuous:
            y = np.asarray(rest, dtype=float) * scale[0]
            ax.plot(t_all[inside], y[inside], color=plot.signal_color("TORSION"), linewidth=1)
            stretches = ((change.stop - WINDOW, change.stop), (change.start, change.start + WINDOW))
            for a, b in stretches:
                part = (t_all >= a) & (t_all < b) & np.isfinite(y)
                ax.hlines(float(np.mean(y[part])), a, b, color="black", linewidth=1.5)
            where = change.turn if change.turn is not None else change.start
        else:
            ax.plot(t_all[inside],
                    (data["MP"] - data["AP"]).to_numpy(dtype=float)[inside] * scale[0],
                    color=plot.signal_color("TORSION"), linewidth=1)  # fmt: skip
            where = change.start
        ax.axvline(where, color="0.3", linewidth=0.8, linestyle=":")
        lost, bound = reversal.lost_motion, reversal.lost_motion_high
        text = (f"lost motion {lost * scale[0]:.3g} {scale[1]}" if lost is not None
                else f"lost motion ≤ {bound * scale[0]:.2g} {scale[1]} (not resolved)"
                if bound is not None else "no lost motion measured")
        ax.set_title(f"{change.kind} at {where:.2f} s\n{text}", fontsize=9)
        ax.set_xlabel("time [s]", fontsize=9)
        ax.tick_params(labelsize=9)
        if k == 0:
            ax.set_ylabel("MP − AP" + (" unexplained" if continuous else "") + f" [{scale[1]}]",
                          fontsize=9)  # fmt: skip
    _place_row(fig, fig.axes)
    return fig


def _place_row(fig: Any, row: list[Any]) -> None:
    """Put a row of axes, each with its own y ticks, where their texts leave room (inches):
    the heights first, then the widths from the y tick labels measured at those heights."""
    renderer = renderer_of(fig)
    width, height = fig.get_size_inches()
    title = extent([ax.title for ax in row], renderer)[1]
    xtick_width, xtick = extent([t for ax in row for t in ax.get_xticklabels()], renderer)
    bottom = 4 * PT + extent([row[0].xaxis.label], renderer)[1] + 4 * PT + xtick + 7 * PT
    size = height - bottom - (4 * PT + title + 6 * PT)
    for ax in row:
        put(ax, 0.0, bottom, width, size)
    ticks = [extent(ax.get_yticklabels(), renderer)[0] for ax in row]
    left = 6 * PT + extent([row[0].yaxis.label], renderer)[0] + 4 * PT + ticks[0] + 7 * PT
    # between two axes: the next one's tick labels and half a time label of this one
    gap = max(ticks[1:], default=0.0) + 7 * PT + xtick_width / 2 + 6 * PT
    right = xtick_width / 2 + 4 * PT
    column = (width - left - right - (len(row) - 1) * gap) / len(row)
    for k, ax in enumerate(row):
        put(ax, left + k * (column + gap), bottom, column, size)
