"""Figures: functional networks, recurrence plots and the paper's Figures 1, 2, 5, 9, 10 and 11.

Every figure is drawn from funcnet's own computations (:func:`funcnet.recurrence_matrix`,
:func:`funcnet.isrn_adjacency`, :func:`funcnet.functional_network`); nothing is re-derived here.
Single-panel functions take ``ax=`` and return it; multi-panel ones return a
:class:`matplotlib.figure.Figure`. Everything works on the Agg backend (no display needed).

Drawing conventions (README method step 8, paper section 3.4): nodes on a circle, one per signal,
every node drawn even without edges; directed edges black with an arrow head at the target,
bidirectional edges red; line width proportional to the weight of Eq. 13 on an absolute scale, so
that widths compare across panels (the paper reads "edges thinning as speed grows" from them).

Every drawn artist carries a ``gid`` (``"node:RP"``, ``"edge:RP->AP:directed"``,
``"phase:cruise"``, ``"window:-20 ms"``) so that tests and users can find what was drawn.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4
   and Figures 1, 2, 5, 9, 10 and 11.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch

from funcnet.network import edges_from_pairs

__all__ = [
    "DIRECTED_COLOR",
    "BIDIRECTIONAL_COLOR",
    "SIGNAL_COLORS",
    "signal_color",
    "network_edges",
    "network_legend_handles",
    "add_network_legend",
    "plot_network",
    "plot_recurrence",
    "plot_signals",
    "plot_edge_timeline",
    "figure_embedding_network",
    "figure_isrn",
    "figure_pair_network",
    "figure_phases",
    "figure_velocity_grid",
    "figure_reversal",
]

DIRECTED_COLOR = "black"
BIDIRECTIONAL_COLOR = "red"
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
_KIND_COLORS = {"forward": "#1f4e9c", "backward": "#e07b00", "bidirectional": "red",
                "conflict": "0.6"}


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


def network_legend_handles(width_scale: float = 10.0, weight: float = 0.2) -> list[Line2D]:
    """Legend entries explaining a network drawing: edge colours and the width scale.

    Parameters
    ----------
    width_scale : float
        The line width per unit of weight used by :func:`plot_network`.
    weight : float
        The reference weight (Eq. 13) whose width the legend shows.

    Returns
    -------
    list of matplotlib.lines.Line2D
        Directed (black), bidirectional (red), and a grey line of the reference weight's width.

    Examples
    --------
    >>> [h.get_label() for h in network_legend_handles()]
    ['directed X → Y', 'bidirectional', 'weight 0.2 (width ∝ weight)']
    """
    return [Line2D([], [], color=DIRECTED_COLOR, linewidth=1.5, marker=">", label="directed X → Y"),
            Line2D([], [], color=BIDIRECTIONAL_COLOR, linewidth=1.5, label="bidirectional"),
            Line2D([], [], color="0.4", linewidth=width_scale * weight,
                   label=f"weight {weight:g} (width ∝ weight)")]


def network_edges(net: Any) -> pd.DataFrame:
    """The edges to draw: a network's ``.edges``, or those of a pairs table.

    Parameters
    ----------
    net : FunctionalNetwork or pandas.DataFrame
        A :class:`funcnet.FunctionalNetwork`, or a pairs table with at least the columns
        ``x, y, kind, weight`` (e.g. one window's rows of a study's results).

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind`` (:func:`funcnet.network.edges_from_pairs`).
    """
    if isinstance(net, pd.DataFrame):
        return edges_from_pairs(net)
    return net.edges


def _network_nodes(net: Any) -> list[str]:
    if isinstance(net, pd.DataFrame):
        return list(dict.fromkeys([*net["x"], *net["y"]]))
    return list(net.nodes)


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
    fontsize: float = 8.0,
    legend: bool = True,
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

    Returns
    -------
    matplotlib.axes.Axes
        The axes; each node is a :class:`~matplotlib.patches.Circle` with gid ``node:NAME``,
        each edge a :class:`~matplotlib.patches.FancyArrowPatch` with gid
        ``edge:SOURCE->TARGET:KIND``, black when directed and red when bidirectional.

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
    for edge in network_edges(net).itertuples(index=False):
        bidirectional = edge.kind == "bidirectional"
        width = max(min_width, width_scale * edge.weight)
        arrow = FancyArrowPatch(
            position[edge.source], position[edge.target],
            arrowstyle="<|-|>" if bidirectional else "-|>",
            # The head grows with the line so that a thick edge does not hide it.
            mutation_scale=fontsize + 1 + 2.0 * width, shrinkA=0, shrinkB=0,
            patchA=None, patchB=None, joinstyle="miter", capstyle="butt",
            linewidth=width,
            color=BIDIRECTIONAL_COLOR if bidirectional else DIRECTED_COLOR,
            # Curved slightly so that the arrows of a cycle do not overlap the node labels.
            connectionstyle="arc3,rad=0.08", zorder=2,
        )
        # Stop the arrow at the node's rim rather than its centre.
        arrow.set_positions(*_trim(position[edge.source], position[edge.target],
                                   radius[edge.source], radius[edge.target]))
        arrow.set_gid(f"edge:{edge.source}->{edge.target}:{edge.kind}")
        ax.add_patch(arrow)
    ax.set_xlim(-1.3, 1.3)
    ax.set_ylim(-1.3, 1.3)
    ax.set_aspect("equal")
    ax.set_axis_off()
    if title is not None:
        ax.set_title(title, fontsize=fontsize + 1)
    if legend:
        ax.legend(handles=network_legend_handles(width_scale), loc="upper center",
                  bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=fontsize - 1, frameon=False,
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
    x: Any,
    y: Any = None,
    *,
    dim: int = 3,
    delay: int = 10,
    rr: float | None = None,
    eps: float | None = None,
    metric: str = "euclidean",
    theiler: int = 0,
    ax: Axes | None = None,
    title: str | None = None,
) -> Axes:
    """Recurrence plot of one window (or cross-recurrence plot of two).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal (e.g. one column of a window of a recording), used as given.
    y : array_like, optional
        A second signal: draw the cross-recurrence matrix ``CR_XY`` (Eq. 3) instead.
    dim, delay, rr, eps, metric, theiler
        As in :func:`funcnet.recurrence_matrix` (``rr`` or ``eps``; for a cross plot ``rr`` is
        passed as the cross rate ``cr``). Neither given: ``rr=0.05`` (paper section 3.4).
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
        Black dots at the recurrent pairs (Eq. 2-3); the image's array is the boolean matrix.

    References
    ----------
    Paper section 2.1, Eq. 1-3 and Fig. 1c.

    Examples
    --------
    >>> import numpy as np
    >>> ax = plot_recurrence(np.sin(np.linspace(0, 8 * np.pi, 251)), eps=0.15)
    >>> ax.images[0].get_array().shape
    (231, 231)
    """
    import funcnet

    ax = _new_axes(ax)
    if rr is None and eps is None:
        rr = 0.05
    if y is None:
        matrix = funcnet.recurrence_matrix(x, dim=dim, delay=delay, rr=rr, eps=eps,
                                           metric=metric, theiler=theiler)
    else:
        matrix = funcnet.cross_recurrence_matrix(x, y, dim=dim, delay=delay, cr=rr, eps=eps,
                                                 metric=metric)
    ax.imshow(np.asarray(matrix, dtype=bool), cmap="binary", origin="lower",
              interpolation="nearest", vmin=0, vmax=1)
    ax.set_xlabel("j" if y is None else "j (Y)")
    ax.set_ylabel("i" if y is None else "i (X)")
    if title is not None:
        ax.set_title(title)
    return ax


def _mark_spans(ax: Axes, spans: Sequence[tuple[str, float, float]], prefix: str,
                label: bool = True) -> None:
    for k, (name, start, stop) in enumerate(spans):
        patch = ax.axvspan(start, stop, color=_PHASE_SHADES[k % len(_PHASE_SHADES)], alpha=0.7,
                           zorder=0, linewidth=0)
        patch.set_gid(f"{prefix}:{name}")
        if label:  # alternate heights so that the names of short phases do not overlap
            ax.annotate(str(name), ((start + stop) / 2, 1.0), xycoords=ax.get_xaxis_transform(),
                        xytext=(0, 2 + 9 * (k % 2)), textcoords="offset points", fontsize=7,
                        ha="center", va="bottom")


# Title padding (points) that clears the two rows of phase names drawn by _mark_spans.
_SPAN_TITLE_PAD = 22.0


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
        ax.legend(fontsize=6, ncol=min(len(data.columns), 6), loc="upper left", frameon=False)
    return ax


def _pair_table(networks: Any, time: str) -> pd.DataFrame:
    if isinstance(networks, pd.DataFrame):
        return networks
    frames = []
    for t, net in networks.items():
        pairs = net if isinstance(net, pd.DataFrame) else net.pairs
        frame = pairs[["x", "y", "kind", "weight"]].copy()
        frame[time] = float(t)
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
    ``Y → X``, red dot bidirectional, grey dot conflict = no edge) and whose area is proportional
    to the weight of Eq. 13. Two legends beside the axes explain the kinds (gid ``legend:kind``)
    and give the marker size of reference weights (gid ``legend:weight``).

    Parameters
    ----------
    networks : mapping of time -> FunctionalNetwork (or pairs table), or pandas.DataFrame
        Networks keyed by the time of their window (e.g. its centre, seconds), or one pairs
        table of all windows with columns ``x, y, kind, weight`` and ``time``.
    time : str
        Name of the time column of a table.
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    size_scale : float
        Marker area (points^2) per unit of weight.

    Returns
    -------
    matplotlib.axes.Axes
        One scatter collection per kind present (gid ``kind:...``), one point per pair and window.

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
    kinds = table["kind"].map({"x->y": "forward", "y->x": "backward"}).fillna(table["kind"])
    first, second = (str(table["x"].iloc[0]), str(table["y"].iloc[0])) if len(table) else "XY"
    weights = table["weight"].to_numpy(dtype=float)
    for kind, marker, label in (
            ("forward", ">", f"X → Y, e.g. {first} → {second} on track {first}–{second}"),
            ("backward", "<", f"Y → X, e.g. {second} → {first} on track {first}–{second}"),
            ("bidirectional", "o", "bidirectional"),
            ("conflict", "o", "conflict (no edge)")):
        mask = (kinds == kind).to_numpy()
        if not mask.any():
            continue
        points = ax.scatter(table[time].to_numpy(dtype=float)[mask], y[mask],
                            s=np.maximum(4.0, size_scale * weights[mask]), marker=marker,
                            color=_KIND_COLORS[kind], label=label, linewidths=0)
        points.set_gid(f"kind:{kind}")
    ax.set_yticks(range(len(pair_names)), pair_names, fontsize=7)
    ax.set_ylabel("pair X–Y", fontsize=8)
    ax.set_ylim(-0.7, len(pair_names) - 0.3)
    ax.invert_yaxis()
    ax.set_xlabel("window time [s]")
    kind_legend = ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                            frameon=False, title="edge kind (marker)", title_fontsize=7)
    kind_legend.set_gid("legend:kind")
    for handle in kind_legend.legend_handles:  # same size for every kind in the key
        if isinstance(handle, PathCollection):
            handle.set_sizes([30.0])
    ax.add_artist(kind_legend)
    scale = [Line2D([], [], linestyle="", marker="o", color="0.5",
                    markersize=float(np.sqrt(max(4.0, size_scale * w))), label=f"{w:g}")
             for w in _reference_weights(weights)]
    weight_legend = ax.legend(handles=scale, fontsize=7, loc="lower left",
                              bbox_to_anchor=(1.0, 0.0), frameon=False, ncol=len(scale),
                              title="weight (Eq. 13, marker area ∝ weight)", title_fontsize=7)
    weight_legend.set_gid("legend:weight")
    return ax


def _reference_weights(weights: np.ndarray) -> list[float]:
    """The three largest round weights (1, 2, 5 × 10^k) not above the data's largest weight."""
    top = float(np.nanmax(weights)) if weights.size and np.nanmax(weights) > 0 else 0.1
    round_weights = [m * 10.0 ** e for e in range(-4, 2) for m in (1, 2, 5)]
    return [float(f"{w:.1g}") for w in round_weights if w <= top][-3:]


