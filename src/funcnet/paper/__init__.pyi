"""Type stub of funcnet.paper: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.paper.analyses import (
    PAPER_PARAMETERS as PAPER_PARAMETERS,
    PAPER_SIGNALS as PAPER_SIGNALS,
    PaperAnalyses as PaperAnalyses,
    TrialAnalysis as TrialAnalysis,
    main_move as main_move,
    network_problems as network_problems,
    run_paper_analyses as run_paper_analyses,
)
from funcnet.paper.claims import (
    BASELINE as BASELINE,
    REVERSAL_AT_ZERO as REVERSAL_AT_ZERO,
    REVERSAL_SEQUENCE as REVERSAL_SEQUENCE,
    VELOCITY as VELOCITY,
    Claim as Claim,
    Finding as Finding,
    FindingSpec as FindingSpec,
    parse_claim as parse_claim,
)
from funcnet.paper.coupling import (
    CouplingEvidence as CouplingEvidence,
    claims_coupling as claims_coupling,
)
from funcnet.paper.evaluate import (
    baseline_findings as baseline_findings,
    reversal_findings as reversal_findings,
    reversal_sequence as reversal_sequence,
    velocity_findings as velocity_findings,
)
from funcnet.paper.relations import (
    pair_kind as pair_kind,
    relation as relation,
    relation_holds as relation_holds,
)
from funcnet.paper.trends import (
    design_effect as design_effect,
    edge_thinning as edge_thinning,
    mean_edge_weight as mean_edge_weight,
    spearman as spearman,
)

__all__: list[str]
