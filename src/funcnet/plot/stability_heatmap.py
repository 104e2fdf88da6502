"""How stable each pair's kind is over a grid of settings, as a heatmap (draws what it is given).

The data come from :func:`funcnet.network.stability.edge_stability`; this module computes
nothing.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes

from funcnet.errors import ParameterError
from funcnet.plot.style import _new_axes

__all__ = ["plot_stability"]

_PREFIX = "stability_"


def _table(result: Any) -> pd.DataFrame:
    table = result if isinstance(result, pd.DataFrame) else getattr(result, "table", None)
    needed = ("x", "y", "kind", "stability")
    if not isinstance(table, pd.DataFrame) or any(c not in table.columns for c in needed):
        raise ParameterError.of(
            "result", "must be an EdgeStability (funcnet.network.edge_stability) or its table "
            f"(columns {', '.join(needed)}, stability_<key>...)"
        )
    return table


def plot_stability(result: Any, ax: Axes | None = None, *, fontsize: float = 10.0) -> Axes:
    """Per pair a row, per grid key a column: the fraction of settings that keep its kind.

    The first column (``all``) is the pair's ``stability`` over every setting, the others its
    ``stability_<key>`` (the settings varying that key alone). Each row is labelled with the
    pair and the kind it has at the base settings; each cell shows its fraction, on a colour
    scale from 0 (the kind never survives) to 1 (it always does). A NaN cell (no setting varies
    that key alone) is left blank.

    Parameters
    ----------
    result : EdgeStability or pandas.DataFrame
        :func:`funcnet.network.stability.edge_stability`'s result, or its ``table``.
    ax : matplotlib.axes.Axes, optional
        Where to draw; default a new figure sized to the table.
    fontsize : float
        Text size in points (never below 9).

    Returns
    -------
    matplotlib.axes.Axes
        The cells carry ``gid`` ``"stability:X-Y:KEY"`` (``KEY`` ``all`` or a grid key).

    Raises
    ------
    ParameterError
        ``result`` has no stability table.

    Examples
    --------
    >>> import pandas as pd
    >>> table = pd.DataFrame({"x": ["RP"], "y": ["AP"], "kind": ["x->y"], "stability": [0.8],
    ...                       "settings": [15], "stability_mu": [0.5], "stability_dim": [1.0]})
    >>> ax = plot_stability(table)
    >>> [t.get_text() for t in ax.get_xticklabels()]
    ['all', 'mu', 'dim']
    """
    table = _table(result)
    fontsize = max(9.0, float(fontsize))
    keys = [c for c in table.columns if c.startswith(_PREFIX)]
    grid = getattr(result, "grid", None)
    # The grid's own keys ("rr+cr") where the result has them; the column names otherwise.
    named = list(grid) if isinstance(grid, Mapping) and len(grid) == len(keys) else None
    labels = ["all", *(named or (c.removeprefix(_PREFIX) for c in keys))]
    values = table[["stability", *keys]].to_numpy(dtype=np.float64)
    n_rows, n_cols = values.shape
    ax = _new_axes(ax, figsize=(3.4 + 0.85 * n_cols, 2.4 + 0.42 * max(n_rows, 1)))
    image = ax.imshow(np.ma.masked_invalid(values), cmap="viridis", vmin=0.0, vmax=1.0,
                      aspect="auto", interpolation="nearest")
    image.set_gid("stability:image")
    pairs = [f"{x}–{y}" for x, y in zip(table["x"], table["y"], strict=True)]
    for i, pair in enumerate(pairs):
        for j, label in enumerate(labels):
            value = values[i, j]
            if np.isnan(value):
                continue
            # Light text on the dark end of viridis, dark on the light end.
            ax.text(j, i, f"{value:.2f}", ha="center", va="center", fontsize=fontsize - 1,
                    color="white" if value < 0.6 else "black",
                    gid=f"stability:{pair.replace('–', '-')}:{label}")
    ax.set_xticks(range(n_cols), labels, fontsize=fontsize, rotation=30, ha="right")
    ax.set_yticks(range(n_rows), [f"{pair}: {kind}" for pair, kind
                                  in zip(pairs, table["kind"], strict=True)], fontsize=fontsize)
    ax.axvline(0.5, color="white", linewidth=2)  # "all" apart from the single keys
    ax.set_xlabel("settings varied", fontsize=fontsize)
    ax.set_ylabel("pair: kind at the base", fontsize=fontsize)
    settings = table["settings"].iloc[0] if "settings" in table and n_rows else None
    counted = "" if settings is None else f" (of {int(settings)} settings)"
    ax.set_title(f"fraction of settings keeping the kind{counted}", fontsize=fontsize + 1)
    bar = ax.figure.colorbar(image, ax=ax, fraction=0.05, pad=0.03)
    bar.ax.tick_params(labelsize=fontsize - 1 if fontsize > 9 else 9)
    bar.set_label("fraction keeping the kind", fontsize=fontsize)
    return ax