def _sine(n: int, periods: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2 * np.pi * periods, n)
    return t, np.sin(t)


def _draw_graph(ax: Axes, adjacency: np.ndarray, colors: Any, seed: int) -> None:
    import networkx as nx

    graph = nx.from_numpy_array(np.asarray(adjacency, dtype=np.int8))
    graph.remove_edges_from(nx.selfloop_edges(graph))
    pos = nx.spring_layout(graph, seed=seed)
    xy = np.array([pos[k] for k in range(len(adjacency))])
    segments = [(xy[a], xy[b]) for a, b in graph.edges()]
    lines = LineCollection(segments, colors="0.55", linewidths=0.3, zorder=1)
    lines.set_gid("isrn-edges")
    ax.add_collection(lines)
    nodes = ax.scatter(xy[:, 0], xy[:, 1], s=6, c=colors, zorder=2, linewidths=0)
    nodes.set_gid("isrn-nodes")
    ax.set_aspect("equal")
    ax.set_axis_off()


def figure_embedding_network(
    *, n: int = 251, periods: float = 4, dim: int = 3, delay: int = 10, eps: float = 0.15,
    seed: int = 0,
) -> Figure:
    """Fig. 1: a sine, its embedding, its recurrence matrix and its recurrence network.

    Parameters
    ----------
    n : int
        Number of samples of ``x(t) = sin t`` over ``periods`` periods (paper: 251 over four).
    periods : float
        Number of periods.
    dim, delay : int
        Embedding dimension and delay in samples (paper: 3 and 10).
    eps : float
        Fixed recurrence threshold (paper: 0.15).
    seed : int
        Seed of the spring layout (the drawing is deterministic).

    Returns
    -------
    matplotlib.figure.Figure
        Panels (a) signal, (b) ``x(t)`` vs ``x(t+τ)``, (c) recurrence matrix, (d) recurrence
        network in a force-directed spring layout.

    References
    ----------
    Paper section 2.1, Eq. 1-2 and Fig. 1.

    Examples
    --------
    >>> fig = figure_embedding_network(n=101, periods=2)
    >>> len(fig.axes)
    4
    """
    import funcnet

    t, x = _sine(n, periods)
    states = funcnet.embed(x, dim, delay)
    matrix = funcnet.recurrence_matrix(x, dim=dim, delay=delay, eps=eps)
    fig = Figure(figsize=(12.0, 3.2), layout="constrained")
    ax_a, ax_b, ax_c, ax_d = fig.subplots(1, 4)
    ax_a.plot(np.arange(n), x, color="tab:blue", linewidth=1)
    ax_a.set_xlabel("$t_i$")
    ax_a.set_ylabel("x")
    ax_a.set_title("(a) x(t) = sin t", fontsize=9)
    ax_b.plot(states[:, 0], states[:, 1], ".", markersize=2, color="tab:blue")
    ax_b.set_xlabel("x(t)")
    ax_b.set_ylabel(f"x(t+{delay})")
    ax_b.set_title(f"(b) embedding, m={dim}, τ={delay}", fontsize=9)
    plot_recurrence(x, dim=dim, delay=delay, eps=eps, ax=ax_c)
    ax_c.set_title(f"(c) recurrence matrix, ε={eps}", fontsize=9)
    _draw_graph(ax_d, matrix, "tab:blue", seed)
    ax_d.set_title("(d) recurrence network", fontsize=9)
    return fig


