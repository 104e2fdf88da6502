"""From a recording and its windows to one functional network per window (paper section 4).

:func:`window_networks` cuts each window out of a :class:`~funcnet.robot.Recording`, computes
its :class:`~funcnet.network.FunctionalNetwork` with one :class:`~funcnet.NetworkParameters`
and says, once per kind of problem for the whole call, what the networks' pairs tables flag.
The warnings are built from those flags (:func:`window_warnings`), not caught from the
computation, so that several calls may run at once in threads.

A window that fails (too short for the embedding, a signal not recorded in it, too short for
the asymmetry intervals of its evidence) raises its error, located; with
``errors="collect"`` it is recorded instead (:class:`WindowFailure`, in the result's
``failures``) and the other windows go on: the one way to compute many windows when some may
fail.

Length: over 600 lines because the batched and the per-window paths, their failures and the
one summary of their warnings belong together.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any, Unpack

import numpy as np
import pandas as pd

from funcnet.core import batch
from funcnet.core.measures import CrossMeasures, threshold_warnings
from funcnet.core.normalization import normalize as normalize_signals
from funcnet.errors import (
    ChannelError,
    FuncnetError,
    FuncnetWarning,
    ParameterError,
    RecordingWarning,
    WindowError,
    caller_stacklevel,
)
from funcnet.network import (
    FunctionalNetwork,
    add_evidence,
    edges_from_pairs,
    functional_network,
)
from funcnet.network.direction import window_directions, window_p_values
from funcnet.network.edge_evidence import check_evidence_settings
from funcnet.network.precision import logged_step, single_spacing
from funcnet.network.rule import rule_columns
from funcnet.network.schema import RESULT_COLUMNS, pairs_frame
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides, resolve
from funcnet.robot.preprocess import staircase_warning
from funcnet.robot.recording import Recording
from funcnet.robot.windows import Window, paper_nodes, phase_windows

__all__ = ["window_networks", "window_evidence", "window_warnings", "constant_warning",
           "constant_signals", "WindowNetworks", "WindowFailure", "CONSTANT_POLICIES",
           "ERROR_POLICIES", "FAILURE_PARTS"]

#: What :func:`window_networks` does with a signal constant inside a window: raise, or leave it
#: out of that window's network (the default: one window does not stop the others).
CONSTANT_POLICIES = ("error", "drop")
#: What :func:`window_networks` and :func:`window_evidence` do with a window that fails: raise
#: its error, or record it (:class:`WindowFailure`) and go on with the other windows.
ERROR_POLICIES = ("raise", "collect")
#: The parts of a window's result a :class:`WindowFailure` can name.
FAILURE_PARTS = ("network", "evidence", "intervals")


# How a summary names a problem (what is wrong, what to read); the pairs follow the first part.
_SUMMARIES: dict[str, tuple[str, str]] = {
    "eps_order": (
        "eps_xy is not below eps_x and eps_y",
        "section 2.2 of the paper asks eps_xy < eps_x, eps_y for a modular ISRN "
        "(eps_ordered is False)",
    ),
    "rate_exceeded": (
        "ties at a threshold pushed an achieved rate above its target",
        "see achieved_rr_x, achieved_rr_y, achieved_cr (rate_exceeded is True)",
    ),
    "degenerate": (
        "degenerate recurrence structure",
        "threshold 0, an achieved rate more than twice its target or a constant signal, i.e. "
        "too few distinct states (e.g. a signal that barely moves); the arrows of these pairs "
        "are meaningless (degenerate is True)",
    ),
}


@dataclass(frozen=True)
class WindowFailure:
    """A window without its network, or without a part of its evidence (``errors="collect"``).

    Attributes
    ----------
    window : str
        The window's label.
    part : str
        What the window lacks (:data:`FAILURE_PARTS`): ``"network"`` (it has none),
        ``"evidence"`` (its network has no evidence columns) or ``"intervals"`` (its evidence
        has no asymmetry intervals, ``c_diff_low`` ... NaN: the subsamples of the intervals are
        too short, while the coupling test ran).
    message : str
        The error's message, after the recording's file, the window's label and its span.
    """

    window: str
    part: str
    message: str


class WindowNetworks(dict[str, FunctionalNetwork]):
    """Window label -> FunctionalNetwork, in window order, and the windows that failed.

    What :func:`window_networks` and :func:`window_evidence` return: a dict, with
    ``failures`` (a tuple of :class:`WindowFailure`, in window order) empty unless they were
    called with ``errors="collect"``.

    Examples
    --------
    >>> found = WindowNetworks({}, [WindowFailure("cruise 1", "network", "too short")])
    >>> dict(found), found.failures[0].part
    ({}, 'network')
    """

    def __init__(self, networks: Mapping[str, FunctionalNetwork] | None = None,
                 failures: Sequence[WindowFailure] = ()) -> None:
        super().__init__(networks or {})
        self.failures: tuple[WindowFailure, ...] = tuple(failures)


def _collects(errors: str) -> bool:
    if errors not in ERROR_POLICIES:
        raise ParameterError.of(
            "errors", f"must be one of {', '.join(ERROR_POLICIES)}; got {errors!r}"
        )
    return errors == "collect"


def window_evidence(recording: Recording, networks: Mapping[str, FunctionalNetwork],
                    windows: Sequence[Window], *, errors: str = "raise",
                    progress: Callable[[int, int, str], None] | None = None,
                    tests: Mapping[str, Mapping[tuple[str, str], Any]] | None = None,
                    **settings: Unpack[EvidenceSettings]) -> WindowNetworks:
    """Each window's network with the evidence columns (:func:`funcnet.network.add_evidence`:
    the measures are not computed again).

    Parameters
    ----------
    recording : Recording
        The recording the networks were computed on.
    networks : mapping of str to FunctionalNetwork
        :func:`window_networks`' result (or part of it), by window label.
    windows : sequence of Window
        The windows, among them one per label of ``networks``.
    errors : {"raise", "collect"}
        A window whose evidence fails (too short for the subsamples of the asymmetry
        intervals, say): ``"raise"`` its error; ``"collect"`` keeps what could be computed and
        records what could not (``failures``): without the intervals (``resamples=0``, part
        ``"intervals"``) when the coupling test still runs, else its plain network (part
        ``"evidence"``). The settings are checked before any window either way.
    progress : callable, optional
        Called as ``progress(done, total, label)`` after each window.
    tests : mapping, optional
        Window label -> its pairs' coupling tests already run
        (:func:`funcnet.network.add_evidence`); a window not named runs its own.
    **settings
        ``evidence=True``'s settings of :func:`funcnet.network.functional_network`
        (``surrogates``, ``alpha``, ``seed``, ``resamples``, ``edge_rule``, ...).

    Returns
    -------
    WindowNetworks
        By label; each keeps its label and its window's record.

    Raises
    ------
    KeyError
        A label of ``networks`` without its window.
    ParameterError
        A bad setting (before any window), or ``errors`` not one of :data:`ERROR_POLICIES`.
    FuncnetError
        With ``errors="raise"``: any error of :func:`~funcnet.network.add_evidence` on a
        window.
    """
    collect = _collects(errors)
    if collect:  # a bad setting is the caller's, not a window's: it is raised, never collected
        check_evidence_settings(**settings)
    spans = {w.label: w for w in windows}
    where = recording.source or "<recording>"
    found = WindowNetworks()
    failures = []
    for done, (label, net) in enumerate(networks.items(), start=1):
        span = spans[label]
        part = recording.window(span.start, span.stop).data[list(net.nodes)]
        given = {} if tests is None or label not in tests else {"tests": tests[label]}
        try:
            found[label] = add_evidence(net, part, **given, **settings)
        except FuncnetError as error:
            if not collect:
                raise
            failure = _evidence_failure(net, part, {**settings, **given}, error, where, span)
            found[label] = failure[0]
            failures.append(failure[1])
        if progress is not None:
            progress(done, len(networks), label)
    found.failures = tuple(failures)
    return found


def _evidence_failure(net: FunctionalNetwork, part: pd.DataFrame, settings: Mapping[str, Any],
                      error: FuncnetError, where: str,
                      window: Window) -> tuple[FunctionalNetwork, WindowFailure]:
    """What is left of a window's evidence that failed: the coupling test without the
    intervals when that runs (the intervals' subsamples are shorter than the window), else the
    plain network; and the failure, located."""
    message = f"{where}: window {window.label!r} {_span(window)}: {error}"
    # Without intervals the "interval" edge rule has nothing to decide on: no fallback there.
    if settings.get("resamples") != 0 and settings.get("edge_rule") != "interval":
        try:
            without = add_evidence(net, part, **{**settings, "resamples": 0})
        except FuncnetError:
            pass
        else:
            return without, WindowFailure(window.label, "intervals", message)
    return net, WindowFailure(window.label, "evidence", message)


def window_networks(
    recording: Recording,
    windows: Sequence[Window] | pd.DataFrame,
    *,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    constant: str = "drop",
    errors: str = "raise",
    progress: Callable[[int, int, str], None] | None = None,
    warn: bool = True,
    max_states: int | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> WindowNetworks:
    """One functional network per window of a recording.

    Parameters
    ----------
    recording : Recording
        Derived signals (V) should already be columns, computed over the whole recording
        (:func:`funcnet.robot.read_recording` or :func:`~funcnet.robot.add_derived_signals`).
    windows : sequence of Window, or a phase table
        Any windows (:func:`~funcnet.robot.phase_windows`, :func:`~funcnet.robot.fixed_windows`,
        :func:`~funcnet.robot.reversal_windows`, :func:`~funcnet.robot.sliding_windows`, by
        hand); each holds the ticks ``start <= time < stop``. A phase table is turned into
        :func:`~funcnet.robot.phase_windows`.
    signals : sequence of str, optional
        The nodes; default the paper's (:data:`~funcnet.robot.windows.PAPER_NODES`) that the
        recording has.
    parameters : NetworkParameters, optional
        The network parameters (default :class:`~funcnet.NetworkParameters`'s defaults), the
        same for every window. Normalization (min-max by default) happens per window. Per-signal
        ``rr`` and ``eps`` follow the order of ``signals``; a window that drops a signal drops
        its entries too.
    constant : {"drop", "error"}
        A signal constant inside a window cannot be normalized (min-max or z-score): ``"drop"``
        (the default) leaves it out of that window's network (listed in its
        ``window["dropped"]``; one :class:`~funcnet.errors.RecordingWarning` names every window
        and signal left out, :func:`constant_warning`); ``"error"`` raises
        :class:`~funcnet.errors.SignalError`. Without normalization (``normalize=None``)
        nothing is dropped.
    errors : {"raise", "collect"}
        A window that has no network (its error is one of those listed under ``WindowError``
        and ``FuncnetError`` below): ``"raise"`` its error; ``"collect"`` records it (the
        result's ``failures``, part ``"network"``) and computes the other windows, whose
        warnings are then summarized together. Errors of the call itself (a bad parameter, a
        signal that is not a column, duplicate labels) are raised either way.
    progress : callable, optional
        Called as ``progress(done, total, label)`` after each window's network.
    warn : bool
        Emit the warnings below; False leaves the flags in the pairs tables alone (a caller
        that reads them itself, without ``warnings.catch_warnings``, which threads share).
    max_states : int, optional
        Most states of a window's network: a longer window's measures and evidence read every
        ``d``-th state (:func:`funcnet.network.functional_network`; its ``state_step``).
        Default every state.
    **overrides
        Network parameters by name (``dim=2``, ``rr=0.1``, ...), applied to ``parameters``.

    Returns
    -------
    WindowNetworks
        A dict: window label -> FunctionalNetwork (labelled so), in window order. Each network's
        ``window`` says where it comes from: the window's ``label``, ``start``, ``stop``
        (seconds), ``phase`` and ``offset``, the ``source`` (the recording's file) and
        ``dropped`` (a tuple of the signals left out). Its ``failures`` are the windows left
        out (``errors="collect"``).

    Raises
    ------
    ParameterError
        A bad network parameter (before any window is computed), ``constant`` not one of
        :data:`CONSTANT_POLICIES` or ``errors`` not one of :data:`ERROR_POLICIES`.
    WindowError
        A window outside the recording, with a signal not recorded (NaN) in it, with fewer than
        two signals left after dropping constant ones, or a duplicate label; the message names
        the file.
    ChannelError
        A signal that is not a column.
    FuncnetError
        Any error of :func:`funcnet.functional_network` on a window (a constant signal, a window
        too short for the embedding), of the same class, its message prefixed with the file,
        the window's label and its span.

    Warns
    -----
    RecordingWarning
        Signals constant inside a window, left out of its network (``problem="constant"``):
        one warning for the whole call, naming each window and its signals.
    StaircaseWarning
        A node's native interval is coarser than the grid (the 4 ms IPO signals AP and MP on the
        2 ms grid): it is a staircase, and recurrences are counted on repeated values. Use
        :func:`~funcnet.robot.resample` to avoid it.
    ThresholdWarning, DegenerateWarning
        At most one per problem (``eps_order``, ``rate_exceeded``, ``degenerate``) for the whole
        call, not one per window; it carries its ``problem``, the ``pairs`` (and for a
        degenerate structure the ``signals``) concerned in any window, and ``window`` when a
        single window has it; its message names the file and every window. The pairs are
        flagged in each network's pairs table; :func:`window_warnings` gives one warning per
        window and problem.

    References
    ----------
    Paper section 3.4 (construction), section 4 (networks per phase and window).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo, Window
    >>> t = np.arange(0, 2, 0.002)
    >>> data = pd.DataFrame({"RP": np.sin(5 * t), "AP": np.sin(5 * t - 0.3),
    ...                      "AC": np.where(t < 1, 0.0, np.cos(7 * t))},
    ...                     index=pd.Index(t, name="time"))
    >>> info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    >>> rec = Recording(data, {}, info, source="trace.csv", sample_period=0.002)
    >>> import warnings
    >>> windows = [Window("still", 0.2, 0.8), Window("moving", 1.2, 1.8)]
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     nets = window_networks(rec, windows, delay=5)
    >>> nets["still"].nodes, nets["still"].window["dropped"]
    (('RP', 'AP'), ('AC',))
    >>> [(w.message.problem, w.message.pairs[:2], w.message.window) for w in caught]
    [('eps_order', (('RP', 'AP'), ('RP', 'AC')), None), ('constant', (), None)]
    >>> window_networks(rec, [Window("still", 0.2, 0.8)], constant="error")
    Traceback (most recent call last):
        ...
    funcnet.errors.SignalError: trace.csv: window 'still' [0.2, 0.8) s: signal 'AC' is constant ...
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     found = window_networks(rec, windows, constant="error", errors="collect", delay=5)
    >>> list(found), found.failures[0].window, found.failures[0].part
    (['moving'], 'still', 'network')
    """
    p = resolve(parameters, overrides)
    if constant not in CONSTANT_POLICIES:
        raise ParameterError.of(
            "constant", f"must be one of {', '.join(CONSTANT_POLICIES)}; got {constant!r}"
        )
    collect = _collects(errors)
    if isinstance(windows, pd.DataFrame):
        windows = phase_windows(windows)
    windows = list(windows)
    where = recording.source or "<recording>"
    duplicated = sorted(label for label, n in Counter(w.label for w in windows).items() if n > 1)
    if duplicated:
        raise WindowError(f"{where}: window labels {duplicated} occur more than once")
    if signals is None:
        signals = paper_nodes(recording.data.columns)
    signals = list(signals)
    missing = [name for name in signals if name not in recording.data.columns]
    if missing or not signals:
        raise ChannelError(
            where,
            f"signals {missing or signals} are not columns of the recording; it "
            f"has {list(recording.data.columns)}",
        )
    staircase = staircase_warning(recording, signals, where)
    if staircase is not None and warn:
        warnings.warn(staircase, stacklevel=caller_stacklevel())
    drop = constant == "drop" and p.normalize is not None
    networks = WindowNetworks()
    failures = []
    steps = channel_steps(recording.data, signals)
    batched, found = _batched_networks(recording, windows, signals, p, steps, max_states)
    for done, window in enumerate(windows, start=1):
        if window.label in batched:
            networks[window.label] = batched[window.label]
        else:
            try:
                networks[window.label] = _window_network(recording, window, signals, p, drop,
                                                         where, steps, max_states)
            except FuncnetError as error:
                if not collect or isinstance(error, ParameterError):
                    raise
                failures.append(WindowFailure(window.label, "network", str(error)))
        if progress is not None:
            progress(done, len(windows), window.label)
    # the per-window networks' warnings beside the batch's, in window order
    order = {w.label: k for k, w in enumerate(windows)}
    found += window_warnings({label: net for label, net in networks.items()
                              if label not in batched})
    found.sort(key=lambda warning: order.get(str(warning.window), -1))
    for warning in _summarized(found, where, len(windows)) if warn else ():
        warnings.warn(warning, stacklevel=caller_stacklevel())
    left_out = constant_warning(where, {label: (net.window or {}).get("dropped", ())
                                        for label, net in networks.items()}, len(windows))
    if left_out is not None and warn:
        warnings.warn(left_out, stacklevel=caller_stacklevel())
    networks.failures = tuple(failures)
    return networks


def constant_signals(part: pd.DataFrame, where: str) -> tuple[str, ...]:
    """The signals of a window that hold one value throughout it (a range of 0).

    The one rule for a constant signal of every command that leaves such a signal out of its
    window (:func:`window_networks`, ``funcnet stability``).

    Parameters
    ----------
    part : DataFrame
        The window's samples, a column per signal.
    where : str
        The window, as an error should name it (the file, the window's label).

    Returns
    -------
    tuple of str
        The constant signals, in column order. An infinite value is not constant (its range is
        not 0); the normalization refuses it, naming the signal.

    Raises
    ------
    WindowError
        A signal has a missing value (NaN) in the window: it is neither constant nor usable;
        the message names ``where`` and the first such signal.

    Examples
    --------
    >>> part = pd.DataFrame({"RP": [0.0, 1.0], "RC": [2.0, 2.0]})
    >>> constant_signals(part, "run.csv: window 'cruise 1'")
    ('RC',)
    >>> constant_signals(part.assign(RC=[2.0, np.nan]), "run.csv: window 'cruise 1'")
    Traceback (most recent call last):
    funcnet.errors.WindowError: run.csv: window 'cruise 1': signal 'RC' has no recorded value...
    """
    values = part.to_numpy(dtype=np.float64)
    missing = np.isnan(values).any(axis=0)
    if missing.any():
        raise WindowError(f"{where}: signal {part.columns[missing][0]!r} has no recorded value "
                          "at some of its ticks")
    return tuple(str(name) for name in part.columns[np.ptp(values, axis=0) == 0])


def constant_warning(where: str, dropped: Mapping[str, Sequence[str]],
                     n_windows: int) -> RecordingWarning | None:
    """The one warning that says which signals were left out of which windows as constant.

    Parameters
    ----------
    where : str
        The recording's file (the message starts with it).
    dropped : mapping
        Window label -> the signals left out of it (empty: none).
    n_windows : int
        How many windows the call computed.

    Returns
    -------
    RecordingWarning or None
        ``problem="constant"`` and ``signals`` every signal left out somewhere (the message
        names the windows); None when no window lost one.

    Examples
    --------
    >>> print(constant_warning("run.csv", {"cruise 1": (), "braking 1": ("RC",)}, 2))
    run.csv: constant inside the window, left out of it (a normalization needs a range;
    constant='error' makes it an error): in 1 of 2 window(s): 'braking 1' (RC)
    >>> constant_warning("run.csv", {"cruise 1": ()}, 1) is None
    True
    """
    lost = {str(label): tuple(names) for label, names in dropped.items() if names}
    if not lost:
        return None
    listed = ", ".join(f"{label!r} ({', '.join(names)})" for label, names in lost.items())
    return RecordingWarning(
        f"{where}: constant inside the window, left out of it (a normalization needs a range; "
        f"constant='error' makes it an error): in {len(lost)} of {n_windows} window(s): "
        f"{listed}",
        problem="constant", signals=tuple(dict.fromkeys(n for v in lost.values() for n in v)))


def channel_steps(data: pd.DataFrame, signals: Sequence[str]) -> dict[str, float]:
    """The precision each channel of ``data`` (a recording's, a trial's: whole channels) is
    logged with (:func:`~funcnet.network.precision.logged_step`): a window that moves
    thousands of steps per sample may hide a decimal grid.

    Examples
    --------
    >>> channel_steps(pd.DataFrame({"RP": [0.0, 0.001, 0.003]}), ["RP"])
    {'RP': 0.001}
    """
    return {str(name): logged_step(data[name].to_numpy(np.float64)) for name in signals}


def window_steps(values: np.ndarray, signals: Sequence[str],
                 channel: Mapping[str, float]) -> dict[str, float]:
    """Each column's precision in one window: its channel's (:func:`channel_steps`), or, for
    values stored in single precision, the spacing at the window's own magnitudes where that
    is finer (:func:`~funcnet.network.precision.single_spacing`). A window can only show a
    multiple of a decimal grid, or hide it; single precision's spacing shrinks with the
    magnitudes a window holds.

    Examples
    --------
    >>> window_steps(np.array([[0.1], [0.3], [0.5]]), ["RP"], {"RP": 0.1})  # decimals
    {'RP': 0.1}
    >>> near_zero = np.float32([[0.001], [0.002]]).astype(float)
    >>> window_steps(near_zero, ["RP"], {"RP": 2.0**-20})["RP"] < 2.0**-20
    True
    """
    found = {}
    for k, name in enumerate(signals):
        read = [step for step in (single_spacing(values[:, k]), float(channel[name]))
                if step > 0]
        found[str(name)] = min(read, default=0.0)
    return found


def _window_network(recording: Recording, window: Window, signals: Sequence[str],
                    p: NetworkParameters, drop: bool, where: str,
                    steps: Mapping[str, float], max_states: int | None = None,
                    ) -> FunctionalNetwork:
    """The network of one window, located (errors name the window; the network records it)."""
    part = recording.window(window.start, window.stop).data[list(signals)]
    values = part.to_numpy(dtype=np.float64)
    constant = constant_signals(part, f"{where}: window {window.label!r} {_span(window)}")
    dropped = constant if drop else ()
    if dropped and len(signals) - len(dropped) < 2:
        raise WindowError(
            f"{where}: window {window.label!r} {_span(window)}: signals {list(dropped)} are "
            "constant in it, which leaves fewer than two signals"
        )
    if dropped:
        p = _without(p, [name not in dropped for name in signals])
    try:
        network = functional_network(
            part.drop(columns=list(dropped)) if dropped else part, parameters=p,
            label=window.label, warn=False, max_states=max_states,
            steps={name: step for name, step in window_steps(
                values, list(signals), steps).items() if name not in dropped})
    except FuncnetError as error:
        _locate(error, where, window)
        raise
    return dataclasses.replace(
        network,
        window={
            "label": window.label,
            "start": window.start,
            "stop": window.stop,
            "phase": window.phase,
            "offset": window.offset,
            "source": recording.source,
            "dropped": dropped,
        },
    )


def _batched_networks(
    recording: Recording, windows: Sequence[Window], signals: Sequence[str], p: NetworkParameters,
    steps: Mapping[str, float], max_states: int | None = None,
) -> tuple[dict[str, FunctionalNetwork], list[FuncnetWarning]]:
    """The windows' networks through the batched engine (:func:`funcnet.core.batch.batch_pairs`),
    equal (``==``) to :func:`_window_network`'s, by label, and their :func:`window_warnings`.

    Windows with NaN or a constant signal are left out (the per-window path computes them and
    raises or drops what it does); nothing where the batch does not apply (no short window,
    explicit ``eps``, any error), and the per-window path computes every window."""
    values = recording.data[list(signals)].to_numpy(np.float64)
    try:  # the rows Recording.window selects (and its errors: then the per-window path's)
        bounds = [recording.rows(w.start, w.stop) for w in windows]
    except FuncnetError:
        return {}, []
    parts = [values[first:last] for first, last in bounds]
    lag = (p.dim - 1) * p.delay  # a window to be thinned (max_states) is not batched
    kept = [k for k, part in enumerate(parts) if np.isfinite(part).all()
            and not (p.normalize and (np.ptp(part, axis=0) == 0).any())
            and (max_states is None or part.shape[0] - lag <= max_states)]
    windows = [windows[k] for k in kept]
    parts = [parts[k] for k in kept]
    # Long windows inside the batch go through the per-window path; none short: no batch.
    if not any(batch.applies(part.shape[0], p) for part in parts):
        return {}, []
    names = [str(s) for s in signals]
    # normalized as functional_network's nodes are: the same bits, the same reading
    normalized, node_steps = _normalized_parts(parts, names, p.normalize, steps)
    origin = (values, np.array([bounds[k][0] for k in kept], dtype=np.int64))
    # The direction's p-values need no cross measure: read in another thread while the
    # kernels (which release the interpreter) compute those.
    with ThreadPoolExecutor(max_workers=1) as pool:
        reading = pool.submit(window_p_values, normalized, p, node_steps, origin=origin)
        try:
            result = batch.batch_pairs(parts, names=names, parameters=p)
        except FuncnetError:
            return {}, []
        p_values = reading.result()
    n_pairs = len(result.pairs)
    # every window's rows, then sliced; each column an array, the table made once
    columns: dict[str, Any] = {"x": [x for x, _ in result.pairs] * len(windows),
                               "y": [y for _, y in result.pairs] * len(windows)}
    columns.update({name: result[name].ravel() for name in RESULT_COLUMNS})
    columns.update(rule_columns(columns["c_diff"].astype(np.float64),
                                columns["t_diff"].astype(np.float64), p))
    columns.update(window_directions(
        normalized, result.names, result.pairs,
        np.reshape(columns["degenerate"], (len(windows), n_pairs)), p, node_steps,
        origin=origin, p_values=p_values))
    table = pairs_frame(columns)
    return _window_tables(recording, windows, parts, table, result, p)


def _normalized_parts(parts: Sequence[np.ndarray], names: Sequence[str], method: str | None,
                      channel: Mapping[str, float]) -> tuple[list[np.ndarray], np.ndarray]:
    """Each window normalized as :func:`funcnet.network.functional_network` normalizes it (the
    same bits), and its nodes' logged steps in that unit, shape ``(W, k)``
    (:func:`window_steps`, :func:`~funcnet.network.precision.normalized_steps`).

    Windows of one length are one stack: min-max and the steps are element-wise (and exact
    extrema), hence the same bits as window by window; a z-score's mean and deviation are
    NumPy's pairwise sums over each window, so z-scored windows are normalized one by one."""
    normalized: list[np.ndarray] = [np.empty(0)] * len(parts)
    found = np.zeros((len(parts), len(names)))
    by_length: dict[int, list[int]] = {}
    for w, part in enumerate(parts):
        by_length.setdefault(part.shape[0], []).append(w)
    logged = np.array([float(channel[name]) for name in names])
    for members in by_length.values():
        raw = np.stack([parts[w] for w in members])
        if method == "minmax":
            low = raw.min(axis=1, keepdims=True)
            scaled = (raw - low) / (raw.max(axis=1, keepdims=True) - low)
        else:
            scaled = np.stack([normalize_signals(parts[w], method) for w in members])
        normalized_members = list(scaled)
        for slot, w in enumerate(members):
            normalized[w] = normalized_members[slot]
        found[members] = _stacked_steps(raw, scaled, logged)
    return normalized, found


def _stacked_steps(raw: np.ndarray, scaled: np.ndarray, logged: np.ndarray) -> np.ndarray:
    """:func:`window_steps` then :func:`~funcnet.network.precision.normalized_steps` of each
    window of a stack ``(W, N, k)`` (raw, and normalized), element-wise: shape ``(W, k)``."""
    single = np.zeros(raw.shape[::2])
    # single precision's spacing only where a column is float32 values (its own mean: as read)
    stored = (raw.astype(np.float32).astype(np.float64) == raw).all(axis=1)
    for w, k in zip(*np.nonzero(stored), strict=True):
        single[w, k] = single_spacing(raw[w, :, k])
    read = np.where((single > 0) & ((single < logged) | ~(logged > 0)), single,
                    np.where(logged > 0, logged, 0.0))
    spread = np.ptp(raw, axis=1)
    scale = np.divide(np.ptp(scaled, axis=1), spread, out=np.zeros(spread.shape),
                      where=spread > 0)
    return read * scale


def _window_tables(recording: Recording, windows: Sequence[Window], parts: Sequence[np.ndarray],
                   table: pd.DataFrame, result: batch.BatchPairs, p: NetworkParameters,
                   ) -> tuple[dict[str, FunctionalNetwork], list[FuncnetWarning]]:
    """Each window's network from the rows of ``table`` (every window's pairs, in order), and
    the warnings its flags call for."""
    n_pairs, n_rows = len(result.pairs), len(table)
    # Edges of every window at once (the rule is row by row); rows named by their position
    # tell which rows became edges, hence where each window's edges start.
    edges = edges_from_pairs(table, degenerate=p.degenerate)
    rows = np.arange(n_rows).astype(str)
    kept = edges_from_pairs(table.assign(x=rows, y=rows), degenerate=p.degenerate)
    ends = np.searchsorted(kept["source"].to_numpy(dtype=np.int64),
                           np.arange(len(windows) + 1) * n_pairs)
    # a window's warnings read its flagged pairs alone (threshold_warnings lists no other)
    unordered, exceeded, degenerate = (~result["eps_ordered"], result["rate_exceeded"],
                                       result["degenerate"])
    flagged = [np.flatnonzero(row).tolist() for row in unordered | exceeded | degenerate]
    # Without a degenerate pair (whose warning prints its rates) a window's warnings name its
    # flagged pairs only: windows flagged alike share them.
    alike: dict[bytes, list[FuncnetWarning]] = {}
    networks, found = {}, []
    for w, window in enumerate(windows):
        # Slices with a fresh index, not reset_index: that copies every block of every slice.
        pairs = table.iloc[w * n_pairs : (w + 1) * n_pairs]
        pairs.index = pd.RangeIndex(n_pairs)
        window_edges = edges.iloc[ends[w] : ends[w + 1]]
        window_edges.index = pd.RangeIndex(ends[w + 1] - ends[w])
        if flagged[w]:  # else no warning: spare building the results
            if degenerate[w].any():
                own = threshold_warnings(result.measures(w, flagged[w]))
            else:
                key = unordered[w].tobytes() + exceeded[w].tobytes()
                if key not in alike:
                    alike[key] = threshold_warnings(result.measures(w, flagged[w]))
                own = alike[key]
            found += [warning.located(str(window.label)) for warning in own]
        networks[str(window.label)] = FunctionalNetwork(
            nodes=result.names, pairs=pairs,
            edges=window_edges, parameters=p,
            n_samples=int(parts[w].shape[0]), label=window.label,
            window={"label": window.label, "start": window.start, "stop": window.stop,
                    "phase": window.phase, "offset": window.offset,
                    "source": recording.source, "dropped": ()},
        )
    return networks, found


def _without(p: NetworkParameters, kept: Sequence[bool]) -> NetworkParameters:
    """``p`` for the kept signals: per-signal rates and thresholds of dropped ones left out."""
    changes: dict[str, Any] = {}
    if isinstance(p.rr, tuple) and len(p.rr) == len(kept):
        changes["rr"] = tuple(r for r, keep in zip(p.rr, kept, strict=True) if keep)
    if p.eps is not None and isinstance(p.eps[0], tuple) and len(p.eps[0]) == len(kept):
        auto = tuple(e for e, keep in zip(p.eps[0], kept, strict=True) if keep)
        changes["eps"] = (auto, p.eps[1])
    return p.replace(**changes) if changes else p


# --------------------------------------------------------------------------------------------
# warnings, from the flags of the pairs tables


def _pair_results(network: FunctionalNetwork) -> dict[tuple[str, str], CrossMeasures]:
    """The pairs table's flagged rows (the only ones
    :func:`~funcnet.core.measures.threshold_warnings` names) as the cross measures they were
    made from."""
    p = network.parameters
    states = network.n_samples - (p.dim - 1) * p.delay  # not used by the warnings
    # column by column: to_dict("records") over every column of a table with evidence was
    # the slowest step of a robot page's warnings (the same Python values)
    columns = {name: network.pairs[name].tolist() for name in ("x", "y", *RESULT_COLUMNS)}
    results = {}
    for k, (x, y) in enumerate(zip(map(str, columns["x"]), map(str, columns["y"]),
                                   strict=True)):
        if columns["eps_ordered"][k] and not (columns["rate_exceeded"][k]
                                              or columns["degenerate"][k]):
            continue  # no flag: threshold_warnings would not name the pair
        results[(x, y)] = CrossMeasures(
            **{name: columns[name][k] for name in RESULT_COLUMNS},
            m_x=states,
            m_y=states,
            parameters=p.for_pair(network.nodes.index(x), network.nodes.index(y)),
        )
    return results


def window_warnings(networks: Mapping[str, FunctionalNetwork]) -> list[FuncnetWarning]:
    """The warnings the networks' pairs tables call for: one per window and problem.

    Parameters
    ----------
    networks : mapping
        Window label -> FunctionalNetwork (as :func:`window_networks` returns).

    Returns
    -------
    list of FuncnetWarning
        In window order, then as :func:`funcnet.core.measures.threshold_warnings` orders them: a
        :class:`~funcnet.errors.ThresholdWarning` for pairs whose ``eps_ordered`` is False
        (``problem="eps_order"``) and for pairs whose ``rate_exceeded`` is True, degenerate
        pairs aside (``"rate_exceeded"``), a :class:`~funcnet.errors.DegenerateWarning` for the
        ``degenerate`` pairs, naming the signals whose own structure is degenerate
        (``"degenerate"``). Each carries ``problem``, ``pairs``, ``signals`` and ``window``
        (the label): the warnings ``functional_network(..., warn=True)`` gives for that window,
        located. Nothing is emitted: this is a pure function of the tables.

    References
    ----------
    Section 2.2 of the paper (``eps_xy < eps_x, eps_y``).

    Examples
    --------
    >>> window_warnings({})
    []
    """
    return [
        warning.located(str(label))
        for label, network in networks.items()
        for warning in threshold_warnings(_pair_results(network))
    ]


def _summarized(found: Sequence[FuncnetWarning], where: str,
                n_windows: int) -> list[FuncnetWarning]:
    """One warning per (class, problem), naming every window, pair and signal that has it."""
    groups: dict[tuple[type[FuncnetWarning], str | None], list[FuncnetWarning]] = {}
    for warning in found:
        groups.setdefault((type(warning), warning.problem), []).append(warning)
    summary = []
    for (cls, problem), group in groups.items():
        labels = [str(w.window) for w in group]
        pairs = tuple(dict.fromkeys(pair for w in group for pair in w.pairs))
        signals = tuple(dict.fromkeys(name for w in group for name in w.signals))
        what, advice = _SUMMARIES.get(str(problem), (group[0].message, ""))
        about = f" of signal(s) {', '.join(signals)}" if signals else ""
        listed = ", ".join(f"({x}, {y})" for x, y in pairs)
        text = f"{what}{about} for {len(pairs)} pair(s): {listed}" if pairs else what
        summary.append(
            cls(
                f"{text}{'; ' + advice if advice else ''}\n{where}: in {len(labels)} of "
                f"{n_windows} window(s): " + ", ".join(repr(label) for label in labels),
                problem=problem,
                signals=signals,
                pairs=pairs,
                window=labels[0] if len(labels) == 1 else None,
            )
        )
    return summary


def _locate(error: FuncnetError, where: str, window: Window) -> None:
    """Put the recording's file and the window in front of ``error``'s message."""
    # Changed in place: the class, the traceback and attributes such as TraceError.path stay,
    # whatever the class's constructor takes.
    error.args = (f"{where}: window {window.label!r} {_span(window)}: {error}",)


def _span(window: Window) -> str:
    return f"[{window.start:g}, {window.stop:g}) s"
