"""The simulated axis: its physics checked against the model's own parameters and closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from funcnet.errors import ParameterError
from funcnet.sim.axis import (
    MAX_TRIAL_DURATION,
    AxisParameters,
    setpoint_profile,
    simulate_trial,
    trial_duration,
)
from funcnet.sim.plan import paper_plan
from funcnet.sim.trial import Trial
from funcnet.sim.writer import write_trace

P = AxisParameters()
RAD = math.pi / 180.0


def _trial(speed, tcp, step, reverse=False, **knobs):
    name = f"t-v{speed:g}-p{tcp * 10:g}-s{step:g}{'-r' if reverse else ''}"
    return Trial(name, "test", speed, tcp, step, reverse, **knobs)


@pytest.fixture(scope="module")
def baseline():
    """The paper's baseline: 35 deg/min, 3 deg, TCP 1.6 m."""
    return simulate_trial(_trial(35, 1.6, 3))


@pytest.fixture(scope="module")
def fast_moves():
    """350 deg/min, 10 deg at the three TCP distances."""
    return {tcp: simulate_trial(_trial(350, tcp, 10)) for tcp in (1.2, 1.6, 2.0)}


# --- set-point generator -------------------------------------------------------------------


@pytest.mark.parametrize(("step", "speed"), [(3.0, 35.0), (10.0, 350.0), (1.0, 350.0), (-2.0, 1.0)])
def test_setpoint_reaches_step_with_jerk_limited_ramps(step, speed):
    dt = 1e-4
    t = np.arange(0.0, abs(step) / speed * 60 + 3.0, dt)
    pos, vel, timing = setpoint_profile(t, step, speed, False, P)
    assert pos[-1] == pytest.approx(step, abs=1e-12)
    assert pos[t < P.lead_time] == pytest.approx(0.0)
    # velocity is the derivative of position; peak = programmed speed unless the step is short
    np.testing.assert_allclose(np.gradient(pos, dt)[1:-1], vel[1:-1], atol=1e-6)
    ramps = (P.acceleration_time + P.deceleration_time) / 2
    peak = min(speed / 60, abs(step) / ramps)
    assert np.abs(vel).max() == pytest.approx(peak, rel=1e-9)
    assert timing["motion_end"] - timing["motion_start"] == pytest.approx(abs(step) / peak + ramps)
    # jerk-limited: acceleration continuous, jerk bounded by a_max / (jerk_fraction * T_dec)
    acc = np.diff(vel) / dt
    a_max = peak / (P.deceleration_time * (1 - P.jerk_fraction))
    assert np.abs(np.diff(acc)).max() <= 1.01 * a_max / (P.jerk_fraction * P.deceleration_time) * dt


def test_setpoint_forward_then_reverse_returns_to_start():
    t = np.arange(0.0, 8.0, 1e-3)
    pos, vel, timing = setpoint_profile(t, 1.0, 35.0, True, P)
    assert pos.max() == pytest.approx(1.0)
    assert pos[-1] == pytest.approx(0.0, abs=1e-12)
    assert timing["reverse_start"] == pytest.approx(timing["forward_end"] + P.dwell_time)
    assert vel.min() == pytest.approx(-35.0 / 60)


# --- control and mechanics -----------------------------------------------------------------


@pytest.mark.parametrize(("speed", "step"), [(35, 3), (175, 10)])
def test_cruise_following_error_settles_to_the_closed_form(speed, step):
    sim = simulate_trial(_trial(speed, 1.6, step))
    start = sim.truth["motion_start"] + P.acceleration_time + 0.9
    stop = sim.truth["motion_end"] - P.deceleration_time - 0.05
    cruise = sim.data.loc[start:stop]
    following = cruise["RP"] - cruise["AP"]
    # PI speed loop: motor speed = command = N (ffw v + Kv e)  =>  e = (1 - ffw) v / Kv
    expected = (1 - P.velocity_feedforward) * speed / 60 / P.position_gain
    assert following.mean() == pytest.approx(expected, rel=0.02)
    assert following.std() < 0.02 * expected


def _measured_lost_motion(data):
    """Motor travel while the arm rests at its forward extreme (from logged MP and AP only)."""
    ap, torsion = data["AP"].to_numpy(), (data["MP"] - data["AP"]).to_numpy()
    first = last = int(np.argmax(ap))
    while ap[first - 1] == ap[first]:
        first -= 1
    while ap[last + 1] == ap[last]:
        last += 1
    return torsion[first : last + 1].max() - torsion[last], data["MP"].iloc[first : last + 1]


