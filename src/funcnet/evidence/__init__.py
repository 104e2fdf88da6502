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
``evidence=True``. Its calibration and error rates are in ``docs/validation/evidence.md``.

Examples
--------
>>> from funcnet.evidence import default_surrogates, EVIDENCE_LABELS
>>> default_surrogates(15), EVIDENCE_LABELS[0]
(299, 'coupled-directed')
"""


from __future__ import annotations

from typing import TYPE_CHECKING

from funcnet._lazy import attach

_EXPORTS = {
    "EVIDENCE_LABELS": "funcnet.evidence.pairs",
    "EDGE_RULES": "funcnet.evidence.interval",
    "SURROGATE_METHODS": "funcnet.evidence.dependence",
    "AsymmetryInterval": "funcnet.evidence.interval",
    "DependenceResult": "funcnet.evidence.dependence",
    "PairEvidence": "funcnet.evidence.pairs",
    "ShiftPlan": "funcnet.evidence.dependence",
    "TwinPlan": "funcnet.evidence.surrogates",
    "asymmetry_interval": "funcnet.evidence.interval",
    "benjamini_hochberg": "funcnet.evidence.dependence",
    "check_evidence_arguments": "funcnet.evidence.pairs",
    "decorrelation_time": "funcnet.evidence.dependence",
    "default_surrogates": "funcnet.evidence.dependence",
    "dependence_test": "funcnet.evidence.dependence",
    "evidence_label": "funcnet.evidence.pairs",
    "evidence_readings": "funcnet.evidence.reading",
    "half_samples": "funcnet.evidence.interval",
    "interval_from": "funcnet.evidence.interval",
    "interval_kind": "funcnet.evidence.interval",
    "pairwise_evidence": "funcnet.evidence.pairs",
    "repetition_evidence": "funcnet.evidence.repetitions",
    "repetition_tests": "funcnet.evidence.repetitions",
    "repetitions_needed": "funcnet.evidence.repetitions",
    "resampled_differences": "funcnet.evidence.interval",
    "shift_plan": "funcnet.evidence.dependence",
    "smallest_p_values": "funcnet.evidence.reading",
    "surrogate_plan": "funcnet.evidence.dependence",
    "twin_groups": "funcnet.evidence.surrogates",
    "twin_plan": "funcnet.evidence.surrogates",
    "untestable": "funcnet.evidence.reading",
}




if TYPE_CHECKING:  # what the lazy table exports, for type checkers and editors
    from funcnet.evidence.dependence import (
        SURROGATE_METHODS as SURROGATE_METHODS,
        DependenceResult as DependenceResult,
        ShiftPlan as ShiftPlan,
        benjamini_hochberg as benjamini_hochberg,
        decorrelation_time as decorrelation_time,
        default_surrogates as default_surrogates,
        dependence_test as dependence_test,
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

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
