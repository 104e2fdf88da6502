"""funcnet: functional networks from inter-system recurrence networks.

One node per signal; directed, weighted edges from the asymmetry of cross-clustering and
cross-transitivity between each pair of signals (El Dabett, Hansen & Geier, sections 2-3).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

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




if TYPE_CHECKING:  # what the lazy table exports, for type checkers and editors
    from funcnet.core.embedding import (
        embed as embed,
        estimate_delay as estimate_delay,
        estimate_dimension as estimate_dimension,
    )
    from funcnet.core.measures import (
        cross_measures as cross_measures,
        isrn_measures as isrn_measures,
    )
    from funcnet.core.normalization import normalize as normalize
    from funcnet.core.recurrence import (
        auto_recurrence as auto_recurrence,
        cross_recurrence as cross_recurrence,
    )
    from funcnet.errors import (
        DegenerateWarning as DegenerateWarning,
        FuncnetError as FuncnetError,
        FuncnetWarning as FuncnetWarning,
        ParameterError as ParameterError,
        RecordingWarning as RecordingWarning,
        StaircaseWarning as StaircaseWarning,
        ThresholdWarning as ThresholdWarning,
    )
    from funcnet.evidence.repetitions import repetition_evidence as repetition_evidence
    from funcnet.network.edge_evidence import add_evidence as add_evidence
    from funcnet.network.functional import (
        FunctionalNetwork as FunctionalNetwork,
        functional_network as functional_network,
    )
    from funcnet.network.stability import edge_stability as edge_stability
    from funcnet.parameters import NetworkParameters as NetworkParameters
    from funcnet.pipeline import (
        window_evidence as window_evidence,
        window_networks as window_networks,
    )
    from funcnet.report.inspect import inspect_trace as inspect_trace
    from funcnet.study.store import load_results as load_results

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS, defined=["__version__"])
