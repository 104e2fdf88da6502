"""The store of a fleet's runs: one SQLite file, every run kept with its per-axis figures.

Why SQLite: it is in the standard library, one file holds the whole fleet, and in WAL mode
(write-ahead log) readers never block the writer and several processes may write one after the
other: each waits for the lock up to :data:`BUSY_TIMEOUT` seconds (the busy timeout) instead of
failing. A run is written in one transaction (``BEGIN IMMEDIATE``: the write lock is taken before
anything is read for it), so two ``track add`` at once both land, and a process killed mid-write
leaves the store as it was before that run. (DuckDB would allow one writing process at a time.)

A run is recognised by its content: ``UNIQUE(robot, checksum)``, the SHA-256 of its file (of a
log folder's files, :func:`funcnet._io.file_sha256`). The same run added twice to one robot is
kept once; the same file added to two robots is two runs.

Tables: ``runs`` (robot, time, how the time was found, program, source, checksum, page),
``figures`` (run, axis, figure, value), ``programs`` (robot, program, its signature as JSON) and
``traces`` (run, the signals its later runs are compared with, compressed).

Examples
--------
>>> import tempfile, os
>>> path = os.path.join(tempfile.mkdtemp(), "fleet.sqlite")
>>> with open_store(path) as db:
...     new = add_run(db, RunRow("r1", "2026-01-05T08:00:00", "given", "P-1", "a.csv", "ab"),
...                   {(1, "lost_motion"): 0.5})
...     again = add_run(db, RunRow("r1", "2026-01-06T08:00:00", "given", "P-1", "b.csv", "ab"),
...                     {(1, "lost_motion"): 0.6})
>>> new, again, len(read_runs(path))
(True, False, 1)
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sqlite3
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError

__all__ = ["BUSY_TIMEOUT", "RunRow", "open_store", "add_run", "read_runs", "read_figures",
           "read_programs", "read_traces", "pack_trace", "unpack_trace", "robots"]

#: Seconds a writer waits for another's transaction before giving up.
BUSY_TIMEOUT = 120.0

_SCHEMA = """
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY,
    robot TEXT NOT NULL,
    time TEXT NOT NULL,
    time_from TEXT NOT NULL,
    program TEXT NOT NULL,
    source TEXT NOT NULL,
    checksum TEXT NOT NULL,
    page TEXT,
    units TEXT,
    UNIQUE (robot, checksum)
);
CREATE INDEX IF NOT EXISTS runs_by_robot ON runs (robot, time);
CREATE TABLE IF NOT EXISTS figures (
    run INTEGER NOT NULL REFERENCES runs (id),
    axis INTEGER NOT NULL,
    figure TEXT NOT NULL,
    value REAL,
    PRIMARY KEY (run, axis, figure)
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS programs (
    robot TEXT NOT NULL,
    program TEXT NOT NULL,
    signature TEXT NOT NULL,
    PRIMARY KEY (robot, program)
);
CREATE TABLE IF NOT EXISTS traces (
    run INTEGER PRIMARY KEY REFERENCES runs (id),
    data BLOB NOT NULL
);
"""


@dataclass(frozen=True)
class RunRow:
    """One run as the store keeps it.

    Attributes
    ----------
    robot : str
    time : str
        ISO 8601.
    time_from : str
        Where the time came from: ``given`` (``--time``), ``file`` (the file's own start time)
        or ``mtime`` (the file's modification time).
    program : str
        The program's identity (:func:`funcnet.track.program.program_signature`).
    source : str
        The path the run was read from.
    checksum : str
        SHA-256 of its content.
    page : str or None
        A page of the run (its ``inspect`` report), when known.
    units : str or None
        JSON: figure -> unit, for the figures whose unit is the recording's (the current's).
    """

    robot: str
    time: str
    time_from: str
    program: str
    source: str
    checksum: str
    page: str | None = None
    units: str | None = None


@contextlib.contextmanager
def open_store(path: str | os.PathLike[str], *, create: bool = True
               ) -> Iterator[sqlite3.Connection]:
    """The store at ``path`` (created when missing and ``create``), in WAL mode; closed after.

    Raises
    ------
    ParameterError
        ``path`` is missing (and not to be created) or is no SQLite store.
    """
    if not create and not os.path.isfile(path):
        raise ParameterError.of("store", f"{os.fspath(path)}: no such store")
    if create:
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    try:
        # isolation_level None: transactions are begun explicitly (BEGIN IMMEDIATE).
        db = sqlite3.connect(os.fspath(path), timeout=BUSY_TIMEOUT, isolation_level=None)
    except sqlite3.Error as error:
        raise ParameterError.of("store", f"{os.fspath(path)}: cannot open ({error})") from None
    try:
        try:
            db.execute("PRAGMA journal_mode=WAL")
            db.execute("PRAGMA synchronous=NORMAL")  # WAL: durable at checkpoints, never torn
            db.executescript(f"BEGIN IMMEDIATE;{_SCHEMA}COMMIT;")
        except sqlite3.DatabaseError as error:
            raise ParameterError.of("store", f"{os.fspath(path)}: not a funcnet store "
                                    f"({error})") from None
        yield db
    finally:
        db.close()


def pack_trace(data: pd.DataFrame, period: float) -> bytes:
    """The signals later runs are compared with, as compressed bytes (:func:`unpack_trace`)."""
    buffer = io.BytesIO()
    np.savez_compressed(buffer, values=data.to_numpy(dtype=np.float64),
                        columns=np.array(list(data.columns)), period=np.float64(period),
                        t0=np.float64(data.index[0] if len(data) else 0.0))
    return buffer.getvalue()


def unpack_trace(blob: bytes) -> tuple[pd.DataFrame, float]:
    """``(data, period)`` of :func:`pack_trace`'s bytes."""
    with np.load(io.BytesIO(blob)) as saved:
        values, columns = saved["values"], [str(c) for c in saved["columns"]]
        period, t0 = float(saved["period"]), float(saved["t0"])
    index = pd.Index(np.round(t0 + np.arange(len(values)) * period, 9), name="time")
    return pd.DataFrame(values, columns=columns, index=index), period


def add_run(db: sqlite3.Connection, row: RunRow,
            figures: Mapping[tuple[int, str], float | None], *, trace: bytes | None = None,
            signature: str | None = None) -> bool:
    """Write one run, its figures, its trace and its program, in one transaction.

    Returns
    -------
    bool
        False when the robot already holds a run of this content (nothing written).
    """
    db.execute("BEGIN IMMEDIATE")
    try:
        cursor = db.execute(
            "INSERT OR IGNORE INTO runs (robot, time, time_from, program, source, checksum, page,"
            " units) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
            (row.robot, row.time, row.time_from, row.program, row.source, row.checksum,
             row.page, row.units))
        if cursor.rowcount == 0:
            db.execute("ROLLBACK")
            return False
        run = cursor.lastrowid
        db.executemany("INSERT INTO figures VALUES (?, ?, ?, ?)",
                       [(run, axis, name, _finite(value))
                        for (axis, name), value in figures.items()])
        if trace is not None:
            db.execute("INSERT INTO traces VALUES (?, ?)", (run, trace))
        if signature is not None:
            db.execute("INSERT OR IGNORE INTO programs VALUES (?, ?, ?)",
                       (row.robot, row.program, signature))
        db.execute("COMMIT")
    except BaseException:
        db.execute("ROLLBACK")
        raise
    return True


def _finite(value: float | None) -> float | None:
    return None if value is None or not np.isfinite(value) else float(value)


def _read(path: str | os.PathLike[str], query: str, args: tuple[object, ...]) -> pd.DataFrame:
    with open_store(path, create=False) as db:
        cursor = db.execute(query, args)
        names = [d[0] for d in cursor.description]
        return pd.DataFrame(cursor.fetchall(), columns=names)


def read_runs(path: str | os.PathLike[str], robot: str | None = None) -> pd.DataFrame:
    """Every run kept (of ``robot``), in time order: id, robot, time, time_from, program,
    source, checksum, page, units."""
    where = "WHERE robot = ?" if robot is not None else ""
    return _read(path, f"SELECT * FROM runs {where} ORDER BY robot, time, id",
                 (robot,) if robot is not None else ())


def read_figures(path: str | os.PathLike[str], robot: str | None = None) -> pd.DataFrame:
    """The figures of every run (of ``robot``): run, axis, figure, value (NaN: not read)."""
    if robot is None:
        return _read(path, "SELECT run, axis, figure, value FROM figures", ())
    return _read(path, "SELECT f.run, f.axis, f.figure, f.value FROM figures f JOIN runs r "
                 "ON f.run = r.id WHERE r.robot = ?", (robot,)).astype({"value": float})


def read_programs(path: str | os.PathLike[str], robot: str) -> dict[str, list[list[float]]]:
    """The programs a robot has run: program -> its signature."""
    table = _read(path, "SELECT program, signature FROM programs WHERE robot = ?", (robot,))
    return {str(p): json.loads(s) for p, s in zip(table["program"], table["signature"],
                                                   strict=True)}


def read_traces(path: str | os.PathLike[str], runs: list[int]
                ) -> dict[int, tuple[pd.DataFrame, float]]:
    """The kept traces of ``runs`` (those that have one)."""
    if not runs:
        return {}
    marks = ", ".join("?" * len(runs))
    table = _read(path, f"SELECT run, data FROM traces WHERE run IN ({marks})", tuple(runs))
    return {int(r): unpack_trace(b) for r, b in zip(table["run"], table["data"], strict=True)}


def robots(path: str | os.PathLike[str]) -> list[str]:
    """The robots of the store, sorted."""
    return sorted(_read(path, "SELECT DISTINCT robot FROM runs", ())["robot"].astype(str))
