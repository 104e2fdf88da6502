"""Direction changes of an axis in a trace, and the recording the indicators read.

A *direction change* is where the position set-point RP stops moving one way and next moves
the other way. When the standstill between the two moves is short (at most ``max_dwell``, 0.5 s
as the reversal phase of :func:`funcnet.robot.detect_phases`) it is a **reversal** as in the
paper's backlash trials (section 4.3): the motor crosses the gear's dead zone right after its
turning point. After a longer standstill (``kind="after standstill"``) the dead zone is crossed
too, at the start of the next move, from rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from funcnet.errors import ChannelError, ParameterError
from funcnet.robot.preprocess import add_derived_signals, resample, staircase_signals, velocity
from funcnet.robot.recording import Recording

__all__ = ["DirectionChange", "find_direction_changes", "motor_side_recording", "MAX_DWELL"]

#: Longest standstill, in s, between the two moves of a reversal (as ``detect_phases``).
MAX_DWELL = 0.5


@dataclass(frozen=True)
class DirectionChange:
    """One direction change of the set-point.

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
        ``"reversal"`` (dwell at most ``max_dwell``) or ``"after standstill"``.
    """

    stop: float
    start: float
    dwell: float
    direction: int
    kind: str

    def to_dict(self) -> dict[str, float | int | str]:
        """The fields as a JSON-ready dict."""
        return {
            "stop": self.stop,
            "start": self.start,
            "dwell": self.dwell,
            "direction": self.direction,
            "kind": self.kind,
        }


def find_direction_changes(
    recording: Recording,
    *,
    reference: str = "RP",
    standstill: float = 1e-4,
    max_dwell: float = MAX_DWELL,
    min_gap: float = 0.05,
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
    """
    if reference not in recording.data.columns:
        raise ChannelError(
            recording.source or "<recording>", f"no {reference!r} column to find the moves"
        )
    if not (0 < standstill < 1) or not (max_dwell >= 0 and math.isfinite(max_dwell)):
        raise ParameterError.of("standstill", "must be in (0, 1), max_dwell >= 0")
    dt = recording.sample_period
    x = recording.data[reference].to_numpy(dtype=np.float64)
    x = np.where(np.isnan(x), np.nanmean(x) if np.isfinite(x).any() else 0.0, x)
    v = velocity(x, dt)
    if not np.any(v):
        return []
    moving = np.abs(v) > standstill * np.abs(v).max()
    edges = np.flatnonzero(np.diff(np.concatenate([[0], moving.astype(np.int8), [0]])))
    runs = [[int(a), int(b)] for a, b in zip(edges[::2], edges[1::2], strict=True)]
    moves: list[list[int]] = []
    for a, b in runs:  # join same-direction runs separated by less than min_gap
        sign = np.sign(v[a:b].sum())
        if moves and np.sign(v[moves[-1][0] : moves[-1][1]].sum()) == sign:
            if (a - moves[-1][1]) * dt < min_gap:
                moves[-1][1] = b
                continue
        moves.append([a, b])
    t0 = float(recording.data.index[0])
    changes = []
    for (a0, b0), (a1, b1) in zip(moves, moves[1:], strict=False):
        s0, s1 = np.sign(v[a0:b0].sum()), np.sign(v[a1:b1].sum())
        if s0 == s1 or s1 == 0:
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
    return changes


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
