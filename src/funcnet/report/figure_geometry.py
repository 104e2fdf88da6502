"""Fixed layouts of the report's figures: margins measured from their own texts, in inches.

Matplotlib's constrained layout finds every figure's margins by laying out every artist of it
twice before the figure is drawn: on a page of thirty figures, a third of the drawing time. The
report's figures are of a few fixed kinds whose texts are known (tick labels, axis labels,
titles, legends), so each kind places its axes itself: the few texts that decide a margin are
measured once (their sizes are cached for the drawing that follows) and the axes are put where
those texts leave room. Tick labels are measured after a first placement, since how many ticks
an axis gets depends on its length.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = ["PT", "renderer_of", "extent", "put", "legend_extent"]

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
