"""The simulator in continuous motion: a gravity load on the arm, smooth multi-turn set-points."""

from __future__ import annotations

import math

import numpy as np
import pytest

from funcnet.diagnosis import find_direction_changes
from funcnet.diagnosis.reversals import motor_side_recording
from funcnet.errors import ParameterError
from funcnet.sim import Trial, continuous_sweep_plan, simulate_trial
from funcnet.sim.axis import AxisParameters, setpoint_profile
from funcnet.validation.sweep import simulated_recording, trial_indicators


def _smooth(backlash_arcmin: float, load: float | None, speed: float = 175) -> Trial:
    return Trial(f"s-{backlash_arcmin}-{load}", "s", speed=speed, tcp=1.6, step=1,
                 profile="smooth", backlash=backlash_arcmin / 60, arm_load=load,
                 sensors="real", seed=1)  # fmt: skip


def test_the_smooth_set_point_turns_three_times_without_a_rest_at_its_speed():
    p = AxisParameters()
    t = np.arange(0, 4, 1e-4)
    pos, vel, timing = setpoint_profile(t, 1.0, 175.0, False, p, "smooth")
    assert abs(np.abs(vel).max() * 60 - 175) < 0.01  # peaks at the programmed speed
    assert np.allclose(np.gradient(pos, t), vel, atol=1e-3)  # the velocity is the position's
    moving = np.abs(vel) > 1e-9
    inside = (t > timing["motion_start"]) & (t < timing["motion_end"])
    assert moving[inside][1:-1].all()  # never rests between start and end
    signs = np.sign(vel[np.abs(vel) > 0.5 * np.abs(vel).max()])
    assert int(np.sum(np.diff(signs) != 0)) == 3
    assert pos[0] == 0 and abs(pos[-1]) < 1e-12 and vel[-1] == 0


def test_the_diagnosis_finds_the_three_continuous_turns_of_a_smooth_trial():
    sim = simulate_trial(_smooth(2, None))
    changes = find_direction_changes(motor_side_recording(simulated_recording(sim)))
    assert [c.kind for c in changes] == ["continuous"] * 3


def test_a_gravity_load_keeps_the_gear_torque_on_one_flank_and_the_truth_follows():
    free = simulate_trial(_smooth(2, None))
    loaded = simulate_trial(_smooth(2, 1000.0))
    # without a load the gear torque changes sign with the motion; with it, never
    torque = free.states["gear_torque"]
    assert torque.min() < -100 and torque.max() > 100
    assert loaded.states["gear_torque"].min() > 100
    # the truth, from the noise-free states: the dead zone where the gear changes flank, about
    # nothing where the load keeps it on one (a tenth of the 2 arcmin)
    assert free.truth["lost_motion"] * 60 == pytest.approx(2.0, rel=0.05)
    assert abs(loaded.truth["lost_motion"] * 60) < 0.2
    # the axis starts at rest under the load: the arm does not sag before the motion
    before = loaded.data.loc[: loaded.truth["motion_start"]]
    assert np.ptp(before["AP"]) < 1e-4


def test_the_new_fields_are_opt_in():
    assert Trial("a", "g", speed=35, tcp=1.6, step=1).profile is None
    assert AxisParameters().arm_load == 0
    with pytest.raises(ParameterError, match="profile"):
        Trial("a", "g", speed=35, tcp=1.6, step=1, profile="wavy")
    with pytest.raises(ParameterError, match="arm_load"):
        Trial("a", "g", speed=35, tcp=1.6, step=1, arm_load=-1.0)


def test_the_continuous_sweep_plan_and_its_rows():
    plan = continuous_sweep_plan()
    assert len(plan) == 6 * 2 * 2 * 3 * 3 and all(t.profile == "smooth" for t in plan)
    row = trial_indicators(_smooth(2, None), networks=False)
    assert row["profile"] == "smooth" and math.isfinite(row["lost_motion"])
    assert row["true_lost_motion"] * 60 == pytest.approx(2.0, rel=0.05)


@pytest.mark.parametrize(
    ("backlash_arcmin", "load"), [(0, None), (1, None), (4, None), (2, 1000.0)]
)
def test_the_truth_is_what_the_encoders_show_with_the_gear_torque_known_and_not_with_the_current(
    backlash_arcmin, load
):
    # docs/validation/backlash.md 5.1: the step of logged MP - AP less the true gear torque's
    # wind-up, at the diagnosis's own turns and windows, is the truth to two arm-encoder steps; the
    # motor current in the gear torque's place (the simulator's exact constants) misses it by the
    # motor's own inertia and friction, which flip with the turn too
    sim = simulate_trial(_smooth(backlash_arcmin, load))
    p = sim.params
    rec = motor_side_recording(simulated_recording(sim))
    turns = [c for c in find_direction_changes(rec) if c.kind == "continuous"]
    assert len(turns) == 3
    t = rec.data.index.to_numpy()
    d = (rec.data["MP"] - rec.data["AP"]).to_numpy()
    tau = sim.states["gear_torque"].reindex(rec.data.index, method="nearest").to_numpy()
    stiffness = p.gear_stiffness * math.pi / 180  # N m per deg

    def mean_step(rest: np.ndarray) -> float:
        steps = []
        for c in turns:
            before = (t >= c.stop - 0.25) & (t < c.stop)
            after = (t >= c.start) & (t < c.start + 0.25)
            steps.append(-c.direction * (rest[before].mean() - rest[after].mean()))
        return float(np.mean(steps))

    encoder_step = 360 / p.arm_encoder_counts
    truth = sim.truth["lost_motion"]
    assert abs(mean_step(d - tau / stiffness) - truth) <= 2 * encoder_step
    current = rec.data["AC"].to_numpy()
    by_current = mean_step(d - p.gear_ratio * p.torque_constant * current / stiffness)
    assert by_current - truth < -0.1 / 60  # the motor's own torque: -0.2 arcmin and more