@pytest.mark.parametrize("trial", [t for t in paper_plan() if t.reverse], ids=lambda t: t.name)
def test_reversal_lost_motion_from_logs_matches_truth(trial):
    sim = simulate_trial(trial)
    truth = sim.truth
    measured, mp_at_rest = _measured_lost_motion(sim.data)
    # MP moves through the backlash while AP stands still ...
    assert mp_at_rest.max() - mp_at_rest.min() > P.backlash
    # ... and the lost motion seen in the logs is the model's within 5 %
    assert measured == pytest.approx(truth["lost_motion"], rel=0.05)
    # the truth is the dead zone plus wind-up on both flanks, each below static friction / k
    assert truth["lost_motion"] == pytest.approx(
        P.backlash + truth["windup_forward"] + truth["windup_reverse"], rel=1e-12
    )
    most = P.backlash + 2 * P.arm_static / P.gear_stiffness / RAD
    assert P.backlash < truth["lost_motion"] < most
    assert truth["reversal_time"] < truth["restart_time"] < truth["motion_end"]


def test_backlash_knob_changes_lost_motion_by_its_width():
    wide = simulate_trial(_trial(35, 1.6, 1, True, backlash=0.06)).truth["lost_motion"]
    narrow = simulate_trial(_trial(35, 1.6, 1, True, backlash=0.02)).truth["lost_motion"]
    assert wide - narrow == pytest.approx(0.04, rel=0.05)


def _breakaway_current(sim):
    """RC (5-sample mean) at the last log sample before the arm leaves static friction."""
    current = sim.data["RC"].rolling(5, center=True, min_periods=1).mean()
    return current.loc[: sim.truth["breakaway_time"]].iloc[-1]


def test_friction_knob_delays_breakaway_and_raises_its_current():
    healthy, worn = (simulate_trial(_trial(1, 1.6, 1, friction_scale=f)) for f in (1.0, 1.5))
    # every friction coefficient grows by 1.5: the torque ramps longer before the arm breaks away
    assert worn.truth["breakaway_time"] > healthy.truth["breakaway_time"] + 0.02
    for sim in (healthy, worn):
        # the motor creeps at N * 1 deg/min = 0.04 rad/s, far below its Stribeck velocity, so it
        # still sees its static friction: current = (F_s,arm / N + F_s,motor) / k_t, both scaled
        scale = sim.params.friction_scale
        needed = scale * (P.arm_static / P.gear_ratio + P.motor_static) / P.torque_constant
        assert _breakaway_current(sim) == pytest.approx(needed, rel=0.03)
    assert _breakaway_current(worn) / _breakaway_current(healthy) == pytest.approx(1.5, rel=0.03)


def test_stiffness_knob_scales_the_torsion_during_acceleration(fast_moves):
    soft = simulate_trial(_trial(350, 1.6, 10, stiffness_scale=0.5))
    ramp = slice(P.lead_time + P.jerk_fraction, P.lead_time + 1 - P.jerk_fraction)
    windup = {}
    for scale, sim in ((1.0, fast_moves[1.6]), (0.5, soft)):
        data = sim.data.loc[ramp]
        windup[scale] = (data["MP"] - data["AP"]).mean() - P.backlash / 2
        # compliance per transmitted N m is the softened gear's, 1 / (scale k) ...
        torque = sim.states["gear_torque"].loc[ramp].mean()
        assert windup[scale] / torque == pytest.approx(
            1 / (scale * P.gear_stiffness * RAD), rel=0.03
        )
    # ... and the torque to accelerate the arm (J_a a + friction) does not depend on k, so the
    # wind-up doubles; 10 %: the softer gear's lower mode rings more and shifts the mean torque
    assert windup[0.5] / windup[1.0] == pytest.approx(2.0, rel=0.1)


def test_static_friction_current_rises_before_the_arm_moves():
    sim = simulate_trial(_trial(1, 1.6, 1))
    data, truth = sim.data, sim.truth
    moved = np.flatnonzero(data["AP"].to_numpy() != data["AP"].iloc[0])
    t_arm = data.index[moved[0]]
    # the arm leaves static friction, then the encoder sees it within a few ms
    assert truth["breakaway_time"] <= t_arm < truth["breakaway_time"] + 0.02
    assert t_arm - truth["motion_start"] > 0.5
    current = data["RC"].rolling(5, center=True, min_periods=1).mean()
    before = current.loc[: t_arm - 0.002]
    assert abs(current.loc[truth["motion_start"]]) < 0.05
    # the torque reaches the arm's static friction (plus the motor's sliding friction) first
    needed = (P.arm_static / P.gear_ratio + P.motor_coulomb) / P.torque_constant
    assert before.iloc[-1] > 0.95 * needed
    assert before.loc[: truth["motion_start"] + 0.3].max() < 0.6 * needed


