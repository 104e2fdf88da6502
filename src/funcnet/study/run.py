"""Running a study: expand the windows, compute the missing networks, store their rows.

Decisions (where the specification leaves room):

* A task's key is the SHA-256 of the source file's content hash, the recording's name and trial
  in the results, the window (label, phase, offset, start, stop), the complete parameter set
  (:meth:`~funcnet.parameters.NetworkParameters.to_dict`), the signal selection, the constant
  policy, the channel map's content hash, the axis, the funcnet version and, when enabled, the
  ``[evidence]`` settings and the ``[stability]`` grid. A re-run therefore
  computes exactly the tasks whose key has no file yet. The name is part of the key so that two
  identical files listed under two names keep their own rows.
* Results are written by the process that runs :func:`run_study` (workers return rows), one file
  per task through a temporary file and a rename: a run killed at any moment leaves only whole
  files, and the restarted run computes what is missing. Leftover temporary files are removed.
  Workers of a Dask cluster need the recordings at the same paths (a shared file system); they
  need not see ``out_dir``.
* ``rows/`` holds exactly the tasks of the last study run in ``out_dir``: finished tasks of other
  studies (an earlier grid) are moved to ``cache/`` and moved back, not recomputed, when a study
  names them again. So ``rows/`` can be read as one data set by pandas, polars or DuckDB.
* Every parameter value is checked before anything is simulated, hashed or written.
* A task whose window cannot be analysed (a window too short for the embedding, an unreadable
  trace, a constant signal under ``constant = "error"``) is recorded in ``failed/`` and
  reported; the other tasks go on. By default (``constant = "drop"``) a signal constant in a
  window is left out of that window's network (:func:`funcnet.window_networks`); its rows name
  the nodes used (``signals``) and the signals left out (``dropped``).
* The problems of a network (degenerate pairs, thresholds out of order, rates above target) are
  counted from the flags of its pairs table (which the rows keep), per kind, in ``study.json``
  and :attr:`StudyResult.warnings`: never captured from :mod:`warnings` (not thread-safe on a
  Dask worker) nor parsed from text.
* A window kind that does not occur in a recording gives it no windows (a ``reversal``
  specification over trials without a reversal), not a failure.
* Without ``signals``, a recording's nodes are its roles (RP, AP, MP, RC, AC, those present) plus
  the velocity V derived from AP (Eq. 11-12), computed on the whole recording before windowing.
"""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import json
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from funcnet import __version__
from funcnet._io import file_sha256, write_text_atomic
from funcnet.errors import StudyError
from funcnet.parameters import NetworkParameters
from funcnet.study import store
from funcnet.study.backends import Backend, check_execution, require_dask
from funcnet.study.provenance import provenance
from funcnet.study.sources import simulated_recordings, sources
from funcnet.study.spec import Study, parameter_grid
from funcnet.study.tasks import (
    NetworkTask,
    Outcome,
    Source,
    WindowTask,
    content_key,
    expand_windows,
    network_rows,
    parameters_record,
)

__all__ = ["TaskFailure", "StudyResult", "run_study", "check_simulated_signals"]

Progress = Callable[[int, int, str], None]


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
        The complete parameter set (empty when the windows could not be built).
    message : str
        The error message (for a window skipped: why it has nothing to analyse).
    skipped : bool
        The window was skipped (the axis stands still in it), not failed.
    """

    recording: str
    window: str
    parameters: dict[str, Any]
    message: str
    skipped: bool = False


@dataclass(frozen=True)
class StudyResult:
    """What :func:`run_study` did.

    Attributes
    ----------
    out_dir : Path
        The results folder; :func:`funcnet.study.load_results` reads its rows.
    tasks : int
        Network tasks the study consists of.
    computed : int
        Network tasks computed by this run.
    cached : int
        Network tasks found done (or failed) by an earlier run.
    failures : tuple of TaskFailure
        Tasks (and window expansions) whose data could not be analysed.
    skipped : tuple of TaskFailure
        Windows with nothing to analyse (the axis stands still in them): listed, not failed.
    warnings : dict
        Kind of problem (``"degenerate"``, ``"eps_order"``, ``"rate_exceeded"``, the
        ``problem`` keys of :class:`funcnet.errors.ThresholdWarning`) -> (number of tasks
        computed by this run that have it, one of their messages).
    """

    out_dir: Path
    tasks: int
    computed: int
    cached: int
    failures: tuple[TaskFailure, ...]
    warnings: dict[str, tuple[int, str]]
    skipped: tuple[TaskFailure, ...] = ()


def run_study(
    study: Study,
    out_dir: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: Progress | None = None,
) -> StudyResult:
    """Run every task of a study that has no result yet in ``out_dir``.

    Parameters
    ----------
    study : Study
    out_dir : path-like
        Results folder (created if needed). See :mod:`funcnet.study.store` for its layout.
    scheduler : str, optional
        ``None`` runs on local processes (:class:`concurrent.futures.ProcessPoolExecutor`);
        ``"tcp://HOST:PORT"`` submits to a running Dask distributed scheduler;
        ``"local-cluster"`` starts a Dask ``LocalCluster`` on the loopback interface for the run
        (both need the ``dask`` extra). The rows are identical either way.
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
        If a parameter value is invalid (before anything is written), Dask is asked for but not
        installed, another run holds ``out_dir``, or the scheduler cannot be reached.
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
    >>> from funcnet.study import WindowSpec, load_results
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
    grid = parameter_grid(study)  # a bad value stops the run before anything is written
    check_simulated_signals(study)  # ... and a signal the simulated plan cannot have
    check_execution(scheduler, workers)
    if scheduler is not None:
        require_dask(scheduler)
    out = Path(out_dir).resolve()
    out.mkdir(parents=True, exist_ok=True)
    with store.exclusive(out):
        return _run_locked(study, grid, out, scheduler, workers, progress)


