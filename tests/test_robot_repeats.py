"""Repetitions of one motion (funcnet.robot.repeats): the real SINUMERIK trace's moves, several
recordings given together, simulated seeds; alignment on the set-point; bad input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet import repetition_evidence
from funcnet.errors import ParameterError, SignalError
from funcnet.robot import find_repetitions, read_recording
from funcnet.robot.recording import Recording, SignalInfo
from funcnet.sim import Trial, simulate_trial


def _recording(data: pd.DataFrame, period: float, t0: float = 0.0) -> Recording:
    data = data.copy()
    data.index = pd.Index(np.round(t0 + np.arange(len(data)) * period, 9), name="time")
    return Recording(data, {}, {c: SignalInfo(c, None, None, period) for c in data.columns},
                     sample_period=period)


def _move(n: int, first: int, travel: float, width: int) -> np.ndarray:
    """A smooth move of ``travel`` starting at sample ``first``, ``width`` samples long."""
    u = np.clip((np.arange(n) - first) / width, 0, 1)
    return travel * (u - np.sin(2 * np.pi * u) / (2 * np.pi))


@pytest.fixture(scope="module")
def real(real_trace: Path) -> Recording:
    return read_recording(real_trace, resample="decimate")


def test_real_trace_moves_one_and_three_repeat(real: Recording) -> None:
    found = find_repetitions(real, signals=["RP", "AP", "MP", "AC"])
    assert found.moves.move.tolist() == [1, 3]
    assert not found.moves.mirrored.any() and found.others == 1
    assert list(found.windows) == ["early spin-up", "late spin-up", "cruise", "braking"]
    for windows in found.windows.values():
        assert len(windows) == 2 and len(windows[0]) == len(windows[1])
        # Aligned on the set-point: the two set-points are the same numbers.
        assert np.abs(windows[0].RP.to_numpy() - windows[1].RP.to_numpy()).max() < 1e-6
        assert np.abs(windows[0].AP.to_numpy() - windows[1].AP.to_numpy()).max() < 0.05
    # The move starts where the phases say, 34.5 s apart.
    assert found.moves.start.diff().iloc[1] == pytest.approx(34.504, abs=0.004)


def test_real_trace_mirrored_move_two(real: Recording) -> None:
    found = find_repetitions(real, signals=["RP", "AP", "AC"], mirror=True)
    assert found.moves.move.tolist() == [1, 2, 3]
    assert found.moves.mirrored.tolist() == [False, True, False]
    assert found.moves.direction.tolist() == [1, -1, 1]
    cruise = found.windows["cruise"]
    # Mirrored: travelling forward again, the current of the same sign.
    assert cruise[1].RP.iloc[-1] > cruise[1].RP.iloc[0]
    assert np.sign(cruise[1].AC.mean()) == np.sign(cruise[0].AC.mean())
    # Three repetitions cannot decide: every pair untestable, and the reason says why.
    table = repetition_evidence(cruise)
    assert (table.evidence == "untestable").all()
    assert table.evidence_reason.str.contains("smallest p 0.167").all()


def test_several_recordings_aligned_and_another_profile_left_out() -> None:
    n = 400
    runs = []
    for first, t0 in ((50, 0.0), (80, 3.0), (65, -1.0)):
        rp = _move(n, first, 10.0, 200)
        noise = np.random.default_rng(first).standard_normal(n) * 0.01
        runs.append(_recording(pd.DataFrame({"RP": rp, "AP": rp + noise}), 0.01, t0))
    other = _recording(pd.DataFrame({"RP": _move(n, 50, 4.0, 100), "AP": _move(n, 50, 4.0, 100)}),
                       0.01)
    found = find_repetitions([runs[0], other, runs[1], runs[2]])
    assert found.moves.recording.tolist() == [0, 2, 3] and found.others == 1
    np.testing.assert_allclose(found.moves.start, [0.5, 3.8, -0.35], atol=0.011)
    for windows in found.windows.values():
        for window in windows[1:]:
            np.testing.assert_allclose(window.RP.to_numpy(), windows[0].RP.to_numpy(), atol=1e-9)


def test_alignment_refined_by_the_set_point() -> None:
    # A creep before the move makes the second recording's move start early; the
    # cross-correlation of the set-point velocities puts it back.
    n = 400
    first = _move(n, 50, 10.0, 200)
    second = _move(n, 50, 10.0, 200)
    second[40:50] += np.linspace(0.0, 1e-3, 10)  # leaves standstill 10 samples early
    second[50:] += 1e-3
    found = find_repetitions([_recording(pd.DataFrame({"RP": first}), 0.01),
                              _recording(pd.DataFrame({"RP": second}), 0.01)],
                             tolerance=0.05, max_lag=0.2)
    lags = found.moves.lag.tolist()
    assert lags[0] == 0.0 and lags[1] != 0.0
    cruise = found.windows["cruise"]
    assert np.abs(cruise[0].RP.to_numpy() - cruise[1].RP.to_numpy()).max() < 2e-3


def test_simulated_seeds_are_repetitions() -> None:
    trial = Trial("repeat", "repetitions", speed=350, tcp=1.2, step=3.0, sensors="real")
    recordings = [_recording(simulate_trial(trial, seed=s).data.iloc[::2], 0.004)
                  for s in range(4)]
    found = find_repetitions(recordings)
    assert len(found) == 4 and found.moves.lag.eq(0).all()
    window = found.windows["braking"]
    assert {len(w) for w in window} == {len(window[0])}
    assert all((w.RP.to_numpy() == window[0].RP.to_numpy()).all() for w in window)
    # The current differs between seeds (its own noise).
    assert not np.array_equal(window[0].AC.to_numpy(), window[1].AC.to_numpy())
    table = repetition_evidence(window, signals=["AP", "MP", "RC", "AC"])
    assert len(table) == 6 and (table.repetitions == 4).all()


def test_bad_input_named() -> None:
    rp = _move(300, 50, 5.0, 100)
    a = _recording(pd.DataFrame({"RP": rp}), 0.01)
    b = _recording(pd.DataFrame({"RP": rp}), 0.02)
    with pytest.raises(ParameterError, match="one sample period"):
        find_repetitions([a, b])
    with pytest.raises(SignalError, match="no signal.*AP"):
        find_repetitions([a], signals=["RP", "AP"])
    still = _recording(pd.DataFrame({"RP": np.zeros(300)}), 0.01)
    with pytest.raises(SignalError, match="no move"):
        find_repetitions(still)
    with pytest.raises(ParameterError, match="tolerance"):
        find_repetitions(a, tolerance=0)
    with pytest.raises(ParameterError, match="no recording"):
        find_repetitions([])
