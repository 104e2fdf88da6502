"""Tasks of a study and what a worker does with them.

A task is plain, picklable data keyed by the SHA-256 of its content; the functions
:func:`expand_windows` and :func:`network_rows` run on a worker (this process, a local process
or a Dask worker thread) and return an :class:`Outcome` instead of raising, so one bad window
does not stop the run. Nothing here writes files or changes process-wide state: the warnings of
a task are read from its networks' pairs-table flags, not captured from :mod:`warnings`.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from funcnet._io import file_sha256
from funcnet.errors import FuncnetError, ParameterError, StudyError
from funcnet.parameters import NetworkParameters
from funcnet.study.spec import BUILDERS, WindowSpec, phase_options
from funcnet.study.store import rows_table

__all__ = [
    "Source",
    "WindowTask",
    "NetworkTask",
    "Outcome",
    "content_key",
    "expand_windows",
    "network_rows", "standstill",
    "task_warnings",
]


@dataclass(frozen=True)
class Source:
    """A recording as the tasks see it: its path, its name and trial in the results, its hash."""

    path: str
    name: str
    trial: str
    sha256: str


@dataclass(frozen=True)
class WindowTask:
    """Expand one window specification on one recording."""

    key: str
    source: Source
    spec: WindowSpec
    signals: tuple[str, ...] | None
    channels: str | None
    axis: int | None
    resample: str | None


@dataclass(frozen=True)
class NetworkTask:
    """One functional network: a recording, a window (as a dict), a parameter set."""

    key: str
    source: Source
    window: dict[str, Any]
    parameters: NetworkParameters
    signals: tuple[str, ...] | None
    channels: str | None
    axis: int | None
    resample: str | None
    constant: str
    # The study's [evidence] and [stability] settings (empty: off), see funcnet.study.spec.
    evidence: tuple[tuple[str, Any], ...] = ()
    stability: tuple[tuple[str, Any], ...] = ()


@dataclass(frozen=True)
class Outcome:
    """What a worker returns: a value, or the message of an error.

    ``error`` is a task's own failure (recorded, the run goes on); ``fatal`` an error that
    would fail every task (the run stops); ``skipped`` why a window has nothing to analyse
    (the axis stands still in it: recorded and listed, not a failure). ``warnings`` holds, per
    kind of problem, the number of pairs (or signals) that have it and one message.
    """

    key: str
    value: Any = None
    error: str | None = None
    fatal: str | None = None
    warnings: tuple[tuple[str, int, str], ...] = ()
    skipped: str | None = None


def content_key(**content: object) -> str:
    """The SHA-256 of ``content`` as canonical JSON: a task's key.

    Parameters
    ----------
    **content
        JSON-compatible values (no NaN).

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> content_key(a=1, b=[2]) == content_key(b=[2], a=1)
    True
    """
    text = json.dumps(content, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _cached_recording(task: WindowTask | NetworkTask) -> Any:
    return _read(task.source.path, task.source.sha256, task.signals, task.channels, task.axis,
                 task.resample)


@lru_cache(maxsize=2)
def _read(path: str, sha256: str, signals: tuple[str, ...] | None, channels: str | None,
          axis: int | None, resample: str | None) -> Any:
    # The read is cached per worker: every task of a recording on that worker reuses it. The
    # content hash is checked so that a file changed during the run cannot be mislabelled.
    from funcnet.robot import read_recording

    if file_sha256(path) != sha256:
        raise StudyError(f"{path}: the file changed while the study was running")
    return read_recording(path, signals=signals, channels=channels, axis=axis, resample=resample)


def window_record(window: Any) -> dict[str, Any]:
    """A :class:`funcnet.robot.Window` as JSON-compatible data (its fields).

    Parameters
    ----------
    window : funcnet.robot.Window

    Returns
    -------
    dict
        ``label``, ``phase``, ``offset``, ``start``, ``stop``; ``Window(**record)`` rebuilds it.

    Examples
    --------
    >>> from funcnet.robot import span_window
    >>> window_record(span_window(1.0, 1.5))
    {'label': '1.000-1.500 s', 'phase': None, 'offset': 0.0, 'start': 1.0, 'stop': 1.5}
    """
    return {
        "label": str(window.label),
        "phase": None if window.phase is None else str(window.phase),
        "offset": float(window.offset),
        "start": float(window.start),
        "stop": float(window.stop),
    }


def expand_windows(task: WindowTask) -> Outcome:
    """Worker side: the windows a specification gives on a recording.

    Parameters
    ----------
    task : WindowTask

    Returns
    -------
    Outcome
        ``value``: the windows as :func:`window_record` dicts; ``error`` if the recording
        cannot be read or has no such windows; ``fatal`` for a bad option value.
    """
    import funcnet.robot as robot

    try:
        recording = _cached_recording(task)
        options = dict(task.spec.options)
        if task.spec.kind == "range":
            windows = [robot.span_window(options["start"], options["stop"])]
        elif task.spec.kind == "sliding":
            windows = robot.sliding_windows(recording, **options)
        else:
            detect = phase_options()
            phases = robot.detect_phases(
                recording, **{k: v for k, v in options.items() if k in detect}
            )
            builder = getattr(robot, BUILDERS[task.spec.kind])
            if task.spec.kind == "reversal" and not phases["phase"].eq("reversal").any():
                windows = []  # a trial without a reversal has no reversal windows
            else:
                windows = builder(phases, **{k: v for k, v in options.items() if k not in detect})
            if task.spec.kind == "fixed":
                overrun = overrunning_windows(windows, phases)
                if overrun:
                    listed = ", ".join(f"{label!r} ({share:.0%} outside)"
                                       for label, share in overrun)
                    message = (f"{task.source.name}: fixed windows mostly outside their phase "
                               f"(a short phase; the window runs into the next): {listed}")
                    return Outcome(task.key, value=[window_record(w) for w in windows],
                                   warnings=(("window_overrun", len(overrun), message),))
        return Outcome(task.key, value=[window_record(w) for w in windows])
    except ParameterError as exc:
        return Outcome(task.key, fatal=str(exc))
    except FuncnetError as exc:
        return Outcome(task.key, error=str(exc))


#: A fixed window is flagged when more than this share of it lies outside its phase.
OVERRUN_SHARE = 0.5


def overrunning_windows(windows: Sequence[Any], phases: Any) -> list[tuple[str, float]]:
    """Fixed windows that lie mostly outside the phase they are anchored at.

    A fixed window (paper section 4.2: 280 / 600 / 600 ms) starts at its phase and keeps its
    length whatever the phase's, so that windows compare across speeds; in a short trial a
    "cruise" window can be mostly braking. Such windows are flagged, not cut.

    Parameters
    ----------
    windows : sequence of funcnet.robot.Window
        From :func:`funcnet.robot.fixed_windows` (``phase`` is the anchor: ``spin-up``,
        ``cruise``, ``braking``).
    phases : pandas.DataFrame
        The phase table they were built from.

    Returns
    -------
    list of (str, float)
        Label and the share of the window outside phases of its kind, for those above
        :data:`OVERRUN_SHARE`.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot import fixed_windows
    >>> phases = pd.DataFrame({"phase": ["cruise", "braking"], "start": [1.0, 1.2],
    ...                        "stop": [1.2, 2.0]})
    >>> overrunning_windows(fixed_windows(phases), phases)
    [('cruise', 0.6666666666666667)]
    """
    flagged = []
    for window in windows:
        kinds = ({"early spin-up", "late spin-up"} if window.phase == "spin-up"
                 else {window.phase})
        inside = sum(max(0.0, min(window.stop, row.stop) - max(window.start, row.start))
                     for row in phases.itertuples(index=False) if row.phase in kinds)
        share = 1.0 - inside / (window.stop - window.start)
        if share > OVERRUN_SHARE:
            flagged.append((str(window.label), float(share)))
    return flagged


def standstill(recording: Any, window: Any) -> str | None:
    """Why ``window`` has no motion to analyse -- every set-point (RP, or ``A<n>.RP`` of each
    axis) holds one value in it -- or None when something moves (or there is no set-point).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo, span_window
    >>> t = np.arange(10) * 0.1
    >>> rec = Recording(pd.DataFrame({"RP": np.r_[np.zeros(5), np.arange(5.0)]},
    ...                              index=pd.Index(t, name="time")), {},
    ...                 {"RP": SignalInfo("RP", None, None, 0.1)}, sample_period=0.1)
    >>> standstill(rec, span_window(0.0, 0.5))
    'the set-point RP holds 0 over 0-0.5 s: the axis stands still'
    >>> standstill(rec, span_window(0.3, 0.8)) is None
    True
    """
    from funcnet.robot.axes import split_qualified

    columns = [c for c in recording.data.columns if split_qualified(c)[1] == "RP"]
    if not columns:
        return None
    part = recording.window(window.start, window.stop).data[columns]
    low, high = part.min(), part.max()
    if bool((high > low).any()) or part.isna().all().any():
        return None
    held = ", ".join(f"{c} holds {low[c]:g}" for c in columns)
    who = "the axis stands" if len(columns) == 1 else "every axis stands"
    return (f"the set-point {held} over {window.start:g}-{window.stop:g} s: {who} still")


def _standstill_of(task: NetworkTask, error: Exception) -> str | None:
    """:func:`standstill` of the task's window, for a window that could not be analysed."""
    import funcnet.robot as robot

    try:
        return standstill(_cached_recording(task), robot.Window(**task.window))
    except FuncnetError:
        return None


