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

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
