"""The paper's analyses: its claims as data, their evaluation on networks, its figures.

===============  ============================================================================
module           what it holds
===============  ============================================================================
``claims``       the claim language (``A->B``, ``A<->B``, ``A-/-B``, ``A!<->B``) and the
                 paper's section 4 findings written in it
``relations``    what a network shows between two signals, read in that language
``evaluate``     one finding measured on networks: yes / partly / no / not evaluable
``trends``       statistics across networks: edge thinning with speed, design factors
``analyses``     :func:`run_paper_analyses`: a simulated plan -> windows -> networks -> findings
``coupling``     the dependence test on every claimed relation: coupled, or untestable
``figures``      the paper's Figures 1, 2, 5, 9, 10, 11 (compute, then draw with
                 :mod:`funcnet.plot`); imported on its own (it needs matplotlib)
===============  ============================================================================

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.

Examples
--------
>>> from funcnet.paper import PAPER_PARAMETERS, parse_claim
>>> PAPER_PARAMETERS.rr, parse_claim("RC<->AC").kind
(0.05, 'bidirectional')
"""

from __future__ import annotations

from funcnet.paper.analyses import (
    PAPER_PARAMETERS,
    PAPER_SIGNALS,
    PaperAnalyses,
    TrialAnalysis,
    main_move,
    network_problems,
    run_paper_analyses,
)
from funcnet.paper.claims import (
    BASELINE,
    REVERSAL_AT_ZERO,
    REVERSAL_SEQUENCE,
    VELOCITY,
    Claim,
    Finding,
    FindingSpec,
    parse_claim,
)
from funcnet.paper.coupling import CouplingEvidence, claims_coupling
from funcnet.paper.evaluate import (
    baseline_findings,
    evaluate,
    reversal_findings,
    reversal_sequence,
    velocity_findings,
)
from funcnet.paper.relations import pair_kind, relation, relation_holds
from funcnet.paper.trends import design_effect, edge_thinning, mean_edge_weight, spearman

__all__ = [
    "BASELINE",
    "VELOCITY",
    "REVERSAL_AT_ZERO",
    "REVERSAL_SEQUENCE",
    "Claim",
    "Finding",
    "FindingSpec",
    "parse_claim",
    "pair_kind",
    "relation",
    "relation_holds",
    "evaluate",
    "baseline_findings",
    "velocity_findings",
    "reversal_findings",
    "reversal_sequence",
    "mean_edge_weight",
    "spearman",
    "edge_thinning",
    "design_effect",
    "PAPER_PARAMETERS",
    "PAPER_SIGNALS",
    "TrialAnalysis",
    "PaperAnalyses",
    "main_move",
    "network_problems",
    "run_paper_analyses",
    "CouplingEvidence",
    "claims_coupling",
]
