"""Drawing: functional networks, recurrence matrices, signals and edge timelines.

Everything here draws what it is given -- a network or its pairs table, a recurrence matrix, a
window of signals -- and computes nothing: no recurrence, no measure, no network. The paper's
figures, which compute their data and then draw it with these functions, are in
:mod:`funcnet.paper.figures`. Single-panel functions take ``ax=`` and return it; figure-level
helpers take a :class:`matplotlib.figure.Figure`. Everything works on the Agg backend.

Drawing conventions (README method step 8, paper section 3.4): nodes on a circle, one per signal,
every node drawn even without edges; directed edges black with an arrow head at the target,
bidirectional edges red; line width proportional to the weight of Eq. 13 on an absolute scale, so
that widths compare across panels (the paper reads "edges thinning as speed grows" from them).
Edges of degenerate pairs (too few distinct states: their arrow means nothing) are present only
when a network keeps them (``degenerate="keep"``); they are drawn dashed and grey.

Every drawn artist carries a ``gid`` (``"node:RP"``, ``"edge:RP->AP:directed"``,
``"phase:cruise"``, ``"window:-20 ms"``) so that tests and users can find what was drawn.

Length: over 600 lines because every drawing shares these conventions (colours, widths, gids,
legends) in one place; what computes (the paper's figures) is elsewhere.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4
   and Figures 1, 2, 5, 9, 10 and 11.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch

from funcnet._io import atomic_path
from funcnet.errors import ParameterError
from funcnet.network.rule import edges_from_pairs
from funcnet.network.schema import PAIR_KINDS

__all__ = [
    "DIRECTED_COLOR",
    "BIDIRECTIONAL_COLOR",
    "DEGENERATE_COLOR",
    "SIGNAL_COLORS",
    "KIND_COLORS",
    "SPAN_TITLE_PAD",
    "PHASE_COLORS",
    "signal_color",
    "phase_color",
    "network_edges",
    "network_nodes",
    "network_legend_handles",
    "add_network_legend",
    "add_signal_legend",
    "plot_network",
    "plot_no_network",
    "plot_recurrence",
    "plot_graph",
    "plot_signals",
    "plot_edge_timeline",
    "network_title",
    "save_network",
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


def network_legend_handles(width_scale: float = 10.0, weight: float = 0.2, *,
                           degenerate: bool = False) -> list[Line2D]:
    """Legend entries explaining a network drawing: edge colours and the width scale.

    Parameters
    ----------
    width_scale : float
        The line width per unit of weight used by :func:`plot_network`.
    weight : float
        The reference weight (Eq. 13) whose width the legend shows.
    degenerate : bool
        Add the entry of degenerate edges (grey, dashed).

    Returns
    -------
    list of matplotlib.lines.Line2D
        Directed (black), bidirectional (red), optionally degenerate (grey, dashed), and a grey
        line of the reference weight's width.

    References
    ----------
    Paper section 3.4 (black directed, red bidirectional edges; width by Eq. 13).

    Examples
    --------
    >>> [h.get_label() for h in network_legend_handles()]
    ['directed (|diff| ≥ μ)', 'bidirectional (|diff| < μ)', 'weight 0.2 (width ∝ weight)']
    >>> network_legend_handles(degenerate=True)[2].get_label()
    'degenerate pair (arrow meaningless)'
    """
    handles = [Line2D([], [], color=DIRECTED_COLOR, linewidth=1.5, marker=">",
                      label="directed (|diff| ≥ μ)"),
               Line2D([], [], color=BIDIRECTIONAL_COLOR, linewidth=1.5,
                      label="bidirectional (|diff| < μ)")]
    if degenerate:
        handles.append(Line2D([], [], color=DEGENERATE_COLOR, linewidth=1.5, linestyle="--",
                              label="degenerate pair (arrow meaningless)"))
    handles.append(Line2D([], [], color="0.4", linewidth=width_scale * weight,
                          label=f"weight {weight:g} (width ∝ weight)"))
    return handles


def network_edges(net: Any, *, degenerate: str = "drop") -> pd.DataFrame:
    """The edges to draw: a network's ``.edges``, or those of a pairs table.

    Parameters
    ----------
    net : FunctionalNetwork or pandas.DataFrame
        A :class:`funcnet.FunctionalNetwork` (its own ``edges``, which hold degenerate pairs
        only when it was built with ``degenerate="keep"``), or a pairs table with at least the
        columns ``x, y, kind, weight`` (e.g. one window's rows of a study's results); a table
        without ``degenerate`` counts as having no degenerate pair.
    degenerate : {"drop", "keep"}
        For a pairs table: leave degenerate pairs out (default) or keep them as edges flagged
        ``degenerate`` (:func:`funcnet.network.rule.edges_from_pairs`).

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind, degenerate``
        (:data:`funcnet.network.schema.EDGE_COLUMNS`).

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["y->x", "x->y"],
    ...                       "weight": [0.2, 0.4], "degenerate": [False, True]})
    >>> network_edges(pairs)[["source", "target"]].values.tolist()
    [['B', 'A']]
    >>> network_edges(pairs, degenerate="keep")["degenerate"].tolist()
    [False, True]
    """
    if not isinstance(net, pd.DataFrame):
        return net.edges
    if "degenerate" in net.columns:
        # Rows of older results mixed with newer ones hold NaN there: not degenerate.
        flags = net["degenerate"].eq(True)
    else:
        flags = pd.Series(False, index=net.index)
    return edges_from_pairs(net.assign(degenerate=flags.astype(bool)), degenerate=degenerate)


def network_nodes(net: Any) -> list[str]:
    """The nodes of a network, or of a pairs table (its signals in order of appearance).

    Examples
    --------
    >>> network_nodes(pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"]}))
    ['A', 'B', 'C']
    """
    if isinstance(net, pd.DataFrame):
        return list(dict.fromkeys([*net["x"], *net["y"]]))
    return list(net.nodes)


_network_nodes = network_nodes


def plot_network(
    net: Any,
    ax: Axes | None = None,
    *,
    nodes: Sequence[str] | None = None,
    width_scale: float = 10.0,
    min_width: float = 0.6,
    node_size: float = 0.13,
    node_color: str = "#f2f2f2",
    title: str | None = None,
    fontsize: float = 10.0,
    legend: bool = True,
    degenerate: str = "drop",
) -> Axes:
    """Draw a functional network in a circular layout (paper section 3.4, Fig. 9-11).

    Parameters
    ----------
    net : FunctionalNetwork or pandas.DataFrame
        The network, or its pairs table (see :func:`network_edges`).
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure's axes when omitted.
    nodes : sequence of str, optional
        The nodes to place, in circle order (default the network's). Giving the same list to
        every panel keeps each signal at the same place; a node the network lacks (e.g. a signal
        left out of a window because it was constant there) is drawn dashed, without edges.
    width_scale : float
        Line width in points per unit of weight (Eq. 13). Absolute, so that widths compare across
        panels and figures.
    min_width : float
        Smallest line width, so that a bidirectional edge of weight near 0 stays visible.
    node_size : float
        Node radius in data units (the circle of nodes has radius 1); names longer than three
        characters get a larger node and a smaller font so that they fit.
    node_color : str
        Face colour of the nodes.
    title : str, optional
        Axes title (e.g. the window's label).
    fontsize : float
        Font size of the node labels.
    legend : bool
        Add a legend below the network explaining the edge colours and the width scale
        (:func:`network_legend_handles`); multi-panel figures draw one for the whole figure.
        When degenerate edges are drawn, the legend has their entry too.
    degenerate : {"drop", "keep"}
        For a pairs table only: draw degenerate pairs as edges (``"keep"``) or not (see
        :func:`network_edges`); a network's own edges say it themselves.

    Returns
    -------
    matplotlib.axes.Axes
        The axes; each node is a :class:`~matplotlib.patches.Circle` with gid ``node:NAME``,
        each edge a :class:`~matplotlib.patches.FancyArrowPatch` with gid
        ``edge:SOURCE->TARGET:KIND``, black when directed and red when bidirectional; an edge
        of a degenerate pair is grey and dashed, with gid ``edge:SOURCE->TARGET:KIND:degenerate``.

    References
    ----------
    Paper section 3.4 (circular layout, black/red edges, width by the weight of Eq. 13).

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["RP", "RP", "AP"], "y": ["AP", "MP", "MP"],
    ...                       "kind": ["x->y", "x->y", "bidirectional"],
    ...                       "weight": [0.2, 0.1, 0.01]})
    >>> ax = plot_network(pairs)
    >>> sorted(p.get_gid() for p in ax.patches if p.get_gid().startswith("edge:"))
    ['edge:AP->MP:bidirectional', 'edge:RP->AP:directed', 'edge:RP->MP:directed']
    """
    ax = _new_axes(ax)
    present = _network_nodes(net)
    nodes = list(present) if nodes is None else [*nodes, *(n for n in present if n not in nodes)]
    # Clockwise from the top, as networkx.circular_layout places them in the paper's figures.
    angles = np.pi / 2 - 2 * np.pi * np.arange(len(nodes)) / max(len(nodes), 1)
    position = {name: (np.cos(a), np.sin(a)) for name, a in zip(nodes, angles, strict=True)}
    radius = {name: _node_radius(name, node_size) for name in nodes}
    for name in nodes:
        circle = Circle(position[name], radius[name], facecolor=node_color, edgecolor="0.2",
                        linewidth=0.8, zorder=3,
                        linestyle="-" if name in present else "--")
        circle.set_gid(f"node:{name}")
        ax.add_patch(circle)
        ax.text(*position[name], str(name), ha="center", va="center", zorder=4,
                fontsize=fontsize * min(1.0, 4.0 / max(len(str(name)), 1)) ** 0.5)
    edges = network_edges(net, degenerate=degenerate)
    for edge in edges.itertuples(index=False):
        bidirectional = edge.kind == "bidirectional"
        width = max(min_width, width_scale * edge.weight)
        color = BIDIRECTIONAL_COLOR if bidirectional else DIRECTED_COLOR
        if edge.degenerate:
            color = DEGENERATE_COLOR
        arrow = FancyArrowPatch(
            position[edge.source], position[edge.target],
            arrowstyle="<|-|>" if bidirectional else "-|>",
            # The head grows with the line so that a thick edge does not hide it.
            mutation_scale=fontsize + 1 + 2.0 * width, shrinkA=0, shrinkB=0,
            patchA=None, patchB=None, joinstyle="miter", capstyle="butt",
            linewidth=width, color=color, linestyle="--" if edge.degenerate else "-",
            # Curved slightly so that the arrows of a cycle do not overlap the node labels.
            connectionstyle="arc3,rad=0.08", zorder=2,
        )
        # Stop the arrow at the node's rim rather than its centre.
        arrow.set_positions(*_trim(position[edge.source], position[edge.target],
                                   radius[edge.source], radius[edge.target]))
        suffix = ":degenerate" if edge.degenerate else ""
        arrow.set_gid(f"edge:{edge.source}->{edge.target}:{edge.kind}{suffix}")
        ax.add_patch(arrow)
    ax.set_xlim(-1.3, 1.3)
    ax.set_ylim(-1.3, 1.3)
    ax.set_aspect("equal")
    ax.set_axis_off()
    if title is not None:
        ax.set_title(title, fontsize=fontsize + 1)
    if legend:
        handles = network_legend_handles(width_scale,
                                         degenerate=bool(edges["degenerate"].any()))
        ax.legend(handles=handles, loc="upper center",
                  bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=max(9.0, fontsize - 1), frameon=False,
                  handlelength=2.5)
    return ax


def _node_radius(name: Any, node_size: float) -> float:
    """A node large enough for its name: names of up to three characters fit ``node_size``."""
    return node_size * max(1.0, 0.25 * len(str(name)))


def _trim(a: tuple[float, float], b: tuple[float, float], ra: float,
          rb: float) -> tuple[Any, Any]:
    pa, pb = np.asarray(a), np.asarray(b)
    unit = (pb - pa) / max(np.linalg.norm(pb - pa), 1e-12)
    return tuple(pa + ra * unit), tuple(pb - rb * unit)


def plot_recurrence(
    matrix: Any,
    *,
    cross: bool = False,
    ax: Axes | None = None,
    title: str | None = None,
) -> Axes:
    """Draw a recurrence matrix (or a cross-recurrence matrix) as a recurrence plot.

    Parameters
    ----------
    matrix : array_like of bool, shape (M, M) or (M_X, M_Y)
        The computed matrix, e.g. :func:`funcnet.recurrence.recurrence_matrix` (Eq. 2) or
        :func:`funcnet.recurrence.cross_recurrence_matrix` (Eq. 3).
    cross : bool
        Label the axes as a cross plot (rows X, columns Y).
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
        Black dots at the recurrent pairs; the image's array is the boolean matrix.

    References
    ----------
    Paper section 2.1, Eq. 2-3 and Fig. 1c.

    Examples
    --------
    >>> import numpy as np
    >>> ax = plot_recurrence(np.eye(5, dtype=bool))
    >>> ax.images[0].get_array().shape
    (5, 5)
    """
    ax = _new_axes(ax)
    ax.imshow(np.asarray(matrix, dtype=bool), cmap="binary", origin="lower",
              interpolation="nearest", vmin=0, vmax=1)
    ax.set_xlabel("j (Y)" if cross else "j")
    ax.set_ylabel("i (X)" if cross else "i")
    if title is not None:
        ax.set_title(title)
    return ax


def plot_graph(adjacency: Any, ax: Axes | None = None, *, colors: Any = "tab:blue",
               seed: int = 0) -> Axes:
    """Draw an undirected graph given by its adjacency matrix in a spring layout.

    Parameters
    ----------
    adjacency : array_like, shape (n, n)
        Symmetric adjacency (e.g. a recurrence network, Eq. 2, or an ISRN, Eq. 4); the diagonal
        is ignored.
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    colors : colour or sequence of colours
        Node colour(s), one per row.
    seed : int
        Seed of the force-directed layout (the drawing is deterministic).

    Returns
    -------
    matplotlib.axes.Axes
        Edges as one line collection (gid ``isrn-edges``), nodes as one scatter (gid
        ``isrn-nodes``).

    References
    ----------
    Paper Fig. 1d and Fig. 2d.

    Examples
    --------
    >>> import numpy as np
    >>> ax = plot_graph(np.ones((3, 3)))
    >>> [len(c.get_paths() if c.get_gid() == "isrn-edges" else c.get_offsets())
    ...  for c in ax.collections]
    [3, 3]
    """
    import networkx as nx

    ax = _new_axes(ax)
    matrix = np.asarray(adjacency, dtype=np.int8)
    graph = nx.from_numpy_array(matrix)
    graph.remove_edges_from(nx.selfloop_edges(graph))
    pos = nx.spring_layout(graph, seed=seed)
    xy = np.array([pos[k] for k in range(len(matrix))])
    segments = [(xy[a], xy[b]) for a, b in graph.edges()]
    lines = LineCollection(segments, colors="0.55", linewidths=0.3, zorder=1)
    lines.set_gid("isrn-edges")
    ax.add_collection(lines)
    nodes = ax.scatter(xy[:, 0], xy[:, 1], s=6, c=colors, zorder=2, linewidths=0)
    nodes.set_gid("isrn-nodes")
    ax.set_aspect("equal")
    ax.set_axis_off()
    return ax


def plot_no_network(ax: Axes, label: Any = None) -> Axes:
    """Mark a panel whose network could not be computed: "no network", no axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    label : str, optional
        Its title.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> plot_no_network(Figure().add_subplot(), "cruise").texts[0].get_text()
    'no network'
    """
    ax.set_axis_off()
    if label is not None:
        ax.set_title(str(label), fontsize=9)
    ax.text(0.5, 0.5, "no network", ha="center", va="center", transform=ax.transAxes)
    return ax


def _mark_spans(ax: Axes, spans: Sequence[tuple[str, float, float]], prefix: str,
                label: bool = True) -> None:
    for k, (name, start, stop) in enumerate(spans):
        patch = ax.axvspan(start, stop, color=phase_color(name, k), alpha=0.7,
                           zorder=0, linewidth=0)
        patch.set_gid(f"{prefix}:{name}")
        if label:  # alternate heights so that the names of short phases do not overlap
            ax.annotate(str(name), ((start + stop) / 2, 1.0), xycoords=ax.get_xaxis_transform(),
                        xytext=(0, 2 + 11 * (k % 2)), textcoords="offset points", fontsize=9,
                        ha="center", va="bottom")


def _spans(phases: Any) -> list[tuple[str, float, float]]:
    """(name, start, stop) from a phase table (phase, start, stop) or a sequence of Windows."""
    if isinstance(phases, pd.DataFrame):
        return [(str(r.phase), float(r.start), float(r.stop)) for r in phases.itertuples()]
    return [(str(w.label), float(w.start), float(w.stop)) for w in phases]


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
        _mark_spans(ax, _spans(spans), span_prefix)
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


def _window_time(key: Any, net: Any) -> float:
    """A network's time on a timeline: its key when a number, else its window's centre."""
    try:
        return float(key)
    except (TypeError, ValueError):
        window = getattr(net, "window", None)
        if window and window.get("start") is not None and window.get("stop") is not None:
            return (float(window["start"]) + float(window["stop"])) / 2
        raise ParameterError.of(
            "networks", f"key {key!r} is not a time and its network has no window to place it "
            "by; key the networks by time (seconds), or pass window_networks' result"
        ) from None


def _pair_table(networks: Any, time: str) -> pd.DataFrame:
    if isinstance(networks, pd.DataFrame):
        return networks
    frames = []
    for key, net in networks.items():
        t = _window_time(key, net)
        pairs = net if isinstance(net, pd.DataFrame) else net.pairs
        columns = ["x", "y", "kind", "weight", *(["degenerate"] if "degenerate" in pairs else [])]
        frame = pairs[columns].copy()
        frame[time] = t
        frames.append(frame)
    return pd.concat(frames, ignore_index=True)


def plot_edge_timeline(
    networks: Mapping[float, Any] | pd.DataFrame,
    *,
    time: str = "time",
    ax: Axes | None = None,
    size_scale: float = 600.0,
) -> Axes:
    """Every pair's edge kind and weight over a recording, from sliding windows.

    One horizontal track per pair of signals ``X–Y`` (X the first signal of the pair); at each
    window's time a marker whose colour and shape tell the kind (blue ▶ ``X → Y``, orange ◀
    ``Y → X``, red dot bidirectional, grey dot conflict = no edge; a grey cross for a pair
    flagged ``degenerate``, whatever its kind) and whose area is proportional to the weight of
    Eq. 13. Two legends beside the axes explain the kinds (gid ``legend:kind``)
    and give the marker size of reference weights (gid ``legend:weight``).

    Parameters
    ----------
    networks : mapping of time -> FunctionalNetwork (or pairs table), or pandas.DataFrame
        Networks keyed by the time of their window (e.g. its centre, seconds) -- or keyed by
        label, as :func:`funcnet.window_networks` returns them: each is then placed at its
        window's centre -- or one pairs table of all windows with columns ``x, y, kind,
        weight``, ``time`` and optionally ``degenerate``.
    time : str
        Name of the time column of a table.
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    size_scale : float
        Marker area (points^2) per unit of weight.

    Returns
    -------
    matplotlib.axes.Axes
        One scatter collection per kind present (gid ``kind:KIND``, KIND one of
        :data:`funcnet.network.schema.PAIR_KINDS`, or ``kind:degenerate``), one point per pair
        and window.

    References
    ----------
    Beyond the paper: its phase windows (Fig. 9) sampled continuously.

    Examples
    --------
    >>> import pandas as pd
    >>> rows = pd.DataFrame({"x": ["A", "A"], "y": ["B", "B"], "kind": ["x->y", "conflict"],
    ...                      "weight": [0.1, 0.2], "time": [0.5, 1.0]})
    >>> sum(len(c.get_offsets()) for c in plot_edge_timeline(rows).collections)
    2
    """
    ax = _new_axes(ax, (8.0, 3.0))
    table = _pair_table(networks, time)
    pair_names = list(dict.fromkeys(f"{a}–{b}" for a, b in zip(table["x"], table["y"],
                                                                 strict=True)))
    track = {name: k for k, name in enumerate(pair_names)}
    names = [f"{a}–{b}" for a, b in zip(table["x"], table["y"], strict=True)]
    y = np.array([track[n] for n in names], dtype=float)
    kinds = table["kind"].astype(str)
    if "degenerate" in table.columns:
        kinds = kinds.where(~table["degenerate"].eq(True), "degenerate")
    first, second = (str(table["x"].iloc[0]), str(table["y"].iloc[0])) if len(table) else "XY"
    weights = table["weight"].to_numpy(dtype=float)
    for kind, marker, label in (
            (_X_Y, ">", f"X → Y, e.g. {first} → {second} on track {first}–{second}"),
            (_Y_X, "<", f"Y → X, e.g. {second} → {first} on track {first}–{second}"),
            (_BIDIRECTIONAL, "o", "bidirectional"),
            (_CONFLICT, "o", "conflict (no edge)"),
            ("degenerate", "X", "degenerate (arrow meaningless)")):
        mask = (kinds == kind).to_numpy()
        if not mask.any():
            continue
        points = ax.scatter(table[time].to_numpy(dtype=float)[mask], y[mask],
                            s=np.maximum(4.0, size_scale * weights[mask]), marker=marker,
                            color=KIND_COLORS[kind], label=label, linewidths=0)
        points.set_gid(f"kind:{kind}")
    ax.set_yticks(range(len(pair_names)), pair_names, fontsize=9)
    ax.set_ylabel("pair X–Y", fontsize=9)
    ax.set_ylim(-0.7, len(pair_names) - 0.3)
    ax.invert_yaxis()
    ax.set_xlabel("window time [s]")
    kind_legend = ax.legend(fontsize=9, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                            frameon=False, title="edge kind (marker)", title_fontsize=9)
    kind_legend.set_gid("legend:kind")
    for handle in kind_legend.legend_handles:  # same size for every kind in the key
        if isinstance(handle, PathCollection):
            handle.set_sizes([30.0])
    ax.add_artist(kind_legend)
    scale = [Line2D([], [], linestyle="", marker="o", color="0.5",
                    markersize=float(np.sqrt(max(4.0, size_scale * w))), label=f"{w:g}")
             for w in _reference_weights(weights)]
    weight_legend = ax.legend(handles=scale, fontsize=9, loc="lower left",
                              bbox_to_anchor=(1.0, 0.0), frameon=False, ncol=len(scale),
                              title="weight (Eq. 13, marker area ∝ weight)", title_fontsize=9)
    weight_legend.set_gid("legend:weight")
    return ax


def _reference_weights(weights: np.ndarray) -> list[float]:
    """The three largest round weights (1, 2, 5 × 10^k) not above the data's largest weight."""
    top = float(np.nanmax(weights)) if weights.size and np.nanmax(weights) > 0 else 0.1
    round_weights = [m * 10.0 ** e for e in range(-4, 2) for m in (1, 2, 5)]
    return [float(f"{w:.1g}") for w in round_weights if w <= top][-3:]




