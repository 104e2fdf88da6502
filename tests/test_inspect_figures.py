"""Figures of the inspect report: the evidence figure's cells, the network panels."""

from __future__ import annotations

import numpy as np
import pandas as pd

from funcnet.report.inspect_figures import ARROWS, _cell_readings, evidence_informs, figure_evidence


def _reference(pairs: pd.DataFrame, a: str, b: str) -> tuple[str, str]:
    """One cell as a table lookup reads it: degenerate, else the evidence, else the kind."""
    row = pairs.set_index(["x", "y"]).loc[(a, b)]
    if bool(row["degenerate"]):
        return "degenerate", str(row["kind"])
    key = row["evidence"] if "evidence" in pairs.columns else row["kind"]
    return str(key), str(row["kind"])


def _pairs(evidence: bool) -> pd.DataFrame:
    table = pd.DataFrame({"x": ["RP", "RP", "AP"], "y": ["AP", "AC", "AC"],
                          "kind": ["x->y", "bidirectional", "y->x"],
                          "degenerate": [False, True, False]})
    if evidence:
        table["evidence"] = ["coupled-directed", "not-coupled", "untestable"]
    return table


def test_each_cell_reads_as_a_lookup_of_its_pair_would():
    for evidence in (True, False):
        pairs = _pairs(evidence)
        cells = _cell_readings(pairs)
        assert set(cells) == {("RP", "AP"), ("RP", "AC"), ("AP", "AC")}
        for a, b in cells:
            assert cells[(a, b)] == _reference(pairs, a, b)
    assert _cell_readings(_pairs(True))[("AP", "AC")] == ("untestable", "y->x")
    assert _cell_readings(_pairs(False))[("AP", "AC")] == ("y->x", "y->x")


def test_the_figure_draws_each_pairs_arrow_and_a_dash_where_a_pair_is_left_out():
    from types import SimpleNamespace

    from funcnet.network import FunctionalNetwork
    from funcnet.robot import Window

    full = _pairs(True).assign(weight=[0.2, 0.1, 0.3])
    networks = {"cruise": FunctionalNetwork.from_pairs(full),
                "braking": FunctionalNetwork.from_pairs(full.iloc[:2])}
    windows = [Window("cruise", 0.0, 1.0, "cruise"), Window("braking", 1.0, 2.0, "braking")]
    inspection = SimpleNamespace(windows=windows, networks=networks, evidence=True,
                                 signals={"RP": None, "AP": None, "AC": None})
    fig = figure_evidence(inspection)
    # each cell's glyph: a marker at the cell, one line of markers per glyph (gid cell:GLYPH)
    texts = sorted(((x, y), line.get_gid().removeprefix("cell:")) for line in fig.axes[0].lines
                   for x, y in zip(line.get_xdata(), line.get_ydata(), strict=True))
    # pairs in signal order: RP–AP (row 0), RP–AC (row 1), AP–AC (row 2); windows as columns
    assert texts == sorted([((0, 0), ARROWS["x->y"]), ((0, 1), ARROWS["bidirectional"]),
                            ((0, 2), ARROWS["y->x"]), ((1, 0), ARROWS["x->y"]),
                            ((1, 1), ARROWS["bidirectional"]), ((1, 2), "–")])


def _one_move():
    """A 4 s axis moving out and back once: its phases and their networks."""
    from funcnet.robot import Recording, SignalInfo

    t = np.arange(0, 4, 0.002)
    acc = np.interp(t, [0.5, 0.6, 0.9, 1.0, 2.0, 2.1, 2.4, 2.5], [0, 1, 1, 0, 0, -1, -1, 0])
    rp = np.cumsum(np.cumsum(acc) * 0.002) * 0.002 * 100
    ap = np.concatenate([[0.0] * 3, rp[:-3]])
    ac = (np.gradient(np.gradient(ap)) * 1e4
          + np.random.default_rng(0).normal(0, 0.05, t.size))
    data = pd.DataFrame({"RP": rp, "AP": ap, "AC": ac}, index=pd.Index(t.round(9), name="time"))
    info = {c: SignalInfo(c, "posn", "double", 0.002) for c in data}
    return Recording(data, {}, info, source="synthetic.csv", sample_period=0.002)