def test_torsion_follows_transmitted_torque(fast_moves):
    sim = fast_moves[1.6]
    torsion = (sim.data["MP"] - sim.data["AP"]).to_numpy()
    torque = sim.states["gear_torque"].to_numpy()
    contact = torque > 20.0
    design = np.column_stack([torque[contact], np.ones(contact.sum())])
    (slope, intercept), *_ = np.linalg.lstsq(design, torsion[contact], rcond=None)
    assert slope == pytest.approx(1 / P.gear_stiffness / RAD, rel=0.03)  # deg per N m
    assert intercept == pytest.approx(P.backlash / 2, rel=0.03)
    # and the torque the logged current implies moves with the torsion
    moving = (sim.data.index > 0.4) & (sim.data.index < sim.truth["motion_end"] - 0.8)
    assert np.corrcoef(torsion[moving], sim.data["RC"].to_numpy()[moving])[0, 1] > 0.9


def test_larger_tcp_needs_more_current_to_accelerate(fast_moves):
    peaks = []
    speed = 350 / 60 * RAD
    a_max = speed / (P.acceleration_time * (1 - P.jerk_fraction))
    for tcp, sim in fast_moves.items():
        current = sim.data["RC"]
        peaks.append(current.rolling(5, center=True).mean().abs().max())
        t0 = P.lead_time
        accelerating = current.loc[t0 + P.jerk_fraction : t0 + 1 - P.jerk_fraction].mean()
        cruising = current.loc[t0 + 1.3 : sim.truth["motion_end"] - P.deceleration_time].mean()
        inertia = P.arm_inertia(tcp) + P.gear_ratio**2 * P.motor_inertia
        viscous = P.arm_viscous + P.motor_viscous * P.gear_ratio**2  # joint side, at half speed
        expected = (inertia * a_max - viscous * speed / 2) / (P.gear_ratio * P.torque_constant)
        assert accelerating - cruising == pytest.approx(expected, rel=0.1)
    assert peaks[0] < peaks[1] < peaks[2]


def test_actual_current_tracks_reference_far_below_one_log_period(fast_moves):
    data = fast_moves[1.6].data.loc[0.1:3.0]
    rc, ac = data["RC"].to_numpy(), data["AC"].to_numpy()
    slope = np.gradient(rc, P.log_period)
    delay = -np.sum((ac - rc) * slope) / np.sum(slope**2)  # AC(t) ~ RC(t - delay)
    assert 0 < delay < 0.25e-3
    assert np.std(ac - rc) < 3 * P.current_noise


# --- sensors and limits --------------------------------------------------------------------


@pytest.mark.parametrize("name", ["baseline", "fast"])
def test_both_encoders_log_on_their_own_grid(name, baseline, fast_moves):
    data = {"baseline": baseline, "fast": fast_moves[2.0]}[name].data
    arm_count = 360 / P.arm_encoder_counts  # deg, joint side
    motor_count = 360 / P.motor_encoder_counts / P.gear_ratio  # a motor count seen at the joint
    for role, count in (("AP", arm_count), ("MP", motor_count)):
        counts = data[role].to_numpy() / count
        np.testing.assert_allclose(counts, np.round(counts), rtol=0, atol=1e-6, err_msg=role)
        # ... and not on a coarser grid: somewhere the signal moves by a single count
        assert np.diff(np.unique(np.round(counts))).min() == 1, role