def network_rows(task: NetworkTask) -> Outcome:
    """Worker side: compute one network and return its rows as an Arrow table.

    Parameters
    ----------
    task : NetworkTask

    Returns
    -------
    Outcome
        ``value``: :func:`funcnet.study.store.rows_table`; ``warnings``: :func:`task_warnings`;
        ``error`` if the window cannot be analysed (a constant signal, too short ...);
        ``skipped`` instead where it cannot because the axis stands still in it.
    """
    import funcnet.robot as robot
    from funcnet.pipeline import window_evidence, window_networks
    from funcnet.robot.axes import split_qualified

    try:
        recording = _cached_recording(task)
        signals = _nodes(task.signals, recording.data.columns, robot.PAPER_NODES)
        window = robot.Window(**task.window)
        # Dropping a constant set-point node would leave the noise of a resting axis to analyse.
        setpoint = any(split_qualified(s)[1] == "RP" for s in signals)
        resting = standstill(recording, window) if setpoint and task.constant == "drop" else None
        if resting is not None:
            return Outcome(task.key, skipped=f"{resting} (its set-point is constant)")
        with _one_thread_per_task():
            networks = window_networks(
                recording, [window], signals=signals, parameters=task.parameters,
                constant=task.constant,
            )
        (network,) = networks.values()
        if task.evidence:
            with _one_thread_per_task():
                networks = window_evidence(recording, networks, [window], **dict(task.evidence))
            (network,) = networks.values()
        part = recording.window(window.start, window.stop).data[list(network.nodes)]
    except ParameterError as exc:
        return Outcome(task.key, fatal=str(exc))
    except FuncnetError as exc:
        # A window where the axis stands still has nothing to analyse: listed, not failed.
        resting = _standstill_of(task, exc)
        if resting is not None:
            return Outcome(task.key, skipped=f"{resting} ({exc})")
        return Outcome(task.key, error=str(exc))
    pairs = network.pairs
    unstable: tuple[tuple[str, int, str], ...] = ()
    if task.stability:
        with _one_thread_per_task():
            pairs, unstable = _with_stability(network, part, task.stability,
                                              f"{task.source.name} [{window.label}]")
    dropped = [s for s in signals if s not in network.nodes]
    identity = {
        "recording": task.source.name,
        "trial": task.source.trial,
        "source_sha256": task.source.sha256,
        "window": task.window["label"],
        "phase": task.window["phase"],
        "offset": task.window["offset"],
        "start": task.window["start"],
        "stop": task.window["stop"],
        "signals": ",".join(network.nodes),
        "constant": task.constant,
        "dropped": ",".join(dropped),
    }
    rows = rows_table(identity, task.parameters, pairs)
    found = task_warnings(networks, recording, signals, task.source.name) + unstable
    return Outcome(task.key, value=rows, warnings=found)


