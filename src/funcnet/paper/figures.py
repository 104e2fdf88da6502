"""The paper's figures: each generates or takes its data, computes, then draws with
:mod:`funcnet.plot`.

Figures 1, 2 and 5 (sections 2.1-2.4) are computed from the paper's synthetic signals with
funcnet's own core (:mod:`funcnet.core.embedding`, :mod:`funcnet.core.recurrence`,
:func:`funcnet.network.functional_network`); Figures 9, 10 and 11 (section 4) lay out networks
already computed (:func:`funcnet.paper.analyses.run_paper_analyses`); nothing is re-derived in
:mod:`funcnet.plot`, which only draws.

Length: over 600 lines because six figures and the captions' helpers (cross links, flags) share
their layout conventions here.

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
from matplotlib.figure import Figure

from funcnet import plot
from funcnet.core.embedding import embed
from funcnet.core.normalization import normalize
from funcnet.core.recurrence import isrn_adjacency, recurrence_matrix
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.parameters import NetworkParameters

__all__ = [
    "figure_embedding_network",
    "figure_isrn",
    "pair_network",
    "figure_pair_network",
    "figure_notes",
    "figure_phases",
    "figure_velocity_grid",
    "figure_reversal",
    "figure_recurrence_plots",
]


def _sine(n: int, periods: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2 * np.pi * periods, n)
    return t, np.sin(t)


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
    t, x = _sine(n, periods)
    states = embed(x, dim, delay)
    matrix = recurrence_matrix(x, dim=dim, delay=delay, eps=eps)
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
    plot.plot_recurrence(matrix, ax=ax_c)
    ax_c.set_title(f"(c) recurrence matrix, ε={eps}", fontsize=9)
    plot.plot_graph(matrix, ax_d, colors="tab:blue", seed=seed)
    ax_d.set_title("(d) recurrence network", fontsize=9)
    return fig


def _coupled_pair(n: int, periods: float, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    t, x = _sine(n, periods)
    return x, np.sin(1.5 * t) + alpha * x


def figure_isrn(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    eps: tuple[Any, Any] = ((0.15, 0.15), 0.05), seed: int = 0,
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
    eps : (auto, cross)
        ``((ε_X, ε_Y), ε_XY)`` in :class:`~funcnet.parameters.NetworkParameters`' shape
        (paper: ε_X = ε_Y = 0.15, ε_XY = 0.05).
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
    x, y = _coupled_pair(n, periods, alpha)
    adjacency = np.asarray(isrn_adjacency(x, y, dim=dim, delay=delay, eps=eps))
    m = len(adjacency) // 2
    fig = Figure(figsize=(12.0, 3.2), layout="constrained")
    ax_a, ax_b, ax_c, ax_d = fig.subplots(1, 4)
    ax_a.plot(x, color="tab:blue", linewidth=1, label="x")
    ax_a.plot(y, color="tab:red", linewidth=1, label="y")
    ax_a.legend(fontsize=9, frameon=False)
    ax_a.set_xlabel("$t_i$")
    ax_a.set_title(f"(a) x = sin t, y = sin 1.5t + {alpha}x", fontsize=9)
    for signal, color in ((x, "tab:blue"), (y, "tab:red")):
        states = embed(signal, dim, delay)
        ax_b.plot(states[:, 0], states[:, 1], ".", markersize=2, color=color)
    ax_b.set_xlabel("s(t)")
    ax_b.set_ylabel(f"s(t+{delay})")
    ax_b.set_title(f"(b) embeddings, m={dim}, τ={delay}", fontsize=9)
    ax_c.imshow(adjacency.astype(bool), cmap="binary", origin="upper", interpolation="nearest")
    ax_c.axhline(m - 0.5, color="tab:green", linewidth=0.8)
    ax_c.axvline(m - 0.5, color="tab:green", linewidth=0.8)
    cross = int(adjacency[:m, m:].sum())
    ax_c.set_title("(c) $A_X$ | $CR_{XY}$ / $CR_{YX}$ | $A_Y$", fontsize=9)
    if cross == 0:  # an empty block looks like a plotting error: say that it is the data
        ax_c.text(0.75, 0.25, "$CR_{XY}$ empty:\nno cross link\nat this $ε_{XY}$",
                  transform=ax_c.transAxes, ha="center", va="center", fontsize=9,
                  color="tab:green")
    plot.plot_graph(adjacency, ax_d, colors=["tab:blue"] * m + ["tab:red"] * m, seed=seed)
    ax_d.set_title("(d) ISRN", fontsize=9)
    return fig


def isrn_cross_links(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    eps: tuple[Any, Any] = ((0.15, 0.15), 0.05),
) -> int:
    """The number of cross links (ones of ``CR_XY``) of :func:`figure_isrn`'s network.

    Zero at the paper's ``ε_XY = 0.05``: no state of ``x`` lies that close to a state of
    ``y``, and the figure's cross blocks are empty -- which its caption must say.

    Examples
    --------
    >>> isrn_cross_links(), isrn_cross_links(eps=((0.15, 0.15), 0.15))
    (0, 64)
    """
    x, y = _coupled_pair(n, periods, alpha)
    adjacency = np.asarray(isrn_adjacency(x, y, dim=dim, delay=delay, eps=eps))
    m = len(adjacency) // 2
    return int(adjacency[:m, m:].sum())


def pair_network(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    mu: float = 0.05, warn: bool = True,
) -> FunctionalNetwork:
    """The functional network of Fig. 5: the coupled pair of Fig. 2, from ``C_diff`` alone.

    Computed by :func:`funcnet.network.functional_network` with ``measure="clustering"`` on the
    min-max normalized signals (the package's default, section 3.3) at the default rates (RR =
    CR = 0.05): ``C_diff = +0.111``, the value docs/validation/direction.md quotes. The rule of
    section 2.4 puts the arrow from ``y`` to ``x`` although ``x`` drives ``y``: the more complex
    signal looks like the driver (docs/guide/direction.md).

    Parameters
    ----------
    n, periods, alpha, dim, delay
        As in :func:`figure_isrn`.
    mu : float
        Bidirectionality threshold of section 2.4.
    warn : bool
        Emit the threshold warnings (else read them with :func:`figure_notes`).

    Returns
    -------
    FunctionalNetwork
        Nodes ``x`` and ``y``.

    References
    ----------
    Paper section 2.4, Eq. 10 and Fig. 5.

    Examples
    --------
    >>> pair_network(n=151, periods=3, warn=False).nodes
    ('x', 'y')
    """
    x, y = _coupled_pair(n, periods, alpha)
    return functional_network(np.column_stack([x, y]), names=["x", "y"], dim=dim, delay=delay,
                              mu=mu, normalize="minmax", measure="clustering", label="Fig. 5",
                              warn=warn)


def figure_pair_network(
    *, n: int = 251, periods: float = 4, alpha: float = 0.3, dim: int = 3, delay: int = 10,
    mu: float = 0.05, network: FunctionalNetwork | None = None, ax: Axes | None = None,
) -> Axes:
    """Fig. 5: the functional network of the coupled pair of Fig. 2, from ``C_diff`` alone.

    Parameters
    ----------
    n, periods, alpha, dim, delay, mu
        As in :func:`pair_network`, which computes the network.
    network : FunctionalNetwork, optional
        The network already computed by :func:`pair_network` (then the others are not used).
    ax : matplotlib.axes.Axes, optional
        Where to draw.

    Returns
    -------
    matplotlib.axes.Axes
        The network drawn by :func:`funcnet.plot.plot_network` (nodes ``x`` and ``y``); the
        title gives ``C_diff``.

    References
    ----------
    Paper section 2.4, Eq. 10 and Fig. 5.

    Examples
    --------
    >>> ax = figure_pair_network(n=151, periods=3)
    >>> sorted(p.get_gid() for p in ax.patches if p.get_gid().startswith("node:"))
    ['node:x', 'node:y']
    """
    if network is None:
        network = pair_network(n=n, periods=periods, alpha=alpha, dim=dim, delay=delay, mu=mu)
    c_diff = float(network.pairs["c_diff"].iloc[0])
    return plot.plot_network(network, ax,
                             title=f"C_diff = {c_diff:+.3f} (μ = {network.parameters.mu})")


def figure_notes(networks: Mapping[str, Any]) -> list[str]:
    """What the networks of a figure flag (thresholds, degenerate pairs), one line each.

    Built from the pairs tables' flags (:func:`funcnet.pipeline.window_warnings`), for a
    caption.

    Parameters
    ----------
    networks : mapping of label -> FunctionalNetwork or None

    Returns
    -------
    list of str
        One plain sentence per problem, naming the networks that have it.

    Examples
    --------
    >>> figure_notes({"cruise": None})
    []
    """
    from funcnet.pipeline import window_warnings

    computed = {str(k): net for k, net in networks.items() if net is not None}
    where: dict[str, list[str]] = {}
    for warning in window_warnings(computed):
        where.setdefault(str(warning.problem), []).append(str(warning.window))
    return [f"Flagged: {_NOTES.get(problem, problem)} in {', '.join(dict.fromkeys(labels))}."
            for problem, labels in sorted(where.items())]


#: A figure caption's words for each problem a pairs table flags.
_NOTES = {
    "eps_order": "ε_XY is not below ε_X and ε_Y (section 2.2 asks it for a modular ISRN)",
    "rate_exceeded": "ties at a threshold pushed an achieved rate above its target",
    "degenerate": "a degenerate pair (too few distinct states; its arrow is meaningless)",
}


def _network_row(fig: Figure, grid: Any, row: int, networks: Mapping[str, Any],
                 nodes: Sequence[str]) -> None:
    """One network per column of a grid row, each node at the same place in every panel."""
    for k, (label, net) in enumerate(networks.items()):
        ax = fig.add_subplot(grid[row, k])
        if net is None:
            plot.plot_no_network(ax, label)
        else:
            plot.plot_network(net, ax, nodes=nodes, title=str(label), legend=False)


def _network_legend(fig: Figure, networks: Mapping[Any, Any],
                    nodes: Sequence[str] = ()) -> None:
    """The figure's edge legend; with the degenerate entry when a panel draws such an edge,
    and the dashed-node entry when a panel lacks one of ``nodes`` (left out: constant)."""
    from matplotlib.lines import Line2D

    computed = [net for net in networks.values() if net is not None]
    degenerate = any(bool(plot.network_edges(net)["degenerate"].any()) for net in computed)
    dropped = any(set(nodes) - set(plot.network_nodes(net)) for net in computed)
    legend = plot.add_network_legend(fig, degenerate=degenerate)
    if dropped:
        legend.remove()
        handles = [*plot.network_legend_handles(degenerate=degenerate),
                   Line2D([], [], color="0.2", linestyle="", marker="o", markersize=9,
                          markerfacecolor="white", markeredgewidth=1,
                          label="dashed node: left out of that window (constant there)")]
        fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=9,
                   frameon=False).set_gid("legend:network")


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
        One network per phase, in drawing order (e.g. from :func:`funcnet.window_networks`);
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
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(
    ...     pd.DataFrame({"x": ["RP"], "y": ["AC"], "kind": ["y->x"], "weight": [0.2]}))
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
    plot.plot_signals(data, normalize=True, spans=phases, ax=top)
    top.set_title("(a) min–max normalized", fontsize=9, loc="left", pad=plot.SPAN_TITLE_PAD)
    for k, (ylabel, columns) in enumerate(groups):
        ax = fig.add_subplot(grid[1 + k, :], sharex=top)
        plot.plot_signals(data[columns], normalize=False, spans=phases, ax=ax)
        ax.set_ylabel(ylabel, fontsize=9)
        ax.set_xlabel("")
        if k == 0:
            ax.set_title("(b) raw", fontsize=9, loc="left", pad=plot.SPAN_TITLE_PAD)
    _network_row(fig, grid, -1, networks, list(data.columns))
    _network_legend(fig, networks, list(data.columns))
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
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(pd.DataFrame(
    ...     {"x": ["RP"], "y": ["AC"], "kind": ["bidirectional"], "weight": [0.0]}))
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
        plot.plot_signals(window, normalize=True, ax=series, legend=False)
        series.set_title(f"{velocity} · {phase}", fontsize=9)
        series.tick_params(labelsize=9)
        series.set_xlabel("time [s]", fontsize=9, labelpad=1)
        series.set_ylabel("normalized" if col == 0 else "", fontsize=9)
        graph = fig.add_subplot(grid[row + 1, col])
        if net is None:
            plot.plot_no_network(graph, None)
        else:
            plot.plot_network(net, graph, nodes=list(window.columns), legend=False)
    plot.add_signal_legend(fig, list(dict.fromkeys(c for window, _ in cells.values()
                                                  for c in window.columns)))
    _network_legend(fig, {k: net for k, (_, net) in cells.items()},
                    list(dict.fromkeys(c for window, _ in cells.values() for c in window.columns)))
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
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(
    ...     pd.DataFrame({"x": ["V"], "y": ["RP"], "kind": ["x->y"], "weight": [0.1]}))
    >>> fig = figure_reversal(data, windows, {w.label: net for w in windows})
    >>> sorted(p.get_gid() for p in fig.axes[1].patches)
    ['window:+0 ms', 'window:+20 ms', 'window:-20 ms']
    """
    fig = Figure(figsize=(max(8.0, 2.4 * len(networks)), 6.5), layout="constrained")
    grid = fig.add_gridspec(3, max(len(networks), 1), height_ratios=[1.0, 1.0, 1.5])
    full = fig.add_subplot(grid[0, :])
    plot.plot_signals(data, normalize=True, spans=phases, ax=full)
    full.set_title("(a) full motion", fontsize=9, loc="left",
                   pad=plot.SPAN_TITLE_PAD if phases is not None else None)
    if zoom is None:
        lo = min(float(w.start) for w in windows)
        hi = max(float(w.stop) for w in windows)
        zoom = (lo - (hi - lo) / 2, hi + (hi - lo) / 2)
    part = data.loc[(data.index >= zoom[0]) & (data.index <= zoom[1])]
    ax_zoom = fig.add_subplot(grid[1, :])
    plot.plot_signals(part, normalize=True, ax=ax_zoom, legend=False)
    bars = []
    for k, window in enumerate(windows):
        patch = ax_zoom.axvspan(float(window.start), float(window.stop), ymin=0.02 + 0.04 * k,
                                ymax=0.06 + 0.04 * k, color=f"C{k}", alpha=0.8,
                                label=str(window.label))
        patch.set_gid(f"window:{window.label}")
        bars.append(patch)
    # the bars are the windows: a key names each (their colours are not phases)
    ax_zoom.legend(handles=bars, fontsize=9, frameon=False, loc="upper left",
                   bbox_to_anchor=(1.0, 1.0), title="windows (bars)", title_fontsize=9)
    ax_zoom.set_title("(b) reversal, shifted windows", fontsize=9, loc="left")
    _network_row(fig, grid, 2, networks, list(data.columns))
    _network_legend(fig, networks, list(data.columns))
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def figure_recurrence_plots(
    data: pd.DataFrame,
    parameters: NetworkParameters,
    *,
    columns: Sequence[str] = ("AP", "V", "AC"),
    left_out: Sequence[str] = (),
) -> Figure:
    """Recurrence plots of a window's signals, prepared as for its network.

    Each column is normalized as the network's signals are (``parameters.normalize``, paper
    section 3.3) and its recurrence matrix computed at ``parameters``' rate and embedding
    (:func:`funcnet.core.recurrence.recurrence_matrix`, Eq. 2), then drawn by
    :func:`funcnet.plot.plot_recurrence`. Beyond the paper.

    Parameters
    ----------
    data : pandas.DataFrame
        One window of a recording (time as index).
    parameters : NetworkParameters
        The network's parameters (``normalize``, ``dim``, ``delay``, ``rr``, ``eps``,
        ``metric``, ``theiler``).
    columns : sequence of str
        One panel per column, in order.
    left_out : sequence of str
        Columns left out of the window's network (constant there): their panel stays empty, as
        does a column the window lacks.

    Returns
    -------
    matplotlib.figure.Figure
        One axes per column, titled by it.

    References
    ----------
    Paper section 2.1, Eq. 1-2 and Fig. 1c; section 3.3 (normalization).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> t = np.arange(200) * 0.002
    >>> data = pd.DataFrame({"AP": np.sin(9 * t), "V": np.cos(9 * t)}, index=t)
    >>> fig = figure_recurrence_plots(data, NetworkParameters(delay=2), columns=("AP", "V"))
    >>> [ax.images[0].get_array().shape for ax in fig.axes]
    [(196, 196), (196, 196)]
    """
    fig = Figure(figsize=(3.0 * max(len(columns), 1), 3.2), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, max(len(columns), 1)))
    for ax, column in zip(axes, columns, strict=False):
        if column not in data or column in left_out:
            ax.set_axis_off()
            continue
        values = normalize(data[column].to_numpy(dtype=float), parameters.normalize,
                           names=column)
        matrix = recurrence_matrix(values, parameters=parameters)
        plot.plot_recurrence(matrix, ax=ax, title=column)
    return fig
