"""`funcnet backlash` on the real trace: a result, exit 0."""

from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from conftest import KUKA, REPO
from funcnet.cli import app

runner = CliRunner()


def test_the_real_trace_is_a_result_not_an_error(real_trace, tmp_path):
    out = tmp_path / "result.json"
    result = runner.invoke(app, ["backlash", str(real_trace), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "no reversal" in result.output and "lost_motion" in result.output
    traces = json.loads(out.read_text())["traces"]
    assert traces[0]["path"] == str(real_trace) and traces[0]["backlash_score"] is None


@pytest.mark.parametrize("args", [["nope.xml"], ["{run}", "-o", "r.txt"]])
def test_bad_input_is_one_line_and_exit_2(tmp_path, args):
    kuka = [str(KUKA / "kr300-run-A.mat"), "--channels",
            str(REPO / "examples" / "kuka-kr300-channels.toml")]
    args = [part for a in args for part in (kuka if a == "{run}" else [a])]
    result = runner.invoke(app, ["backlash", *args])
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "error" in result.output


# --------------------------------------------------------------------------------------------
# funcnet backlash-report: the sweep's report from a folder funcnet simulate wrote


@pytest.fixture(scope="module")
def sweep_report(tmp_path_factory):
    """A fixed small sweep (12 trials) written, then reported through the command line."""
    from funcnet.sim.plan import backlash_sweep_plan, write_plan

    root = tmp_path_factory.mktemp("sweep")
    plan = backlash_sweep_plan(backlash_arcmin=(0, 0.5, 2), speeds=(35, 175), tcps=(1.6,),
                               friction_scales=(1.0,), stiffness_scales=(0.7, 1.4), seeds=(1,),
                               noise_scales=(1.0,))  # fmt: skip
    write_plan(plan, root / "traces")
    out = root / "report" / "sweep.html"
    result = runner.invoke(app, ["backlash-report", str(root / "traces"), "-o", str(out),
                                 "--resamples", "200", "-q"])  # fmt: skip
    assert result.exit_code == 0, result.output
    return out, result.output


def _brute_force_auc(positive, negative):
    """Mann-Whitney AUC by counting every (positive, negative) pair, ties one half."""
    wins = sum(1.0 if p > n else 0.5 if p == n else 0.0 for p in positive for n in negative)
    return wins / (len(positive) * len(negative))


def _rows(html_text):
    """The cells of every table row of the page, as text."""
    return [[re.sub(r"<[^>]+>", "", cell) for cell in re.findall(r"<td[^>]*>(.*?)</td>", row)]
            for row in re.findall(r"<tr>(.*?)</tr>", html_text)]  # fmt: skip


def test_the_sweep_report_has_its_figures_tables_and_the_right_auc(sweep_report):
    import pandas as pd

    from funcnet.diagnosis import SCORE

    out, printed = sweep_report
    assert f"report: {out}" in printed and f"backlash_score {SCORE}" in printed
    page = out.read_text()
    for name in ("sweep-roc", "sweep-scatter"):
        figure = out.parent / "figures" / f"{name}.png"
        assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert f'src="figures/{name}.png"' in page
    indicators = pd.read_csv(out.parent / "sweep-indicators.csv")
    scores = pd.read_csv(out.parent / "sweep-scores.csv")
    assert len(indicators) == 12
    rows = _rows(page)
    for indicator in (SCORE, "vibration", "fn_asymmetry"):
        for speed, part in indicators.groupby("speed"):
            truth, values = part["backlash_arcmin"], part[indicator]
            auc = _brute_force_auc(values[truth >= 0.5].tolist(), values[truth == 0].tolist())
            row = scores[(scores["indicator"] == indicator) & (scores["speed"] == speed)]
            assert row["auc_0.5_vs_0"].item() == pytest.approx(auc, abs=1e-12)
            rho = part[[indicator, "backlash_arcmin"]].rank().corr().iloc[0, 1]
            assert row["rho"].item() == pytest.approx(rho, abs=1e-12)
            # the page's table shows the same number (two decimals, then its interval)
            cells = [r for r in rows if indicator in r and f"{speed:g}" == r[0]]
            assert cells and cells[0][4].startswith(f"{auc:.2f} [")
    # the reading counts the reversal windows with the paper's signature
    shown = int(indicators["signature"].sum())
    assert f"appeared in {shown} of 12 reversal windows" in page


def test_the_sweep_report_reads_its_own_indicator_table(sweep_report, tmp_path):
    out, _ = sweep_report
    again = tmp_path / "again.html"
    result = runner.invoke(app, ["backlash-report", str(out.parent / "sweep-indicators.csv"),
                                 "-o", str(again), "--resamples", "200", "-q"])  # fmt: skip
    assert result.exit_code == 0, result.output
    assert (tmp_path / "again-scores.csv").read_text() == (
        out.parent / "sweep-scores.csv").read_text()


@pytest.mark.parametrize("args", [["{missing}"], ["{folder}", "-o", "r.txt"]])
def test_the_sweep_report_on_bad_input_is_one_line_and_exit_2(tmp_path, args):
    args = [a.replace("{missing}", str(tmp_path / "none")).replace("{folder}", str(tmp_path))
            for a in args]  # fmt: skip
    result = runner.invoke(app, ["backlash-report", *args])
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "error" in result.output


def test_a_continuous_sweep_is_reported_with_its_lost_motion_against_the_truth(tmp_path):
    """The continuous sweep's trials (smooth turns, with and without a load) go through
    `simulate` and `backlash-report`: the manifest carries `arm_load` and `profile`, the rest
    reversals' indicators are absent there (no crash), and the lost-motion table's shares are
    those counted here from the indicator table."""
    import pandas as pd

    from funcnet.sim.plan import continuous_sweep_plan, write_plan

    plan = continuous_sweep_plan(backlash_arcmin=(0, 2), arm_loads=(0.0, 1000.0), speeds=(175,),
                                 tcps=(1.6,), friction_scales=(1.0,))  # fmt: skip
    manifest = pd.read_csv(write_plan(plan, tmp_path / "traces"))
    assert sorted(set(manifest["arm_load"])) == [0.0, 1000.0]
    assert set(manifest["profile"]) == {"smooth"}
    out = tmp_path / "report" / "cs.html"
    result = runner.invoke(app, ["backlash-report", str(tmp_path / "traces"), "-o", str(out),
                                 "--no-fn", "--resamples", "50", "-q"])  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "warning" not in result.output
    table = pd.read_csv(out.parent / "cs-indicators.csv")
    assert table["motor_hysteresis"].isna().all() and table["lost_motion"].notna().all()
    page = out.read_text()
    assert 'id="lost-motion"' in page and "smooth" in page
    # independent count: the unloaded 2-arcmin trial crosses its dead zone, the others do not
    crossed = (table["backlash_arcmin"] > 0) & (table["arm_load"] == 0)
    assert (table["true_lost_motion"][crossed] * 60 > 1.0).all()
    assert (table["true_lost_motion"][~crossed].abs() * 60 < 0.05).all()
    step = 360 / 2**22
    for load in (0.0, 1000.0):
        part = table[table["arm_load"] == load]
        error = part["lost_motion"] - part["true_lost_motion"]
        within = (error.abs() <= 2 * step)[~crossed[part.index]].mean()
        assert f"{within:.1%}" in page.split('id="lost-motion"')[1].split("</table>")[0]


def test_an_existing_plan_keeps_its_manifest_columns(tmp_path):
    import pandas as pd

    from funcnet.sim import MANIFEST_COLUMNS, OPTIONAL_MANIFEST_COLUMNS, Trial
    from funcnet.sim.plan import write_plan

    manifest = write_plan([Trial("q", "g", speed=350, tcp=1.2, step=1)], tmp_path)
    assert list(pd.read_csv(manifest).columns) == list(MANIFEST_COLUMNS)
    assert not set(OPTIONAL_MANIFEST_COLUMNS) & set(MANIFEST_COLUMNS)