def _with_stability(network: Any, part: Any, stability: tuple[tuple[str, Any], ...],
                    where: str) -> tuple[Any, tuple[tuple[str, int, str], ...]]:
    """The pairs table with each pair's stability columns (``stability``, ``stability_*``).

    A setting of the grid the window cannot be analysed at (a doubled delay on a short window)
    does not cost the window its network: the columns stay empty and a ``stability`` warning
    says why.
    """
    from funcnet.network.stability import edge_stability

    grid = dict(stability)["grid"]
    try:
        result = edge_stability(part, parameters=network.parameters,
                                grid=None if grid is None else {k: list(v) for k, v in grid})
    except FuncnetError as exc:
        return network.pairs, (("stability", 1, f"{where}: no stability: {exc}"),)
    table = result.table.drop(columns=["kind"])
    table = table.rename(columns={c: c if c.startswith("stability") else f"stability_{c}"
                                  for c in table.columns if c not in ("x", "y")})
    merged = network.pairs.merge(table, on=["x", "y"], how="left", validate="one_to_one")
    return merged, ()


def _nodes(signals: Sequence[str] | None, columns: Any, paper: Sequence[str]) -> list[str]:
    # Passed explicitly so that the signals a window left out are known (``dropped``).
    if signals is not None:
        return list(signals)
    return [name for name in paper if name in set(columns)]