def add_network_legend(fig: Figure, width_scale: float = 10.0, *,
                       degenerate: bool = False) -> Any:
    """One legend of the edge colours and widths below a figure of several networks.

    Draw the panels with ``plot_network(..., legend=False)`` and call this once.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (constrained layout makes room for the legend below the panels).
    width_scale : float
        The panels' line width per unit of weight.
    degenerate : bool
        Explain degenerate edges too (when a panel draws some).

    Returns
    -------
    matplotlib.legend.Legend
        The legend (gid ``legend:network``), entries of :func:`network_legend_handles`.

    Examples
    --------
    >>> fig = Figure(layout="constrained")
    >>> add_network_legend(fig).get_gid()
    'legend:network'
    """
    legend = fig.legend(handles=network_legend_handles(width_scale, degenerate=degenerate),
                        loc="outside lower center", ncol=3, fontsize=9, frameon=False,
                        handlelength=2.5)
    legend.set_gid("legend:network")
    return legend


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


def network_title(net: Any, source: str | None = None) -> str:
    """A network's title: trace, window (label and span) and its parameters, on two lines.

    Parameters
    ----------
    net : FunctionalNetwork
    source : str, optional
        The trace; default the file of the network's window.

    Returns
    -------
    str

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.network import functional_network
    >>> x = np.random.default_rng(0).random((120, 2))
    >>> print(network_title(functional_network(x, delay=1, warn=False, label="cruise 1")))
    cruise 1 (120 samples)
    m = 3, τ = 1, RR = 0.05, CR = 0.05, μ = 0.05, minmax
    """
    window = getattr(net, "window", None) or {}
    source = source if source is not None else window.get("source")
    where = [Path(str(source)).name] if source else []
    label = net.label or window.get("label")
    if label:
        where.append(str(label))
    if window.get("start") is not None:
        where.append(f"{float(window['start']):.3f}–{float(window['stop']):.3f} s")
    p = net.parameters
    first = " · ".join(where) + f" ({net.n_samples} samples)"
    second = (f"m = {p.dim}, τ = {p.delay}, RR = {p.rr}, CR = {p.cr}, μ = {p.mu}, "
              f"{p.normalize or 'not normalized'}")
    return f"{first.strip()}\n{second}"


