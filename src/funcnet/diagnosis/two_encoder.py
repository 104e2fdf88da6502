"""The two-encoder lost motion at a direction change (needs AP and MP).

``MP - AP`` changes across a reversal by the motor's travel while the arm rests -- the gear's
dead zone plus its wind-up on both flanks -- plus what the arm still coasts forward after the
motor has turned: :func:`lost_motion` measures that change from the motor's turning point to
the arm's restart, the simulator's truth (:class:`funcnet.sim.axis.SimulatedTrial`). The
restart is the first after the set-point's turn with which the arm moves the new way from a
rest (a reading it reached moving the old way, or two equal readings: a loop hunting across the
dead zone stops the arm in it); the turn is the motor's last move the old way before it
(between ticks, AP interpolated there, when the arm still coasts). The restart is placed
between the 4 ms readings by a least-squares fit of the arm's start to the readings' distances
from the rest reading: the physics of a rigid arm driven through the gear's spring by the logged
motor travel against friction falling from its static to its sliding level
(:func:`_fit_restart`), its resonance and friction drop the mean of their fits at the reversal
and, where the arm first starts from a long rest in the same recording, there
(:func:`first_start`); where that puts the restart far earlier than the shape-only fit (a
jerk-driven cube law bent by the gear-arm resonance, :func:`_restart_time`) -- the motor
hitting the flank at speed -- the latter is taken. After a standstill: the motor's travel from
its rest to the arm's restart (the shape-only fit). Each choice and its validation:
docs/validation/backlash.md section 3.1.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numba
import numpy as np

from funcnet.diagnosis.reversals import DirectionChange
from funcnet.robot.preprocess import encoder_step
from funcnet.robot.recording import Recording

__all__ = ["ArmStart", "first_start", "lost_motion"]

# The arm's start after its restart (:func:`_restart_time`): a jerk-driven cube law bent by the
# gear's spring; the spans were chosen on every third trial of the sweep, confirmed on the rest
_RESTART_SPAN = 40  # encoder steps of the arm's distance from its rest fitted for the restart
_SHAPE_SPAN = 100  # ... and for the gear-arm resonance that bends the start
_OMEGAS = tuple(np.arange(0.0, 401.0, 10.0))  # rad/s: the resonance's candidates
# the spring's bend is offset in part by the friction's Stribeck drop early on: the restart is
# fitted with this share of the fitted resonance (chosen on every third trial of the sweep,
# confirmed on the rest and on the other sweeps; docs/validation/backlash.md section 3.1)
_STRIBECK = 0.7
# encoder steps by which the physical start's estimate may fall below the shape-only one
# (chosen on every third trial of the sweep with the physical start's spans; section 3.1)
_GUARD = 5


def _values(rec: Recording, name: str) -> np.ndarray:
    return rec.data[name].to_numpy(dtype=np.float64)


def _index(t: np.ndarray, time: float) -> int:
    return int(np.clip(np.searchsorted(t, time), 0, t.size - 1))


def _turn(rec: Recording, change: DirectionChange) -> int:
    """Index of the motor's turning point: MP's extreme in the first move's direction.

    After a standstill the motor rests where the first move left it: the turning point is then
    sought from just before the second move starts.
    """
    t = rec.data.index.to_numpy()
    mp = _values(rec, "MP")
    a = _index(t, change.stop - 0.3 if change.kind == "reversal" else change.start - 0.1)
    b = _index(t, change.start + min(change.dwell, 1.0) + 0.5)
    old = -change.direction
    return a + int(np.argmax(old * mp[a : b + 1]))


def _arm_restart(
    t: np.ndarray, mp: np.ndarray, ap: np.ndarray, change: DirectionChange, quantum: float
) -> int | None:
    """Index of the first reading with which the arm moves back from a rest after the turn.

    The set-point's turn (``change.stop``) starts the search, as the simulator's truth counts
    the first restart after it. A rest is a reading the arm stays on after moving the old way
    (the arm coasted, bounced or rested there), or a run of at least two equal readings (the
    arm came to a stick while moving back: the loop hunts across the dead zone); a single
    repeated reading within a move back is the encoder's resolution, not a stop. The gear
    drives the arm back only once the motor has turned and moved back itself (by more than an
    arm-encoder step): an elastic arm's hub dragged back by its ringing tip while the motor
    still moves forward is no restart across the dead zone.
    """
    new = change.direction
    # the rest reading itself read at or after the set-point's turn: a rest the arm leaves in the
    # tick across the turn is a hunting loop's swing through zero speed before it, not the
    # restart the truth counts (the first after the turn)
    a = max(_index(t, change.stop) + 1, 2)
    b = _index(t, change.start + min(change.dwell, 1.0) + 1.0)
    for k in range(a, b + 1):
        if new * (ap[k] - ap[k - 1]) > 0 and new * (ap[k - 1] - ap[k - 2]) <= 0:
            r0 = k - 1
            while r0 > 0 and ap[r0 - 1] == ap[k - 1]:
                r0 -= 1
            came_old_way = r0 == 0 or new * (ap[r0] - ap[r0 - 1]) < 0
            motor_back = new * (mp[k - 1] - _motor_turn(t, mp, k - 1, -new)[2]) > quantum
            if (came_old_way or k - 1 - r0 >= 2) and motor_back:
                return k
    return None


def _start_shape(tau: np.ndarray, omega: float) -> np.ndarray:
    """The arm's distance after its restart per unit gain, ``tau`` s after it: ``tau**3`` bent
    by the gear's spring, ``6 (w tau - sin(w tau)) / w**3`` (``tau**3`` when ``w`` is 0)."""
    if omega == 0:
        return tau**3
    return 6 * (omega * tau - np.sin(omega * tau)) / omega**3