def drawn_texts(fig) -> list[tuple[object, object]]:
    """Every text the figure draws (those outside an axis's view are not drawn) with its box
    in pixels, and each legend with its box: the figure drawn as :func:`save_figure` draws it."""
    from unittest import mock

    from matplotlib.legend import Legend
    from matplotlib.text import Text

    from funcnet.report.figure_geometry import renderer_of
    from funcnet.report.html import _settle_layout

    _settle_layout(fig, 100)
    renderer = renderer_of(fig)
    found: list[tuple[object, object]] = []
    draw_text, draw_legend = Text.draw, Legend.draw

    def text(self, r):
        draw_text(self, r)
        if self.get_visible() and self.get_text():
            found.append((self, self.get_window_extent(r)))

    def legend(self, r):
        draw_legend(self, r)
        found.append((self, self.get_window_extent(r)))

    with mock.patch.object(Text, "draw", text), mock.patch.object(Legend, "draw", legend):
        fig.canvas.draw()
    assert renderer is fig.canvas.get_renderer()
    return found


def layout_faults(fig) -> list[str]:
    """What a reader would stumble on: a text or legend (partly) outside the canvas, two texts
    on each other, a text under a legend it is not part of. Rotated texts (the slanted tick
    labels, whose boxes are wider than their letters) are not compared with each other."""
    from matplotlib.legend import Legend

    found = drawn_texts(fig)
    canvas = fig.bbox
    faults = [f"outside the canvas: {a!r}" for a, box in found
              if box.x0 < canvas.x0 - 1 or box.x1 > canvas.x1 + 1 or box.y0 < canvas.y0 - 1
              or box.y1 > canvas.y1 + 1]
    legends = [a for a, _ in found if isinstance(a, Legend)]

    def owner(artist):
        return next((g for g in legends if artist in g.texts or artist is g.get_title()), None)

    for k, (a, box_a) in enumerate(found):
        for b, box_b in found[k + 1:]:
            if isinstance(a, Legend) and isinstance(b, Legend):
                pass
            elif isinstance(a, Legend) or isinstance(b, Legend):
                legend, other = (a, b) if isinstance(a, Legend) else (b, a)
                if owner(other) is legend:
                    continue
            elif owner(a) is not None or owner(b) is not None:
                continue  # a legend's own texts: laid out by the legend
            elif a.get_rotation() and b.get_rotation():
                continue
            inter_w = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            inter_h = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if inter_w > 1 and inter_h > 1:
                faults.append(f"overlap: {a!r} and {b!r}")
    return faults


def test_the_layout_check_sees_a_label_outside_and_two_texts_on_each_other():
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4, 3))
    ax = fig.add_axes((0.0, 0.1, 0.9, 0.8))  # no room left for the y tick labels
    ax.plot([0, 1], [0, 1000])
    assert any(f.startswith("outside") for f in layout_faults(fig))
    fig = Figure(figsize=(4, 3))
    fig.text(0.5, 0.5, "one text")
    fig.text(0.52, 0.5, "another")
    assert any(f.startswith("overlap") for f in layout_faults(fig))
    fig = Figure(figsize=(4, 3))
    fig.add_axes((0.2, 0.2, 0.7, 0.7)).plot([0, 1], label="a line")
    fig.legend(loc="center")
    fig.text(0.5, 0.5, "under the legend")
    assert any(f.startswith("overlap") for f in layout_faults(fig))


