"""Analysis windows over a recording (paper section 4).

The paper computes networks per motion phase (section 4.1), in fixed windows of 280 / 600 /
600 ms anchored at the start of spin-up, cruise and braking (section 4.2), and in windows
shifted by +-20 and +-40 ms around a reversal (section 4.3, Fig. 11). A :class:`Window` is a
labelled time span ``start <= time < stop`` in seconds
(:meth:`~funcnet.robot.Recording.window` cuts it out of a recording); the builders make lists
of them and :func:`funcnet.window_networks` computes a functional network for each.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import pandas as pd

from funcnet.errors import ParameterError, WindowError
from funcnet.robot.axes import axes_of, qualified
from funcnet.robot.phases import PHASES, phase_table
from funcnet.robot.recording import Recording

__all__ = [
    "Window",
    "FIXED_LENGTHS",
    "REVERSAL_SHIFTS",
    "PAPER_NODES",
    "paper_nodes",
    "span_window",
    "complete_span",
    "phase_windows",
    "fixed_windows",
    "reversal_windows",
    "sliding_windows",
]

#: Window lengths in seconds of the velocity study (paper section 4.2), by the phase whose start
#: anchors them; ``spin-up`` starts with early spin-up.
FIXED_LENGTHS = {"spin-up": 0.28, "cruise": 0.6, "braking": 0.6}
#: Shifts in seconds of the reversal windows (paper section 4.3, Fig. 11).
REVERSAL_SHIFTS = (-0.04, -0.02, 0.0, 0.02, 0.04)
#: The paper's nodes (section 4.1, Fig. 9), the default signals of
#: :func:`funcnet.window_networks`.
PAPER_NODES = ("RP", "AP", "MP", "V", "RC", "AC")


def paper_nodes(columns: Iterable[str]) -> list[str]:
    """The paper's nodes among a recording's columns: the default nodes of a network.

    In a recording of several axes, every axis's (``A1.RP``, ``A1.AP``, ..., ``A2.RP``, ...),
    grouped per axis.

    Examples
    --------
    >>> paper_nodes(["AC", "RP", "aaStat", "V"])
    ['RP', 'V', 'AC']
    >>> paper_nodes(["A1.RP", "A2.RP", "A1.MP", "time_disc"])
    ['A1.RP', 'A1.MP', 'A2.RP']
    """
    present = list(columns)
    axes = axes_of(present)
    if not axes:
        return [name for name in PAPER_NODES if name in present]
    return [qualified(a, name) for a in axes for name in PAPER_NODES
            if qualified(a, name) in present]


@dataclass(frozen=True)
class Window:
    """A labelled analysis window ``start <= time < stop`` (seconds).

    Attributes
    ----------
    label : str
        Unique within one list of windows; the label of its network.
    start, stop : float
        Seconds on the recording's time axis.
    phase : str or None
        The phase it belongs to (None for sliding windows).
    offset : float
        Its shift in seconds from the phase it is anchored at (reversal windows), else 0.

    Examples
    --------
    >>> Window("cruise", 1.0, 1.6, phase="cruise").duration
    0.6
    """

    label: str
    start: float
    stop: float
    phase: str | None = None
    offset: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.start) and math.isfinite(self.stop) and self.start < self.stop):
            raise WindowError(
                f"window {self.label!r}: needs start < stop, got {self.start}, {self.stop}"
            )

    @property
    def duration(self) -> float:
        """``stop - start`` in seconds, rounded to the nanosecond."""
        return round(self.stop - self.start, 9)


def span_window(start: float, stop: float) -> Window:
    """A window over a time range, labelled by its span (``1.000-1.280 s``).

    Parameters
    ----------
    start, stop : float
        Seconds on the recording's time axis, ``start < stop``.

    Returns
    -------
    Window
        Without a phase; the label of sliding windows and of explicit time ranges.

    Raises
    ------
    WindowError
        ``start >= stop``.

    Examples
    --------
    >>> span_window(1.0, 1.28)
    Window(label='1.000-1.280 s', start=1.0, stop=1.28, phase=None, offset=0.0)
    """
    return Window(f"{start:.3f}-{stop:.3f} s", start, stop)


def complete_span(recording: Recording) -> Window:
    """The span where every signal of a recording has a recorded value, as one window.

    Signals logged on a coarser grid (the 4 ms IPO signals AP and MP on a 2 ms trace) have no
    value at the first ticks; a window starting there would hold NaN. The window runs from the
    first tick where every column has a value to one sample period past the last such tick
    (windows hold ``start <= time < stop``).

    Parameters
    ----------
    recording : Recording

    Returns
    -------
    Window
        Labelled ``"whole recording"``, without a phase.

    Raises
    ------
    WindowError
        No tick where every signal has a value; the message names the recording's source.

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.robot import Recording, SignalInfo
    >>> data = pd.DataFrame({"RC": [0.0, 1.0, 2.0, 3.0], "AP": [np.nan, 1.0, np.nan, 2.0]},
    ...                     index=pd.Index([0.0, 0.002, 0.004, 0.006], name="time"))
    >>> info = {n: SignalInfo(n, None, None, 0.002) for n in data}
    >>> rec = Recording(data.ffill().where(data.notna().cummax()), {}, info, source="t.csv",
    ...                 sample_period=0.002)
    >>> complete_span(rec)
    Window(label='whole recording', start=0.002, stop=0.008, phase=None, offset=0.0)
    """
    recorded = recording.data.index[recording.data.notna().all(axis=1).to_numpy()]
    if recorded.empty:
        raise WindowError(f"{recording.source or '<recording>'}: no tick where every signal has "
                          "a recorded value")
    start, stop = float(recorded[0]), float(recorded[-1]) + recording.sample_period
    return Window(label="whole recording", start=start, stop=stop)


def _numbered(names: Sequence[str]) -> list[str]:
    """Append 1, 2, ... to the names that occur more than once."""
    counts = Counter(names)
    seen: Counter[str] = Counter()
    labels = []
    for name in names:
        seen[name] += 1
        labels.append(f"{name} {seen[name]}" if counts[name] > 1 else name)
    return labels


def phase_windows(
    phases: pd.DataFrame | Mapping[str, tuple[float, float]] | Iterable[tuple[str, float, float]],
    *,
    include: Iterable[str] | None = None,
) -> list[Window]:
    """One window per phase.

    Parameters
    ----------
    phases : table, dict or tuples
        From :func:`~funcnet.robot.detect_phases` or by hand (see
        :func:`~funcnet.robot.phases.phase_table`).
    include : iterable of str, optional
        Phases to keep; default every phase but ``standstill``.

    Returns
    -------
    list of Window
        In table order, labelled by phase, numbered when a phase occurs more than once
        (``cruise 1``, ``cruise 2``).

    References
    ----------
    Paper section 4.1: one network per phase (Fig. 9).

    Examples
    --------
    >>> phase_windows({"early spin-up": (0.0, 0.22), "cruise": (1.0, 5.0)})
    [Window(label='early spin-up', start=0.0, stop=0.22, phase='early spin-up', offset=0.0),
     Window(label='cruise', start=1.0, stop=5.0, phase='cruise', offset=0.0)]
    """
    table = phase_table(phases)
    keep = set(PHASES[1:]) if include is None else set(include)
    rows = [row for row in table.itertuples(index=False) if row.phase in keep]
    labels = _numbered([row.phase for row in rows])
    return [
        Window(label, row.start, row.stop, phase=row.phase)
        for label, row in zip(labels, rows, strict=True)
    ]


def fixed_windows(
    phases: pd.DataFrame | Mapping[str, tuple[float, float]] | Iterable[tuple[str, float, float]],
    lengths: Mapping[str, float] | None = None,
) -> list[Window]:
    """Windows of fixed length anchored at the start of phases.

    Parameters
    ----------
    phases : table, dict or tuples
        As for :func:`phase_windows`.
    lengths : dict, optional
        Anchor phase -> length in seconds; default :data:`FIXED_LENGTHS` (spin-up 280 ms,
        cruise 600 ms, braking 600 ms). ``spin-up`` anchors at the start of an early spin-up, or
        of a late spin-up not preceded by one; any other key is a phase name of the table.

    Returns
    -------
    list of Window
        In time order, labelled by anchor (numbered when repeated). A window may reach beyond its
        phase (600 ms of braking into the standstill after it), so that windows compare across
        speeds.

    References
    ----------
    Paper section 4.2: fixed windows of 280, 600 and 600 ms for spin-up, cruise and braking.

    Examples
    --------
    >>> table = {"early spin-up": (1.0, 1.2), "late spin-up": (1.2, 1.7),
    ...          "cruise": (1.7, 3.1), "braking": (3.1, 3.8)}
    >>> [(w.label, w.start, w.stop) for w in fixed_windows(table)]
    [('spin-up', 1.0, 1.28), ('cruise', 1.7, 2.3), ('braking', 3.1, 3.7)]
    """
    lengths = dict(FIXED_LENGTHS if lengths is None else lengths)
    for anchor, length in lengths.items():
        if not (length > 0 and math.isfinite(length)):
            raise ParameterError(f"lengths: {anchor!r} needs a length > 0 s, got {length}")
    table = phase_table(phases)
    anchors = []
    previous = None
    for row in table.itertuples(index=False):
        name = row.phase
        if name == "early spin-up" or (name == "late spin-up" and previous != "early spin-up"):
            name = "spin-up"
        if name in lengths:
            anchors.append((name, row.start))
        previous = row.phase
    anchors.sort(key=lambda anchor: anchor[1])
    labels = _numbered([name for name, _ in anchors])
    return [
        Window(label, start, round(start + lengths[name], 9), phase=name)
        for label, (name, start) in zip(labels, anchors, strict=True)
    ]


def reversal_windows(
    phases: pd.DataFrame | Mapping[str, tuple[float, float]] | Iterable[tuple[str, float, float]],
    *,
    shifts: Sequence[float] = REVERSAL_SHIFTS,
    width: float | None = None,
) -> list[Window]:
    """Windows around each reversal, shifted in time.

    Parameters
    ----------
    phases : table, dict or tuples
        As for :func:`phase_windows`; its ``reversal`` rows are used.
    shifts : sequence of float
        Shifts in seconds; default :data:`REVERSAL_SHIFTS` (-40, -20, 0, +20, +40 ms).
    width : float, optional
        Window length in seconds, centred on the reversal phase's middle; default the reversal
        phase's own span.

    Returns
    -------
    list of Window
        ``offset`` = shift; labelled ``reversal -40 ms`` ... (``reversal 2 -40 ms`` when there
        are several reversals).

    Raises
    ------
    WindowError
        The table has no reversal.

    References
    ----------
    Paper section 4.3, Fig. 11: windows shifted by +-20 and +-40 ms around the reversal.

    Examples
    --------
    >>> [(w.label, w.start, w.stop) for w in reversal_windows({"reversal": (1.7, 2.0)},
    ...                                                       shifts=(-0.02, 0.0, 0.02))]
    [('reversal -20 ms', 1.68, 1.98), ('reversal +0 ms', 1.7, 2.0), ('reversal +20 ms', 1.72, 2.02)]
    """
    if width is not None and not (width > 0 and math.isfinite(width)):
        raise ParameterError(f"width: must be > 0 seconds, got {width}")
    table = phase_table(phases)
    reversals = table[table["phase"] == "reversal"]
    if reversals.empty:
        raise WindowError("reversal_windows: the phase table has no reversal")
    names = _numbered(["reversal"] * len(reversals))
    windows = []
    for name, row in zip(names, reversals.itertuples(index=False), strict=True):
        middle = (row.start + row.stop) / 2
        half = (row.stop - row.start if width is None else width) / 2
        for shift in shifts:
            windows.append(
                Window(
                    f"{name} {shift * 1e3:+.0f} ms",
                    round(middle - half + shift, 9),
                    round(middle + half + shift, 9),
                    phase="reversal",
                    offset=float(shift),
                )
            )
    return windows


def sliding_windows(
    recording: Recording,
    width: float,
    step: float,
    *,
    start: float | None = None,
    stop: float | None = None,
) -> list[Window]:
    """Windows of ``width`` seconds every ``step`` seconds over a recording.

    Parameters
    ----------
    recording : Recording
    width, step : float
        Seconds, both > 0.
    start, stop : float, optional
        The span to cover; default the whole recording.

    Returns
    -------
    list of Window
        ``[start + k step, start + k step + width)`` for every k that fits before ``stop``;
        labelled by their span (``1.000-1.280 s``). Each holds the ticks ``start <= t < stop``
        (:meth:`Recording.window <funcnet.robot.Recording.window>`), so windows with
        ``step == width`` share no tick.

    Raises
    ------
    WindowError
        ``width`` is longer than the span (the message names the recording's file).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0] * 10}, index=pd.Index([i / 10 for i in range(10)],
    ...                     name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.1)}, sample_period=0.1)
    >>> windows = sliding_windows(rec, 0.4, 0.3)
    >>> [w.label for w in windows]
    ['0.000-0.400 s', '0.300-0.700 s', '0.600-1.000 s']
    >>> rec.window(windows[1].start, windows[1].stop).data.index.tolist()
    [0.3, 0.4, 0.5, 0.6]
    """
    for value, name in ((width, "width"), (step, "step")):
        if not (value > 0 and math.isfinite(value)):
            raise ParameterError(f"{name}: must be > 0 seconds, got {value}")
    t0 = float(recording.data.index[0])
    first = t0 if start is None else start
    last = t0 + recording.duration if stop is None else stop
    if width > last - first + 1e-9:
        raise WindowError(
            f"{recording.source or '<recording>'}: a {width:g} s window is longer than the "
            f"{last - first:g} s it should slide over"
        )
    count = math.floor((last - first - width) / step + 1e-9) + 1
    starts = [round(first + k * step, 9) for k in range(count)]
    return [span_window(begin, round(begin + width, 9)) for begin in starts]
