"""The lost motion at a direction change in continuous motion: the reversal error (needs AP).

Where the arm never rests at a turn (a robot's smooth trajectories; ``kind="continuous"`` in
:func:`~funcnet.diagnosis.reversals.find_direction_changes`) the arm follows the motor through
the turn, elastically. ``MP - AP`` there is the gear's wind-up under its torque, plus the lost
motion -- the reversal error of ISO 230-2: the arm lags the motor by more in one direction than
in the other (backlash crossed where the gear torque changes sign; friction in the gear) -- plus
what the two encoders' timing adds: an encoder read a little earlier than the other reads
``speed x skew`` apart (on the KUKA KR 300 runs 2.8-3.1 ms on every axis,
docs/validation/backlash.md).

:func:`fit_gear` fits, over the recording's samples where the motor moves faster than 1 deg/s,

``MP - AP = offset + compliance * torque + skew * VM + hysteresis / 2 * sign(VM)``

(least squares; ``torque`` the AC column, the motor torque or current) and
:func:`reversal_error` measures at each direction change the step of the part the torque and
the speed do not explain, ``MP - AP - compliance * torque - skew * VM``, from the stretch before
the turn to the stretch after it (0.25 s each, beyond the bracket where the set-point moves
slower than 1 deg/s), with a circular block bootstrap interval over the samples (the fit
redone on each resample). :func:`torque_traversed` says whether the gear torque changed sign
there (the backlash is crossed only then); :func:`funcnet.diagnosis.dead_zone.gear_parts` tells
the dead zone from the friction over the recording, where the torque's sign allows.

A recording with gaps (:attr:`funcnet.robot.Recording.gaps`) is fitted over the samples of all
its segments: the motor speed and the gear torque's moving mean within each segment, and no
bootstrap block across a gap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special  # stdtrit is scipy.stats.t.ppf, without its import

from funcnet.diagnosis.reversals import DirectionChange
from funcnet.errors import ChannelError, ParameterError
from funcnet.robot.phases import move_threshold
from funcnet.robot.preprocess import segment_ticks, segment_velocity
from funcnet.robot.recording import Recording

__all__ = [
    "GearFit",
    "ReversalError",
    "fit_gear",
    "friction_bias",
    "gear_torque",
    "reversal_error",
    "torque_traversed",
    "torque_column",
    "unexplained",
    "WINDOW",
]

#: deg/s the motor must exceed for a sample to enter the gear's fit (as in the plain least-squares
#: fit).
FIT_SPEED = 1.0
#: s of each stretch beside the turn over which the step is measured.
WINDOW = 0.25
_BLOCK = 0.05  # s, the bootstrap's blocks (the torque ripples at 10-25 Hz)
_SMOOTH = 0.04  # s, the gear torque's moving mean (takes the ripple out)
_MARGIN = 2.0  # the gear torque's noise (s.d. of its moving mean) a sign must lie beyond


def torque_column(rec: Recording) -> str:
    """The motor torque or current column (AC, else RC).

    Raises
    ------
    ChannelError
        Neither.
    """
    for name in ("AC", "RC"):
        if name in rec.data.columns:
            return name
    raise ChannelError(rec.source or "<recording>", "no AC or RC (motor torque or current)")


def _columns(rec: Recording) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Times, MP - AP, the motor speed VM (from MP, Eq. 11-12) and the torque."""
    for name in ("MP", "AP"):
        if name not in rec.data.columns:
            raise ChannelError(rec.source or "<recording>", f"no {name} column")
    t = rec.data.index.to_numpy(dtype=np.float64)
    mp = rec.data["MP"].to_numpy(dtype=np.float64)
    ap = rec.data["AP"].to_numpy(dtype=np.float64)
    torque = rec.data[torque_column(rec)].to_numpy(dtype=np.float64)
    return t, mp - ap, segment_velocity(rec, mp), torque