def test_network_panels_keep_their_frame_and_everything_inside_the_canvas():
    """Each phase's panel: a framed square in the phase's colour under its network, its title
    above; every title, node name and the legend inside the figure, none on another."""
    import warnings

    from matplotlib.colors import to_hex

    from funcnet.inspection import inspect_recording
    from funcnet.plot import phase_color
    from funcnet.report.inspect_figures import figure_networks

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ins = inspect_recording(_one_move(), evidence=False, backlash=False)
    fig = figure_networks(ins)
    (ax,) = fig.axes
    squares = {p.get_gid().removeprefix("panel:"): p for p in ax.patches
               if str(p.get_gid()).startswith("panel:")}
    assert set(squares) == set(ins.networks) and len(squares) >= 2
    by_label = {w.label: w for w in ins.windows}
    # every panel's nodes: one collection of circles in data units (one path each)
    (collection,) = [c for c in ax.collections if c.get_gid() == "nodes"]
    centres = [path.get_extents().get_points().mean(axis=0) for path in collection.get_paths()]
    assert len(centres) == len(squares) * len(ins.signals)
    for label, square in squares.items():
        assert to_hex(square.get_facecolor()) == to_hex(phase_color(by_label[label].phase))
        assert square.get_linewidth() > 0  # framed
        nodes = [c for c in centres if square.contains_point(ax.transData.transform(c))]
        assert len(nodes) == len(ins.signals)  # each network inside its own square
    # every undecided pair a line (one subpath of one path), every decided one an arrow
    from matplotlib.path import Path

    from funcnet.plot.network_diagram import direction_edges

    edges = pd.concat([direction_edges(net) for net in ins.networks.values()])
    lines = [p.get_path() for p in ax.patches if p.get_gid() == "edges:none"]
    starts = sum(int((path.codes == Path.MOVETO).sum()) for path in lines)
    assert starts == int((edges["kind"] == "none").sum())
    arrows = [p for p in ax.patches if str(p.get_gid()).startswith("edge:")]
    assert len(arrows) == int((edges["kind"] == "directed").sum())
    titles = {t.get_gid().removeprefix("title:") for t in ax.texts
              if str(t.get_gid()).startswith("title:")}
    assert titles == {w.label for w in ins.windows}
    assert fig.legends
    assert layout_faults(fig) == []


def test_every_figure_of_a_page_keeps_its_texts_inside_and_apart():
    """The figures placed without a layout engine: motion, timeline, evidence (and the
    networks above) of a synthetic move, and of a trace at rest."""
    import warnings

    from funcnet.inspection import inspect_recording
    from funcnet.report import inspect_figures

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ins = inspect_recording(_one_move(), evidence=False, backlash=False)
    for name in ("motion", "timeline", "evidence"):
        fig = getattr(inspect_figures, f"figure_{name}")(ins)
        assert fig.get_layout_engine() is None
        assert layout_faults(fig) == [], name


def _twin_figures(x, y, shown_x):
    """The same axes twice: matplotlib's own ticks, and those of axis_ticks/fix_ticks."""
    from matplotlib.figure import Figure

    from funcnet.report.figure_geometry import renderer_of

    figs = []
    for _ in range(2):
        fig = Figure(figsize=(4.0, 3.0))
        ax = fig.add_axes((0.25, 0.2, 0.7, 0.65))
        ax.plot(x, y)
        ax.tick_params(labelsize=9)
        if not shown_x:
            ax.tick_params(labelbottom=False)
        ax.set_xlabel("time [s]", fontsize=9)
        ax.set_ylabel("value", fontsize=9)
        ax.set_title("a title", loc="left", fontsize=10)
        renderer_of(fig)
        figs.append((fig, ax))
    return figs


