"""Figures of the inspect report: the evidence figure's cells, the network panels."""

from __future__ import annotations

import numpy as np
import pandas as pd

from funcnet.report.inspect_figures import ARROWS, _cell_readings, figure_evidence


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
    texts = sorted((t.get_position(), t.get_text()) for t in fig.axes[0].texts)
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


def test_network_panels_keep_their_frame_and_everything_inside_the_canvas():
    """Each phase's panel: its frame in the phase's colour, no axis (no tick, no label) for the
    layout; after the layout every title, node name and the legend lie inside the figure."""
    import warnings

    from matplotlib.colors import to_hex

    from funcnet.inspection import inspect_recording
    from funcnet.plot import phase_color
    from funcnet.report.html import _settle_layout
    from funcnet.report.inspect_figures import figure_networks

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ins = inspect_recording(_one_move(), evidence=False, backlash=False)
    fig = figure_networks(ins)
    panels = [ax for ax in fig.axes if ax.get_title()]
    assert len(panels) == len(ins.networks) >= 2
    by_label = {w.label: w for w in ins.windows}
    for ax in panels:
        assert ax.axison and all(spine.get_visible() for spine in ax.spines.values())
        assert not ax.xaxis.get_visible() and not ax.yaxis.get_visible()
        label = ax.get_title().split("\n")[0]
        assert to_hex(ax.get_facecolor()) == to_hex(phase_color(by_label[label].phase))
    _settle_layout(fig, 100)
    fig.canvas.draw()  # as saved: titles take their place when drawn
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    texts = [t for ax in panels for t in (ax.title, *ax.texts)]
    legends = fig.legends
    assert legends
    for artist in [*texts, *legends]:
        box = artist.get_window_extent(renderer)
        assert (box.x0 >= canvas.x0 - 1 and box.x1 <= canvas.x1 + 1
                and box.y0 >= canvas.y0 - 1 and box.y1 <= canvas.y1 + 1), artist
