"""funcnet: functional networks from inter-system recurrence networks.

One node per signal; directed, weighted edges from the asymmetry of cross-clustering and
cross-transitivity between each pair of signals (El Dabett, Hansen & Geier, sections 2-3).
"""

from __future__ import annotations

from funcnet._lazy import attach

__version__ = "0.1.0"

# Public names, resolved lazily so that `import funcnet` stays cheap (no Numba compilation, no
# matplotlib) for the trace reader and the command line.
_EXPORTS = {
    "NetworkParameters": "funcnet.parameters",
    "embed": "funcnet.embedding",
    "signal_states": "funcnet.embedding",
    "estimate_delay": "funcnet.embedding",
    "estimate_dimension": "funcnet.embedding",
    "recurrence_matrix": "funcnet.recurrence",
    "cross_recurrence_matrix": "funcnet.recurrence",
    "isrn_adjacency": "funcnet.recurrence",
    "PackedRecurrence": "funcnet.recurrence",
    "auto_recurrence": "funcnet.recurrence",
    "cross_recurrence": "funcnet.recurrence",
    "CrossMeasures": "funcnet.measures",
    "isrn_measures": "funcnet.measures",
    "cross_measures": "funcnet.measures",
    "pairwise_cross_measures": "funcnet.measures",
    "threshold_warnings": "funcnet.measures",
    "local_cross_clustering": "funcnet.measures",
    "cross_degree": "funcnet.measures",
    "normalize": "funcnet.normalization",
    "FunctionalNetwork": "funcnet.network",
    "functional_network": "funcnet.network",
    "add_evidence": "funcnet.network",
    "edge_kind": "funcnet.network",
    "combine_kinds": "funcnet.network",
    "edges_from_pairs": "funcnet.network",
    "check_parameters": "funcnet.network",
    "edge_stability": "funcnet.network",
    "window_networks": "funcnet.pipeline",
    "window_evidence": "funcnet.pipeline",
    "repetition_evidence": "funcnet.evidence.repetitions",
    "inspect_trace": "funcnet.report.inspect",
    "Study": "funcnet.study",
    "load_study": "funcnet.study",
    "run_study": "funcnet.study",
    "load_results": "funcnet.study",
    "FuncnetError": "funcnet.errors",
    "ParameterError": "funcnet.errors",
    "SignalError": "funcnet.errors",
    "TraceError": "funcnet.errors",
    "FuncnetWarning": "funcnet.errors",
    "ThresholdWarning": "funcnet.errors",
    "DegenerateWarning": "funcnet.errors",
    "StaircaseWarning": "funcnet.errors",
    "RecordingWarning": "funcnet.errors",
}

__getattr__, _dir, _names = attach(__name__, _EXPORTS)
__all__ = ["__version__", *_names]


def __dir__() -> list[str]:
    return sorted(__all__)
