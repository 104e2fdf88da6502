"""The axis's gear-arm parameters from the arm's first start from rest.

:func:`funcnet.diagnosis.two_encoder.first_start` fits the resonance and the friction's Stribeck
drop where the arm starts from a long rest; the two-encoder lost motion at a reversal then fits
only the restart's instant. Checked against the simulator's own parameters and truth.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from funcnet.diagnosis.reversals import find_direction_changes, motor_side_recording
from funcnet.diagnosis.two_encoder import ArmStart, first_start, lost_motion
from funcnet.robot import Recording, SignalInfo, read_trace
from funcnet.sim.axis import AxisParameters, SimulatedTrial, simulate_trial
from funcnet.sim.plan import backlash_sweep_plan
from funcnet.sim.trial import Trial
from funcnet.validation.sweep import simulated_recording

STEP = 360 / 2**22  # the arm encoder's step with the real sensors, deg


def _recording(
    trial_name: str | None = None, **grid: tuple[float, ...]
) -> list[tuple[Trial, SimulatedTrial, Recording]]:
    plan = backlash_sweep_plan(**grid)  # type: ignore[arg-type]
    if trial_name is not None:
        plan = [t for t in plan if t.name == trial_name]
    out = []
    for trial in plan:
        assert trial.seed is not None
        sim = simulate_trial(trial, seed=trial.seed)
        out.append((trial, sim, motor_side_recording(simulated_recording(sim))))
    return out


def _resonance(trial: Trial, sim: SimulatedTrial) -> float:
    """The simulator's gear-arm resonance ``sqrt(k / J)``, rad/s."""
    p = sim.params
    return math.sqrt(p.gear_stiffness * p.stiffness_scale / AxisParameters().arm_inertia(trial.tcp))


def test_the_start_recovers_the_simulators_resonance_and_friction_drop() -> None:
    base = AxisParameters()
    ratios, drops = [], []
    for trial, sim, rec in _recording(backlash_arcmin=(0, 2), speeds=(35, 175), tcps=(1.2, 2.0),
                                      friction_scales=(1.0,), stiffness_scales=(0.7, 1.4),
                                      seeds=(1,), noise_scales=(1.0,)):  # fmt: skip
        start = first_start(rec)
        assert isinstance(start, ArmStart)
        p = sim.params
        inertia = base.arm_inertia(trial.tcp)
        ratios.append(start.omega / _resonance(trial, sim))
        drops.append(start.drop / ((p.arm_static - p.arm_coulomb) * p.friction_scale / inertia))
        # the start is the simulator's first breakaway, within a tick
        assert abs(start.time - sim.truth["breakaway_time"]) < 0.004
    off = np.abs(np.array(ratios) - 1)
    assert np.median(off) < 0.03 and off.max() < 0.15  # measured: median 1.3 %, max 11 %
    assert 0.5 < np.median(drops) < 1.5


def test_with_the_axis_parameters_a_former_miss_is_read_within_two_steps() -> None:
    # no backlash, 175 deg/min, 1.2 m, friction 1.4, stiffness 0.7, seed 2: 2.02 steps off with
    # the resonance and drop fitted at the reversal alone (80 rad/s, the true 74; at the start 75)
    name = "sweep-v175-p12-s1-b0-f1.4-k0.7-n1-r2"
    ((trial, sim, rec),) = _recording(name, backlash_arcmin=(0,), speeds=(175,), tcps=(1.2,),
                                      friction_scales=(1.4,), stiffness_scales=(0.7,),
                                      seeds=(2,), noise_scales=(1.0,))  # fmt: skip
    change = next(c for c in find_direction_changes(rec) if c.kind == "reversal")
    axis = first_start(rec)
    assert axis is not None
    steps = (lost_motion(rec, change, axis=axis) - sim.truth["lost_motion"]) / STEP
    assert abs(steps) < 2.0  # measured 1.21


def test_the_start_fitted_over_a_resonance_period_reads_a_former_motor_loop_miss() -> None:
    # position loop on the motor encoder, no backlash, 35 deg/min, 2.0 m, stiffness 0.7, seed 1:
    # the start fitted over 24 readings fell into a wrong minimum (42.5 rad/s, the true 49.3),
    # and the lost motion was 2.25 steps off; over 40 readings (160 ms, more than a period) the
    # resonance is pinned
    ((trial, sim, rec),) = _recording(backlash_arcmin=(0,), speeds=(35,), tcps=(2.0,),
                                      friction_scales=(1.0,), stiffness_scales=(0.7,), seeds=(1,),
                                      noise_scales=(1.0,), position_feedback="motor")  # fmt: skip
    omega = _resonance(trial, sim)
    axis = first_start(rec)
    assert axis is not None
    assert abs(axis.omega / omega - 1) < 0.05  # measured 1.3 %
    change = next(c for c in find_direction_changes(rec) if c.kind == "reversal")
    steps = (lost_motion(rec, change, axis=axis) - sim.truth["lost_motion"]) / STEP
    assert abs(steps) < 1.0  # measured 0.26