def _fit_start(
    times: np.ndarray, distance: np.ndarray, candidates: np.ndarray, omegas: Sequence[float]
) -> tuple[float, float]:
    """Least-squares restart time and spring frequency over the candidates and ``omegas``."""
    tau = np.clip(times[None, :] - candidates[:, None], 0.0, None)
    best = (math.inf, float(candidates[-1]), 0.0)
    for omega in omegas:
        shape = _start_shape(tau, omega)
        norm = (shape * shape).sum(axis=1)
        gain = np.maximum((shape * distance).sum(axis=1), 0.0) / np.where(norm > 0, norm, 1.0)
        error = ((distance - gain[:, None] * shape) ** 2).sum(axis=1)
        j = int(np.argmin(error))
        if error[j] < best[0]:
            best = (float(error[j]), float(candidates[j]), float(omega))
    return best[1], best[2]


def _restart_time(
    t: np.ndarray, ap: np.ndarray, rest: float, first: int, earliest: int, new: int,
    quantum: float, back: int,
) -> float:  # fmt: skip
    """The arm's restart between ticks, from its distance to the rest reading after it.

    The arm leaves its rest as the gear's torque builds up with the motor's travel: a
    jerk-driven start, ``u = A tau**3`` at first, which the gear's spring bends within 10-20 ms
    (the arm catching up with the motor: ``u = 6 A (w tau - sin(w tau)) / w**3`` for a motor at
    constant speed, ``w = sqrt(k / J)`` the gear-arm resonance). ``w`` is fitted with the
    restart over the readings up to ``_SHAPE_SPAN`` encoder steps (10 ticks), where the bend
    shows above the rounding; the restart is then fitted over the readings up to
    ``_RESTART_SPAN`` steps with ``_STRIBECK * w``: the sliding friction falls from its static
    to its Coulomb level as the arm speeds up, an acceleration that offsets part of the spring's
    bend early on. Both least squares are in the distance itself, the rounding's errors being
    uniform there (within half a step), on a 50 us grid of restart times. The arm creeps below
    one step for several ticks, so the restart may lie up to ``back`` ticks before ``first``,
    never before the rest began (``earliest``).
    """
    ticks = np.arange(first, min(first + 10, t.size))
    distance = new * (ap[ticks] - rest)
    candidates = np.arange(t[max(earliest, first - back)], t[first] + 2.5e-5, 5e-5)
    near = distance < _SHAPE_SPAN * quantum
    if near.sum() < 2:
        return float(t[first - 1])
    _, omega = _fit_start(t[ticks[near]], distance[near], candidates, _OMEGAS)
    near = distance < _RESTART_SPAN * quantum
    if near.sum() < 2:
        return float(t[first - 1])
    restart, _ = _fit_start(t[ticks[near]], distance[near], candidates, [_STRIBECK * omega])
    return restart


