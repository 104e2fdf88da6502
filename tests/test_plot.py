"""Figures: each draws, and draws the right content (edges, colours, nodes, spans, panels)."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch
from matplotlib.text import Text

import funcnet
from funcnet import plot
from funcnet.core.recurrence import isrn_adjacency, recurrence_matrix
from funcnet.network import FunctionalNetwork
from funcnet.network.schema import PAIR_KINDS
from funcnet.paper import figures

NODES = ("RP", "AP", "MP", "V", "RC", "AC")

# The synthetic signals trip the eps ordering / ties warnings; they are about the data, and this
# module tests drawing.
pytestmark = pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")


def net_of(pairs, **parameters):
    """The network of a small pairs table (default parameters, or those given)."""
    return FunctionalNetwork.from_pairs(
        pairs, funcnet.NetworkParameters(**parameters) if parameters else None)


def gids(ax, prefix):
    """The gids of the axes' patches (nodes, edges) and collections (shaded spans)."""
    return sorted(p.get_gid() for p in [*ax.patches, *ax.collections]
                  if (p.get_gid() or "").startswith(prefix))


def edge_patches(ax):
    return [p for p in ax.patches if isinstance(p, FancyArrowPatch)]


@pytest.fixture(scope="module")
def network():
    """A real 6-signal network: smooth positions, a derivative, noisy currents."""
    rng = np.random.default_rng(3)
    t = np.linspace(0, 6, 400)
    rp = np.sin(t) + 0.2 * t
    data = pd.DataFrame({
        "RP": rp,
        "AP": np.roll(rp, 3) + 0.01 * rng.standard_normal(t.size),
        "MP": np.roll(rp, 5) + 0.02 * rng.standard_normal(t.size),
        "V": np.gradient(rp) + 0.05 * rng.standard_normal(t.size),
        "RC": np.cos(2 * t) + 0.3 * rng.standard_normal(t.size),
        "AC": np.cos(2 * t + 0.1) + 0.3 * rng.standard_normal(t.size),
    })
    return funcnet.functional_network(data, label="test")


def test_plot_network_draws_every_edge_with_its_colour(network):
    ax = plot.plot_network(network)
    edges = network.edges
    bidirectional = {frozenset(p) for p in
                     edges.loc[edges["kind"] == "bidirectional", ["source", "target"]].values}
    directed = edges[edges["kind"] == "directed"]
    patches = edge_patches(ax)
    assert len(patches) == len(directed) + len(bidirectional)
    red = [p for p in patches if p.get_edgecolor() == to_rgba("red")]
    black = [p for p in patches if p.get_edgecolor() == to_rgba("black")]
    assert len(red) == len(bidirectional) and len(black) == len(directed)
    # directed arrows point the network's way
    drawn = {p.get_gid() for p in black}
    assert drawn == {f"edge:{s}->{t}:directed" for s, t in directed[["source", "target"]].values}
    # every node drawn, edges or not
    assert gids(ax, "node:") == sorted(f"node:{n}" for n in network.nodes)


def test_plot_network_from_pairs_matches_the_network(network):
    again = FunctionalNetwork.from_pairs(network.pairs, network.parameters)
    assert again.nodes == network.nodes and again.edges.equals(network.edges)
    from_net = sorted(p.get_gid() for p in edge_patches(plot.plot_network(network)))
    from_pairs = sorted(p.get_gid() for p in edge_patches(plot.plot_network(again)))
    # a bidirectional pair may be drawn from either end; compare as unordered pairs for those
    def norm(g):
        _, rest = g.split(":", 1)
        pair, kind = rest.rsplit(":", 1)
        a, b = pair.split("->")
        return (frozenset((a, b)), kind) if kind == "bidirectional" else (a, b, kind)
    assert sorted(map(str, map(norm, from_net))) == sorted(map(str, map(norm, from_pairs)))