@dataclass(frozen=True)
class GearFit:
    """The gear between the two encoders, fitted from a recording (:func:`fit_gear`).

    Attributes
    ----------
    compliance : float
        deg of ``MP - AP`` per unit of torque (the gear's elastic wind-up).
    skew : float
        s: ``MP - AP`` per motor speed -- the two encoders read this far apart in time.
    offset : float
        deg, ``MP - AP`` at rest without torque.
    hysteresis : float
        deg, twice the direction term: the reversal error over the whole recording.
    rms : float
        deg, the fit's residual.
    samples : int
        Samples fitted (motor faster than ``min_speed``).
    torque : str
        The torque column fitted (AC or RC).
    min_speed : float
        deg/s, the fit's ``min_speed`` (:func:`fit_gear`): the bootstrap of
        :func:`reversal_error` refits on the same samples.
    """

    compliance: float
    skew: float
    offset: float
    hysteresis: float
    rms: float
    samples: int
    torque: str
    min_speed: float = FIT_SPEED

    def to_dict(self) -> dict[str, float | int | str | None]:
        """JSON-ready."""
        return {
            "compliance": self.compliance,
            "skew": self.skew,
            "offset": self.offset,
            "hysteresis": self.hysteresis,
            "rms": self.rms,
            "samples": self.samples,
            "torque": self.torque,
        }


def _design(torque: np.ndarray, vm: np.ndarray) -> np.ndarray:
    """Offset, wind-up, skew and hysteresis."""
    return np.column_stack([np.ones_like(vm), torque, vm, np.sign(vm)])


def _fit_rows(vm: np.ndarray, d: np.ndarray, torque: np.ndarray, min_speed: float) -> np.ndarray:
    """The samples fitted: the motor faster than ``min_speed`` (or half its peak speed, if
    that is less: a slow recording), every value finite."""
    fast = move_threshold(vm, min_speed)
    return np.flatnonzero((np.abs(vm) > fast) & np.isfinite(d) & np.isfinite(torque)
                          & np.isfinite(vm))  # fmt: skip