# The physical start (:func:`_fit_restart`). Assumed, not fitted -- the simulator's values, a real
# axis's are unknown (docs/validation/backlash.md section 3.1): the gear-arm mode's damping ratio
# (its ``gear_damping``: about 10 %) and the arm bearing's Stribeck velocity (rad/s)
_ZETA = 0.1
_STRIBECK_VELOCITY = 0.002
# encoder steps of the arm's travel over which w and s are fitted (with t0), and over which t0
# is then fitted alone; chosen on every third no-backlash trial of the sweep, confirmed on the
# rest and on the other sweeps (docs/validation/backlash.md section 3.1)
_PARAM_SPAN = 200
_START_SPAN = 25
_TICKS = 24  # readings at most, from the first beyond the rest's rounding
_RAD = math.pi / 180


@numba.njit(cache=True)
def _squared_errors(
    starts: np.ndarray, w2: np.ndarray, cj: np.ndarray, drop: np.ndarray, v_s: float,
    motor: np.ndarray, speed: np.ndarray, at: np.ndarray, distance: np.ndarray, dt: float,
) -> np.ndarray:  # fmt: skip
    """Sum of squared errors of the modelled travel at the readings, per parameter set and start.

    Infinite where the sum already exceeds the least found before (only the least is used).

    ``motor``, ``speed``: the motor's travel (rad) and speed on a grid of step ``dt``; ``starts``
    and ``at`` (the readings): indices on that grid; ``distance``: the readings' travel (rad).
    Explicit (semi-implicit Euler) integration; before its start the arm reads its rest.
    """
    out = np.full((w2.size, starts.size), np.inf)
    last = at[-1]
    best = np.inf
    for p in range(w2.size):
        for a in range(starts.size):
            n0 = starts[a]
            m0, v0 = motor[n0], speed[n0]
            x = xd = s = 0.0
            r = 0
            while r < at.size and at[r] <= n0:
                s += distance[r] ** 2
                r += 1
            for n in range(n0, last):
                acc = (w2[p] * (motor[n] - m0 - x) + cj[p] * (speed[n] - v0 - xd)
                       + drop[p] * (1.0 - math.exp(-((xd / v_s) ** 2))))  # fmt: skip
                if acc < 0.0 and xd <= 0.0:  # the arm sticks again rather than move back
                    acc = 0.0
                xd += acc * dt
                x += xd * dt
                while r < at.size and at[r] == n + 1:
                    s += (distance[r] - x) ** 2
                    r += 1
                if s > best:  # the sum only grows: this one cannot be the least (left at inf)
                    break
            if s <= best:
                out[p, a] = s
                best = s
    return out


