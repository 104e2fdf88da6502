"""The two-encoder lost motion: the simulator's truth and the estimate, on fixed small sweeps.

The truth (``SimulatedTrial.truth["lost_motion"]``) is the change of the torsion
``theta_m / N - theta_a`` (MP - AP) from the motor's turning point to the arm's restart; these
tests check it against the simulator's own hidden states, then pin the estimate of
:func:`funcnet.diagnosis.indicators.lost_motion` against it (figures measured, docs/backlash.md).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from funcnet.diagnosis.sweep import run_sweep
from funcnet.robot.sim.axis import SimulatedTrial, simulate_trial
from funcnet.robot.sim.plan import ARCMIN, backlash_sweep_plan

STEP = 360 / 2**22  # the arm encoder's step with the real sensors, deg


def _one(**grid: tuple[float, ...]) -> SimulatedTrial:
    (trial,) = backlash_sweep_plan(**grid)  # type: ignore[arg-type]
    return simulate_trial(trial, seed=trial.seed)


def _at(frame: pd.Series, time: float) -> float:
    return float(np.interp(time, frame.index.to_numpy(), frame.to_numpy()))


def _ipo(sim: SimulatedTrial, name: str) -> pd.Series:
    """A logged position on its own 4 ms grid (the 2 ms log holds each sample for two ticks)."""
    return sim.data[name].iloc[::2]


def test_truth_is_the_motor_travel_when_the_arm_rests_across_the_reversal() -> None:
    sim = _one(backlash_arcmin=(2,), speeds=(35,), tcps=(1.2,), friction_scales=(0.7,),
               stiffness_scales=(1.0,), seeds=(1,), noise_scales=(1,))  # fmt: skip
    truth, states = sim.truth, sim.states
    rest = states.loc[truth["reversal_time"] + 0.004 : truth["restart_time"] - 0.004]
    assert (rest["arm_velocity"] == 0).all()  # the arm rests from the motor's turn on
    mp = _ipo(sim, "MP")
    travel = _at(mp, truth["reversal_time"]) - _at(mp, truth["restart_time"])
    assert truth["lost_motion"] == pytest.approx(travel, abs=3e-4)
    assert truth["lost_motion"] == pytest.approx(
        truth["backlash"] + truth["windup_forward"] + truth["windup_reverse"], rel=1e-12
    )
    assert truth["windup_forward"] > 0  # the arm rests on the forward flank at the turn


def test_truth_counts_what_the_arm_coasts_after_the_motor_has_turned() -> None:
    # a heavy arm on a soft gear: the arm-encoder loop overshoots, the motor turns before the
    # set-point does, and the arm coasts off the forward flank into the dead zone
    sim = _one(backlash_arcmin=(0.5,), speeds=(35,), tcps=(2.0,), friction_scales=(1.0,),
               stiffness_scales=(0.7,), seeds=(2,), noise_scales=(2,))  # fmt: skip
    truth, states = sim.truth, sim.states
    assert truth["windup_forward"] < 0  # the gear had left the forward flank at the turn
    ap = _ipo(sim, "AP")
    coast = _at(ap, truth["restart_time"]) - _at(ap, truth["reversal_time"])
    assert coast > 10 * STEP  # the arm still moved forward after the motor's turn
    torsion = states["torsion"]
    change = _at(torsion, truth["reversal_time"]) - _at(torsion, truth["restart_time"])
    assert truth["lost_motion"] == pytest.approx(change, abs=1e-4)  # MP - AP across the reversal
    assert truth["lost_motion"] > truth["backlash"] / 2


@pytest.fixture(scope="module")
def heavy_soft_sweep() -> pd.DataFrame:
    """The sweep's hardest corner for the estimate: TCP 2.0 m, friction and stiffness 0.7."""
    plan = backlash_sweep_plan(backlash_arcmin=(0, 0.5, 2, 4), tcps=(2.0,),
                               friction_scales=(0.7,), stiffness_scales=(0.7,), seeds=(1,),
                               noise_scales=(1.0,))  # fmt: skip
    return run_sweep(plan, networks=False)


def test_the_estimate_follows_the_truth_on_the_heavy_soft_corner(
    heavy_soft_sweep: pd.DataFrame,
) -> None:
    table = heavy_soft_sweep
    worn = table[table["backlash_arcmin"] > 0]
    error = worn["lost_motion"] / worn["true_lost_motion"] - 1
    assert error.abs().max() < 0.05  # measured 0.4-3.9 %
    new = table[table["backlash_arcmin"] == 0]
    steps = (new["lost_motion"] - new["true_lost_motion"]).abs() / STEP
    assert steps.max() < 2.5  # measured 1.4 and 2.0 arm-encoder steps


def test_the_estimate_grows_with_the_dead_zone(heavy_soft_sweep: pd.DataFrame) -> None:
    for _, part in heavy_soft_sweep.groupby("speed"):
        part = part.sort_values("backlash_arcmin")
        assert part["lost_motion"].is_monotonic_increasing
        widest = part.iloc[-1]
        # most of the 4 arcmin dead zone (the arm may run ahead into it while braking, before
        # the motor turns), plus wind-ups far below the zone itself
        assert 3 * ARCMIN < widest["lost_motion"] < 5 * ARCMIN
