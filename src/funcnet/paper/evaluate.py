"""Measuring the paper's claims on functional networks.

Each claim (:mod:`funcnet.paper.claims`) is checked against what a network shows, pair by pair.
Nothing here asserts that the simulated axis behaves like the paper's robot; where it does not,
the :class:`~funcnet.paper.claims.Finding` says so (``reproduced="no"``) with the counts.

A claim is *not evaluable* in a network that lacks one of its two signals (a signal constant in
the window cannot be min-max normalized and is left out of that window's network), in a network
whose pair of the two signals is flagged ``degenerate`` (too few distinct states: the pair's
arrow is meaningless), or when the network is missing altogether (not computed, or no such
trial in the plan). Such a claim is neither a success nor a failure: it is counted and named in
the evidence.

How a finding is decided (one rule for all of them, fixed before looking at any result and the
same whatever the results are):

- ``"yes"``: every claimed relation was evaluated, and every one holds;
- ``"partly"``: some claimed relation was evaluated, not ``"yes"``, and at least one network
  shows all its claimed relations or at least half of the evaluated relations hold. This
  includes a finding whose evaluated relations all hold while others could not be evaluated:
  its evidence then says ``"n of m claims could not be evaluated"``;
- ``"no"``: some claimed relation was evaluated, and neither of the above;
- ``"not evaluable"``: no claimed relation could be evaluated;
- ``"n/a"``: analyses beyond the paper (TCP distance and step size): measured and described.

Relations are read from a network's pairs table (its ``kind`` column,
:data:`funcnet.network.schema.PAIR_KINDS`), so the same code runs on
:class:`funcnet.FunctionalNetwork` objects and on rows of a study's results. The edge rule
itself (``μ``) is applied once, in :mod:`funcnet.network.rule`, never here. Reading a relation
is in :mod:`funcnet.paper.relations`, statistics across networks (edge thinning, the design's
factors) in :mod:`funcnet.paper.trends`; both are re-exported here.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", section 4
   (Fig. 9-11) and section 3.1 (Table 1).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from funcnet.paper.claims import (
    BASELINE,
    REVERSAL_AT_ZERO,
    REVERSAL_SEQUENCE,
    VELOCITY,
    Finding,
    FindingSpec,
    parse_claim,
)
from funcnet.paper.relations import (
    DEGENERATE,
    nodes_of,
    pair_kind,
    relation,
    relation_holds,
)
from funcnet.paper.trends import design_effect, edge_thinning, mean_edge_weight, spearman

# relation, thinning and design effect are re-exported: evaluate is where a user looks first.
__all__ = [
    "DEGENERATE",
    "pair_kind",
    "relation",
    "relation_holds",
    "evaluate",
    "baseline_findings",
    "velocity_findings",
    "mean_edge_weight",
    "spearman",
    "edge_thinning",
    "reversal_findings",
    "reversal_sequence",
    "design_effect",
]


def _where(key: Any) -> str:
    if isinstance(key, tuple):
        return " · ".join(str(k) for k in key)
    return str(key)


def _decide(full: int, claims: int, checked: int, held: int) -> str:
    """The module's rule from counts: networks showing every claimed relation, claims in all,
    claims evaluated, claims holding."""
    if checked == 0:
        return "not evaluable"
    if held == claims:
        return "yes"
    if full > 0 or 2 * held >= checked:
        return "partly"
    return "no"


def _why_not_evaluable(claim: str, net: Any, left_out: Sequence[str]) -> str:
    """Why a claim cannot be evaluated in a network: a signal it lacks, or a degenerate pair."""
    parsed = parse_claim(claim)
    absent = [s for s in dict.fromkeys((parsed.a, parsed.b)) if s not in nodes_of(net)]
    if not absent:
        return DEGENERATE
    constant = [s for s in absent if s in left_out]
    other = [s for s in absent if s not in left_out]
    reasons = ([f"{', '.join(constant)} constant in the window, left out of its network"]
               if constant else [])
    reasons += [f"{', '.join(other)} not in the network"] if other else []
    return " and ".join(reasons)


def evaluate(spec: FindingSpec, networks: Mapping[Any, Any], *,
             left_out: Mapping[Any, Sequence[str]] | None = None) -> Finding:
    """Measure one finding on the networks it is about.

    Parameters
    ----------
    spec : FindingSpec
        The claimed relations per network key.
    networks : mapping of key -> FunctionalNetwork or None
        The networks; a key that is missing, or maps to ``None`` (the network could not be
        computed), makes all its claims not evaluable, and so does a network lacking a signal
        for the claims about that signal, or flagging a pair ``degenerate`` for the claims
        about that pair.
    left_out : mapping of key -> sequence of str, optional
        Signals left out of a key's network because they are constant in its window; only used
        to say why a claim is not evaluable.

    Returns
    -------
    Finding
        Decided by the module's rule; the evidence counts networks (or trials) that show every
        claimed relation, relations that hold among those evaluated, and names the claims that
        could not be evaluated, with the reason.

    References
    ----------
    Paper section 4 (the statements of ``spec``).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> net = FunctionalNetwork.from_pairs(pd.DataFrame(
    ...     {"x": ["RP", "RP"], "y": ["AP", "MP"], "kind": ["x->y", "y->x"], "weight": [.1, .1]}))
    >>> spec = FindingSpec("t", "4.1", "RP drives AP and MP", {"early": ("RP->AP", "RP->MP")})
    >>> f = evaluate(spec, {"early": net})
    >>> f.reproduced, f.evidence
    ('partly', '0/1 networks show all claimed relations; 1/2 relations hold')
    >>> evaluate(spec, {"early": None}).reproduced
    'not evaluable'
    """
    left_out = left_out or {}
    full = held = checked = claimed = 0
    seen_all: list[str] = []
    missing: list[str] = []
    expected: list[str] = []
    for key, claims in spec.claims.items():
        where = _where(key)
        expected.extend(f"[{where}] {c}" for c in claims)
        claimed += len(claims)
        net = networks.get(key)
        if net is None:
            missing.extend(f"[{where}] {c}: no network" for c in claims)
            continue
        results = [(claim, *relation_holds(net, claim)) for claim in claims]
        # A claim about a node the network lacks or about a degenerate pair is not evaluable;
        # the network still counts for its other claims, never as a full match.
        missing.extend(
            f"[{where}] {claim}: {_why_not_evaluable(claim, net, left_out.get(key) or ())}"
            for claim, ok, _ in results if ok is None)
        results = [(claim, ok, seen) for claim, ok, seen in results if ok is not None]
        n_held = sum(bool(ok) for _, ok, _ in results)
        held += n_held
        checked += len(results)
        full += n_held == len(claims)
        seen_all.extend(f"[{where}] {seen}" for _, _, seen in results)
    evidence = (f"{full}/{len(spec.claims)} {spec.unit} show all claimed relations; "
                f"{held}/{checked} relations hold")
    if missing:
        evidence += (f"; {len(missing)} of {claimed} claims could not be evaluated: "
                     + ", ".join(missing))
    verdict = _decide(full, claimed, checked, held)
    return Finding(spec.id, spec.section, spec.statement, verdict, evidence, tuple(seen_all),
                   tuple(expected), tuple(missing))


def baseline_findings(networks: Mapping[Any, Any], *,
                      left_out: Mapping[Any, Sequence[str]] | None = None) -> list[Finding]:
    """Section 4.1 on the baseline trial's phase networks.

    Parameters
    ----------
    networks : mapping of phase -> FunctionalNetwork (or None)
        Keys ``"early spin-up"``, ``"late spin-up"``, ``"cruise"``, ``"braking"``.
    left_out : mapping of phase -> sequence of str, optional
        Signals left out of a phase's network as constant (see :func:`evaluate`).

    Returns
    -------
    list of Finding
        One per statement of :data:`funcnet.paper.claims.BASELINE`.

    References
    ----------
    Paper section 4.1 and Fig. 9.

    Examples
    --------
    >>> [f.reproduced for f in baseline_findings({})][:2]
    ['not evaluable', 'not evaluable']
    """
    return [evaluate(spec, networks, left_out=left_out) for spec in BASELINE]


def velocity_findings(networks: Mapping[Any, Any], *,
                      left_out: Mapping[Any, Sequence[str]] | None = None) -> list[Finding]:
    """Section 4.2 on the networks of the four velocity trials.

    Parameters
    ----------
    networks : mapping of (velocity, phase) -> FunctionalNetwork (or None)
        Velocities ``"V1", "V35", "V175", "V350"``; phases ``"spin-up", "cruise", "braking"``
        (fixed windows of 280 / 600 / 600 ms).
    left_out : mapping of (velocity, phase) -> sequence of str, optional
        Signals left out of a network as constant (see :func:`evaluate`).

    Returns
    -------
    list of Finding
        One per statement of :data:`funcnet.paper.claims.VELOCITY`, then :func:`edge_thinning`.

    References
    ----------
    Paper section 4.2 and Fig. 10.

    Examples
    --------
    >>> len(velocity_findings({}))
    8
    """
    return [*(evaluate(spec, networks, left_out=left_out) for spec in VELOCITY),
            edge_thinning(networks)]


def reversal_findings(networks: Mapping[str, Mapping[Any, Any]], *,
                      left_out: Mapping[str, Mapping[Any, Sequence[str]]] | None = None
                      ) -> list[Finding]:
    """Section 4.3 on the backlash trials' reversal windows.

    Parameters
    ----------
    networks : mapping of trial -> (mapping of offset in ms -> FunctionalNetwork or None)
        For each backlash trial the networks of its windows at -40, -20, 0, +20, +40 ms.
    left_out : mapping of trial -> (mapping of offset in ms -> sequence of str), optional
        Signals left out of a window's network as constant (see :func:`evaluate`).

    Returns
    -------
    list of Finding
        The signature at 0 ms (velocity drives all; MP -> AP -> RP), counted over trials, and
        :func:`reversal_sequence`.

    References
    ----------
    Paper section 4.3 and Fig. 11.

    Examples
    --------
    >>> [f.id for f in reversal_findings({})]
    ['4.3-v-drives', '4.3-position-chain', '4.3-sequence']
    """
    left_out = left_out or {}
    found = []
    for finding_id, (statement, claims) in REVERSAL_AT_ZERO.items():
        spec = FindingSpec(finding_id, "4.3", statement, {t: claims for t in networks},
                           unit="trials")
        found.append(evaluate(spec, {t: nets.get(0) for t, nets in networks.items()},
                              left_out={t: left_out.get(t, {}).get(0, ()) for t in networks}))
    found.append(reversal_sequence(networks))
    return found


def reversal_sequence(networks: Mapping[str, Mapping[Any, Any]]) -> Finding:
    """Section 4.3: the reversal signature develops over -40, -20, 0, +20, +40 ms.

    In each trial every offset's window is checked against
    :data:`funcnet.paper.claims.REVERSAL_SEQUENCE`. The sequence *appears* in a trial when
    every window shows all its claimed relations, and *largely appears* when every window shows
    at least half of them (the paper: "resembles", "largely present"); a claim that cannot be
    evaluated (no network, a signal left out of it, or a degenerate pair) counts as not shown,
    and the evidence says how many. ``"yes"`` when it appears in every trial, ``"partly"`` when
    it largely appears in at least one, ``"no"`` otherwise, and ``"not evaluable"`` when no
    claim of any trial could be evaluated.

    Parameters
    ----------
    networks : mapping of trial -> (mapping of offset in ms -> FunctionalNetwork or None)
        The shifted windows' networks of each backlash trial.

    Returns
    -------
    Finding
        Evidence: trials with the whole sequence, with most of it, and per offset the trials
        whose window shows all of its claims.

    References
    ----------
    Paper section 4.3 and Fig. 11b.

    Examples
    --------
    >>> reversal_sequence({}).reproduced
    'not evaluable'
    """
    strict = largely = unevaluated = 0
    per_offset = dict.fromkeys(REVERSAL_SEQUENCE, 0)
    seen: list[str] = []
    for trial, nets in networks.items():
        fractions = []
        for offset, claims in REVERSAL_SEQUENCE.items():
            net = nets.get(offset)
            results = [relation_holds(net, c) for c in claims] if net is not None else []
            unevaluated += len(claims) - sum(ok is not None for ok, _ in results)
            n_held = sum(bool(ok) for ok, _ in results)
            fractions.append(n_held / len(claims))
            per_offset[offset] += n_held == len(claims)
            seen.extend(f"[{trial} · {offset:+d} ms] {s}" for _, s in results if s)
        strict += all(f == 1.0 for f in fractions)
        largely += all(f >= 0.5 for f in fractions)
    n = len(networks)
    claimed = n * sum(len(cs) for cs in REVERSAL_SEQUENCE.values())
    if unevaluated == claimed:
        reproduced = "not evaluable"
    else:
        reproduced = "yes" if strict == n else ("partly" if largely else "no")
    evidence = (f"whole sequence in {strict}/{n} trials, at least half of each window's claims "
                f"in {largely}/{n}; windows showing all claims: "
                + ", ".join(f"{o:+d} ms {k}/{n}" for o, k in per_offset.items()))
    if unevaluated:
        evidence += (f"; {unevaluated} of {claimed} claims could not be evaluated (no network, "
                     "a signal constant in the window and left out, or a degenerate recurrence "
                     "structure)")
    expected = tuple(f"[{o:+d} ms] {c}" for o, cs in REVERSAL_SEQUENCE.items() for c in cs)
    return Finding("4.3-sequence", "4.3",
                   "Around the reversal the network changes in sequence: at -40 ms RC and AC "
                   "drive V and the positions; at -20 ms V and the currents are bidirectional; "
                   "at 0 and +20 ms V drives all and MP -> AP -> RP; at +40 ms AP and RP cluster, "
                   "MP drives both, V reconnects with RC and AC.", reproduced, evidence,
                   tuple(seen), expected)


