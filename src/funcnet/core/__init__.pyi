"""Type stub of funcnet.core: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.core.batch import batch_pairs as batch_pairs
from funcnet.core.embedding import (
    embed as embed,
    estimate_delay as estimate_delay,
    estimate_dimension as estimate_dimension,
)
from funcnet.core.kinds import edge_kind as edge_kind
from funcnet.core.measures import cross_measures as cross_measures, isrn_measures as isrn_measures
from funcnet.core.normalization import normalize as normalize
from funcnet.core.recurrence import (
    auto_recurrence as auto_recurrence,
    cross_recurrence as cross_recurrence,
    estimate_cost as estimate_cost,
    isrn_adjacency as isrn_adjacency,
)
from funcnet.core.thresholds import signal_thresholds as signal_thresholds

__all__: list[str]