def _solve(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    return np.asarray(coef)


def _check_min_speed(min_speed: float) -> None:
    if not (min_speed >= 0 and math.isfinite(min_speed)):
        raise ParameterError.of("min_speed", f"must be a speed >= 0 in deg/s, got {min_speed!r}")


def fit_gear(rec: Recording, *, min_speed: float = FIT_SPEED) -> GearFit | None:
    """Fit the gear's compliance, the encoders' skew and the reversal error over a recording.

    Parameters
    ----------
    rec : Recording
        With MP, AP and AC (or RC), on the positions' own grid.
    min_speed : float
        deg/s the motor speed must exceed for a sample to be fitted (or half its peak speed
        where that is less: a slow recording).

    Returns
    -------
    GearFit or None
        None with fewer than 20 such samples or AP all NaN.

    Raises
    ------
    ChannelError
        No MP, AP or torque.

    References
    ----------
    Paper section 5.1 (backlash at the reversals); ISO 230-2 (reversal error).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.004)
    >>> mp = 10 * np.sin(t)
    >>> vm = 10 * np.cos(t)
    >>> torque = 3 * np.sin(2 * t)
    >>> ap = mp - (0.001 * torque + 0.003 * vm + 0.02 * np.sign(vm))
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP", "AC")}
    >>> rec = Recording(pd.DataFrame({"MP": mp, "AP": ap, "AC": torque},
    ...                              index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> fit = fit_gear(rec)
    >>> round(fit.compliance, 4), round(fit.skew, 4), round(fit.hysteresis, 3)
    (0.001, 0.003, 0.04)
    """
    _check_min_speed(min_speed)
    _, d, vm, torque = _columns(rec)
    use = _fit_rows(vm, d, torque, min_speed)
    if use.size < 20:
        return None
    x = _design(torque[use], vm[use])
    coef = _solve(x, d[use])
    rms = float(np.sqrt(np.mean((d[use] - x @ coef) ** 2)))
    return GearFit(
        compliance=float(coef[1]),
        skew=float(coef[2]),
        offset=float(coef[0]),
        hysteresis=float(2 * coef[3]),
        rms=rms,
        samples=int(use.size),
        torque=torque_column(rec),
        min_speed=min_speed,
    )


def gear_torque(rec: Recording, *, motor_inertia: float = 0.0) -> tuple[np.ndarray, float]:
    """The gear torque estimated from the motor torque, and its noise.

    The motor torque (or current) less the motor's own inertia torque ``motor_inertia * d VM /
    dt`` (0 by default: a recording does not say the motor's inertia), as a moving mean over 40
    ms (the torque ripples at 10-25 Hz on a real robot); its noise is the standard deviation of
    the torque about that mean, divided by the root of the samples averaged. The motor's own
    friction, which flips with the motor's direction, is left in: it cannot be told apart from
    the arm's in the motor torque (docs/validation/backlash.md). In a recording with gaps both are
    taken within each segment (NaN in a gap).

    Parameters
    ----------
    rec : Recording
        With MP and AC or RC.
    motor_inertia : float
        Torque units per deg/s**2 of the motor (joint side): the motor inertia times the gear
        ratio (times pi/180 for N m and kg m**2).

    Returns
    -------
    tuple
        The estimate per sample and its noise (torque units).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 1, 0.004)
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AC")}
    >>> rec = Recording(pd.DataFrame({"MP": t, "AC": np.where(t < 0.5, -2.0, 2.0)},
    ...                              index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> tau, noise = gear_torque(rec)
    >>> float(tau[0]), float(tau[-1]), noise < 0.5
    (-2.0, 2.0, True)
    """
    if "MP" not in rec.data.columns:
        raise ChannelError(rec.source or "<recording>", "no MP column")
    dt = rec.sample_period
    torque = rec.data[torque_column(rec)].to_numpy(dtype=np.float64)
    ticks = segment_ticks(rec)  # the whole recording when it has no gap
    if motor_inertia:
        vm = segment_velocity(rec, rec.data["MP"].to_numpy(dtype=np.float64))
        accel = np.full(vm.shape, np.nan)
        for a, b in ticks:
            if b - a >= 2:
                accel[a:b] = np.gradient(vm[a:b], dt)
        torque = torque - motor_inertia * accel
    n = max(1, round(_SMOOTH / dt))
    smooth = np.full(torque.shape, np.nan)
    for a, b in ticks:
        if b > a:
            padded = np.pad(torque[a:b], (n // 2, n - 1 - n // 2), mode="edge")
            smooth[a:b] = np.convolve(padded, np.ones(n) / n, mode="valid")
    scatter = torque - smooth
    noise = float(np.nanstd(scatter) / math.sqrt(n)) if np.isfinite(scatter).any() else math.nan
    return smooth, noise


def _unexplained(d: np.ndarray, torque: np.ndarray, vm: np.ndarray, compliance: float,
                 skew: float) -> np.ndarray:  # fmt: skip
    return d - compliance * torque - skew * vm


def unexplained(rec: Recording, gear: GearFit) -> np.ndarray:
    """``MP - AP`` less the gear's wind-up and the encoders' skew: what the reversal error steps.

    Parameters
    ----------
    rec : Recording
        With MP, AP and AC (or RC).
    gear : GearFit
        :func:`fit_gear` of the recording.

    Returns
    -------
    ndarray
        deg per sample, ``MP - AP - compliance * torque - skew * VM``.

    Raises
    ------
    ChannelError
        No MP, AP or torque.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.004)
    >>> mp, torque = 10 * np.sin(t), 3 * np.sin(2 * t)
    >>> ap = mp - (0.001 * torque + 0.003 * 10 * np.cos(t) + 0.02 * np.sign(np.cos(t)))
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP", "AC")}
    >>> rec = Recording(pd.DataFrame({"MP": mp, "AP": ap, "AC": torque},
    ...                              index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> rest = unexplained(rec, fit_gear(rec))
    >>> round(float(rest[100] - rest[-100]), 3)  # the direction's step: +0.02 out, -0.02 back
    0.04
    """
    _, d, vm, torque = _columns(rec)
    return _unexplained(d, torque, vm, gear.compliance, gear.skew)


def _windows(t: np.ndarray, change: DirectionChange, window: float) -> tuple[np.ndarray, ...]:
    """Indices of the stretch before the turn and of the one after it."""
    before = np.flatnonzero((t >= change.stop - window) & (t < change.stop))
    after = np.flatnonzero((t >= change.start) & (t < change.start + window))
    return before, after


def torque_traversed(
    rec: Recording, change: DirectionChange, *, motor_inertia: float = 0.0,
    window: float = WINDOW,
) -> bool:  # fmt: skip
    """Whether the gear torque changed sign at a direction change, beyond its noise.

    True when the gear torque (:func:`gear_torque`) lies below ``-2 noise`` and above ``+2
    noise`` within ``window`` s before the change's ``stop`` to ``window`` s after its
    ``start``: the gear then crosses its dead zone there (if it has one).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 2, 0.004)
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AC")}
    >>> change = DirectionChange(0.9, 1.1, 0.0, -1, "continuous", 1.0)
    >>> def rec(torque):
    ...     return Recording(pd.DataFrame({"MP": -(t - 1) ** 2, "AC": torque},
    ...                      index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> (torque_traversed(rec(-5 * (t - 1)), change),
    ...  torque_traversed(rec(-5 - 2 * (t - 1)), change))
    (True, False)
    """
    t = rec.data.index.to_numpy(dtype=np.float64)
    tau, noise = gear_torque(rec, motor_inertia=motor_inertia)
    near = (t >= change.stop - window) & (t <= change.start + window) & np.isfinite(tau)
    if not near.any() or not math.isfinite(noise):
        return False
    part = tau[near]
    return bool(part.min() < -_MARGIN * noise and part.max() > _MARGIN * noise)


@dataclass(frozen=True)
class ReversalError:
    """The lost motion at a continuous direction change (:func:`reversal_error`).

    Attributes
    ----------
    lost_motion : float
        deg, the step of ``MP - AP`` the torque and the speed do not explain, from before the
        turn to after it, in the old direction's sign (positive: the arm lags the motor more
        in each direction of motion). The estimate itself: it may be negative where the data
        cannot resolve the lost motion (:attr:`resolved`).
    low, high : float
        deg, the interval (95 %; :func:`reversal_error`): ``lost_motion - noise`` to
        ``lost_motion + noise + bias`` (``bias`` counted where it is bounded).
    traversed : bool
        The gear torque changed sign there (:func:`torque_traversed`).
    noise : float
        deg, the bootstrap's half-width (:func:`reversal_error`).
    bias : float
        deg, the bound of the motor friction's bias (:func:`friction_bias`): the estimate lies
        below the lost motion by at most this; NaN where it cannot be bounded.
    """

    lost_motion: float
    low: float
    high: float
    traversed: bool
    noise: float = math.nan
    bias: float = math.nan

    @property
    def terms(self) -> tuple[str, ...]:
        """The error terms the interval carries: ``"noise"``, and ``"motor friction bias"``
        where it is bounded."""
        return ("noise",) + (("motor friction bias",) if math.isfinite(self.bias) else ())

    @property
    def resolved(self) -> bool:
        """Whether the interval lies above 0: a lost motion the data resolve."""
        return bool(self.low > 0)


def _blocks(
    rng: np.random.Generator, n: int, size: int, firsts: np.ndarray | None = None
) -> np.ndarray:
    """A circular block bootstrap draw of ``n`` indices in blocks of ``size`` (circular: every
    sample as likely as any other, the ends included); with ``firsts`` (the index each segment
    starts at, 0 first) a block wraps round within the segment it starts in."""
    size = max(1, min(size, n))
    starts = rng.integers(0, n, size=-(-n // size))
    if firsts is None:
        return ((starts[:, None] + np.arange(size)[None, :]) % n).ravel()[:n]
    bounds = np.append(firsts, n)
    k = np.searchsorted(bounds, starts, side="right") - 1
    lo, length = bounds[k][:, None], (bounds[k + 1] - bounds[k])[:, None]
    return (lo + (starts[:, None] - lo + np.arange(size)[None, :]) % length).ravel()[:n]


def _firsts(rec: Recording, rows: np.ndarray) -> np.ndarray | None:
    """Where in ``rows`` (ticks within the segments, in order) each segment starts; None without
    gaps."""
    if not rec.gaps:
        return None
    firsts = np.searchsorted(rows, [a for a, _ in segment_ticks(rec)])
    firsts[0] = 0
    return firsts


def reversal_error(
    rec: Recording, change: DirectionChange, gear: GearFit | None = None, *,
    window: float = WINDOW, resamples: int = 400, level: float = 0.95, seed: int = 0,
    motor_inertia: float = 0.0, traversed: bool | None = None,
    refits: dict[tuple[int, ...], list[np.ndarray]] | None = None,
) -> ReversalError:  # fmt: skip
    """The lost motion at a direction change in continuous motion, with an interval.

    The interval carries two error terms (:attr:`ReversalError.terms`): the noise (a
    bootstrap, below) and the motor friction's bias. The motor torque holds the motor's own
    friction, which never reaches the gear and flips with the motor's direction; taking the
    gear's wind-up as ``compliance * torque`` counts it as wind-up, and the step measured falls
    short of the lost motion by ``2 * compliance * F_motor``. That is bounded by
    :func:`friction_bias` and added to the interval's upper end only.

    Parameters
    ----------
    rec : Recording
        With MP, AP and AC (or RC) on the positions' own grid.
    change : DirectionChange
        Its ``stop`` and ``start`` bracket the turn (a ``"continuous"`` change).
    gear : GearFit, optional
        :func:`fit_gear` of the same recording (fitted here when omitted).
    window : float
        s of each stretch, before ``stop`` and after ``start``, whose means are compared.
    resamples : int
        Bootstrap resamples: blocks of 50 ms of the fit's samples and of each stretch drawn
        with replacement (circular), the gear refitted and the step measured again on each;
        the interval is the step -+ a t quantile (degrees of freedom: the stretches' blocks
        less two) times the resamples' standard deviation.
    level : float
        The interval's coverage.
    seed : int
        Of the bootstrap.
    motor_inertia : float
        For ``traversed`` (:func:`gear_torque`).
    traversed : bool, optional
        :func:`torque_traversed` at ``change`` with this ``motor_inertia`` and ``window``
        (computed here when omitted).
    refits : dict, optional
        The bootstrap's gear refits, shared by the calls on one recording and ``gear``; same values.

    Returns
    -------
    ReversalError
        NaN lost motion (and interval) without AP there or without a gear fit.

    References
    ----------
    Paper section 5.1; ISO 230-2 (reversal error).

    Examples
    --------
    An arm lagging its motor by 0.01 deg more in each direction (0.02 deg lost motion), a
    gear winding up 0.001 deg per N m and encoders 3 ms apart:

    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> from funcnet.diagnosis.reversals import find_direction_changes
    >>> t = np.arange(0, 6, 0.004)
    >>> mp = 10 * np.sin(t)
    >>> vm = 10 * np.cos(t)
    >>> torque = 3 * np.sin(2 * t) + 0.3 * np.sign(vm)
    >>> rng = np.random.default_rng(1)
    >>> ap = mp - (0.001 * torque + 0.003 * vm + 0.01 * np.sign(vm)
    ...            + 0.001 * rng.standard_normal(t.size))
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("RP", "MP", "AP", "AC")}
    >>> rec = Recording(pd.DataFrame({"RP": mp, "MP": mp, "AP": ap, "AC": torque},
    ...                              index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> change = find_direction_changes(rec)[0]
    >>> error = reversal_error(rec, change)
    >>> round(error.lost_motion, 3), error.noise < 0.001, error.traversed
    (0.02, True, True)
    >>> error.terms, math.isclose(error.high, error.lost_motion + error.noise + error.bias)
    (('noise', 'motor friction bias'), True)
    """
    if not (window > 0 and resamples >= 0 and 0 < level < 1):
        raise ParameterError.of("window", "must be > 0 s, resamples >= 0, level in (0, 1)")
    gear = fit_gear(rec) if gear is None else gear
    if traversed is None:
        traversed = torque_traversed(rec, change, motor_inertia=motor_inertia, window=window)
    nan = ReversalError(math.nan, math.nan, math.nan, traversed)
    if gear is None:
        return nan
    t, d, vm, torque = _columns(rec)
    before, after = _windows(t, change, window)
    before = before[np.isfinite(d[before]) & np.isfinite(torque[before])]
    after = after[np.isfinite(d[after]) & np.isfinite(torque[after])]
    if before.size < 3 or after.size < 3:
        return nan
    old = -change.direction

    def step(c: float, skew: float, b: np.ndarray, a: np.ndarray) -> float:
        return float(old * (_unexplained(d[b], torque[b], vm[b], c, skew).mean()
                            - _unexplained(d[a], torque[a], vm[a], c, skew).mean()))

    point = step(gear.compliance, gear.skew, before, after)
    fitted = _fit_rows(vm, d, torque, gear.min_speed)
    firsts = _firsts(rec, fitted)
    rng = np.random.default_rng(seed)
    block = max(1, round(_BLOCK / rec.sample_period))
    key = (seed, resamples, block, before.size, after.size)  # sets the generator's states
    known = refits.get(key) if refits is not None else None
    coefs = known if known is not None else []
    draws = []
    for r in range(resamples):
        if known is None:
            rows = fitted[_blocks(rng, fitted.size, block, firsts)]
            coefs.append(_solve(_design(torque[rows], vm[rows]), d[rows]))
        else:  # the same draw (the generator's state), its refit known
            rng.integers(0, fitted.size, size=-(-fitted.size // max(1, min(block, fitted.size))))
        draws.append(step(coefs[r][1], coefs[r][2], before[_blocks(rng, before.size, block)],
                          after[_blocks(rng, after.size, block)]))  # fmt: skip
    if refits is not None:
        refits[key] = coefs
    # the stretches hold a few blocks each, so the bootstrap's spread is itself uncertain: a
    # t quantile with as many degrees of freedom as blocks in both less two (as batch means)
    dof = max(1, -(-before.size // block) + -(-after.size // block) - 2)
    half = float(special.stdtrit(dof, (1 + level) / 2) * np.std(draws)) if draws else 0.0
    bias = friction_bias(t, torque, gear.compliance, before, after, change)
    upper = point + half + (bias if math.isfinite(bias) else 0.0)
    return ReversalError(point, point - half, upper, traversed, half, bias)


def friction_bias(t: np.ndarray, torque: np.ndarray, compliance: float, before: np.ndarray,
                  after: np.ndarray, change: DirectionChange) -> float:
    """The bound of the motor friction's bias of a reversal error (deg, at least 0).

    The torque's smooth part (the arm's weight and inertia) runs on through the turn; its
    friction (the motor's and the gear's) jumps by twice their sum where the motor turns. A
    straight line fitted to the torque over each stretch beside the turn, both read at the
    turn, gives that jump ``J``; the motor's share ``2 F_motor`` is at most ``|J|``, so the
    bias ``2 * compliance * F_motor`` is at most ``|compliance * J|``.

    Parameters
    ----------
    t, torque : ndarray
        Times and the motor torque (or current) of the recording.
    compliance : float
        The gear's (:class:`GearFit`).
    before, after : ndarray of int
        The stretches' ticks (finite torque).
    change : DirectionChange
        Its ``turn`` (else the middle of ``stop`` and ``start``) is where the lines are read.

    Returns
    -------
    float
        NaN with fewer than three ticks in a stretch.

    Examples
    --------
    >>> from funcnet.diagnosis.reversals import DirectionChange
    >>> t = np.arange(0, 2, 0.004)
    >>> torque = 3 * t + np.where(t < 1, -0.5, 0.5)  # a ramp, friction jumping by 1 at 1 s
    >>> change = DirectionChange(0.9, 1.1, 0.0, -1, "continuous", 1.0)
    >>> before = np.flatnonzero((t >= 0.65) & (t < 0.9))
    >>> after = np.flatnonzero((t >= 1.1) & (t < 1.35))
    >>> round(friction_bias(t, torque, 0.002, before, after, change), 6)
    0.002
    """
    if before.size < 3 or after.size < 3:
        return math.nan
    at = change.turn if change.turn is not None else 0.5 * (change.stop + change.start)
    ends = [np.polyval(np.polyfit(t[part] - at, torque[part], 1), 0.0)
            for part in (before, after)]
    return float(abs(compliance * (ends[1] - ends[0])))