def test_plot_network_width_proportional_to_weight_and_isolated_nodes():
    pairs = pd.DataFrame([{"x": a, "y": b, "kind": "conflict", "weight": 0.0}
                          for a, b in itertools.combinations(NODES, 2)])
    pairs.loc[0, ["kind", "weight"]] = ["x->y", 0.2]
    pairs.loc[1, ["kind", "weight"]] = ["y->x", 0.05]
    pairs.loc[2, ["kind", "weight"]] = ["bidirectional", 0.0]
    ax = plot.plot_network(net_of(pairs), width_scale=40, min_width=0.5)
    widths = {p.get_gid(): p.get_linewidth() for p in edge_patches(ax)}
    assert widths == {"edge:RP->AP:directed": pytest.approx(8.0),
                      "edge:MP->RP:directed": pytest.approx(2.0),
                      "edge:RP->V:bidirectional": pytest.approx(0.5)}
    assert len(gids(ax, "node:")) == 6  # nodes without any edge are drawn too


def test_plot_network_places_given_nodes_and_dashes_absent_ones():
    pairs = pd.DataFrame({"x": ["RP"], "y": ["AC"], "kind": ["x->y"], "weight": [0.1]})
    ax = plot.plot_network(net_of(pairs), nodes=NODES)
    circles = {p.get_gid(): p for p in ax.patches if (p.get_gid() or "").startswith("node:")}
    assert sorted(circles) == sorted(f"node:{n}" for n in NODES)
    assert {n for n, c in circles.items() if c.get_linestyle() == "-"} == {"node:RP", "node:AC"}
    # circle order follows `nodes`: RP at the top, AC last (clockwise)
    assert circles["node:RP"].center == pytest.approx((0.0, 1.0))
    assert circles["node:AC"].center == pytest.approx((np.cos(np.pi / 2 - 5 * np.pi / 3),
                                                       np.sin(np.pi / 2 - 5 * np.pi / 3)))


def test_plot_recurrence_shows_the_recurrence_matrix():
    x = np.sin(np.linspace(0, 8 * np.pi, 251))
    expected = recurrence_matrix(x, dim=3, delay=10, eps=0.15)
    ax = plot.plot_recurrence(expected)
    image = np.asarray(ax.images[0].get_array())
    assert np.array_equal(image.astype(bool), np.asarray(expected, dtype=bool))
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("j", "i")
    cross = plot.plot_recurrence(np.zeros((4, 5), dtype=bool), cross=True)
    assert cross.get_ylabel() == "i (X)" and cross.images[0].get_array().shape == (4, 5)


def test_figure_embedding_network_graph_has_the_matrix_edges():
    fig = figures.figure_embedding_network(n=121, periods=2)
    assert isinstance(fig, Figure) and len(fig.axes) == 4
    matrix = np.asarray(recurrence_matrix(np.sin(np.linspace(0, 4 * np.pi, 121)),
                                          dim=3, delay=10, eps=0.15))
    (lines,) = [c for c in fig.axes[3].collections if c.get_gid() == "isrn-edges"]
    off_diagonal = np.triu(matrix, 1).sum()
    assert len(lines.get_segments()) == off_diagonal
    (nodes,) = [c for c in fig.axes[3].collections if c.get_gid() == "isrn-nodes"]
    assert len(nodes.get_offsets()) == matrix.shape[0] == 121 - 20


def test_figure_isrn_blocks_and_colours():
    fig = figures.figure_isrn(n=121, periods=2)
    t = np.linspace(0, 4 * np.pi, 121)
    x, y = np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)
    adjacency = np.asarray(isrn_adjacency(x, y, dim=3, delay=10, eps=((0.15, 0.15), 0.05)))
    assert np.array_equal(np.asarray(fig.axes[2].images[0].get_array()).astype(bool),
                          adjacency.astype(bool))
    (nodes,) = [c for c in fig.axes[3].collections if c.get_gid() == "isrn-nodes"]
    colours = nodes.get_facecolors()
    m = adjacency.shape[0] // 2
    assert (colours[:m] == to_rgba("tab:blue")).all() and (colours[m:] == to_rgba("tab:red")).all()