def test_a_start_the_rigid_model_does_not_fit_over_a_period_is_fitted_as_a_restart() -> None:
    # an arm whose gear opens again as it rings (backlash 4 arcmin, friction 0.7) leaves the
    # model over 160 ms: its fit's residual is far above the rounding, and the start is then
    # fitted over the reversal's span, near the true resonance
    from funcnet.diagnosis.two_encoder import _START_READINGS, _START_RESIDUAL, _fit_restart

    ((trial, sim, rec),) = _recording(backlash_arcmin=(4,), speeds=(175,), tcps=(1.6,),
                                      friction_scales=(0.7,), stiffness_scales=(1.4,), seeds=(1,),
                                      noise_scales=(1.0,))  # fmt: skip
    t = rec.data.index.to_numpy()
    mp, ap = rec.data["MP"].to_numpy(float), rec.data["AP"].to_numpy(float)
    rest = ap[0]
    assert np.all(ap[:25] == rest)  # the trial begins with a long rest: the start fitted
    first = int(np.flatnonzero(np.abs(ap - rest) > 1.5 * STEP)[0])
    new = 1 if ap[first] > rest else -1
    over_a_period = _fit_restart(t, mp, ap, rest, first, 0, new, STEP,
                                 max_readings=_START_READINGS, span=math.inf)  # fmt: skip
    assert over_a_period is not None
    _, omega_long, _, residual = over_a_period
    assert residual > _START_RESIDUAL  # measured 15.6 steps
    omega = _resonance(trial, sim)
    assert abs(omega_long / omega - 1) > 0.2  # measured -41 %
    axis = first_start(rec)
    assert axis is not None
    assert abs(axis.omega / omega - 1) < 0.05  # measured -2 %
    assert abs(axis.time - sim.truth["breakaway_time"]) < 0.004


def test_an_arm_without_a_long_rest_has_no_start(real_trace: Path) -> None:
    # the real arm's reading jitters by a step at standstill: no run of equal readings
    rec = motor_side_recording(read_trace(real_trace))
    assert first_start(rec) is None


def test_an_arm_moving_ahead_of_its_motor_is_no_start() -> None:
    t = np.arange(0.0, 0.5, 0.004)
    ap = np.round(np.clip(t - 0.3, 0, None) ** 2 * 50 / STEP) * STEP  # the arm moves on ...
    mp = np.full(t.size, 1.0)  # ... while the motor stands
    info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP")}
    rec = Recording(pd.DataFrame({"MP": mp, "AP": ap}, index=pd.Index(t, name="time")), {},
                    info, sample_period=0.004)  # fmt: skip
    assert first_start(rec) is None


@pytest.mark.parametrize("new", [1, -1])
def test_the_start_is_found_in_either_direction(new: int) -> None:
    # an independent start: the arm's model integrated by scipy (rigid arm on the gear's spring
    # and damper behind a motor at constant speed, friction falling from static to sliding, the
    # fit's assumed damping ratio and Stribeck velocity), read every 4 ms by a 2**22-count
    # encoder after a rest of 0.3 s
    from scipy.integrate import solve_ivp

    from funcnet.diagnosis.two_encoder import _STRIBECK_VELOCITY, _ZETA

    omega, drop, speed, t0 = 77.0, 0.1, math.radians(0.2), 0.3017  # w between the grids' points

    def arm(time: float, y: np.ndarray) -> list[float]:
        x, xd = y
        return [xd, omega**2 * (speed * time - x) - 2 * _ZETA * omega * xd
                + drop * (1 - np.exp(-((xd / _STRIBECK_VELOCITY) ** 2)))]  # fmt: skip

    t = np.arange(0.0, 0.6, 0.004)
    after = t[t > t0] - t0
    path = solve_ivp(arm, (0.0, after[-1]), [0.0, 0.0], t_eval=after, rtol=1e-10,
                     atol=1e-14).y[0]  # fmt: skip
    x = np.degrees(np.concatenate([np.zeros(t.size - after.size), path]))
    ap = new * np.round((0.3 * STEP + x) / STEP) * STEP  # the rest off the grid
    mp = new * (math.degrees(speed) * (t - t0) + 0.01)  # the motor leads by the wind-up
    info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP")}
    rec = Recording(pd.DataFrame({"MP": mp, "AP": ap}, index=pd.Index(t, name="time")), {},
                    info, sample_period=0.004)  # fmt: skip
    start = first_start(rec)
    assert start is not None
    assert abs(start.time - t0) < 1e-3  # measured 0.1 ms
    assert abs(start.omega / omega - 1) < 0.1  # measured 77.5, the grid's nearest
