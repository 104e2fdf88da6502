"""Studies: many recordings x analysis windows x network parameters, run as independent tasks.

A study names recordings (trace files, glob patterns, or the simulated plan of experiments),
analysis windows (detected phases, fixed windows anchored at phase starts, windows around a
reversal, sliding windows, explicit time ranges) and network parameters, each of which may be a
list: the lists span a grid of :class:`~funcnet.parameters.NetworkParameters`.
:func:`run_study` computes one functional network per (recording, window, parameter set) -- a
*task* -- on local processes or on a Dask cluster (the ``dask`` extra), and writes the pairs
table of every network as Parquet rows.

Modules, in the order the data flows through them:

* :mod:`~funcnet.study.spec` -- the TOML file -> a frozen :class:`Study`, checked on reading;
* :mod:`~funcnet.study.sources` -- recordings and simulated plans;
* :mod:`~funcnet.study.tasks` -- tasks, content keys, what a worker computes;
* :mod:`~funcnet.study.backends` -- this process, local processes, Dask;
* :mod:`~funcnet.study.store` -- the results folder: lock, Parquet rows, :func:`load_results`;
* :mod:`~funcnet.study.provenance` -- versions and input hashes;
* :mod:`~funcnet.study.run` -- :func:`run_study`.
"""

from __future__ import annotations

from typing import Any

from funcnet.study.provenance import package_versions
from funcnet.study.run import StudyResult, TaskFailure, run_study
from funcnet.study.spec import WINDOW_KINDS, Study, WindowSpec, load_study, parameter_grid
from funcnet.study.store import PARAMETER_COLUMNS, load_results, network_from_rows

__all__ = [
    "PARAMETER_COLUMNS",
    "WINDOW_KINDS",
    "Study",
    "StudyResult",
    "TaskFailure",
    "WindowSpec",
    "package_versions",
    "load_results",
    "network_from_rows",
    "load_study",
    "parameter_grid",
    "run_study",
]


def __getattr__(name: str) -> Any:
    # read_recording moved to funcnet.robot; kept importable from here for existing callers.
    if name == "read_recording":
        from funcnet.robot import read_recording

        return read_recording
    raise AttributeError(f"module 'funcnet.study' has no attribute {name!r}")
