"""Runs added to the store: each read as ``inspect`` reads it, its figures kept.

:func:`read_run` reads one run (a trace file, or a log folder through a channel map) and
computes everything that needs only the run: its checksum, time, program signature, per-axis
figures (:mod:`funcnet.track.figures`) and the signals kept for later comparisons. It is a
plain function of a picklable :class:`RunTask`, so that many runs are read on local processes
or a Dask cluster (:class:`funcnet.study.backends.Backend`, as studies do). :func:`add_runs`
then, in time order and in this process, names each run's program among the robot's, computes
its departure from the program's earliest runs (:data:`REFERENCES` of them, kept in the store)
and writes it in one transaction (:func:`funcnet.track.store.add_run`). The robot's runs and
programs are read from the store once per call and kept up to date as the call adds runs, so
adding many runs at once gives the store adding them one call each, in time order, gives; a run
another process adds meanwhile is not among this call's references.

The run's time: ``--time`` when given, else the file's own start time where the format has one
(a SINUMERIK trace's ``startTime``), else the file's modification time (a folder's newest file);
a naive time is taken as UTC. Which one is said per run.
"""

from __future__ import annotations

import bisect
import contextlib
import math
import os
import sqlite3
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from datetime import UTC, datetime
from typing import TYPE_CHECKING, Any

import pandas as pd

from funcnet._io import file_sha256
from funcnet.errors import FuncnetError, FuncnetWarning, ParameterError
from funcnet.track import store as kept
from funcnet.track.figures import (
    as_recording,
    axis_figures,
    departures,
    recorded_units,
    run_axes,
    trace_columns,
)
from funcnet.track.program import program_name, program_signature, same_program

if TYPE_CHECKING:
    from funcnet.robot import Recording

__all__ = ["REFERENCES", "REFERENCE_COUNT", "RunTask", "ReadRun", "Added", "iso_time", "read_run",
           "add_runs"]

#: The earliest runs of a program a new run's departure is measured against.
REFERENCES = 5
#: The figure (not shown) that keeps how many references a run's departure had.
REFERENCE_COUNT = "departure_references"


@dataclass(frozen=True)
class RunTask:
    """One run to read: its path, channel map, axis, and the time given (or None)."""

    path: str
    channels: str | None = None
    axis: int | None = None
    time: str | None = None

    @property
    def key(self) -> str:
        """A name for a Dask task."""
        return f"track-{abs(hash(self.path)):x}"


@dataclass(frozen=True)
class ReadRun:
    """What :func:`read_run` found: everything but the program's name and the departure."""

    source: str
    checksum: str
    time: str
    time_from: str
    signature: list[list[float]]
    figures: dict[tuple[int, str], float]
    trace: bytes
    notes: tuple[str, ...]
    units: dict[str, str]


@dataclass(frozen=True)
class Added:
    """One run handed to :func:`add_runs`: kept, already there, or not read (``error``), with
    what was said."""

    source: str
    added: bool
    time: str
    time_from: str
    program: str
    notes: tuple[str, ...]
    error: bool = False


def _read_or_why(task: RunTask) -> tuple[str, ReadRun | str]:
    """:func:`read_run`, or why the run cannot be read (one line)."""
    try:
        return task.path, read_run(task)
    except (FuncnetError, OSError) as error:
        return task.path, f"not read: {error}"


def iso_time(value: str | datetime) -> str:
    """An ISO 8601 time in UTC, to the second (a naive time is taken as UTC).

    Examples
    --------
    >>> iso_time("2026-03-01T09:30:00+01:00"), iso_time("2026-03-01")
    ('2026-03-01T08:30:00+00:00', '2026-03-01T00:00:00+00:00')
    """
    try:
        moment = value if isinstance(value, datetime) else datetime.fromisoformat(value)
    except ValueError:
        raise ParameterError.of("time", f"{value!r} is not an ISO 8601 time") from None
    if moment.tzinfo is None:
        moment = moment.replace(tzinfo=UTC)
    return moment.astimezone(UTC).isoformat(timespec="seconds")


def _modified(path: str) -> float:
    if os.path.isdir(path):
        times = [e.stat().st_mtime for e in os.scandir(path) if e.is_file()]
        return max(times, default=os.path.getmtime(path))
    return os.path.getmtime(path)


def _time(task: RunTask, start_time: str | None) -> tuple[str, str]:
    if task.time is not None:
        return iso_time(task.time), "given"
    if start_time:
        with contextlib.suppress(ParameterError):
            return iso_time(start_time), "file"
    return iso_time(datetime.fromtimestamp(_modified(task.path), UTC)), "mtime"


def read_run(task: RunTask) -> ReadRun:
    """Read one run and compute what needs only it (module notes).

    Raises
    ------
    TraceError
        The run cannot be read.
    """
    from funcnet.robot.io.read import read_trace
    from funcnet.robot.units import in_degrees

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FuncnetWarning)
        recording = read_trace(task.path, channels=task.channels, axis=task.axis,
                               keep_setpoint=True)
        recording, _ = in_degrees(replace(recording, source=task.path), warn=False)
    time, time_from = _time(task, recording.start_time)
    figures: dict[tuple[int, str], float] = {}
    notes: list[str] = []
    for axis in run_axes(recording):
        found = axis_figures(recording, axis)
        figures.update({(axis, name): value for name, value in found.values.items()})
        notes += found.notes
    return ReadRun(source=task.path, checksum=file_sha256(task.path), time=time,
                   time_from=time_from, signature=program_signature(recording),
                   figures=figures,
                   trace=kept.pack_trace(trace_columns(recording), recording.sample_period),
                   notes=tuple(notes), units=recorded_units(recording))


