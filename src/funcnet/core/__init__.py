"""The numerical core: from sampled signals to the cross measures of every pair (sections 2.1-2.4).

Everything here works on NumPy arrays and :class:`funcnet.parameters.NetworkParameters`; it
knows nothing of robots, files or pages. Data flows down the table:

==================  ==========================================================================
module              what it holds
==================  ==========================================================================
``normalization``   per-window normalization (min-max, z-score; section 3.3)
``embedding``       delay embedding (Eq. 1), delay and dimension estimation
``thresholds``      every threshold search: a block's eps from its rate (the exact order
                    statistic of its distances, no distance matrix), each signal's of a network
``recurrence``      bit-packed auto- and cross-recurrence structures (Eq. 2-5)
``measures``        cross-clustering and cross-transitivity of one pair or many (Eq. 6-10)
``kinds``           the kind of a pair from its asymmetries under mu (section 2.4 [1]_)
``batch``           many windows at once: their pairs' numbers in one compiled pass
``_isrn_kernels``   compiled kernels of the recurrences and the cross measures
``_batch_kernels``  compiled kernels of the batched engine (and of one short pair)
==================  ==========================================================================

What other packages of funcnet may use is named without a leading underscore:
:func:`~funcnet.core.thresholds.signal_thresholds`,
:func:`~funcnet.core.batch.window_ranks`, :func:`~funcnet.core.batch.windows_per_block` and
:func:`~funcnet.core.batch.batch_kernel_for` (the evidence's resamples run on the batched
engine). Names with a leading underscore stay inside this package. Names are imported lazily:
``import funcnet.core`` compiles no kernel.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.

Examples
--------
>>> import numpy as np
>>> from funcnet.core import cross_measures
>>> t = np.linspace(0, 8 * np.pi, 251)
>>> m = cross_measures(np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t))
>>> round(m.achieved_cr, 2)
0.05
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "normalize": "funcnet.core.normalization",
    "embed": "funcnet.core.embedding",
    "estimate_delay": "funcnet.core.embedding",
    "estimate_dimension": "funcnet.core.embedding",
    "signal_thresholds": "funcnet.core.thresholds",
    "auto_recurrence": "funcnet.core.recurrence",
    "cross_recurrence": "funcnet.core.recurrence",
    "isrn_adjacency": "funcnet.core.recurrence",
    "estimate_cost": "funcnet.core.recurrence",
    "isrn_measures": "funcnet.core.measures",
    "cross_measures": "funcnet.core.measures",
    "edge_kind": "funcnet.core.kinds",
    "batch_pairs": "funcnet.core.batch",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
