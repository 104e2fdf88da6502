"""The robot matrix keeps its legend and labels inside the figure, apart from each other."""

from __future__ import annotations

import itertools

import pandas as pd
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from funcnet.network import FunctionalNetwork
from funcnet.report.robot_figures import figure_robot_matrix


def _robot(axes: int, roles: tuple[str, ...] = ("RP", "AP")) -> FunctionalNetwork:
    nodes = [f"A{a}.{r}" for a in range(1, axes + 1) for r in roles]
    pairs = pd.DataFrame([{"x": x, "y": y, "kind": "x->y" if k % 3 else "bidirectional",
                           "weight": 0.01 * (k % 5 + 1), "direction": "x->y"}
                          for k, (x, y) in enumerate(itertools.combinations(nodes, 2))])
    return FunctionalNetwork.from_pairs(pairs)


@pytest.mark.parametrize(("axes", "roles", "arrows"), [
    (4, ("RP", "AP"), "direction"),                # the MCS500: 4 axes, 8 nodes
    (4, ("RP", "AP"), "rule"),
    (2, ("RP", "AP"), "direction"),
    (6, ("RP", "AP"), "direction"),
    (6, ("RP", "AP", "MP", "TORSION"), "rule"),    # a large robot, a long role name
])
def test_legend_and_labels_stay_inside_and_apart(axes, roles, arrows):
    fig = figure_robot_matrix(_robot(axes, roles), "whole recording", arrows=arrows)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    frame = fig.bbox
    legend = fig.legends[0].get_window_extent(renderer)
    assert frame.x0 <= legend.x0 and legend.x1 <= frame.x1, (legend, frame)
    ax = fig.axes[0]
    label = ax.yaxis.label.get_window_extent(renderer)
    assert frame.x0 <= label.x0
    names = [t for t in ax.texts if t.get_text().startswith("A") and t.get_ha() == "right"]
    assert len(names) == axes
    for name in names:
        box = name.get_window_extent(renderer)
        assert label.x1 < box.x0, f"source X overlaps {name.get_text()}"
        assert frame.x0 <= box.x0
    roles = min(t.get_window_extent(renderer).x0 for t in ax.get_yticklabels())
    assert all(n.get_window_extent(renderer).x1 < roles for n in names)


@pytest.mark.parametrize(("axes", "arrows"), [(4, "direction"), (4, "rule"), (6, "direction")])
def test_every_text_is_inside_and_the_legend_overlaps_none(axes, arrows):
    fig = figure_robot_matrix(_robot(axes), "whole recording 0-1.698 s", arrows=arrows)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    frame = fig.bbox
    ax = fig.axes[0]
    texts = [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.texts, *ax.get_xticklabels(),
             *ax.get_yticklabels()]
    boxes = {f"{t.get_text()!r} ({k})": t.get_window_extent(renderer)
             for k, t in enumerate(texts) if t.get_text()}
    for name, box in boxes.items():
        assert (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0
                and box.y1 <= frame.y1), f"{name} outside the figure: {box} in {frame}"
    legend = fig.legends[0].get_window_extent(renderer)
    assert frame.y0 <= legend.y0 and legend.y1 <= frame.y1
    for name, box in boxes.items():
        assert not legend.overlaps(box), f"the legend overlaps {name}"
    # the axis names below the columns stay clear of "target Y"
    below = [t.get_window_extent(renderer) for t in ax.texts if t.get_ha() == "center"]
    assert len(below) == axes
    assert all(not b.overlaps(ax.xaxis.label.get_window_extent(renderer)) for b in below)
