"""Functional networks: the edge rule, the network as data, its readers and writers.

=================  ==========================================================================
module             what it holds
=================  ==========================================================================
``schema``         the one pairs-table and edges-table schema, the kind vocabulary
``rule``           the edge rule as pure functions of a pairs table (section 2.4, Eq. 10, 13)
``functional``     :class:`FunctionalNetwork` and :func:`functional_network`
``edge_evidence``  :func:`add_evidence`: the evidence columns of a network already computed
``readwrite``      JSON, GraphML, networkx
``stability``      :func:`edge_stability`: how many settings of a grid keep each pair's kind
=================  ==========================================================================

``functional_network(..., evidence=True)`` adds the evidence columns of :mod:`funcnet.evidence`
(dependence test, intervals, direction, each pair's reading; :data:`EVIDENCE_COLUMNS`).

Examples
--------
>>> from funcnet.network import PAIR_KINDS, EDGE_KINDS
>>> PAIR_KINDS, EDGE_KINDS
(('x->y', 'y->x', 'bidirectional', 'conflict'), ('directed', 'bidirectional'))
"""


from __future__ import annotations

from typing import TYPE_CHECKING

from funcnet._lazy import attach

_EXPORTS = {
    "MEASURES": "funcnet.parameters",
    "PAIR_KINDS": "funcnet.network.schema",
    "MEASURE_KINDS": "funcnet.network.schema",
    "EDGE_KINDS": "funcnet.network.schema",
    "PAIR_COLUMNS": "funcnet.network.schema",
    "EDGE_COLUMNS": "funcnet.network.schema",
    "EVIDENCE_COLUMNS": "funcnet.network.schema",
    "EVIDENCE_LABELS": "funcnet.network.schema",
    "FunctionalNetwork": "funcnet.network.functional",
    "functional_network": "funcnet.network.functional",
    "add_evidence": "funcnet.network.edge_evidence",
    "edge_kind": "funcnet.network.rule",
    "combine_kinds": "funcnet.network.rule",
    "kinds_for": "funcnet.network.rule",
    "pair_kinds": "funcnet.network.rule",
    "edges_from_pairs": "funcnet.network.rule",
    "EdgeStability": "funcnet.network.stability",
    "edge_stability": "funcnet.network.stability",
}




if TYPE_CHECKING:  # what the lazy table exports, for type checkers and editors
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
        EDGE_COLUMNS as EDGE_COLUMNS,
        EDGE_KINDS as EDGE_KINDS,
        EVIDENCE_COLUMNS as EVIDENCE_COLUMNS,
        EVIDENCE_LABELS as EVIDENCE_LABELS,
        MEASURE_KINDS as MEASURE_KINDS,
        PAIR_COLUMNS as PAIR_COLUMNS,
        PAIR_KINDS as PAIR_KINDS,
    )
    from funcnet.network.stability import (
        EdgeStability as EdgeStability,
        edge_stability as edge_stability,
    )
    from funcnet.parameters import MEASURES as MEASURES

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
