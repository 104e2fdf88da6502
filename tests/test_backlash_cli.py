"""`funcnet backlash` (the SHELL owner's command) on the real trace: a result, exit 0 (issue 11)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from funcnet.cli import app

REAL = (
    Path(__file__).resolve().parents[2]
    / "shared"
    / "data"
    / "sinumerik"
    / "axis7-braking-trace.xml"
)

runner = CliRunner()


def test_the_real_trace_is_a_result_not_an_error(tmp_path):
    out = tmp_path / "result.json"
    result = runner.invoke(app, ["backlash", str(REAL), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "no reversal" in result.output and "lost_motion" in result.output
    traces = json.loads(out.read_text())["traces"]
    assert traces[0]["path"] == str(REAL) and traces[0]["backlash_score"] is None


@pytest.mark.parametrize("args", [["nope.xml"], ["{real}", "-o", "r.txt"]])
def test_bad_input_is_one_line_and_exit_2(tmp_path, args):
    args = [a.replace("{real}", str(REAL)) for a in args]
    result = runner.invoke(app, ["backlash", *args])
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "error" in result.output