def test_figure_pair_network_uses_the_clustering_difference():
    ax = figures.figure_pair_network()
    t = np.linspace(0, 8 * np.pi, 251)
    net = funcnet.functional_network(np.column_stack([np.sin(t), np.sin(1.5 * t)
                                                      + 0.3 * np.sin(t)]), names=["x", "y"],
                                     normalize="minmax", measure="clustering")
    assert f"{float(net.pairs['c_diff'].iloc[0]):+.3f}" in ax.get_title()
    assert len(edge_patches(ax)) == len(plot.network_edges(net))
    # normalized input, as the package does by default: the README's +0.11, arrow y -> x
    assert ax.get_title().startswith("C_diff = +0.111")
    assert net.pairs["kind"].iloc[0] == "y->x"


def test_figure_isrn_says_when_the_cross_block_is_empty():
    fig = figures.figure_isrn()
    assert figures.isrn_cross_links() == 0
    assert any("no cross link" in t.get_text() for t in fig.axes[2].texts)
    fig = figures.figure_isrn(eps=((0.15, 0.15), 0.15))
    assert not fig.axes[2].texts


def test_figure_notes_are_sentences_naming_the_networks():
    net = figures.pair_network(warn=False)
    notes = figures.figure_notes({"Fig. 5": net})
    assert notes and all(n.startswith("Flagged: ") and n.endswith("in Fig. 5.") for n in notes)
    assert not any("Warning" in n for n in notes)


def trial_frame(n=600):
    t = np.arange(n) * 0.002
    ramp = np.clip(t - 0.2, 0, None)
    return pd.DataFrame({"RP": ramp, "AP": ramp * 0.99, "MP": ramp * 1.01,
                         "V": np.gradient(ramp), "RC": np.sin(t * 20), "AC": np.sin(t * 20 + .1)},
                        index=pd.Index(t, name="time"))


def test_figure_phases_marks_every_phase_and_draws_a_network_per_phase(network):
    data = trial_frame().assign(FE=lambda d: d["RP"] - d["AP"])
    phases = pd.DataFrame({"phase": ["early spin-up", "cruise", "braking"],
                           "start": [0.0, 0.4, 0.9], "stop": [0.4, 0.9, 1.19]})
    fig = figures.figure_phases(data, phases, {"early spin-up": network, "cruise": network,
                                            "braking": net_of(network.pairs)})
    signal_axes = [ax for ax in fig.axes if ax.lines]
    # normalized + raw panels by units: positions, velocity, currents, other (FE)
    assert len(signal_axes) == 5
    assert [line.get_label() for line in signal_axes[-1].lines] == ["FE"]
    for ax in signal_axes:
        assert gids(ax, "phase:") == sorted(f"phase:{p}" for p in phases["phase"])
    network_axes = [ax for ax in fig.axes if gids(ax, "node:")]
    assert [ax.get_title() for ax in network_axes] == ["early spin-up", "cruise", "braking"]
    normalized = signal_axes[0]
    assert all(np.nanmax(line.get_ydata()) <= 1.0 for line in normalized.lines)


def test_figure_velocity_grid_cells(network):
    data = trial_frame(150)
    cells = {(v, p): (data, None if (v, p) == ("V1", "cruise") else network)
             for p in ("spin-up", "cruise", "braking") for v in ("V1", "V35", "V175", "V350")}
    fig = figures.figure_velocity_grid(cells)
    network_axes = [ax for ax in fig.axes if gids(ax, "node:")]
    series_axes = [ax for ax in fig.axes if ax.lines]
    assert len(network_axes) == 11 and len(series_axes) == 12
    assert series_axes[0].get_title() == "V1 · spin-up"
    for ax in network_axes:
        assert len(edge_patches(ax)) == len(plot.network_edges(network))


