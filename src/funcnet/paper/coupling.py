"""Coupling evidence of the paper's claimed relations: is each claimed pair coupled at all?

The paper's arrows come from the asymmetry of cross-clustering and cross-transitivity, which
does not look at time alignment: an arrow can be drawn between two signals that are
not coupled. For every relation a finding claims (a pair of signals in one window), this module
runs the joint-recurrence dependence test of :mod:`funcnet.evidence` on that window's network
(:func:`funcnet.functional_network` with ``evidence=True, resamples=0``: the test only, no
intervals) and counts, per finding, the claimed relations whose pair the test shows coupled.

Untestable is not uncoupled. The test's surrogates are time shifts of at least the
decorrelation time; a short window holds few of them (4-12 on the paper's 140- and 300-sample
robot windows, docs/validation/evidence.md), and with ``K`` surrogates no p-value is below
``1/(K+1)``. A pair that could not have been shown coupled whatever the data (that bound, after the
Benjamini-Hochberg adjustment over the window's pairs, above ``alpha``, or no surrogate at all:
:func:`funcnet.evidence.untestable`) is counted as *untestable*, never as *not coupled*.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2.4
   and 4.
.. [2] Romano et al., "Detection of synchronization for non-phase-coherent and non-stationary
   data", Europhys. Lett. 71 (2005) (joint recurrences).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from funcnet.evidence import untestable
from funcnet.paper.analyses import PaperAnalyses, TrialAnalysis
from funcnet.paper.claims import (
    BASELINE,
    REVERSAL_AT_ZERO,
    REVERSAL_SEQUENCE,
    VELOCITY,
    parse_claim,
)

__all__ = ["CouplingEvidence", "pair_reading", "claimed_windows", "claims_coupling"]

#: A claimed relation: the trial analysis, the window key in it, and the claim text.
ClaimSite = tuple[TrialAnalysis | None, Any, str]


@dataclass(frozen=True)
class CouplingEvidence:
    """What the dependence test says about one finding's claimed relations.

    Attributes
    ----------
    relations : int
        Claimed relations (a pair of signals in one window), each counted once per window.
    coupled : int
        Those whose pair the test shows coupled (``coupled`` at ``alpha``, BH-adjusted over
        the window's pairs).
    not_coupled : int
        Tested and not shown coupled.
    untestable : int
        Too few surrogates to reject at ``alpha`` (:func:`funcnet.evidence.untestable`).
    untested : int
        No network, a signal left out of it, or the test failed on the window.
    max_untestable_surrogates : int
        The most surrogates any untestable pair had (for the text).
    alpha : float
        The level.

    Examples
    --------
    >>> CouplingEvidence(12, 3, 0, 9, 0, 12, 0.05).text
    'coupled in 3/12 claimed relations; untestable in 9 (≤ 12 surrogates)'
    >>> CouplingEvidence(0, 0, 0, 0, 0, 0, 0.05).text
    '—'
    """

    relations: int
    coupled: int
    not_coupled: int
    untestable: int
    untested: int
    max_untestable_surrogates: int
    alpha: float

    @property
    def text(self) -> str:
        """One line for the findings table, e.g. ``coupled in 3/12 claimed relations; ...``."""
        if self.relations == 0:
            return "—"
        parts = [f"coupled in {self.coupled}/{self.relations} claimed relations"]
        if self.not_coupled:
            parts.append(f"not shown coupled in {self.not_coupled}")
        if self.untestable:
            parts.append(f"untestable in {self.untestable} "
                         f"(≤ {self.max_untestable_surrogates} surrogates)")
        if self.untested:
            parts.append(f"no test in {self.untested} (no network or a signal left out)")
        return "; ".join(parts)


def pair_reading(pairs: pd.DataFrame, a: str, b: str, alpha: float) -> tuple[str, int]:
    """The test's reading of the pair ``a``-``b`` in a pairs table with evidence columns.

    Parameters
    ----------
    pairs : pandas.DataFrame
        One network's pairs table with :data:`funcnet.network.schema.EVIDENCE_COLUMNS` (all
        its pairs: whether a pair is untestable depends on the others' surrogates through the
        Benjamini-Hochberg adjustment, :func:`funcnet.evidence.untestable`).
    a, b : str
        The pair's signals, in either order.
    alpha : float

    Returns
    -------
    (str, int)
        ``"coupled"``, ``"not coupled"``, ``"untestable"`` or ``"untested"`` (no such pair),
        and the pair's surrogates.

    Examples
    --------
    >>> pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "coupled": [False], "coupling_p": [0.5],
    ...                       "surrogates": [8]})
    >>> pair_reading(pairs, "B", "A", 0.05), pair_reading(pairs, "A", "C", 0.05)
    (('untestable', 8), ('untested', 0))
    """
    match = (((pairs["x"] == a) & (pairs["y"] == b)) | ((pairs["x"] == b) & (pairs["y"] == a)))
    if not match.any():
        return "untested", 0
    where = int(np.flatnonzero(match.to_numpy())[0])
    row = pairs.iloc[where]
    k = 0 if pd.isna(row["surrogates"]) else int(row["surrogates"])
    if bool(row["coupled"]):
        return "coupled", k
    if untestable(pairs["surrogates"].to_numpy(dtype=float), alpha)[where]:
        return "untestable", k
    return "not coupled", k


def claimed_windows(analyses: PaperAnalyses) -> dict[str, list[ClaimSite]]:
    """Every finding's claimed relations, each with the trial and window it is evaluated on.

    The same mapping of findings to networks as :func:`funcnet.paper.run_paper_analyses`:
    section 4.1 on the baseline trial's phases, 4.2 on the velocity trials' fixed windows, 4.3
    on each backlash trial's reversal windows (0 ms for the signature, every offset for the
    sequence). Findings without claimed relations (trends, the design's factors) are absent.

    Parameters
    ----------
    analyses : PaperAnalyses

    Returns
    -------
    dict
        Finding id -> list of ``(trial analysis or None, window key, claim)``.
    """
    sites: dict[str, list[ClaimSite]] = {}
    for spec in BASELINE:
        sites[spec.id] = [(analyses.baseline, key, claim)
                          for key, claims in spec.claims.items() for claim in claims]
    for spec in VELOCITY:
        sites[spec.id] = [(analyses.velocity.get(label), phase, claim)
                          for (label, phase), claims in spec.claims.items() for claim in claims]
    for finding_id, (_, claims) in REVERSAL_AT_ZERO.items():
        sites[finding_id] = [(trial, 0, claim) for trial in analyses.reversal.values()
                             for claim in claims]
    sites["4.3-sequence"] = [(trial, offset, claim) for trial in analyses.reversal.values()
                             for offset, claims in REVERSAL_SEQUENCE.items() for claim in claims]
    return sites


def claims_coupling(
    analyses: PaperAnalyses,
    *,
    alpha: float = 0.05,
    seed: int = 0,
    surrogates: int | None = None,
    surrogate_method: str = "shift",
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, CouplingEvidence]:
    """The dependence test on every window a claimed relation is evaluated on, per finding.

    Each window's network is computed again with ``evidence=True, resamples=0`` (the coupling
    test only; same nodes, parameters and data as the analysis's network), once however many
    findings use it.

    Parameters
    ----------
    analyses : PaperAnalyses
        From :func:`funcnet.paper.run_paper_analyses`.
    alpha, seed, surrogates, surrogate_method
        As :func:`funcnet.functional_network` (``surrogates=None``: chosen from the number of
        pairs).
    progress : callable, optional
        ``progress(done, total)`` after each window.

    Returns
    -------
    dict
        Finding id -> :class:`CouplingEvidence` (findings with claimed relations only).
    """
    sites = claimed_windows(analyses)
    windows = list(dict.fromkeys((id(t), key) for found in sites.values()
                                 for t, key, _ in found if t is not None))
    by_id = {id(t): t for found in sites.values() for t, _, _ in found if t is not None}
    tested: dict[tuple[int, Any], pd.DataFrame | None] = {}
    for done, (trial_id, key) in enumerate(windows, start=1):
        tested[(trial_id, key)] = _tested_pairs(by_id[trial_id], key, alpha=alpha, seed=seed,
                                                surrogates=surrogates,
                                                surrogate_method=surrogate_method)
        if progress is not None:
            progress(done, len(windows))
    return {finding_id: _count(((tested.get((id(t), key)) if t is not None else None, claim)
                                for t, key, claim in found), alpha)
            for finding_id, found in sites.items()}


def _tested_pairs(trial: TrialAnalysis, key: Any, *, alpha: float, seed: int,
                  surrogates: int | None, surrogate_method: str) -> pd.DataFrame | None:
    """The window's pairs table with the coupling test, or None (no network, or it failed)."""
    from funcnet.errors import FuncnetError
    from funcnet.network import functional_network
    from funcnet.pipeline import channel_steps, window_steps

    net = trial.networks.get(key)
    if net is None or key not in trial.windows:
        return None
    part = trial.window_data(key)[list(net.nodes)]
    # the direction read as window_networks reads it: each channel's logged precision
    steps = window_steps(part.to_numpy(np.float64), list(net.nodes),
                         channel_steps(trial.data, list(net.nodes)))
    try:
        full = functional_network(part, parameters=net.parameters, label=net.label, warn=False,
                                  evidence=True, resamples=0, alpha=alpha, seed=seed,
                                  surrogates=surrogates, surrogate_method=surrogate_method,
                                  steps=steps)
    except FuncnetError:
        return None
    # The same network: only the evidence columns are new (a guard against a data mismatch).
    if not np.allclose(full.pairs["c_diff"], net.pairs["c_diff"], equal_nan=True):
        return None
    return full.pairs


def _count(readings: Iterable[tuple[pd.DataFrame | None, str]], alpha: float) -> CouplingEvidence:
    tally = {"coupled": 0, "not coupled": 0, "untestable": 0, "untested": 0}
    worst = 0
    for pairs, claim in readings:
        parsed = parse_claim(claim)
        if pairs is None:
            tally["untested"] += 1
            continue
        reading, k = pair_reading(pairs, parsed.a, parsed.b, alpha)
        tally[reading] += 1
        if reading == "untestable":
            worst = max(worst, k)
    return CouplingEvidence(sum(tally.values()), tally["coupled"], tally["not coupled"],
                            tally["untestable"], tally["untested"], worst, float(alpha))