def test_fixed_ticks_are_where_and_what_matplotlib_draws():
    """axis_ticks + fix_ticks against matplotlib's own ticks on the same axes: the same tick
    labels at the same places (within a pixel), the same offset texts, the axis labels and
    the title moved as matplotlib moves them."""
    from funcnet.report.figure_geometry import axis_ticks, fix_ticks

    t = 1e5 + np.linspace(0.1, 0.15, 200)  # an offset on x ("+1e5"), and on y ("1e−5")
    for y, shown_x in ((1e-5 * np.sin(100 * t), True), (40 + 3 * np.cos(100 * t), False)):
        (old, old_ax), (new, new_ax) = _twin_figures(t, y, shown_x)
        renderer = new.canvas.get_renderer()
        fix_ticks(new_ax, axis_ticks(new_ax, "x", labels=shown_x), axis_ticks(new_ax, "y"),
                  renderer)
        old.canvas.draw()
        new.canvas.draw()
        drawn = [label for axis in (old_ax.xaxis, old_ax.yaxis)
                 for at, label in zip(axis.get_majorticklocs(), axis.get_ticklabels(),
                                      strict=False)
                 if label.get_visible() and label.get_text()
                 and min(axis.get_view_interval()) <= at <= max(axis.get_view_interval())]
        made = [t for t in new.artists if hasattr(t, "get_text")]
        assert [t.get_text() for t in drawn] == [t.get_text() for t in made]
        assert len(made) >= (8 if shown_x else 3)
        for a, b in [*zip(drawn, made, strict=True),
                     (old_ax.xaxis.label, new_ax.xaxis.label),
                     (old_ax.yaxis.label, new_ax.yaxis.label),
                     (old_ax.xaxis.offsetText, new_ax.xaxis.offsetText),
                     (old_ax.yaxis.offsetText, new_ax.yaxis.offsetText),
                     (old_ax._left_title, new_ax._left_title)]:
            assert a.get_text() == b.get_text()
            assert a.get_visible() == b.get_visible()
            box_a, box_b = a.get_window_extent(renderer), b.get_window_extent(renderer)
            assert np.allclose(box_a.get_points(), box_b.get_points(), atol=1.0), (
                a.get_text(), box_a, box_b)
        if shown_x:  # the offsets were there to compare (the second case: x's, hidden)
            assert new_ax.yaxis.offsetText.get_text() and new_ax.xaxis.offsetText.get_text()
        else:
            assert not new_ax.xaxis.offsetText.get_visible() and new_ax.xaxis.label.get_text()
        # matplotlib's own tick objects left with nothing to draw
        assert len(new_ax.xaxis.get_major_locator()()) == 0


def test_the_evidence_figure_informs_unless_every_cell_is_untestable():
    from types import SimpleNamespace

    def inspection(*tables):
        return SimpleNamespace(networks={str(k): SimpleNamespace(pairs=t)
                                         for k, t in enumerate(tables)})

    untestable = _pairs(True).assign(evidence="untestable")  # one pair degenerate
    assert not evidence_informs(inspection(untestable, untestable.iloc[1:]))
    assert evidence_informs(inspection(untestable, _pairs(True)))  # one coupled-directed cell
    assert evidence_informs(inspection(_pairs(False)))  # no evidence: coloured by kind


def test_a_page_whose_every_pair_is_untestable_says_so_instead_of_figure_4(tmp_path):
    import dataclasses
    import warnings

    from funcnet.inspection import inspect_recording
    from funcnet.report.inspect import write_inspection

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ins = inspect_recording(_one_move(), evidence=False, backlash=False)
        write_inspection(ins, tmp_path / "kinds")
        tested = inspect_recording(_one_move(), backlash=False)
        untestable = dataclasses.replace(tested, networks={
            label: dataclasses.replace(net, pairs=net.pairs.assign(evidence="untestable"))
            for label, net in tested.networks.items()})
        write_inspection(untestable, tmp_path / "untestable")
    assert (tmp_path / "kinds" / "figures" / "evidence.png").exists()
    assert not (tmp_path / "untestable" / "figures" / "evidence.png").exists()
    page = (tmp_path / "untestable" / "index.html").read_text()
    assert "Figure 4 (pairs × windows" in page and "is not drawn: every pair" in page
    assert (tmp_path / "untestable" / "figures" / "timeline.png").exists()
