"""Fixed layouts of the report's figures: margins measured from their own texts, in inches.

Matplotlib's constrained layout finds every figure's margins by laying out every artist of it
twice before the figure is drawn: on a page of thirty figures, a third of the drawing time. The
report's figures are of a few fixed kinds whose texts are known (tick labels, axis labels,
titles, legends), so each kind places its axes itself: the few texts that decide a margin are
measured once (their sizes are cached for the drawing that follows) and the axes are put where
those texts leave room. Tick labels are measured after a first placement, since how many ticks
an axis gets depends on its length.

Figures of many small axes draw their ticks with :func:`axis_ticks` and :func:`fix_ticks`: the
ticks matplotlib would draw, as one marker line per axis and a text per label, without its
tick objects (five artists each, set up and laid out at every draw: more than the data cost).
"""

from __future__ import annotations

import functools
from collections.abc import Iterable
from typing import Any, NamedTuple

import numpy as np

__all__ = ["PT", "renderer_of", "extent", "put", "legend_extent", "Ticks", "axis_ticks",
           "fix_ticks"]

#: One point in inches.
PT = 1.0 / 72.0


def renderer_of(fig: Any) -> Any:
    """The Agg renderer of ``fig`` (the one it is saved with), attached if it has none.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> type(renderer_of(Figure())).__name__
    'RendererAgg'
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def extent(artists: Iterable[Any], renderer: Any) -> tuple[float, float]:
    """The largest width and height (inches) of the visible artists that are drawn.

    Texts without text count as nothing.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> fig = Figure()
    >>> w, h = extent([fig.text(0, 0, "label", fontsize=9), fig.text(0, 0, "")],
    ...               renderer_of(fig))
    >>> 0.2 < w < 0.5 and 0.1 < h < 0.2
    True
    """
    width = height = 0.0
    for artist in artists:
        if not artist.get_visible() or (hasattr(artist, "get_text") and not artist.get_text()):
            continue
        box = artist.get_window_extent(renderer)
        width, height = max(width, box.width), max(height, box.height)
    dpi = renderer.dpi
    return float(width / dpi), float(height / dpi)


def legend_extent(legend: Any, renderer: Any) -> tuple[float, float]:
    """A legend's width and height in inches."""
    box = legend.get_window_extent(renderer)
    return float(box.width / renderer.dpi), float(box.height / renderer.dpi)


def put(ax: Any, left: float, bottom: float, width: float, height: float) -> None:
    """Place axes at a rectangle given in inches from the figure's lower left corner."""
    fig_width, fig_height = ax.get_figure(root=True).get_size_inches()
    ax.set_position((left / fig_width, bottom / fig_height, max(width, 0.05) / fig_width,
                     max(height, 0.05) / fig_height))


#: Matplotlib's default major tick: its length and the gap to its label (points), its width.
_TICK, _TICK_PAD, _TICK_WIDTH = 3.5, 3.5, 0.8


class Ticks(NamedTuple):
    """The major ticks of one axis: their places (data), their labels (texts of the figure,
    placed by :func:`fix_ticks`; none where the axis shows no labels) and the offset text."""

    locations: Any
    labels: list[Any]
    offset: str


def axis_ticks(ax: Any, which: str, *, labels: bool = True, fontsize: float = 9.0,
               rotation: float = 0.0, ha: str | None = None) -> Ticks:
    """The major ticks matplotlib would draw now on ``ax``'s ``which`` (``"x"``/``"y"``) axis.

    Its own locator and formatter, at the axes' present size and limits (how many ticks an
    axis gets depends on its length); the labels are texts of the figure, to be measured
    with :func:`extent` and placed by :func:`fix_ticks`, ``fontsize`` points, turned by
    ``rotation`` degrees and aligned ``ha`` (default matplotlib's: centred below an x tick,
    ending at a y tick).

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> ax = Figure(figsize=(4, 3)).add_axes((0.2, 0.2, 0.7, 0.7))
    >>> ax.set_xlim(0, 1)
    (0.0, 1.0)
    >>> [t.get_text() for t in axis_ticks(ax, "x").labels]
    ['0.0', '0.2', '0.4', '0.6', '0.8', '1.0']
    """
    from matplotlib.text import Text

    axis = ax.xaxis if which == "x" else ax.yaxis
    locations = np.asarray(axis.get_major_locator()(), dtype=float)
    formatter = axis.get_major_formatter()
    texts = formatter.format_ticks(locations)
    offset = formatter.get_offset()
    lo, hi = sorted(axis.get_view_interval())
    slack = 1e-10 * max(hi - lo, 1e-300)  # as matplotlib keeps a tick at the view's very end
    inside = (locations >= lo - slack) & (locations <= hi + slack)
    made = []
    if labels:
        fig = ax.get_figure(root=True)
        for location, text in zip(locations[inside], np.asarray(texts, dtype=object)[inside],
                                  strict=True):
            x, y = (location, 0.0) if which == "x" else (0.0, location)
            label = Text(x=x, y=y, text=str(text), fontsize=fontsize,
                         rotation=rotation,
                         ha=ha or ("center" if which == "x" else "right"),
                         va="top" if which == "x" else "center_baseline")
            fig.add_artist(label)
            made.append(label)
    return Ticks(locations[inside], made, offset)  # shown as the axis shows its labels