def test_figure_reversal_windows_and_networks(network):
    data = trial_frame(1000)
    from types import SimpleNamespace

    windows = [SimpleNamespace(label=f"{o:+d} ms", start=1.0 + o / 1000 - 0.05,
                               stop=1.0 + o / 1000 + 0.05) for o in (-40, -20, 0, 20, 40)]
    nets = {w.label: network for w in windows}
    nets["+40 ms"] = None
    fig = figures.figure_reversal(data, windows, nets)
    zoom = fig.axes[1]
    assert gids(zoom, "window:") == sorted(f"window:{w.label}" for w in windows)
    network_axes = [ax for ax in fig.axes if gids(ax, "node:")]
    assert [ax.get_title() for ax in network_axes] == ["-40 ms", "-20 ms", "+0 ms", "+20 ms"]
    # the zoom spans the windows (0.91-1.09 s) with half their span on either side
    shown = zoom.lines[0].get_xdata()
    assert min(shown) == pytest.approx(0.82) and max(shown) == pytest.approx(1.18)


def test_plot_edge_timeline_one_point_per_pair_and_window(network):
    timeline = {0.5: network, 1.0: network, 1.5: net_of(network.pairs)}
    ax = plot.plot_edge_timeline(timeline)
    points = sum(len(c.get_offsets()) for c in ax.collections)
    assert points == 3 * len(network.pairs)
    kinds = network.pairs["kind"].value_counts()
    for collection in ax.collections:
        kind = collection.get_gid().split(":", 1)[1]
        assert kind in PAIR_KINDS  # the network's own vocabulary
        assert len(collection.get_offsets()) == 3 * kinds[kind]
    assert len(ax.get_yticks()) == len(network.pairs)


def test_signal_colours_are_distinct_and_used_by_every_series_figure(network):
    roles = ("RP", "AP", "MP", "V", "RC", "AC", "FE", "TORSION")
    assert set(plot.SIGNAL_COLORS) == set(roles)
    assert len({to_rgba(c) for c in plot.SIGNAL_COLORS.values()}) == len(roles)
    # no signal is drawn in the red of bidirectional edges
    assert to_rgba(plot.BIDIRECTIONAL_COLOR) not in {to_rgba(c) for c in
                                                     plot.SIGNAL_COLORS.values()}
    assert plot.signal_color("XYZ") == plot.signal_color("XYZ")  # stable for unknown names
    data = trial_frame(300)
    phases = pd.DataFrame({"phase": ["a", "b"], "start": [0.0, 0.3], "stop": [0.3, 0.6]})
    fig9 = figures.figure_phases(data, phases, {"a": network, "b": network})
    fig10 = figures.figure_velocity_grid({("V1", "a"): (data, network), ("V35", "a"): (data[
        ["RP", "AC"]], network)})
    for fig in (fig9, fig10):
        for ax in fig.axes:
            for line in ax.lines:
                assert to_rgba(line.get_color()) == to_rgba(plot.SIGNAL_COLORS[line.get_label()])


def test_velocity_grid_has_one_shared_legend_of_signals_and_one_of_edges(network):
    data = trial_frame(150)
    cells = {(v, p): (data, network) for p in ("spin-up", "cruise") for v in ("V1", "V35")}
    fig = figures.figure_velocity_grid(cells)
    assert all(ax.get_legend() is None for ax in fig.axes)
    legends = {legend.get_gid(): legend for legend in fig.legends}
    assert set(legends) == {"legend:signals", "legend:network"}
    signals = legends["legend:signals"]
    assert [t.get_text() for t in signals.get_texts()] == list(data.columns)
    assert [to_rgba(h.get_color()) for h in signals.legend_handles] == [
        to_rgba(plot.SIGNAL_COLORS[c]) for c in data.columns]
    series = [ax for ax in fig.axes if ax.lines]
    assert all(ax.get_xlabel() == "time [s]" for ax in series)
    assert series[0].get_ylabel() == "normalized"