def check_simulated_signals(study: Study) -> None:
    """Refuse, before simulating anything, signals the simulated traces cannot provide.

    A simulated trace holds the roles of :data:`funcnet.sim.writer.SIGNALS`; the derived
    signals (V, FE, TORSION, VM) are computed from them. Any other name would fail every task
    of every trial, one identical error each, after the whole plan was simulated.

    Parameters
    ----------
    study : Study

    Raises
    ------
    StudyError
        One error naming every such signal, what the traces have and what can be derived.

    Examples
    --------
    >>> check_simulated_signals(Study(simulated="paper", signals=("RP", "V", "AC")))
    >>> check_simulated_signals(Study(simulated="paper", signals=("RP", "XX")))
    Traceback (most recent call last):
        ...
    funcnet.errors.StudyError: signals: XX cannot be in the simulated plan's traces; they ...
    """
    if study.simulated is None or study.signals is None:
        return
    from funcnet.robot.preprocess import DERIVED_SIGNALS
    from funcnet.sim.writer import SIGNALS

    unknown = [name for name in study.signals
               if name not in SIGNALS and name not in DERIVED_SIGNALS]
    if unknown and not study.recordings:
        where = f"{study.source}: " if study.source is not None else ""
        raise StudyError(
            f"{where}signals: {', '.join(unknown)} cannot be in the simulated plan's traces; "
            f"they have {', '.join(SIGNALS)} and derive {', '.join(DERIVED_SIGNALS)}"
        )


def _run_locked(
    study: Study,
    grid: Sequence[NetworkParameters],
    out: Path,
    scheduler: str | None,
    workers: int | None,
    progress: Progress | None,
) -> StudyResult:
    dirs = store.prepare(out)
    recordings = [*study.recordings, *simulated_recordings(study, out, progress)]
    found = sources(recordings, study.base_dir)
    recorded = provenance(study, found)
    _write_study_json(out, study, recorded, status="running")

    with contextlib.closing(Backend(scheduler, workers)) as backend:
        window_tasks = _window_tasks(study, found)
        _expand_missing_windows(window_tasks, dirs["windows"], backend, study)
        tasks, failures = _network_tasks(study, grid, window_tasks, dirs["windows"])
        store.select_current(dirs, {t.key for t in tasks})
        todo = [t for t in tasks if not store.done(dirs, t.key)]
        problems: dict[str, tuple[tuple[str, int, str], ...]] = {}
        if progress is not None:
            progress(0, len(todo), "networks")
        by_key = {t.key: t for t in todo}
        for finished, outcome in enumerate(backend.map_unordered(network_rows, todo), start=1):
            _check_fatal(outcome, study)
            _store(dirs, by_key[outcome.key], outcome)
            problems[outcome.key] = outcome.warnings
            if progress is not None:
                progress(finished, len(todo), "networks")

    # Counted in task order, not in the order tasks finish: the same example on every run.
    counts: dict[str, int] = {}
    examples: dict[str, str] = {}
    for task in todo:
        for problem, _, message in problems.get(task.key, ()):
            counts[problem] = counts.get(problem, 0) + 1
            examples.setdefault(problem, message)
    # Windows flagged when they were expanded (fixed windows mostly outside their phase), once
    # per flagged window and parameter set: the networks concerned.
    for wt in window_tasks:
        record = json.loads((dirs["windows"] / f"{wt.key}.json").read_text())
        for problem, n, message in record.get("warnings", []):
            counts[problem] = counts.get(problem, 0) + int(n) * len(grid)
            examples.setdefault(problem, message)
    ended = _failures(dirs, tasks)
    failures.extend(f for f in ended if not f.skipped)
    result = StudyResult(
        skipped=tuple(f for f in ended if f.skipped),
        out_dir=out,
        tasks=len(tasks),
        computed=len(todo),
        cached=len(tasks) - len(todo),
        failures=tuple(failures),
        warnings={p: (n, examples[p]) for p, n in sorted(counts.items())},
    )
    _write_study_json(out, study, recorded, status="complete", result=result)
    return result


def _channels(study: Study) -> tuple[str | None, str | None]:
    """The channel map's path and content hash (None, None without one)."""
    if study.channels is None:
        return None, None
    return str(study.channels), file_sha256(study.channels)


