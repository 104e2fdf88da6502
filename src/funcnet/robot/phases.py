"""Motion phases of a robot axis, from the reference motion (paper section 4).

The paper computes one functional network per motion phase: early spin-up, late spin-up, cruise
and braking (section 4.1, Fig. 9), and the reversal of a forward-and-reverse move (section 4.3,
Fig. 11). :func:`detect_phases` finds them from the position set-point RP and its derivatives;
:func:`phase_table` takes phases given by hand. Both give the same table: one row per phase with
``phase``, ``start`` and ``stop`` (seconds, ``start <= time < stop``), in time order.
:func:`direction_changes` finds where the set-point turns, after a standstill or in continuous
motion. :func:`merge_runs` joins a move's runs across short standstills; :func:`move_threshold`
is the speed a move must exceed to count in the backlash diagnosis and its simulated truth (1
deg/s, or half the peak speed if less).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet._lazy import deprecated_names
from funcnet.errors import ParameterError
from funcnet.robot.grid import mask_runs
from funcnet.robot.preprocess import reference_speed, velocity
from funcnet.robot.recording import Recording

__all__ = [
    "MOVE_SPEED",
    "PHASES",
    "SetpointTurn",
    "detect_phases",
    "direction_changes",
    "merge_runs",
    "move_threshold",
    "phase_table",
]

#: Phase names, as the paper writes them.
PHASES = ("standstill", "early spin-up", "late spin-up", "cruise", "braking", "reversal")

#: Default of :func:`direction_changes`' ``relative``: a stretch of motion counts when its speed
#: exceeds this fraction of the reference's peak speed.
TURN_SPEED = 0.05
#: Default of :func:`move_threshold`: 1 deg/s on an axis in degrees.
MOVE_SPEED = 1.0


def _fraction(value: float, name: str) -> float:
    if not (0.0 < value < 1.0):
        raise ParameterError(f"{name}: must be a fraction in (0, 1), got {value}")
    return value


def move_threshold(speed: np.ndarray, min_speed: float = MOVE_SPEED) -> float:
    """The speed a motion must exceed to count as a move: ``min_speed``, or half the peak speed
    where that is less (a slow trace keeps its moves).

    Parameters
    ----------
    speed : ndarray
        Speeds (either sign) of the motion, e.g. deg/s; NaN values are ignored.
    min_speed : float
        The threshold of a trace that moves faster than twice it.

    Returns
    -------
    float
        ``min(min_speed, max|speed| / 2)``; 0 when no speed is finite.

    Examples
    --------
    >>> move_threshold(np.array([0.0, 3.0, -5.0])), move_threshold(np.array([0.2, -0.8]))
    (1.0, 0.4)
    """
    if not np.isfinite(speed).any():
        return 0.0
    return min(min_speed, 0.5 * float(np.nanmax(np.abs(speed))))


def merge_runs(
    runs: list[tuple[int, int]], signed: np.ndarray, max_gap: float, period: float = 1.0
) -> list[tuple[int, int]]:
    """Join consecutive runs in the same direction that lie less than ``max_gap`` apart.

    Parameters
    ----------
    runs : list of (int, int)
        ``(first, stop)`` tick pairs in time order (:func:`~funcnet.robot.grid.mask_runs`).
    signed : ndarray
        The signed speed per tick: a run's direction is the sign of its sum.
    max_gap : float
        The gap (ticks from one run's stop to the next's first, times ``period``) below which
        two runs the same way are one.
    period : float
        1 for ``max_gap`` in ticks (``min_gap / dt``: :func:`detect_phases`); the sample period
        for ``max_gap`` in seconds (:func:`funcnet.diagnosis.reversals.find_direction_changes`).
        The two round differently at an exact tie, so each caller keeps its own.

    Returns
    -------
    list of (int, int)

    Examples
    --------
    >>> v = np.array([1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0])
    >>> [(int(a), int(b)) for a, b in merge_runs(mask_runs(v != 0), v, 2)]
    [(0, 4), (7, 8)]
    """
    merged: list[tuple[int, int]] = []
    for first, stop in runs:
        if merged:
            prev_first, prev_stop = merged[-1]
            same = np.sign(signed[prev_first:prev_stop].sum()) == np.sign(signed[first:stop].sum())
            if same and (first - prev_stop) * period < max_gap:
                merged[-1] = (prev_first, stop)
                continue
        merged.append((first, stop))
    return merged


@dataclass(frozen=True)
class SetpointTurn:
    """One direction change of the reference motion, as the set-point alone shows it: its turn.

    The backlash diagnosis's view of the same change, between two moves and classified, is
    :class:`funcnet.diagnosis.DirectionChange`. Formerly ``Turn`` (deprecated).

    Attributes
    ----------
    time : float
        s, the turning point: where the reference reaches its extreme position between the two
        stretches (the middle of the ticks that hold it, when it rests there).
    stop : float
        s, the end of the stretch before: the first tick whose speed no longer exceeds
        ``threshold``.
    start : float
        s, the start of the stretch after: its first tick above ``threshold``.
    direction : int
        The direction of the motion after the turn, +1 or -1.
    dwell : float
        s of standstill at the turn: from the first to the last tick between ``stop`` and
        ``start`` whose speed is at most ``standstill`` times the peak (0 when there is none;
        a tick or two where a continuous motion passes through zero).
    threshold : float
        The speed (reference units per second) both stretches exceed.
    """

    time: float
    stop: float
    start: float
    direction: int
    dwell: float
    threshold: float

    def to_dict(self) -> dict[str, float | int]:
        """The fields as a JSON-ready dict."""
        return {
            "time": self.time,
            "stop": self.stop,
            "start": self.start,
            "direction": self.direction,
            "dwell": self.dwell,
            "threshold": self.threshold,
        }


def _stretches(signed: np.ndarray, threshold: float) -> list[tuple[int, int, int]]:
    """Maximal runs of ticks moving faster than ``threshold`` one way: (first, stop, sign)."""
    label = np.where(signed > threshold, 1, np.where(signed < -threshold, -1, 0)).astype(np.int8)
    change = np.flatnonzero(np.diff(label)) + 1
    starts = np.concatenate([[0], change])
    stops = np.concatenate([change, [label.size]])
    return [(int(a), int(b), int(label[a])) for a, b in zip(starts, stops, strict=True) if label[a]]


def _turn_ticks(
    position: np.ndarray, signed: np.ndarray, threshold: float
) -> list[tuple[int, int, float, int]]:
    """Turns as ticks: (stop, start, turning tick (may be half-way), direction after)."""
    turns = []
    stretches = _stretches(signed, threshold)
    for (_, stop, before), (start, _, after) in zip(stretches, stretches[1:], strict=False):
        if before == after:
            continue
        # the extreme position from the last tick of the stretch before to the first after
        lo = stop - 1
        reached = before * position[lo : start + 1]
        first = int(np.argmax(reached))
        held = np.flatnonzero(reached[first:] != reached[first])
        last = first + (int(held[0]) if held.size else reached.size - first) - 1
        turns.append((stop, start, lo + (first + last) / 2, after))
    return turns


def direction_changes(
    recording: Recording,
    *,
    reference: str = "RP",
    min_speed: float | None = None,
    relative: float = TURN_SPEED,
    standstill: float = 1e-4,
) -> list[SetpointTurn]:
    """Where the reference motion changes direction, after a standstill or in continuous motion.

    With ``v`` the velocity of the reference (:func:`~funcnet.robot.preprocess.velocity`, Eq.
    11-12), a *stretch* is a maximal run of ticks with ``v > threshold`` or one with
    ``v < -threshold``. A direction change is a pair of consecutive stretches of opposite sign;
    what lies between them (the gap, slower than ``threshold``) holds the turn, whether the
    reference rests there or passes through zero speed. A wiggle that never exceeds
    ``threshold`` is no stretch, so it makes no direction change, and two stretches the same way
    with a wiggle between them are one way of motion.

    Parameters
    ----------
    recording : Recording
    reference : str
        Column of the position set-point.
    min_speed : float, optional
        The threshold in the reference's units per second (1.0 for 1 deg/s on an axis in
        degrees). Default ``relative`` times the reference's peak speed.
    relative : float
        The threshold as a fraction of the peak speed, in (0, 1), when ``min_speed`` is not
        given.
    standstill : float
        A tick rests when ``|v| <= standstill * max|v|`` (as in :func:`detect_phases`); only
        ``dwell`` reads it.

    Returns
    -------
    list of SetpointTurn
        In time order; empty when the reference moves one way only or not at all.

    Raises
    ------
    ChannelError
        No ``reference`` column.
    SignalError
        The reference has NaN values.
    ParameterError
        ``min_speed`` not positive, or a fraction outside (0, 1).

    References
    ----------
    Paper section 4.3 (the reversal of a forward-and-reverse move, Fig. 11); Eq. 11-12 (the
    velocity).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.004)
    >>> rp = 30 * np.sin(np.pi * t / 2)  # out and back: turns at 1 s and 3 s, no rest
    >>> data = pd.DataFrame({"RP": rp}, index=pd.Index(t.round(9), name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", "posn", None, 0.004)},
    ...                 sample_period=0.004)
    >>> [(round(c.time, 3), c.direction, round(c.stop, 3), round(c.start, 3))
    ...  for c in direction_changes(rec, min_speed=1.0)]
    [(1.0, -1, 0.988, 1.016), (3.0, 1, 2.988, 3.016)]
    """
    _fraction(relative, "relative")
    _fraction(standstill, "standstill")
    if min_speed is not None and not (min_speed > 0 and math.isfinite(min_speed)):
        raise ParameterError(f"min_speed: must be > 0 (units per second), got {min_speed}")
    dt = recording.sample_period
    speed = reference_speed(recording, reference)
    peak = float(speed.max())
    if peak == 0:
        return []
    position = recording.data[reference].to_numpy(dtype=np.float64)
    signed = velocity(position, dt)
    threshold = float(min_speed) if min_speed is not None else relative * peak
    resting = speed <= standstill * peak
    t0 = float(recording.data.index[0])
    turns = []
    for stop, start, turn, after in _turn_ticks(position, signed, threshold):
        rest = np.flatnonzero(resting[stop:start])
        dwell = (rest[-1] - rest[0] + 1) * dt if rest.size else 0.0
        turns.append(
            SetpointTurn(
                time=round(t0 + turn * dt, 9),
                stop=round(t0 + stop * dt, 9),
                start=round(t0 + start * dt, 9),
                direction=after,
                dwell=round(float(dwell), 9),
                threshold=threshold,
            )
        )
    return turns


def _dips(speed: np.ndarray, first: int, stop: int, threshold: float, dip: float) -> list[int]:
    """Ticks where a one-way stretch slows between two humps faster than ``threshold`` to below
    ``dip`` times the lower of them: the deepest first, then within each side."""
    part = speed[first:stop]
    if part.size < 3:
        return []
    before = np.maximum.accumulate(part)
    after = np.maximum.accumulate(part[::-1])[::-1]
    lower = np.minimum(before, after)
    ratio = np.where(lower > threshold, part / np.where(lower > 0, lower, 1.0), 1.0)
    deepest = int(np.argmin(ratio))
    if ratio[deepest] >= dip:
        return []
    cut = first + deepest
    return [
        *_dips(speed, first, cut, threshold, dip),
        cut,
        *_dips(speed, cut, stop, threshold, dip),
    ]


def _segments(
    moves: list[tuple[int, int]],
    turns: list[float],
    speed: np.ndarray,
    threshold: float,
    dip: float,
) -> list[tuple[int, int, bool]]:
    """The moves cut at the turns inside them and at deep dips: (first, stop, from rest)."""
    segments: list[tuple[int, int, bool]] = []
    for first, stop in moves:
        cuts = [first]
        for turn in turns:
            cut = int(math.ceil(turn))
            if first < cut < stop:
                cuts.append(cut)
        cuts.append(stop)
        edges = [first]
        for a, b in zip(cuts, cuts[1:], strict=False):
            edges.extend([*_dips(speed, a, b, threshold, dip), b])
        segments.extend(
            (a, b, a == first) for a, b in zip(edges, edges[1:], strict=False) if b > a
        )
    return segments


def detect_phases(
    recording: Recording,
    *,
    reference: str = "RP",
    standstill: float = 1e-4,
    cruise: float = 0.98,
    early: float = 0.95,
    reversal: float = 0.5,
    reversal_dwell: float = 0.5,
    min_gap: float = 0.05,
    min_speed: float | None = None,
    relative: float = TURN_SPEED,
    dip: float = 0.5,
) -> pd.DataFrame:
    """Find the motion phases from the reference motion.

    With ``v`` the velocity of the reference (:func:`~funcnet.robot.preprocess.velocity`, Eq.
    11-12 applied to RP) and ``a`` the same derivative of ``v``:

    - a *move* is a maximal run of ticks with ``|v| > standstill * max|v|``; runs in the same
      direction less than ``min_gap`` seconds apart are one move (a slow set-point written with
      finite decimals stands still for a few ticks while it creeps off and onto its target); a
      run never faster than the turn threshold (``min_speed``, default ``relative * max|v|``, as
      in :func:`direction_changes`) is a creep, not a move; every other tick is **standstill**;
    - a move is cut into *segments* where the reference turns inside it (a direction change of
      :func:`direction_changes` in continuous motion, cut at its turning point) and where it
      slows between two humps faster than the turn threshold to below ``dip`` times the lower
      of them (cut at the slowest tick); a point-to-point move is one segment;
    - in a segment of peak speed ``p``, **cruise** (the steady speed) runs from the first to the
      last tick with ``|v| >= cruise * p``; before it is the spin-up (accelerating), after it
      **braking** (decelerating). On a smooth profile without a plateau, cruise is where the
      speed stays within ``1 - cruise`` of the segment's peak;
    - the spin-up of a segment that starts from rest is **early spin-up** until ``|a|`` first
      reaches ``early`` times its maximum over the spin-up (the jerk-limited build-up of
      acceleration, where static friction is overcome; 0-220 ms in the paper's baseline),
      **late spin-up** after; a segment that starts moving (after a dip) has late spin-up only;
    - two consecutive segments in opposite directions with at most ``reversal_dwell`` seconds of
      standstill between them and a direction change of :func:`direction_changes` between them
      make a **reversal**: from the tick in the first segment's braking where ``|v|`` falls
      below ``reversal * p`` to the tick in the second's spin-up where it rises to
      ``reversal * p`` of that segment, the standstill or the continuous turn between included.
      What remains of the braking stays braking; what remains of the spin-up is late spin-up.

    Parameters
    ----------
    recording : Recording
    reference : str
        Column of the position set-point (noise-free; a measured position would need looser
        thresholds).
    standstill, cruise, early, reversal, dip : float
        The fractions above, each in (0, 1).
    reversal_dwell : float
        Longest standstill, in seconds, between the two moves of a reversal.
    min_gap : float
        Shortest standstill, in seconds, that separates two moves in the same direction.
    min_speed : float, optional
        The turn threshold in the reference's units per second (see :func:`direction_changes`);
        default ``relative`` times the peak speed.
    relative : float
        The turn threshold as a fraction of the peak speed, in (0, 1).

    Returns
    -------
    DataFrame
        Columns ``phase`` (one of :data:`PHASES`), ``start``, ``stop`` (seconds; ``stop`` of one
        row is ``start`` of the next), covering the whole recording; empty phases are left out.

    Raises
    ------
    ChannelError
        No ``reference`` column.
    SignalError
        The reference has NaN values.
    ParameterError
        A threshold outside its range.

    References
    ----------
    Paper section 4.1 (phases early spin-up, late spin-up, cruise, braking; Fig. 9), 4.2 (fixed
    windows per phase), 4.3 (reversal, Fig. 11). The paper's moves are point-to-point: the
    segments, the creep rule and the turns' test leave them as the paper's rule gives them.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> t = np.arange(0, 5, 0.002)  # jerk-limited: acceleration ramps up, holds, ramps down
    >>> acc = np.interp(t, [1, 1.2, 1.6, 1.8, 3, 3.2, 3.6, 3.8], [0, 1, 1, 0, 0, -1, -1, 0])
    >>> rp = np.cumsum(np.cumsum(acc) * 0.002) * 0.002
    >>> data = pd.DataFrame({"RP": rp}, index=pd.Index(t.round(9), name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> detect_phases(rec).round(3)
               phase  start   stop
    0     standstill  0.000  1.004
    1  early spin-up  1.004  1.190
    2   late spin-up  1.190  1.730
    3         cruise  1.730  3.068
    4        braking  3.068  3.794
    5     standstill  3.794  5.000

    Continuous motion, out and back twice without a rest (turns at 1, 2 and 3 s):

    >>> rp = 10 * (1 - np.cos(np.pi * t[:2000]))
    >>> data = pd.DataFrame({"RP": rp}, index=pd.Index(t[:2000].round(9), name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> table = detect_phases(rec).round(3)
    >>> table[table["stop"] <= 2.2]  # cruise: sin(pi t) >= 0.98; reversal: below 0.5
               phase  start   stop
    0  early spin-up  0.000  0.006
    1   late spin-up  0.006  0.438
    2         cruise  0.438  0.564
    3        braking  0.564  0.834
    4       reversal  0.834  1.168
    5   late spin-up  1.168  1.438
    6         cruise  1.438  1.564
    7        braking  1.564  1.834
    8       reversal  1.834  2.168
    """
    for value, name in (
        (standstill, "standstill"),
        (cruise, "cruise"),
        (early, "early"),
        (reversal, "reversal"),
        (relative, "relative"),
        (dip, "dip"),
    ):
        _fraction(value, name)
    if min_speed is not None and not (min_speed > 0 and math.isfinite(min_speed)):
        raise ParameterError(f"min_speed: must be > 0 (units per second), got {min_speed}")
    for value, name in ((reversal_dwell, "reversal_dwell"), (min_gap, "min_gap")):
        if not (value >= 0 and math.isfinite(value)):
            raise ParameterError(f"{name}: must be >= 0 seconds, got {value}")
    dt = recording.sample_period
    speed = reference_speed(recording, reference)
    n = speed.size
    labels = np.zeros(n, dtype=np.int8)  # index into PHASES; 0 = standstill
    if speed.max() > 0:
        signed = velocity(recording.data[reference].to_numpy(dtype=np.float64), dt)
        accel = np.abs(velocity(signed, dt))
        position = recording.data[reference].to_numpy(dtype=np.float64)
        threshold = float(min_speed) if min_speed is not None else relative * speed.max()
        turns = [turn for _, _, turn, _ in _turn_ticks(position, signed, threshold)]
        moves = merge_runs(mask_runs(speed > standstill * speed.max()), signed, min_gap / dt)
        # a creep or wiggle never faster than the threshold is no move
        moves = [(first, stop) for first, stop in moves if speed[first:stop].max() > threshold]
        segments = _segments(moves, turns, speed, threshold, dip)
        for first, stop, from_rest in segments:
            peak = speed[first:stop].max()
            cruising = np.flatnonzero(speed[first:stop] >= cruise * peak) + first
            c0, c1 = cruising[0], cruising[-1] + 1
            labels[first:c0] = PHASES.index("late spin-up")
            if c0 > first and from_rest:
                reached = np.flatnonzero(accel[first:c0] >= early * accel[first:c0].max())
                labels[first : first + reached[0]] = PHASES.index("early spin-up")
            labels[c0:c1] = PHASES.index("cruise")
            labels[c1:stop] = PHASES.index("braking")
        for (first_a, stop_a, _), (first_b, stop_b, _) in zip(
            segments, segments[1:], strict=False
        ):
            opposite = np.sign(signed[first_a:stop_a].sum()) != np.sign(
                signed[first_b:stop_b].sum()
            )
            if not opposite or (first_b - stop_a) * dt > reversal_dwell:
                continue
            if not any(first_a <= turn < stop_b for turn in turns):
                continue
            level_a = reversal * speed[first_a:stop_a].max()
            level_b = reversal * speed[first_b:stop_b].max()
            fast_a = np.flatnonzero(speed[first_a:stop_a] >= level_a)
            fast_b = np.flatnonzero(speed[first_b:stop_b] >= level_b)
            r0, r1 = first_a + fast_a[-1] + 1, first_b + fast_b[0]
            labels[r0:r1] = PHASES.index("reversal")
            spin_up = labels[r1:stop_b] == PHASES.index("early spin-up")
            labels[r1:stop_b][spin_up] = PHASES.index("late spin-up")
    t0 = float(recording.data.index[0])
    change = np.flatnonzero(np.diff(labels)) + 1
    starts = np.concatenate([[0], change])
    stops = np.concatenate([change, [n]])
    return pd.DataFrame(
        {
            "phase": [PHASES[labels[i]] for i in starts],
            "start": np.round(t0 + starts * dt, 9),
            "stop": np.round(t0 + stops * dt, 9),
        }
    )


def phase_table(
    phases: pd.DataFrame | Mapping[str, tuple[float, float]] | Iterable[tuple[str, float, float]],
) -> pd.DataFrame:
    """Phases given by hand, as the table :func:`detect_phases` returns.

    Parameters
    ----------
    phases : DataFrame, dict or iterable
        A table with columns ``phase``, ``start``, ``stop``; a dict ``{phase: (start, stop)}``;
        or ``(phase, start, stop)`` tuples. Times in seconds, ``start < stop``. Names are free
        (the paper's are :data:`PHASES`); rows keep their order.

    Returns
    -------
    DataFrame
        Columns ``phase`` (str), ``start``, ``stop`` (float).

    Raises
    ------
    ParameterError
        A row without a name, or with ``start >= stop`` or a non-finite time.

    References
    ----------
    Paper section 4.1: the baseline's phases 0-220, 220-1000, 1000-5000 and 5000-5700 ms.

    Examples
    --------
    >>> phase_table({"early spin-up": (0.0, 0.22), "late spin-up": (0.22, 1.0),
    ...              "cruise": (1.0, 5.0), "braking": (5.0, 5.7)})
               phase  start  stop
    0  early spin-up   0.00  0.22
    1   late spin-up   0.22  1.00
    2         cruise   1.00  5.00
    3        braking   5.00  5.70
    """
    if isinstance(phases, pd.DataFrame):
        missing = {"phase", "start", "stop"} - set(phases.columns)
        if missing:
            raise ParameterError(f"phases: the table lacks the columns {sorted(missing)}")
        rows = list(zip(phases["phase"], phases["start"], phases["stop"], strict=True))
    elif isinstance(phases, Mapping):
        rows = [(name, *span) for name, span in phases.items()]
    else:
        rows = [tuple(row) for row in phases]
    table = []
    for row in rows:
        if len(row) != 3:
            raise ParameterError(f"phases: {row!r} is not (phase, start, stop)")
        name, start, stop = row
        try:
            start, stop = float(start), float(stop)
        except (TypeError, ValueError):
            raise ParameterError(f"phases: {row!r} has a time that is not a number") from None
        if not isinstance(name, str) or not name:
            raise ParameterError(f"phases: {row!r} needs a phase name")
        if not (math.isfinite(start) and math.isfinite(stop) and start < stop):
            raise ParameterError(f"phases: {name!r} needs finite start < stop, got {start}, {stop}")
        table.append((name, start, stop))
    return pd.DataFrame(
        {
            "phase": pd.Series([r[0] for r in table], dtype=object),
            "start": np.array([r[1] for r in table], dtype=np.float64),
            "stop": np.array([r[2] for r in table], dtype=np.float64),
        }
    )


# Renamed names, still given with a DeprecationWarning.
__getattr__ = deprecated_names(__name__, {"Turn": "SetpointTurn"})
