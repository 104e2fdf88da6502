"""A simulated robot base axis: two-mass drivetrain with backlash, friction and a CNC cascade.

(Over 600 lines: about half is the model's documentation and the sourcing of each parameter.)

The paper's recordings (first axis of a large milling robot, SINUMERIK 840D sl, 500 Hz) cannot be
downloaded here, and nobody can check a diagnosis without ground truth. This module stands in for
the machine: it produces the five signals the paper records -- reference position RP, arm-side
(direct encoder) position AP, motor-encoder position MP, reference current RC and actual current
AC -- every 2 ms, for any trial of the design of experiments (:mod:`funcnet.sim.plan`),
together with the quantities a real trace never shows (gear torque, true lost motion, breakaway
time).

Model
-----
Mechanics (joint side angles in rad, motor angle on the motor shaft)::

    J_m dw_m/dt = k_t i - tau / N - F_m(w_m)          motor + gear input stage
    J_a dw_a/dt = tau - F_a(w_a)                      arm, J_a = J_0 + m_tcp r^2
    delta = theta_m / N - theta_a                     gear torsion (joint side)
    tau = k dz(delta) + c d(delta)/dt  if |delta| > b/2, else 0   (never pulls in contact)

with ``dz`` the dead zone of full width ``b`` (backlash) and ``F`` the Coulomb + viscous +
Stribeck friction ``sign(w) (F_c + (F_s - F_c) exp(-(w / w_s)^2)) + F_v w``. A body at rest
sticks while the torque on it stays within its static friction ``F_s`` (Karnopp's model, which
keeps a fixed step exact at zero velocity). The axis turns about the vertical: no gravity torque.

Control, as the cascade of a CNC axis:

- set-point generator (:func:`setpoint_profile`): jerk-limited step of a given size and speed,
  optionally forward then back; the ramps have a constant duration (see below);
- position loop on the arm-side (direct) encoder, gain ``position_gain`` (Kv) plus velocity
  feed-forward, evaluated every speed-controller cycle (fine interpolation of the set-point);
- speed PI loop on the differentiated motor encoder at ``speed_loop_rate``; its output is the
  current set-point RC, limited to ``+-current_limit``;
- current PI loop at ``current_loop_rate`` on the noisy, quantized current measurement, designed
  for ``current_bandwidth`` (zero on the winding's pole), one sample of computation delay, acting
  on a DC-equivalent q-axis winding ``L di/dt = u - R i - k_t w_m``.

Everything is integrated at the current loop's rate (16 kHz by default) by one Numba-compiled
kernel in :mod:`funcnet.sim._kernel` (semi-implicit Euler for the mechanics, the exact
exponential step for the winding).

Assumptions the docs must state
-------------------------------
- Ramp timing. A CNC would reach 35 deg/min in a few milliseconds; the paper's baseline (Fig. 9,
  35 deg/min, 3 deg, 1.6 m) spins up for about 1 s (early spin-up 0-220 ms) and brakes for about
  0.7 s. The set-point generator therefore uses ramps of *constant duration* -- 1.0 s to
  accelerate, 0.7 s to decelerate -- whatever the speed, with jerk phases of 22 % of each ramp
  (the acceleration has built up at 220 ms, the end of Fig. 9's early spin-up). A 3 deg step at
  35 deg/min then cruises from 1.0 s to 5.3 s after the start; a 10 deg step at 350 deg/min still
  has a 0.85 s cruise phase (paper, section 4.2). A step too short for both ramps at the requested
  speed (1 or 3 deg at 350 deg/min, 1 deg at 175 deg/min) keeps the ramp durations and lowers
  the peak speed to ``step / ((T_acc + T_dec) / 2)``: it never cruises.
- Logging. All five signals are written every 2 ms (the paper: 500 Hz). In a real 840D sl trace
  the measuring-system positions ``measPos1/2`` are IPO signals (4 ms); the simulator logs them
  on the servo grid like the others, which the trace reader handles alike.
- Numbers. The defaults describe a large milling robot's base axis (the paper's Flexmatik robot
  is not documented in this detail); every field of :class:`AxisParameters` says where its value
  comes from, and most are assumptions of the right order of magnitude.
- Start and end. The axis starts at rest with the gear in the middle of its dead zone. Every
  trial of the paper's plan ends at rest at its target within a few encoder steps. Faults far
  outside the defaults can keep it from settling, as on a real machine: a wide backlash (0.1 deg
  at 2 m) makes the position loop, closed on the arm encoder, hunt in a limit cycle; a doubled
  friction can leave the arm stuck about 1e-3 deg short of the target.

References
----------
.. [1] K. El Dabett, S. Hansen, C. Geier, "Functional Network-Based Analysis of Industrial Robot
   Dynamics", sections 3.1-3.2
   (experimental setup, 500 Hz acquisition of RP, AP, MP, RC, AC), section 4.1 and Fig. 9
   (phase timing of the baseline), Table 1 (design of experiments).
.. [2] D. Karnopp, "Computer simulation of stick-slip friction in mechanical dynamic systems",
   J. Dyn. Sys., Meas., Control 107 (1985) 100-103.
.. [3] B. Armstrong-Helouvry, P. Dupont, C. Canudas de Wit, "A survey of models, analysis tools
   and compensation methods for the control of machines with friction", Automatica 30 (1994).
"""

from __future__ import annotations

import dataclasses
import math
import zlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd
from scipy.signal import lfilter