def _coupled_pair(n: int, periods: float, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    t, x = _sine(n, periods)
    return x, np.sin(1.5 * t) + alpha * x


def figure_isrn(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    eps: tuple[float, float, float] = (0.15, 0.15, 0.05), seed: int = 0,
) -> Figure:
    """Fig. 2: the inter-system recurrence network of ``x = sin t``, ``y = sin 1.5t + 0.3x``.

    Parameters
    ----------
    n, periods : int, float
        Samples and periods (paper: 251 over four).
    alpha : float
        Coupling strength of X into Y (paper: 0.3).
    dim, delay : int
        Embedding (paper: m = 3, τ = 10).
    eps : (float, float, float)
        ``(ε_X, ε_Y, ε_XY)`` (paper: 0.15, 0.15, 0.05).
    seed : int
        Seed of the spring layout.

    Returns
    -------
    matplotlib.figure.Figure
        (a) both signals, (b) their embeddings, (c) the ISRN adjacency of Eq. 4 (blocks
        ``A_X``, ``CR_XY``, ``A_Y``), (d) the ISRN in a spring layout, X blue and Y red.

    References
    ----------
    Paper section 2.2, Eq. 3-4 and Fig. 2.

    Examples
    --------
    >>> len(figure_isrn(n=101, periods=2).axes)
    4
    """
    import funcnet

    x, y = _coupled_pair(n, periods, alpha)
    adjacency = np.asarray(funcnet.isrn_adjacency(x, y, dim=dim, delay=delay, eps=eps))
    m = len(adjacency) // 2
    fig = Figure(figsize=(12.0, 3.2), layout="constrained")
    ax_a, ax_b, ax_c, ax_d = fig.subplots(1, 4)
    ax_a.plot(x, color="tab:blue", linewidth=1, label="x")
    ax_a.plot(y, color="tab:red", linewidth=1, label="y")
    ax_a.legend(fontsize=7, frameon=False)
    ax_a.set_xlabel("$t_i$")
    ax_a.set_title(f"(a) x = sin t, y = sin 1.5t + {alpha}x", fontsize=9)
    for signal, color in ((x, "tab:blue"), (y, "tab:red")):
        states = funcnet.embed(signal, dim, delay)
        ax_b.plot(states[:, 0], states[:, 1], ".", markersize=2, color=color)
    ax_b.set_xlabel("s(t)")
    ax_b.set_ylabel(f"s(t+{delay})")
    ax_b.set_title(f"(b) embeddings, m={dim}, τ={delay}", fontsize=9)
    ax_c.imshow(adjacency.astype(bool), cmap="binary", origin="upper", interpolation="nearest")
    ax_c.axhline(m - 0.5, color="tab:green", linewidth=0.8)
    ax_c.axvline(m - 0.5, color="tab:green", linewidth=0.8)
    ax_c.set_title("(c) $A_X$ | $CR_{XY}$ / $CR_{YX}$ | $A_Y$", fontsize=9)
    _draw_graph(ax_d, adjacency, ["tab:blue"] * m + ["tab:red"] * m, seed)
    ax_d.set_title("(d) ISRN", fontsize=9)
    return fig


def figure_pair_network(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    mu: float = 0.05, ax: Axes | None = None,
) -> Axes:
    """Fig. 5: the functional network of the coupled pair of Fig. 2, from ``C_diff`` alone.

    The network is computed by :func:`funcnet.functional_network` with ``measure="clustering"``
    on the signals as given (``normalize=None``) at the default rates (RR = CR = 0.05).

    Parameters
    ----------
    n, periods, alpha, dim, delay
        As in :func:`figure_isrn`.
    mu : float
        Bidirectionality threshold of section 2.4.
    ax : matplotlib.axes.Axes, optional
        Where to draw.

    Returns
    -------
    matplotlib.axes.Axes
        The network (nodes ``x`` and ``y``); the title gives ``C_diff``.

    References
    ----------
    Paper section 2.4, Eq. 10 and Fig. 5.

    Examples
    --------
    >>> ax = figure_pair_network(n=151, periods=3)
    >>> sorted(p.get_gid() for p in ax.patches if p.get_gid().startswith("node:"))
    ['node:x', 'node:y']
    """
    import funcnet

    x, y = _coupled_pair(n, periods, alpha)
    net = funcnet.functional_network(np.column_stack([x, y]), names=["x", "y"], dim=dim,
                                     delay=delay, mu=mu, normalize=None, measure="clustering",
                                     label="Fig. 5")
    c_diff = float(net.pairs["c_diff"].iloc[0])
    return plot_network(net, ax, title=f"C_diff = {c_diff:+.3f} (μ = {mu})")


def _no_network(ax: Axes, label: Any) -> None:
    ax.set_axis_off()
    if label is not None:
        ax.set_title(str(label), fontsize=9)
    ax.text(0.5, 0.5, "no network", ha="center", va="center", transform=ax.transAxes)


def _network_row(fig: Figure, grid: Any, row: int, networks: Mapping[str, Any],
                 nodes: Sequence[str]) -> None:
    """One network per column of a grid row, each node at the same place in every panel."""
    for k, (label, net) in enumerate(networks.items()):
        ax = fig.add_subplot(grid[row, k])
        if net is None:
            _no_network(ax, label)
        else:
            plot_network(net, ax, nodes=nodes, title=str(label), legend=False)


def add_network_legend(fig: Figure, width_scale: float = 10.0) -> Any:
    """One legend of the edge colours and widths below a figure of several networks.

    Draw the panels with ``plot_network(..., legend=False)`` and call this once.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (constrained layout makes room for the legend below the panels).
    width_scale : float
        The panels' line width per unit of weight.

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
    legend = fig.legend(handles=network_legend_handles(width_scale), loc="outside lower center",
                        ncol=3, fontsize=7, frameon=False, handlelength=2.5)
    legend.set_gid("legend:network")
    return legend


def _signal_figure_legend(fig: Figure, names: Sequence[str]) -> None:
    """One legend of the signals' colours above a figure of several series panels."""
    handles = [Line2D([], [], color=signal_color(name), linewidth=1.5, label=str(name))
               for name in names]
    legend = fig.legend(handles=handles, loc="outside upper center", ncol=len(handles),
                        fontsize=7, frameon=False)
    legend.set_gid("legend:signals")


def _raw_groups(data: pd.DataFrame) -> list[tuple[str, list[str]]]:
    """Panels of raw signals that share units: positions, velocity, currents, the rest."""
    groups = [("positions [°]", [c for c in ("RP", "AP", "MP") if c in data]),
              ("velocity [°/s]", [c for c in ("V",) if c in data]),
              ("currents [A]", [c for c in ("RC", "AC") if c in data])]
    grouped = {c for _, columns in groups for c in columns}
    groups.append(("other", [c for c in data.columns if c not in grouped]))
    return [(label, columns) for label, columns in groups if columns]


def figure_phases(
    data: pd.DataFrame,
    phases: Any,
    networks: Mapping[str, Any],
    *,
    title: str | None = None,
) -> Figure:
    """Fig. 9: a trial's normalized and raw signals with its phases, and a network per phase.

    Parameters
    ----------
    data : pandas.DataFrame
        The trial's signals (time in seconds as index; columns RP, AP, MP, V, RC, AC or any).
    phases : phase table or sequence of Window
        The phases (``phase, start, stop`` from :func:`funcnet.robot.detect_phases`, or windows).
    networks : mapping of label -> FunctionalNetwork or None
        One network per phase, in drawing order (e.g. from :func:`funcnet.robot.phase_networks`);
        ``None`` where none could be computed. Nodes are placed in the order of ``data``'s
        columns in every panel.
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        (a) normalized signals, (b) raw signals in panels of shared units (positions [°],
        velocity [°/s] as in the paper, currents [A], any other column), phases shaded (gid
        ``phase:NAME``) on each; below, one network per phase.

    References
    ----------
    Paper section 4.1 and Fig. 9.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> t = np.arange(500) * 0.002
    >>> data = pd.DataFrame({"RP": t ** 2, "AC": np.cos(9 * t)}, index=t)
    >>> net = pd.DataFrame({"x": ["RP"], "y": ["AC"], "kind": ["y->x"], "weight": [0.2]})
    >>> phases = pd.DataFrame({"phase": ["spin-up", "cruise"], "start": [0.0, 0.4],
    ...                        "stop": [0.4, 1.0]})
    >>> fig = figure_phases(data, phases, {"spin-up": net, "cruise": None})
    >>> [ax.get_title() for ax in fig.axes if ax.patches and not ax.lines]
    ['spin-up']
    """
    groups = _raw_groups(data)
    fig = Figure(figsize=(max(8.0, 2.4 * len(networks)), 4.6 + 1.5 * len(groups)),
                 layout="constrained")
    grid = fig.add_gridspec(2 + len(groups), max(len(networks), 1),
                            height_ratios=[1.2, *[0.8] * len(groups), 1.6])
    top = fig.add_subplot(grid[0, :])
    plot_signals(data, normalize=True, spans=phases, ax=top)
    top.set_title("(a) min–max normalized", fontsize=9, loc="left", pad=_SPAN_TITLE_PAD)
    for k, (ylabel, columns) in enumerate(groups):
        ax = fig.add_subplot(grid[1 + k, :], sharex=top)
        plot_signals(data[columns], normalize=False, spans=phases, ax=ax)
        ax.set_ylabel(ylabel, fontsize=7)
        ax.set_xlabel("")
        if k == 0:
            ax.set_title("(b) raw", fontsize=9, loc="left", pad=_SPAN_TITLE_PAD)
    _network_row(fig, grid, -1, networks, list(data.columns))
    add_network_legend(fig)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def figure_velocity_grid(
    cells: Mapping[tuple[str, str], tuple[pd.DataFrame, Any]],
    *,
    title: str | None = None,
) -> Figure:
    """Fig. 10: velocities (columns) × phases (rows), each cell a window's series over its network.

    Parameters
    ----------
    cells : mapping of (velocity label, phase label) -> (window data, FunctionalNetwork or None)
        Column order follows the first appearance of each velocity, row order that of each phase.
        A cell whose network could not be computed (``None``) shows its series and the text
        "no network".
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        For each cell a short axes of normalized series and an axes with the network; one
        legend of the signals above the grid (gid ``legend:signals``) and one of the edges
        below it (gid ``legend:network``).

    References
    ----------
    Paper section 4.2 and Fig. 10.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> window = pd.DataFrame({"RP": np.arange(10.0), "AC": np.ones(10)})
    >>> net = pd.DataFrame({"x": ["RP"], "y": ["AC"], "kind": ["bidirectional"], "weight": [0.0]})
    >>> cells = {(v, p): (window, net) for v in ("V35", "V175") for p in ("cruise", "braking")}
    >>> len(figure_velocity_grid(cells).axes)
    8
    """
    velocities = list(dict.fromkeys(v for v, _ in cells))
    phases = list(dict.fromkeys(p for _, p in cells))
    fig = Figure(figsize=(2.6 * len(velocities), 3.6 * len(phases)), layout="constrained")
    grid = fig.add_gridspec(2 * len(phases), len(velocities),
                            height_ratios=[0.6, 1.4] * len(phases))
    for (velocity, phase), (window, net) in cells.items():
        row, col = 2 * phases.index(phase), velocities.index(velocity)
        series = fig.add_subplot(grid[row, col])
        plot_signals(window, normalize=True, ax=series, legend=False)
        series.set_title(f"{velocity} · {phase}", fontsize=8)
        series.tick_params(labelsize=6)
        series.set_xlabel("time [s]", fontsize=6, labelpad=1)
        series.set_ylabel("normalized" if col == 0 else "", fontsize=6)
        graph = fig.add_subplot(grid[row + 1, col])
        if net is None:
            _no_network(graph, None)
        else:
            plot_network(net, graph, nodes=list(window.columns), legend=False)
    _signal_figure_legend(fig, list(dict.fromkeys(c for window, _ in cells.values()
                                                  for c in window.columns)))
    add_network_legend(fig)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def figure_reversal(
    data: pd.DataFrame,
    windows: Sequence[Any],
    networks: Mapping[str, Any],
    *,
    phases: Any = None,
    zoom: tuple[float, float] | None = None,
    title: str | None = None,
) -> Figure:
    """Fig. 11: a backlash trial, its reversal and the networks of the shifted windows.

    Parameters
    ----------
    data : pandas.DataFrame
        The whole trial (time in seconds as index).
    windows : sequence of Window
        The reversal windows (e.g. offsets −40, −20, 0, +20, +40 ms from
        :func:`funcnet.robot.reversal_windows`); each is shaded in the zoom (gid
        ``window:LABEL``).
    networks : mapping of label -> FunctionalNetwork or None
        The network of each window, in drawing order.
    phases : phase table or sequence of Window, optional
        The trial's phases, shaded on the full view (gid ``phase:NAME``).
    zoom : (float, float), optional
        Time range of the zoom; by default the windows' span with a margin of half its length.
    title : str, optional
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        (a) full motion, normalized, with the phases; (b) the zoom with the windows; below, one
        network per window.

    References
    ----------
    Paper section 4.3 and Fig. 11.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.windows import Window
    >>> t = np.arange(1000) * 0.002
    >>> data = pd.DataFrame({"RP": np.abs(t - 1.0), "V": np.sign(t - 1.0)}, index=t)
    >>> windows = [Window(f"{s:+d} ms", 0.9 + s / 1000, 1.1 + s / 1000, offset=s / 1000)
    ...            for s in (-20, 0, 20)]
    >>> net = pd.DataFrame({"x": ["V"], "y": ["RP"], "kind": ["x->y"], "weight": [0.1]})
    >>> fig = figure_reversal(data, windows, {w.label: net for w in windows})
    >>> sorted(p.get_gid() for p in fig.axes[1].patches)
    ['window:+0 ms', 'window:+20 ms', 'window:-20 ms']
    """
    fig = Figure(figsize=(max(8.0, 2.4 * len(networks)), 6.5), layout="constrained")
    grid = fig.add_gridspec(3, max(len(networks), 1), height_ratios=[1.0, 1.0, 1.5])
    full = fig.add_subplot(grid[0, :])
    plot_signals(data, normalize=True, spans=phases, ax=full)
    full.set_title("(a) full motion", fontsize=9, loc="left",
                   pad=_SPAN_TITLE_PAD if phases is not None else None)
    if zoom is None:
        lo = min(float(w.start) for w in windows)
        hi = max(float(w.stop) for w in windows)
        zoom = (lo - (hi - lo) / 2, hi + (hi - lo) / 2)
    part = data.loc[(data.index >= zoom[0]) & (data.index <= zoom[1])]
    ax_zoom = fig.add_subplot(grid[1, :])
    plot_signals(part, normalize=True, ax=ax_zoom, legend=False)
    for k, window in enumerate(windows):
        patch = ax_zoom.axvspan(float(window.start), float(window.stop), ymin=0.02 + 0.04 * k,
                                ymax=0.06 + 0.04 * k, color=f"C{k}", alpha=0.8)
        patch.set_gid(f"window:{window.label}")
    ax_zoom.set_title("(b) reversal, shifted windows", fontsize=9, loc="left")
    _network_row(fig, grid, 2, networks, list(data.columns))
    add_network_legend(fig)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig
