"""Backlash indicators at one direction change: physical baselines and functional-network features.

Each indicator is a number computed from one reversal of a trace (:mod:`.reversals`); higher
means more backlash for every one of them except where noted. Motor-side indicators read only
RP (to find the moves), MP, RC and AC -- what a robot without the arm-side encoder logs; the
two-encoder lost motion and the paper's signature need AP too.

Physical indicators
-------------------
``lost_motion`` (deg, needs AP)
    The change of ``MP - AP`` across the reversal: at the motor's turning point (MP's extreme)
    minus at the arm's restart, where ``AP`` leaves its own turning point's reading (the arm
    may still coast forward into the dead zone after the motor has turned: that counts). The
    restart is placed between ticks by fitting ``cbrt(|AP - AP_rest|)`` linearly in time over
    the ticks that moved 2-20 encoder steps (the arm leaves its rest as the gear's torque
    builds up: its distance grows as ``t**3``; the reading's difference from the rest reading
    is taken as the distance, both roundings being symmetric), and MP is interpolated there.
    This is the manifest's ``lost_motion`` (:class:`funcnet.robot.sim.axis.SimulatedTrial`):
    dead zone plus the gear's wind-up on both flanks, plus the arm's coast. After a
    standstill: the motor's travel from its rest to the arm's restart.
``motor_hysteresis`` (deg, motor side: RP and MP)
    The motor's lead on the set-point ``MP - RP`` where the set-point runs at half its peak
    speed before the reversal, minus the same after it (sign: old direction). The position
    loop's lag changes sign with the direction; the gear's dead zone and wind-up add to it.
``motor_travel`` (deg, motor side)
    The motor travel from its turning point to the gear's contact, placed where a two-level fit
    of the current set-point ``RC`` (20 ms smoothing, new direction) splits, over the motor's
    way back from 0.002 to 0.15 deg from its turning point: the motor crosses the dead zone
    with its own load only and takes up the arm's when the gear closes.
``current_dwell`` (s, motor side)
    The time from the motor leaving its turning point (0.002 deg) to that contact.
``current_step`` (A, motor side)
    The two levels' difference (after minus before the contact).
``vibration`` (deg/s, motor side)
    The RMS of the motor speed ``VM`` minus its 40 ms moving average over 0.4 s after the
    turning point: the vibration backlash leaves on the motor speed at a direction change
    (J. Intell. Manuf. 2022, doi 10.1007/s10845-022-01934-z).

Functional-network indicators (motor side: nodes MP, VM, RC, AC)
----------------------------------------------------------------
Networks (:func:`funcnet.network.functional_network`, default parameters) in a 0.6 s window
from 0.1 s before the turn (the dead-zone crossing) and in the 0.6 s before that (the braking
of the first move), and the differences reversal - braking of: ``fn_asymmetry`` (mean of
``|c_diff| + |t_diff|`` over pairs), ``fn_edges`` (number of edges) and ``fn_vm_out`` (sum of
the weights of VM's out-edges) and, with ``evidence=True``, ``fn_coupled`` (the pairs the
coupling test of :mod:`funcnet.evidence` finds coupled, against time-shift surrogates).

The paper's signature (section 5.1; needs AP)
---------------------------------------------
In the 0.6 s reversal window with the paper's nodes RP, AP, MP, V, RC, AC: ``signature`` is 1
when V has a directed edge to every other node and the positions are ordered MP -> AP -> RP
(edges MP -> AP and AP -> RP), else 0.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from funcnet.diagnosis.reversals import DirectionChange
from funcnet.errors import FuncnetError, FuncnetWarning
from funcnet.parameters import NetworkParameters
from funcnet.robot.recording import Recording

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = [
    "PHYSICAL",
    "FN_FEATURES",
    "INDICATORS",
    "MOTOR_SIDE",
    "reversal_indicators",
    "lost_motion",
]

#: Physical indicators (the baselines).
PHYSICAL = (
    "lost_motion",
    "motor_hysteresis",
    "motor_travel",
    "current_dwell",
    "current_step",
    "vibration",
)
#: Functional-network indicators on motor-side nodes.
FN_FEATURES = ("fn_asymmetry", "fn_edges", "fn_vm_out", "fn_coupled")
#: Every indicator :func:`reversal_indicators` returns, the paper's signature last.
INDICATORS = PHYSICAL + FN_FEATURES + ("signature",)
#: Indicators that need only motor-side signals (RP, MP, RC, AC).
MOTOR_SIDE = (
    "motor_hysteresis",
    "motor_travel",
    "current_dwell",
    "current_step",
    "vibration",
) + FN_FEATURES

_MOTOR_NODES = ("MP", "VM", "RC", "AC")
_PAPER_NODES = ("RP", "AP", "MP", "V", "RC", "AC")
_WINDOW = 0.6  # s, the paper's cruise and braking window length (section 4.2)
_LEAD = 0.1  # s of the reversal window before the turning point
# The arm's distance from its rest after the restart grows as (t - t0)**3 while the gear's
# torque builds up with the motor's travel (a jerk-driven start); fitted over its first 1-20
# encoder steps, before the acceleration settles into a parabola
_RESTART_POWER = 3.0


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


def lost_motion(rec: Recording, change: DirectionChange, turn: int | None = None) -> float:
    """Two-encoder lost motion at a direction change, in deg (NaN if the arm never restarts).

    Parameters
    ----------
    rec : Recording
        With MP and AP on the positions' own grid (:func:`.motor_side_recording`).
    change : DirectionChange
    turn : int, optional
        Index of the motor's turning point (found from MP when omitted).

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
    turn = _turn(rec, change) if turn is None else turn
    new = change.direction
    steps = np.abs(np.diff(ap))
    quantum = float(steps[steps > 0].min()) if np.any(steps > 0) else 1e-9
    threshold = 1.5 * quantum
    if change.kind == "reversal":
        # the arm's own turning point: it may still coast (or bounce) after the motor's turn
        b = _index(t, change.start + min(change.dwell, 1.0) + 0.5)
        rest_at = turn + int(np.argmax(-new * ap[turn : b + 1]))
        rest = float(ap[rest_at])
    else:  # a resting arm's reading jitters by an encoder step or two
        rest_at = turn
        before = ap[_index(t, change.start - 0.2) : _index(t, change.start) + 1]
        rest = float(np.median(before))
        threshold = max(threshold, 4 * float(np.std(before)), float(np.ptp(before)))
    moved = np.flatnonzero(new * (ap[rest_at:] - rest) > threshold)
    if moved.size == 0:
        return math.nan
    first = rest_at + int(moved[0])

    # the restart between ticks: the arm leaves its rest as the gear's torque builds up, the
    # distance growing as (t - t0)**3, so its cube root grows linearly from the restart t0; the
    # arm creeps below one encoder step for several ticks, so t0 may lie up to 8 ticks back.
    # The reading's difference from the rest reading is the distance itself: both readings round
    # to the nearest step, errors symmetric about zero (no half-step offset, which would bias
    # the distance up and place t0 early)
    fit = np.arange(first, min(first + 8, t.size))
    distance = new * (ap[fit] - rest)
    near = (distance > quantum) & (distance < 20 * quantum)
    fit, distance = fit[near], distance[near]
    restart = t[first - 1]
    if fit.size >= 2:
        slope, intercept = np.polyfit(t[fit], distance ** (1 / _RESTART_POWER), 1)
        if slope > 0:
            # after a standstill the rest reading jitters by a step or two and a creep cannot
            # be told from it: the restart is placed at most two ticks before the first move
            back = 8 if change.kind == "reversal" else 2
            restart = float(np.clip(-intercept / slope, t[max(rest_at, first - back)], t[first]))
    if change.kind != "reversal":  # the arm rested since long before the motor turned
        return float(abs(mp[turn] - np.interp(restart, t, mp)))
    # MP - AP across the reversal (old direction's sign): at the motor's turning point minus at
    # the restart, where the arm still reads its rest; the motor's travel when the arm rests at
    # the turn, and what the arm still coasts forward after it counts too
    old = -new
    return float(old * (mp[turn] - ap[turn]) - old * (np.interp(restart, t, mp) - rest))


