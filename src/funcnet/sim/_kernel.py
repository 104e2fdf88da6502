"""The compiled kernel of the simulated axis (:mod:`funcnet.sim.axis`).

One Numba-compiled loop integrates the drivetrain and the control cascade at the current loop's
rate; the model, its units and its assumptions are described in :mod:`funcnet.sim.axis`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["axis_kernel"]


@numba.njit(cache=True)
def _friction_step(
    w: float,
    torque: float,
    inertia: float,
    dt: float,
    coulomb: float,
    static: float,
    viscous: float,
    stribeck: float,
) -> float:
    """New velocity of a body with Coulomb + viscous + Stribeck friction (Karnopp's stick)."""
    if w == 0.0:
        if abs(torque) <= static:
            return 0.0
        return dt / inertia * (torque - math.copysign(static, torque))
    sliding = coulomb + (static - coulomb) * math.exp(-((w / stribeck) ** 2))
    new = w + dt / inertia * (torque - math.copysign(sliding, w) - viscous * w)
    if new * w < 0.0:  # passed through zero within the step: stick, decided again next step
        return 0.0
    return new


# One compiled loop on purpose: split into calls, Numba would no longer keep the whole step
# in registers, and the step is the simulator's cost.
@numba.njit(cache=True)
def axis_kernel(
    sp_pos: np.ndarray,
    sp_vel: np.ndarray,
    noise: np.ndarray,
    dt: float,
    steps: tuple[int, int, int, int],
    mechanics: tuple[float, ...],
    friction: tuple[float, ...],
    control: tuple[float, ...],
    sensors: tuple[float, ...],
    extra: tuple[float, ...],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Integrate the axis at ``dt``; log RP, AP, MP, RC, AC and the hidden states.

    ``sp_pos``, ``sp_vel``: set-point (joint rad, rad/s) per speed-controller cycle; ``noise``:
    current-sensor noise (A) per step; the tuples are unpacked below (SI units, joint side
    except the motor's own quantities). ``extra`` holds the optional parts: the elastic arm's
    tip inertia, link stiffness and damping (a rigid arm when the stiffness is 0), whether the
    position loop reads the motor encoder (1.0) instead of the arm encoder (0.0), and the
    cogging ripple's amplitude (N m) and periods per motor turn, and a gravity load on the arm
    (N m, joint side; the axis starts at rest with the gear and the motor holding it). Returns
    the log, the states
    (gear torque, torsion, arm (hub) and motor velocity, tip velocity) and the truth events.
    """
    per_speed, per_log, n_start, n_reverse = steps
    ratio, j_m, j_a, k, c, half_b, kt, r, l_ind = mechanics
    m_coul, m_stat, m_visc, m_strib, a_coul, a_stat, a_visc, a_strib = friction
    i_max, kp_i, ki_i, kp_v, ki_v, kv, ffw = control
    q_m, q_a, q_i = sensors
    j_tip, k_link, c_link, motor_feedback, ripple, ripple_periods, load = extra
    elastic = k_link > 0.0
    th_t = w_t = 0.0
    n_steps = sp_pos.shape[0] * per_speed
    n_log = (n_steps + per_log - 1) // per_log
    log = np.empty((n_log, 5))
    states = np.empty((n_log, 5))
    events = np.full(6, np.nan)  # breakaway, reversal, restart, lost motion, windups fwd / rev
    th_m = w_m = th_a = w_a = cur = 0.0
    u_next = u_now = integ_i = integ_v = i_cmd = 0.0
    enc_m_prev = enc_m = enc_a = 0.0
    if load != 0.0:  # at rest under the load: the gear wound up on its flank, the motor holding
        th_m = ratio * (load / k + half_b)
        enc_m_prev = round(th_m / q_m) * q_m
        cur = i_cmd = integ_v = load / (ratio * kt)
        integ_i = u_next = u_now = r * cur
    decay = math.exp(-dt * r / l_ind)
    t_speed = dt * per_speed
    # the lost motion is the change of the torsion theta_m / N - theta_a (MP - AP) from the
    # motor's turning point (its last forward step) to the arm's restart: the motor's travel
    # when the arm rests there, plus what the arm still coasts (or bounces) forward in the dead
    # zone after the motor has turned (a heavy arm, a soft gear, the arm-encoder loop's overshoot)
    d_max = -np.inf
    t_d_max = np.nan
    for n in range(n_steps):
        if n % per_speed == 0:
            kk = n // per_speed
            enc_m = round(th_m / q_m) * q_m
            enc_a = round(th_a / q_a) * q_a
            fed_back = enc_m / ratio if motor_feedback > 0.0 else enc_a
            w_meas = (enc_m - enc_m_prev) / t_speed
            enc_m_prev = enc_m
            w_cmd = ratio * (ffw * sp_vel[kk] + kv * (sp_pos[kk] - fed_back))
            err_v = w_cmd - w_meas
            wanted = kp_v * err_v + integ_v
            i_cmd = min(max(wanted, -i_max), i_max)
            if wanted == i_cmd or wanted * err_v < 0.0:  # anti-windup: freeze when saturated
                integ_v += ki_v * t_speed * err_v
        i_meas = round((cur + noise[n]) / q_i) * q_i
        err_i = i_cmd - i_meas
        u_now = u_next  # one controller cycle of computation delay
        u_next = kp_i * err_i + integ_i
        integ_i += ki_i * dt * err_i
        delta = th_m / ratio - th_a
        if delta > half_b:
            tau = max(k * (delta - half_b) + c * (w_m / ratio - w_a), 0.0)
        elif delta < -half_b:
            tau = min(k * (delta + half_b) + c * (w_m / ratio - w_a), 0.0)
        else:
            tau = 0.0
        if n % per_log == 0:
            j = n // per_log
            log[j, 0] = sp_pos[n // per_speed]
            log[j, 1] = enc_a
            log[j, 2] = enc_m / ratio
            log[j, 3] = i_cmd
            log[j, 4] = i_meas
            states[j, 0] = tau
            states[j, 1] = delta
            states[j, 2] = w_a
            states[j, 3] = w_m / ratio
            states[j, 4] = w_t if elastic else w_a
        cur = cur * decay + (1.0 - decay) * (u_now - kt * w_m) / r
        drive = kt * cur - tau / ratio
        if ripple != 0.0:  # cogging: a torque periodic in the motor angle
            drive += ripple * math.sin(ripple_periods * th_m)
        w_m_new = _friction_step(w_m, drive, j_m, dt, m_coul, m_stat, m_visc, m_strib)
        if elastic:  # the arm's hub (on the gear, with the bearing's friction) and its tip
            link = k_link * (th_a - th_t) + c_link * (w_a - w_t)
            w_a_new = _friction_step(w_a, tau - link - load, j_a, dt, a_coul, a_stat, a_visc,
                                     a_strib)  # fmt: skip
            w_t += dt / j_tip * link
            th_t += w_t * dt
        else:
            w_a_new = _friction_step(w_a, tau - load, j_a, dt, a_coul, a_stat, a_visc, a_strib)
        if w_m > 0.0 and np.isnan(events[2]):  # still moving forward: not yet the turning point
            d_max, t_d_max = delta, n * dt
        if w_a == 0.0 and w_a_new != 0.0:
            if n >= n_start and np.isnan(events[0]):
                events[0] = (n + 1) * dt
            # the restart the lost motion ends at is the gear driving the arm back (tau < 0):
            # an elastic arm's hub can be dragged back by its ringing tip while the gear still
            # pushes forward, which crosses no dead zone (a rigid arm restarts back only so)
            if (n_reverse >= 0 and n >= n_reverse and w_a_new < 0.0 and tau < 0.0
                    and np.isnan(events[2])):  # fmt: skip
                events[1] = t_d_max
                events[2] = (n + 1) * dt
                events[3] = d_max - delta
                events[4] = d_max - half_b
                events[5] = -delta - half_b
        w_m, w_a = w_m_new, w_a_new
        th_m += w_m * dt
        th_a += w_a * dt
    return log, states, events
