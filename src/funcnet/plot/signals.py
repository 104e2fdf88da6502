"""Drawing signals over time with their phases or windows shaded, and the signals' legend."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from funcnet.plot.style import _new_axes, phase_color, signal_color

__all__ = ["plot_signals", "add_signal_legend", "shade_spans"]


def shade_spans(ax: Axes, spans: Any, *, prefix: str | None = "phase", alpha: float = 0.7,
                names: bool = False, within: tuple[float, float] | None = None,
                color: str | None = None) -> None:
    """Shade spans of time (phases, windows) in their phases' colours, behind what is drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    spans : phase table, sequence of Window, or sequence of (name, start, stop)
        A phase table (``phase, start, stop``: each row shaded as its phase), windows (each
        shaded as its label names it) or explicit triples.
    prefix : str or None
        The spans of one name are one :class:`~matplotlib.collections.PolyCollection` of
        rectangles, its gid ``{prefix}:{name}``; None sets none.
    alpha : float
        Opacity of the shading.
    names : bool
        Write each span's name above the axes (at alternate heights, so that the names of
        short spans do not overlap).
    within : (float, float), optional
        Shade only the spans that overlap this range, clipped to it.
    color : str, optional
        One colour for every span (the gaps of a recording: :data:`funcnet.plot.GAP_COLOR`)
        instead of each span's phase colour.

    Examples
    --------
    >>> ax = Figure().add_subplot()
    >>> spans = [("cruise", 0.0, 1.0), ("braking", 1.0, 2.0), ("cruise 2", 2.0, 3.0)]
    >>> shade_spans(ax, spans, within=(0.5, 1.5))
    >>> [(c.get_gid(), len(c.get_paths())) for c in ax.collections]
    [('phase:cruise', 1), ('phase:braking', 1)]
    """
    # One collection of rectangles per kind of span (in data x, axes y, as axvspan draws):
    # a patch per span cost more than the rest of a panel where an axis moves often.
    groups: dict[tuple[str, str], list[Any]] = {}
    for k, (name, start, stop) in enumerate(_spans(spans)):
        if within is not None:
            if not (stop > within[0] and start < within[1]):
                continue
            start, stop = max(start, within[0]), min(stop, within[1])
        groups.setdefault((name, color or phase_color(name, k)), []).append(
            [(start, 0.0), (stop, 0.0), (stop, 1.0), (start, 1.0)])
        if names:
            ax.annotate(str(name), ((start + stop) / 2, 1.0), xycoords=ax.get_xaxis_transform(),
                        xytext=(0, 2 + 11 * (k % 2)), textcoords="offset points", fontsize=9,
                        ha="center", va="bottom")
    for (name, colour), rectangles in groups.items():
        shading = PolyCollection(rectangles, transform=ax.get_xaxis_transform(),
                                 facecolors=colour, alpha=alpha, zorder=0, linewidths=0,
                                 edgecolors="none")
        if prefix is not None:
            shading.set_gid(f"{prefix}:{name}")
        ax.add_collection(shading, autolim=False)


def _spans(phases: Any) -> list[tuple[str, float, float]]:
    """(name, start, stop) from a phase table (phase, start, stop), a sequence of Windows or
    of (name, start, stop)."""
    if isinstance(phases, pd.DataFrame):
        return [(str(r.phase), float(r.start), float(r.stop)) for r in phases.itertuples()]
    return [(str(w[0]), float(w[1]), float(w[2])) if isinstance(w, tuple)
            else (str(w.label), float(w.start), float(w.stop)) for w in phases]


def plot_signals(
    data: pd.DataFrame,
    *,
    normalize: bool = True,
    spans: Any = None,
    ax: Axes | None = None,
    span_prefix: str = "phase",
    legend: bool = True,
) -> Axes:
    """Plot the columns of a recording window over time, optionally min-max normalized.

    Parameters
    ----------
    data : pandas.DataFrame
        Time (seconds) as index, one column per signal.
    normalize : bool
        Scale every column to [0, 1] over the plotted range (paper section 3.3); a constant column
        is drawn at 0.5.
    spans : phase table or sequence of Window, optional
        Intervals to shade (gid ``{span_prefix}:{name}``).
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    span_prefix : str
        Prefix of the spans' gids.
    legend : bool
        Draw a legend of the signals.

    Returns
    -------
    matplotlib.axes.Axes
        One line per column (label = column name, colour :func:`signal_color`).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> df = pd.DataFrame({"RP": np.arange(5.0), "AC": np.ones(5)}, index=np.arange(5) * 0.002)
    >>> [line.get_label() for line in plot_signals(df).lines]
    ['RP', 'AC']
    """
    ax = _new_axes(ax, (6.0, 2.5))
    if spans is not None:
        shade_spans(ax, spans, prefix=span_prefix, names=True)
    for name in data.columns:
        values = data[name].to_numpy(dtype=float)
        if normalize:
            lo, hi = np.nanmin(values), np.nanmax(values)
            values = (values - lo) / (hi - lo) if hi > lo else np.full_like(values, 0.5)
        ax.plot(data.index.to_numpy(dtype=float), values, label=str(name), linewidth=0.9,
                color=signal_color(name))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("normalized" if normalize else "value")
    if legend:
        # beside the axes: a legend inside would hide the data (Fig. 9)
        ax.legend(fontsize=9, loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
    return ax



def add_signal_legend(fig: Figure, names: Sequence[str]) -> Any:
    """One legend of the signals' colours above a figure of several series panels.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    names : sequence of str
        The signals, in legend order (colours of :func:`signal_color`).

    Returns
    -------
    matplotlib.legend.Legend
        The legend (gid ``legend:signals``).

    Examples
    --------
    >>> [t.get_text() for t in add_signal_legend(Figure(), ["RP", "V"]).get_texts()]
    ['RP', 'V']
    """
    handles = [Line2D([], [], color=signal_color(name), linewidth=1.5, label=str(name))
               for name in names]
    legend = fig.legend(handles=handles, loc="outside upper center", ncol=max(len(handles), 1),
                        fontsize=9, frameon=False)
    legend.set_gid("legend:signals")
    return legend

