"""A lost motion the data cannot resolve: never negative, a bound with the reason, and an interval
that says which error terms it carries (the noise, the motor friction's bias)."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from funcnet.diagnosis import diagnose_recording, find_direction_changes, write_results
from funcnet.diagnosis.diagnose import resolved_lost_motion
from funcnet.diagnosis.reversal_error import fit_gear, reversal_error
from funcnet.robot import Recording, SignalInfo

COMPLIANCE = 0.001  # deg per N m


def _gear_with_motor_friction(lost: float, friction: float, seed: int = 0) -> Recording:
    """A smooth motion turning twice; the motor torque is the gear's plus the motor's own
    friction ``friction * sign(VM)`` (N m), which never reaches the gear; the arm lags by the
    gear's wind-up, the encoders' 3 ms and ``lost / 2`` per direction."""
    t = np.arange(0, 8, 0.004)
    mp = 20 * np.sin(2 * np.pi * t / 8 + 0.3)
    vm = np.gradient(mp, t)
    gear = 3 * np.sin(2 * np.pi * t / 8) + 2.0
    switch = np.tanh(vm / 0.3)
    rng = np.random.default_rng(seed)
    ap = mp - (COMPLIANCE * gear + 0.003 * vm + lost / 2 * switch
               + 0.0002 * rng.standard_normal(t.size))  # fmt: skip
    motor = gear + friction * switch
    data = pd.DataFrame({"RP": mp, "MP": mp, "AP": ap, "AC": motor},
                        index=pd.Index(t, name="time"))  # fmt: skip
    info = {c: SignalInfo(c, "posn", None, 0.004) for c in data}
    return Recording(data, {}, info, source="synthetic.csv", sample_period=0.004)


def _walk(value, key=""):
    """Every (key, number) of a JSON document, nested."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _walk(v, k)
    elif isinstance(value, list):
        for v in value:
            yield from _walk(v, key)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield key, value


def test_the_motor_friction_biases_the_estimate_low_and_the_interval_carries_it():
    lost, friction = 0.01, 4.0  # deg, N m: the bias 2 c F = 0.008 deg
    rec = _gear_with_motor_friction(lost, friction)
    gear = fit_gear(rec)
    for change in find_direction_changes(rec):
        error = reversal_error(rec, change, gear, resamples=100)
        # closed form: the wind-up taken from the motor torque over-counts 2 c F at a turn,
        # less what the fitted compliance absorbs; the estimate falls short of the truth
        assert error.lost_motion < lost
        assert error.bias == pytest.approx(2 * gear.compliance * friction, rel=0.25)
        assert error.low <= lost <= error.high
        assert error.high == pytest.approx(error.lost_motion + error.noise + error.bias)
        assert error.terms == ("noise", "motor friction bias")


def test_an_unresolved_lost_motion_is_none_with_its_bound_never_negative(tmp_path):
    rec = _gear_with_motor_friction(0.0, 4.0)  # no lost motion: the estimate is negative
    raw = [reversal_error(rec, c, fit_gear(rec))
           for c in find_direction_changes(rec)]
    assert all(e.lost_motion < 0 for e in raw)
    result = diagnose_recording(rec)
    assert result.lost_motion is None and result.lost_motion_spread is None
    # the axis's interval: the means of its changes' interval ends, then bounded at 0
    high = float(np.mean([e.high for e in raw]))
    assert result.lost_motion_low == 0.0 and result.lost_motion_high == pytest.approx(high)
    assert result.lost_motion_reason == (
        f"below what this estimate resolves: <= {high * 60:.2g} arcmin")
    assert result.lost_motion_terms == ("noise", "motor friction bias")
    for r, e in zip(result.reversals, raw, strict=True):
        assert r.lost_motion is None and r.lost_motion_low == 0.0
        assert r.lost_motion_high == pytest.approx(e.high)
        assert r.lost_motion_reason.startswith("below what this estimate resolves: <= ")
    document = json.loads(write_results([result], tmp_path / "r.json").read_text())
    entry = document["traces"][0]
    assert entry["lost_motion"] is None and entry["lost_motion_high"] > 0
    assert {"lost_motion_low", "lost_motion_high", "lost_motion_terms"} <= set(entry)
    assert all(v >= 0 for k, v in _walk(document) if k.startswith("lost_motion"))


def test_a_resolved_lost_motion_keeps_its_value():
    rec = _gear_with_motor_friction(0.03, 1.0)
    result = diagnose_recording(rec)
    assert result.lost_motion is not None and result.lost_motion_reason is None
    assert 0 < result.lost_motion_low <= result.lost_motion <= result.lost_motion_high
    values = [r.lost_motion for r in result.reversals]
    assert result.lost_motion == pytest.approx(np.mean(values))


@pytest.mark.parametrize(("lost", "low", "high", "expected"), [
    (0.02, 0.01, 0.03, (0.02, 0.01, 0.03, None)),
    (-0.001, -0.002, 0.004, (None, 0.0, 0.004, "<= 0.24 arcmin")),
    (-0.004, -0.005, -0.003, (None, 0.0, 0.002, "<= 0.12 arcmin")),  # all below 0: its width
    (None, None, None, (None, None, None, None)),
])
def test_resolved_lost_motion_cases(lost, low, high, expected):
    got = resolved_lost_motion(lost, low, high)
    assert got[:2] == expected[:2]
    assert (got[2] is None and expected[2] is None) or math.isclose(got[2], expected[2])
    assert (got[3] is None) is (expected[3] is None)
    if expected[3] is not None:
        assert got[3] == f"below what this estimate resolves: {expected[3]}"
