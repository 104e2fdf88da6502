"""A study's results folder: its lock, the Parquet rows of each task, failures, the cache.

Layout of a results folder ``out_dir``::

    rows/<key>.parquet     one file per finished task: one row per pair of signals
    failed/<key>.json      a task whose data could not be analysed (message kept, not retried)
    windows/<key>.json     the windows a window specification gave on a recording (cached)
    cache/                 finished tasks of earlier runs that the current study does not name
    study.json             the study, provenance (versions, input hashes, command), run counts

A row is the task's identity (:data:`IDENTITY_SCHEMA`), its parameter set (one column per
network parameter, :data:`PARAMETER_COLUMNS`) and the pairs table's columns, in the order and
types of :mod:`funcnet.network.schema` (with a study's ``[evidence]``, its evidence columns; with
``[stability]``, ``stability`` and the ``stability_*`` columns of
:func:`funcnet.network.stability.edge_stability`). Decisions:

* The target rates keep their parameter names, ``rr`` and ``cr`` (the pairs table names what
  was achieved ``achieved_rr_x``, ``achieved_rr_y``, ``achieved_cr``); the edge policy
  ``degenerate`` is the column ``degenerate_policy``, since ``degenerate`` is the pair's flag.
* ``eps`` (a pair ``(auto, cross)``) is its JSON text (``[0.2, null]``), null without
  thresholds; ``mu_c``, ``mu_t`` and ``normalize`` are null when None. Every parameter column
  has one type in every file, so the rows read as one data set.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from funcnet._io import atomic_path, write_text_atomic
from funcnet.errors import StudyError
from funcnet.parameters import NetworkParameters

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = [
    "IDENTITY_SCHEMA",
    "PARAMETER_COLUMNS",
    "FOLDERS",
    "exclusive",
    "prepare",
    "rows_table",
    "write_rows",
    "write_failure",
    "done",
    "select_current",
    "load_results",
    "network_from_rows",
]

#: The columns that say which task a row belongs to.
IDENTITY_SCHEMA = pa.schema(
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
    ]
)

# The pairs table has a boolean ``degenerate`` column; the policy of the same name is renamed.
_RENAMED = {"degenerate": "degenerate_policy"}

#: The results' column of each network parameter: its name, except ``degenerate`` (the policy)
#: which is ``degenerate_policy`` since the pairs table's ``degenerate`` is the pair's flag.
PARAMETER_COLUMNS: dict[str, str] = {
    name: _RENAMED.get(name, name) for name in NetworkParameters.names()
}

# Arrow type of each parameter's column; a parameter not listed (or a value that is not a
# scalar, such as ``eps``) is stored as its JSON text.
_PARAMETER_TYPES: dict[str, pa.DataType] = {
    **dict.fromkeys(("dim", "delay", "theiler"), pa.int64()),
    **dict.fromkeys(("rr", "cr", "mu", "mu_c", "mu_t"), pa.float64()),
    **dict.fromkeys(("metric", "rule", "normalize", "measure", "degenerate"), pa.string()),
}

#: The folders of a results folder.
FOLDERS = ("rows", "failed", "windows", "cache")


def _pairs_schema(evidence: bool = False) -> pa.Schema:
    """The pairs table's columns as an Arrow schema, from :mod:`funcnet.network.schema` (with
    ``evidence``, its evidence columns too)."""
    from funcnet.network.schema import EVIDENCE_DTYPES, PAIR_DTYPES

    fields = []
    dtypes = {**PAIR_DTYPES, **(EVIDENCE_DTYPES if evidence else {})}
    for name, dtype in dtypes.items():
        kind = pd.api.types.pandas_dtype(dtype)
        if pd.api.types.is_bool_dtype(kind):
            fields.append((name, pa.bool_()))
        elif pd.api.types.is_float_dtype(kind):
            fields.append((name, pa.float64()))
        elif pd.api.types.is_integer_dtype(kind):
            fields.append((name, pa.int64()))
        else:
            fields.append((name, pa.string()))
    return pa.schema(fields)


def _parameter_value(name: str, value: Any) -> Any:
    if name in _PARAMETER_TYPES or value is None:
        return value
    return json.dumps(value)


def rows_table(identity: Mapping[str, Any], parameters: NetworkParameters,
               pairs: pd.DataFrame) -> pa.Table:
    """One task's rows: its identity and parameters repeated on every pair of its network.

    Parameters
    ----------
    identity : mapping
        A value per column of :data:`IDENTITY_SCHEMA`.
    parameters : NetworkParameters
        The task's parameter set (columns :data:`PARAMETER_COLUMNS`).
    pairs : DataFrame
        The network's pairs table.

    Returns
    -------
    pyarrow.Table
        Plain (no pandas metadata): every reader sees the same columns and types.
    """
    n = len(pairs)
    columns: dict[str, pa.Array] = {
        field.name: pa.array([identity[field.name]] * n, type=field.type)
        for field in IDENTITY_SCHEMA
    }
    for name, value in parameters.to_dict().items():
        kind = _PARAMETER_TYPES.get(name, pa.string())
        columns[PARAMETER_COLUMNS[name]] = pa.array([_parameter_value(name, value)] * n,
                                                    type=kind)
    schema = _pairs_schema(evidence="evidence" in pairs.columns)
    # Columns beyond the schema (a study's stability columns) follow, typed by pandas.
    extra = [c for c in pairs.columns if c not in schema.names]
    table = pa.Table.from_pandas(pairs.reset_index(drop=True)[[*schema.names, *extra]],
                                 preserve_index=False)
    table = table.cast(pa.schema([*schema, *(table.schema.field(c) for c in extra)]))
    for name, column in zip(table.column_names, table.columns, strict=True):
        columns[name] = column
    return pa.table(columns).replace_schema_metadata(None)


def prepare(out: Path) -> dict[str, Path]:
    """Create the folders of ``out`` and remove the temporary files of a killed run.

    Parameters
    ----------
    out : Path
        The results folder (it exists).

    Returns
    -------
    dict
        Folder name (:data:`FOLDERS`) -> path.
    """
    dirs = {name: out / name for name in FOLDERS}
    for folder in dirs.values():
        folder.mkdir(exist_ok=True)
        for leftover in folder.glob(".*.tmp"):
            leftover.unlink(missing_ok=True)
    return dirs


@contextlib.contextmanager
def exclusive(out: Path) -> Iterator[None]:
    """Hold ``out/.lock`` for the duration.

    Parameters
    ----------
    out : Path
        The results folder.

    Yields
    ------
    None

    Raises
    ------
    StudyError
        Another process (or this one) holds the lock.
    """
    # The operating system drops the lock when its holder dies, even by SIGKILL.
    with open(out / ".lock", "a") as fh:
        try:
            unlock = _lock(fh)
        except BlockingIOError:
            raise StudyError(f"{out}: another study run is using this folder") from None
        try:
            yield
        finally:
            unlock()


def _lock(fh: Any) -> Any:
    """Lock the open file ``fh`` without waiting; return the function that unlocks it.

    POSIX: an advisory ``flock``. Windows (no :mod:`fcntl`): ``msvcrt.locking`` of the file's
    first byte. Raises :class:`BlockingIOError` when another holds the lock.
    """
    try:
        import fcntl
    except ImportError:
        fcntl = None  # type: ignore[assignment]
    if fcntl is not None:
        fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return lambda: fcntl.flock(fh, fcntl.LOCK_UN)
    import msvcrt

    fh.seek(0)
    try:
        msvcrt.locking(fh.fileno(), msvcrt.LK_NBLCK, 1)  # type: ignore[attr-defined]
    except OSError as exc:  # Windows reports a held lock as a permission error
        raise BlockingIOError(str(exc)) from None

    def unlock() -> None:
        fh.seek(0)
        msvcrt.locking(fh.fileno(), msvcrt.LK_UNLCK, 1)  # type: ignore[attr-defined]

    return unlock


def done(dirs: Mapping[str, Path], key: str) -> bool:
    """Whether the task ``key`` has its rows or its failure on file.

    Parameters
    ----------
    dirs : mapping
        As :func:`prepare` returns.
    key : str
        A task's key.

    Returns
    -------
    bool
    """
    return (dirs["rows"] / f"{key}.parquet").exists() or (dirs["failed"] / f"{key}.json").exists()


def write_rows(dirs: Mapping[str, Path], key: str, table: pa.Table) -> None:
    """Write a task's rows to ``rows/<key>.parquet``, whole or not at all.

    Parameters
    ----------
    dirs : mapping
        As :func:`prepare` returns.
    key : str
        The task's key.
    table : pyarrow.Table
        As :func:`rows_table` returns.
    """
    with atomic_path(dirs["rows"] / f"{key}.parquet") as tmp:
        pq.write_table(table, tmp)


def write_failure(dirs: Mapping[str, Path], key: str, record: Mapping[str, Any]) -> None:
    """Record a task that could not be analysed in ``failed/<key>.json`` (not retried).

    Parameters
    ----------
    dirs : mapping
        As :func:`prepare` returns.
    key : str
        The task's key.
    record : mapping
        ``recording``, ``window``, ``parameters``, ``message`` (JSON-compatible).
    """
    write_text_atomic(dirs["failed"] / f"{key}.json", json.dumps(record))


def read_failure(dirs: Mapping[str, Path], key: str) -> dict[str, Any] | None:
    """The failure record of task ``key``, or None.

    Parameters
    ----------
    dirs : mapping
        As :func:`prepare` returns.
    key : str
        A task's key.

    Returns
    -------
    dict or None
        As written by :func:`write_failure`.
    """
    path = dirs["failed"] / f"{key}.json"
    return json.loads(path.read_text()) if path.exists() else None


def select_current(dirs: Mapping[str, Path], keys: set[str]) -> None:
    """Make ``rows/`` and ``failed/`` hold exactly the study's finished tasks.

    Tasks of other studies move to ``cache/``; the study's tasks found there move back.

    Parameters
    ----------
    dirs : mapping
        As :func:`prepare` returns.
    keys : set of str
        The keys of the study's tasks.
    """
    for kind, suffix in (("rows", ".parquet"), ("failed", ".json")):
        for path in dirs[kind].glob(f"*{suffix}"):
            if path.name[: -len(suffix)] not in keys:
                os.replace(path, dirs["cache"] / path.name)
        for key in keys:
            kept = dirs["cache"] / f"{key}{suffix}"
            if kept.exists():
                os.replace(kept, dirs[kind] / kept.name)


def load_results(out_dir: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the rows of a study's results folder into one DataFrame.

    The rows are plain Parquet files in ``out_dir/rows``; other tools read them directly (for
    example DuckDB: ``SELECT * FROM 'out/rows/*.parquet'``, polars:
    ``pl.read_parquet('out/rows/*.parquet')``).

    Parameters
    ----------
    out_dir : path-like
        A folder written by :func:`funcnet.study.run_study`.

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

    Examples
    --------
    >>> import tempfile
    >>> load_results(tempfile.mkdtemp())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    funcnet.errors.StudyError: ...: no study results (no rows/*.parquet)
    """
    rows = Path(out_dir) / "rows"
    files = sorted(rows.glob("*.parquet")) if rows.is_dir() else []
    if not files:
        raise StudyError(f"{Path(out_dir)}: no study results (no rows/*.parquet)")
    tables = [pq.read_table(f) for f in files]
    frame = pa.concat_tables(tables, promote_options="default").to_pandas()
    # Within one task the rows keep the pairs table's order (a stable sort of whole files).
    order = ["recording", "start", "stop", "window", "signals",
             *(c for c in PARAMETER_COLUMNS.values() if c in frame.columns)]
    return frame.sort_values(order, na_position="first", kind="stable").reset_index(drop=True)