def _pairs(omegas: np.ndarray, drops: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every pair of the two grids, as two flat arrays."""
    grid = np.meshgrid(omegas, drops, indexing="ij")
    return grid[0].ravel(), grid[1].ravel()


def _best(
    t: np.ndarray, motor_deg: np.ndarray, origin: float, times: np.ndarray,
    distance: np.ndarray, starts: np.ndarray, omegas: np.ndarray, drops: np.ndarray, dt: float,
) -> tuple[float, float, float, float]:  # fmt: skip
    """The least-squares start time, ``w`` and ``s`` over the candidates (pairs ``omegas``,
    ``drops``), on a grid of step ``dt`` from ``origin``; MP linear between its readings. Last:
    the least sum of squared errors (rad**2)."""
    grid = origin + np.arange(int(round((times[-1] - origin) / dt)) + 2) * dt
    motor = np.interp(grid, t, motor_deg) * _RAD
    seg = np.clip(np.searchsorted(t, grid, side="right"), 1, t.size - 1)
    speed = (motor_deg[seg] - motor_deg[seg - 1]) / (t[seg] - t[seg - 1]) * _RAD
    at = np.round((times - origin) / dt).astype(np.int64)
    n0 = np.unique(np.clip(np.round((starts - origin) / dt).astype(np.int64), 0, grid.size - 1))
    errors = _squared_errors(n0, omegas**2, 2 * _ZETA * omegas, drops, _STRIBECK_VELOCITY,
                             motor, speed, at, distance, dt)  # fmt: skip
    p, a = np.unravel_index(int(np.argmin(errors)), errors.shape)
    return float(grid[n0[a]]), float(omegas[p]), float(drops[p]), float(errors[p, a])


def _fit_restart(
    t: np.ndarray, mp: np.ndarray, ap: np.ndarray, rest: float, first: int, earliest: int,
    new: int, quantum: float, back: int = 8, max_readings: int = _TICKS,
    span: float = _PARAM_SPAN, alone: bool = True,
) -> tuple[float, float, float, float] | None:  # fmt: skip
    """The arm's restart between ticks, fitted with the physics of its start.

    The two-encoder lost motion (:func:`lost_motion`) ends where
    the gear drives the arm back from rest, an instant between the 4 ms readings: the arm creeps
    below one encoder step for a few ticks after it breaks free. Its start follows the physics
    of a rigid arm of inertia ``J`` on a gear of stiffness ``k`` and damping ``c`` driven by the
    motor (whose travel ``m`` the motor encoder logs), against the bearing's friction falling
    from its static to its sliding level as the arm speeds up (Stribeck):

    ``x'' = w**2 (m - x) + 2 zeta w (m' - m'(t0) - x') + s (1 - exp(-(x' / v_s)**2))``

    with ``x`` the arm's travel from its rest and ``m`` the motor's (joint side) since the
    restart ``t0``, ``w = sqrt(k / J)``, ``s = (F_s - F_c) / J`` the Stribeck drop per inertia
    (the gear torque equals the static friction at ``t0``; the arm's viscous friction is left
    out, below 5 % of the drop at these speeds). Fitted per reversal: ``w`` and ``s`` with
    ``t0`` over the readings up to ``span`` encoder steps (``max_readings`` at most), then ``t0``
    alone over those up to ``_START_SPAN`` steps (where the model with the fitted parameters
    is closest; the larger span carries the parameters). Assumed, not fitted: the gear's
    damping ratio ``_ZETA`` and the Stribeck velocity ``v_s`` -- the simulator's values
    (:class:`funcnet.sim.axis.AxisParameters`: ``gear_damping`` gives about 10 %,
    ``arm_stribeck_velocity`` 0.002 rad/s); a real axis's are unknown (docs/validation/backlash.md
    section 3.1 gives the estimate's sensitivity to them).

    Parameters
    ----------
    t, mp, ap : ndarray
        Times (s) and the motor and arm positions (deg, joint side) on their own grid.
    rest : float
        The arm's rest reading.
    first : int
        Index of the first reading a step and a half beyond the rest.
    earliest : int
        Index of the first reading of the rest (the restart is not before it).
    new : int
        The new direction, +1 or -1.
    quantum : float
        The arm encoder's step, deg.
    back : int
        Ticks before ``first`` the restart may lie (the arm creeps below a step).
    max_readings, span : int, float
        The parameters are fitted over at most ``max_readings`` readings from ``first``, those
        up to ``span`` encoder steps from the rest.
    alone : bool
        Whether the restart is then fitted alone with the fitted parameters (False: the start
        fitted with them is returned, for a caller that fits it alone with other parameters).

    Returns
    -------
    tuple of float or None
        The restart (s), ``w`` (rad/s), ``s`` (rad/s**2) and the RMS residual of the
        parameters' fit (encoder steps); None with fewer than three readings within ``span``
        steps.

    Examples
    --------
    A rigid arm breaking free at 0.08 s behind a motor moving back at 0.2 deg/s (no friction
    drop), read every 4 ms by a 2**22-count encoder:

    >>> q = 360 / 2**22
    >>> t = np.arange(0.0, 0.2, 0.004)
    >>> mp = -0.2 * np.clip(t - 0.05, 0, None)
    >>> tau = np.clip(t - 0.08, 0, None)
    >>> ap = np.round(-0.2 * (tau - np.sin(70 * tau) / 70) / q) * q
    >>> first = int(np.flatnonzero(ap < -1.5 * q)[0])
    >>> restart, omega, drop, residual = _fit_restart(t, mp, ap, 0.0, first, 0, -1, q)
    >>> round(restart, 4)
    0.0797
    """
    readings = np.arange(first, min(first + max_readings, t.size))
    distance = new * (ap[readings] - rest)
    readings = readings[distance < span * quantum]
    distance = distance[distance < span * quantum] * _RAD
    if readings.size < 3:
        return None
    times, motor_deg = t[readings], new * mp
    origin = float(t[max(earliest, first - back)])
    end = float(t[first])
    # the parameters and the start, coarse to fine (a grid: the error has local minima)
    omegas, drops = _pairs(np.arange(30.0, 181.0, 10.0), np.arange(0.0, 0.41, 0.04))
    coarse = np.arange(origin, end + 1e-9, 5e-4)
    start, omega, drop, _ = _best(t, motor_deg, origin, times, distance, coarse, omegas, drops,
                                  2e-4)  # fmt: skip
    omegas, drops = _pairs(np.arange(omega - 10, omega + 10.1, 2.5), np.arange(0.0, 0.401, 0.02))
    starts = np.arange(max(origin, start - 2e-3), min(end, start + 2e-3) + 1e-9, 1e-4)
    start, omega, drop, error = _best(t, motor_deg, origin, times, distance, starts, omegas, drops,
                                      1e-4)  # fmt: skip
    residual = math.sqrt(error / distance.size) / (quantum * _RAD)
    if alone:
        # the restart alone, over the readings nearest the rest (without one the arm left fast:
        # the start fitted with the parameters stands)
        refined = _restart_alone(t, mp, ap, rest, first, earliest, new, quantum, omega, drop, back)
        start = start if refined is None else refined
    return start, omega, drop, residual


# readings (0.1 s at 4 ms) the arm rests on one reading before a start whose physics is fitted
# for the axis's parameters (:func:`first_start`): a rest, not a pause of the encoder's count
_REST_READINGS = 25
# readings over which the start from a long rest is fitted, and the RMS residual (encoder steps)
# up to which that fit stands (:func:`first_start`; the bound chosen on the main sweep's seeds 1-3
# and a motor-encoder loop sweep, where 2.5-4 give the same misses; validated on other seeds:
# docs/validation/backlash.md section 3.1)
_START_READINGS = 40
_START_RESIDUAL = 3.0


@dataclass(frozen=True)
class ArmStart:
    """The arm's start from a rest, fitted with its physics (:func:`first_start`).

    Attributes
    ----------
    time : float
        The restart, s.
    omega : float
        The gear-arm resonance ``sqrt(k / J)``, rad/s.
    drop : float
        The bearing friction's Stribeck drop per inertia ``(F_s - F_c) / J``, rad/s**2.
    """

    time: float
    omega: float
    drop: float


def first_start(rec: Recording) -> ArmStart | None:
    """The arm's first start from a rest in a recording, fitted with the physics of its start.

    The resonance ``w = sqrt(k / J)`` and the Stribeck drop ``s`` are the axis's, not the
    reversal's: fitted where the arm starts from a long rest (the recording's first run of at
    least ``_REST_READINGS`` equal AP readings followed by a move of more than a step and a
    half that the motor leads), they steady the restart's fit at a reversal
    (:func:`lost_motion`'s ``axis``, which takes the mean of both fits): on the main sweep the
    resonance fitted at the start is off the simulator's ``sqrt(k / J)`` by 3.5 % (s.d.), at the
    reversal by 20 %, a few reversals falling into a wrong minimum (docs/validation/backlash.md
    section 3.1). The fit is that of the reversal's restart (:func:`_fit_restart`), with its assumed
    damping ratio and Stribeck velocity, over ``_START_READINGS`` readings whatever the arm's
    travel (160 ms: a period of the resonance or more at 40 rad/s and above, which pins it where
    the reversal's span of 24 readings at most -- shorter than a period below about 65 rad/s --
    lets the fit trade it for the friction drop) where the model holds there, its RMS residual
    at most ``_START_RESIDUAL`` encoder steps; else (a gear that opens again as the arm rings,
    or a gap in MP within those readings) over the reversal's span.

    Parameters
    ----------
    rec : Recording
        With MP and AP on the positions' own grid (:func:`.motor_side_recording`).

    Returns
    -------
    ArmStart or None
        The first such start that can be fitted; None without one (an arm whose reading
        jitters at rest, as on the real trace, has none; a start with a gap in MP, or with
        fewer than three readings within the fit's span, cannot be fitted).

    References
    ----------
    Paper section 5.1 (backlash at the reversals); the start's model: :func:`_fit_restart`.

    Examples
    --------
    A rigid arm breaking free at 0.3 s behind a motor moving at 0.2 deg/s, read every 4 ms by a
    2**22-count encoder:

    >>> import pandas as pd
    >>> from funcnet.robot import SignalInfo
    >>> q = 360 / 2**22
    >>> t = np.arange(0.0, 0.5, 0.004)
    >>> tau = np.clip(t - 0.3, 0, None)
    >>> ap = np.round(0.2 * (tau - np.sin(70 * tau) / 70) / q) * q
    >>> mp = 0.2 * np.clip(t - 0.25, 0, None)
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP")}
    >>> rec = Recording(pd.DataFrame({"MP": mp, "AP": ap}, index=pd.Index(t, name="time")),
    ...                 {}, info, sample_period=0.004)
    >>> start = first_start(rec)
    >>> round(start.time, 3), abs(start.omega - 70) < 7
    (0.3, True)
    """
    t = rec.data.index.to_numpy()
    mp, ap = _values(rec, "MP"), _values(rec, "AP")
    quantum = encoder_step(ap)
    bounds = np.concatenate(([0], np.flatnonzero(np.diff(ap) != 0) + 1, [ap.size]))
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        if b - a < _REST_READINGS or b == ap.size:
            continue
        rest = float(ap[a])
        moved = np.flatnonzero(np.abs(ap[b:] - rest) > 1.5 * quantum)
        if moved.size == 0:
            return None
        first = b + int(moved[0])
        new = 1 if ap[first] > rest else -1
        if not new * (mp[first] - mp[a]) > 0:  # the arm moved without the motor leading it
            continue
        if not np.isfinite(mp[a : first + _TICKS]).all():  # a gap in MP: nothing to fit
            continue
        fit = None
        if np.isfinite(mp[a : first + _START_READINGS]).all():
            fit = _fit_restart(t, mp, ap, rest, first, a, new, quantum,
                               max_readings=_START_READINGS, span=math.inf)  # fmt: skip
        if fit is None or fit[3] > _START_RESIDUAL:
            fit = _fit_restart(t, mp, ap, rest, first, a, new, quantum)
        if fit is not None:
            return ArmStart(*fit[:3])
    return None


def _restart_alone(
    t: np.ndarray, mp: np.ndarray, ap: np.ndarray, rest: float, first: int, earliest: int,
    new: int, quantum: float, omega: float, drop: float, back: int = 8,
) -> float | None:  # fmt: skip
    """The restart fitted alone with a given resonance and drop (:func:`_fit_restart`'s last
    stage), over the readings up to ``_START_SPAN`` steps; None without such a reading."""
    ticks = np.arange(first, min(first + _TICKS, t.size))
    distance = new * (ap[ticks] - rest)
    near = distance < _START_SPAN * quantum
    if not near.any():
        return None
    origin = float(t[max(earliest, first - back)])
    candidates = np.arange(origin, float(t[first]) + 1e-9, 5e-5)
    start, _, _, _ = _best(t, new * mp, origin, t[ticks[near]], distance[near] * _RAD, candidates,
                           np.array([omega]), np.array([drop]), 5e-5)  # fmt: skip
    return start


def _motor_turn(t: np.ndarray, mp: np.ndarray, end: int, old: int) -> tuple[int, float, float]:
    """The motor's turning point before index ``end``: its last move the old way.

    Returns the tick after that move, the time the motor came to rest within it (a constant
    deceleration to zero over the last two moves: ``x`` of the last tick interval with
    ``x**2 / (2 x + 1)`` the ratio of the last move to the one before) and MP there.
    """
    forward = np.flatnonzero(old * np.diff(mp[: end + 1]) > 0)
    j = int(forward[-1]) + 1 if forward.size else end
    x = 1.0
    if j >= 2:
        last, before = old * (mp[j] - mp[j - 1]), old * (mp[j - 1] - mp[j - 2])
        if before > 0:
            ratio = last / before
            x = min(1.0, ratio + math.sqrt(ratio * ratio + ratio))
    return j, float(t[j - 1] + x * (t[j] - t[j - 1])) if j >= 1 else float(t[j]), float(mp[j])


def lost_motion(
    rec: Recording, change: DirectionChange, turn: int | None = None, *,
    axis: ArmStart | None = None,
) -> float:  # fmt: skip
    """Two-encoder lost motion at a direction change, in deg (NaN if the arm never restarts).

    Parameters
    ----------
    rec : Recording
        With MP and AP on the positions' own grid (:func:`.motor_side_recording`).
    change : DirectionChange
    turn : int, optional
        Index of the motor's turning point, used after a standstill only (found from MP when
        omitted); at a reversal the turn is the motor's last move the old way before the
        arm's restart (see the module's notes).
    axis : ArmStart, optional
        The axis's start from a long rest (:func:`first_start`): at a reversal the restart is
        then fitted alone with the mean of its resonance and drop and those fitted at the
        reversal; without, the reversal's own.

    Returns
    -------
    float
        ``MP - AP`` at the motor's turn minus at the arm's restart, in the old direction's sign
        (``|MP(turn) - MP(restart)|`` after a standstill; see the module's notes).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> from funcnet.diagnosis.reversals import DirectionChange
    >>> t = np.arange(0, 2, 0.004)
    >>> mp = np.where(t < 1, t, 2 - t)           # the motor turns at 1 s
    >>> ap = np.where(t < 1.1, np.minimum(t, 0.95), 0.95 - 25 * (t - 1.1) ** 3)
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP")}
    >>> rec = Recording(pd.DataFrame({"MP": mp, "AP": ap}, index=pd.Index(t, name="time")),
    ...                 {}, info, sample_period=0.004)
    >>> round(lost_motion(rec, DirectionChange(1.0, 1.0, 0.0, -1, "reversal")), 3)
    0.1
    """
    t = rec.data.index.to_numpy()
    mp, ap = _values(rec, "MP"), _values(rec, "AP")
    new = change.direction
    old = -new
    quantum = encoder_step(ap)
    if change.kind == "reversal":
        k = _arm_restart(t, mp, ap, change, quantum)
        if k is None:
            return math.nan
        rest = float(ap[k - 1])
        earliest = k - 1
        while earliest > 0 and ap[earliest - 1] == rest:
            earliest -= 1
        # the first tick a step and a half beyond the rest (a creep of one step is resolution)
        moved = np.flatnonzero(new * (ap[k:] - rest) > 1.5 * quantum)
        if moved.size == 0:
            return math.nan
        first = k + int(moved[0])

        def across(restart: float) -> float:
            # MP - AP across the reversal (old direction's sign): at the motor's turning point
            # (the arm may still coast forward there: AP between ticks) minus at the restart,
            # where the arm still reads its rest
            j, t_turn, _ = _motor_turn(t, mp, _index(t, restart), old)
            at_turn = old * (mp[j] - float(np.interp(t_turn, t, ap)))
            return float(at_turn - old * (np.interp(restart, t, mp) - rest))

        # the restart from the physics of the arm's start, its parameters fitted per reversal
        # (_fit_restart); the shape-only fit when the arm moves too little for that, or when the
        # physics puts the restart far earlier (the motor hitting the flank at speed: its impact
        # lies between the MP readings, and the model, which has the gear transmit the static
        # friction at the restart, then finds an earlier start with a too low resonance)
        shape = across(_restart_time(t, ap, rest, first, earliest, new, quantum, back=8))
        fit = _fit_restart(t, mp, ap, rest, first, earliest, new, quantum, back=8,
                           alone=axis is None)  # fmt: skip
        if fit is None:
            return shape
        restart = fit[0]
        if axis is not None:
            # the resonance and drop are the axis's: the mean of their fits at its start from a
            # long rest and here (a reversal's own fit at times falls into a wrong minimum)
            alone = _restart_alone(t, mp, ap, rest, first, earliest, new, quantum,
                                   (axis.omega + fit[1]) / 2, (axis.drop + fit[2]) / 2)  # fmt: skip
            restart = restart if alone is None else alone
        physics = across(restart)
        return shape if physics < shape - _GUARD * quantum else physics
    # after a standstill: the arm rested since long before the motor turned; its reading
    # jitters by an encoder step or two
    turn = _turn(rec, change) if turn is None else turn
    before = ap[_index(t, change.start - 0.2) : _index(t, change.start) + 1]
    rest = float(np.median(before))
    threshold = max(1.5 * quantum, 4 * float(np.std(before)), float(np.ptp(before)))
    moved = np.flatnonzero(new * (ap[turn:] - rest) > threshold)
    if moved.size == 0:
        return math.nan
    first = turn + int(moved[0])
    # a creep cannot be told from the rest's jitter: at most two ticks before the first move
    restart = _restart_time(t, ap, rest, first, turn, new, quantum, back=2)
    return float(abs(mp[turn] - np.interp(restart, t, mp)))
