"""Evidence for every edge: whether two signals are coupled at all, how sure an asymmetry is.

=================  ==========================================================================
module             what it holds
=================  ==========================================================================
``dependence``     the joint-recurrence dependence test with non-circular time-shift
                   surrogates (or twin surrogates), the direction index of conditional
                   recurrence probabilities, Benjamini-Hochberg, the default number of
                   surrogates
``surrogates``     twin surrogates (Thiel et al. 2006), an option of the dependence test
``interval``       half-sampling (blocks without replacement) intervals of ``C_diff`` and
                   ``T_diff``, and the interval edge rule
``pairs``          :func:`pairwise_evidence` over a set of signals, and the reading of a pair
``reading``        whether a pair's test could have rejected at all (:func:`untestable`),
                   the labels of a network's pairs and why (:func:`evidence_readings`)
``repetitions``    :func:`repetition_evidence`: coupling beyond the command, tested across
                   aligned repetitions of one motion (repetition-shuffled pairings)
=================  ==========================================================================

This package sits above the measures and below the network (it never imports
:mod:`funcnet.network`); :func:`funcnet.network.functional_network` calls it with
``evidence=True``. Its calibration and error rates are in ``docs/evidence.md``.

Examples
--------
>>> from funcnet.evidence import default_surrogates, EVIDENCE_LABELS
>>> default_surrogates(15), EVIDENCE_LABELS[0]
(299, 'coupled-directed')
"""

from __future__ import annotations

from funcnet.evidence.dependence import (
    SURROGATE_METHODS,
    DependenceResult,
    ShiftPlan,
    benjamini_hochberg,
    decorrelation_time,
    default_surrogates,
    dependence_test,
    shift_plan,
    surrogate_plan,
)
from funcnet.evidence.interval import (
    AsymmetryInterval,
    asymmetry_interval,
    half_samples,
    interval_from,
    interval_kind,
    resampled_differences,
)
from funcnet.evidence.pairs import (
    EVIDENCE_LABELS,
    PairEvidence,
    check_evidence_arguments,
    evidence_label,
    pairwise_evidence,
)
from funcnet.evidence.reading import evidence_readings, smallest_p_values, untestable
from funcnet.evidence.repetitions import (
    repetition_evidence,
    repetition_tests,
    repetitions_needed,
)
from funcnet.evidence.surrogates import TwinPlan, twin_groups, twin_plan

__all__ = [
    "EVIDENCE_LABELS",
    "EDGE_RULES",
    "SURROGATE_METHODS",
    "AsymmetryInterval",
    "DependenceResult",
    "PairEvidence",
    "ShiftPlan",
    "TwinPlan",
    "asymmetry_interval",
    "benjamini_hochberg",
    "check_evidence_arguments",
    "decorrelation_time",
    "default_surrogates",
    "dependence_test",
    "evidence_label",
    "evidence_readings",
    "half_samples",
    "interval_from",
    "interval_kind",
    "pairwise_evidence",
    "repetition_evidence",
    "repetition_tests",
    "repetitions_needed",
    "resampled_differences",
    "shift_plan",
    "smallest_p_values",
    "surrogate_plan",
    "twin_groups",
    "twin_plan",
    "untestable",
]

#: Edge rules: the paper's (``mu`` only, the default) and ``mu`` with the interval.
EDGE_RULES: tuple[str, ...] = ("paper", "interval")
