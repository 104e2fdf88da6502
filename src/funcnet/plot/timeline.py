"""Every pair's edge kind and weight over a recording, from sliding windows."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.collections import PathCollection
from matplotlib.lines import Line2D

from funcnet.errors import ParameterError
from funcnet.plot.style import (
    _BIDIRECTIONAL,
    _CONFLICT,
    _X_Y,
    _Y_X,
    KIND_COLORS,
    _category_ticks,
    _new_axes,
)

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = ["plot_edge_timeline"]


def _window_time(key: Any, net: FunctionalNetwork) -> float:
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


def _pair_table(networks: Mapping[Any, FunctionalNetwork]) -> pd.DataFrame:
    """One table of every network's pairs, with the time of its window."""
    frames = []
    for key, net in networks.items():
        t = _window_time(key, net)
        pairs = net.pairs
        columns = ["x", "y", "kind", "weight", *(["degenerate"] if "degenerate" in pairs else [])]
        frame = pairs[columns].copy()
        frame["time"] = t
        frames.append(frame)
    return pd.concat(frames, ignore_index=True)


def plot_edge_timeline(
    networks: Mapping[Any, FunctionalNetwork],
    *,
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
    networks : mapping of time -> FunctionalNetwork
        Networks keyed by the time of their window (e.g. its centre, seconds) -- or keyed by
        label, as :func:`funcnet.window_networks` returns them: each is then placed at its
        window's centre.
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
    >>> from funcnet.network import FunctionalNetwork
    >>> def net(kind, weight):
    ...     return FunctionalNetwork.from_pairs(pd.DataFrame(
    ...         {"x": ["A"], "y": ["B"], "kind": [kind], "weight": [weight]}))
    >>> networks = {0.5: net("x->y", 0.1), 1.0: net("conflict", 0.2)}
    >>> sum(len(c.get_offsets()) for c in plot_edge_timeline(networks).collections)
    2
    """
    ax = _new_axes(ax, (8.0, 3.0))
    table = _pair_table(networks)
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
        points = ax.scatter(table["time"].to_numpy(dtype=float)[mask], y[mask],
                            s=np.maximum(4.0, size_scale * weights[mask]), marker=marker,
                            color=KIND_COLORS[kind], label=label, linewidths=0)
        points.set_gid(f"kind:{kind}")
    _category_ticks(ax.yaxis, pair_names)
    ax.tick_params(axis="y", labelsize=9)
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
    # an artist that is not clipped counts in the figure's layout (a clipped one is cut off)
    kind_legend.set_clip_on(False)
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