def _longest_run(mask):
    """Length of the longest stretch of True in a boolean array."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
    return int(np.max(edges[1::2] - edges[::2], initial=0))


def test_current_limit_saturates_a_demanding_move(fast_moves):
    healthy = fast_moves[2.0]  # 350 deg/min, 10 deg, TCP 2.0 m
    peak = healthy.data["RC"].abs().max()
    assert peak < 0.5 * P.current_limit  # the default limit never binds ...
    limit = 1.5  # ... a limit well below the move's peak does: accelerating needs about 1.6 A
    assert limit < 0.6 * peak
    sim = simulate_trial(healthy.trial, P.replace(current_limit=limit))
    rc = sim.data["RC"].to_numpy()
    assert np.abs(rc).max() <= limit
    at_limit = np.abs(rc) == limit
    assert _longest_run(at_limit) * P.log_period > 0.5  # saturated for a stretch of the ramp
    first = sim.data.index[np.argmax(at_limit)]
    assert P.lead_time < first < P.lead_time + P.acceleration_time
    # the arm falls behind while the current is capped, then catches up and settles
    lag = (sim.data["RP"] - sim.data["AP"]).abs().max()
    assert lag > 3 * (healthy.data["RP"] - healthy.data["AP"]).abs().max()
    assert sim.data["AP"].iloc[-1] == pytest.approx(healthy.trial.step, abs=2e-4)


def test_baseline_has_the_phase_timing_of_fig9(baseline):
    rp = baseline.data["RP"]
    speed = np.gradient(rp.to_numpy(), P.log_period)
    time = rp.index.to_numpy()
    cruise = 35 / 60
    moving = time[speed > 0.01 * cruise]
    at_speed = time[speed > 0.98 * cruise]
    assert moving[0] < 0.3  # spin-up starts in the first few hundred ms ...
    assert 0.9 < at_speed[0] < 1.3  # ... and reaches cruise after about 1 s
    assert 5.0 < at_speed[-1] < 5.6  # braking after about 5 s
    assert 0.5 < moving[-1] - at_speed[-1] < 0.8  # lasting about 0.7 s
    arm_speed = np.gradient(baseline.data["AP"].to_numpy(), P.log_period)
    assert time[arm_speed > 0.01 * cruise][0] < 0.5
    assert baseline.truth["breakaway_time"] < 0.5


def test_same_seed_same_bytes_other_seed_other_noise(tmp_path):
    trial = _trial(350, 1.2, 1)
    paths = [tmp_path / f"{name}.xml" for name in "abc"]
    for path, seed in zip(paths, (7, 7, 8), strict=True):
        write_trace(path, simulate_trial(trial, seed=seed).data)
    assert paths[0].read_bytes() == paths[1].read_bytes()
    assert paths[0].read_bytes() != paths[2].read_bytes()


def test_fault_knobs_of_the_trial_override_the_axis():
    sim = simulate_trial(
        _trial(35, 1.6, 1, backlash=0.05, friction_scale=2.0), AxisParameters(stiffness_scale=0.5)
    )
    assert (sim.params.backlash, sim.params.friction_scale, sim.params.stiffness_scale) == (
        0.05,
        2.0,
        0.5,
    )
    assert sim.truth["backlash"] == 0.05


@pytest.mark.parametrize(
    "changes",
    [
        {"gear_ratio": 0.0},
        {"backlash": -0.1},
        {"arm_static": 100.0},
        {"speed_loop_rate": 7000.0},
        {"jerk_fraction": 0.6},
        {"motor_inertia": math.nan},
    ],
)
def test_axis_parameters_reject_values_out_of_range(changes):
    with pytest.raises(ParameterError):
        AxisParameters(**changes)
    with pytest.raises(ParameterError, match="no field"):
        P.replace(gear_rate=3)


@pytest.mark.parametrize(
    ("speed", "step", "reverse"), [(35, 3, False), (1, 1, True), (350, 1, False)]
)
def test_trial_duration_is_lead_motion_and_settling(speed, step, reverse):
    # Closed form: a move lasts |step| / peak + (T_acc + T_dec) / 2, the peak limited by the step.
    ramps = (P.acceleration_time + P.deceleration_time) / 2
    move = step / min(speed / 60, step / ramps) + ramps
    moves = 2 * move + P.dwell_time if reverse else move
    expected = P.lead_time + moves + P.settle_time
    assert trial_duration(_trial(speed, 1.6, step, reverse)) == pytest.approx(expected, rel=1e-12)


def test_an_overlong_trial_is_refused_before_any_allocation():
    import tracemalloc

    # 1 deg at 0.001 deg/min: 60 000 s of motion, about 40 GB of loop arrays.
    slow = Trial("too-slow", "test", speed=0.001, tcp=1.6, step=1)
    tracemalloc.start()
    try:
        with pytest.raises(ParameterError, match=r"too-slow.*6e\+04 s.*3600 s"):
            simulate_trial(slow)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2**20
    # The limit applies to the whole trace: at 60 deg/min (1 deg/s) the longest step fits
    # the lead, the 0.85 s the ramps add, and the settling in MAX_TRIAL_DURATION.
    longest = MAX_TRIAL_DURATION - P.lead_time - P.settle_time - 0.85
    assert trial_duration(_trial(60, 1.6, longest - 1e-6)) <= MAX_TRIAL_DURATION
    with pytest.raises(ParameterError, match="MAX_TRIAL_DURATION"):
        trial_duration(_trial(60, 1.6, longest + 1e-3))
