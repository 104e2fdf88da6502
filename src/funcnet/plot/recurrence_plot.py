"""Drawing recurrence matrices and the graphs they define (paper Fig. 1 and 2)."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection

from funcnet.plot.style import _new_axes

__all__ = ["plot_recurrence", "plot_graph"]


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
        The computed matrix, e.g. :func:`funcnet.core.recurrence.recurrence_matrix` (Eq. 2) or
        :func:`funcnet.core.recurrence.cross_recurrence_matrix` (Eq. 3).
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

