"""A robot's health over weeks: every run kept, its figures trended, an alarm when it changes.

:mod:`~funcnet.track.store` keeps a fleet's runs in one SQLite file (WAL mode, one transaction
per run, a run recognised by its content); :mod:`~funcnet.track.program` tells which program a
run is a run of; :mod:`~funcnet.track.figures` reads each axis's health figures from what the
backlash, inspect and compare code computes; :mod:`~funcnet.track.add` adds runs
(:func:`add_runs`, on local processes or a Dask cluster); :mod:`~funcnet.track.detect` is the
change detector (a self-starting CUSUM per figure, :func:`detect_changes`) and
:mod:`~funcnet.track.trend` judges a robot's history with it (:func:`robot_trends`). The page
is :mod:`funcnet.report.track_page`. Names are imported lazily.

Examples
--------
>>> from funcnet.track import LEVEL
>>> LEVEL
5.0
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "open_store": "funcnet.track.store",
    "read_runs": "funcnet.track.store",
    "read_figures": "funcnet.track.store",
    "FIGURES": "funcnet.track.figures",
    "axis_figures": "funcnet.track.figures",
    "program_signature": "funcnet.track.program",
    "same_program": "funcnet.track.program",
    "add_runs": "funcnet.track.add",
    "read_run": "funcnet.track.add",
    "Added": "funcnet.track.add",
    "detect_changes": "funcnet.track.detect",
    "Detection": "funcnet.track.detect",
    "LEVEL": "funcnet.track.detect",
    "DRIFT": "funcnet.track.detect",
    "LEARN": "funcnet.track.detect",
    "Trends": "funcnet.track.trend",
    "robot_trends": "funcnet.track.trend",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
