"""Physics of the simulator's new parts, each against its own parameters."""

from __future__ import annotations

import math

import numpy as np
import pytest

from funcnet.errors import ParameterError
from funcnet.robot import read_trace
from funcnet.sim.axis import (
    AxisParameters,
    _drift,
    effective_parameters,
    real_axis_parameters,
    simulate_trial,
)
from funcnet.sim.trial import Trial
from funcnet.sim.writer import write_trace


def _trial(**kw: object) -> Trial:
    base = dict(name="t", group="g", speed=175, tcp=1.6, step=1, reverse=True, seed=1)
    base.update(kw)
    return Trial(**base)  # type: ignore[arg-type]


def test_ipo_logging_holds_positions_for_two_ticks_and_the_writer_says_4_ms(tmp_path):
    sim = simulate_trial(_trial(sensors="real"))
    for name in ("AP", "MP"):
        values = sim.data[name].to_numpy()
        changed = np.flatnonzero(np.diff(values)) + 1
        assert changed.size > 50
        assert np.all(changed % 2 == 0)  # only on the 4 ms grid
    for name in ("RC", "AC"):
        assert np.any((np.flatnonzero(np.diff(sim.data[name].to_numpy())) + 1) % 2 == 1)
    path = write_trace(tmp_path / "t.xml", sim.data, intervals={"AP": 0.004, "MP": 0.004})
    rec = read_trace(path)
    assert rec.signals["AP"].interval == 0.004 and rec.signals["RC"].interval == 0.002
    assert np.allclose(rec.data["AP"], sim.data["AP"].round(6), atol=1e-9)


def test_position_log_period_must_be_a_multiple_of_the_log_period():
    with pytest.raises(ParameterError, match="position_log_period"):
        AxisParameters(position_log_period=0.003)


def test_paper_sensors_are_the_defaults_and_real_sensors_the_trace_figures():
    assert effective_parameters(_trial()) == AxisParameters()
    real = effective_parameters(_trial(sensors="real"))
    assert real.position_log_period == 0.004 and real.arm_encoder_counts == 2**22
    assert 360 / real.arm_encoder_counts == pytest.approx(8.58e-5, rel=1e-3)
    assert real_axis_parameters().current_noise == 0.013


def test_drift_has_its_std_and_corner():
    rng = np.random.default_rng(0)
    dt, sigma, corner = 1 / 2000, 0.05, 2.0
    x = _drift(rng, 400_000, sigma, corner, dt)
    assert np.std(x) == pytest.approx(sigma, rel=0.1)
    lag = round(0.01 / dt)
    expected = math.exp(-2 * math.pi * corner * 0.01)
    assert np.corrcoef(x[:-lag], x[lag:])[0, 1] == pytest.approx(expected, abs=0.03)


def test_noise_scale_scales_the_current_sensor_noise():
    def scatter(scale: float) -> float:
        sim = simulate_trial(_trial(noise_scale=scale, reverse=False))
        ac = sim.data["AC"].to_numpy()[-500:]  # 1 s at rest at the target
        return float(np.std(np.diff(ac)))

    assert scatter(4.0) / scatter(1.0) == pytest.approx(4.0, rel=0.25)
    assert scatter(0.0) < scatter(1.0)


def test_elastic_arm_tip_rings_at_its_link_mode_after_the_move():
    p = AxisParameters(arm_model="elastic")
    sim = simulate_trial(_trial(arm_model="elastic", reverse=False, speed=350))
    tip = sim.states["tip_velocity"].to_numpy()
    hub = sim.states["arm_velocity"].to_numpy()
    t = sim.states.index.to_numpy()
    end = sim.truth["motion_end"]
    after = (t > end + 0.3) & (t < end + 1.3)  # the hub has settled, the tip rings on
    assert np.abs(tip[after]).max() > 5 * np.abs(hub[after]).max()
    j_tip = p.arm_tcp_mass * 1.6**2
    spectrum = np.abs(np.fft.rfft(tip[after] - tip[after].mean()))
    freqs = np.fft.rfftfreq(after.sum(), d=p.log_period)
    expected = math.sqrt(p.link_stiffness / j_tip) / (2 * math.pi)
    assert freqs[np.argmax(spectrum)] == pytest.approx(expected, rel=0.2)
    rigid = simulate_trial(_trial(reverse=False, speed=350))
    assert np.allclose(rigid.states["tip_velocity"], rigid.states["arm_velocity"])


def test_position_loop_on_the_motor_encoder_leaves_the_arm_off_by_the_torsion():
    motor = simulate_trial(_trial(position_feedback="motor", reverse=False, backlash=2 / 60))
    arm = simulate_trial(_trial(reverse=False, backlash=2 / 60))
    count = 360 / AxisParameters().arm_encoder_counts
    assert abs(arm.data["AP"].iloc[-1] - 1.0) < 50 * count
    assert abs(motor.data["MP"].iloc[-1] - 1.0) < 1e-4
    # the arm rests somewhere in the dead zone: off by up to half of it plus the wind-up
    assert abs(motor.data["AP"].iloc[-1] - 1.0) > 50 * count
    assert abs(motor.data["AP"].iloc[-1] - 1.0) < 2 / 60


def test_cogging_ripple_has_its_period_in_the_motor_angle():
    p = AxisParameters(cogging_torque=2.0, current_noise=0.0)
    trial = _trial(reverse=False, speed=175, step=10)
    sim = simulate_trial(trial, p)
    t = sim.data.index.to_numpy()
    cruise = (t > 1.5) & (t < 3.0)
    rc = sim.data["RC"].to_numpy()[cruise]
    spectrum = np.abs(np.fft.rfft(rc - rc.mean()))
    freqs = np.fft.rfftfreq(rc.size, d=p.log_period)
    motor_turns = 175 / 60 * p.gear_ratio / 360  # per s
    assert freqs[np.argmax(spectrum)] == pytest.approx(p.cogging_periods * motor_turns, rel=0.05)
    plain = simulate_trial(trial, AxisParameters(current_noise=0.0)).data["RC"].to_numpy()[cruise]
    assert np.std(rc) > 3 * np.std(plain)


def test_trial_options_are_checked():
    with pytest.raises(ParameterError, match="arm_model"):
        _trial(arm_model="floppy")
    with pytest.raises(ParameterError, match="seed"):
        _trial(seed=-1)
