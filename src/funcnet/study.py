"""Studies: many recordings x analysis windows x network parameters, run as independent tasks.

A study names recordings (trace files, glob patterns, or the simulated plan of experiments),
analysis windows (detected phases, fixed windows anchored at phase starts, windows around a
reversal, sliding windows, explicit time ranges) and network parameters, each of which may be a
list: the lists span a grid. :func:`run_study` computes one functional network per (recording,
window, parameter set) -- a *task* -- on local processes or on a Dask cluster, and writes the pairs
table of every network as Parquet rows.

Layout of a results folder ``out_dir``::

    rows/<key>.parquet     one file per finished task: one row per pair of signals
    failed/<key>.json      a task whose data could not be analysed (message kept, not retried)
    windows/<key>.json     the windows a window specification gave on a recording (cached)
    cache/                 finished tasks of earlier runs that the current study does not name
    study.json             the study, provenance (versions, input hashes, command), run counts

Decisions (where the specification leaves room):

* A task's key is the SHA-256 of the source file's content hash, the recording's name and trial
  in the results, the window (label, phase, offset, start, stop), the complete parameter set
  (defaults filled in), the signal selection, the channel map's content hash, the axis and the
  funcnet version. A re-run therefore computes exactly the tasks whose key has no file yet. The
  name is part of the key so that two identical files listed under two names keep their own rows.
* Results are written by the process that runs :func:`run_study` (workers return rows), one file
  per task through a temporary file and a rename: a run killed at any moment leaves only whole
  files, and the restarted run computes what is missing. Leftover temporary files are removed.
  Workers of a Dask cluster need the recordings at the same paths (a shared file system); they
  need not see ``out_dir``.
* ``rows/`` holds exactly the tasks of the last study run in ``out_dir``: finished tasks of other
  studies (an earlier grid) are moved to ``cache/`` and moved back, not recomputed, when a study
  names them again. So ``rows/`` can be read as one data set by pandas, polars or DuckDB.
* The target rates are columns ``rr_target`` and ``cr_target``: the pairs table already has a
  column ``cr`` (the achieved cross-recurrence rate).
* A task whose window cannot be analysed (a constant signal, a window too short for the
  embedding, an unreadable trace) is recorded in ``failed/`` and reported; the other tasks go on.
  With ``constant = "drop"`` a signal constant in a window is left out of that window's network
  instead (:func:`funcnet.robot.phase_networks`); its rows name the nodes used (``signals``) and
  the signals left out (``dropped``).
  A bad parameter value (:class:`~funcnet.errors.ParameterError`) stops the run with a
  :class:`~funcnet.errors.StudyError`, since it would fail every task.
* Warnings raised while computing a task (thresholds, staircase signals) are counted per message
  in ``study.json`` rather than printed by the workers.
* A window kind that does not occur in a recording gives it no windows (a ``reversal``
  specification over trials without a reversal), not a failure.
* Without ``signals``, a recording's nodes are its roles (RP, AP, MP, RC, AC, those present) plus
  the velocity V derived from AP (Eq. 11-12), computed on the whole recording before windowing.
"""

from __future__ import annotations

import contextlib
import dataclasses
import fcntl
import glob
import hashlib
import inspect
import itertools
import json
import logging
import os
import platform
import sys
import threading
import tomllib
import warnings
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from funcnet import __version__
from funcnet._io import atomic_path, file_sha256, write_text_atomic
from funcnet.errors import FuncnetError, ParameterError, StudyError

__all__ = [
    "NETWORK_PARAMETERS",
    "PARAMETER_COLUMNS",
    "WINDOW_KINDS",
    "Study",
    "StudyResult",
    "TaskFailure",
    "WindowSpec",
    "read_recording",
    "package_versions",
    "load_results",
    "load_study",
    "parameter_grid",
    "run_study",
]

#: Network parameters a study may set (a value or a list of values), with the type each takes.
NETWORK_PARAMETERS: dict[str, tuple[type, ...]] = {
    "dim": (int,),
    "delay": (int,),
    "rr": (float, int),
    "cr": (float, int),
    "mu": (float, int),
    "metric": (str,),
    "normalize": (str,),
    "measure": (str,),
    "rule": (str,),
    "theiler": (int,),
}

#: The results' column of each network parameter: the target rates are ``rr_target`` and
#: ``cr_target``, since the pairs table's ``cr`` is the achieved cross-recurrence rate.
PARAMETER_COLUMNS: dict[str, str] = {
    name: {"rr": "rr_target", "cr": "cr_target"}.get(name, name) for name in NETWORK_PARAMETERS
}

#: Window kinds of a study: one per builder of :mod:`funcnet.robot.windows`, and ``range``.
WINDOW_KINDS = ("phases", "fixed", "reversal", "sliding", "range")
_BUILDERS = {
    "phases": "phase_windows",
    "fixed": "fixed_windows",
    "reversal": "reversal_windows",
    "sliding": "sliding_windows",
}

_DEFAULT_WORKERS = 2


# --------------------------------------------------------------------------------------------
# the study description