def task_warnings(networks: Mapping[str, Any], recording: Any, signals: Sequence[str],
                  where: str) -> tuple[tuple[str, int, str], ...]:
    """Per kind of problem: how many pairs (or signals) have it, and one message.

    Built from typed warnings that are themselves built from the networks' pairs-table flags
    (:func:`funcnet.pipeline.window_warnings`) and from the recording's sampling
    (:func:`funcnet.robot.preprocess.staircase_signals`), never caught from :mod:`warnings`, so
    it is the same on every back end and thread.

    Parameters
    ----------
    networks : mapping
        Window label -> FunctionalNetwork.
    recording : Recording
        The recording the networks come from.
    signals : sequence of str
        The signals asked for.
    where : str
        The recording's name, put in front of the messages.

    Returns
    -------
    tuple of (problem, count, message)
        ``problem`` is the warning's :attr:`~funcnet.errors.FuncnetWarning.problem`
        (``"eps_order"``, ``"rate_exceeded"``, ``"degenerate"``, ``"staircase"``, and
        ``"constant"`` for signals left out of a window as constant in it).
    """
    from funcnet.pipeline import constant_warning, window_warnings
    from funcnet.robot.preprocess import staircase_warning

    found: dict[str, tuple[int, str]] = {}
    staircase = staircase_warning(recording, list(signals), where)
    if staircase is not None:
        found["staircase"] = (len(staircase.signals), str(staircase))
    constant = constant_warning(where, {label: (net.window or {}).get("dropped", ())
                                        for label, net in networks.items()}, len(networks))
    if constant is not None:
        found["constant"] = (len(constant.signals), str(constant))
    for warning in window_warnings(networks):
        problem = str(warning.problem)
        count, message = found.get(problem, (0, f"{where}: {warning}"))
        found[problem] = (count + max(len(warning.pairs), 1), message)
    return tuple((problem, count, message) for problem, (count, message) in found.items())


@contextlib.contextmanager
def _one_thread_per_task() -> Iterator[None]:
    # Tasks run in parallel already (one per process or Dask thread): Numba's parallel loops
    # inside a task only oversubscribe the cores (measured: 10-20x slower on small windows of a
    # loaded machine). The setting is per thread; it is restored for an in-process run.
    import numba

    previous = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(previous)


def parameters_record(parameters: NetworkParameters) -> Mapping[str, Any]:
    """A parameter set as JSON-compatible data (tuples as lists), for keys and files.

    Parameters
    ----------
    parameters : NetworkParameters

    Returns
    -------
    dict

    Examples
    --------
    >>> parameters_record(NetworkParameters(eps=(0.2, None)))["eps"]
    [0.2, None]
    """
    return json.loads(json.dumps(parameters.to_dict()))