def save_network(net: Any, path: str | os.PathLike[str], *,
                 size: tuple[float, float] = (7.0, 7.5), dpi: int = 100,
                 title: str | None = None) -> Path:
    """Draw a network into an image file (PNG, SVG or PDF), titled and with its legend.

    Parameters
    ----------
    net : FunctionalNetwork
    path : path-like
        The file; its suffix (``.png``, ``.svg``, ``.pdf``) names the format. Written
        atomically.
    size : (float, float)
        Width and height in inches (pixels = inches × ``dpi`` for PNG).
    dpi : int
        Resolution of a PNG.
    title : str, optional
        Default :func:`network_title`: trace, window, parameters.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        Another suffix, or a size that is not positive.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from funcnet.network import functional_network
    >>> net = functional_network(np.random.default_rng(0).random((120, 3)), delay=1, warn=False)
    >>> out = save_network(net, pathlib.Path(tempfile.mkdtemp()) / "net.png", size=(8, 6))
    >>> from matplotlib.image import imread
    >>> imread(out).shape[:2]
    (600, 800)
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".png", ".svg", ".pdf"):
        raise ParameterError.of("path", f"must end in .png, .svg or .pdf, got {path.name!r}")
    if len(size) != 2 or not all(float(v) > 0 for v in size):
        raise ParameterError.of("size", f"must be two positive sizes in inches, got {size!r}")
    fig = Figure(figsize=(float(size[0]), float(size[1])), dpi=dpi, layout="constrained")
    ax = fig.add_subplot()
    plot_network(net, ax, legend=True)
    ax.set_title(network_title(net) if title is None else title, fontsize=10)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=suffix[1:], dpi=dpi)
    return path
