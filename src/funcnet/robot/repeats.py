"""Repetitions of one motion: moves with the same set-point profile, aligned on the set-point.

A robot repeats its motions: a trace holds several moves of one profile, a plant runs one
program many times (several traces given together), a simulator gives any number of seeds. The
repetition test of the evidence layer (:func:`funcnet.evidence.repetitions.repetition_evidence`)
takes one window per repetition, all aligned on the command; :func:`find_repetitions` makes
them.

Moves
    A move is a maximal stretch of a recording between standstills (its phases from
    :func:`~funcnet.robot.detect_phases`: spin-up, cruise, braking, and a reversal with the move
    back when there is no standstill between them).

Same profile
    Two moves repeat each other when their set-point displacements from the start of the move
    agree: the same number of samples (within ``tolerance`` of the duration) and a largest
    difference of at most ``tolerance`` of the travel, after the alignment below. A move in the
    opposite direction is the *mirror* of one whose displacement is its negative; with
    ``mirror=True`` it counts as a repetition, its signals negated (positions, speeds and
    currents all change sign with the direction). That assumes the axis behaves alike in both
    directions: no gravity load, symmetric friction -- what a real axis need not do, so it is
    off by default.

Alignment on the set-point
    Each move's start (the first sample that leaves standstill) is refined by the lag, within
    ``max_lag`` seconds, that maximizes the cross-correlation of its set-point velocity with
    the first move's; the phases are the first move's, at the same offsets from the start in
    every repetition. Positions are taken relative to the set-point at the start of the move,
    so that repetitions at other places on the axis line up.

The moves of the largest group of repetitions form the result, whatever order the recordings
and moves come in (ties: the group of the earliest move).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from funcnet._lazy import deprecated_names
from funcnet.errors import ParameterError, SignalError
from funcnet.robot.phases import detect_phases
from funcnet.robot.preprocess import velocity
from funcnet.robot.recording import Recording
from funcnet.robot.windows import _numbered

__all__ = ["Repetitions", "find_repetitions", "ABSOLUTE_POSITION_ROLES"]

#: Roles whose values are positions from the axis's zero (not differences of positions, as FE):
#: taken relative to the set-point at the start of the move.
ABSOLUTE_POSITION_ROLES = ("RP", "AP", "MP")


@dataclass(frozen=True)
class Repetitions:
    """Repetitions of one motion, aligned on the set-point, cut into phase windows.

    Attributes
    ----------
    moves : pandas.DataFrame
        One row per repetition: ``recording`` (position in the input), ``source``, ``move``
        (its number in that recording, from 1), ``start``, ``stop`` (s, aligned),
        ``direction`` (+1 or -1), ``mirrored`` (bool) and ``lag`` (s, the alignment's shift
        of the start).
    phases : pandas.DataFrame
        The phases of the first repetition, ``phase``, ``start``, ``stop`` in seconds from the
        start of the move.
    windows : dict of str to list of pandas.DataFrame
        Per phase (labelled as :func:`~funcnet.robot.phase_windows` labels them) one window
        per repetition, equal in length, columns the signals: ready for
        :func:`funcnet.evidence.repetitions.repetition_evidence`.
    others : int
        Moves left out: of another profile (another group), too short, or mirrored without
        ``mirror=True``.
    left_out : tuple of str
        Per move left out, why it does not repeat the first repetition: ``"recording 1 move
        2: 1964 samples against 2707 (more than 2 % apart)"``, ... (in the order found).
    """

    moves: pd.DataFrame
    phases: pd.DataFrame
    windows: dict[str, list[pd.DataFrame]] = field(repr=False)
    others: int
    left_out: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.moves)


@dataclass(frozen=True)
class _Move:
    recording: int
    number: int
    first: int
    stop: int
    direction: int
    displacement: np.ndarray = field(repr=False)


def _moves(
    recordings: Sequence[Recording], tables: Sequence[pd.DataFrame], reference: str
) -> list[_Move]:
    """The moves of each recording, from its phase table (:func:`detect_phases`)."""
    found = []
    for r, (recording, table) in enumerate(zip(recordings, tables, strict=True)):
        moving = (table.phase != "standstill").to_numpy()
        index = recording.data.index
        rp = recording.data[reference].to_numpy(dtype=np.float64)
        number = 0
        row = 0
        while row < len(table):
            if not moving[row]:
                row += 1
                continue
            last = row
            while last + 1 < len(table) and moving[last + 1]:
                last += 1
            first = int(index.get_indexer([table.start.iloc[row]], method="nearest")[0])
            stop = int(index.get_indexer([table.stop.iloc[last]], method="nearest")[0])
            if table.stop.iloc[last] >= index[-1]:
                stop = len(index)
            number += 1
            travel = rp[stop - 1] - rp[first]
            signed = velocity(rp[first:stop], recording.sample_period).sum()
            direction = 1 if (travel if travel != 0 else signed) >= 0 else -1
            found.append(_Move(r, number, first, stop, direction, rp[first:stop] - rp[first]))
            row = last + 1
    return found


def _lag(reference: np.ndarray, other: np.ndarray, max_lag: int) -> int:
    """Shift of ``other`` (samples) that best matches ``reference`` (set-point velocities,
    zero outside the moves); ties: the smallest shift."""
    padded = np.concatenate([np.zeros(max_lag), other, np.zeros(max_lag + reference.size)])
    best, best_value = 0, -np.inf
    for lag in sorted(range(-max_lag, max_lag + 1), key=abs):
        value = float(np.dot(reference, padded[max_lag + lag: max_lag + lag + reference.size]))
        if value > best_value * (1 + 1e-12) + 1e-300:
            best, best_value = lag, value
    return best


def _checked_signals(items: Sequence[Recording], signals: Sequence[str] | None,
                     tolerance: float, max_lag: float) -> list[str]:
    """The windows' columns, after the recordings and the parameters are checked."""
    if not items:
        raise ParameterError.of("recordings", "holds no recording")
    periods = {round(item.sample_period, 12) for item in items}
    if len(periods) != 1:
        raise ParameterError.of("recordings", f"must share one sample period, got "
                                f"{sorted(periods)} s (resample them first)")
    if not 0 < tolerance < 1:
        raise ParameterError.of("tolerance", f"must be in (0, 1), got {tolerance!r}")
    if not max_lag >= 0:
        raise ParameterError.of("max_lag", f"must be >= 0 seconds, got {max_lag!r}")
    if signals is None:
        signals = [c for c in items[0].data.columns if all(c in i.data.columns for i in items)]
    for r, item in enumerate(items):
        missing = [s for s in signals if s not in item.data.columns]
        if missing:
            raise SignalError(f"recording {r} ({item.source}) has no signal(s) "
                              f"{', '.join(map(str, missing))}")
    return list(signals)


