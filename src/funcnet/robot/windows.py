"""Analysis windows over a recording, and one functional network per window (paper section 4).

The paper computes networks per motion phase (section 4.1), in fixed windows of 280 / 600 /
600 ms anchored at the start of spin-up, cruise and braking (section 4.2), and in windows
shifted by +-20 and +-40 ms around a reversal (section 4.3, Fig. 11). A :class:`Window` is a
labelled time span ``start <= time < stop`` in seconds; the builders make lists of them and
:func:`phase_networks` computes a :class:`~funcnet.network.FunctionalNetwork` for each.
"""

from __future__ import annotations

import dataclasses
import math
import re
import warnings
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet.errors import (
    ChannelError,
    FuncnetError,
    ParameterError,
    StaircaseWarning,
    ThresholdWarning,
    WindowError,
)
from funcnet.network import FunctionalNetwork, functional_network
from funcnet.robot.phases import PHASES, phase_table
from funcnet.robot.preprocess import staircase_signals
from funcnet.robot.recording import Recording

__all__ = [
    "Window",
    "FIXED_LENGTHS",
    "REVERSAL_SHIFTS",
    "PAPER_NODES",
    "span_window",
    "phase_windows",
    "fixed_windows",
    "reversal_windows",
    "sliding_windows",
    "phase_networks",
    "CONSTANT_POLICIES",
]

#: Window lengths in seconds of the velocity study (paper section 4.2), by the phase whose start
#: anchors them; ``spin-up`` starts with early spin-up.
FIXED_LENGTHS = {"spin-up": 0.28, "cruise": 0.6, "braking": 0.6}
#: Shifts in seconds of the reversal windows (paper section 4.3, Fig. 11).
REVERSAL_SHIFTS = (-0.04, -0.02, 0.0, 0.02, 0.04)
#: The paper's nodes (section 4.1, Fig. 9), the default signals of :func:`phase_networks`.
PAPER_NODES = ("RP", "AP", "MP", "V", "RC", "AC")
#: What :func:`phase_networks` does with a signal constant inside a window: raise, or leave it out.
CONSTANT_POLICIES = ("error", "drop")
# The pairs a ThresholdWarning lists (funcnet.measures) differ from window to window.
_PAIR_LIST = re.compile(r" for \d+ pair\(s\):[^;]*")


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
        labelled by their span (``1.000-1.280 s``).

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
    >>> [w.label for w in sliding_windows(rec, 0.4, 0.3)]
    ['0.000-0.400 s', '0.300-0.700 s', '0.600-1.000 s']
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


