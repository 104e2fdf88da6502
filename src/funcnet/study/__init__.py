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

from funcnet._lazy import attach

_EXPORTS = {
    "PARAMETER_COLUMNS": "funcnet.study.store",
    "WINDOW_KINDS": "funcnet.study.spec",
    "Study": "funcnet.study.spec",
    "StudyResult": "funcnet.study.run",
    "TaskFailure": "funcnet.study.run",
    "WindowSpec": "funcnet.study.spec",
    "package_versions": "funcnet.study.provenance",
    "load_results": "funcnet.study.store",
    "network_from_rows": "funcnet.study.store",
    "load_study": "funcnet.study.spec",
    "parameter_grid": "funcnet.study.spec",
    "run_study": "funcnet.study.run",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
