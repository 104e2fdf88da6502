"""The figure of a robot's page: its network as an adjacency matrix ordered by axis and role.

A network of every axis's signals (21 nodes on a six-axis robot with two encoders on three
axes, 24 with four signals each) drawn as a circle is a tangle of some 200 edges; as a matrix it
reads at any size: row X, column Y, one cell per pair; the axes are blocks along the diagonal
(within an axis) and off it (between two axes), each block's rows and columns in the same order
of roles (RP, AP, MP, V, RC, AC as recorded).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from funcnet.network import FunctionalNetwork
from funcnet.robot.axes import split_qualified

__all__ = ["figure_robot_matrix"]

_DIRECTED = "Blues"
_BIDIRECTIONAL = "Reds"
_COUPLED = ("coupled", "coupled-directed")


#: Width of a character in units of the font size, a generous estimate for DejaVu Sans.
_TEXT_WIDTH = 0.62


def figure_robot_matrix(network: FunctionalNetwork, title: str = "", *,
                        arrows: str = "rule") -> Any:
    """The robot network as an adjacency matrix: rows the source X, columns the target Y.

    Parameters
    ----------
    network : FunctionalNetwork
        Of nodes named ``A<axis>.<signal>`` (a node without an axis comes last).
    title : str
        Above the matrix.
    arrows : {"rule", "direction"}
        Whose edges: the rule's (``kind``), or the ``direction`` reading's (a directed cell
        where one past improves the other's prediction; undecided pairs empty).

    Returns
    -------
    matplotlib.figure.Figure
        A directed edge X -> Y is the cell (X, Y) in blue, a bidirectional edge both cells in
        red, darker with its weight (Eq. 13); an empty cell is no edge (a conflict, a degenerate
        pair). Where the evidence's test rejects independence the cell holds a dot. Lines part
        the axes; each axis is named above its columns and beside its rows.
    """
    from matplotlib import colormaps
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    nodes = list(network.nodes)
    axes = [split_qualified(name)[0] for name in nodes]
    order = sorted(range(len(nodes)), key=lambda k: (axes[k] is None, axes[k] or 0, k))
    nodes = [nodes[k] for k in order]
    axes = [axes[k] for k in order]
    place = {name: k for k, name in enumerate(nodes)}
    n = len(nodes)
    if arrows == "direction":
        from funcnet.plot.network_diagram import direction_edges

        edges = direction_edges(network)
        edges = edges[edges["kind"] == "directed"]
    else:
        edges = network.edges
    weights = edges["weight"].to_numpy(dtype=float) if len(edges) else np.zeros(0)
    top = float(weights.max()) if weights.size and weights.max() > 0 else 1.0
    shade = Normalize(0.0, top)
    image = np.ones((n, n, 4))
    image[np.arange(n), np.arange(n)] = (0.85, 0.85, 0.85, 1.0)
    for row in edges.itertuples():
        i, j = place[str(row.source)], place[str(row.target)]
        level = 0.25 + 0.75 * shade(float(row.weight))
        if row.kind == "bidirectional":
            image[i, j] = image[j, i] = colormaps[_BIDIRECTIONAL](level)
        else:
            image[i, j] = colormaps[_DIRECTED](level)
    size = max(6.0, 0.34 * n + 2.6)
    fig = Figure(figsize=(size + 1.2, size))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))  # placed once its texts are known
    ax.imshow(image, interpolation="nearest")
    if "evidence" in network.pairs.columns:
        coupled = network.pairs[network.pairs["evidence"].isin(_COUPLED)]
        for x, y in zip(coupled["x"], coupled["y"], strict=True):
            i, j = place[str(x)], place[str(y)]
            ax.plot([j, i], [i, j], linestyle="", marker="o", markersize=4, color="black")
    roles = [split_qualified(name)[1] if a is not None else name
             for name, a in zip(nodes, axes, strict=True)]
    ax.set_xticks(range(n), roles, rotation=90, fontsize=9)
    ax.set_yticks(range(n), roles, fontsize=9)
    ax.tick_params(top=True, labeltop=True, bottom=False, labelbottom=False, length=0)
    bounds = [k for k in range(1, n) if axes[k] != axes[k - 1]]
    for k in bounds:
        ax.hlines(k - 0.5, -0.5, n - 0.5, color="0.2", linewidth=1.0)
        ax.vlines(k - 0.5, -0.5, n - 0.5, color="0.2", linewidth=1.0)
    for side in ("bottom", "left", "right"):
        ax.spines[side].set_visible(False)
    starts = [0, *bounds]
    ends = [*bounds, n]
    names = ["common" if axes[a] is None else f"A{axes[a]}" for a in starts]
    # Beside the rows the axis names stand a fixed distance in points left of the role labels,
    # and "source X" beyond them: in cell units the distance shrank with a small matrix's few,
    # large cells until the names ran into the label.
    beside = _TEXT_WIDTH * 9 * max(len(r) for r in roles) + 10
    for name, a, b in zip(names, starts, ends, strict=True):
        middle = (a + b - 1) / 2
        ax.text(middle, n - 0.3, name, ha="center", va="top", fontsize=10, fontweight="bold")
        ax.annotate(name, (0, middle), xycoords=("axes fraction", "data"), xytext=(-beside, 0),
                    textcoords="offset points", ha="right", va="center", fontsize=10,
                    fontweight="bold")
    ax.set_xlim(-0.5, n - 0.5)
    ax.set_ylim(n + 0.6, -0.5)
    ax.set_xlabel("target Y", fontsize=9)
    ax.set_ylabel("source X", fontsize=9,
                  labelpad=beside - _TEXT_WIDTH * 9 * max(len(r) for r in roles)
                  + _TEXT_WIDTH * 11 * max(len(m) for m in names) + 6)
    if title:
        ax.set_title(title, fontsize=10)
    _place(fig, ax, _legend(fig, arrows, top), beside)
    return fig


def _place(fig: Any, ax: Any, legend: Any, beside: float) -> None:
    """The matrix put where its texts leave room: the roles above and beside it, the axes'
    names ``beside`` points left of it, "source X" beyond them, the title on top; "target Y"
    and the legend below."""
    import matplotlib

    from funcnet.report.figure_geometry import PT, extent, legend_extent, put, renderer_of

    renderer = renderer_of(fig)
    width, height = fig.get_size_inches()
    gap = 4 * PT
    pad = matplotlib.rcParams["ytick.major.pad"] * PT
    roles_wide = extent(ax.get_yticklabels(), renderer)[0]
    roles_high = extent(ax.get_xticklabels(), renderer)[1]
    names = [t for t in ax.texts if t.get_ha() == "right"]
    label_wide = extent([ax.yaxis.label], renderer)[0]
    left = gap + max(beside * PT + extent(names, renderer)[0],
                     roles_wide + pad + ax.yaxis.labelpad * PT + label_wide)
    title_high = extent([ax.title], renderer)[1]
    top = gap + roles_high + pad + (title_high + matplotlib.rcParams["axes.titlepad"] * PT
                                    if title_high else 0.0)
    legend_high = legend_extent(legend, renderer)[1]
    legend.set_bbox_to_anchor((0.5, gap / height), transform=fig.transFigure)
    bottom = 2 * gap + legend_high + extent([ax.xaxis.label], renderer)[1] \
        + ax.xaxis.labelpad * PT
    put(ax, left, bottom, width - left - 3 * gap, height - bottom - top)

def _legend(fig: Any, arrows: str, top: float) -> Any:
    """The matrix's legend below it: the cell colours, the dot, the weight's scale."""
    from matplotlib import colormaps
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    directed = ("X → Y: X's past improves Y's prediction (row → column); undecided: empty"
                if arrows == "direction" else "X → Y: directed (row → column)")
    handles = [Patch(facecolor=colormaps[_DIRECTED](0.8), label=directed),
               Patch(facecolor=colormaps[_BIDIRECTIONAL](0.8),
                     label="bidirectional (|diff| < μ), both cells"),
               Patch(facecolor="white", edgecolor="0.6", label="no edge (conflict, degenerate)"),
               Line2D([], [], linestyle="", marker="o", markersize=4, color="black",
                      label="coupled (the test rejects independence)")]
    # two columns where they fit the figure's width, else one: a small robot's legend was cut
    widest = _TEXT_WIDTH * 9 * max(len(str(h.get_label())) for h in handles) + 40
    return fig.legend(handles=handles, loc="lower center",
                      ncol=2 if 2 * widest <= 72 * fig.get_figwidth() else 1, fontsize=9,
                      frameon=False, title=f"darker: heavier (weight up to {top:.2g}, Eq. 13)",
                      title_fontsize=9, borderaxespad=0.0)
