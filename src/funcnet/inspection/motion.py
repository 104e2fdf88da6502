"""The moves of a recording: consecutive moving phases, and per move what an engineer reads
first (times, directions and the direction changes within, distance, peak speeds and currents,
following error).

A recording with gaps (missing values: :attr:`funcnet.robot.Recording.gaps`) is read segment by
segment (:func:`segment_phases`): no phase and no move spans a gap, and a move that a gap
interrupts is two moves, each marked as cut by the gap. The speed thresholds are those of the
whole recording, and a direction change across a gap (no segment holds it) is found from the
moves on either side (:func:`turns_across_gaps`).

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", section 4
   (phases), Eq. 11-12 (speed).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from funcnet.robot import Recording, detect_phases
from funcnet.robot.grid import format_spans
from funcnet.robot.phases import TURN_SPEED, SetpointTurn, direction_changes
from funcnet.robot.preprocess import segment_ticks, segment_velocity

#: A tick rests when its set-point speed is at most this fraction of the recording's peak (the
#: default of :func:`funcnet.robot.detect_phases`).
STANDSTILL = 1e-4

__all__ = ["numbered_moves", "motion_summary", "segment_phases", "turns_across_gaps"]


def segment_phases(recording: Recording) -> tuple[pd.DataFrame, tuple[SetpointTurn, ...]]:
    """The phases and the set-point's direction changes of a recording, segment by segment.

    Parameters
    ----------
    recording : Recording
        With RP; its :attr:`~funcnet.robot.Recording.gaps` split it into segments.

    Returns
    -------
    phases : pandas.DataFrame
        :func:`numbered_moves` of :func:`funcnet.robot.detect_phases` of each segment, in time
        order: the gaps are not covered, and a segment of one tick (no speed to read) has no
        row. Without gaps: the phases of the whole recording. The thresholds (the turn speed,
        ``TURN_SPEED`` of the peak, and the standstill, :data:`STANDSTILL` of it) are those of
        the whole recording: its peak set-point speed read within each segment
        (:func:`funcnet.robot.preprocess.segment_velocity`), so that a segment where the
        set-point only jitters at rest holds no move.
    turns : tuple of SetpointTurn
        :func:`funcnet.robot.direction_changes` of each segment, at the same thresholds; a turn
        across a gap is in none (:func:`turns_across_gaps`).

    Examples
    --------
    >>> from funcnet.robot import SignalInfo
    >>> t = np.arange(0, 4, 0.002).round(9)
    >>> rp = 10 * (1 - np.cos(np.pi * t / 2))  # out and back, a gap at 1.5-1.6 s
    >>> rp[(t >= 1.5) & (t < 1.6)] = np.nan
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)}, gaps=((1.5, 1.6),))
    >>> phases, turns = segment_phases(rec)
    >>> phases.groupby("move")[["start", "stop"]].agg({"start": "min", "stop": "max"})
          start  stop
    move
    1       0.0   1.5
    2       1.6   4.0
    >>> [round(turn.time, 2) for turn in turns]
    [2.0]
    """
    if not recording.gaps:
        return (numbered_moves(detect_phases(recording)),
                tuple(direction_changes(recording)))  # fmt: skip
    # the thresholds those of the whole recording (as the backlash diagnosis reads its
    # segments), not of each segment: a resting segment's jitter is no move
    speed = np.abs(segment_velocity(recording, recording.data["RP"].to_numpy(dtype=float)))
    peak = float(np.nanmax(speed)) if np.isfinite(speed).any() else 0.0
    fast = TURN_SPEED * peak
    tables, turns = [], []
    for (a, b), (first, last) in zip(recording.segments, segment_ticks(recording), strict=True):
        part = recording.window(a, b)
        if len(part.data) < 2:
            continue
        if peak == 0:  # nothing moves anywhere: each segment's own (zero) thresholds
            tables.append(detect_phases(part))
            continue
        # standstill: STANDSTILL of the whole recording's peak, as a fraction of this
        # segment's (below 1: a segment never faster than ``fast`` has no move at all)
        rest = STANDSTILL * peak / max(float(np.nanmax(speed[first:last])), fast)
        tables.append(detect_phases(part, min_speed=fast, standstill=rest))
        turns += direction_changes(part, min_speed=fast, standstill=rest)
    # every segment a tick long: the whole recording's error names the file and the gap
    tables = tables or [detect_phases(recording)]
    return numbered_moves(pd.concat(tables, ignore_index=True)), tuple(turns)


def numbered_moves(phases: pd.DataFrame) -> pd.DataFrame:
    """A phase table with each phase's move and duration.

    Parameters
    ----------
    phases : pandas.DataFrame
        :func:`funcnet.robot.detect_phases` (``phase``, ``start``, ``stop``).

    Returns
    -------
    pandas.DataFrame
        ``phases`` with ``move`` (consecutive non-standstill rows form one move, numbered from
        1; 0 for standstill; a row that does not start where the one before stops, after a gap,
        starts a new move) and ``duration`` (seconds, rounded to the microsecond).

    Examples
    --------
    >>> phases = pd.DataFrame({"phase": ["standstill", "cruise", "braking", "standstill"],
    ...                        "start": [0.0, 0.5, 1.0, 1.5], "stop": [0.5, 1.0, 1.5, 2.0]})
    >>> numbered_moves(phases)["move"].tolist()
    [0, 1, 1, 0]
    """
    moving = (phases["phase"] != "standstill").to_numpy()
    after_gap = np.concatenate(
        [[False], phases["start"].to_numpy()[1:] != phases["stop"].to_numpy()[:-1]])
    starts = moving & ~(np.concatenate([[False], moving[:-1]]) & ~after_gap)
    move = np.where(moving, np.cumsum(starts), 0)
    return phases.assign(move=move, duration=(phases["stop"] - phases["start"]).round(6))


def _peak(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(np.abs(finite).max()) if finite.size else float("nan")


def _sign(value: float) -> str:
    return "+" if value >= 0 else "−"


def motion_summary(
    recording: Recording, phases: pd.DataFrame, turns: Sequence[SetpointTurn] | None = None
) -> pd.DataFrame:
    """One row per move of a recording: times, directions, distance, speeds, currents, errors.

    Parameters
    ----------
    recording : Recording
        With RP (the set-point); AP, V, AC optional.
    phases : pandas.DataFrame
        :func:`numbered_moves` of :func:`funcnet.robot.detect_phases`.
    turns : sequence of SetpointTurn, optional
        The set-point's direction changes; default :func:`funcnet.robot.direction_changes` of
        ``recording`` (of each segment: :func:`segment_phases`).

    Returns
    -------
    pandas.DataFrame
        One row per move: ``move, start, stop, duration``, ``direction`` (``+`` or ``−``; one
        sign per stretch, ``+−+``, when the move changes direction without a rest),
        ``direction changes`` (within the move), ``distance`` (net), ``peak speed`` (set-point,
        unit/s, Eq. 11-12), ``peak V`` (arm side), ``peak |AC|``, ``peak |FE|`` (RP - AP),
        ``final |FE|`` (at the move's end); columns whose signal is missing are left out.
        A recording with gaps adds ``cut by a gap``: the gap (``"3.5-3.8 s"``) the move starts
        or stops at, its distance and peaks then only those of the part recorded ("" for a move
        that no gap touches).

    Examples
    --------
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 2, 0.002)
    >>> rp = np.clip(t - 0.5, 0, 1) * 90.0
    >>> data = pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> phases = numbered_moves(pd.DataFrame({"phase": ["standstill", "cruise", "standstill"],
    ...                                       "start": [0.0, 0.5, 1.5],
    ...                                       "stop": [0.5, 1.5, 2.0]}))
    >>> motion_summary(rec, phases)[["move", "direction", "distance"]].round(1)
       move direction  distance
    0     1         +      89.8

    Out and back without a rest:

    >>> rp = 45 * (1 - np.cos(2 * np.pi * t / 2))
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)})
    >>> phases = numbered_moves(pd.DataFrame({"phase": ["cruise"], "start": [0.0],
    ...                                       "stop": [2.0]}))
    >>> motion_summary(rec, phases)[["direction", "direction changes"]]
      direction  direction changes
    0        +−                  1
    """
    if turns is None:
        turns = segment_phases(recording)[1] if recording.gaps else direction_changes(recording)
    data = recording.data
    t = data.index.to_numpy(dtype=float)
    rp = data["RP"].to_numpy(dtype=float)
    set_speed = np.abs(segment_velocity(recording, rp))
    rows = []
    for move, group in phases[phases["move"] > 0].groupby("move"):
        start, stop = float(group["start"].min()), float(group["stop"].max())
        inside = (t >= start) & (t < stop)
        first, last = np.flatnonzero(inside)[[0, -1]]
        distance = float(rp[last] - rp[first])
        within = [turn.direction for turn in turns if start <= turn.time < stop]
        direction = _sign(distance) if not within else _sign(-within[0]) + "".join(
            _sign(d) for d in within)
        row: dict[str, Any] = {"move": int(move), "start": start, "stop": stop,
                               "duration": round(stop - start, 6),
                               "direction": direction,
                               "direction changes": len(within),
                               "distance": distance,
                               "peak speed": _peak(set_speed[inside])}
        if "V" in data:
            row["peak V"] = _peak(data["V"].to_numpy(dtype=float)[inside])
        if "AC" in data:
            row["peak |AC|"] = _peak(data["AC"].to_numpy(dtype=float)[inside])
        if "AP" in data:
            fe = rp - data["AP"].to_numpy(dtype=float)
            row["peak |FE|"] = _peak(fe[inside])
            row["final |FE|"] = _peak(fe[last:last + 1])
        if recording.gaps:
            row["cut by a gap"] = format_spans(
                [(a, b) for a, b in recording.gaps
                 if abs(stop - a) < recording.sample_period / 2
                 or abs(start - b) < recording.sample_period / 2])
        rows.append(row)
    return pd.DataFrame(rows)


def turns_across_gaps(
    moves: pd.DataFrame, gaps: Sequence[tuple[float, float]]
) -> tuple[tuple[float, float], ...]:
    """Where the set-point changes direction across a gap: what no segment's turns hold.

    Parameters
    ----------
    moves : pandas.DataFrame
        :func:`motion_summary` (``start``, ``stop``, ``direction``).
    gaps : sequence of (float, float)
        :attr:`funcnet.robot.Recording.gaps`.

    Returns
    -------
    tuple of (float, float)
        Per such change, in time order: the end of the move before the gap and the start of the
        next move, which goes the other way (its first direction against the last of the move
        before); a gap lies between them. Empty without gaps.

    Examples
    --------
    >>> moves = pd.DataFrame({"start": [0.5, 5.0], "stop": [2.5, 7.0],
    ...                       "direction": ["+", "−"]})
    >>> turns_across_gaps(moves, [(3.5, 3.8)]), turns_across_gaps(moves, [])
    (((2.5, 5.0),), ())
    """
    if not gaps or not len(moves):
        return ()
    rows = list(zip(moves["start"], moves["stop"], moves["direction"], strict=True))
    return tuple(
        (float(stop), float(start))
        for (_, stop, before), (start, _, after) in zip(rows, rows[1:], strict=False)
        if before[-1] != after[0] and any(stop <= a and b <= start for a, b in gaps)
    )
