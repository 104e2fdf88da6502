"""Comparison of a run of a program with earlier runs of it: what changed, and when.

:mod:`~funcnet.comparison.align` aligns the runs on their position set-points cycle by cycle;
:mod:`~funcnet.comparison.band` learns from the references how much runs of the program differ
(per signal, per axis, along the program) and finds where RUN departs beyond that;
:mod:`~funcnet.comparison.networks` does the same with the functional networks' measures over
sliding windows; :mod:`~funcnet.comparison.compare` puts them together
(:func:`compare_runs`, a :class:`Comparison`). Names are imported lazily.
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "Alignment": "funcnet.comparison.align",
    "align_on_setpoints": "funcnet.comparison.align",
    "Band": "funcnet.comparison.band",
    "reference_band": "funcnet.comparison.band",
    "Interval": "funcnet.comparison.intervals",
    "Difference": "funcnet.comparison.intervals",
    "find_intervals": "funcnet.comparison.intervals",
    "NetworkComparison": "funcnet.comparison.networks",
    "compare_networks": "funcnet.comparison.networks",
    "Comparison": "funcnet.comparison.compare",
    "compare_runs": "funcnet.comparison.compare",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