def test_network_legend_explains_colours_and_width():
    pairs = pd.DataFrame({"x": ["RP"], "y": ["TORSION"], "kind": ["x->y"], "weight": [0.3]})
    ax = plot.plot_network(net_of(pairs), width_scale=10)
    legend = ax.get_legend()
    handles = dict(zip([t.get_text() for t in legend.get_texts()], legend.legend_handles,
                       strict=True))
    assert to_rgba(handles["directed (|diff| ≥ μ)"].get_color()) == to_rgba("black")
    assert to_rgba(handles["bidirectional (|diff| < μ)"].get_color()) == to_rgba("red")
    (reference,) = [h for label, h in handles.items() if label.startswith("weight 0.2")]
    assert reference.get_linewidth() == pytest.approx(2.0)  # same scale as the edges
    assert plot.plot_network(net_of(pairs), legend=False).get_legend() is None
    # the long name gets a larger node; the arrow head grows with the line and ends at its rim
    circles = {p.get_gid(): p for p in ax.patches if (p.get_gid() or "").startswith("node:")}
    assert circles["node:TORSION"].radius > circles["node:RP"].radius
    (arrow,) = edge_patches(ax)
    assert arrow.get_mutation_scale() > 9 + arrow.get_linewidth()
    end = np.asarray(arrow._posA_posB[1])  # no public getter for the arrow's end point
    assert np.hypot(*(end - circles["node:TORSION"].center)) == pytest.approx(
        circles["node:TORSION"].radius)


def test_phase_names_sit_between_panel_and_title():
    data = trial_frame(300)
    phases = pd.DataFrame({"phase": ["early spin-up", "cruise"], "start": [0.0, 0.3],
                           "stop": [0.3, 0.6]})
    fig = figures.figure_phases(data, phases, {"early spin-up": None, "cruise": None})
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw_without_rendering()
    top = fig.axes[0]
    (title,) = [t for t in top.get_children()
                if isinstance(t, Text) and t.get_text() == "(a) min–max normalized"]
    title = title.get_window_extent(renderer)
    names = [t for t in top.texts if t.get_text() in ("early spin-up", "cruise")]
    assert len(names) == 2
    for name in names:
        box = name.get_window_extent(renderer)
        assert box.y1 <= title.y0 and box.y0 >= top.get_window_extent(renderer).y1


def test_edge_timeline_legends_name_the_direction_and_the_weight_scale(network):
    ax = plot.plot_edge_timeline({0.5: network, 1.0: network})
    legends = {a.get_gid(): a for a in ax.get_children() if a.get_gid() in
               ("legend:kind", "legend:weight")}
    assert set(legends) == {"legend:kind", "legend:weight"}
    x, y = network.pairs[["x", "y"]].iloc[0]
    texts = [t.get_text() for t in legends["legend:kind"].get_texts()]
    assert any(f"{x} → {y} on track {x}–{y}" in t or f"{y} → {x} on track {x}–{y}" in t
               for t in texts)
    weights = [float(t.get_text()) for t in legends["legend:weight"].get_texts()]
    assert weights and max(weights) <= network.pairs["weight"].max()
    # marker area is size_scale × weight in the key as on the axes
    sizes = [h.get_markersize() ** 2 for h in legends["legend:weight"].legend_handles]
    assert sizes == pytest.approx([max(4.0, 600.0 * w) for w in weights])


def test_plot_draws_and_computes_nothing():
    """The plot package imports nothing that computes (recurrence, measures, networks, ...)."""
    import ast
    from pathlib import Path

    files = sorted(Path(plot.__file__).parent.glob("*.py"))
    assert len(files) > 1  # the package, not one module
    trees = [ast.parse(f.read_text(encoding="utf-8")) for f in files]
    # imports for type annotations only (`if TYPE_CHECKING:`) run nothing
    type_only = {id(n) for tree in trees for block in ast.walk(tree)
                 if isinstance(block, ast.If) and getattr(block.test, "id", "") == "TYPE_CHECKING"
                 for stmt in block.body for n in ast.walk(stmt)}
    imported = set()
    for node in (n for tree in trees for n in ast.walk(tree) if id(n) not in type_only):
        if isinstance(node, ast.Import):
            imported |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add(node.module or "")
            imported |= {f"{node.module}.{alias.name}" for alias in node.names}
    funcnet_imports = {name for name in imported if name.split(".")[0] == "funcnet"}
    allowed = ("funcnet.network.schema", "funcnet.network.rule", "funcnet.errors", "funcnet._io",
               "funcnet._lazy", "funcnet.parameters", "funcnet.plot")
    assert all(name.startswith(allowed) for name in funcnet_imports), funcnet_imports
    assert "funcnet" not in imported  # no `import funcnet` reaching the core at call time
    called = {node.func.attr if isinstance(node.func, ast.Attribute) else
              getattr(node.func, "id", "") for tree in trees for node in ast.walk(tree)
              if isinstance(node, ast.Call)}
    assert not called & {"functional_network", "recurrence_matrix", "cross_recurrence_matrix",
                         "isrn_adjacency", "window_networks", "cross_measures"}


