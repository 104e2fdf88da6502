"""The drawing conventions every figure shares: colours of signals, edges, kinds and phases.

One colour per signal role and one shade per phase kind, the same in every figure and report
(paper section 3.4: black directed, red bidirectional edges).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from funcnet.network.schema import PAIR_KINDS

__all__ = [
    "DIRECTED_COLOR",
    "BIDIRECTIONAL_COLOR",
    "DEGENERATE_COLOR",
    "SIGNAL_COLORS",
    "KIND_COLORS",
    "SPAN_TITLE_PAD",
    "PHASE_COLORS",
    "GAP_COLOR",
    "signal_color",
    "phase_color",
    "glyph_markers",
]

DIRECTED_COLOR = "black"
BIDIRECTIONAL_COLOR = "red"
#: Edges of degenerate pairs (kept only on request): grey and dashed, never like a real edge.
DEGENERATE_COLOR = "0.6"
#: One colour per signal role, the same in every figure (Okabe-Ito-like, distinguishable in
#: print); the currents differ clearly from V, and no signal uses the red of bidirectional edges.
SIGNAL_COLORS = {
    "RP": "#0072b2",  # blue
    "AP": "#e69f00",  # orange
    "MP": "#009e73",  # green
    "V": "#cc79a7",  # magenta
    "RC": "#56b4e9",  # sky blue
    "AC": "#7f3c8d",  # purple
    "FE": "#8c6d31",  # brown
    "TORSION": "#555555",  # grey
}
_OTHER_COLORS = ("#bcbd22", "#17becf", "#9c755f", "#f0e442", "#4e79a7", "#b07aa1")
_PHASE_SHADES = ("#dbe9f6", "#fde9d9", "#e2f0d9", "#ede0f3", "#fff2cc", "#e7e6e6")
#: One shade per phase kind (:data:`funcnet.robot.phases.PHASES`), the same in every figure and
#: report whatever order the phases come in: "cruise 2" is shaded as "cruise".
PHASE_COLORS = {
    "standstill": "#e7e6e6",  # grey: nothing moves
    "early spin-up": "#fde2c4",  # light orange
    "late spin-up": "#f9c58f",  # orange
    "cruise": "#cfe2f3",  # light blue
    "braking": "#f4cccc",  # light red
    "reversal": "#d9ead3",  # light green
}
#: The shade of a gap in a recording (values missing): darker than any phase, standstill too.
GAP_COLOR = "#8c8c8c"
_X_Y, _Y_X, _BIDIRECTIONAL, _CONFLICT = PAIR_KINDS
#: Colour of each pair kind in :func:`plot_edge_timeline`.
KIND_COLORS = {_X_Y: "#1f4e9c", _Y_X: "#e07b00", _BIDIRECTIONAL: "red", _CONFLICT: "0.6",
               "degenerate": "0.35"}
#: Title padding (points) that clears the two rows of span names drawn by :func:`plot_signals`.
SPAN_TITLE_PAD = 26.0


def phase_color(name: Any, position: int = 0) -> str:
    """The shade of a phase (or of a window labelled by its phase) in every figure.

    Parameters
    ----------
    name : str
        A phase kind (``"cruise"``) or a window label made from one (``"cruise 2"``).
    position : int
        For a label that names no phase kind (``"+20 ms"``, ``"1.000-1.280 s"``): its position
        among the spans drawn, which picks a stable neutral shade.

    Returns
    -------
    str
        :data:`PHASE_COLORS` of the kind, else one of a fixed set of shades.

    Examples
    --------
    >>> phase_color("cruise 2") == phase_color("cruise") == PHASE_COLORS["cruise"]
    True
    """
    text = str(name)
    base = text.rsplit(" ", 1)[0] if text.rsplit(" ", 1)[-1].isdigit() else text
    if base in PHASE_COLORS:
        return PHASE_COLORS[base]
    return _PHASE_SHADES[position % len(_PHASE_SHADES)]


def _new_axes(ax: Axes | None, figsize: tuple[float, float] = (4.0, 4.0)) -> Axes:
    if ax is not None:
        return ax
    return Figure(figsize=figsize, layout="constrained").add_subplot()



def _category_ticks(axis: Any, labels: Sequence[str]) -> None:
    """An axis of named columns or rows: a tick at 0, 1, ... labelled; no tick object made
    (``set_xticks`` makes one per label, set up again at every draw)."""
    from matplotlib.ticker import FixedFormatter, FixedLocator

    axis.set_major_locator(FixedLocator(range(len(labels))))
    axis.set_major_formatter(FixedFormatter(list(labels)))


def signal_color(name: Any) -> str:
    """The colour of a signal in every figure: :data:`SIGNAL_COLORS`, else a stable extra colour.

    Parameters
    ----------
    name : str
        The signal's name (column of a recording).

    Returns
    -------
    str
        A matplotlib colour; the same name always gets the same colour.

    Examples
    --------
    >>> signal_color("RP"), signal_color("AC")
    ('#0072b2', '#7f3c8d')
    """
    name = str(name)
    if name in SIGNAL_COLORS:
        return SIGNAL_COLORS[name]
    # A stable (not hash-randomized) choice, so that a figure looks the same on every run.
    return _OTHER_COLORS[sum(map(ord, name)) % len(_OTHER_COLORS)]



def glyph_markers(ax: Axes,
                  glyphs: Mapping[tuple[str, float, str], Sequence[tuple[float, float]]],
                  prefix: str = "cell") -> None:
    """Short texts drawn many times (a cell's arrow, a node's name) as markers of their outline.

    Each text is then one path, drawn at all its places at once: a text each cost more than
    the rest of a figure of thousands of them. The outline is the font's (DejaVu Sans), at the
    size given, centred on each place (the centre of its ink, not of its line box).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    glyphs : mapping of (text, size in points, colour) to sequence of (x, y)
        Where each text goes, in data coordinates.
    prefix : str
        Each marker line's gid is ``{prefix}:{text}``.

    Examples
    --------
    >>> ax = Figure().add_subplot()
    >>> glyph_markers(ax, {("→", 10.0, "black"): [(0, 0), (1, 0)], ("RP", 9.0, "0.4"): [(0, 1)]})
    >>> [(line.get_gid(), len(line.get_xdata())) for line in ax.lines]
    [('cell:→', 2), ('cell:RP', 1)]
    """
    from matplotlib.markers import MarkerStyle
    from matplotlib.path import Path
    from matplotlib.textpath import TextPath

    for (text, size, colour), where in glyphs.items():
        outline = TextPath((0.0, 0.0), text, size=size)  # in points
        box = outline.get_extents()
        vertices = np.asarray(outline.vertices, dtype=float) - [(box.x0 + box.x1) / 2,
                                                                  (box.y0 + box.y1) / 2]
        centred = Path(vertices, outline.codes)
        # a path marker is scaled to half its size at its farthest vertex: the text's own size
        reach = float(np.abs(vertices).max())
        xs, ys = zip(*where, strict=True)
        ax.plot(xs, ys, linestyle="", marker=MarkerStyle(centred), markersize=2 * reach,
                markerfacecolor=colour, markeredgewidth=0.0, gid=f"{prefix}:{text}",
                scalex=False, scaley=False, zorder=4)  # over patches, as texts are
