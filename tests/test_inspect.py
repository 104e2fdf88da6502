"""The engineer's report of a trace: on the real SINUMERIK trace, once, end to end.

The trace lives outside the repository (its source has no licence file): ``../shared/data/
sinumerik/axis7-braking-trace.xml`` from the repository root. Without it the real-trace tests skip
(``real_trace`` in ``conftest.py``); the small tests run on a synthetic recording.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import REAL_TRACE
from test_report import check_page

ROOT = Path(__file__).resolve().parents[1]

_RUN = """
import sys
from funcnet.report.inspect import inspect_trace
print(inspect_trace(sys.argv[1], out_dir=sys.argv[2]))
"""


@pytest.fixture(scope="module")
def real_report(real_trace, tmp_path_factory):
    out = tmp_path_factory.mktemp("inspect")
    # Its time is measured in benchmarks/bench_inspect.py, not asserted here.
    result = subprocess.run(_inspect_command(real_trace, out), capture_output=True, text=True,
                            timeout=900, cwd=ROOT)
    return out, result


def _inspect_command(trace: Path, out: Path) -> list[str]:
    cli = Path(sys.executable).with_name("funcnet")
    help_text = subprocess.run([str(cli), "--help"], capture_output=True, text=True).stdout
    if re.search(r"\binspect\b", help_text):
        return [str(cli), "inspect", str(trace), "-o", str(out), "--quiet"]
    return [sys.executable, "-c", _RUN, str(trace), str(out)]


def test_inspect_real_trace_end_to_end(real_report, tmp_path):
    out, result = real_report
    assert result.returncode == 0, result.stderr
    page = out / "index.html"
    text = page.read_text(encoding="utf-8")
    images = check_page(page, tmp_path)  # relative, present, loaded; no narrow cell
    assert len(images) >= 4
    assert all(not Path(str(i["src"])).is_absolute() for i in images)
    assert all(i.get("alt") for i in images), "every figure has a caption"
    # the set-point check comes first, then the summary, the contents, the figures
    order = [text.index(s) for s in ('id="setpoint-check"', 'id="summary"', 'class="toc"',
                                     "<img")]
    assert order == sorted(order)
    assert "3 time(s)" in text  # three moves in the real trace
    assert "lost motion" in text and "arcsec" in text
    assert "Reading an arrow" in text
    assert "Here the rule&#x27;s arrows point into the set-point" in text
    assert "Here the direction reading points into the set-point" in text
    assert "Values are missing" not in text and "a gap" not in text  # the trace has none
    for label in ("early spin-up 1", "cruise 2", "braking 3"):
        assert label in text
    shown = text[:text.index('id="parameters"')]  # provenance records the command as typed
    assert str(REAL_TRACE.parent) not in shown, "absolute path of the trace in the page"


def test_real_trace_page_says_no_long_text_more_than_twice(real_report):
    # A reason several pairs share (the same Benjamini-Hochberg sentence in three windows) is
    # said once below the pairs tables, with the pairs it is for; the cells point to it.
    import html as html_module

    from funcnet.report.html import repeated_texts
    from test_inspect_robot import long_texts_said_more_than_twice

    out, result = real_report
    assert result.returncode == 0, result.stderr
    text = (out / "index.html").read_text(encoding="utf-8")
    assert not long_texts_said_more_than_twice(text)
    assert repeated_texts(text) == {}
    notes = re.findall(r'<ol class="notes">(.*?)</ol>', text, re.S)
    assert len(notes) == 1
    items = [html_module.unescape(re.sub(r"<[^>]+>", "", i))
             for i in re.findall(r"<li>(.*?)</li>", notes[0], re.S)]
    plain = html_module.unescape(re.sub(r"<[^>]+>", "", text))
    assert items
    for k, item in enumerate(items, start=1):  # said once, for several pairs, cited in cells
        reason, pairs = item.rsplit(" (", 1)
        assert len(reason) > 60 and plain.count(reason) == 1
        assert len(pairs.split(", ")) >= 2
        assert text.count(f"<td>note {k} below</td>") == len(pairs.split(", "))


def _synthetic():
    from funcnet.robot import Recording, SignalInfo

    t = np.arange(0, 4, 0.002)
    acc = np.interp(t, [0.5, 0.6, 0.9, 1.0, 2.0, 2.1, 2.4, 2.5], [0, 1, 1, 0, 0, -1, -1, 0])
    rp = np.cumsum(np.cumsum(acc) * 0.002) * 0.002 * 100
    rng = np.random.default_rng(0)
    ap = np.concatenate([[0.0] * 3, rp[:-3]])
    ac = np.gradient(np.gradient(ap)) * 1e4 + rng.normal(0, 0.05, t.size)
    data = pd.DataFrame({"RP": rp, "AP": ap, "AC": ac}, index=pd.Index(t.round(9), name="time"))
    info = {c: SignalInfo(c, "posn", "double", 0.002) for c in data}
    return Recording(data, {}, info, source="synthetic.csv", sample_period=0.002)


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_inspect_recording_summarizes_the_motion_without_evidence():
    from funcnet.inspection import inspect_recording

    calls = []
    ins = inspect_recording(_synthetic(), evidence=False, backlash=False,
                            progress=lambda *a: calls.append(a))
    assert list(ins.moves["move"]) == [1]
    assert ins.signals == ("RP", "AP", "V", "AC")
    assert set(ins.networks) == {w.label for w in ins.windows} - set(ins.failed("network"))
    assert {w.phase for w in ins.windows} <= {"early spin-up", "late spin-up", "cruise",
                                              "braking"}
    assert ins.moves["peak speed"].iloc[0] > 0 and ins.moves["peak |FE|"].iloc[0] > 0
    assert calls and calls[-1][0] == calls[-1][1]


def test_inspect_trace_needs_a_path_and_checks_parameters_first(tmp_path):
    from funcnet.errors import ParameterError
    from funcnet.report.inspect import inspect_trace

    with pytest.raises(ParameterError, match="rr"):
        inspect_trace(tmp_path / "missing.xml", out_dir=tmp_path, rr=2.0)


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_inspect_recording_takes_detrended_nodes():
    from funcnet.inspection import inspect_recording

    rec = _synthetic()
    ins = inspect_recording(rec, signals=["FE", "V", "AC"], evidence=False, backlash=False)
    assert ins.signals == ("FE", "V", "AC")
    # FE is derived (RP - AP), not read: the same values as the difference
    fe = ins.recording.data["FE"].to_numpy()
    assert np.allclose(fe, rec.data["RP"].to_numpy() - rec.data["AP"].to_numpy())
    assert ins.networks and all(set(n.nodes) <= {"FE", "V", "AC"}
                                for n in ins.networks.values())


def test_inspect_command_detrended_option(tmp_path):
    from typer.testing import CliRunner

    from funcnet.cli import app
    from funcnet.inspection import DETRENDED_NODES

    runner = CliRunner()
    assert "--detrended" in runner.invoke(app, ["inspect", "--help"]).stdout
    both = runner.invoke(app, ["inspect", str(tmp_path / "t.csv"), "--detrended", "--signals",
                               "RP,AP"])
    assert both.exit_code == 2 and "--signals or --detrended" in both.stderr
    assert len(both.stderr.splitlines()) == 1
    assert DETRENDED_NODES[:2] == ("FE", "TORSION")


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_inspect_takes_the_evidence_options_of_funcnet_network(tmp_path):
    from typer.testing import CliRunner

    from funcnet.cli import app
    from funcnet.inspection import inspect_recording

    ins = inspect_recording(_synthetic(), evidence=True, backlash=False,
                            evidence_options={"surrogates": 9, "resamples": 0, "seed": 2})
    assert ins.networks
    for net in ins.networks.values():
        assert net.evidence["surrogates"] == 9 and net.evidence["resamples"] == 0
        assert net.pairs["c_diff_low"].isna().all()  # no intervals asked
    bad = CliRunner().invoke(app, ["inspect", str(tmp_path / "t.csv"), "--alpha", "1.5"])
    assert bad.exit_code == 2 and len(bad.stderr.splitlines()) == 1 and "--alpha" in bad.stderr


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_a_phase_too_short_for_part_of_its_evidence_is_left_out_of_it_not_an_error(tmp_path):
    from funcnet.inspection import inspect_recording
    from funcnet.report.inspect import write_inspection

    # 9 surrogates cannot reach 0.05: every pair's intervals asked for all the same
    options = {"surrogates": 9, "resamples": 10, "intervals": "all"}
    # delay 10: the early spin-up's 46 samples give 26 states, enough for its network, but the
    # intervals' smaller subsamples keep one block of 6 states (an embedding needs 7)
    ins = inspect_recording(_synthetic(), backlash=False, evidence_options=options, delay=10)
    assert [(f.window, f.part) for f in ins.failures] == [("early spin-up", "intervals")]
    assert "got shape (6, 3)" in ins.failures[0].message
    short = ins.networks["early spin-up"]
    assert short.pairs["c_diff_low"].isna().all() and short.evidence["resamples"] == 0
    assert all(net.pairs["c_diff_low"].notna().all() for label, net in ins.networks.items()
               if label != "early spin-up")
    text = write_inspection(ins, tmp_path / "a").read_text(encoding="utf-8")
    assert "1 without part of them, too short for it" in text
    assert "without its intervals" in text and "got shape (6, 3)" in text
    # delay 20: 6 states, no network at all; the other windows keep theirs
    ins = inspect_recording(_synthetic(), backlash=False, evidence_options=options, delay=20)
    assert [(f.window, f.part) for f in ins.failures] == [("early spin-up", "network")]
    assert set(ins.networks) == {w.label for w in ins.windows} - {"early spin-up"}
    text = write_inspection(ins, tmp_path / "b").read_text(encoding="utf-8")
    assert "(1 could not be computed: see" in text and "why no network" in text