@dataclass(frozen=True)
class WindowSpec:
    """One ``[[windows]]`` entry: a window kind and the options passed to its builder.

    Parameters
    ----------
    kind : str
        One of :data:`WINDOW_KINDS`.
    options : tuple of (str, value)
        Keyword arguments of the builder (``width``, ``step`` for ``"sliding"``; ``start``,
        ``stop`` for ``"range"``; the builder's own options otherwise), sorted by name.
    """

    kind: str
    options: tuple[tuple[str, Any], ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """The specification as a plain dict (``kind`` plus options)."""
        return {"kind": self.kind, **dict(self.options)}


@dataclass(frozen=True)
class Study:
    """A batch of functional networks: recordings x windows x parameter grid.

    Parameters
    ----------
    recordings : tuple of Path
        Trace files (SINUMERIK XML, CSV or Parquet), absolute.
    windows : tuple of WindowSpec
        Window specifications; each expands, per recording, to one or more windows.
    parameters : tuple of (str, tuple)
        Network parameters and their values; several values span a grid (see
        :func:`parameter_grid`). Parameters not named take :func:`funcnet.functional_network`'s
        defaults.
    signals : tuple of str, optional
        Node columns; ``None`` takes every role of each trace plus V, in the paper's order
        (:data:`funcnet.robot.windows.PAPER_NODES`).
    simulated : str, optional
        ``"paper"`` (the paper's plan of experiments) or the path of a plan TOML file: the plan
        is simulated into ``plan_dir`` before the run and its traces are added to ``recordings``.
    plan_dir : Path, optional
        Where the simulated plan is written; ``None`` means ``<out_dir>/plan``.
    seed : int
        Seed of the simulated plan.
    channels : Path, optional
        Channel map (TOML) for reading the traces.
    axis : int, optional
        Axis to read from traces of several axes.
    constant : str
        ``"error"`` (a signal constant in a window fails the task) or ``"drop"`` (it is left out
        of that window's network); see :func:`funcnet.robot.phase_networks`.
    base_dir : Path
        Folder that recording names in the results are relative to (the study file's folder).
    source : Path, optional
        The study file, for error messages and provenance.
    """

    recordings: tuple[Path, ...] = ()
    windows: tuple[WindowSpec, ...] = (WindowSpec("phases"),)
    parameters: tuple[tuple[str, tuple[Any, ...]], ...] = ()
    signals: tuple[str, ...] | None = None
    simulated: str | None = None
    plan_dir: Path | None = None
    seed: int = 0
    channels: Path | None = None
    axis: int | None = None
    constant: str = "error"
    base_dir: Path = dataclasses.field(default_factory=Path.cwd)
    source: Path | None = None

    def to_dict(self) -> dict[str, Any]:
        """The study as JSON-compatible data (paths as strings)."""
        return {
            "source": _str_or_none(self.source),
            "base_dir": str(self.base_dir),
            "recordings": [str(p) for p in self.recordings],
            "simulated": self.simulated,
            "plan_dir": _str_or_none(self.plan_dir),
            "seed": self.seed,
            "channels": _str_or_none(self.channels),
            "axis": self.axis,
            "signals": None if self.signals is None else list(self.signals),
            "constant": self.constant,
            "windows": [w.as_dict() for w in self.windows],
            "parameters": {name: list(values) for name, values in self.parameters},
        }


def _str_or_none(value: object) -> str | None:
    return None if value is None else str(value)


def load_study(path: str | os.PathLike[str]) -> Study:
    """Read a study description from a TOML file.

    Relative paths and glob patterns are taken relative to the file's folder. See
    ``examples/study.toml`` for a documented example. Layout::

        signals = ["RP", "AP", "MP", "V", "RC", "AC"]   # optional
        constant = "drop"            # optional: "error" (default) or "drop"
        [recordings]
        paths = ["traces/*.xml"]     # files or glob patterns
        simulated = "paper"          # optional: "paper" or a plan TOML file
        plan_dir = "plan"            # optional, default <out_dir>/plan
        seed = 0                     # optional, seed of the simulated plan
        channels = "channels.toml"   # optional channel map
        axis = 7                     # optional
        [[windows]]                  # default: one table with kind = "phases"
        kind = "sliding"             # phases | fixed | reversal | sliding | range
        width = 0.6
        step = 0.3
        [network]
        delay = [5, 10]              # a list spans a grid

    Parameters
    ----------
    path : path-like
        The TOML file.

    Returns
    -------
    Study

    Raises
    ------
    StudyError
        On malformed TOML, an unknown key, a value of the wrong type, a window kind or option
        that does not exist, or a pattern that matches no file; the message names the file and
        the key.
    OSError
        If the file cannot be read.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.xml").write_text("<traceSession/>")
    >>> _ = (folder / "s.toml").write_text('''
    ... [recordings]
    ... paths = ["*.xml"]
    ... [[windows]]
    ... kind = "range"
    ... start = 0.5
    ... stop = 1.5
    ... [network]
    ... delay = [5, 10]
    ... ''')
    >>> study = load_study(folder / "s.toml")
    >>> [p.name for p in study.recordings], study.windows[0].as_dict()
    (['a.xml'], {'kind': 'range', 'start': 0.5, 'stop': 1.5})
    >>> parameter_grid(study)
    [{'delay': 5}, {'delay': 10}]
    """
    source = Path(path).resolve()
    with open(source, "rb") as fh:
        raw = fh.read()
    try:
        doc = tomllib.loads(raw.decode("utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise StudyError(f"{source}: not valid TOML: {exc}") from None
    return _study_from_document(doc, source)


def _study_from_document(doc: Mapping[str, Any], source: Path) -> Study:
    base = source.parent

    def fail(key: str, message: str) -> StudyError:
        return StudyError(f"{source}: {key}: {message}")

    _reject_unknown(doc, {"signals", "constant", "recordings", "windows", "network"}, "", fail)
    recordings_table = doc.get("recordings", {})
    if not isinstance(recordings_table, dict):
        raise fail("recordings", "must be a table ([recordings])")
    _reject_unknown(
        recordings_table,
        {"paths", "simulated", "plan_dir", "seed", "channels", "axis"},
        "recordings.",
        fail,
    )
    patterns = recordings_table.get("paths", [])
    if isinstance(patterns, str):
        patterns = [patterns]
    if not isinstance(patterns, list) or not all(isinstance(p, str) for p in patterns):
        raise fail("recordings.paths", "must be a list of file names or glob patterns")
    files: list[Path] = []
    for pattern in patterns:
        matches = sorted(glob.glob(str(base / pattern), recursive=True))
        matches = [m for m in matches if Path(m).is_file()]
        if not matches:
            raise fail("recordings.paths", f"{pattern!r} matches no file")
        files.extend(Path(m).resolve() for m in matches)
    simulated = recordings_table.get("simulated")
    if simulated is not None:
        if not isinstance(simulated, str):
            raise fail("recordings.simulated", 'must be "paper" or a plan TOML file')
        if simulated != "paper":
            plan_file = (base / simulated).resolve()
            if not plan_file.is_file():
                raise fail("recordings.simulated", f"plan file {plan_file} does not exist")
            simulated = str(plan_file)
    if not files and simulated is None:
        raise fail("recordings", "names no recording (give paths or simulated)")
    plan_dir = recordings_table.get("plan_dir")
    if plan_dir is not None and not isinstance(plan_dir, str):
        raise fail("recordings.plan_dir", "must be a folder name")
    seed = recordings_table.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise fail("recordings.seed", "must be a non-negative integer")
    channels = recordings_table.get("channels")
    if channels is not None:
        if not isinstance(channels, str):
            raise fail("recordings.channels", "must be the name of a channel map TOML file")
        channels = (base / channels).resolve()
        if not channels.is_file():
            raise fail("recordings.channels", f"channel map {channels} does not exist")
    axis = recordings_table.get("axis")
    if axis is not None and (isinstance(axis, bool) or not isinstance(axis, int) or axis < 0):
        raise fail("recordings.axis", "must be a non-negative integer")

    signals = doc.get("signals")
    if signals is not None:
        if isinstance(signals, str):
            signals = [s.strip() for s in signals.split(",")]
        if not isinstance(signals, list) or not all(isinstance(s, str) and s for s in signals):
            raise fail("signals", "must be a list of signal names")
        if len(set(signals)) != len(signals) or len(signals) < 2:
            raise fail("signals", "must name at least two distinct signals")
        signals = tuple(signals)

    from funcnet.robot.windows import CONSTANT_POLICIES

    constant = doc.get("constant", "error")
    if constant not in CONSTANT_POLICIES:
        raise fail("constant", f"must be {' or '.join(map(repr, CONSTANT_POLICIES))}")

    windows_list = doc.get("windows", [{"kind": "phases"}])
    if not isinstance(windows_list, list) or not windows_list:
        raise fail("windows", "must be one or more [[windows]] tables")
    windows = tuple(
        _window_spec(entry, f"windows[{i}]", fail) for i, entry in enumerate(windows_list)
    )

    network = doc.get("network", {})
    if not isinstance(network, dict):
        raise fail("network", "must be a table ([network])")
    _reject_unknown(network, set(NETWORK_PARAMETERS), "network.", fail)
    parameters = []
    for name, value in network.items():
        values = value if isinstance(value, list) else [value]
        if not values:
            raise fail(f"network.{name}", "an empty list spans no grid")
        types = NETWORK_PARAMETERS[name]
        for v in values:
            if isinstance(v, bool) or not isinstance(v, types):
                kind = " or ".join(t.__name__ for t in types)
                raise fail(f"network.{name}", f"{v!r} is not of type {kind}")
        if len(set(values)) != len(values):
            raise fail(f"network.{name}", "repeats a value")
        parameters.append((name, tuple(_parameter_value(name, v) for v in values)))

    return Study(
        recordings=tuple(files),
        windows=windows,
        parameters=tuple(parameters),
        signals=signals,
        simulated=simulated,
        plan_dir=None if plan_dir is None else (base / plan_dir).resolve(),
        seed=seed,
        channels=channels,
        axis=axis,
        constant=constant,
        base_dir=base,
        source=source,
    )


def _reject_unknown(table: Mapping[str, Any], known: set[str], prefix: str, fail: Any) -> None:
    for key in table:
        if key not in known:
            raise fail(f"{prefix}{key}", f"unknown key (known: {', '.join(sorted(known))})")


def _parameter_value(name: str, value: Any) -> Any:
    # TOML has no null: normalize = "none" means no normalization.
    if name == "normalize" and value.lower() == "none":
        return None
    if name in ("rr", "cr", "mu"):
        return float(value)
    return value


def _window_spec(entry: Any, key: str, fail: Any) -> WindowSpec:
    if not isinstance(entry, dict):
        raise fail(key, "must be a table")
    kind = entry.get("kind")
    if kind not in WINDOW_KINDS:
        raise fail(f"{key}.kind", f"{kind!r} is not one of {', '.join(WINDOW_KINDS)}")
    options = {k: v for k, v in entry.items() if k != "kind"}
    allowed, required = _window_options(kind)
    _reject_unknown(options, allowed, f"{key}.", fail)
    for name in required:
        if name not in options:
            raise fail(f"{key}.{name}", f"is required for {kind} windows")
    if kind == "range":
        for bound in ("start", "stop"):
            value = options[bound]
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise fail(f"{key}.{bound}", "must be a time in seconds")
        if not options["start"] < options["stop"]:
            raise fail(f"{key}.stop", "must be greater than start")
        options = {k: float(v) for k, v in options.items()}
    return WindowSpec(kind, tuple(sorted(options.items())))


def _window_options(kind: str) -> tuple[set[str], set[str]]:
    """Options of a window kind and those required: its builder's parameters after the first.

    The kinds built from detected phases also take :func:`~funcnet.robot.detect_phases`'s
    thresholds (``standstill``, ``cruise``, ...).
    """
    if kind == "range":
        return {"start", "stop"}, {"start", "stop"}
    from funcnet.robot import detect_phases
    from funcnet.robot import windows as builders

    builder = getattr(builders, _BUILDERS[kind])
    parameters = list(inspect.signature(builder).parameters.values())[1:]
    allowed = {p.name for p in parameters}
    required = {p.name for p in parameters if p.default is inspect.Parameter.empty}
    if kind != "sliding":
        detect = list(inspect.signature(detect_phases).parameters.values())[1:]
        allowed |= {p.name for p in detect}
    return allowed, required


def parameter_grid(study: Study) -> list[dict[str, Any]]:
    """Every parameter set of the study's grid, in a fixed order.

    The product is taken over the parameters in the order the study names them, the last one
    varying fastest.

    Parameters
    ----------
    study : Study

    Returns
    -------
    list of dict
        One dict per parameter set, holding only the parameters the study names.
    """
    names = [name for name, _ in study.parameters]
    return [
        dict(zip(names, combo, strict=True))
        for combo in itertools.product(*(values for _, values in study.parameters))
    ]


@lru_cache(maxsize=1)
def _network_defaults() -> dict[str, Any]:
    from funcnet.network import functional_network

    signature = inspect.signature(functional_network)
    return {name: signature.parameters[name].default for name in NETWORK_PARAMETERS}


# --------------------------------------------------------------------------------------------
# reading recordings (cached per worker process)


def _derived_needed(signals: Sequence[str] | None, columns: Iterable[str]) -> tuple[str, ...]:
    from funcnet.robot.preprocess import DERIVED_SIGNALS

    columns = set(columns)
    if signals is None:  # the default nodes: V where AP is there to derive it from
        signals = ("V",) if "AP" in columns else ()
    return tuple(s for s in DERIVED_SIGNALS if s in signals and s not in columns)


def read_recording(
    path: str | os.PathLike[str],
    *,
    signals: Sequence[str] | None = None,
    channels: str | os.PathLike[str] | None = None,
    axis: int | None = None,
) -> Any:
    """Read a trace and add the derived signals a selection needs (V by default).

    Parameters
    ----------
    path : path-like
        Trace file.
    signals : sequence of str, optional
        The nodes that will be used; derived ones (V, FE, TORSION) are computed on the whole
        recording, before any windowing, so that no window loses samples at its ends.
    channels, axis
        Passed to :func:`funcnet.robot.read_trace`.

    Returns
    -------
    funcnet.robot.Recording
    """
    from funcnet.robot import add_derived_signals, read_trace

    recording = read_trace(path, channels=channels, axis=axis)
    derived = _derived_needed(signals, recording.data.columns)
    if derived:
        recording = add_derived_signals(recording, list(derived))
    return recording


@lru_cache(maxsize=2)
def _cached_recording(
    path: str, sha256: str, signals: tuple[str, ...] | None, channels: str | None, axis: int | None
) -> Any:
    # The read is cached per worker: every task of a recording on that worker reuses it. The
    # content hash is checked so that a file changed during the run cannot be mislabelled.
    if file_sha256(path) != sha256:
        raise StudyError(f"{path}: the file changed while the study was running")
    return read_recording(path, signals=signals, channels=channels, axis=axis)


# --------------------------------------------------------------------------------------------
# tasks


@dataclass(frozen=True)
class _Source:
    """A recording as the tasks see it."""

    path: str
    name: str
    trial: str
    sha256: str


@dataclass(frozen=True)
class _WindowTask:
    """Expand one window specification on one recording."""

    key: str
    source: _Source
    spec: WindowSpec
    signals: tuple[str, ...] | None
    channels: str | None
    axis: int | None


@dataclass(frozen=True)
class _NetworkTask:
    """One functional network: a recording, a window, a parameter set."""

    key: str
    source: _Source
    window: dict[str, Any]
    parameters: dict[str, Any]
    signals: tuple[str, ...] | None
    channels: str | None
    axis: int | None
    constant: str


@dataclass(frozen=True)
class _Outcome:
    key: str
    value: Any = None
    error: str | None = None
    fatal: str | None = None
    warnings: tuple[tuple[str, str], ...] = ()  # (category, first message) per category


def _content_key(**content: Any) -> str:
    text = json.dumps(content, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _window_record(window: Any) -> dict[str, Any]:
    return {
        "label": str(window.label),
        "phase": None if window.phase is None else str(window.phase),
        "offset": float(window.offset),
        "start": float(window.start),
        "stop": float(window.stop),
    }


def _expand_windows(task: _WindowTask) -> _Outcome:
    """Worker side: the windows a specification gives on a recording."""
    from funcnet.robot import detect_phases
    from funcnet.robot import windows as builders

    try:
        recording = _cached_recording(
            task.source.path, task.source.sha256, task.signals, task.channels, task.axis
        )
        options = dict(task.spec.options)
        if task.spec.kind == "range":
            windows = [builders.span_window(options["start"], options["stop"])]
        elif task.spec.kind == "sliding":
            windows = builders.sliding_windows(recording, **options)
        else:
            detect = set(inspect.signature(detect_phases).parameters)
            phases = detect_phases(recording, **{k: v for k, v in options.items() if k in detect})
            builder = getattr(builders, _BUILDERS[task.spec.kind])
            if task.spec.kind == "reversal" and not phases["phase"].eq("reversal").any():
                windows = []  # a trial without a reversal has no reversal windows
            else:
                windows = builder(phases, **{k: v for k, v in options.items() if k not in detect})
        return _Outcome(task.key, value=[_window_record(w) for w in windows])
    except ParameterError as exc:
        return _Outcome(task.key, fatal=str(exc))
    except FuncnetError as exc:
        return _Outcome(task.key, error=str(exc))


def _network_rows(task: _NetworkTask) -> _Outcome:
    """Worker side: compute one network and return its rows as an Arrow table."""
    from funcnet.robot import phase_networks
    from funcnet.robot.windows import Window

    try:
        recording = _cached_recording(
            task.source.path, task.source.sha256, task.signals, task.channels, task.axis
        )
        signals = None if task.signals is None else list(task.signals)
        window = Window(**task.window)
        with warnings.catch_warnings(record=True) as caught, _one_thread_per_task():
            warnings.simplefilter("always")
            networks = phase_networks(
                recording, [window], signals=signals, constant=task.constant, **task.parameters
            )
        (network,) = networks.values()
    except ParameterError as exc:
        return _Outcome(task.key, fatal=str(exc))
    except FuncnetError as exc:
        return _Outcome(task.key, error=str(exc))
    rows = _rows_table(task, network)
    first: dict[str, str] = {}
    for w in caught:
        first.setdefault(w.category.__name__, str(w.message))
    return _Outcome(task.key, value=rows, warnings=tuple(sorted(first.items())))


_IDENTITY_SCHEMA = pa.schema(
    [
        ("recording", pa.string()),
        ("trial", pa.string()),
        ("source_sha256", pa.string()),
        ("window", pa.string()),
        ("phase", pa.string()),
        ("offset", pa.float64()),
        ("start", pa.float64()),
        ("stop", pa.float64()),
        ("signals", pa.string()),
        ("constant", pa.string()),
        ("dropped", pa.string()),
        ("dim", pa.int64()),
        ("delay", pa.int64()),
        ("rr_target", pa.float64()),
        ("cr_target", pa.float64()),
        ("mu", pa.float64()),
        ("metric", pa.string()),
        ("normalize", pa.string()),
        ("measure", pa.string()),
        ("rule", pa.string()),
        ("theiler", pa.int64()),
    ]
)


def _rows_table(task: _NetworkTask, network: Any) -> pa.Table:
    pairs = network.pairs
    n = len(pairs)
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
        "dropped": ",".join(network.parameters["dropped"]),
        **{PARAMETER_COLUMNS[k]: v for k, v in task.parameters.items()},
    }
    columns = {
        field.name: pa.array([identity[field.name]] * n, type=field.type)
        for field in _IDENTITY_SCHEMA
    }
    pairs_table = pa.Table.from_pandas(pairs.reset_index(drop=True), preserve_index=False)
    for name, column in zip(pairs_table.column_names, pairs_table.columns, strict=True):
        columns[name] = column
    # Plain Parquet: no pandas metadata, so every reader sees the same columns and types.
    return pa.table(columns).replace_schema_metadata(None)


# --------------------------------------------------------------------------------------------
# execution back ends


def _watch_parent(parent: int) -> None:
    """Initializer of the local worker processes: exit when the parent is gone.

    A worker whose parent was killed (SIGKILL leaves no chance to shut the pool down) exits
    instead of waiting forever for tasks.
    """
    def watch() -> None:
        while True:
            if os.getppid() != parent:
                os._exit(1)
            threading.Event().wait(0.5)

    threading.Thread(target=watch, name="funcnet-parent-watch", daemon=True).start()


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


def _check_execution(scheduler: str | None, workers: int | None) -> int:
    """Validate ``scheduler`` and ``workers``; return the number of local workers."""
    n_workers = _DEFAULT_WORKERS if workers is None else workers
    if isinstance(n_workers, bool) or not isinstance(n_workers, int) or n_workers < 0:
        raise ParameterError(f"workers must be an integer >= 0, got {workers!r}")
    if scheduler is not None and scheduler != "local-cluster":
        host, _, port = scheduler.removeprefix("tcp://").rpartition(":")
        if not scheduler.startswith("tcp://") or not host or not port.isdigit():
            raise ParameterError(
                f"scheduler must be 'tcp://HOST:PORT' or 'local-cluster', got {scheduler!r}"
            )
    return n_workers


class _Backend:
    """Run task functions in this process, on local processes or on a Dask cluster.

    Nothing is started until the first :meth:`map_unordered`: a run with nothing to compute
    starts no process and connects to no scheduler.
    """

    def __init__(self, scheduler: str | None, workers: int | None) -> None:
        self._scheduler = scheduler
        self._workers = _check_execution(scheduler, workers)
        self._stack = contextlib.ExitStack()
        self._started = False
        self._client: Any = None
        self._pool: Any = None

    def _start(self) -> None:
        self._started = True
        if self._scheduler is None:
            if self._workers == 0:
                return
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            # spawn: the caller may run threads (progress bars, Dask) that fork must not copy.
            self._pool = ProcessPoolExecutor(
                max_workers=self._workers,
                mp_context=multiprocessing.get_context("spawn"),
                initializer=_watch_parent,
                initargs=(os.getpid(),),
            )
            # On an error or Ctrl-C, tasks not yet started are dropped rather than awaited.
            self._stack.callback(self._pool.shutdown, wait=True, cancel_futures=True)
            return
        from distributed import Client, LocalCluster

        if self._scheduler == "local-cluster":
            cluster = LocalCluster(
                n_workers=max(self._workers, 1),
                threads_per_worker=1,
                processes=True,
                host="127.0.0.1",
                dashboard_address=None,
                # On a busy machine the workers log "event loop unresponsive" warnings to
                # stderr; the command line's output is one line per error, nothing else.
                silence_logs=logging.ERROR,
            )
            self._stack.enter_context(cluster)
            self._client = self._stack.enter_context(Client(cluster))
            return
        try:
            self._client = self._stack.enter_context(Client(self._scheduler, timeout="30s"))
        except OSError as exc:
            raise StudyError(f"scheduler {self._scheduler}: cannot connect: {exc}") from None

    def map_unordered(self, fn: Callable[[Any], _Outcome], tasks: Sequence[Any]) -> Iterator[Any]:
        """Run ``fn`` on every task; yield the outcomes as they finish."""
        if not tasks:
            return
        if not self._started:
            self._start()
        if self._client is not None:
            from distributed import as_completed

            futures = [
                self._client.submit(fn, task, key=f"funcnet-{task.key}", pure=False)
                for task in tasks
            ]
            for future in as_completed(futures):
                yield future.result()
        elif self._pool is not None:
            import concurrent.futures

            futures = [self._pool.submit(fn, task) for task in tasks]
            for future in concurrent.futures.as_completed(futures):
                yield future.result()
        else:
            for task in tasks:
                yield fn(task)

    def close(self) -> None:
        """Stop what :meth:`map_unordered` started."""
        self._stack.close()


# --------------------------------------------------------------------------------------------
# running a study


@dataclass(frozen=True)
class TaskFailure:
    """A task whose data could not be analysed.

    Attributes
    ----------
    recording : str
        The recording's name in the results.
    window : str
        The window label (or the window specification when the windows could not be built).
    parameters : dict
        The parameter set (empty when the windows could not be built).
    message : str
        The error message.
    """

    recording: str
    window: str
    parameters: dict[str, Any]
    message: str


@dataclass(frozen=True)
class StudyResult:
    """What :func:`run_study` did.

    Attributes
    ----------
    out_dir : Path
        The results folder; :func:`load_results` reads its rows.
    tasks : int
        Network tasks the study consists of.
    computed : int
        Network tasks computed by this run.
    cached : int
        Network tasks found done (or failed) by an earlier run.
    failures : tuple of TaskFailure
        Tasks (and window expansions) whose data could not be analysed.
    warnings : dict
        Warning category -> (number of tasks computed by this run that raised it, one of its
        messages).
    """

    out_dir: Path
    tasks: int
    computed: int
    cached: int
    failures: tuple[TaskFailure, ...]
    warnings: dict[str, tuple[int, str]]


def run_study(
    study: Study,
    out_dir: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: Callable[[int, int, str], None] | None = None,
) -> StudyResult:
    """Run every task of a study that has no result yet in ``out_dir``.

    Parameters
    ----------
    study : Study
    out_dir : path-like
        Results folder (created if needed). See the module docstring for its layout.
    scheduler : str, optional
        ``None`` runs on local processes (:class:`concurrent.futures.ProcessPoolExecutor`);
        ``"tcp://HOST:PORT"`` submits to a running Dask distributed scheduler;
        ``"local-cluster"`` starts a Dask ``LocalCluster`` on the loopback interface for the run.
        The rows are identical either way.
    workers : int, optional
        Worker processes for the local pool and the local cluster (default 2); 0 runs the tasks
        one after the other in this process (for debugging and tiny studies). Ignored for an
        external scheduler.
    progress : callable, optional
        Called as ``progress(done, total, description)`` as trials of a simulated plan are
        written and as network tasks finish (``total`` counts the tasks still to compute).

    Returns
    -------
    StudyResult

    Raises
    ------
    StudyError
        If another run holds ``out_dir``, the scheduler cannot be reached, or a parameter value
        is invalid (it would fail every task).
    ParameterError
        If ``scheduler`` or ``workers`` is invalid.

    Notes
    -----
    A run killed at any moment (even SIGKILL) and started again ends with the same rows as an
    uninterrupted run: each finished task is one file written atomically, and a task is
    computed again only if its file is missing.

    Examples
    --------
    Two signals of a small CSV trace, one window, two delays, run in this process:

    >>> import pathlib, tempfile
    >>> import numpy as np, pandas as pd
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> t = np.arange(0, 2, 0.002)
    >>> trace = pd.DataFrame({"time": t, "RP": np.sin(5 * t), "AP": np.sin(5 * t - 0.3)})
    >>> trace.to_csv(folder / "trace.csv", index=False)
    >>> study = Study(recordings=(folder / "trace.csv",), signals=("RP", "AP"),
    ...               windows=(WindowSpec("range", (("start", 0.5), ("stop", 1.5))),),
    ...               parameters=(("delay", (5, 10)),), base_dir=folder)
    >>> result = run_study(study, folder / "out", workers=0)
    >>> result.tasks, result.computed, result.cached
    (2, 2, 0)
    >>> rows = load_results(folder / "out")
    >>> rows[["recording", "window", "delay", "x", "y"]]
       recording         window  delay   x   y
    0  trace.csv  0.500-1.500 s      5  RP  AP
    1  trace.csv  0.500-1.500 s     10  RP  AP
    >>> run_study(study, folder / "out", workers=0).computed  # nothing new to compute
    0
    """
    _check_execution(scheduler, workers)
    out = Path(out_dir).resolve()
    out.mkdir(parents=True, exist_ok=True)
    with _exclusive(out):
        return _run_locked(study, out, scheduler, workers, progress)


@contextlib.contextmanager
def _exclusive(out: Path) -> Iterator[None]:
    # An advisory lock: the kernel drops it when the holder dies, even by SIGKILL.
    with open(out / ".lock", "a") as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise StudyError(f"{out}: another study run is using this folder") from None
        yield


def _run_locked(
    study: Study,
    out: Path,
    scheduler: str | None,
    workers: int | None,
    progress: Callable[[int, int, str], None] | None,
) -> StudyResult:
    dirs = {name: out / name for name in ("rows", "failed", "windows", "cache")}
    for folder in dirs.values():
        folder.mkdir(exist_ok=True)
        for leftover in folder.glob(".*.tmp"):  # temporary files of a killed run
            leftover.unlink(missing_ok=True)

    recordings = list(study.recordings)
    if study.simulated is not None:
        recordings.extend(_simulated_recordings(study, study.simulated, out, progress))
    sources = _sources(recordings, study.base_dir)
    provenance = _provenance(study, sources)
    _write_study_json(out, study, provenance, status="running")

    with contextlib.closing(_Backend(scheduler, workers)) as backend:
        window_tasks = _window_tasks(study, sources)
        _expand_missing_windows(window_tasks, dirs["windows"], backend, study)
        tasks, failures = _network_tasks(study, window_tasks, dirs["windows"])
        _select_current(dirs, {t.key for t in tasks})
        todo = [t for t in tasks if not _done(dirs, t.key)]
        warning_counts: Counter[str] = Counter()
        warning_examples: dict[str, str] = {}
        if progress is not None:
            progress(0, len(todo), "networks")
        by_key = {t.key: t for t in todo}
        for done, outcome in enumerate(backend.map_unordered(_network_rows, todo), start=1):
            _check_fatal(outcome, study)
            _store(dirs, by_key[outcome.key], outcome)
            for category, message in outcome.warnings:
                warning_counts[category] += 1
                warning_examples.setdefault(category, message)
            if progress is not None:
                progress(done, len(todo), "networks")

    failures.extend(_failures(dirs, tasks))
    result = StudyResult(
        out_dir=out,
        tasks=len(tasks),
        computed=len(todo),
        cached=len(tasks) - len(todo),
        failures=tuple(failures),
        warnings={c: (n, warning_examples[c]) for c, n in sorted(warning_counts.items())},
    )
    _write_study_json(out, study, provenance, status="complete", result=result)
    return result


def _channels(study: Study) -> tuple[str | None, str | None]:
    """The channel map's path and content hash (None, None without one)."""
    if study.channels is None:
        return None, None
    return str(study.channels), file_sha256(study.channels)


def _window_tasks(study: Study, sources: Sequence[_Source]) -> list[_WindowTask]:
    """One task per (recording, window specification), keyed by content."""
    channels, channels_sha = _channels(study)
    return [
        _WindowTask(
            key=_content_key(
                stage="windows",
                source_sha256=source.sha256,
                spec=spec.as_dict(),
                channels_sha256=channels_sha,
                axis=study.axis,
                funcnet=__version__,
            ),
            source=source,
            spec=spec,
            signals=study.signals,
            channels=channels,
            axis=study.axis,
        )
        for source in sources
        for spec in study.windows
    ]


def _expand_missing_windows(
    tasks: Sequence[_WindowTask], folder: Path, backend: _Backend, study: Study
) -> None:
    """Stage 1: the windows of every (recording, specification) not expanded before."""
    todo = [t for t in tasks if not (folder / f"{t.key}.json").exists()]
    for outcome in backend.map_unordered(_expand_windows, todo):
        _check_fatal(outcome, study)
        record = {"windows": outcome.value, "error": outcome.error}
        write_text_atomic(folder / f"{outcome.key}.json", json.dumps(record))


def _network_tasks(
    study: Study, window_tasks: Sequence[_WindowTask], folder: Path
) -> tuple[list[_NetworkTask], list[TaskFailure]]:
    """Stage 2's tasks: every (recording, window, parameter set), keyed by content."""
    channels, channels_sha = _channels(study)
    defaults = _network_defaults()
    grid = [{**defaults, **p} for p in parameter_grid(study)]
    signals = None if study.signals is None else list(study.signals)
    tasks: dict[str, _NetworkTask] = {}
    failures = []
    for wt in window_tasks:
        expanded = json.loads((folder / f"{wt.key}.json").read_text())
        if expanded["error"] is not None:
            spec = json.dumps(wt.spec.as_dict())
            failures.append(TaskFailure(wt.source.name, spec, {}, expanded["error"]))
            continue
        for window, parameters in itertools.product(expanded["windows"], grid):
            key = _content_key(
                stage="network",
                source_sha256=wt.source.sha256,
                recording=wt.source.name,
                trial=wt.source.trial,
                window=window,
                parameters=parameters,
                signals=signals,
                constant=study.constant,
                channels_sha256=channels_sha,
                axis=study.axis,
                funcnet=__version__,
            )
            tasks[key] = _NetworkTask(
                key, wt.source, window, parameters, study.signals, channels, study.axis,
                study.constant,
            )
    return list(tasks.values()), failures


def _check_fatal(outcome: _Outcome, study: Study) -> None:
    if outcome.fatal is not None:
        where = study.source if study.source is not None else "study"
        raise StudyError(f"{where}: network: {outcome.fatal}")


def _done(dirs: Mapping[str, Path], key: str) -> bool:
    return (dirs["rows"] / f"{key}.parquet").exists() or (dirs["failed"] / f"{key}.json").exists()


def _store(dirs: Mapping[str, Path], task: _NetworkTask, outcome: _Outcome) -> None:
    if outcome.error is not None:
        record = {
            "recording": task.source.name,
            "window": task.window["label"],
            "parameters": task.parameters,
            "message": outcome.error,
        }
        write_text_atomic(dirs["failed"] / f"{task.key}.json", json.dumps(record))
        return
    with atomic_path(dirs["rows"] / f"{task.key}.parquet") as tmp:
        pq.write_table(outcome.value, tmp)


def _select_current(dirs: Mapping[str, Path], keys: set[str]) -> None:
    """Make ``rows/`` and ``failed/`` hold exactly the study's finished tasks."""
    for kind, suffix in (("rows", ".parquet"), ("failed", ".json")):
        for path in dirs[kind].glob(f"*{suffix}"):
            if path.name[: -len(suffix)] not in keys:
                os.replace(path, dirs["cache"] / path.name)
        for key in keys:
            kept = dirs["cache"] / f"{key}{suffix}"
            if kept.exists():
                os.replace(kept, dirs[kind] / kept.name)


def _failures(dirs: Mapping[str, Path], tasks: Sequence[_NetworkTask]) -> list[TaskFailure]:
    failures = []
    for task in tasks:
        path = dirs["failed"] / f"{task.key}.json"
        if path.exists():
            record = json.loads(path.read_text())
            failures.append(
                TaskFailure(
                    record["recording"], record["window"], record["parameters"], record["message"]
                )
            )
    return failures


def _simulated_recordings(
    study: Study, simulated: str, out: Path, progress: Callable[[int, int, str], None] | None
) -> list[Path]:
    """Simulate the study's plan (trials already written are kept) and list its traces."""
    from funcnet.robot import paper_plan, write_plan
    from funcnet.robot.plan import read_plan

    trials = paper_plan() if simulated == "paper" else read_plan(simulated)
    plan_dir = study.plan_dir if study.plan_dir is not None else out / "plan"
    write_plan(trials, plan_dir, seed=study.seed, progress=progress)
    return [plan_dir / f"{trial.name}.xml" for trial in trials]


def _sources(paths: Iterable[Path], base_dir: Path) -> list[_Source]:
    """The recordings as the tasks see them; each folder's ``manifest.csv`` is read once."""
    base = base_dir.resolve()
    trial_names: dict[Path, dict[str, str]] = {}
    sources = []
    for path in paths:
        path = Path(path).resolve()
        try:
            name = path.relative_to(base).as_posix()
        except ValueError:
            name = path.as_posix()
        if path.parent not in trial_names:
            trial_names[path.parent] = _manifest_trials(path.parent / "manifest.csv")
        trial = trial_names[path.parent].get(path.name, path.stem)
        sources.append(_Source(str(path), name, trial, file_sha256(path)))
    return sources


def _manifest_trials(manifest: Path) -> dict[str, str]:
    """File name -> trial name from a plan's manifest (:func:`funcnet.robot.write_plan`)."""
    if not manifest.is_file():
        return {}
    table = pd.read_csv(manifest, dtype=str)
    if not {"file", "name"} <= set(table.columns):
        return {}
    files = table["file"].map(lambda v: Path(v).name)
    unique = ~files.duplicated(keep=False)  # a file listed twice names no trial
    return dict(zip(files[unique], table["name"][unique], strict=True))


def package_versions(packages: Iterable[str]) -> dict[str, str | None]:
    """Versions of Python, funcnet and the given packages, for provenance.

    Parameters
    ----------
    packages : iterable of str
        Distribution names.

    Returns
    -------
    dict
        ``python``, ``funcnet``, then each package's installed version (``None`` if absent).

    Examples
    --------
    >>> versions = package_versions(["numpy", "no-such-distribution"])
    >>> list(versions), versions["no-such-distribution"]
    (['python', 'funcnet', 'numpy', 'no-such-distribution'], None)
    """
    from importlib.metadata import PackageNotFoundError, version

    versions: dict[str, str | None] = {
        "python": platform.python_version(),
        "funcnet": __version__,
    }
    for package in packages:
        try:
            versions[package] = version(package)
        except PackageNotFoundError:
            versions[package] = None
    return versions


def _provenance(study: Study, sources: Sequence[_Source]) -> dict[str, Any]:
    versions = package_versions(
        ("numpy", "numba", "scipy", "pandas", "pyarrow", "dask", "distributed")
    )
    inputs = {s.name: s.sha256 for s in sources}
    if study.channels is not None:
        inputs[str(study.channels)] = file_sha256(study.channels)
    if study.source is not None:
        inputs[str(study.source)] = file_sha256(study.source)
    return {"versions": versions, "inputs": inputs, "command": list(sys.argv)}


def _write_study_json(
    out: Path,
    study: Study,
    provenance: Mapping[str, Any],
    *,
    status: str,
    result: StudyResult | None = None,
) -> None:
    document: dict[str, Any] = {
        "status": status,
        "study": study.to_dict(),
        "provenance": dict(provenance),
    }
    if result is not None:
        document["run"] = {
            "tasks": result.tasks,
            "computed": result.computed,
            "cached": result.cached,
            "failures": [dataclasses.asdict(f) for f in result.failures],
            "warnings": {
                category: {"tasks": n, "example": message}
                for category, (n, message) in result.warnings.items()
            },
        }
    write_text_atomic(out / "study.json", json.dumps(document, indent=2, default=str) + "\n")


# --------------------------------------------------------------------------------------------
# reading results


def load_results(out_dir: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the rows of a study's results folder into one DataFrame.

    The rows are plain Parquet files in ``out_dir/rows``; other tools read them directly (for
    example DuckDB: ``SELECT * FROM 'out/rows/*.parquet'``, polars:
    ``pl.read_parquet('out/rows/*.parquet')``).

    Parameters
    ----------
    out_dir : path-like
        A folder written by :func:`run_study`.

    Returns
    -------
    DataFrame
        One row per pair per window per parameter set, sorted by recording, window (start,
        stop, label), signals and parameters; the pairs of one network in its pairs table's
        order.

    Raises
    ------
    StudyError
        If the folder holds no rows.
    """
    rows = Path(out_dir) / "rows"
    files = sorted(rows.glob("*.parquet")) if rows.is_dir() else []
    if not files:
        raise StudyError(f"{Path(out_dir)}: no study results (no rows/*.parquet)")
    tables = [pq.read_table(f) for f in files]
    frame = pa.concat_tables(tables, promote_options="default").to_pandas()
    # Within one task the rows keep the pairs table's order (a stable sort of whole files).
    order = ["recording", "start", "stop", "window", "signals", *PARAMETER_COLUMNS.values()]
    return frame.sort_values(order, na_position="first", kind="stable").reset_index(drop=True)