def phase_networks(
    recording: Recording,
    windows: Sequence[Window] | pd.DataFrame,
    *,
    signals: Sequence[str] | None = None,
    constant: str = "error",
    **network_parameters,
) -> dict[str, FunctionalNetwork]:
    """One functional network per window.

    Parameters
    ----------
    recording : Recording
        Derived signals (V) should already be columns (:func:`add_derived_signals`), computed
        over the whole recording.
    windows : sequence of Window, or a phase table
        A phase table is turned into :func:`phase_windows`.
    signals : sequence of str, optional
        The nodes; default the paper's (:data:`PAPER_NODES`) that the recording has.
    constant : {"error", "drop"}
        A signal constant inside a window cannot be normalized (min-max or z-score): ``"error"``
        raises :class:`~funcnet.errors.SignalError`; ``"drop"`` leaves it out of that window's
        network (listed in its ``parameters["dropped"]``). Without normalization
        (``normalize=None``) nothing is dropped.
    **network_parameters
        Passed to :func:`funcnet.functional_network` (``dim``, ``delay``, ``rr``, ``cr``, ``mu``,
        ``normalize`` ...). Normalization (min-max by default) happens there, per window.

    Returns
    -------
    dict
        Window label -> FunctionalNetwork (labelled so), in window order. Each network's
        ``parameters`` also hold its window: ``window_start``, ``window_stop`` (seconds),
        ``phase``, ``source`` (the recording's file) and ``dropped`` (the signals left out).

    Raises
    ------
    WindowError
        A window outside the recording, with a signal not recorded (NaN) in it, with fewer than
        two signals left after dropping constant ones, or a duplicate label; the message names
        the file.
    ChannelError
        A signal that is not a column.
    ParameterError
        ``constant`` is not ``"error"`` or ``"drop"``.
    FuncnetError
        Any error of :func:`funcnet.functional_network` on a window (a constant signal, a window
        too short for the embedding, a bad parameter), of the same class, its message prefixed
        with the file, the window's label and its span.

    Warns
    -----
    StaircaseWarning
        A node's native interval is coarser than the grid (the 4 ms IPO signals AP and MP on the
        2 ms grid): it is a staircase, and recurrences are counted on repeated values. Use
        :func:`~funcnet.robot.resample` to avoid it.
    ThresholdWarning
        At most one per kind of problem for the whole call (not one per window), naming the
        windows that have it; the pairs concerned are flagged in each network's pairs table
        (``eps_ordered``, ``rate_exceeded``).

    References
    ----------
    Paper section 3.4 (construction), section 4 (networks per phase and window).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> t = np.arange(0, 2, 0.002)
    >>> data = pd.DataFrame({"RP": np.sin(5 * t), "AP": np.sin(5 * t - 0.3),
    ...                      "AC": np.where(t < 1, 0.0, np.cos(7 * t))},
    ...                     index=pd.Index(t, name="time"))
    >>> info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    >>> rec = Recording(data, {}, info, source="trace.csv", sample_period=0.002)
    >>> nets = phase_networks(rec, [Window("still", 0.2, 0.8), Window("moving", 1.2, 1.8)],
    ...                       constant="drop")
    >>> nets["still"].nodes, nets["still"].parameters["dropped"]
    (('RP', 'AP'), ['AC'])
    >>> {k: nets["moving"].parameters[k] for k in ("window_start", "window_stop", "source")}
    {'window_start': 1.2, 'window_stop': 1.8, 'source': 'trace.csv'}
    >>> phase_networks(rec, [Window("still", 0.2, 0.8)])
    Traceback (most recent call last):
        ...
    funcnet.errors.SignalError: trace.csv: window 'still' [0.2, 0.8) s: signal 'AC' is constant ...
    """
    if constant not in CONSTANT_POLICIES:
        raise ParameterError(f"constant must be 'error' or 'drop', got {constant!r}")
    if isinstance(windows, pd.DataFrame):
        windows = phase_windows(windows)
    where = recording.source or "<recording>"
    labels = [window.label for window in windows]
    duplicated = sorted(label for label, n in Counter(labels).items() if n > 1)
    if duplicated:
        raise WindowError(f"{where}: window labels {duplicated} occur more than once")
    if signals is None:
        signals = [name for name in PAPER_NODES if name in recording.data.columns]
    missing = [name for name in signals if name not in recording.data.columns]
    if missing or not signals:
        raise ChannelError(
            where,
            f"signals {missing or list(signals)} are not columns of the recording; it "
            f"has {list(recording.data.columns)}",
        )
    staircases = staircase_signals(recording, signals)
    if staircases:
        warnings.warn(
            StaircaseWarning(
                f"{where}: {staircases} change at most every "
                f"{max(recording.signals[s].interval for s in staircases) * 1e3:g} ms but are "
                f"analysed on the {recording.sample_period * 1e3:g} ms grid (staircases); "
                "funcnet.robot.resample decimates or interpolates them"
            ),
            stacklevel=2,
        )
    drop = constant == "drop" and network_parameters.get("normalize", "minmax") is not None
    networks = {}
    # The windows' warnings are gathered and issued once per kind below: a notebook looping
    # over a dozen windows should not print a dozen copies of the same advice.
    raised: list[tuple[str, warnings.WarningMessage]] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for window in windows:
            part = recording.window(window.start, window.stop).data[list(signals)]
            values = part.to_numpy(dtype=np.float64)
            if np.isnan(values).any():
                column = part.columns[np.isnan(values).any(axis=0)][0]
                raise WindowError(
                    f"{where}: window {window.label!r} {_span(window)}: "
                    f"signal {column!r} has no recorded value at some of its ticks"
                )
            dropped: list[str] = []
            if drop:
                dropped = [str(name) for name in part.columns[np.ptp(values, axis=0) == 0]]
            if dropped and len(signals) - len(dropped) < 2:
                raise WindowError(
                    f"{where}: window {window.label!r} {_span(window)}: signals {dropped} are "
                    "constant in it, which leaves fewer than two signals"
                )
            seen = len(caught)
            try:
                network = functional_network(
                    part.drop(columns=dropped), label=window.label, **network_parameters
                )
            except FuncnetError as error:
                _locate(error, where, window)
                raise
            raised.extend((window.label, w) for w in caught[seen:])
            networks[window.label] = dataclasses.replace(
                network,
                parameters={
                    **network.parameters,
                    "window_start": window.start,
                    "window_stop": window.stop,
                    "phase": window.phase,
                    "source": recording.source,
                    "dropped": dropped,
                },
            )
    # Kind -> (window label, first line without its list of pairs) of each window that has it.
    threshold_windows: dict[tuple[type[Warning], str], list[tuple[str, str]]] = {}
    for label, w in raised:
        if issubclass(w.category, ThresholdWarning):
            first_line = _PAIR_LIST.sub("", (str(w.message).splitlines() or [""])[0])
            kind = (w.category, _warning_kind(first_line, signals))
            threshold_windows.setdefault(kind, []).append((label, first_line))
        else:
            warnings.warn(w.message, stacklevel=2)
    for (category, _), concerned in threshold_windows.items():
        (label, text), *others = concerned
        details = f" (details as in {label!r})" if any(t != text for _, t in others) else ""
        warnings.warn(
            f"{text}\n{where}: in {len(concerned)} of {len(windows)} window(s): "
            f"{', '.join(repr(label) for label, _ in concerned)}{details}",
            category,
            stacklevel=2,
        )
    return networks


def _warning_kind(text: str, signals: Sequence[str]) -> str:
    """The words of ``text`` before its first detail (a number, a parenthesis, a signal name).

    The details differ from window to window; the words before them name the kind of problem.
    """
    words = []
    for word in text.split():
        if word[0] in "(0123456789" or word.strip(",;:") in signals:
            break
        words.append(word)
    return " ".join(words)


def _locate(error: FuncnetError, where: str, window: Window) -> None:
    """Put the recording's file and the window in front of ``error``'s message."""
    # Changed in place: the class, the traceback and attributes such as TraceError.path stay,
    # whatever the class's constructor takes.
    error.args = (f"{where}: window {window.label!r} {_span(window)}: {error}",)


def _span(window: Window) -> str:
    return f"[{window.start:g}, {window.stop:g}) s"
