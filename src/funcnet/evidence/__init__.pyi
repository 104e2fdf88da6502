"""Type stub of funcnet.evidence: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.evidence.dependence import (
    SURROGATE_METHODS as SURROGATE_METHODS,
    DependenceResult as DependenceResult,
    ShiftPlan as ShiftPlan,
    benjamini_hochberg as benjamini_hochberg,
    decorrelation_time as decorrelation_time,
    default_surrogates as default_surrogates,
    dependence_test as dependence_test,
    planned_surrogates as planned_surrogates,
    shift_plan as shift_plan,
    surrogate_plan as surrogate_plan,
)
from funcnet.evidence.interval import (
    EDGE_RULES as EDGE_RULES,
    AsymmetryInterval as AsymmetryInterval,
    asymmetry_interval as asymmetry_interval,
    half_samples as half_samples,
    interval_from as interval_from,
    interval_kind as interval_kind,
    resampled_differences as resampled_differences,
)
from funcnet.evidence.pairs import (
    EVIDENCE_LABELS as EVIDENCE_LABELS,
    INTERVAL_SCOPES as INTERVAL_SCOPES,
    PairEvidence as PairEvidence,
    check_evidence_arguments as check_evidence_arguments,
    evidence_label as evidence_label,
    pairwise_evidence as pairwise_evidence,
)
from funcnet.evidence.reading import (
    evidence_readings as evidence_readings,
    smallest_p_values as smallest_p_values,
    untestable as untestable,
)
from funcnet.evidence.repetitions import (
    repetition_evidence as repetition_evidence,
    repetition_tests as repetition_tests,
    repetitions_needed as repetitions_needed,
)
from funcnet.evidence.surrogates import (
    TwinPlan as TwinPlan,
    twin_groups as twin_groups,
    twin_plan as twin_plan,
)

__all__: list[str]