def degenerate_pairs():
    pairs = pd.DataFrame({"x": ["RP", "RP", "AP"], "y": ["AP", "MP", "MP"],
                          "kind": ["x->y", "y->x", "bidirectional"],
                          "weight": [0.2, 0.4, 0.05], "degenerate": [False, True, False]})
    return pairs


def test_degenerate_edges_are_drawn_only_when_kept_and_then_dashed_grey():
    pairs = degenerate_pairs()
    # by default a degenerate pair is no edge: not drawn, no legend entry
    ax = plot.plot_network(net_of(pairs))
    assert sorted(p.get_gid() for p in edge_patches(ax)) == [
        "edge:AP->MP:bidirectional", "edge:RP->AP:directed"]
    assert "degenerate" not in " ".join(t.get_text() for t in ax.get_legend().get_texts())
    # kept: drawn, grey and dashed, unlike every real edge, and the legend says so
    ax = plot.plot_network(net_of(pairs, degenerate="keep"))
    arrows = {p.get_gid(): p for p in edge_patches(ax)}
    assert set(arrows) == {"edge:RP->AP:directed", "edge:AP->MP:bidirectional",
                           "edge:MP->RP:directed:degenerate"}
    flagged = arrows["edge:MP->RP:directed:degenerate"]
    assert flagged.get_edgecolor() == to_rgba(plot.DEGENERATE_COLOR)
    assert flagged.get_linestyle() == "--"
    for gid, arrow in arrows.items():
        if not gid.endswith(":degenerate"):
            assert arrow.get_linestyle() == "-"
            assert arrow.get_edgecolor() != to_rgba(plot.DEGENERATE_COLOR)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    handles = dict(zip(texts, ax.get_legend().legend_handles, strict=True))
    (entry,) = [t for t in texts if t.startswith("degenerate")]
    assert handles[entry].get_linestyle() == "--"
    # a table without the flag, or with gaps (older study rows), has no degenerate pair
    assert len(edge_patches(plot.plot_network(net_of(pairs.drop(columns="degenerate"))))) == 3
    gaps = pairs.assign(degenerate=[None, True, None])
    assert len(edge_patches(plot.plot_network(net_of(gaps, degenerate="keep")))) == 3


def test_a_network_that_keeps_degenerate_pairs_draws_them_differently():
    rng = np.random.default_rng(4)
    t = np.linspace(0, 6, 300)
    data = pd.DataFrame({"RP": np.sin(t) + 0.01 * rng.standard_normal(t.size),
                         "AP": np.cos(t) + 0.01 * rng.standard_normal(t.size),
                         "Q": np.round(np.sin(t))})  # three distinct values: degenerate
    kept = funcnet.functional_network(data, degenerate="keep", warn=False)
    dropped = funcnet.functional_network(data, warn=False)
    assert kept.pairs["degenerate"].any()
    flagged = {f"edge:{s}->{t}:{k}:degenerate" for s, t, k in
               kept.edges.loc[kept.edges["degenerate"], ["source", "target", "kind"]].values}
    assert flagged
    drawn = {p.get_gid() for p in edge_patches(plot.plot_network(kept))}
    assert flagged <= drawn
    assert not any(g.endswith(":degenerate")
                   for g in (p.get_gid() for p in edge_patches(plot.plot_network(dropped))))
    # the figure-wide legend explains them when asked
    fig = Figure(layout="constrained")
    legend = plot.add_network_legend(fig, degenerate=True)
    assert any(t.get_text().startswith("degenerate") for t in legend.get_texts())


