"""The evidence figure of the inspect report: each cell's colour key and arrow."""

from __future__ import annotations

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