def _window_tasks(study: Study, found: Sequence[Source]) -> list[WindowTask]:
    """One task per (recording, window specification), keyed by content."""
    channels, channels_sha = _channels(study)
    return [
        WindowTask(
            key=content_key(
                stage="windows",
                source_sha256=source.sha256,
                spec=spec.as_dict(),
                channels_sha256=channels_sha,
                axis=study.axis,
                resample=study.resample,
                funcnet=__version__,
            ),
            source=source,
            spec=spec,
            signals=study.signals,
            channels=channels,
            axis=study.axis,
            resample=study.resample,
        )
        for source in found
        for spec in study.windows
    ]


def _expand_missing_windows(
    tasks: Sequence[WindowTask], folder: Path, backend: Backend, study: Study
) -> None:
    """Stage 1: the windows of every (recording, specification) not expanded before."""
    todo = [t for t in tasks if not (folder / f"{t.key}.json").exists()]
    for outcome in backend.map_unordered(expand_windows, todo):
        _check_fatal(outcome, study)
        record = {"windows": outcome.value, "error": outcome.error,
                  "warnings": [list(w) for w in outcome.warnings]}
        write_text_atomic(folder / f"{outcome.key}.json", json.dumps(record))


def _network_tasks(
    study: Study, grid: Sequence[NetworkParameters], window_tasks: Sequence[WindowTask],
    folder: Path,
) -> tuple[list[NetworkTask], list[TaskFailure]]:
    """Stage 2's tasks: every (recording, window, parameter set), keyed by content."""
    channels, channels_sha = _channels(study)
    signals = None if study.signals is None else list(study.signals)
    tasks: dict[str, NetworkTask] = {}
    failures = []
    for wt in window_tasks:
        expanded = json.loads((folder / f"{wt.key}.json").read_text())
        if expanded["error"] is not None:
            spec = json.dumps(wt.spec.as_dict())
            failures.append(TaskFailure(wt.source.name, spec, {}, expanded["error"]))
            continue
        for window, parameters in itertools.product(expanded["windows"], grid):
            key = content_key(
                stage="network",
                source_sha256=wt.source.sha256,
                recording=wt.source.name,
                trial=wt.source.trial,
                window=window,
                parameters=parameters_record(parameters),
                signals=signals,
                constant=study.constant,
                channels_sha256=channels_sha,
                axis=study.axis,
                resample=study.resample,
                funcnet=__version__,
                # only when on: the keys of plain tasks (and their cached rows) stay as they were
                **({"evidence": dict(study.evidence)} if study.evidence else {}),
                **({"stability": study.to_dict()["stability"]} if study.stability else {}),
            )
            tasks[key] = NetworkTask(
                key, wt.source, window, parameters, study.signals, channels, study.axis,
                study.resample, study.constant, study.evidence, study.stability,
            )
    return list(tasks.values()), failures


def _check_fatal(outcome: Outcome, study: Study) -> None:
    if outcome.fatal is not None:
        where = study.source if study.source is not None else "study"
        raise StudyError(f"{where}: {outcome.fatal}")


def _store(dirs: Mapping[str, Path], task: NetworkTask, outcome: Outcome) -> None:
    if outcome.error is not None or outcome.skipped is not None:
        record = {
            "recording": task.source.name,
            "window": task.window["label"],
            "parameters": parameters_record(task.parameters),
            "message": outcome.error if outcome.error is not None else outcome.skipped,
            # kept with the failures (done, not retried), told apart by this flag
            **({"skipped": True} if outcome.error is None else {}),
        }
        store.write_failure(dirs, task.key, record)
    else:
        store.write_rows(dirs, task.key, outcome.value)


def _failures(dirs: Mapping[str, Path], tasks: Sequence[NetworkTask]) -> list[TaskFailure]:
    failures = []
    for task in tasks:
        record = store.read_failure(dirs, task.key)
        if record is not None:
            failures.append(TaskFailure(
                record["recording"], record["window"], record["parameters"], record["message"],
                bool(record.get("skipped", False)),
            ))
    return failures


def _failure_record(failure: TaskFailure) -> dict[str, Any]:
    """A failure as study.json lists it (the ``skipped`` flag only where it is set)."""
    record = dataclasses.asdict(failure)
    del record["skipped"]  # the list it is in says it
    return record


def _write_study_json(
    out: Path,
    study: Study,
    recorded: Mapping[str, Any],
    *,
    status: str,
    result: StudyResult | None = None,
) -> None:
    document: dict[str, Any] = {
        "status": status,
        "study": study.to_dict(),
        "provenance": dict(recorded),
    }
    if result is not None:
        document["run"] = {
            "tasks": result.tasks,
            "computed": result.computed,
            "cached": result.cached,
            "failures": [_failure_record(f) for f in result.failures],
            **({"skipped": [_failure_record(f) for f in result.skipped]}
               if result.skipped else {}),
            "warnings": {
                problem: {"tasks": n, "example": message}
                for problem, (n, message) in result.warnings.items()
            },
        }
    write_text_atomic(out / "study.json", json.dumps(document, indent=2, default=str) + "\n")