def _match(a: _Move, b: _Move, *, setpoints: Sequence[np.ndarray], period: float, mirror: bool,
           tolerance: float, lag_samples: int) -> tuple[bool, bool, int, str]:
    """(same profile, mirrored, lag of ``b`` behind ``a`` in samples, why not)."""
    n_a, n_b = a.displacement.size, b.displacement.size
    mirrored = a.direction != b.direction
    if mirrored and not mirror:
        return False, False, 0, "it moves the other way (mirrored moves are not counted)"
    if abs(n_a - n_b) > tolerance * max(n_a, n_b) + 2 * lag_samples:
        return False, False, 0, (f"{n_b} samples long against {n_a} (more than "
                                 f"{tolerance:.0%} and {2 * lag_samples} samples apart)")
    sign = -1.0 if mirrored else 1.0
    lag = _lag(velocity(a.displacement, period),
               velocity(sign * b.displacement, period), lag_samples)
    rp = setpoints[b.recording]
    start = b.first + lag
    n = min(n_a, rp.size - start) if start >= 0 else 0
    if n < 2:
        return False, False, 0, "aligned, it leaves its recording"
    other = sign * (rp[start:start + n] - rp[start])
    travel = max(np.abs(a.displacement).max(), 1e-300)
    apart = float(np.abs(a.displacement[:n] - other).max())
    same = apart <= tolerance * travel
    why = "" if same else (f"its set-point departs from the first's by {apart / travel:.1%} "
                           f"of the travel once aligned (more than {tolerance:.0%})")
    return bool(same), mirrored, lag, why


def _cut_windows(items: Sequence[Recording], group: Sequence[tuple[_Move, bool, int]],
                 starts: Sequence[int], relative: pd.DataFrame, signals: Sequence[str],
                 reference: str) -> dict[str, list[pd.DataFrame]]:
    """Each phase's window of every repetition, positions from the move's start, a mirrored
    repetition negated, on the time from the phase's start in the first repetition."""
    period = items[0].sample_period
    labels = _numbered(list(relative.phase))
    windows: dict[str, list[pd.DataFrame]] = {label: [] for label in labels}
    for (move, mirrored, _), start in zip(group, starts, strict=True):
        data = items[move.recording].data
        origin = float(data[reference].iloc[move.first])
        sign = -1.0 if mirrored else 1.0
        for label, phase in zip(labels, relative.itertuples(index=False), strict=True):
            a = start + int(round(phase.start / period))
            b = start + int(round(phase.stop / period))
            if a < 0 or b > len(data):
                raise SignalError(f"recording {move.recording}: move {move.number} aligned "
                                  f"by {(start - move.first) * period:g} s leaves the recording")
            window = data[list(signals)].iloc[a:b].copy()
            for column in window.columns:
                if column in ABSOLUTE_POSITION_ROLES:
                    window[column] = window[column] - origin
            window = window * sign
            window.index = pd.Index(np.round(np.arange(b - a) * period + phase.start, 9),
                                    name="time")
            windows[label].append(window)
    return windows


