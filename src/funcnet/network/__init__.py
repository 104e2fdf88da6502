"""Functional networks: the edge rule, the network as data, its readers and writers.

=================  ==========================================================================
module             what it holds
=================  ==========================================================================
``schema``         the one pairs-table and edges-table schema, the kind vocabulary
``rule``           the edge rule as pure functions of a pairs table (section 2.4, Eq. 10, 13)
``functional``     :class:`FunctionalNetwork` and :func:`functional_network`
``evidence``       :func:`add_evidence`: the evidence columns of a network already computed
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

from funcnet.network.edge_evidence import add_evidence
from funcnet.network.functional import FunctionalNetwork, check_parameters, functional_network
from funcnet.network.rule import combine_kinds, edge_kind, edges_from_pairs, kinds_for, pair_kinds
from funcnet.network.schema import (
    EDGE_COLUMNS,
    EDGE_KINDS,
    EVIDENCE_COLUMNS,
    EVIDENCE_LABELS,
    MEASURE_KINDS,
    PAIR_COLUMNS,
    PAIR_KINDS,
)
from funcnet.network.stability import EdgeStability, edge_stability
from funcnet.parameters import MEASURES

__all__ = [
    "MEASURES",
    "PAIR_KINDS",
    "MEASURE_KINDS",
    "EDGE_KINDS",
    "PAIR_COLUMNS",
    "EDGE_COLUMNS",
    "EVIDENCE_COLUMNS",
    "EVIDENCE_LABELS",
    "FunctionalNetwork",
    "functional_network",
    "add_evidence",
    "check_parameters",
    "edge_kind",
    "combine_kinds",
    "kinds_for",
    "pair_kinds",
    "edges_from_pairs",
    "EdgeStability",
    "edge_stability",
]