def network_from_rows(rows: pd.DataFrame) -> FunctionalNetwork:
    """The functional network of one task's rows (one recording, window and parameter set).

    The inverse of :func:`rows_table`, so that what draws and evaluates networks takes a
    study's results as networks.

    Parameters
    ----------
    rows : pandas.DataFrame
        The rows of one task, as :func:`load_results` returns them (one per pair).

    Returns
    -------
    FunctionalNetwork
        Its nodes (the ``signals`` column), its parameters (:data:`PARAMETER_COLUMNS`; a column
        missing from older results takes its default), its pairs table (the rows without the
        identity and parameter columns; ``degenerate`` False where older rows hold none), its
        edges under its own ``degenerate`` policy, labelled by the window, whose record
        (label, start, stop, phase, offset, source, dropped) it keeps. The rows do not record
        the window's length: ``n_samples`` is 0. With evidence columns, ``evidence`` is an
        empty mapping (the settings are the study's, not the rows').

    Examples
    --------
    >>> from funcnet.network import functional_network
    >>> from funcnet.validation.systems import henon_pair
    >>> net = functional_network(henon_pair(300, 0.6, seed=0), names=["x", "y"], delay=1,
    ...                          warn=False)
    >>> identity = {"recording": "r.csv", "trial": "", "source_sha256": "", "window": "w",
    ...             "phase": None, "offset": 0.0, "start": 0.0, "stop": 0.6, "signals": "x,y",
    ...             "constant": "error", "dropped": ""}
    >>> rows = rows_table(identity, net.parameters, net.pairs).to_pandas()
    >>> again = network_from_rows(rows)
    >>> again.parameters == net.parameters, again.pairs.equals(net.pairs)
    (True, True)
    >>> again.edges.equals(net.edges), again.nodes, again.label
    (True, ('x', 'y'), 'w')
    """
    from funcnet.network import FunctionalNetwork

    first = rows.iloc[0]
    values = {}
    for name, column in PARAMETER_COLUMNS.items():
        if column not in rows.columns:
            continue
        value = first[column]
        value = value.item() if hasattr(value, "item") else value
        if value is None or (isinstance(value, float) and math.isnan(value)):
            value = None
        elif name not in _PARAMETER_TYPES:
            value = json.loads(value)
        values[name] = value
    parameters = NetworkParameters.from_mapping(values)
    known = {field.name for field in IDENTITY_SCHEMA} | set(PARAMETER_COLUMNS.values())
    pairs = rows[[c for c in rows.columns if c not in known]].reset_index(drop=True)
    signals = str(first.get("signals") or "")
    dropped = str(first.get("dropped") or "")
    window = {"label": first.get("window"), "start": first.get("start"),
              "stop": first.get("stop"), "phase": first.get("phase"),
              "offset": first.get("offset"), "source": first.get("recording"),
              "dropped": tuple(dropped.split(",")) if dropped else ()}
    network = FunctionalNetwork.from_pairs(
        pairs, parameters, nodes=tuple(signals.split(",")) if signals else None,
        label=first.get("window"), window=window)
    return replace(network, evidence={}) if "evidence" in pairs.columns else network
