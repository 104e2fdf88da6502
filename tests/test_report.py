"""Reports: built on a tiny simulated plan and on a tiny study; every figure loads in Chromium."""

from __future__ import annotations

import html
import html.parser
import io
import json
import re
import shutil
import subprocess
from pathlib import Path

import pandas as pd
import pytest

from funcnet.paper.demo import build_demo_report
from funcnet.report import write_report

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
WINDOW_WIDTH = 1300  # pixels; the report must read without sideways scrolling at this width

# Marks each image in the DOM once the page has loaded; the test copies the page and injects
# it, so the report itself stays free of scripts.
_PROBE = """<script>
window.addEventListener("load", () => {
  for (const img of document.images) {
    img.setAttribute("data-loaded", img.complete && img.naturalWidth > 0 ? "yes" : "no");
  }
  // Every table shown, then the page's width: it must fit the window (no sideways scrolling).
  for (const details of document.querySelectorAll("details")) { details.open = true; }
  document.body.setAttribute("data-scroll-width", document.documentElement.scrollWidth);
  // A cell narrower than its longest word wraps inside the word ("n/o/t/e/v/a/l"): measure
  // each word of each cell in the cell's own font and compare with the cell's content width.
  const canvas = document.createElement("canvas").getContext("2d");
  const narrow = [];
  for (const cell of document.querySelectorAll("td, th")) {
    const style = getComputedStyle(cell);
    if (style.wordBreak === "break-all") { continue; }  // hashes wrap on purpose
    canvas.font = `${style.fontWeight} ${style.fontSize} ${style.fontFamily}`;
    const inner = cell.clientWidth - parseFloat(style.paddingLeft)
      - parseFloat(style.paddingRight);
    for (const word of cell.textContent.split(/\\s+/)) {
      if (word && canvas.measureText(word).width > inner + 1) { narrow.push(word); break; }
    }
  }
  document.body.setAttribute("data-narrow", narrow.slice(0, 20).join(" | "));
  document.body.setAttribute("data-probed", "yes");
});
</script>"""


class _Images(html.parser.HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.images: list[dict[str, str | None]] = []
        self.probed = False
        self.scroll_width = -1
        self.narrow = ""

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        if tag == "img":
            self.images.append(attributes)
        if tag == "body" and attributes.get("data-probed") == "yes":
            self.probed = True
            self.scroll_width = int(attributes["data-scroll-width"])
            self.narrow = attributes.get("data-narrow") or ""


def images_of(page: Path) -> list[dict[str, str | None]]:
    parser = _Images()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser.images


def load_in_chromium(page: Path, tmp_path: Path) -> _Images:
    probe = page.with_name("_probe.html")
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", _PROBE + "</body>"),
                     encoding="utf-8")
    profile = tmp_path / "chromium-profile"
    result = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", f"--user-data-dir={profile}", "--virtual-time-budget=10000",
         f"--window-size={WINDOW_WIDTH},900",
         "--dump-dom", probe.as_uri()],
        capture_output=True, text=True, timeout=120, check=True,
    )
    probe.unlink()
    parser = _Images()
    parser.feed(result.stdout)
    return parser


def check_page(page: Path, tmp_path: Path) -> list[dict[str, str | None]]:
    """Every <img> is a file beside the page, and Chromium loads every one of them."""
    text = page.read_text(encoding="utf-8")
    assert not re.search(r"""(src|href)=["']?(https?:)?//""", text), "external resource"
    images = images_of(page)
    assert images
    for image in images:
        assert (page.parent / image["src"]).is_file(), image["src"]
    dom = load_in_chromium(page, tmp_path)
    assert dom.probed, "the page did not finish loading in Chromium"
    assert len(dom.images) == len(images)
    assert [i["src"] for i in dom.images if i.get("data-loaded") != "yes"] == []
    assert 0 < dom.scroll_width <= WINDOW_WIDTH, "the page scrolls sideways"
    assert dom.narrow == "", f"table cells narrower than their longest word: {dom.narrow}"
    return images


@pytest.fixture(scope="module")
def tiny_plan(tmp_path_factory):
    """The baseline trial and one backlash trial, simulated."""
    from funcnet.sim import Trial, write_plan

    out = tmp_path_factory.mktemp("plan")
    write_plan([Trial("main-v35-p16-s3", "main", speed=35, tcp=1.6, step=3),
                Trial("backlash-v175-p16-s1", "backlash", speed=175, tcp=1.6, step=1,
                      reverse=True)], out)
    return out


