"""Direction changes of an axis in a trace, and the recording the indicators read.

A *direction change* is where the position set-point RP stops moving one way and next moves
the other way. When the standstill between the two moves is short (at most ``max_dwell``, 0.5 s
as the reversal phase of :func:`funcnet.robot.detect_phases`) it is a **reversal** as in the
paper's backlash trials (section 4.3): the motor crosses the gear's dead zone right after its
turning point. After a longer standstill (``kind="after standstill"``) the dead zone is crossed
too, at the start of the next move, from rest. In continuous motion (``kind="continuous"``) the
set-point's speed changes sign without resting at all: the arm never stops, it follows the motor
through the turn (the smooth multi-axis trajectories of a real robot).

A move counts only when the set-point's speed reaches ``min_speed`` (1 deg/s, or half the trace's
peak speed on a slower trace): a set-point that wiggles below it near a standstill does not
change direction.

A recording with gaps (missing values: :attr:`funcnet.robot.Recording.gaps`) is read segment by
segment: the set-point's speed within each (:func:`funcnet.robot.preprocess.segment_velocity`),
the thresholds those of the whole recording; no move spans a gap, and a direction change across
one (:func:`changes_across_gaps`) is not among those found (:func:`changes_within_and_across`
gives both from one reading).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import groupby

import numpy as np

from funcnet.errors import ChannelError, ParameterError
from funcnet.robot.grid import mask_runs
from funcnet.robot.phases import MOVE_SPEED, direction_changes, merge_runs, move_threshold
from funcnet.robot.preprocess import (
    add_derived_signals,
    resample,
    segment_ticks,
    segment_velocity,
    staircase_signals,
    velocity,
)
from funcnet.robot.recording import Recording

__all__ = [
    "DirectionChange",
    "find_direction_changes",
    "changes_across_gaps",
    "changes_within_and_across",
    "motor_side_recording",
    "MAX_DWELL",
    "MIN_SPEED",
]

#: Longest standstill, in s, between the two moves of a reversal (as ``detect_phases``).
MAX_DWELL = 0.5
#: deg/s a set-point must exceed for a move (or half its peak speed, if less:
#: :func:`funcnet.robot.phases.move_threshold`).
MIN_SPEED = MOVE_SPEED


@dataclass(frozen=True)
class DirectionChange:
    """One direction change of the set-point, as the backlash diagnosis reads it: between moves.

    The change between two moves faster than the move threshold, classified by what lies
    between them (``kind``). The set-point's own view of a direction change, its turning point
    (:class:`funcnet.robot.SetpointTurn`), gives a continuous change its bracket and ``turn``.

    Attributes
    ----------
    stop : float
        s, the first move's end (the set-point comes to rest).
    start : float
        s, the second move's start.
    dwell : float
        s of standstill between them (``start - stop``).
    direction : int
        The second move's direction, +1 or -1.
    kind : str
        ``"reversal"`` (dwell at most ``max_dwell``), ``"after standstill"`` or
        ``"continuous"`` (no standstill: ``stop`` and ``start`` then bracket the set-point's turn,
        the end and the start of the stretches where its speed exceeds the move threshold, and
        ``dwell`` is 0).
    turn : float or None
        s, where the set-point's speed changes sign (continuous changes; None otherwise).
    """

    stop: float
    start: float
    dwell: float
    direction: int
    kind: str
    turn: float | None = None

    def to_dict(self) -> dict[str, float | int | str | None]:
        """The fields as a JSON-ready dict."""
        return {
            "stop": self.stop,
            "start": self.start,
            "dwell": self.dwell,
            "direction": self.direction,
            "kind": self.kind,
            "turn": self.turn,
        }


def find_direction_changes(
    recording: Recording,
    *,
    reference: str = "RP",
    standstill: float = 1e-4,
    max_dwell: float = MAX_DWELL,
    min_gap: float = 0.05,
    min_speed: float = MIN_SPEED,
) -> list[DirectionChange]:
    """The direction changes of the reference motion.

    Parameters
    ----------
    recording : Recording
    reference : str
        The position set-point's column.
    standstill : float
        A tick moves when ``|v| > standstill * max|v|`` (``v``: Eq. 11-12 applied to the
        reference), as in :func:`funcnet.robot.detect_phases`.
    max_dwell : float
        Longest standstill, in s, of a ``"reversal"``.
    min_gap : float
        Moves in the same direction less than ``min_gap`` s apart are one move.
    min_speed : float
        deg/s a move's set-point speed must exceed to count, or half the trace's peak speed
        where that is less (a slow trace); a wiggle below it is no move. The stretches above it
        bracket a continuous change.

    Returns
    -------
    list of DirectionChange
        In time order; empty when the axis moves one way only (or not at all).

    Raises
    ------
    ChannelError
        No ``reference`` column.
    ParameterError
        A threshold out of range.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.002)
    >>> rp = np.interp(t, [0, 1, 2, 2.2, 3.2, 4], [0, 0, 1, 1, 0, 0])
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> [(round(c.stop, 2), round(c.dwell, 2), c.direction, c.kind)
    ...  for c in find_direction_changes(rec)]
    [(2.0, 0.2, -1, 'reversal')]

    A smooth set-point turning without a rest (a continuous change, bracketed by the stretches
    where it moves faster than 1 deg/s):

    >>> rp = 10 * np.sin(np.pi * t / 2)
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> [(round(c.stop, 2), round(c.turn, 2), round(c.start, 2), c.kind)
    ...  for c in find_direction_changes(rec)]
    [(0.96, 1.0, 1.04, 'continuous'), (2.96, 3.0, 3.04, 'continuous')]
    """
    return changes_within_and_across(
        recording, reference=reference, standstill=standstill, max_dwell=max_dwell,
        min_gap=min_gap, min_speed=min_speed,
    )[0]  # fmt: skip


def changes_across_gaps(
    recording: Recording,
    *,
    reference: str = "RP",
    standstill: float = 1e-4,
    max_dwell: float = MAX_DWELL,
    min_gap: float = 0.05,
    min_speed: float = MIN_SPEED,
) -> list[tuple[float, float]]:
    """Where the set-point changes direction across a gap: what no segment shows.

    Parameters
    ----------
    recording : Recording
    reference, standstill, max_dwell, min_gap, min_speed
        As for :func:`find_direction_changes`.

    Returns
    -------
    list of (float, float)
        Per such change, in time order: the end of the move before the gap and the start of
        the next move, the other way, after it (s). Empty without gaps.

    Raises
    ------
    ChannelError, ParameterError
        As :func:`find_direction_changes`.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.002).round(9)
    >>> rp = 10 * np.sin(np.pi * t / 2)  # turns at 1 s and 3 s; 0.9-1.1 s missing
    >>> rp[(t >= 0.9) & (t < 1.1)] = np.nan
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)}, gaps=((0.9, 1.1),))
    >>> changes_across_gaps(rec), [c.turn for c in find_direction_changes(rec)]
    ([(0.9, 1.1)], [3.0])
    """
    across = changes_within_and_across(
        recording, reference=reference, standstill=standstill, max_dwell=max_dwell,
        min_gap=min_gap, min_speed=min_speed,
    )[1]  # fmt: skip
    return [(stop, start) for stop, start, _ in across]


def changes_within_and_across(
    recording: Recording,
    *,
    reference: str = "RP",
    standstill: float = 1e-4,
    max_dwell: float = MAX_DWELL,
    min_gap: float = 0.05,
    min_speed: float = MIN_SPEED,
) -> tuple[list[DirectionChange], list[tuple[float, float, tuple[float, float]]]]:
    """:func:`find_direction_changes` and :func:`changes_across_gaps` from one reading.

    Parameters
    ----------
    recording : Recording
    reference, standstill, max_dwell, min_gap, min_speed
        As for :func:`find_direction_changes`.

    Returns
    -------
    changes : list of DirectionChange
        As :func:`find_direction_changes`.
    across : list of (float, float, (float, float))
        As :func:`changes_across_gaps`, each with the gap that ends the segment of the move
        before it (``[start, stop)``, s; the first, where the two moves lie several segments
        apart).

    Raises
    ------
    ChannelError, ParameterError
        As :func:`find_direction_changes`.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 4, 0.002).round(9)
    >>> rp = 10 * np.sin(np.pi * t / 2)  # turns at 1 s and 3 s; 0.9-1.1 s missing
    >>> rp[(t >= 0.9) & (t < 1.1)] = np.nan
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)}, gaps=((0.9, 1.1),))
    >>> changes, across = changes_within_and_across(rec)
    >>> [c.turn for c in changes], across
    ([3.0], [(0.9, 1.1, (0.9, 1.1))])
    """
    if reference not in recording.data.columns:
        raise ChannelError(
            recording.source or "<recording>", f"no {reference!r} column to find the moves"
        )
    if not (0 < standstill < 1) or not (max_dwell >= 0 and math.isfinite(max_dwell)):
        raise ParameterError.of("standstill", "must be in (0, 1), max_dwell >= 0")
    if not (min_speed > 0 and math.isfinite(min_speed)):
        raise ParameterError.of("min_speed", f"must be a speed > 0 in deg/s, got {min_speed!r}")
    dt = recording.sample_period
    x = recording.data[reference].to_numpy(dtype=np.float64, copy=True)
    written = np.flatnonzero(np.isfinite(x))
    if written.size:
        # the values a signal has not yet written are no gap and no move: held at its first
        x[: written[0]] = x[written[0]]
    x = np.where(np.isnan(x), np.nanmean(x) if written.size else 0.0, x)
    segment = None
    if recording.gaps:
        # each segment's speed on its own (0 in a gap: no move there) and its ticks' segment
        v = np.nan_to_num(segment_velocity(recording, x))
        segment = np.full(x.size, -1)
        for k, (a, b) in enumerate(segment_ticks(recording)):
            segment[a:b] = k
    else:
        v = velocity(x, dt)
    if not np.any(v):
        return [], []
    fast = move_threshold(v, min_speed)
    runs = []
    for a, b in mask_runs(np.abs(v) > standstill * np.abs(v).max()):
        # a run whose speed changes sign is a continuous change: one move per sign
        flips = np.flatnonzero(np.diff(np.sign(v[a:b])) != 0) + a + 1
        bounds = [int(a), *(int(f) for f in flips), int(b)]
        runs += list(zip(bounds[:-1], bounds[1:], strict=True))
    # a wiggle below the move threshold is no move; same-direction runs less than min_gap apart
    # are one move
    runs = [(a, b) for a, b in runs if np.abs(v[a:b]).max() > fast]
    if segment is None:
        moves = merge_runs(runs, v, min_gap, dt)
    else:  # runs in different segments are never one move
        moves = [move for _, part in groupby(runs, key=lambda run: segment[run[0]])
                 for move in merge_runs(list(part), v, min_gap, dt)]  # fmt: skip
    t0 = float(recording.data.index[0])
    changes, across = [], []
    turns: dict[int | None, list] = {}
    for (a0, b0), (a1, b1) in zip(moves, moves[1:], strict=False):
        s0, s1 = np.sign(v[a0:b0].sum()), np.sign(v[a1:b1].sum())
        if s0 == s1 or s1 == 0:
            continue
        if segment is not None and segment[a0] != segment[a1]:
            gap = _gap_after(recording, int(segment[a0]))
            across.append((round(t0 + b0 * dt, 9), round(t0 + a1 * dt, 9), gap))
            continue
        # no standstill between -- the set-point turns while moving, its speed at most dipping
        # below the standstill threshold as it crosses zero, its reading never held: continuous
        if a1 == b0 or not np.any(np.diff(x[b0 - 1 : a1 + 1]) == 0):
            # bracketed by the stretches faster than the move threshold (robot.phases)
            key = None if segment is None else int(segment[a0])
            if key not in turns:
                part = recording if key is None else recording.window(*recording.segments[key])
                turns[key] = direction_changes(part, reference=reference, min_speed=fast)
            at = round(t0 + b0 * dt, 9)
            turn = next((u for u in turns[key] if u.stop - 1e-9 <= at <= u.start + 1e-9), None)
            bracket = (at, at, at) if turn is None else (turn.stop, turn.start, turn.time)
            changes.append(DirectionChange(bracket[0], bracket[1], 0.0, int(s1), "continuous",
                                           bracket[2]))  # fmt: skip
            continue
        dwell = (a1 - b0) * dt
        changes.append(
            DirectionChange(
                stop=round(t0 + b0 * dt, 9),
                start=round(t0 + a1 * dt, 9),
                dwell=round(dwell, 9),
                direction=int(s1),
                kind="reversal" if dwell <= max_dwell else "after standstill",
            )
        )
    return changes, across


def _gap_after(recording: Recording, segment: int) -> tuple[float, float]:
    """The gap that ends segment ``segment`` of ``recording`` (a segment ends where one starts)."""
    end = recording.segments[segment][1]
    gap = next((g for g in recording.gaps if g[0] == end), None)
    if gap is None:  # Recording.segments ends every segment but the last at a gap's start
        raise AssertionError(
            f"{recording.source or '<recording>'}: no gap starts where segment {segment} ends "
            f"({end:g} s; gaps {list(recording.gaps)})"
        )
    return gap


def motor_side_recording(recording: Recording) -> Recording:
    """The recording the indicators read: on the positions' own grid, with VM (and V).

    Staircase positions (the 4 ms IPO signals on the 2 ms servo grid) are decimated onto their
    own grid first (:func:`funcnet.robot.resample`), so that the velocities of Eq. 11-12 are
    not made of steps; then ``VM`` (from MP) and ``V`` (from AP, when AP is there) are added.

    Parameters
    ----------
    recording : Recording
        With RP, MP, RC or AC; AP optional.

    Returns
    -------
    Recording

    Raises
    ------
    ChannelError
        No MP.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 0.02, 0.002)
    >>> rec = Recording(pd.DataFrame({"MP": t * 10}, index=pd.Index(t, name="time")), {},
    ...                 {"MP": SignalInfo("MP", "posn", None, 0.002)})
    >>> motor_side_recording(rec).data.columns.tolist()
    ['MP', 'VM']
    """
    if "MP" not in recording.data.columns:
        raise ChannelError(recording.source or "<recording>", "no MP (motor encoder) column")
    if staircase_signals(recording, [c for c in ("MP", "AP") if c in recording.data.columns]):
        recording = resample(recording, method="decimate")
    derived = ["VM"] + (["V"] if "AP" in recording.data.columns else [])
    return add_derived_signals(recording, derived)