@dataclass
class _Known:
    """The robot's runs and programs as the store holds them: read once per call, then kept up
    to date in memory as this call adds runs (not O(runs) of reading per run added)."""

    store: str
    robot: str
    runs: list[tuple[str, int, str, str]]  # (time, id, program, source), in the store's order
    checksums: set[str]
    programs: dict[str, list[list[float]]]
    traces: dict[int, tuple[pd.DataFrame, float] | None]

    @classmethod
    def read(cls, store: str, robot: str) -> _Known:
        table = kept.read_runs(store, robot)
        runs = [(str(t), int(i), str(p), str(s)) for t, i, p, s in zip(
            table["time"], table["id"], table["program"], table["source"], strict=True)]
        return cls(store, robot, runs, set(table["checksum"]), kept.read_programs(store, robot),
                   {})

    def program(self, signature: list[list[float]]) -> str:
        """The name of the robot's program the signature is, else a new program's name."""
        for name, theirs in self.programs.items():
            if same_program(signature, theirs):
                return name
        return program_name(signature)

    def references(self, program: str, time: str) -> list[Recording]:
        """The program's earliest runs before ``time`` (at most :data:`REFERENCES`) that have
        a kept trace, as recordings."""
        earlier = [(i, s) for t, i, p, s in self.runs if p == program and t < time]
        earlier = earlier[:REFERENCES]
        missing = [i for i, _ in earlier if i not in self.traces]
        found = kept.read_traces(self.store, missing)
        self.traces.update({i: found.get(i) for i in missing})
        return [as_recording(trace[0].copy(), trace[1], source=s)
                for i, s in earlier if (trace := self.traces[i]) is not None]

    def added(self, run: ReadRun, program: str, db: sqlite3.Connection) -> None:
        """Note a run this call has just added (its id as the store gave it)."""
        (run_id,), = db.execute("SELECT id FROM runs WHERE robot = ? AND checksum = ?",
                                (self.robot, run.checksum)).fetchall()
        bisect.insort(self.runs, (run.time, int(run_id), program, run.source))
        self.checksums.add(run.checksum)
        self.programs.setdefault(program, run.signature)
        self.traces[int(run_id)] = kept.unpack_trace(run.trace)


def _departure(known: _Known, program: str, run: ReadRun) -> tuple[dict[int, float], str, int]:
    references = known.references(program, run.time)
    own = as_recording(*kept.unpack_trace(run.trace), source=run.source)
    return (*departures(own, references), len(references))


def _keep(known: _Known, run: ReadRun) -> Added:
    import json

    program = known.program(run.signature)
    found, note, count = _departure(known, program, run)
    figures = dict(run.figures)
    for axis in {a for a, _ in figures}:
        figures[(axis, "departure")] = found.get(axis, math.nan)
        figures[(axis, REFERENCE_COUNT)] = float(count)
    row = kept.RunRow(known.robot, run.time, run.time_from, program, run.source, run.checksum,
                      units=json.dumps(run.units))
    with kept.open_store(known.store) as db:
        added = kept.add_run(db, row, figures, trace=run.trace,
                             signature=json.dumps(run.signature))
        if added:
            known.added(run, program, db)
    return Added(run.source, added, run.time, run.time_from, program, (*run.notes, note))


def add_runs(paths: Sequence[str | os.PathLike[str]], store: str | os.PathLike[str],
             robot: str, *, channels: str | None = None, axis: int | None = None,
             time: str | None = None, workers: int | None = 0, scheduler: str | None = None,
             progress: Callable[[int, int], None] | None = None) -> list[Added]:
    """Add runs to a robot's history in the store (module notes).

    Parameters
    ----------
    paths : sequence of path-like
        Trace files or log folders.
    store : path-like
        The SQLite store (created when missing).
    robot : str
        The robot they are runs of.
    channels, axis
        As :func:`funcnet.robot.read_trace`.
    time : str, optional
        ISO 8601 time of every run given (default: the file's own, else its modification time).
    workers, scheduler
        Where the runs are read (:class:`funcnet.study.backends.Backend`): 0 workers reads
        them in this process.
    progress : callable, optional
        ``progress(done, total)``.

    Returns
    -------
    list of Added
        In time order; ``added`` False for a run the robot already held (same content).

    Raises
    ------
    ParameterError
        An empty robot name, a bad time, or a store that is no store.


    A run that cannot be read (a :class:`~funcnet.errors.FuncnetError` or an operating-system
    error) is not kept and the others are: its :class:`Added` has ``added`` False, ``error``
    True and the reason as its note.
    """
    from funcnet.study.backends import Backend

    if not robot.strip():
        raise ParameterError.of("robot", "must name the robot")
    if time is not None:
        iso_time(time)
    target = os.fspath(store)
    with kept.open_store(target):
        pass  # created (or refused) before anything is read
    known = _Known.read(target, robot)
    tasks, done = [], []
    for path in (os.fspath(p) for p in paths):
        if os.path.exists(path) and file_sha256(path) in known.checksums:
            done.append(Added(path, False, "", "", "", ("already kept for this robot",)))
        else:
            tasks.append(RunTask(path, channels, axis, time))
    backend: Any = Backend(scheduler, workers)
    with contextlib.closing(backend):
        results = list(backend.map_unordered(_read_or_why, tasks))
    done += [Added(path, False, "", "", "", (why,), error=True)
             for path, why in results if isinstance(why, str)]
    read = sorted((r for _, r in results if isinstance(r, ReadRun)),
                  key=lambda r: (r.time, r.source))
    for k, run in enumerate(read):
        done.append(_keep(known, run))
        if progress is not None:
            progress(k + 1, len(read))
    return done