from funcnet.errors import ParameterError
from funcnet.robot.phases import move_threshold
from funcnet.sim._kernel import axis_kernel
from funcnet.sim.trial import FAULT_KNOBS, Trial

__all__ = [
    "AxisParameters",
    "SimulatedTrial",
    "effective_parameters",
    "setpoint_profile",
    "reversal_error_truth",
    "simulate_trial",
    "trial_duration",
    "FAULT_KNOBS",
    "MAX_TRIAL_DURATION",
    "real_axis_parameters",
]

#: The longest trace a trial may span, in s (lead time, motion and settling; one hour). The
#: simulator holds about 0.65 MB per simulated second at the default loop rates (measured with
#: tracemalloc on a 62 s trial), so one hour peaks near 2.3 GB; a longer trial -- e.g. a tiny
#: speed -- is refused by :func:`trial_duration` before anything is allocated.
MAX_TRIAL_DURATION = 3600.0


@dataclass(frozen=True)
class AxisParameters:
    """Physical and control parameters of the simulated base axis (trial independent).

    Angles and speeds without a suffix are on the joint (arm) side; ``motor_*`` friction acts on
    the motor shaft. The three fault knobs -- ``backlash``, ``friction_scale``,
    ``stiffness_scale`` -- are what a :class:`~funcnet.sim.trial.Trial` may override.

    Parameters
    ----------
    gear_ratio : float
        Motor turns per arm turn. 150: base axes of large robots use RV / cycloidal reducers of
        ratio 100-200 (assumption).
    motor_inertia : float
        kg m^2 on the motor shaft, motor + brake + gear input stage. 0.012: a servo motor of
        about 10 N m rated torque (catalogue order of magnitude; assumption).
    arm_inertia_base : float
        kg m^2 about the axis of everything whose inertia does not depend on the TCP distance
        (turntable, column). 150 (assumption).
    arm_tcp_mass : float
        kg, the equivalent point mass at the TCP distance ``r`` (arm, swivel head, spindle), so
        that the arm inertia is ``arm_inertia_base + arm_tcp_mass * r**2``: 510 / 790 /
        1150 kg m^2 at 1.2 / 1.6 / 2.0 m (assumption). Its share is what makes a larger TCP
        distance need more current to accelerate (paper, section 3.1).
    gear_stiffness : float
        N m/rad, torsional stiffness of the reducer, joint side. 4e6: catalogue values of RV
        reducers for 300-500 kg robots are 1e6-1e7; with the inertias above the first mode lies
        near 20 Hz, typical of large robots (assumption).
    gear_damping : float
        N m s/rad, structural damping of the gear in contact; 1.2e4 gives about 10 % damping of
        the arm mode against a locked motor at 1.6 m (assumption).
    backlash : float
        Degrees, the full width of the gear's dead zone, joint side. 0.02 (72 arcsec): a worn-in
        reducer slightly above the 1 arcmin lost motion of a new RV reducer (assumption).
    motor_coulomb, motor_static : float
        N m, sliding and breakaway friction on the motor shaft (bearings, seals, input stage):
        0.8 and 1.2, about 10 % of the rated torque (assumption).
    motor_viscous : float
        N m s/rad on the motor shaft, 0.002 (assumption).
    motor_stribeck_velocity : float
        rad/s on the motor shaft, 1.0 (assumption).
    arm_coulomb, arm_static : float
        N m, sliding and breakaway friction of the slewing bearing and the gear output stage,
        joint side: 150 and 220 (assumption, a few percent of the axis's rated torque).
    arm_viscous : float
        N m s/rad, joint side, 300 (assumption).
    arm_stribeck_velocity : float
        rad/s, joint side: 0.002 (0.11 deg/s), so that 1 deg/min creeps deep in the Stribeck
        region -- the reason for the paper's static-friction trials (assumption).
    friction_scale : float
        Fault knob: multiplies every friction coefficient on both sides (1 = healthy).
    stiffness_scale : float
        Fault knob: multiplies ``gear_stiffness`` (1 = healthy; < 1 a worn, softer gear).
    torque_constant : float
        N m/A of the motor (q-axis current), 2.0 (catalogue order of magnitude; assumption).
    winding_resistance, winding_inductance : float
        Ohm and H of the DC-equivalent q-axis winding: 1.2 and 0.012 (assumption).
    current_limit : float
        A, the limit of the current set-point RC (motor peak current), 20 (assumption).
    current_loop_rate : float
        Hz, the current controller's rate and the integration rate: 16000 (SINUMERIK drives run
        the current loop every 62.5 us; the reference trace's drive rate is 8 kHz).
    current_bandwidth : float
        Hz, closed-loop bandwidth of the current loop: 1000 (the paper, section 4.2: current
        loops run at 1-2 kHz, well above the 500 Hz log).
    speed_loop_rate : float
        Hz, the speed controller's rate: 8000 (``driveSampleRate1`` = 125 us in the reference
        trace). Must divide ``current_loop_rate``.
    speed_gain : float
        A s/rad, proportional gain of the speed PI loop on the motor speed: 3.0 (tuned here for a
        crossover near 80 Hz on the motor inertia; assumption).
    speed_integral_time : float
        s, integral time of the speed PI loop: 0.02 (assumption).
    position_gain : float
        1/s, the position loop's Kv on the arm encoder: 10 (0.6 (m/min)/mm; kept well below the
        arm's antiresonance because the loop is closed on the direct encoder; assumption).
    velocity_feedforward : float
        Weight of the velocity feed-forward, 0.9: leaves the constant cruise lag
        ``(1 - 0.9) v / Kv`` that Fig. 9 shows between RP and AP (assumption).
    motor_encoder_counts : int
        Counts per motor turn: 2**22 (a 22-bit absolute motor encoder).
    arm_encoder_counts : int
        Counts per arm turn: 2**26 (5.4e-6 deg), a 26-bit absolute angle encoder as fits the
        secondary encoders of a precision milling robot (paper, section 3.1). The reference
        trace's ``measPos2`` steps by about 2**-22 of a turn; with that resolution the lost
        motion at a reversal could be read from the log only to about 10 %.
    current_noise : float
        A, standard deviation of the current-sensor noise, 0.01 (assumption, of the order of
        the standstill scatter in the reference trace).
    current_resolution : float
        A, quantum of the current measurement: 0.0066, the step of ``ActCurr32`` in the
        reference trace.
    acceleration_time, deceleration_time : float
        s, constant ramp durations of the set-point generator, 1.0 and 0.7 (fitted to Fig. 9's
        spin-up of about 1 s and braking of about 0.7 s; see the module notes).
    jerk_fraction : float
        Share of each ramp spent building up or removing acceleration, 0.22 (Fig. 9's early
        spin-up ends at 220 ms).
    lead_time : float
        s of standstill logged before the set-point starts, 0.1.
    dwell_time : float
        s the set-point rests at the far end of a forward-then-reverse trial, 0.0 (the reverse
        move follows at once).
    settle_time : float
        s logged after the set-point has arrived, 1.5, so every trace ends with the axis at rest
        at its target.
    log_period : float
        s between logged samples, 0.002 (500 Hz, the paper's rate). Must be a multiple of the
        speed-loop period.
    position_log_period : float
        s between updates of the logged measuring-system positions AP and MP: 0.002 (every
        servo tick, the paper's description) or 0.004 -- the real 840D sl trace logs
        ``measPos1/2`` as IPO signals every 4 ms (``interval="0.004"``). A multiple of
        ``log_period``; the value is held in between (a staircase on the 2 ms grid).
    noise_scale : float
        Plan knob: multiplies every noise source (current-sensor noise, its drift, cogging), 1.
    current_drift : float
        A, standard deviation of a slow, first-order low-pass component of the current
        measurement (offset drift): 0 by default; the real trace's standstill current wanders
        with a lag-1 autocorrelation of 0.9-0.99 at 2 ms.
    current_drift_frequency : float
        Hz, corner frequency of that drift, 2.0 (from the real trace's standstill
        autocorrelation: ``-ln(0.977) / (2 pi 2 ms)``).
    cogging_torque : float
        N m, amplitude of a torque ripple periodic in the motor angle (cogging), 0 by default;
        it makes the current ripple in spin-up and cruise that a real servo motor shows.
    cogging_periods : float
        Ripple periods per motor turn, 72 (the least common multiple of 36 slots and 8 pole
        pairs; assumption).
    arm_model : {"rigid", "elastic"}
        ``"elastic"`` adds a third mass: the arm's TCP share ``arm_tcp_mass * r**2`` becomes a
        tip coupled to the hub (``arm_inertia_base``, which carries the bearing friction and
        the arm encoder) through ``link_stiffness`` and ``link_damping``: the standard
        flexible-joint / flexible-link chain. ``"rigid"`` (default) is the two-mass model.
    link_stiffness : float
        N m/rad of the elastic link, 1.6e6: a first link mode near 10 Hz at 1.6 m, where large
        serial robots have their first structural modes (assumption).
    link_damping : float
        N m s/rad of the elastic link, 1.6e3 (about 3 % damping at 1.6 m; assumption).
    position_feedback : {"arm", "motor"}
        The encoder the position loop reads: ``"arm"`` (default, the direct encoder as in the
        paper's robot) or ``"motor"`` (a robot without the second encoder): RC, AC and MP then
        carry no arm-side feedback.
    arm_load : float
        N m, a constant load torque on the arm against the forward direction: gravity on an arm
        that carries its weight (axes 2 and 3 of a six-axis robot). The gear torque then keeps
        its sign unless the motion overcomes the load, and the gear stays on one flank through a
        direction change. 0 by default (the base axis); the axis starts at rest holding it.

    References
    ----------
    .. [1] El Dabett, Hansen & Geier, sections 3.1-3.2 and Fig. 9.

    Examples
    --------
    >>> p = AxisParameters()
    >>> round(p.arm_inertia(1.6))
    790
    >>> p.replace(backlash=0.05).backlash
    0.05
    """

    gear_ratio: float = 150.0
    motor_inertia: float = 0.012
    arm_inertia_base: float = 150.0
    arm_tcp_mass: float = 250.0
    gear_stiffness: float = 4.0e6
    gear_damping: float = 1.2e4
    backlash: float = 0.02
    motor_coulomb: float = 0.8
    motor_static: float = 1.2
    motor_viscous: float = 0.002
    motor_stribeck_velocity: float = 1.0
    arm_coulomb: float = 150.0
    arm_static: float = 220.0
    arm_viscous: float = 300.0
    arm_stribeck_velocity: float = 0.002
    friction_scale: float = 1.0
    stiffness_scale: float = 1.0
    torque_constant: float = 2.0
    winding_resistance: float = 1.2
    winding_inductance: float = 0.012
    current_limit: float = 20.0
    current_loop_rate: float = 16000.0
    current_bandwidth: float = 1000.0
    speed_loop_rate: float = 8000.0
    speed_gain: float = 3.0
    speed_integral_time: float = 0.02
    position_gain: float = 10.0
    velocity_feedforward: float = 0.9
    motor_encoder_counts: int = 2**22
    arm_encoder_counts: int = 2**26
    current_noise: float = 0.01
    current_resolution: float = 0.0066
    acceleration_time: float = 1.0
    deceleration_time: float = 0.7
    jerk_fraction: float = 0.22
    lead_time: float = 0.1
    dwell_time: float = 0.0
    settle_time: float = 1.5
    log_period: float = 0.002
    position_log_period: float = 0.002
    noise_scale: float = 1.0
    current_drift: float = 0.0
    current_drift_frequency: float = 2.0
    cogging_torque: float = 0.0
    cogging_periods: float = 72.0
    arm_model: str = "rigid"
    link_stiffness: float = 1.6e6
    link_damping: float = 1.6e3
    position_feedback: str = "arm"
    arm_load: float = 0.0

    def __post_init__(self) -> None:
        for name, allowed in _CHOICES.items():
            if getattr(self, name) not in allowed:
                raise ParameterError(
                    f"AxisParameters.{name} must be one of {allowed}: {getattr(self, name)!r}"
                )
        for f in _numeric_fields():
            value = getattr(self, f.name)
            if not (isinstance(value, int | float) and math.isfinite(value)):
                raise ParameterError(f"AxisParameters.{f.name} must be a finite number: {value!r}")
        nonnegative = {
            "backlash",
            "lead_time",
            "dwell_time",
            "settle_time",
            "current_noise",
            "current_resolution",
            "velocity_feedforward",
            "gear_damping",
            "noise_scale",
            "current_drift",
            "cogging_torque",
            "link_damping",
            "arm_load",
        }
        nonnegative |= {
            f.name
            for f in _numeric_fields()
            if "coulomb" in f.name or "static" in f.name or "viscous" in f.name
        }
        for f in _numeric_fields():
            value = getattr(self, f.name)
            if value < 0 or (value == 0 and f.name not in nonnegative):
                kind = "non-negative" if f.name in nonnegative else "positive"
                raise ParameterError(f"AxisParameters.{f.name} must be {kind}: {value!r}")
        if self.jerk_fraction > 0.5:
            raise ParameterError(
                f"AxisParameters.jerk_fraction must be <= 0.5: {self.jerk_fraction}"
            )
        if self.motor_static < self.motor_coulomb or self.arm_static < self.arm_coulomb:
            raise ParameterError(
                "AxisParameters: static friction must not be below Coulomb friction"
            )
        ratio = self.current_loop_rate / self.speed_loop_rate
        per_log = self.log_period * self.speed_loop_rate
        per_position = self.position_log_period / self.log_period
        if abs(per_position - round(per_position)) > 1e-9:
            raise ParameterError(
                "AxisParameters: position_log_period must be a multiple of log_period"
            )
        if abs(ratio - round(ratio)) > 1e-9 or abs(per_log - round(per_log)) > 1e-6:
            raise ParameterError(
                "AxisParameters: current_loop_rate must be a multiple of speed_loop_rate and "
                "log_period a multiple of the speed-loop period"
            )

    def arm_inertia(self, tcp: float) -> float:
        """Arm inertia about the axis in kg m^2 at TCP distance ``tcp`` (m)."""
        return self.arm_inertia_base + self.arm_tcp_mass * tcp**2

    def replace(self, **changes: float | str) -> AxisParameters:
        """A copy with ``changes`` applied (validated like the constructor)."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise ParameterError(f"AxisParameters has no field(s) {sorted(unknown)}")
        fields: dict[str, Any] = dict(changes)  # each checked by __post_init__
        return dataclasses.replace(self, **fields)


#: Fields of :class:`AxisParameters` that take a word, and the words.
_CHOICES = {"arm_model": ("rigid", "elastic"), "position_feedback": ("arm", "motor")}


def _numeric_fields() -> list[dataclasses.Field[Any]]:
    return [f for f in dataclasses.fields(AxisParameters) if f.name not in _CHOICES]


#: What :func:`real_axis_parameters` changes: the sensors and the logging, not the mechanics.
REAL_SENSOR_FIELDS = ("position_log_period", "arm_encoder_counts", "motor_encoder_counts",
                      "current_noise", "current_drift", "current_drift_frequency",
                      "cogging_torque")  # fmt: skip


def real_axis_parameters(**changes: float | str) -> AxisParameters:
    """The axis with its sensors and logging set from the real 840D sl trace.

    The mechanics stay those of :class:`AxisParameters`; what a controller trace shows is set
    from ``axis7-braking-trace.xml`` (see ``docs/validation/backlash.md`` for the side-by-side
    table):

    - ``position_log_period = 0.004``: ``measPos1/2`` are IPO signals (4 ms);
    - ``arm_encoder_counts = 2**22``: ``measPos2`` steps by 8-9e-5 deg (360 / 2**22 =
      8.6e-5 deg);
    - the motor encoder stays at 2**22 counts per turn: ``measPos1`` moves in steps of 1e-5 deg,
      but every position in the file is written with five decimals (``measPos2``'s steps are
      8e-5 and 9e-5 deg: its 8.6e-5 deg quantum rounded), so the log does not show the motor
      encoder's resolution;
    - ``current_noise = 0.013`` A: the standstill current's sample-to-sample scatter
      (``std(diff(AC)) / sqrt(2)`` = 0.013-0.014 A in all three standstill stretches);
    - ``current_drift = 0.04`` A at 2 Hz: the slow wander of the standstill current (within
      0.5 s: 0.02-0.055 A; lag-1 autocorrelation 0.89-0.99);
    - ``cogging_torque = 1.0`` N m: a current ripple of a few tenths of an ampere in cruise
      (the real cruise current's sample-to-sample scatter is 0.50 A at 108 deg/s; at the
      sweep's speeds the ripple is slower and partly regulated away).

    Parameters
    ----------
    **changes
        Further fields to set (validated as in the constructor).

    Returns
    -------
    AxisParameters

    Examples
    --------
    >>> p = real_axis_parameters()
    >>> p.position_log_period, p.arm_encoder_counts == 2**22
    (0.004, True)
    >>> real_axis_parameters(noise_scale=2.0).noise_scale
    2.0
    """
    base = AxisParameters(
        position_log_period=0.004,
        arm_encoder_counts=2**22,
        current_noise=0.013,
        current_drift=0.04,
        current_drift_frequency=2.0,
        cogging_torque=1.0,
    )
    return base.replace(**changes) if changes else base


@dataclass(frozen=True)
class SimulatedTrial:
    """One simulated trial: the logged signals, the hidden states and the ground truth.

    Attributes
    ----------
    trial : Trial
        What was simulated.
    params : AxisParameters
        The parameters in effect (the trial's fault knobs applied).
    seed : int
        The seed the noise was drawn from (combined with the trial's name).
    data : pandas.DataFrame
        Index ``time`` (s, every ``log_period``), columns RP, AP, MP (deg, joint side), RC, AC
        (A): what the controller logs.
    states : pandas.DataFrame
        Same index; the true ``gear_torque`` (N m, transmitted by the gear), ``torsion`` (deg,
        ``theta_m / N - theta_a`` before quantization), ``arm_velocity`` and
        ``motor_velocity`` (deg/s, joint side).
    truth : dict
        ``backlash`` (deg), ``breakaway_time`` (s, when the arm first leaves static friction
        after the set-point starts; NaN if it never does), ``motion_start`` (s), ``motion_end``
        (s, the set-point arrives), and for a forward-then-reverse trial ``reversal_time`` (s,
        the motor's turning point: its last step forward before the arm's restart),
        ``restart_time`` (s, the gear drives the arm back from rest: an elastic arm's hub
        dragged back by its tip while the gear still pushes forward does not count),
        ``lost_motion`` (deg, the change of the torsion ``theta_m / N - theta_a`` between the
        two, i.e. of MP - AP across the reversal:
        the motor's travel while the arm rests -- dead zone plus the gear's wind-up on both
        flanks -- plus what the arm still coasts forward in the dead zone after the motor has
        turned), ``windup_forward`` (deg, the torsion at the turning point minus half the dead
        zone; negative when the arm has already left the forward flank) and ``windup_reverse``
        (deg, the torsion beyond the other half at the restart); NaN for a forward-only trial.
    """

    trial: Trial
    params: AxisParameters
    seed: int
    data: pd.DataFrame = field(repr=False)
    states: pd.DataFrame = field(repr=False)
    truth: dict[str, float]


def _ramp_velocity(u: np.ndarray, f: float) -> np.ndarray:
    """Normalized velocity of a jerk-limited ramp (0 -> 1 over u in [0, 1], jerk share f)."""
    a = 1.0 / (1.0 - f)
    lo = np.minimum(u, 1.0 - u)  # the ramp is point-symmetric about (1/2, 1/2)
    s = np.where(lo <= f, a * lo**2 / (2 * f), a * (lo - f / 2))
    return np.where(u <= 0.5, s, 1.0 - s)


def _ramp_distance(u: np.ndarray, f: float) -> np.ndarray:
    """Integral of :func:`_ramp_velocity` from 0 to u; equals 1/2 at u = 1."""
    a = 1.0 / (1.0 - f)
    lo = np.minimum(u, 1.0 - u)
    at_f = a * f**2 / 6
    s = np.where(
        lo <= f,
        a * lo**3 / (6 * f),
        at_f + a * ((lo - f / 2) ** 2 - (f / 2) ** 2) / 2,
    )
    return np.where(u <= 0.5, s, u - 0.5 + s)


def _move(
    t: np.ndarray, step: float, speed: float, p: AxisParameters
) -> tuple[np.ndarray, np.ndarray, float]:
    """Position and velocity of one jerk-limited move starting at t = 0; and its duration."""
    ta, td, f = p.acceleration_time, p.deceleration_time, p.jerk_fraction
    peak = min(speed, abs(step) / ((ta + td) / 2))
    cruise = abs(step) / peak - (ta + td) / 2
    duration = ta + cruise + td
    tc = np.clip(t, 0.0, duration)
    in_acc, in_dec = tc < ta, tc > ta + cruise
    u_dec = np.clip((tc - ta - cruise) / td, 0.0, 1.0)
    pos = np.where(
        in_acc,
        ta * _ramp_distance(np.clip(tc / ta, 0.0, 1.0), f),
        np.where(
            in_dec, ta / 2 + cruise + td * (u_dec - _ramp_distance(u_dec, f)), ta / 2 + (tc - ta)
        ),
    )
    vel = np.where(
        in_acc,
        _ramp_velocity(np.clip(tc / ta, 0.0, 1.0), f),
        np.where(in_dec, 1.0 - _ramp_velocity(u_dec, f), 1.0),
    )
    vel = np.where((t < 0) | (t > duration), 0.0, vel)
    sign = math.copysign(1.0, step)
    return sign * peak * pos, sign * peak * vel, duration


def setpoint_profile(
    t: np.ndarray, step: float, speed: float, reverse: bool, params: AxisParameters,
    profile: str = "step",
) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:  # fmt: skip
    """Reference position and velocity of a trial's jerk-limited set-point generator.

    Parameters
    ----------
    t : ndarray
        Times in s from the start of the trace (the motion starts at ``params.lead_time``).
    step : float
        Step size in deg (its sign is the forward direction).
    speed : float
        Programmed speed in deg/min.
    reverse : bool
        Whether the axis goes back to its start after the forward move (and ``dwell_time``).
    params : AxisParameters
        Ramp durations (``acceleration_time``, ``deceleration_time``) and ``jerk_fraction``.
    profile : {"step", "smooth"}
        ``"smooth"``: out by ``step`` and back twice along ``step (1 - cos(4 pi u)) / 2`` (``u``
        from 0 to 1 over the motion), peaking at ``speed``: three direction changes without a
        rest, as a robot's smooth trajectories (``reverse`` does not apply).

    Returns
    -------
    position : ndarray
        deg.
    velocity : ndarray
        deg/s.
    timing : dict
        ``motion_start``, ``forward_end``, ``reverse_start`` (NaN without reverse) and
        ``motion_end``, in s.

    References
    ----------
    .. [1] El Dabett, Hansen & Geier, Fig. 9 (spin-up about 1 s, braking about 0.7 s).

    Examples
    --------
    >>> import numpy as np
    >>> p = AxisParameters()
    >>> pos, vel, timing = setpoint_profile(np.array([0.0, 3.0, 10.0]), 3.0, 35.0, False, p)
    >>> pos.round(6).tolist(), round(float(vel[1]) * 60, 6), round(timing["motion_end"], 4)
    ([0.0, 1.4, 3.0], 35.0, 6.0929)
    """
    t = np.asarray(t, dtype=np.float64)
    start = params.lead_time
    if profile == "smooth":
        turns = 2  # out and back twice
        duration = abs(step) * math.pi * turns / (speed / 60.0)
        u = np.clip((t - start) / duration, 0.0, 1.0)
        inside = (t > start) & (t < start + duration)
        pos = step * (1.0 - np.cos(2 * math.pi * turns * u)) / 2
        vel = np.where(inside, step * math.pi * turns / duration
                       * np.sin(2 * math.pi * turns * u), 0.0)  # fmt: skip
        end = start + duration
        return pos, vel, {"motion_start": start, "forward_end": end, "reverse_start": math.nan,
                          "motion_end": end}  # fmt: skip
    pos, vel, duration = _move(t - start, step, speed / 60.0, params)
    forward_end = start + duration
    timing = {
        "motion_start": start,
        "forward_end": forward_end,
        "reverse_start": math.nan,
        "motion_end": forward_end,
    }
    if reverse:
        back_start = forward_end + params.dwell_time
        back_pos, back_vel, back_duration = _move(t - back_start, -step, speed / 60.0, params)
        pos, vel = pos + back_pos, vel + back_vel
        timing["reverse_start"] = back_start
        timing["motion_end"] = back_start + back_duration
    return pos, vel, timing


def _drift(rng: np.random.Generator, n: int, sigma: float, corner: float, dt: float) -> np.ndarray:
    """A stationary first-order low-pass (AR(1)) noise of std ``sigma``, corner ``corner`` Hz."""
    a = math.exp(-2 * math.pi * corner * dt)
    white = rng.standard_normal(n) * (sigma * math.sqrt(1 - a * a))
    white[0] = rng.standard_normal() * sigma  # start in the stationary distribution
    return np.asarray(lfilter([1.0], [1.0, -a], white), dtype=np.float64)


def _trial_seed(seed: int, name: str) -> np.random.SeedSequence:
    """Noise seed of one trial: the user's seed with the trial's name, independent of order."""
    return np.random.SeedSequence([int(seed), zlib.crc32(name.encode("utf-8"))])


def effective_parameters(trial: Trial, params: AxisParameters | None = None) -> AxisParameters:
    """``params`` (default :class:`AxisParameters`) with the trial's fault knobs applied."""
    params = AxisParameters() if params is None else params
    if trial.sensors == "real":  # the sensor and logging fields of the real trace
        real = real_axis_parameters()
        params = params.replace(**{name: getattr(real, name) for name in REAL_SENSOR_FIELDS})
    overrides: dict[str, Any] = {
        knob: getattr(trial, knob) for knob in FAULT_KNOBS if getattr(trial, knob) is not None
    }
    for option in ("arm_model", "position_feedback"):
        if getattr(trial, option) is not None:
            overrides[option] = getattr(trial, option)
    return params.replace(**overrides) if overrides else params


def trial_duration(trial: Trial, params: AxisParameters | None = None) -> float:
    """Time a trial's trace spans, in s: lead time, the motion(s) and ``settle_time``.

    Computed from the set-point profile's timing alone, without simulating anything.

    Parameters
    ----------
    trial : Trial
        The trial (its fault knobs override ``params``).
    params : AxisParameters, optional
        The axis; :class:`AxisParameters` defaults when omitted.

    Returns
    -------
    float
        The duration in s, at most :data:`MAX_TRIAL_DURATION`.

    Raises
    ------
    ParameterError
        The trial would span more than :data:`MAX_TRIAL_DURATION` (the message names the trial).

    Examples
    --------
    >>> from funcnet.sim.trial import Trial
    >>> round(trial_duration(Trial("base", "main", speed=35, tcp=1.6, step=3)), 4)
    7.5929
    >>> trial_duration(Trial("slow", "main", speed=0.001, tcp=1.6, step=1))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    funcnet.errors.ParameterError: Trial slow: the trace would span 6e+04 s (about 17 h) ...
    """
    p = effective_parameters(trial, params)
    _, _, timing = setpoint_profile(np.zeros(1), trial.step, trial.speed, trial.reverse, p,
                                    trial.profile or "step")  # fmt: skip
    duration = timing["motion_end"] + p.settle_time
    if not duration <= MAX_TRIAL_DURATION:
        raise ParameterError(
            f"Trial {trial.name}: the trace would span {duration:.3g} s (about "
            f"{duration / 3600:.2g} h) at speed {trial.speed:g} deg/min and step {trial.step:g} "
            f"deg; at most {MAX_TRIAL_DURATION:g} s (MAX_TRIAL_DURATION) is simulated: raise "
            "the speed or shorten the step"
        )
    return duration


#: s of each stretch beside a continuous turn over which the reversal error is taken (as
#: :func:`funcnet.diagnosis.reversal_error.reversal_error`'s window)
TRUTH_WINDOW = 0.25


def reversal_error_truth(
    states: pd.DataFrame, setpoint_speed: np.ndarray, stiffness: float,
    window: float = TRUTH_WINDOW,
) -> list[float]:  # fmt: skip
    """The true reversal error at each continuous turn of the set-point, from noise-free states.

    At a turn in continuous motion the arm follows the motor through the gear; the reversal error
    is the step of the torsion ``theta_m / N - theta_a`` (MP - AP) that the gear torque does not
    explain, ``torsion - gear_torque / stiffness``, from the stretch before the turn to the one
    after (``window`` s each beyond the bracket where the set-point moves slower than 1 deg/s,
    or half its peak speed if that is less), in the old direction's sign: the dead zone where the
    gear torque changes sign there, about 0 where a load keeps it on one flank.

    Parameters
    ----------
    states : DataFrame
        :attr:`SimulatedTrial.states` (``torsion`` in deg, ``gear_torque`` in N m).
    setpoint_speed : ndarray
        deg/min, the set-point's speed on the states' grid.
    stiffness : float
        N m per deg, the gear's.
    window : float
        s.

    Returns
    -------
    list of float
        deg, one per turn.

    Examples
    --------
    >>> from funcnet.sim.trial import Trial
    >>> sim = simulate_trial(Trial("s", "s", speed=175, tcp=1.6, step=1, profile="smooth",
    ...                            backlash=2 / 60), seed=1)
    >>> abs(sim.truth["lost_motion"] * 60 - 2) < 0.1  # arcmin: the dead zone, at each turn
    True
    """
    t = states.index.to_numpy()
    v = np.asarray(setpoint_speed, dtype=np.float64) / 60.0
    fast = move_threshold(v)
    rest = (states["torsion"] - states["gear_torque"] / stiffness).to_numpy()
    sign = np.where(v > fast, 1, np.where(v < -fast, -1, 0))
    moving = np.flatnonzero(sign)
    errors = []
    for a, b in zip(moving, moving[1:], strict=False):
        if sign[a] != sign[b]:  # a stretch ends at a, the next (other way) starts at b
            before = (t >= t[a + 1] - window) & (t < t[a + 1])
            after = (t >= t[b]) & (t < t[b] + window)
            errors.append(float(sign[a] * (rest[before].mean() - rest[after].mean())))
    return errors


def _kernel_groups(p: AxisParameters, trial: Trial) -> tuple[tuple[float, ...], ...]:
    """The kernel's parameter groups in SI units: mechanics, friction, control, sensors, extra."""
    rad = math.pi / 180.0
    fs, ks = p.friction_scale, p.stiffness_scale
    omega_i = 2 * math.pi * p.current_bandwidth
    elastic = p.arm_model == "elastic"
    tip = p.arm_tcp_mass * trial.tcp**2
    hub = p.arm_inertia_base if elastic else p.arm_inertia(trial.tcp)
    mechanics = (p.gear_ratio, p.motor_inertia, hub,
                 p.gear_stiffness * ks, p.gear_damping, p.backlash * rad / 2,
                 p.torque_constant, p.winding_resistance, p.winding_inductance)  # fmt: skip
    friction = (p.motor_coulomb * fs, p.motor_static * fs, p.motor_viscous * fs,
                p.motor_stribeck_velocity, p.arm_coulomb * fs, p.arm_static * fs,
                p.arm_viscous * fs, p.arm_stribeck_velocity)  # fmt: skip
    control = (p.current_limit, p.winding_inductance * omega_i, p.winding_resistance * omega_i,
               p.speed_gain, p.speed_gain / p.speed_integral_time, p.position_gain,
               p.velocity_feedforward)  # fmt: skip
    sensors = (2 * math.pi / p.motor_encoder_counts, 2 * math.pi / p.arm_encoder_counts,
               p.current_resolution)  # fmt: skip
    extra = (tip, p.link_stiffness if elastic else 0.0, p.link_damping,
             1.0 if p.position_feedback == "motor" else 0.0, p.cogging_torque * p.noise_scale,
             p.cogging_periods, p.arm_load)  # fmt: skip
    return tuple(tuple(map(float, g)) for g in (mechanics, friction, control, sensors, extra))


def _logged(log: np.ndarray, states: np.ndarray, n_log: int,
            p: AxisParameters) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The kernel's log as the trace's signals (degrees, IPO positions held) and its states."""
    log = log[:n_log]
    hold = round(p.position_log_period / p.log_period)
    if hold > 1:  # IPO logging: AP and MP are sampled every `hold` ticks and held in between
        held = (np.arange(n_log) // hold) * hold
        log[:, 1:3] = log[held, 1:3]
    index = pd.Index(np.arange(n_log) * p.log_period, name="time")
    deg = 180.0 / math.pi
    data = pd.DataFrame({"RP": log[:, 0] * deg, "AP": log[:, 1] * deg, "MP": log[:, 2] * deg,
                         "RC": log[:, 3], "AC": log[:, 4]}, index=index)
    hidden = pd.DataFrame({"gear_torque": states[:n_log, 0], "torsion": states[:n_log, 1] * deg,
                           "arm_velocity": states[:n_log, 2] * deg,
                           "motor_velocity": states[:n_log, 3] * deg,
                           "tip_velocity": states[:n_log, 4] * deg}, index=index)
    return data, hidden


def simulate_trial(
    trial: Trial, params: AxisParameters | None = None, *, seed: int = 0
) -> SimulatedTrial:
    """Simulate one trial of the axis and log it as the controller would.

    Parameters
    ----------
    trial : Trial
        Speed (deg/min), TCP distance (m), step (deg), forward or forward-then-reverse, and
        optional fault knobs that override ``params``.
    params : AxisParameters, optional
        The axis; :class:`AxisParameters` defaults when omitted.
    seed : int
        Seed of the current-sensor noise, combined with ``trial.name`` so that a trial's
        result does not depend on which other trials run or in what order. The same seed gives
        the same numbers, bit for bit.

    Returns
    -------
    SimulatedTrial
        ``data`` (RP, AP, MP in deg; RC, AC in A; every ``log_period``), ``states`` and
        ``truth``.

    Raises
    ------
    ParameterError
        If a parameter is out of its domain, or the trace would span more than
        :data:`MAX_TRIAL_DURATION` (checked before any allocation; see :func:`trial_duration`).

    Notes
    -----
    The trace spans ``lead_time`` of standstill, the motion, and ``settle_time`` after the
    set-point has arrived. The kernel runs at ``current_loop_rate``; its first call compiles it
    (a few seconds, then cached on disk).

    References
    ----------
    .. [1] El Dabett, Hansen & Geier, sections 3.1-3.2, Table 1, Fig. 9.

    Examples
    --------
    >>> from funcnet.sim.trial import Trial
    >>> sim = simulate_trial(Trial("demo", "main", speed=350, tcp=1.2, step=1.0), seed=1)
    >>> list(sim.data.columns)
    ['RP', 'AP', 'MP', 'RC', 'AC']
    >>> round(float(sim.data["RP"].iloc[-1]), 6), bool(abs(sim.data["AP"].iloc[-1] - 1.0) < 1e-3)
    (1.0, True)
    """
    p = effective_parameters(trial, params)
    per_speed = round(p.current_loop_rate / p.speed_loop_rate)
    per_log = round(p.log_period * p.current_loop_rate)
    t_speed = 1.0 / p.speed_loop_rate
    duration = trial_duration(trial, p)  # refuses an overlong trial before allocating
    profile = trial.profile or "step"
    _, _, timing = setpoint_profile(np.zeros(1), trial.step, trial.speed, trial.reverse, p,
                                    profile)  # fmt: skip
    n_log = math.ceil(duration / p.log_period) + 1
    n_speed = n_log * (per_log // per_speed)
    t = np.arange(n_speed) * t_speed
    sp_pos, sp_vel, _ = setpoint_profile(t, trial.step, trial.speed, trial.reverse, p, profile)
    rng = np.random.default_rng(_trial_seed(seed, trial.name))
    noise = rng.standard_normal(n_speed * per_speed) * (p.current_noise * p.noise_scale)
    if p.current_drift > 0:  # drawn after the white noise: without drift nothing changes
        noise += _drift(rng, noise.size, p.current_drift * p.noise_scale,
                        p.current_drift_frequency, 1.0 / p.current_loop_rate)  # fmt: skip

    dt = 1.0 / p.current_loop_rate
    n_reverse = round(timing["forward_end"] / dt) if trial.reverse and profile == "step" else -1
    steps = (per_speed, per_log, round(timing["motion_start"] / dt), n_reverse)
    rad, deg = math.pi / 180.0, 180.0 / math.pi
    log, states, events = axis_kernel(sp_pos * rad, sp_vel * rad, noise, dt, steps,
                                      *_kernel_groups(p, trial))
    data, hidden = _logged(log, states, n_log, p)
    truth = {
        "backlash": p.backlash,
        "breakaway_time": float(events[0]),
        "motion_start": timing["motion_start"],
        "motion_end": timing["motion_end"],
        "reversal_time": float(events[1]),
        "restart_time": float(events[2]),
        "lost_motion": float(events[3] * deg),
        "windup_forward": float(events[4] * deg),
        "windup_reverse": float(events[5] * deg),
    }
    if profile == "smooth":  # the reversal error at each continuous turn, its mean the truth
        errors = reversal_error_truth(hidden, sp_vel[:: per_log // per_speed][:n_log] * 60.0,
                                      p.gear_stiffness * p.stiffness_scale * rad)  # fmt: skip
        truth["lost_motion"] = float(np.mean(errors)) if errors else math.nan
    return SimulatedTrial(
        trial=trial, params=p, seed=int(seed), data=data, states=hidden, truth=truth
    )
