"""Backlash indicators at one direction change: physical baselines and functional-network features.

Each indicator is a number computed from one reversal of a trace (:mod:`.reversals`); higher
means more backlash for every one of them except where noted. Motor-side indicators read only
RP (to find the moves), MP, RC and AC -- what a robot without the arm-side encoder logs; the
two-encoder lost motion and the paper's signature need AP too.

Physical indicators
-------------------
``lost_motion`` (deg, needs AP)
    The change of ``MP - AP`` across the reversal, from the motor's turning point to the arm's
    restart (:mod:`.two_encoder`): the dead zone plus the gear's wind-up on both flanks, plus
    what the arm still coasts forward after the motor has turned.
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
coupling test of :mod:`funcnet.evidence` finds coupled, against time-shift surrogates). The two
windows' networks come from one batched call (:func:`funcnet.pipeline.window_networks`: the
numbers of ``functional_network`` per window); the coupling test runs alone, without the
half-sampling intervals (``resamples=0``), which ``fn_coupled`` does not use.

The paper's signature (section 5.1; needs AP)
---------------------------------------------
In the 0.6 s reversal window with the paper's nodes RP, AP, MP, V, RC, AC: ``signature`` is 1
when V has a directed edge to every other node and the positions are ordered MP -> AP -> RP
(edges MP -> AP and AP -> RP), else 0.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from funcnet.diagnosis.reversals import DirectionChange
from funcnet.diagnosis.two_encoder import (
    ArmStart,
    _index,
    _turn,
    _values,
    first_start,
    lost_motion,
)
from funcnet.errors import FuncnetError, ParameterError
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
    "CONTACT_FEATURES",
    "with_contact_score",
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


def _smooth(x: np.ndarray, n: int) -> np.ndarray:
    n = max(1, n)
    kernel = np.ones(n) / n
    padded = np.pad(x, (n // 2, n - 1 - n // 2), mode="edge")
    return np.convolve(padded, kernel, mode="valid")


def _physical(
    rec: Recording, change: DirectionChange, turn: int, arm_start: ArmStart | None
) -> dict[str, float]:
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
    lost = math.nan
    if "AP" in rec.data.columns:
        axis = None
        if change.kind == "reversal":
            axis = first_start(rec) if arm_start is None else arm_start
        lost = lost_motion(rec, change, turn, axis=axis)
    result = {
        "motor_hysteresis": hysteresis,
        "motor_travel": float(travel[at]),
        "current_dwell": float(t[at] - t[left]),
        "current_step": step,
        "vibration": float(np.sqrt(np.mean(residual**2))) if residual.size else math.nan,
        "lost_motion": lost,
    }
    return result


def _part(rec: Recording, start: float, nodes: Sequence[str]) -> np.ndarray | None:
    """The window's values of ``nodes``; None where no network can be built (too short, NaN,
    a constant node)."""
    values = rec.window(start, start + _WINDOW).data[list(nodes)].to_numpy(dtype=np.float64)
    if values.shape[0] < 50 or np.isnan(values).any() or np.any(np.ptp(values, axis=0) == 0):
        return None
    return values


def _networks(rec: Recording, starts: Sequence[float], nodes: Sequence[str],
              parameters: NetworkParameters, parts: Sequence[np.ndarray | None] | None = None
              ) -> list[FunctionalNetwork | None]:  # fmt: skip
    """The networks of 0.6 s windows from ``starts``, in one batched call.

    :func:`funcnet.pipeline.window_networks` computes the windows' pairs numbers together (the
    batched engine, numbers equal to :func:`funcnet.network.functional_network`'s per window);
    a window that cannot give a network is None, and any error there falls back to one
    network per window (each None on its own error). ``parts``: the windows' :func:`_part`,
    when the caller has them.
    """
    from funcnet.network import functional_network  # the physical indicators do without
    from funcnet.pipeline import window_networks
    from funcnet.robot.windows import Window

    if parts is None:
        parts = [_part(rec, start, nodes) for start in starts]
    usable = [k for k, part in enumerate(parts) if part is not None]
    found: list[FunctionalNetwork | None] = [None] * len(starts)
    # flags stay in the pairs table; nothing to say here (and no catch_warnings: the
    # diagnosis runs in threads beside other computations)
    try:
        windows = [Window(str(k), starts[k], starts[k] + _WINDOW) for k in usable]
        nets = window_networks(rec, windows, signals=list(nodes), parameters=parameters,
                               warn=False)
        for k in usable:
            found[k] = nets[str(k)]
    except FuncnetError:
        for k in usable:
            part = rec.window(starts[k], starts[k] + _WINDOW).data[list(nodes)]
            try:
                found[k] = functional_network(part, parameters=parameters, warn=False)
            except FuncnetError:
                found[k] = None
    return found


def _coupled(values: np.ndarray, nodes: Sequence[str], parameters: NetworkParameters,
             intervals: int = 0) -> float:
    """The pairs the coupling test of :mod:`funcnet.evidence` finds coupled in one window's
    ``values`` (from :func:`_part`).

    The test alone (time-shift surrogates, BH across the pairs at alpha 0.05), on the values
    ``functional_network(..., evidence=True)`` tests (min-max per window): its ``coupled``
    column does not depend on the half-sampling intervals, which are not computed
    (``resamples=0``) where :func:`funcnet.evidence.pairwise_evidence` allows it (else the
    smallest number, 1) unless ``intervals`` subsamples are asked for (to time them).
    """
    from funcnet.core.normalization import normalize
    from funcnet.evidence import pairwise_evidence

    try:
        values = normalize(values, parameters.normalize, names=list(nodes))
        found = pairwise_evidence([values[:, k] for k in range(values.shape[1])],
                                  names=list(nodes), parameters=parameters,
                                  resamples=intervals or _resamples())  # fmt: skip
    except FuncnetError:
        return math.nan
    return float(sum(e.coupled for e in found.values()))


@functools.cache
def _resamples() -> int:
    """Resamples to ask of :func:`~funcnet.evidence.pairwise_evidence`: 0 (the intervals are
    not used here) where the evidence module takes it, else its smallest, 1."""
    from funcnet.evidence.pairs import check_evidence_arguments

    try:
        check_evidence_arguments(None, 0.05, 0)
    except ParameterError:
        return 1
    return 0


def _fn_summary(net: FunctionalNetwork | None, coupled: float = math.nan
                ) -> tuple[float, float, float, float]:  # fmt: skip
    if net is None:
        return math.nan, math.nan, math.nan, math.nan
    pairs = net.pairs
    asym = float(np.mean(np.abs(pairs["c_diff"]) + np.abs(pairs["t_diff"])))
    edges = net.edges
    vm_out = float(edges.loc[edges["source"] == "VM", "weight"].abs().sum())
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
    intervals: int = 0,
    arm_start: ArmStart | None = None,
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
    intervals : int
        With ``evidence``: subsamples of the resampling intervals (0: none; they do not
        change ``fn_coupled``; a number > 0 only costs their time, for the timing of the sweep
        with intervals).
    arm_start : ArmStart, optional
        The arm's first start from rest in ``rec`` (:func:`.first_start`), for the lost motion;
        found in ``rec`` when omitted (pass it to fit it once for several reversals).

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
    result.update(_physical(rec, change, turn, arm_start))
    names = FN_FEATURES
    if networks and all(n in rec.data.columns for n in _MOTOR_NODES):
        # the reversal window (the dead-zone crossing) and the braking before it, batched
        starts = (t_turn - _LEAD, t_turn - _LEAD - _WINDOW)
        parts = [_part(rec, start, _MOTOR_NODES) for start in starts]
        nets = _networks(rec, starts, _MOTOR_NODES, p, parts)
        coupled = [
            _coupled(part, _MOTOR_NODES, p, intervals)
            if evidence and net is not None and part is not None else math.nan
            for part, net in zip(parts, nets, strict=True)
        ]
        after, before = (_fn_summary(n, c) for n, c in zip(nets, coupled, strict=True))
        result.update({n: a - b for n, a, b in zip(names, after, before, strict=True)})
    else:
        result.update(dict.fromkeys(names, math.nan))
    if networks and all(n in rec.data.columns for n in _PAPER_NODES):
        result["signature"] = _signature(_networks(rec, [t_turn - _LEAD], _PAPER_NODES, p)[0])
    else:
        result["signature"] = math.nan
    return result


#: The motor-side features ``motor_contact`` adds up (:func:`with_contact_score`): where the gear
#: closes and how much load the motor takes up there.
CONTACT_FEATURES = ("motor_travel", "current_step")

def with_contact_score(
    table: pd.DataFrame, reference: dict[str, Any], *, by: str = "peak_speed"
) -> pd.DataFrame:
    """``table`` with ``motor_contact``: the features' robust z-scores against no backlash, summed.

    Each of :data:`CONTACT_FEATURES` is centred on its median without backlash at the nearest
    reference speed and divided by its interquartile range there; the two are added (higher =
    more backlash). It is the motor-side score of an axis whose position loop reads the motor
    encoder (``docs/validation/backlash.md``).

    Examples
    --------
    >>> ref = {"35": {"motor_travel": [2.0, 1.0], "current_step": [0.5, 0.25]}}
    >>> t = pd.DataFrame({"peak_speed": [35.0], "motor_travel": [4.0], "current_step": [1.0]})
    >>> float(with_contact_score(t, ref)["motor_contact"].iloc[0])
    4.0
    """
    speeds = sorted(float(s) for s in reference)
    score = np.zeros(len(table))
    for i, speed in enumerate(table[by].to_numpy(dtype=float)):
        key = f"{min(speeds, key=lambda s: abs(math.log(s / speed))):g}"
        score[i] = sum(
            (float(table[name].iloc[i]) - reference[key][name][0]) / reference[key][name][1]
            for name in CONTACT_FEATURES
        )
    return table.assign(motor_contact=score)