@pytest.fixture(scope="module")
def demo_report(tiny_plan, tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    calls = []
    page = build_demo_report(tiny_plan, out, progress=lambda *a: calls.append(a),
                             max_phase_length=0.5, timeline_width=0.6, timeline_step=1.5)
    return page, calls


def test_demo_report_figures_load_in_chromium(demo_report, tmp_path):
    page, calls = demo_report
    assert page.name == "index.html" and calls
    sources = [i["src"] for i in check_page(page, tmp_path)]
    for name in ("fig1-embedding-network", "fig2-isrn", "fig5-pair-network",
                 "fig9-baseline-phases", "fig10-velocity-grid", "fig11-reversal",
                 "edge-timeline", "recurrence-cruise"):
        assert f"figures/{name}.png" in sources
    assert not list(page.parent.rglob("*.tmp")), "a temporary file was left behind"


def test_demo_report_findings_tables_and_provenance(demo_report, tiny_plan):
    page, _ = demo_report
    text = page.read_text(encoding="utf-8")
    tables = pd.read_html(page, keep_default_na=False)
    findings = next(t for t in tables if "reproduced" in t.columns)
    assert set(findings["reproduced"]) <= {"yes", "partly", "no", "not evaluable", "n/a"}
    assert {"4.1-early-rp-drives", "4.2-edges-thin", "4.3-sequence", "3.1-tcp",
            "3.1-step"} <= set(findings["finding"])
    # a plain statement for every finding not fully reproduced
    plain = html.unescape(re.sub(r"<[^>]+>", "", text))
    for row in findings.itertuples(index=False):
        verdict = {"no": "does not reproduce this", "partly": "reproduces this only in part",
                   "not evaluable": "cannot test this: nothing could be measured"}
        if row.reproduced in verdict:
            assert re.search(re.escape(row.finding) + r" — the paper: “[^”]*” The simulation "
                             + verdict[row.reproduced] + " " + re.escape(f"({row.evidence})"),
                             plain)
    # the summary counts each verdict as the table shows it
    counts = findings["reproduced"].value_counts()
    assert (f"reproduces {counts.get('yes', 0)} fully, {counts.get('partly', 0)} partly, "
            f"{counts.get('no', 0)} not at all, {counts.get('not evaluable', 0)} not evaluable"
            ) in plain
    # V1, V175 and V350 are not in this plan: said, not hidden, and never a full "yes"
    by_id = findings.set_index("finding")
    rc_ac = by_id.loc["4.2-rc-ac-everywhere"]
    assert "9 of 12 claims could not be evaluated" in rc_ac["evidence"]
    # one entry per reason, counted, not the same reason nine times
    assert "no network ×9: [V1 · spin-up] RC<->AC" in rc_ac["evidence"]
    assert rc_ac["evidence"].count("no network") == 1
    assert rc_ac["reproduced"] != "yes"
    # thinning needs two speeds: with V35 alone nothing is measured
    assert by_id.loc["4.2-edges-thin", "reproduced"] == "not evaluable"
    assert '<td class="ne">not evaluable</td>' in text
    # provenance: versions and the SHA-256 of every input
    import hashlib

    import numba
    import numpy

    assert numpy.__version__ in text and numba.__version__ in text
    for trace in [*tiny_plan.glob("*.xml"), tiny_plan / "manifest.csv"]:
        assert hashlib.sha256(trace.read_bytes()).hexdigest() in text
    # coupling evidence per finding with claimed relations; "untestable" is said, never hidden
    assert "coupling evidence" in findings.columns
    coupling = by_id["coupling evidence"]
    pattern = re.compile(r"coupled in (\d+)/(\d+) claimed relations")
    for finding_id in ("4.1-early-rp-drives", "4.3-v-drives", "4.3-sequence"):
        assert pattern.match(coupling[finding_id]), coupling[finding_id]
    assert coupling["3.1-tcp"] == "—" and coupling["4.2-edges-thin"] == "—"
    # the reversal windows (0.2 s = 100 samples) hold a few shifts only: untestable
    assert re.search(r"untestable in \d+ \(≤ \d+ surrogates\)", coupling["4.3-v-drives"])
    assert "Untestable</i> is not <i>uncoupled" in text
    # every computed network has its pairs table (15 pairs of 6 signals, or fewer if dropped)
    pair_tables = [t for t in tables if {"x", "y", "kind", "c_diff", "t_diff"} <= set(t.columns)]
    assert len(pair_tables) >= 10
    assert all(set(t["kind"]) <= {"x->y", "y->x", "bidirectional", "conflict"}
               for t in pair_tables)


@pytest.fixture(scope="module")
def tiny_study(tiny_plan, tmp_path_factory):
    from funcnet.study import load_study, run_study

    out = tmp_path_factory.mktemp("study")
    toml = out / "study.toml"
    trace = (tiny_plan / "main-v35-p16-s3.xml").as_posix()
    toml.write_text(f'[recordings]\npaths = ["{trace}"]\n'
                    '[[windows]]\nkind = "sliding"\nwidth = 0.6\nstep = 1.0\nstart = 0.5\n'
                    'stop = 4.2\n', encoding="utf-8")
    run_study(load_study(toml), out / "results", workers=1)
    return out / "results"


def test_study_report_networks_timeline_and_chromium(tiny_study, tmp_path):
    from funcnet.study import load_results

    page = write_report(tiny_study, tmp_path / "report")
    rows = load_results(tiny_study)
    sources = [i["src"] for i in check_page(page, tmp_path)]
    assert any(s.endswith("-timeline.png") for s in sources)
    assert any("-networks-" in s for s in sources)
    tables = pd.read_html(page, keep_default_na=False)
    pair_tables = [t for t in tables if {"x", "y", "kind"} <= set(t.columns)]
    assert len(pair_tables) == rows.groupby(["window", "start"]).ngroups
    assert sum(len(t) for t in pair_tables) == len(rows)
    # the set-point check first, counted over every row: into RP is the arrow toward it
    text = page.read_text(encoding="utf-8")
    assert text.index('id="setpoint-check"') < text.index('id="summary"')
    plain = rows[~rows["degenerate"].astype(bool)]
    into = int((((plain["y"] == "RP") & (plain["kind"] == "x->y"))
                | ((plain["x"] == "RP") & (plain["kind"] == "y->x"))).sum())
    out = int((((plain["x"] == "RP") & (plain["kind"] == "x->y"))
               | ((plain["y"] == "RP") & (plain["kind"] == "y->x"))).sum())
    times = {0: "0 times", 1: "once"}
    assert (f"arrows point into the set-point {times.get(into, f'{into} times')} and out of "
            f"it {times.get(out, f'{out} times')}") in text.replace("&#x27;", "'")


def test_study_report_shows_the_run_record_and_the_provenance_once(tiny_study, tmp_path):
    page = write_report(tiny_study, tmp_path / "report")
    document = json.loads((tiny_study / "study.json").read_text())
    study = page.read_text(encoding="utf-8").split('<section id="study">', 1)[1]
    tables = pd.read_html(io.StringIO(study), keep_default_na=False)
    # the study's own run record under "run": its counts as study.json has them
    run = next(t for t in tables if list(t.columns) == ["run", "value"])
    record = dict(zip(run["run"], run["value"].astype(str), strict=True))
    assert record == {k: str(v) for k, v in document["run"].items()
                      if k not in ("failures", "warnings")}
    # the provenance once, under "item", with the study's command and the report's
    items = [t for t in tables if list(t.columns) == ["item", "value"]]
    assert len(items) == 1
    names = set(items[0]["item"])
    assert {"report date (UTC)", "report command", "study command"} <= names
    assert not names & set(record)


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_study_report_shows_the_evidence(tiny_plan, tmp_path):
    from funcnet.report.study_report import evidence_counts
    from funcnet.study import load_results, load_study, run_study

    trace = (tiny_plan / "main-v35-p16-s3.xml").as_posix()
    toml = tmp_path / "study.toml"
    toml.write_text(f'[recordings]\npaths = ["{trace}"]\n'
                    '[[windows]]\nkind = "sliding"\nwidth = 0.6\nstep = 1.0\nstart = 0.5\n'
                    'stop = 2.2\n[evidence]\nenabled = true\nresamples = 0\nalpha = 0.1\n',
                    encoding="utf-8")
    run_study(load_study(toml), tmp_path / "results", workers=0)
    rows = load_results(tmp_path / "results")
    page = write_report(tmp_path / "results", tmp_path / "report")
    text = page.read_text(encoding="utf-8")
    assert "Coupling evidence" in text and "α = 0.1" in text and "Dotted, pale" in text
    tables = pd.read_html(page, keep_default_na=False)
    (counts,) = [t for t in tables if "untestable" in t.columns]
    expected = evidence_counts(rows, 0.1)
    assert counts["pairs"].tolist() == expected["pairs"].tolist()
    assert counts["coupled"].sum() == rows["evidence"].isin(["coupled", "coupled-directed"]).sum()
    assert counts["asymmetry-only"].sum() == (rows["evidence"] == "asymmetry-only").sum()
    pair_tables = [t for t in tables if {"x", "y", "kind"} <= set(t.columns)]
    assert pair_tables and all({"coupling_p", "evidence"} <= set(t.columns) for t in pair_tables)


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_run_paper_analyses_windows_networks_and_findings(tiny_plan):
    import numpy as np

    from funcnet.paper import PAPER_PARAMETERS, run_paper_analyses
    from funcnet.pipeline import window_networks
    from funcnet.robot import add_derived_signals, read_trace

    analyses = run_paper_analyses(tiny_plan, max_phase_length=0.5, timeline_step=2.0)
    base = analyses.baseline
    assert base.trial == "main-v35-p16-s3"
    assert set(base.networks) <= {"early spin-up", "late spin-up", "cruise", "braking"}
    assert "cruise" in base.networks
    for window in base.windows.values():
        assert window.stop - window.start <= 0.5 + 1e-9
    # V35 is the baseline trial in fixed windows; V1, V175, V350 are not in this plan
    assert list(analyses.velocity) == ["V35"]
    assert analyses.velocity["V35"] is analyses.main["main-v35-p16-s3"]
    assert set(analyses.velocity["V35"].windows) == {"spin-up", "cruise", "braking"}
    (reversal,) = analyses.reversal.values()
    assert list(reversal.windows) == [-40, -20, 0, 20, 40]
    widths = {round(w.stop - w.start, 9) for w in reversal.windows.values()}
    assert widths == {0.2}
    assert reversal.windows[40].start - reversal.windows[0].start == pytest.approx(0.04)
    # the networks are funcnet.window_networks' own, on the same windows and parameters
    assert analyses.parameters == PAPER_PARAMETERS
    recording = add_derived_signals(read_trace(reversal.path), ["V"])
    (expected,) = window_networks(recording, [reversal.windows[0]],
                                  parameters=PAPER_PARAMETERS).values()
    assert reversal.networks[0] == expected
    # a signal constant in a window is left out of that network, and only then
    for trial in (base, *analyses.main.values(), reversal):
        for key, net in trial.networks.items():
            window = trial.windows[key]
            part = trial.data[(trial.data.index >= window.start)
                              & (trial.data.index < window.stop)]
            constant = {c for c in part if np.ptp(part[c].to_numpy()) == 0}
            assert set(trial.dropped.get(key, ())) == constant
            if net is not None:
                assert set(net.nodes) == set(part.columns) - constant
    ids = [f.id for f in analyses.findings]
    assert len(ids) == len(set(ids)) == 8 + 8 + 3 + 2
    assert {f.reproduced for f in analyses.findings if f.section == "3.1"} == {"n/a"}
    assert set(analyses.inputs) == {"manifest.csv", *(p.name for p in tiny_plan.glob("*.xml"))}


def test_write_report_without_results_names_the_folder(tmp_path):
    from funcnet.errors import StudyError

    with pytest.raises(StudyError, match=re.escape(str(tmp_path))):
        write_report(tmp_path)
    assert not (tmp_path / "report").exists()


def test_run_paper_analyses_takes_network_parameters(tiny_plan):
    from funcnet.errors import ParameterError
    from funcnet.paper import run_paper_analyses
    from funcnet.parameters import NetworkParameters

    # a bad value or an unknown name is refused before anything is read
    with pytest.raises(ParameterError, match="^rr must be in"):
        run_paper_analyses(tiny_plan / "nowhere", rr=2.0)
    with pytest.raises(ParameterError, match="radius"):
        run_paper_analyses(tiny_plan / "nowhere", parameters=NetworkParameters(), radius=1)


def test_report_shows_the_schemas_pairs_columns(demo_report):
    from funcnet.network.schema import PAIR_COLUMNS

    page, _ = demo_report
    tables = pd.read_html(page, keep_default_na=False)
    pair_tables = [t for t in tables if {"x", "y", "kind", "c_diff"} <= set(t.columns)]
    assert pair_tables
    # the degenerate flag and reason too; direction_reason (a sentence per pair) stays in files
    shown = [c for c in PAIR_COLUMNS if c != "direction_reason"]
    for t in pair_tables:
        assert list(t.columns) == shown


def test_report_package_keeps_its_names():
    import funcnet.report
    from funcnet.report import save_figure  # noqa: F401

    assert {"write_report", "save_figure", "write_backlash_page"} <= set(funcnet.report.__all__)
    # the paper's demo report is the bench's, not the library's
    assert "build_demo_report" not in funcnet.report.__all__
