"""funcnet: functional networks from inter-system recurrence networks.

One node per signal; directed, weighted edges from the asymmetry of cross-clustering and
cross-transitivity between each pair of signals (El Dabett, Hansen & Geier, sections 2-3).
"""

from __future__ import annotations

from funcnet._lazy import attach

__version__ = "0.1.0"

# Public names, resolved lazily so that `import funcnet` stays cheap (no Numba compilation, no
# matplotlib) for the trace reader and the command line. What the README and the docs teach;
# everything else is imported from its module (funcnet.core.recurrence.isrn_adjacency, ...).
_EXPORTS = {
    "NetworkParameters": "funcnet.parameters",
    "normalize": "funcnet.core.normalization",
    "embed": "funcnet.core.embedding",
    "estimate_delay": "funcnet.core.embedding",
    "estimate_dimension": "funcnet.core.embedding",
    "auto_recurrence": "funcnet.core.recurrence",
    "cross_recurrence": "funcnet.core.recurrence",
    "isrn_measures": "funcnet.core.measures",
    "cross_measures": "funcnet.core.measures",
    "FunctionalNetwork": "funcnet.network.functional",
    "functional_network": "funcnet.network.functional",
    "add_evidence": "funcnet.network.edge_evidence",
    "edge_stability": "funcnet.network.stability",
    "window_networks": "funcnet.pipeline",
    "window_evidence": "funcnet.pipeline",
    "repetition_evidence": "funcnet.evidence.repetitions",
    "inspect_trace": "funcnet.report.inspect",
    "load_results": "funcnet.study.store",
    "FuncnetError": "funcnet.errors",
    "ParameterError": "funcnet.errors",
    "FuncnetWarning": "funcnet.errors",
    "ThresholdWarning": "funcnet.errors",
    "DegenerateWarning": "funcnet.errors",
    "StaircaseWarning": "funcnet.errors",
    "RecordingWarning": "funcnet.errors",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS, defined=["__version__"])
