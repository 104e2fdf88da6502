"""The repetitions of an inspection (funcnet.inspection.repeated) and `funcnet inspect --repeated`:
several traces of one motion read together, one trace with too few repetitions."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet.inspection.repeated import inspect_repetitions
from funcnet.robot.recording import Recording, SignalInfo
from funcnet.sim import Trial, simulate_trial

SIGNALS = ["RP", "AP", "MP", "RC", "AC"]


def _runs(n: int) -> list[pd.DataFrame]:
    trial = Trial("repeat", "repetitions", speed=350, tcp=1.2, step=3.0, sensors="real")
    return [simulate_trial(trial, seed=s).data[SIGNALS].iloc[::2] for s in range(n)]


def _recording(data: pd.DataFrame) -> Recording:
    return Recording(data, {}, {c: SignalInfo(c, None, None, 0.004) for c in data.columns},
                     sample_period=0.004)


def test_simulated_runs_read_together_per_phase() -> None:
    found = inspect_repetitions([_recording(d) for d in _runs(5)], SIGNALS)
    assert len(found.moves) == 5
    assert found.message.startswith("5 repetitions of the motion (0 other move(s) left out)")
    assert "a decision needs 4 for one pair, 6 for the 10 pairs of 5 nodes" in found.message
    assert set(found.evidence) | set(found.failures) == {"early spin-up", "late spin-up",
                                                         "cruise", "braking"}
    for table in found.evidence.values():
        assert len(table) == 10 and (table.repetitions == 5).all()
        # The set-point is the same in every run: nothing beyond the command.
        assert (table[table.x == "RP"].coupling_p == 1.0).all()


def test_one_move_says_how_many_repetitions_a_decision_needs() -> None:
    found = inspect_repetitions([_recording(_runs(1)[0])], ["RP", "AP", "AC", "Q"])
    assert found.evidence == {} and len(found.moves) == 1
    assert found.message == ("one repetition of the motion: a decision needs 4 for one pair, "
                             "5 for the 3 pairs of 3 nodes")


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_inspect_command_repeated_on_several_traces(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from funcnet.cli import app

    paths = []
    for k, data in enumerate(_runs(4)):
        path = tmp_path / f"run{k}.csv"
        data.reset_index().to_csv(path, index=False)
        paths.append(str(path))
    result = CliRunner().invoke(app, ["inspect", *paths, "--repeated", "--no-evidence", "-q",
                                      "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.stderr
    assert f"repetitions: {tmp_path / 'out' / 'repeated.html'}" in result.stdout
    text = (tmp_path / "out" / "repeated.html").read_text()
    assert "4 repetitions of the motion" in text and "<h2>braking</h2>" in text
    assert "repeated.html" in (tmp_path / "out" / "index.html").read_text()
    np.testing.assert_equal(text.count("R=4 repetitions (every permutation)"), text.count("<h2>"))
