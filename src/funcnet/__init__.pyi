"""Type stub of funcnet: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.core.embedding import (
    embed as embed,
    estimate_delay as estimate_delay,
    estimate_dimension as estimate_dimension,
)
from funcnet.core.measures import cross_measures as cross_measures, isrn_measures as isrn_measures
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
from funcnet.pipeline import window_evidence as window_evidence, window_networks as window_networks
from funcnet.report.inspect import inspect_trace as inspect_trace
from funcnet.study.store import load_results as load_results

__version__: str
__all__: list[str]