def test_edge_timeline_marks_degenerate_pairs():
    net = net_of(degenerate_pairs())
    ax = plot.plot_edge_timeline({0.5: net, 1.0: net})
    by_kind = {c.get_gid(): len(c.get_offsets()) for c in ax.collections}
    assert by_kind == {"kind:x->y": 2, "kind:bidirectional": 2, "kind:degenerate": 2}


def test_recurrence_plots_figure_computes_as_the_network_does():
    from funcnet.core.normalization import normalize
    from funcnet.parameters import NetworkParameters

    data = trial_frame(300)
    parameters = NetworkParameters(delay=4, rr=0.1)
    fig = figures.figure_recurrence_plots(data, parameters, columns=("RP", "RC", "AC"),
                                          left_out=("AC",))
    rp, rc, ac = fig.axes
    expected = recurrence_matrix(normalize(data["RC"].to_numpy(), "minmax"), dim=3, delay=4,
                                 rr=0.1)
    assert np.array_equal(np.asarray(rc.images[0].get_array()).astype(bool), expected)
    assert rp.get_title() == "RP" and not ac.images  # left out of the network: left out here


def test_pair_network_notes_come_from_the_flags():
    net = figures.pair_network(n=151, periods=3, warn=False)
    notes = figures.figure_notes({"Fig. 5": net, "none": None})
    flagged = (~net.pairs["eps_ordered"]) | net.pairs["rate_exceeded"] | net.pairs["degenerate"]
    assert bool(notes) == bool(flagged.any())
    ax = figures.figure_pair_network(network=net)
    assert f"{float(net.pairs['c_diff'].iloc[0]):+.3f}" in ax.get_title()


# --------------------------------------------------------------------------------------------
# evidence: edges without coupling evidence look different, and the legend says so


def evidence_pairs():
    return pd.DataFrame({"x": ["RP", "RP", "AP", "RP"], "y": ["AP", "MP", "MP", "V"],
                         "kind": ["x->y", "y->x", "bidirectional", "x->y"],
                         "weight": [0.2, 0.4, 0.05, 0.3],
                         "evidence": ["coupled-directed", "asymmetry-only", "not-coupled",
                                      "untestable"]})


def test_edges_without_coupling_evidence_are_dotted_and_pale():
    ax = plot.plot_network(net_of(evidence_pairs()))
    arrows = {p.get_gid(): p for p in edge_patches(ax)}
    assert set(arrows) == {"edge:RP->AP:directed:coupled-directed",
                           "edge:MP->RP:directed:asymmetry-only",
                           "edge:AP->MP:bidirectional:not-coupled",
                           "edge:RP->V:directed:untestable"}
    coupled = arrows["edge:RP->AP:directed:coupled-directed"]
    assert coupled.get_linestyle() == "-"
    assert coupled.get_edgecolor() == to_rgba(plot.DIRECTED_COLOR)
    for gid in ("edge:MP->RP:directed:asymmetry-only", "edge:AP->MP:bidirectional:not-coupled"):
        assert arrows[gid].get_linestyle() == ":"
        assert arrows[gid].get_edgecolor() not in (to_rgba(plot.DIRECTED_COLOR),
                                                   to_rgba(plot.BIDIRECTIONAL_COLOR))
    # an untestable pair is drawn neither as a finding nor as a tested absence
    blind = arrows["edge:RP->V:directed:untestable"]
    assert blind.get_linestyle() not in ("-", ":")
    assert blind.get_edgecolor() not in {arrows[g].get_edgecolor() for g in arrows
                                         if g != "edge:RP->V:directed:untestable"}
    # the legend explains the three styles
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    handles = dict(zip(texts, ax.get_legend().legend_handles, strict=True))
    (solid,) = [t for t in texts if t.startswith("coupled")]
    (dotted,) = [t for t in texts if "not shown coupled" in t]
    (untested,) = [t for t in texts if t.startswith("untestable")]
    assert handles[solid].get_linestyle() == "-" and handles[dotted].get_linestyle() == ":"
    assert handles[untested].get_linestyle() == blind.get_linestyle()