def _smooth(x: np.ndarray, n: int) -> np.ndarray:
    n = max(1, n)
    kernel = np.ones(n) / n
    padded = np.pad(x, (n // 2, n - 1 - n // 2), mode="edge")
    return np.convolve(padded, kernel, mode="valid")


def _physical(rec: Recording, change: DirectionChange, turn: int) -> dict[str, float]:
    t = rec.data.index.to_numpy()
    dt = rec.sample_period
    new = change.direction
    mp = _values(rec, "MP")
    current = "RC" if "RC" in rec.data.columns else "AC"
    c = new * _smooth(_values(rec, current), round(0.02 / dt))
    # the gear's contact: where the motor, moving back freely, takes up the arm's load -- the
    # steepest rise of the current (new direction) once the motor has left its turning point
    travel = np.abs(mp - mp[turn])
    end = _index(t, t[turn] + 0.8)
    moving = np.flatnonzero((travel[turn:end] > 0.002) & (travel[turn:end] < 0.15)) + turn
    if moving.size >= 4:
        # a two-level fit of the current along the move: the split with the least squared
        # error (robust to the ripple that makes the steepest rise wander)
        part = c[moving]
        k = np.arange(1, part.size)
        left_sum, total = np.cumsum(part)[:-1], part.sum()
        left_sq, total_sq = np.cumsum(part**2)[:-1], (part**2).sum()
        sse = (left_sq - left_sum**2 / k) + (
            (total_sq - left_sq) - (total - left_sum) ** 2 / (part.size - k)
        )
        split = int(np.argmin(sse)) + 1
        at = int(moving[split])
        left = moving[0]
        step = float(part[split:].mean() - part[:split].mean())
    else:
        at, left, step = turn, turn, math.nan
    vm = _values(rec, "VM")
    after = slice(turn, _index(t, t[turn] + 0.4))
    residual = vm[after] - _smooth(vm, round(0.04 / dt))[after]
    # the motor's lead on the set-point, at the reversal phase's two ends (half the peak speed
    # on either side): the loop's lag flips sign, the gear's dead zone and wind-up add to it
    rp = _values(rec, "RP")
    v_rp = np.abs(np.gradient(rp, dt))
    lo, hi = _index(t, change.stop - 1.0), _index(t, change.start + 1.2)
    peak_a = v_rp[lo:turn].max() if turn > lo else 0.0
    peak_b = v_rp[turn:hi].max() if hi > turn else 0.0
    a_side = np.flatnonzero(v_rp[lo:turn] >= 0.5 * peak_a)
    b_side = np.flatnonzero(v_rp[turn:hi] >= 0.5 * peak_b)
    hysteresis = math.nan
    if a_side.size and b_side.size:
        ia, ib = lo + int(a_side[-1]), turn + int(b_side[0])
        hysteresis = float(-new * ((mp[ia] - rp[ia]) - (mp[ib] - rp[ib])))
    result = {
        "motor_hysteresis": hysteresis,
        "motor_travel": float(travel[at]),
        "current_dwell": float(t[at] - t[left]),
        "current_step": step,
        "vibration": float(np.sqrt(np.mean(residual**2))) if residual.size else math.nan,
        "lost_motion": lost_motion(rec, change, turn) if "AP" in rec.data.columns else math.nan,
    }
    return result


def _network(rec: Recording, start: float, nodes: Sequence[str], parameters: NetworkParameters,
             evidence: bool = False) -> FunctionalNetwork | None:  # fmt: skip
    from funcnet.network import functional_network  # the physical indicators do without

    part = rec.window(start, start + _WINDOW).data[list(nodes)]
    values = part.to_numpy(dtype=np.float64)
    if values.shape[0] < 50 or np.isnan(values).any() or np.any(np.ptp(values, axis=0) == 0):
        return None
    try:
        with warnings.catch_warnings():  # flags stay in the pairs table; nothing to say here
            warnings.simplefilter("ignore", FuncnetWarning)
            if evidence:  # the coupling test; one half-sample (intervals are not used here)
                return functional_network(
                    part, parameters=parameters, warn=False, evidence=True, resamples=1
                )
            return functional_network(part, parameters=parameters, warn=False)
    except FuncnetError:
        return None


def _fn_summary(net: FunctionalNetwork | None) -> tuple[float, float, float, float]:
    if net is None:
        return math.nan, math.nan, math.nan, math.nan
    pairs = net.pairs
    asym = float(np.mean(np.abs(pairs["c_diff"]) + np.abs(pairs["t_diff"])))
    edges = net.edges
    vm_out = float(edges.loc[edges["source"] == "VM", "weight"].abs().sum())
    coupled = float(pairs["coupled"].sum()) if "coupled" in pairs else math.nan
    return asym, float(len(edges)), vm_out, coupled


def _signature(net: FunctionalNetwork | None) -> float:
    if net is None:
        return math.nan
    edges = net.edges
    directed = set(zip(edges["source"], edges["target"], strict=True))
    velocity_drives = all(("V", other) in directed for other in net.nodes if other != "V")
    ordered = ("MP", "AP") in directed and ("AP", "RP") in directed
    return float(velocity_drives and ordered)


def reversal_indicators(
    rec: Recording,
    change: DirectionChange,
    *,
    parameters: NetworkParameters | None = None,
    networks: bool = True,
    evidence: bool = False,
) -> dict[str, Any]:
    """Every indicator of :data:`INDICATORS` at one direction change.

    Parameters
    ----------
    rec : Recording
        From :func:`.motor_side_recording` (MP, VM, RC and/or AC; AP and V optional).
    change : DirectionChange
    parameters : NetworkParameters, optional
        For the functional networks (default :class:`~funcnet.NetworkParameters`).
    networks : bool
        Compute the functional-network features and the signature (NaN when False).
    evidence : bool
        Build the motor-side networks with the coupling test of :mod:`funcnet.evidence`
        (``fn_coupled``; NaN without it).

    Returns
    -------
    dict
        Indicator -> float (NaN where it cannot be computed), plus ``turn_time`` (s).

    References
    ----------
    Paper section 4.3 and 5.1 (reversal windows, the signature); Eq. 11-12 (VM from MP).

    Examples
    --------
    >>> sorted(INDICATORS)[:3]
    ['current_dwell', 'current_step', 'fn_asymmetry']
    """
    p = NetworkParameters() if parameters is None else parameters
    turn = _turn(rec, change)
    t_turn = float(rec.data.index[turn])
    result: dict[str, Any] = {"turn_time": t_turn}
    result.update(_physical(rec, change, turn))
    names = FN_FEATURES
    if networks and all(n in rec.data.columns for n in _MOTOR_NODES):
        start = t_turn - _LEAD
        after = _fn_summary(_network(rec, start, _MOTOR_NODES, p, evidence))
        before = _fn_summary(_network(rec, start - _WINDOW, _MOTOR_NODES, p, evidence))
        result.update({n: a - b for n, a, b in zip(names, after, before, strict=True)})
    else:
        result.update(dict.fromkeys(names, math.nan))
    if networks and all(n in rec.data.columns for n in _PAPER_NODES):
        result["signature"] = _signature(_network(rec, t_turn - _LEAD, _PAPER_NODES, p))
    else:
        result["signature"] = math.nan
    return result


def indicator_frame(rows: Sequence[dict[str, Any]]) -> pd.DataFrame:
    """Rows of indicators as a table with the :data:`INDICATORS` columns (helper)."""
    return pd.DataFrame(list(rows), columns=["turn_time", *INDICATORS])
