"""A recording with gaps diagnosed segment by segment.

Missing values split a recording into segments (:attr:`funcnet.robot.Recording.gaps`). The
diagnosis reads each direction change within the segment that holds it: the set-point's moves
never span a gap (:func:`~funcnet.diagnosis.reversals.find_direction_changes`), the indicators
and the two-encoder lost motion read that segment alone (:func:`segment_part`), and the arm's
start from rest is sought segment by segment (:func:`segment_first_start`); the gear is fitted
over the samples of every segment, its speeds and bootstrap blocks within each
(:mod:`~funcnet.diagnosis.reversal_error`). A direction change is left out (:class:`LeftOut`)
where a gap lies within what the diagnosis reads around it (:func:`reach`), or where the
set-point turns across a gap (:func:`~funcnet.diagnosis.reversals.changes_across_gaps`).
Without gaps every function here returns what the whole recording gives.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from funcnet.diagnosis.reversal_error import WINDOW
from funcnet.diagnosis.reversals import MAX_DWELL, DirectionChange, changes_within_and_across
from funcnet.diagnosis.two_encoder import ArmStart, first_start
from funcnet.robot.grid import format_spans, segments_phrase
from funcnet.robot.recording import Recording

__all__ = [
    "REACH",
    "reach",
    "LeftOut",
    "SegmentedChanges",
    "segment_changes",
    "segment_part",
    "segment_first_start",
    "segments_note",
]

def reach(kind: str, max_dwell: float = MAX_DWELL) -> tuple[float, float]:
    """s the diagnosis reads before a direction change's ``stop`` and after its ``start``.

    A gap within is a change left out. At a reversal the motor hysteresis reads the set-point
    from 1 s before the stop to 1.2 s after the start (:mod:`.indicators`) and the arm's
    restart is sought up to the dwell (at most ``max_dwell``, counted up to 1 s) and 1 s after
    the start (:mod:`.two_encoder`); after a standstill the gear torque is read 0.25 s before
    the stop and the motor's turn sought up to 1.5 s after the start; in continuous motion the
    reversal error's stretches (0.25 s each).

    Parameters
    ----------
    kind : str
        The change's :attr:`~funcnet.diagnosis.reversals.DirectionChange.kind`.
    max_dwell : float
        Longest standstill (s) of a reversal, as the changes were found with.

    Returns
    -------
    before, after : float
        s before ``stop`` and after ``start``.

    Examples
    --------
    >>> reach("reversal"), reach("reversal", max_dwell=0.8), reach("continuous")
    ((1.0, 1.5), (1.0, 1.8), (0.25, 0.25))
    """
    if kind == "reversal":
        return 1.0, max(1.2, min(max_dwell, 1.0) + 1.0)
    return {"after standstill": (WINDOW, 1.5), "continuous": (WINDOW, WINDOW)}[kind]


#: :func:`reach` by kind at the default ``max_dwell``.
REACH = {kind: reach(kind) for kind in ("reversal", "after standstill", "continuous")}


@dataclass(frozen=True)
class LeftOut:
    """A direction change the diagnosis leaves out: a gap lies within what it reads there.

    Attributes
    ----------
    stop, start : float
        s, the change's ``stop`` and ``start`` (across a gap: the end of the move before it
        and the start of the move after it).
    gap : tuple of (float, float)
        s, the gap ``[start, stop)``.
    across : bool
        The set-point turns across the gap (no segment holds the change).
    """

    stop: float
    start: float
    gap: tuple[float, float]
    across: bool = False

    def to_dict(self) -> dict[str, object]:
        """JSON-ready."""
        return {"stop": self.stop, "start": self.start, "gap": list(self.gap),
                "across": self.across}  # fmt: skip


@dataclass(frozen=True)
class SegmentedChanges:
    """The direction changes of a recording read segment by segment (:func:`segment_changes`).

    Attributes
    ----------
    changes : tuple of DirectionChange
        Those the diagnosis reads, in time order.
    left_out : tuple of LeftOut
        Those a gap hides, in time order.
    segments : tuple of (float, float)
        s, the segments read; () without gaps.
    gaps : tuple of (float, float)
        s, the recording's gaps.
    """

    changes: tuple[DirectionChange, ...]
    left_out: tuple[LeftOut, ...] = ()
    segments: tuple[tuple[float, float], ...] = ()
    gaps: tuple[tuple[float, float], ...] = ()


def _gap_within(gaps: Sequence[tuple[float, float]], start: float, stop: float
                ) -> tuple[float, float] | None:  # fmt: skip
    """The first gap overlapping ``[start, stop]``; None if none does."""
    return next(((a, b) for a, b in gaps if a <= stop and b > start), None)


def segment_changes(recording: Recording, *, max_dwell: float = MAX_DWELL) -> SegmentedChanges:
    """The direction changes the diagnosis reads, and those a gap hides.

    Parameters
    ----------
    recording : Recording
        From :func:`.motor_side_recording`.
    max_dwell : float
        Longest standstill (s) of a reversal.

    Returns
    -------
    SegmentedChanges
        Without gaps: every change of :func:`.find_direction_changes`. With gaps: those whose
        reach (:func:`reach`, from ``stop`` back and from ``start`` on) holds no gap; the
        others, and the changes across a gap (:func:`.changes_across_gaps`, labelled with the
        gap after the move before), left out.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 8, 0.002).round(9)
    >>> rp = 10 * np.sin(np.pi * t / 2)  # turns at 1, 3, 5 and 7 s
    >>> rp[(t >= 2.8) & (t < 2.9)] = np.nan  # in the stretch before the turn at 3 s
    >>> rp[(t >= 4.9) & (t < 5.1)] = np.nan  # over the turn at 5 s
    >>> rec = Recording(pd.DataFrame({"RP": rp}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.002)},
    ...                 gaps=((2.8, 2.9), (4.9, 5.1)))
    >>> found = segment_changes(rec)
    >>> [round(c.turn, 2) for c in found.changes], [(o.gap, o.across) for o in found.left_out]
    ([1.0, 7.0], [((2.8, 2.9), False), ((4.9, 5.1), True)])
    """
    changes, across = changes_within_and_across(recording, max_dwell=max_dwell)
    if not recording.gaps:
        return SegmentedChanges(tuple(changes))
    gaps = recording.gaps
    kept, left = [], []
    for change in changes:
        before, after = reach(change.kind, max_dwell)
        gap = _gap_within(gaps, change.stop - before, change.start + after)
        if gap is None:
            kept.append(change)
        else:
            left.append(LeftOut(change.stop, change.start, gap))
    left += [LeftOut(stop, start, gap, across=True) for stop, start, gap in across]
    return SegmentedChanges(
        tuple(kept), tuple(sorted(left, key=lambda o: o.stop)), tuple(recording.segments), gaps
    )


def segment_part(recording: Recording, change: DirectionChange) -> Recording:
    """The segment of ``recording`` that holds ``change`` (the recording itself without gaps).

    Parameters
    ----------
    recording : Recording
        From :func:`.motor_side_recording`.
    change : DirectionChange
        One of :attr:`SegmentedChanges.changes`.

    Returns
    -------
    Recording
        :meth:`~funcnet.robot.Recording.window` of the segment whose span holds
        ``change.stop``; ``recording`` itself without gaps (or where no segment holds it).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> t = np.arange(0, 1, 0.1).round(9)
    >>> rec = Recording(pd.DataFrame({"RP": t}, index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", "posn", None, 0.1)}, sample_period=0.1,
    ...                 gaps=((0.3, 0.4),))
    >>> part = segment_part(rec, DirectionChange(0.6, 0.7, 0.1, 1, "reversal"))
    >>> part.data.index.tolist()
    [0.4, 0.5, 0.6, 0.7, 0.8, 0.9]
    """
    span = next(((a, b) for a, b in recording.segments if a <= change.stop < b), None)
    return recording if not recording.gaps or span is None else recording.window(*span)


def segment_first_start(recording: Recording) -> ArmStart | None:
    """:func:`.first_start` of the first segment that has one (the whole recording's without
    gaps): no start's fit reads across a gap.

    Parameters
    ----------
    recording : Recording
        With MP and AP, from :func:`.motor_side_recording`.

    Returns
    -------
    ArmStart or None
        The axis's first start from a long rest, found within one segment; None where no
        segment has one.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import SignalInfo
    >>> t = np.arange(0.0, 0.5, 0.004).round(9)
    >>> info = {c: SignalInfo(c, "posn", None, 0.004) for c in ("MP", "AP")}
    >>> rec = Recording(pd.DataFrame({"MP": 0 * t, "AP": 0 * t}, index=pd.Index(t, name="time")),
    ...                 {}, info, sample_period=0.004, gaps=((0.2, 0.24),))
    >>> segment_first_start(rec) is None  # the arm never moves
    True
    """
    if not recording.gaps:
        return first_start(recording)
    for span in recording.segments:
        found = first_start(recording.window(*span))
        if found is not None:
            return found
    return None


def segments_note(found: SegmentedChanges) -> str:
    """What the message of a diagnosis says of the gaps ("" without gaps).

    Parameters
    ----------
    found : SegmentedChanges
        From :func:`segment_changes`.

    Returns
    -------
    str
        The segments read (counted as the reader's warning counts them:
        :func:`funcnet.robot.grid.segments_phrase`), the gaps, and each change left out with
        its gap; "" without gaps.

    Examples
    --------
    >>> print(segments_note(SegmentedChanges((), (LeftOut(2.9, 3.1, (2.8, 2.9)),),
    ...                                      ((0.0, 2.8), (2.9, 8.0)), ((2.8, 2.9),))))
    read in 2 segments, values missing at 2.8-2.9 s (nothing read across a gap); 1 direction \
change left out, a gap within what is read around it: 2.9-3.1 s (gap 2.8-2.9 s)
    """
    if not found.gaps:
        return ""
    note = (f"read in {segments_phrase(found.segments)}, values missing at "
            f"{format_spans(found.gaps)} (nothing read across a gap)")  # fmt: skip
    if found.left_out:
        where = "; ".join(
            f"{o.stop:g}-{o.start:g} s ("
            + ("turns within" if o.across else "gap") + f" {o.gap[0]:g}-{o.gap[1]:g} s)"
            for o in found.left_out
        )
        n = len(found.left_out)
        note += (f"; {n} direction change{'s' if n > 1 else ''} left out, a gap within what is "
                 f"read around it: {where}")  # fmt: skip
    return note
