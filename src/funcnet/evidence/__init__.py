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
    "planned_surrogates": "funcnet.evidence.dependence",
    "INTERVAL_SCOPES": "funcnet.evidence.pairs",
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

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