def find_repetitions(
    recordings: Recording | Sequence[Recording],
    *,
    signals: Sequence[str] | None = None,
    reference: str = "RP",
    mirror: bool = False,
    tolerance: float = 0.02,
    max_lag: float = 0.05,
) -> Repetitions:
    """The repetitions of the most repeated motion in one or several recordings (module notes).

    Parameters
    ----------
    recordings : Recording or sequence of Recording
        One trace, several traces of one program, or simulated runs; one sample period.
    signals : sequence of str, optional
        The columns of the windows (default: every column of the first recording that all
        have).
    reference : str
        The set-point column.
    mirror : bool
        Count moves in the opposite direction with the mirrored profile, negated.
    tolerance : float
        Largest relative difference of duration and of set-point displacement (fraction of
        the travel) between repetitions.
    max_lag : float
        Largest shift in seconds of the alignment on the set-point.

    Returns
    -------
    Repetitions

    Raises
    ------
    ParameterError
        No recording, unequal sample periods, a bad ``tolerance`` or ``max_lag``.
    ChannelError
        No ``reference`` column.
    SignalError
        No move, or a signal missing in a recording.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> t = np.arange(0, 7, 0.01)
    >>> ramp = lambda t0: np.clip(t - t0, 0, 1) - np.clip(t - t0 - 1.5, 0, 1)
    >>> rp = np.cumsum(ramp(0.5) - ramp(3.8)) * 0.01  # a move there, a pause, one back
    >>> data = pd.DataFrame({"RP": rp, "AC": np.gradient(rp)},
    ...                     index=pd.Index(t.round(9), name="time"))
    >>> rec = Recording(data, {}, {c: SignalInfo(c, None, None, 0.01) for c in data},
    ...                 sample_period=0.01)
    >>> len(find_repetitions(rec)), len(find_repetitions(rec, mirror=True))
    (1, 2)
    >>> find_repetitions(rec, mirror=True).moves[["move", "direction", "mirrored"]]
       move  direction  mirrored
    0     1          1     False
    1     2         -1      True
    """
    items = [recordings] if isinstance(recordings, Recording) else list(recordings)
    signals = _checked_signals(items, signals, tolerance, max_lag)
    period = items[0].sample_period
    tables = [detect_phases(item, reference=reference) for item in items]
    moves = _moves(items, tables, reference)
    if not moves:
        raise SignalError(f"no move of the set-point {reference} in the recordings")
    lag_samples = int(round(max_lag / period))

    setpoints = [item.data[reference].to_numpy(dtype=np.float64) for item in items]

    matches = functools.partial(_match, setpoints=setpoints, period=period, mirror=mirror,
                                tolerance=tolerance, lag_samples=lag_samples)

    groups: list[list[tuple[_Move, bool, int]]] = []
    for move in moves:
        for group in groups:
            same, mirrored, lag, _ = matches(group[0][0], move)
            if same:
                group.append((move, mirrored, lag))
                break
        else:
            groups.append([(move, False, 0)])
    group = max(groups, key=len)  # max keeps the first of equal length
    first = group[0][0]
    taken = {id(move) for move, _, _ in group}
    left_out = tuple(
        f"recording {move.recording + 1} move {move.number}: {matches(first, move)[3]}"
        for move in moves if id(move) not in taken
    )
    length = min(min(move.stop, setpoints[move.recording].size) - (move.first + lag)
                 for move, _, lag in group)
    rows, starts = [], []
    for move, mirrored, lag in group:
        starts.append(move.first + lag)
        start = float(items[move.recording].data.index[0]) + (move.first + lag) * period
        rows.append({"recording": move.recording, "source": items[move.recording].source,
                     "move": move.number, "start": round(start, 9),
                     "stop": round(start + length * period, 9), "direction": move.direction,
                     "mirrored": mirrored, "lag": round(lag * period, 9)})
    relative = tables[first.recording]
    t0 = float(items[first.recording].data.index[first.first])
    relative = relative[(relative.stop > t0 + 1e-9) & (relative.start < t0 + length * period
                                                          - 1e-9)].copy()
    relative["start"] = np.maximum(relative.start - t0, 0.0).round(9)
    relative["stop"] = np.minimum(relative.stop - t0, length * period).round(9)
    relative = relative[relative.phase != "standstill"].reset_index(drop=True)
    windows = _cut_windows(items, group, starts, relative, signals, reference)
    return Repetitions(moves=pd.DataFrame(rows), phases=relative, windows=windows,
                       others=len(moves) - len(group), left_out=left_out)


# Renamed names, still given with a DeprecationWarning.
__getattr__ = deprecated_names(__name__, {"POSITION_ROLES": "ABSOLUTE_POSITION_ROLES"})