def fix_ticks(ax: Any, x: Ticks, y: Ticks, renderer: Any) -> None:
    """Draw ``ax``'s ticks from :func:`axis_ticks`, where matplotlib would, and switch its own
    off: the marks one marker line per axis (of the figure, not the axes), the labels placed
    beside them, the axis labels and the x offset text moved past them as matplotlib moves
    them. Call it once the axes' place and limits are final (the marks and labels follow
    the axes, but the ticks chosen do not)."""
    from matplotlib import lines, ticker
    from matplotlib.markers import TICKDOWN, TICKLEFT
    from matplotlib.transforms import ScaledTranslation

    fig = ax.get_figure(root=True)
    gap = ScaledTranslation(0.0, -(_TICK + _TICK_PAD) * PT, fig.dpi_scale_trans)
    marker: Any  # matplotlib's tick markers: ints its annotations do not list
    for ticks, transform, marker in ((x, ax.get_xaxis_transform(), TICKDOWN),
                                     (y, ax.get_yaxis_transform(), TICKLEFT)):
        if not len(ticks.locations):
            continue
        flat = np.zeros(len(ticks.locations))
        places = (ticks.locations, flat) if marker == TICKDOWN else (flat, ticks.locations)
        fig.add_artist(lines.Line2D(*places, transform=transform, linestyle="none",
                                    marker=marker, markersize=_TICK, color="black",
                                    markeredgewidth=_TICK_WIDTH))
    for label in x.labels:
        label.set_transform(ax.get_xaxis_transform() + gap)
    gap = ScaledTranslation(-(_TICK + _TICK_PAD) * PT, 0.0, fig.dpi_scale_trans)
    for label in y.labels:
        label.set_transform(ax.get_yaxis_transform() + gap)
    # the axis labels and the x offset go past the tick labels, as matplotlib puts them
    height = extent(x.labels, renderer)[1] * 72.0
    width = extent(y.labels, renderer)[0] * 72.0
    # (past the tick marks alone where an axis shows no labels: its spine's extent held them)
    if x.labels:
        ax.xaxis.labelpad += _TICK + _TICK_PAD + height
        ax.xaxis.OFFSETTEXTPAD = ax.xaxis.OFFSETTEXTPAD + _TICK + _TICK_PAD + height
    elif len(x.locations):
        ax.xaxis.labelpad += _TICK
    if y.labels:
        ax.yaxis.labelpad += _TICK + _TICK_PAD + width
    elif len(y.locations):
        ax.yaxis.labelpad += _TICK
    for axis, ticks in ((ax.xaxis, x), (ax.yaxis, y)):
        axis.set_major_locator(ticker.NullLocator())
        axis.set_major_formatter(_offset_only()(ticks.offset))


@functools.cache
def _offset_only() -> Any:
    """A formatter class that writes no tick label, only an axis's offset text ("1e−5"): the
    axis still draws and places that text (above a y axis, where a title makes room for it)."""
    from matplotlib.ticker import Formatter

    class OffsetOnly(Formatter):  # type: ignore[misc]
        def __init__(self, offset: str) -> None:
            self.offset = offset

        def __call__(self, x: float, pos: int | None = None) -> str:
            return ""

        def get_offset(self) -> str:
            return self.offset

    return OffsetOnly