def test_without_evidence_columns_the_drawing_is_unchanged():
    with_evidence = plot.plot_network(net_of(evidence_pairs()))
    plain = plot.plot_network(net_of(evidence_pairs().drop(columns="evidence")))
    assert all(p.get_linestyle() == "-" for p in edge_patches(plain))
    assert all(g.count(":") == 2 for g in (p.get_gid() for p in edge_patches(plain)))
    texts = [t.get_text() for t in plain.get_legend().get_texts()]
    assert not any("coupl" in t for t in texts)
    assert len(with_evidence.get_legend().get_texts()) == len(texts) + 3
    # rows of a study run without evidence (NaN) count as no evidence at all
    gaps = evidence_pairs().assign(evidence=[None] * 4)
    assert all(p.get_linestyle() == "-" for p in edge_patches(plot.plot_network(net_of(gaps))))


def test_a_network_with_evidence_draws_its_readings():
    from funcnet.validation.systems import henon_pair

    x = henon_pair(600, 0.6, seed=1)
    noise = np.random.default_rng(3).normal(size=len(x))
    data = pd.DataFrame({"X": x[:, 0], "Y": x[:, 1], "N": noise})
    net = funcnet.functional_network(data, dim=2, delay=1, evidence=True, resamples=0,
                                     warn=False)
    readings = dict(zip(zip(net.pairs["x"], net.pairs["y"], strict=True), net.pairs["evidence"],
                        strict=True))
    arrows = {p.get_gid(): p for p in edge_patches(plot.plot_network(net))}
    assert arrows
    for gid, arrow in arrows.items():
        source, target = gid.split(":")[1].split("->")
        reading = readings.get((source, target), readings.get((target, source)))
        assert gid.endswith(f":{reading}")
        assert arrow.get_linestyle() == (":" if reading in plot.NO_COUPLING_EVIDENCE else "-")


def test_an_undecided_line_stops_just_short_of_both_node_rims():
    # The pale line of an undecided pair ends outside each node's circle, a small gap (about
    # 2 pt) before the rim, as every other edge stops at the rim: measured on the drawing.
    pairs = pd.DataFrame({"x": ["RP", "RP"], "y": ["AP", "AC"], "kind": ["x->y", "x->y"],
                          "weight": [0.2, 0.3], "direction": ["none", "x->y"]})
    fig = Figure(figsize=(2.6, 2.6), dpi=100)
    ax = fig.add_subplot()
    plot.plot_network(net_of(pairs), ax, arrows="direction", legend=False)
    FigureCanvasAgg(fig).draw()
    circles = {p.get_gid()[5:]: p for p in ax.patches if (p.get_gid() or "").startswith("node:")}
    line = next(p for p in ax.patches if p.get_gid() == "edge:RP->AP:none")
    vertices = ax.transData.transform(line.get_path().vertices)
    points_per_pixel = 72 / fig.dpi
    for end, node in ((vertices[0], "RP"), (vertices[-1], "AP")):
        circle = circles[node]
        centre = ax.transData.transform(circle.center)
        rim = ax.transData.transform((circle.center[0] + circle.radius, circle.center[1]))
        radius = rim[0] - centre[0]
        gap = (np.hypot(*(end - centre)) - radius) * points_per_pixel
        assert 0.5 < gap < 4.0, (node, gap)


def test_a_panel_without_network_takes_its_neighbours_title_size():
    ax = Figure().add_subplot()
    plot.plot_no_network(ax, "early spin-up", fontsize=11)
    assert ax.title.get_fontsize() == 11 and ax.title.get_text() == "early spin-up"
    assert plot.plot_no_network(Figure().add_subplot(), "x").title.get_fontsize() == 9
