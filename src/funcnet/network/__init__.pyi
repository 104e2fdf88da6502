"""Type stub of funcnet.network: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.network.direction import (
    DIRECTIONS as DIRECTIONS,
    read_direction as read_direction,
)
from funcnet.network.edge_evidence import add_evidence as add_evidence
from funcnet.network.functional import (
    FunctionalNetwork as FunctionalNetwork,
    functional_network as functional_network,
)
from funcnet.network.rule import (
    combine_kinds as combine_kinds,
    edge_kind as edge_kind,
    edges_from_pairs as edges_from_pairs,
    kinds_for as kinds_for,
    pair_kinds as pair_kinds,
)
from funcnet.network.schema import (
    DIRECTION_COLUMNS as DIRECTION_COLUMNS,
    EDGE_COLUMNS as EDGE_COLUMNS,
    EDGE_KINDS as EDGE_KINDS,
    EVIDENCE_COLUMNS as EVIDENCE_COLUMNS,
    EVIDENCE_LABELS as EVIDENCE_LABELS,
    MEASURE_KINDS as MEASURE_KINDS,
    PAIR_COLUMNS as PAIR_COLUMNS,
    PAIR_KINDS as PAIR_KINDS,
)
from funcnet.network.setpoint import (
    SetpointCheck as SetpointCheck,
    setpoint_check as setpoint_check,
)
from funcnet.network.stability import (
    EdgeStability as EdgeStability,
    edge_stability as edge_stability,
)
from funcnet.parameters import MEASURES as MEASURES

__all__: list[str]
