"""The paper's analyses [1]_: its claims as data, their evaluation on networks, its figures.

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

from funcnet._lazy import attach

_EXPORTS = {
    "BASELINE": "funcnet.paper.claims",
    "VELOCITY": "funcnet.paper.claims",
    "REVERSAL_AT_ZERO": "funcnet.paper.claims",
    "REVERSAL_SEQUENCE": "funcnet.paper.claims",
    "Claim": "funcnet.paper.claims",
    "Finding": "funcnet.paper.claims",
    "FindingSpec": "funcnet.paper.claims",
    "parse_claim": "funcnet.paper.claims",
    "pair_kind": "funcnet.paper.relations",
    "relation": "funcnet.paper.relations",
    "relation_holds": "funcnet.paper.relations",
    "baseline_findings": "funcnet.paper.evaluate",
    "velocity_findings": "funcnet.paper.evaluate",
    "reversal_findings": "funcnet.paper.evaluate",
    "reversal_sequence": "funcnet.paper.evaluate",
    "mean_edge_weight": "funcnet.paper.trends",
    "spearman": "funcnet.paper.trends",
    "edge_thinning": "funcnet.paper.trends",
    "design_effect": "funcnet.paper.trends",
    "PAPER_PARAMETERS": "funcnet.paper.analyses",
    "PAPER_SIGNALS": "funcnet.paper.analyses",
    "TrialAnalysis": "funcnet.paper.analyses",
    "PaperAnalyses": "funcnet.paper.analyses",
    "main_move": "funcnet.paper.analyses",
    "network_problems": "funcnet.paper.analyses",
    "run_paper_analyses": "funcnet.paper.analyses",
    "CouplingEvidence": "funcnet.paper.coupling",
    "claims_coupling": "funcnet.paper.coupling",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
