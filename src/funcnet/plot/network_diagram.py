"""Drawing functional networks: circular layout, edge colours and widths, legends, titles.

Paper section 3.4: nodes on a circle, one per signal, every node drawn even without edges;
directed edges black with an arrow head at the target, bidirectional edges red; line width
proportional to the weight of Eq. 13 on an absolute scale, so that widths compare across panels.
Edges of degenerate pairs (kept only with ``degenerate="keep"``) are drawn dashed and grey.

Length: just over 600 lines; the drawing, its edge styles per reading and the shared legend
belong together.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch, PathPatch
from matplotlib.path import Path as BezierPath

from funcnet._io import atomic_path
from funcnet.errors import ParameterError
from funcnet.plot.style import (
    BIDIRECTIONAL_COLOR,
    DEGENERATE_COLOR,
    DIRECTED_COLOR,
    _new_axes,
)

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = [
    "network_edges",
    "network_nodes",
    "network_legend_handles",
    "add_network_legend",
    "plot_network",
    "plot_no_network",
    "network_title",
    "save_network",
    "edge_evidence",
    "direction_edges",
    "ARROWS",
    "NetworkPieces",
]

#: Whose arrows a drawing shows: the paper's rule (``kind``) or the ``direction`` reading.
ARROWS = ("rule", "direction")
#: An undecided pair (``direction`` ``none``) under ``arrows="direction"``: a thin pale line.
UNDECIDED_COLOR = "0.8"
_UNDECIDED_GAP = 0.03  # between an undecided line and a node's rim, in data units

#: Readings of :data:`funcnet.network.schema.EVIDENCE_LABELS` whose pair the coupling test did
#: not show coupled: their edges are drawn dotted and pale (the paper's arrow, nothing more).
NO_COUPLING_EVIDENCE = ("asymmetry-only", "not-coupled")
UNCOUPLED_COLOR = "0.55"
UNCOUPLED_BIDIRECTIONAL_COLOR = "#f0a0a0"  # a pale red: still bidirectional, not coupled
UNCOUPLED_STYLE = ":"
#: The reading of a pair whose test could not have rejected: drawn paler still, dash-dotted,
#: so that it reads as neither a finding nor a tested absence.
UNTESTABLE = "untestable"
UNTESTABLE_COLOR = "0.75"
UNTESTABLE_BIDIRECTIONAL_COLOR = "#f6c8c8"
UNTESTABLE_STYLE = "-."


def network_legend_handles(width_scale: float = 10.0, weight: float = 0.2, *,
                           degenerate: bool = False, evidence: bool = False) -> list[Line2D]:
    """Legend entries explaining a network drawing: edge colours and the width scale.

    Parameters
    ----------
    width_scale : float
        The line width per unit of weight used by :func:`plot_network`.
    weight : float
        The reference weight (Eq. 13) whose width the legend shows.
    degenerate : bool
        Add the entry of degenerate edges (grey, dashed).
    evidence : bool
        Add the entries of the evidence styles (a network with evidence columns): solid where
        the coupling test shows the pair coupled, dotted and pale where it was tested and did
        not, dash-dotted and paler where it could not have (untestable).

    Returns
    -------
    list of matplotlib.lines.Line2D
        Directed (black), bidirectional (red), optionally degenerate (grey, dashed), optionally
        the three evidence styles, and a grey line of the reference weight's width.

    References
    ----------
    Paper section 3.4 (black directed, red bidirectional edges; width by Eq. 13).

    Examples
    --------
    >>> [h.get_label() for h in network_legend_handles()]
    ['directed (|diff| ≥ μ)', 'bidirectional (|diff| < μ)', 'weight 0.2 (width ∝ weight)']
    >>> network_legend_handles(degenerate=True)[2].get_label()
    'degenerate pair (arrow meaningless)'
    >>> [h.get_linestyle() for h in network_legend_handles(evidence=True)[2:5]]
    ['-', ':', '-.']
    >>> network_legend_handles(evidence=True)[4].get_label()
    'untestable (too few surrogates)'
    """
    handles = [Line2D([], [], color=DIRECTED_COLOR, linewidth=1.5, marker=">",
                      label="directed (|diff| ≥ μ)"),
               Line2D([], [], color=BIDIRECTIONAL_COLOR, linewidth=1.5,
                      label="bidirectional (|diff| < μ)")]
    if degenerate:
        handles.append(Line2D([], [], color=DEGENERATE_COLOR, linewidth=1.5, linestyle="--",
                              label="degenerate pair (arrow meaningless)"))
    if evidence:
        handles += [Line2D([], [], color=DIRECTED_COLOR, linewidth=1.5,
                           label="coupled (coupling test)"),
                    Line2D([], [], color=UNCOUPLED_COLOR, linewidth=1.5,
                           linestyle=":", label="tested, not shown coupled"),
                    Line2D([], [], color=UNTESTABLE_COLOR, linewidth=1.5,
                           linestyle="-.", label="untestable (too few surrogates)")]
    handles.append(Line2D([], [], color="0.4", linewidth=width_scale * weight,
                          label=f"weight {weight:g} (width ∝ weight)"))
    return handles


def network_edges(net: FunctionalNetwork) -> pd.DataFrame:
    """The edges to draw: the network's own ``edges``.

    They hold degenerate pairs only when the network was built with ``degenerate="keep"``.

    Parameters
    ----------
    net : FunctionalNetwork
        The network (for a study's rows, :func:`funcnet.study.store.network_from_rows`).

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind, degenerate``
        (:data:`funcnet.network.schema.EDGE_COLUMNS`).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["y->x", "x->y"],
    ...                       "weight": [0.2, 0.4], "degenerate": [False, True]})
    >>> network_edges(FunctionalNetwork.from_pairs(pairs))[["source", "target"]].values.tolist()
    [['B', 'A']]
    """
    return net.edges


def direction_edges(net: FunctionalNetwork) -> pd.DataFrame:
    """The edges of the ``direction`` reading: one per pair, ``directed`` from the signal
    whose past improves the other's prediction, ``none`` (a line, no arrow) where undecided;
    degenerate pairs left out.

    Parameters
    ----------
    net : FunctionalNetwork
        A network whose pairs table has ``direction`` (:mod:`funcnet.network.direction`).

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind, degenerate``; ``kind`` ``directed`` or
        ``none``, ``weight`` the pair's (Eq. 13).

    Examples
    --------
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["x->y", "x->y"],
    ...                       "weight": [0.2, 0.4], "direction": ["y->x", "none"]})
    >>> direction_edges(FunctionalNetwork.from_pairs(pairs))[["source", "target", "kind"]]
      source target      kind
    0      B      A  directed
    1      A      C      none
    """
    pairs = net.pairs
    if "direction" not in pairs.columns:
        raise ParameterError.of("net", "has no direction column: draw it with arrows='rule'")
    pairs = pairs[~pairs["degenerate"].eq(True)] if "degenerate" in pairs.columns else pairs
    backward = pairs["direction"].eq("y->x").to_numpy()
    x, y = pairs["x"].to_numpy(dtype=object), pairs["y"].to_numpy(dtype=object)
    return pd.DataFrame({
        "source": np.where(backward, y, x).astype(str),
        "target": np.where(backward, x, y).astype(str),
        "weight": pairs["weight"].to_numpy(dtype=np.float64),
        "kind": np.where(pairs["direction"].isin(["x->y", "y->x"]), "directed", "none"),
        "degenerate": np.zeros(len(pairs), dtype=bool),
    })


def network_nodes(net: FunctionalNetwork) -> list[str]:
    """The nodes of a network, in its order.

    Examples
    --------
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["x->y", "x->y"],
    ...                       "weight": [0.1, 0.1]})
    >>> network_nodes(FunctionalNetwork.from_pairs(pairs))
    ['A', 'B', 'C']
    """
    return list(net.nodes)


def edge_evidence(net: FunctionalNetwork, edges: pd.DataFrame) -> list[str] | None:
    """The ``evidence`` reading of each edge's pair, or ``None`` for a network without evidence.

    Parameters
    ----------
    net : FunctionalNetwork
        The network; the evidence is its pairs table's ``evidence`` column
        (:data:`funcnet.network.schema.EVIDENCE_COLUMNS`).
    edges : pandas.DataFrame
        Its edges (:func:`network_edges`), ``source`` and ``target`` in either order of the
        pair's ``x`` and ``y``.

    Returns
    -------
    list of str or None
        One reading per edge (``""`` for a pair without one, e.g. rows of a study run without
        evidence among rows with it); ``None`` when no pair has a reading.

    Examples
    --------
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A", "A"], "y": ["B", "C"], "kind": ["y->x", "x->y"],
    ...                       "weight": [0.2, 0.4], "evidence": ["coupled", "asymmetry-only"]})
    >>> net = FunctionalNetwork.from_pairs(pairs)
    >>> edge_evidence(net, network_edges(net))
    ['coupled', 'asymmetry-only']
    >>> plain = FunctionalNetwork.from_pairs(pairs.drop(columns="evidence"))
    >>> edge_evidence(plain, network_edges(plain)) is None
    True
    """
    pairs = net.pairs
    if "evidence" not in pairs.columns:
        return None
    # lists, not Series: a Series of strings read item by item costs more than the drawing
    labels = ["" if pd.isna(v) else str(v) for v in pairs["evidence"].tolist()]
    if not any(labels):
        return None
    reading = {frozenset((str(x), str(y))): label for x, y, label in zip(
        pairs["x"].tolist(), pairs["y"].tolist(), labels, strict=True)}
    return [reading.get(frozenset((str(a), str(b))), "")
            for a, b in zip(edges["source"].tolist(), edges["target"].tolist(), strict=True)]


class NetworkPieces:
    """The nodes and undecided lines of many networks in one axes, gathered by
    :func:`plot_network` (``pieces=``) and drawn by :meth:`draw` as a few artists: one
    collection of every node, one path of every undecided line of a style (a patch each
    cost more to set up and draw than the rest of a figure of forty networks).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "kind": ["x->y"], "weight": [0.2],
    ...                       "direction": ["none"]})
    >>> ax, pieces = Figure().add_subplot(), NetworkPieces()
    >>> for at in ((0.0, 0.0), (3.0, 0.0)):
    ...     _ = plot_network(FunctionalNetwork.from_pairs(pairs), ax, arrows="direction",
    ...                      at=at, pieces=pieces)
    >>> pieces.draw(ax)
    >>> [(c.get_gid(), len(c.get_paths())) for c in ax.collections]
    [('nodes', 4)]
    >>> [(p.get_gid(), len(p.get_path().to_polygons(closed_only=False))) for p in ax.patches]
    [('edges:none', 2)]
    """

    def __init__(self) -> None:
        self.nodes: list[Circle] = []
        self.lines: dict[tuple[float, str], list[BezierPath]] = {}

    def draw(self, ax: Axes) -> None:
        """Add what was gathered to ``ax``: the lines under the arrows, the nodes over them
        (the zorders of :func:`plot_network`'s own patches)."""
        from matplotlib.collections import PatchCollection

        for (width, colour), paths in self.lines.items():
            line = PathPatch(BezierPath.make_compound_path(*paths), fill=False,
                             linewidth=width, edgecolor=colour, capstyle="round",
                             joinstyle="round", zorder=1)
            line.set_gid("edges:none")
            ax.add_artist(line)
        if self.nodes:
            nodes = PatchCollection(self.nodes, match_original=True, zorder=3)
            nodes.set_gid("nodes")
            ax.add_collection(nodes, autolim=False)


def _draw_edge(ax: Axes, edge: Any, reading: str, position: Mapping[Any, tuple[float, float]],
               radius: Mapping[Any, float], width_scale: float, min_width: float,
               fontsize: float, pieces: NetworkPieces | None = None) -> None:
    """One edge of :func:`plot_network`: an arrow styled by its kind, degeneracy and coupling
    evidence, or a pale line when the direction is undecided (gathered in ``pieces``, where
    given)."""
    bidirectional = edge.kind == "bidirectional"
    width = max(min_width, width_scale * edge.weight)
    color = BIDIRECTIONAL_COLOR if bidirectional else DIRECTED_COLOR
    style = "-"
    if edge.kind == "none":  # undecided: a line, no head, no weight to read
        # arc3's curve built once in data units (equal aspect: the same arc), not an arrow
        # patch laid out at every draw; a gap of about 2 pt at the rims
        arc = _arc(*_trim(position[edge.source], position[edge.target],
                          radius[edge.source] + _UNDECIDED_GAP,
                          radius[edge.target] + _UNDECIDED_GAP), 0.08)
        if pieces is not None:
            pieces.lines.setdefault((min_width, UNDECIDED_COLOR), []).append(arc)
            return
        line = PathPatch(arc, fill=False, linewidth=min_width, edgecolor=UNDECIDED_COLOR,
                         capstyle="round", joinstyle="round", zorder=1)
        line.set_gid(f"edge:{edge.source}->{edge.target}:none")
        ax.add_artist(line)
        return
    if reading in NO_COUPLING_EVIDENCE:
        color = UNCOUPLED_BIDIRECTIONAL_COLOR if bidirectional else UNCOUPLED_COLOR
        style = UNCOUPLED_STYLE
    elif reading == UNTESTABLE:
        color = UNTESTABLE_BIDIRECTIONAL_COLOR if bidirectional else UNTESTABLE_COLOR
        style = UNTESTABLE_STYLE
    if edge.degenerate:
        color, style = DEGENERATE_COLOR, "--"
    arrow = FancyArrowPatch(
        position[edge.source], position[edge.target],
        arrowstyle="<|-|>" if bidirectional else "-|>",
        # The head grows with the line so that a thick edge does not hide it.
        mutation_scale=fontsize + 1 + 2.0 * width, shrinkA=0, shrinkB=0,
        patchA=None, patchB=None, joinstyle="miter", capstyle="butt",
        linewidth=width, color=color, linestyle=style,
        # Curved slightly so that the arrows of a cycle do not overlap the node labels.
        connectionstyle="arc3,rad=0.08", zorder=2,
    )
    # Stop the arrow at the node's rim rather than its centre.
    arrow.set_positions(*_trim(position[edge.source], position[edge.target],
                               radius[edge.source], radius[edge.target]))
    suffix = (":degenerate" if edge.degenerate else "") + (f":{reading}" if reading else "")
    arrow.set_gid(f"edge:{edge.source}->{edge.target}:{edge.kind}{suffix}")
    ax.add_artist(arrow)  # as the nodes: the limits are fixed below


def _draw_nodes(ax: Axes, nodes: Sequence[Any], present: Sequence[Any],
                label: Mapping[Any, str], position: Mapping[Any, tuple[float, float]],
                radius: Mapping[Any, float], node_color: str, fontsize: float,
                names: dict[tuple[str, float, str], list[Any]] | None = None,
                pieces: NetworkPieces | None = None) -> None:
    """The nodes of :func:`plot_network`: a circle and a name each, dashed when absent; the
    names collected in ``names`` and the circles in ``pieces`` instead of drawn, where given."""
    for name in nodes:
        circle = Circle(position[name], radius[name], facecolor=node_color, edgecolor="0.2",
                        linewidth=0.8, zorder=3,
                        linestyle="-" if name in present else "--")
        circle.set_gid(f"node:{name}")
        if pieces is not None:
            pieces.nodes.append(circle)
        else:
            ax.add_artist(circle)  # not add_patch, names not in the layout: fixed limits
        text = label.get(name, str(name))
        size = fontsize * min(1.0, 4.0 / max(len(text), 1)) ** 0.5
        if names is not None:
            names.setdefault((text, size, "black"), []).append(position[name])
            continue
        ax.text(*position[name], text, ha="center", va="center", zorder=4, fontsize=size,
                in_layout=False)


def plot_network(
    net: FunctionalNetwork,
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
    groups: Mapping[str, Sequence[str]] | None = None,
    arrows: str = "rule",
    at: tuple[float, float] | None = None,
    names: dict[tuple[str, float, str], list[Any]] | None = None,
    pieces: NetworkPieces | None = None,
) -> Axes:
    """Draw a functional network in a circular layout (paper section 3.4, Fig. 9-11).

    Parameters
    ----------
    net : FunctionalNetwork
        The network (for a study's rows, :func:`funcnet.study.store.network_from_rows`).
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
        When degenerate edges are drawn, the legend has their entry too; for a network with
        evidence columns, the entries of the evidence styles.
    groups : mapping of str to sequence of str, optional
        Nodes grouped (the axes of a robot: ``{"A1": ["A1.RP", ...], ...}``): each group
        placed together on the circle, a gap between groups, its name outside the circle and
        its nodes labelled without the ``"<group>."`` prefix; an edge within a group is then a
        short chord of its sector, one between groups crosses the circle. Replaces ``nodes``.
    arrows : {"rule", "direction"}
        ``"rule"`` (default, the paper's figures): the edges of the rule (``kind``);
        ``"direction"``: the ``direction`` reading's (:func:`direction_edges`): an arrow where
        one past improves the other's prediction, a thin pale line (gid
        ``edge:X->Y:none``) where undecided.
    at : (float, float), optional
        Draw the network centred there, in the data coordinates of ``ax``, and leave the axes'
        limits, aspect, frame and title alone: several networks in one axes (of equal aspect),
        each a circle of radius 1 around its centre, far cheaper than an axes each.
    names : dict, optional
        Collect the node names here instead of drawing them: ``(name, font size, colour)`` to
        the places it goes, for :func:`funcnet.plot.glyph_markers` to draw each name once over
        many networks.
    pieces : NetworkPieces, optional
        Gather the nodes' circles and the undecided lines here instead of drawing them, for
        :meth:`NetworkPieces.draw` to draw those of many networks as a few artists.

    Returns
    -------
    matplotlib.axes.Axes
        The axes; each node is a :class:`~matplotlib.patches.Circle` with gid ``node:NAME``,
        each edge a :class:`~matplotlib.patches.FancyArrowPatch` (an undecided line a
        :class:`~matplotlib.patches.PathPatch`) with gid ``edge:SOURCE->TARGET:KIND``, black
        when directed and red when bidirectional; an edge
        of a degenerate pair is grey and dashed, with gid ``edge:SOURCE->TARGET:KIND:degenerate``.
        For a network with evidence (:func:`edge_evidence`), each edge's gid ends with its
        pair's reading (``edge:RP->AP:directed:coupled``), an edge whose pair the coupling
        test did not show coupled (:data:`NO_COUPLING_EVIDENCE`) is dotted and pale (grey when
        directed, pale red when bidirectional), and one whose test could not have
        (``untestable``) dash-dotted and paler; without evidence columns nothing changes.

    References
    ----------
    Paper section 3.4 (circular layout, black/red edges, width by the weight of Eq. 13).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["RP", "RP", "AP"], "y": ["AP", "MP", "MP"],
    ...                       "kind": ["x->y", "x->y", "bidirectional"],
    ...                       "weight": [0.2, 0.1, 0.01]})
    >>> ax = plot_network(FunctionalNetwork.from_pairs(pairs))
    >>> sorted(p.get_gid() for p in ax.patches if p.get_gid().startswith("edge:"))
    ['edge:AP->MP:bidirectional', 'edge:RP->AP:directed', 'edge:RP->MP:directed']
    """
    ax = _new_axes(ax)
    present = network_nodes(net)
    label = {name: str(name) for name in present}
    slots: list[Any] = []  # the circle's places in order; None is a gap between groups
    if groups is not None:
        for group, members in groups.items():
            slots += [*members, None]
            label.update({m: str(m).removeprefix(f"{group}.") for m in members})
        nodes = [n for n in slots if n is not None]
        nodes += [n for n in present if n not in nodes]
        slots += [n for n in present if n not in slots]
    else:
        nodes = list(present) if nodes is None else [
            *nodes, *(n for n in present if n not in nodes)]
        slots = list(nodes)
    # Clockwise from the top, as networkx.circular_layout places them in the paper's figures.
    angle = {name: np.pi / 2 - 2 * np.pi * k / max(len(slots), 1)
             for k, name in enumerate(slots) if name is not None}
    cx, cy = (0.0, 0.0) if at is None else (float(at[0]), float(at[1]))
    position = {name: (cx + np.cos(angle[name]), cy + np.sin(angle[name])) for name in nodes}
    radius = {name: _node_radius(label.get(name, str(name)), node_size) for name in nodes}
    _draw_nodes(ax, nodes, present, label, position, radius, node_color, fontsize, names,
                pieces)
    for group, members in (groups or {}).items():
        placed = [angle[m] for m in members if m in angle]
        if placed:
            middle = float(np.mean(placed))
            ax.text(cx + 1.2 * np.cos(middle), cy + 1.2 * np.sin(middle), str(group),
                    ha="center", va="center", fontsize=fontsize + 1, fontweight="bold",
                    gid=f"group:{group}")
    if arrows not in ARROWS:
        raise ParameterError.of("arrows", f"must be one of {list(ARROWS)}, got {arrows!r}")
    edges = network_edges(net) if arrows == "rule" else direction_edges(net)
    readings = edge_evidence(net, edges)
    columns = (edges[c].tolist() for c in ("source", "target", "weight", "kind", "degenerate"))
    for k, edge in enumerate(map(_Edge._make, zip(*columns, strict=True))):
        _draw_edge(ax, edge, "" if readings is None else readings[k], position, radius,
                   width_scale, min_width, fontsize, pieces)
    if at is not None:
        return ax
    ax.set_xlim(-1.3, 1.3)
    ax.set_ylim(-1.3, 1.3)
    ax.set_aspect("equal")
    ax.set_axis_off()
    if title is not None:
        ax.set_title(title, fontsize=fontsize + 1)
    if legend:
        handles = network_legend_handles(width_scale,
                                         degenerate=bool(edges["degenerate"].any()),
                                         evidence=readings is not None)
        if arrows == "direction":
            handles[:2] = [
                Line2D([], [], color=DIRECTED_COLOR, linewidth=1.5,
                       label="direction: its past predicts the other"),
                Line2D([], [], color=UNDECIDED_COLOR, linewidth=1.5, label="undecided")]
        ax.legend(handles=handles, loc="upper center",
                  bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=max(9.0, fontsize - 1), frameon=False,
                  handlelength=2.5)
    return ax


class _Edge(NamedTuple):
    """One row of an edges table, as :func:`_draw_edge` reads it (built from the columns'
    lists: ``itertuples`` made a class and a Series per column for every network)."""

    source: Any
    target: Any
    weight: float
    kind: str
    degenerate: bool


def _node_radius(name: Any, node_size: float) -> float:
    """A node large enough for its name: names of up to three characters fit ``node_size``."""
    return node_size * max(1.0, 0.25 * len(str(name)))


def _arc(a: Any, b: Any, rad: float) -> BezierPath:
    """The quadratic Bezier arc from ``a`` to ``b`` of matplotlib's ``arc3`` connection style."""
    (x1, y1), (x2, y2) = a, b
    control = ((x1 + x2) / 2 + rad * (y2 - y1), (y1 + y2) / 2 - rad * (x2 - x1))
    return BezierPath([a, control, b], [BezierPath.MOVETO, *[BezierPath.CURVE3] * 2])


def _trim(a: tuple[float, float], b: tuple[float, float], ra: float,
          rb: float) -> tuple[Any, Any]:
    pa, pb = np.asarray(a), np.asarray(b)
    unit = (pb - pa) / max(np.linalg.norm(pb - pa), 1e-12)
    return tuple(pa + ra * unit), tuple(pb - rb * unit)


def plot_no_network(ax: Axes, label: Any = None, *, fontsize: float = 9.0) -> Axes:
    """Mark a panel whose network could not be computed: "no network", no axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    label : str, optional
        Its title.
    fontsize : float
        Size of the title, to match its neighbours' (:func:`plot_network`: ``fontsize + 1``).

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
        ax.set_title(str(label), fontsize=fontsize)
    ax.text(0.5, 0.5, "no network", ha="center", va="center", transform=ax.transAxes)
    return ax


def add_network_legend(fig: Figure, width_scale: float = 10.0, *,
                       degenerate: bool = False, evidence: bool = False) -> Any:
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
    evidence : bool
        Explain the evidence styles too (when the panels have evidence columns).

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
    legend = fig.legend(handles=network_legend_handles(width_scale, degenerate=degenerate,
                                                       evidence=evidence),
                        loc="outside lower center", ncol=3, fontsize=9, frameon=False,
                        handlelength=2.5)
    legend.set_gid("legend:network")
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
                 title: str | None = None, arrows: str = "direction") -> Path:
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
    arrows : {"direction", "rule"}
        Whose arrows (:func:`plot_network`): by default the ``direction`` reading's; a
        network without that column (a study's older rows) is drawn with the rule's.

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
    arrows = arrows if "direction" in net.pairs.columns else "rule"
    plot_network(net, ax, legend=True, arrows=arrows)
    ax.set_title(network_title(net) if title is None else title, fontsize=10)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=suffix[1:], dpi=dpi)
    return path
