"""Backlash told from friction in the gear's fit, where the gear torque's sign allows.

The reversal error of :func:`~funcnet.diagnosis.reversal_error.fit_gear` is the backlash (a dead
zone, crossed only where the gear torque changes sign) plus the friction in the gear, which flips
with the direction of motion. :func:`gear_parts` fits the two sign terms together and tells them
apart where the torque and the direction disagree in sign often enough; else it says why not (a
load keeping the torque on one flank).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from funcnet.diagnosis.reversal_error import (
    _BLOCK,
    _MARGIN,
    FIT_SPEED,
    _blocks,
    _check_min_speed,
    _columns,
    _design,
    _firsts,
    _fit_rows,
    _solve,
    gear_torque,
)
from funcnet.errors import ParameterError
from funcnet.robot.recording import Recording

__all__ = ["GearParts", "gear_parts", "PARTS_SHARE"]


#: The share of the fitted samples that must hold each sign of the gear torque, and that must
#: (and must not) have the torque's sign differ from the motor's direction, for a dead zone to be
#: told from the friction that flips with the direction.
PARTS_SHARE = 0.05


@dataclass(frozen=True)
class GearParts:
    """The lost motion told apart, where the recording allows (:func:`gear_parts`).

    Attributes
    ----------
    dead_zone : float or None
        deg: twice the term that flips with the gear torque's sign -- the backlash, crossed
        only where the torque changes sign. None where it cannot be told from ``friction``.
    dead_zone_low, dead_zone_high : float or None
        deg, its 95 % block-bootstrap interval.
    friction : float or None
        deg: twice the term that flips with the motor's direction -- the friction's share of
        the reversal error (with the motor's own friction in the motor torque). None with
        ``dead_zone``.
    friction_low, friction_high : float or None
        deg, its 95 % block-bootstrap interval.
    compliance : float or None
        deg per torque unit in the same fit: the elastic wind-up.
    disagreeing : float
        The share of the fitted samples (gear torque beyond its noise) whose torque and
        direction differ in sign: what separates the two terms.
    samples : int
        Samples fitted.
    reason : str or None
        Why ``dead_zone`` is None.
    """

    dead_zone: float | None
    dead_zone_low: float | None
    dead_zone_high: float | None
    friction: float | None
    friction_low: float | None
    friction_high: float | None
    compliance: float | None
    disagreeing: float
    samples: int
    reason: str | None

    def to_dict(self) -> dict[str, float | int | str | None]:
        """JSON-ready."""
        return dataclasses.asdict(self)


def gear_parts(
    rec: Recording, *, min_speed: float = FIT_SPEED, resamples: int = 200, seed: int = 0
) -> GearParts:
    """Tell the lost motion's backlash from its friction, where the torque's sign allows.

    Fits, over the samples where the motor moves faster than ``min_speed`` and the gear torque
    (:func:`gear_torque`) lies beyond twice its noise,

    ``MP - AP = offset + compliance * torque + skew * VM + friction / 2 * sign(VM)
    + dead_zone / 2 * sign(gear torque)``.

    The dead zone is crossed only where the torque changes sign, and the two sign terms are told
    apart only by the samples where the torque and the direction disagree (the arm's inertia
    against its friction, decelerating; a load overcome): each torque sign, and the torque and
    direction both differing and agreeing, on at least :data:`PARTS_SHARE` of the samples, else
    ``dead_zone`` is None with the reason (a load keeping the torque on one flank). The motor's own
    friction stays in the motor torque and so in ``friction`` (docs/validation/backlash.md).

    Parameters
    ----------
    rec : Recording
        With MP, AP and AC (or RC).
    min_speed : float
        deg/s, as :func:`fit_gear`.
    resamples : int
        Bootstrap resamples of the intervals: the fitted samples drawn in blocks of 50 ms
        (circular), the fit redone; the 2.5 and 97.5 % percentiles (0: no interval).
    seed : int
        Of the bootstrap.

    Returns
    -------
    GearParts

    Raises
    ------
    ChannelError
        No MP, AP or torque.
    ParameterError
        ``min_speed`` not a speed >= 0.

    References
    ----------
    Paper section 5.1 (backlash at the reversals); ISO 230-2 (reversal error).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 8, 0.004)
    >>> mp = 10 * np.sin(t)
    >>> torque = 3 * np.sin(t + 1.0)  # leads the direction: the signs disagree a sixth of the time
    >>> ap = mp - (0.001 * torque + 0.01 * np.sign(torque) + 0.004 * np.sign(np.cos(t)))
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP", "AC")}
    >>> rec = Recording(pd.DataFrame({"MP": mp, "AP": ap, "AC": torque},
    ...                              index=pd.Index(t, name="time")), {}, info, sample_period=0.004)
    >>> parts = gear_parts(rec)
    >>> round(parts.dead_zone, 3), round(parts.friction, 3), round(parts.compliance, 4)
    (0.02, 0.008, 0.001)
    """
    _check_min_speed(min_speed)
    if not (isinstance(resamples, int) and resamples >= 0):
        raise ParameterError.of("resamples", f"must be an integer >= 0, got {resamples!r}")
    _, d, vm, torque = _columns(rec)
    tau, noise = gear_torque(rec)
    use = _fit_rows(vm, d, torque, min_speed)
    use = use[np.abs(tau[use]) > max(_MARGIN * noise, 0.1 * float(np.nanmax(np.abs(tau))))]
    direction, flank = np.sign(vm[use]), np.sign(tau[use])
    disagreeing = float(np.mean(direction != flank)) if use.size else 0.0
    negative = float(np.mean(flank < 0)) if use.size else 0.0
    if use.size < 20 or min(negative, 1 - negative) < PARTS_SHARE:
        reason = "the gear torque keeps one sign: the dead zone is not crossed"
    elif min(disagreeing, 1 - disagreeing) < PARTS_SHARE:
        reason = (f"the gear torque and the direction differ in sign on {disagreeing:.1%} of "
                  f"the samples (at least {PARTS_SHARE:.0%} and at most "
                  f"{1 - PARTS_SHARE:.0%} tell backlash from friction)")  # fmt: skip
    else:
        reason = None
    if reason is not None:
        return GearParts(None, None, None, None, None, None, None, disagreeing, int(use.size),
                         reason)  # fmt: skip
    x, y = np.column_stack([_design(torque[use], vm[use]), flank]), d[use]
    coef = _solve(x, y)
    rng = np.random.default_rng(seed)
    block = max(1, round(_BLOCK / rec.sample_period))
    firsts = _firsts(rec, use)  # no block across a gap
    draws = np.array([_solve(x[rows], y[rows])[3:] for rows in
                      (_blocks(rng, use.size, block, firsts) for _ in range(resamples))])
    low, high = (2 * np.percentile(draws, [2.5, 97.5], axis=0) if resamples
                 else np.full((2, 2), math.nan))  # fmt: skip
    return GearParts(
        dead_zone=float(2 * coef[4]), dead_zone_low=float(low[1]), dead_zone_high=float(high[1]),
        friction=float(2 * coef[3]), friction_low=float(low[0]), friction_high=float(high[0]),
        compliance=float(coef[1]), disagreeing=disagreeing, samples=int(use.size), reason=None,
    )
