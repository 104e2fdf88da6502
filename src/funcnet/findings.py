"""The paper's section 4 findings, measured on functional networks.

Each qualitative finding of the paper (El Dabett, Hansen & Geier, section 4) is written down as
the edges it claims — ``"RP->AP"`` (RP drives AP), ``"RC<->AC"`` (bidirectional), ``"V!<->RC"``
(anything but bidirectional: directed either way, or no edge) — in the networks it claims them
for, and then *measured*: the networks are asked, pair by pair, which relation they show. Nothing
here asserts that the simulated axis behaves like the paper's robot; where it does not, the
:class:`Finding` says so (``reproduced="no"``) with the counts.

A claimed relation is *not evaluable* in a network that lacks one of its two signals (a signal
constant in the window cannot be min-max normalized and is left out of that window's network),
in a network whose pair of the two signals is flagged ``degenerate`` (a degenerate recurrence
structure: a signal barely moves in the window, so the pair's arrow is meaningless; pairs tables
without that column, from older results, count as not degenerate), or when the network is
missing altogether (not computed, or no such trial in the plan). Such a claim is neither a
success nor a failure: it is counted and named in the evidence.

How a finding is decided (one rule for all of them, fixed before looking at any result and the
same whatever the results are):

- ``"yes"``: every claimed relation was evaluated, and every one holds;
- ``"partly"``: some claimed relation was evaluated, not ``"yes"``, and at least one network
  shows all its claimed relations or at least half of the evaluated relations hold. This
  includes a finding whose evaluated relations all hold while others could not be evaluated:
  its evidence then says ``"n of m claims could not be evaluated"``;
- ``"no"``: some claimed relation was evaluated, and neither of the above;
- ``"not evaluable"``: no claimed relation could be evaluated: nothing was measured, so the
  finding is neither reproduced nor contradicted;
- ``"n/a"``: analyses beyond the paper (TCP distance and step size, which the paper does not
  report): measured and described, nothing to reproduce.

Relations are read from a network's pairs table (``kind`` of each pair: ``x->y``, ``y->x``,
``bidirectional``, ``conflict``), so the same code runs on :class:`funcnet.FunctionalNetwork`
objects and on rows of a study's results. The edge rule itself (``μ``, README method step 7) is
applied once, in :mod:`funcnet.network`, never here.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", section 4
   (4.1 baseline, Fig. 9; 4.2 velocity, Fig. 10; 4.3 backlash, Fig. 11) and section 3.1
   (Table 1, the design of experiments).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError
from funcnet.robot.windows import PAPER_NODES

__all__ = [
    "Finding",
    "FindingSpec",
    "relation",
    "relation_holds",
    "evaluate",
    "BASELINE",
    "VELOCITY",
    "REVERSAL_AT_ZERO",
    "REVERSAL_SEQUENCE",
    "TrialAnalysis",
    "PaperAnalyses",
    "PAPER_PARAMETERS",
    "main_move",
    "run_paper_analyses",
    "baseline_findings",
    "velocity_findings",
    "edge_thinning",
    "reversal_findings",
    "reversal_sequence",
    "design_effect",
]

REPRODUCED = ("yes", "partly", "no", "not evaluable", "n/a")
POSITIONS = ("RP", "AP", "MP")
CURRENTS = ("RC", "AC")
MOTION = ("RP", "AP", "MP", "V")

_RELATION = re.compile(r"^\s*(\w+)\s*(<->|!<->|->)\s*(\w+)\s*$")


@dataclass(frozen=True)
class Finding:
    """One of the paper's findings, measured.

    Attributes
    ----------
    id : str
        Short stable identifier (``"4.1-early-rp-drives"``).
    section : str
        Paper section (``"4.1"``, ``"4.2"``, ``"4.3"``, ``"3.1"``).
    statement : str
        What the paper says (or, for ``"n/a"``, what was measured).
    reproduced : str
        ``"yes"``, ``"partly"``, ``"no"``, ``"not evaluable"`` or ``"n/a"`` (see the module's
        rule).
    evidence : str
        Counts, e.g. ``"4/6 trials show all claimed relations; 26/30 relations hold"``.
    edges_seen : tuple of str
        The relations actually seen where the claim was checked, ``"[where] RP->AP"``.
    expected : tuple of str
        The claimed relations, ``"[where] RP->AP"``.
    not_evaluable : tuple of str
        The claims that could not be evaluated and why, ``"[where] AP<->V: AP, V constant in
        the window, left out of its network"``.
    """

    id: str
    section: str
    statement: str
    reproduced: str
    evidence: str
    edges_seen: tuple[str, ...] = ()
    expected: tuple[str, ...] = ()
    not_evaluable: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.reproduced not in REPRODUCED:
            raise ParameterError(f"reproduced must be one of {REPRODUCED}, not {self.reproduced!r}")


@dataclass(frozen=True)
class FindingSpec:
    """A finding of the paper as claimed relations per network.

    Attributes
    ----------
    id, section, statement : str
        As in :class:`Finding`.
    claims : mapping of key -> tuple of str
        For each network key (a phase, ``(velocity, phase)``, an offset, ...) the relations the
        paper reports there.
    unit : str
        What a key is, for the evidence text (``"networks"``, ``"trials"``, ``"conditions"``).
    """

    id: str
    section: str
    statement: str
    claims: Mapping[Any, tuple[str, ...]] = field(default_factory=dict)
    unit: str = "networks"


def _pairs(net: Any) -> pd.DataFrame:
    return net if isinstance(net, pd.DataFrame) else net.pairs


def relation(net: Any, a: str, b: str) -> str | None:
    """The relation a network shows between signals ``a`` and ``b``.

    Parameters
    ----------
    net : FunctionalNetwork or pandas.DataFrame
        A network or its pairs table (columns ``x, y, kind``).
    a, b : str
        Node names.

    Returns
    -------
    str or None
        ``"a->b"``, ``"b->a"``, ``"a<->b"`` (bidirectional: mutual or no coupling, paper section
        2.4), ``"a-/-b"`` (conflict between C_diff and T_diff: no edge), or ``None`` when the
        network has no such pair.

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["RP"], "y": ["AP"], "kind": ["y->x"]})
    >>> relation(pairs, "RP", "AP"), relation(pairs, "AP", "RP"), relation(pairs, "RP", "V")
    ('AP->RP', 'AP->RP', None)
    """
    table = _pairs(net)
    for row in table.itertuples(index=False):
        if {row.x, row.y} != {a, b} or a == b:
            continue
        if row.kind == "bidirectional":
            return f"{a}<->{b}"
        if row.kind == "conflict":
            return f"{a}-/-{b}"
        source, target = (row.x, row.y) if row.kind == "x->y" else (row.y, row.x)
        return f"{source}->{target}"
    return None


def relation_holds(net: Any, claim: str) -> tuple[bool | None, str | None]:
    """Whether a network shows a claimed relation.

    Parameters
    ----------
    net : FunctionalNetwork or pandas.DataFrame
        A network or its pairs table.
    claim : str
        ``"A->B"`` (A drives B), ``"A<->B"`` (bidirectional) or ``"A!<->B"`` (not bidirectional:
        directed either way, or no edge).

    Returns
    -------
    (bool or None, str or None)
        Whether it holds and the relation seen; ``(None, None)`` when the pair is absent or
        flagged ``degenerate`` (not evaluable, see the module's rule).

    Raises
    ------
    ParameterError
        When ``claim`` is not written in one of the three forms.

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["RC"], "y": ["AC"], "kind": ["bidirectional"]})
    >>> relation_holds(pairs, "AC<->RC"), relation_holds(pairs, "RC->AC")[0]
    ((True, 'AC<->RC'), False)
    >>> relation_holds(pairs.assign(degenerate=True), "AC<->RC")
    (None, None)
    """
    match = _RELATION.match(claim)
    if match is None:
        raise ParameterError(f"claim {claim!r} is not of the form A->B, A<->B or A!<->B")
    a, op, b = match.groups()
    seen = relation(net, a, b)
    if seen is None or _degenerate(net, a, b):
        return None, None
    if op == "->":
        return seen == f"{a}->{b}", seen
    if op == "<->":
        return seen == f"{a}<->{b}", seen
    return seen != f"{a}<->{b}", seen


DEGENERATE = "degenerate recurrence structure (a signal barely moves in the window)"


def _degenerate(net: Any, a: str, b: str) -> bool:
    """Whether the pair of ``a`` and ``b`` is flagged ``degenerate`` (False without the column)."""
    table = _pairs(net)
    if "degenerate" not in table.columns:
        return False
    pair = table[table["x"].isin((a, b)) & table["y"].isin((a, b))]
    # Rows of older results mixed with newer ones hold NaN there: not degenerate.
    return bool(pair["degenerate"].eq(True).any())


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


def _nodes(net: Any) -> set[str]:
    if isinstance(net, pd.DataFrame):
        return {*net["x"], *net["y"]}
    return set(net.nodes)


def _why_not_evaluable(claim: str, net: Any, left_out: Sequence[str]) -> str:
    """Why a claim cannot be evaluated in a network: a signal it lacks, or a degenerate pair."""
    absent = [s for s in dict.fromkeys(re.findall(r"\w+", claim)) if s not in _nodes(net)]
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
    networks : mapping of key -> FunctionalNetwork, pairs table or None
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
    >>> net = pd.DataFrame({"x": ["RP", "RP"], "y": ["AP", "MP"], "kind": ["x->y", "y->x"]})
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
        # A claim about a node the network lacks (a signal constant in the window) or about a
        # degenerate pair is not evaluable; the network still counts for its other claims,
        # never as a full match.
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


def _drive(sources: Sequence[str], targets: Sequence[str]) -> tuple[str, ...]:
    return tuple(f"{s}->{t}" for s in sources for t in targets if s != t)


def _cluster(nodes: Sequence[str]) -> tuple[str, ...]:
    return tuple(f"{a}<->{b}" for k, a in enumerate(nodes) for b in nodes[k + 1:])


# Phase keys used by the specs; run_paper_analyses maps detected phases onto them.
EARLY, LATE, CRUISE, BRAKING, SPIN_UP = ("early spin-up", "late spin-up", "cruise", "braking",
                                         "spin-up")

#: Section 4.1 (Fig. 9), keyed by baseline phase.
BASELINE: tuple[FindingSpec, ...] = (
    FindingSpec("4.1-early-rp-drives", "4.1",
                "Early spin-up: strong outward edges from RP to AP and MP (motion initiated by "
                "the reference position).", {EARLY: _drive(["RP"], ["AP", "MP"])}),
    FindingSpec("4.1-early-ap-v", "4.1", "Early spin-up: a bidirectional edge between AP and V.",
                {EARLY: ("AP<->V",)}),
    FindingSpec("4.1-early-rc-ac", "4.1", "Early spin-up: RC and AC form a coupled "
                "(bidirectional) pair.", {EARLY: ("RC<->AC",)}),
    FindingSpec("4.1-early-currents-drive", "4.1",
                "Early spin-up: outgoing edges from RC and AC to all other variables.",
                {EARLY: _drive(CURRENTS, MOTION)}),
    FindingSpec("4.1-late-cluster-drives", "4.1",
                "Late spin-up: bidirectional edges between RP, AP and MP; outgoing edges from "
                "the position variables to V, RC and AC.",
                {LATE: _cluster(POSITIONS) + _drive(POSITIONS, ("V", *CURRENTS))}),
    FindingSpec("4.1-cruise-cluster-drives", "4.1",
                "Cruise: the RP-AP-MP cluster remains intact; directed edges from the position "
                "cluster to V, RC and AC persist.",
                {CRUISE: _cluster(POSITIONS) + _drive(POSITIONS, ("V", *CURRENTS))}),
    FindingSpec("4.1-braking-currents-drive", "4.1",
                "Braking: RC and AC show outward edges toward all other motion variables.",
                {BRAKING: _drive(CURRENTS, MOTION)}),
    FindingSpec("4.1-braking-ap-drives", "4.1", "Braking: AP projects outward to MP and RP.",
                {BRAKING: _drive(["AP"], ["MP", "RP"])}),
)

VELOCITIES = ("V1", "V35", "V175", "V350")
VELOCITY_PHASES = (SPIN_UP, CRUISE, BRAKING)

#: Section 4.2 (Fig. 10), keyed by (velocity label, phase).
VELOCITY: tuple[FindingSpec, ...] = (
    FindingSpec("4.2-spinup-ap-v", "4.2",
                "Spin-up: the AP-V edge is bidirectional at V35; at higher speed it turns "
                "directed, V->AP at V175 and AP->V at V350 (section 5.1).",
                {("V35", SPIN_UP): ("AP<->V",), ("V175", SPIN_UP): ("V->AP",),
                 ("V350", SPIN_UP): ("AP->V",)}, unit="conditions"),
    FindingSpec("4.2-cruise-v-currents", "4.2",
                "Cruise: the currents drive V at low speed (V35); V drives the currents at "
                "V175 and V350.",
                {("V35", CRUISE): _drive(CURRENTS, ["V"]),
                 ("V175", CRUISE): _drive(["V"], CURRENTS),
                 ("V350", CRUISE): _drive(["V"], CURRENTS)}, unit="conditions"),
    FindingSpec("4.2-v1-two-clusters", "4.2",
                "V1 cruise: two relatively independent clusters, RP-AP-MP and V-RC-AC (read as: "
                "bidirectional inside each cluster, no bidirectional edge across).",
                {("V1", CRUISE): _cluster(POSITIONS) + _cluster(("V", *CURRENTS))
                 + tuple(f"{a}!<->{b}" for a in POSITIONS for b in ("V", *CURRENTS))}),
    FindingSpec("4.2-v1-braking-mp-ap", "4.2", "V1 braking: an outward connection from MP to AP.",
                {("V1", BRAKING): ("MP->AP",)}),
    FindingSpec("4.2-rc-ac-everywhere", "4.2",
                "The bidirectional RC-AC edge is preserved in all conditions (4 speeds x 3 "
                "phases).", {(v, p): ("RC<->AC",) for v in VELOCITIES for p in VELOCITY_PHASES},
                unit="conditions"),
    FindingSpec("4.2-cruise-position-cluster", "4.2",
                "The position cluster (RP-AP-MP) remains well-defined during cruise at every "
                "speed.", {(v, CRUISE): _cluster(POSITIONS) for v in VELOCITIES},
                unit="conditions"),
    FindingSpec("4.2-braking-currents-drive", "4.2",
                "Braking networks consistently show outward influence from RC and AC to the "
                "motion variables at every speed.",
                {(v, BRAKING): _drive(CURRENTS, MOTION) for v in VELOCITIES}, unit="conditions"),
)

#: Section 4.3 (Fig. 11): the reversal signature in the window centred on the reversal.
REVERSAL_AT_ZERO = {
    "4.3-v-drives": ("Reversal (0 ms): velocity is the dominant driver, with outward edges to "
                     "all other parameters.", _drive(["V"], ["RP", "AP", "MP", *CURRENTS])),
    "4.3-position-chain": ("Reversal (0 ms): MP projects to AP and RP, AP projects to RP.",
                           ("MP->AP", "MP->RP", "AP->RP")),
}

#: Section 4.3: what each shifted window shows, by offset in ms.
REVERSAL_SEQUENCE: Mapping[int, tuple[str, ...]] = {
    -40: _drive(CURRENTS, MOTION),
    -20: ("V<->RC", "V<->AC"),
    0: REVERSAL_AT_ZERO["4.3-v-drives"][1] + REVERSAL_AT_ZERO["4.3-position-chain"][1],
    20: REVERSAL_AT_ZERO["4.3-v-drives"][1] + REVERSAL_AT_ZERO["4.3-position-chain"][1],
    40: ("AP<->RP", "MP->AP", "MP->RP", "V<->RC", "V<->AC"),
}


def baseline_findings(networks: Mapping[Any, Any], *,
                      left_out: Mapping[Any, Sequence[str]] | None = None) -> list[Finding]:
    """Section 4.1 on the baseline trial's phase networks.

    Parameters
    ----------
    networks : mapping of phase -> FunctionalNetwork (or pairs table, or None)
        Keys ``"early spin-up"``, ``"late spin-up"``, ``"cruise"``, ``"braking"``.
    left_out : mapping of phase -> sequence of str, optional
        Signals left out of a phase's network as constant (see :func:`evaluate`).

    Returns
    -------
    list of Finding
        One per statement of :data:`BASELINE`.

    References
    ----------
    Paper section 4.1 and Fig. 9.
    """
    return [evaluate(spec, networks, left_out=left_out) for spec in BASELINE]


def velocity_findings(networks: Mapping[Any, Any], *,
                      left_out: Mapping[Any, Sequence[str]] | None = None) -> list[Finding]:
    """Section 4.2 on the networks of the four velocity trials.

    Parameters
    ----------
    networks : mapping of (velocity, phase) -> FunctionalNetwork (or pairs table, or None)
        Velocities ``"V1", "V35", "V175", "V350"``; phases ``"spin-up", "cruise", "braking"``
        (fixed windows of 280 / 600 / 600 ms).
    left_out : mapping of (velocity, phase) -> sequence of str, optional
        Signals left out of a network as constant (see :func:`evaluate`).

    Returns
    -------
    list of Finding
        One per statement of :data:`VELOCITY`, then :func:`edge_thinning`.

    References
    ----------
    Paper section 4.2 and Fig. 10.
    """
    return [*(evaluate(spec, networks, left_out=left_out) for spec in VELOCITY),
            edge_thinning(networks)]


def _mean_weight(net: Any) -> float:
    """Mean weight (Eq. 13) of the network's edges (conflicts have none)."""
    pairs = _pairs(net)
    drawn = pairs.loc[pairs["kind"] != "conflict", "weight"]
    return float(drawn.mean()) if len(drawn) else 0.0


def _spearman(a: Sequence[float], b: Sequence[float]) -> float:
    ra = pd.Series(a).rank().to_numpy()
    rb = pd.Series(b).rank().to_numpy()
    if np.std(ra) == 0 or np.std(rb) == 0:
        return 0.0
    return float(np.corrcoef(ra, rb)[0, 1])


def edge_thinning(networks: Mapping[Any, Any], *,
                  speeds: Mapping[str, float] | None = None, rho: float = -0.8) -> Finding:
    """Section 4.2: "as velocity increases, the connections generally become thinner".

    Per phase, the mean edge weight (Eq. 13) of each speed's network is ranked against the speed
    (Spearman); a phase counts as thinning when ``ρ ≤ rho`` (with four speeds, -0.8 allows one
    swap of neighbours); a phase with fewer than two speeds' networks is not evaluable. Decided
    as ``"yes"`` when every phase was evaluated and thins, ``"partly"`` when some do, ``"no"``
    when none of the evaluated phases does, ``"not evaluable"`` when no phase could be.

    Parameters
    ----------
    networks : mapping of (velocity, phase) -> FunctionalNetwork (or pairs table, or None)
        As for :func:`velocity_findings`.
    speeds : mapping of velocity label -> °/min, optional
        Defaults to V1 = 1, V35 = 35, V175 = 175, V350 = 350.
    rho : float
        Largest rank correlation that counts as thinning.

    Returns
    -------
    Finding
        Evidence: the phases that thin and every mean weight.

    References
    ----------
    Paper sections 4.2 and 5.1 ("edges become thinner at higher speeds").

    Examples
    --------
    >>> import pandas as pd
    >>> def net(w):
    ...     return pd.DataFrame({"x": ["A"], "y": ["B"], "kind": ["x->y"], "weight": [w]})
    >>> nets = {(v, p): net(w) for p in ("spin-up", "cruise", "braking")
    ...         for v, w in (("V1", .4), ("V35", .3), ("V175", .2), ("V350", .1))}
    >>> edge_thinning(nets).reproduced
    'yes'
    """
    speeds = dict(speeds or {"V1": 1.0, "V35": 35.0, "V175": 175.0, "V350": 350.0})
    phases = list(dict.fromkeys(p for _, p in networks))
    thinning, parts, unevaluated = [], [], []
    for phase in phases:
        rows = [(speeds[v], _mean_weight(n)) for (v, p), n in networks.items()
                if p == phase and n is not None and v in speeds]
        if len(rows) < 2:
            unevaluated.append(f"{phase}: {len(rows)} speed(s) with a network")
            continue
        rows.sort()
        r = _spearman([s for s, _ in rows], [w for _, w in rows])
        thinning.append(r <= rho)
        parts.append(f"{phase}: ρ={r:+.2f} (" + ", ".join(f"{s:g}°/min {w:.3f}" for s, w in rows)
                     + ")")
    n = sum(thinning)
    if not thinning:
        reproduced = "not evaluable"
    elif n == len(phases):
        reproduced = "yes"
    else:
        reproduced = "partly" if n else "no"
    evidence = (f"{n}/{len(thinning)} phases thin with speed (Spearman ρ ≤ {rho}); mean weights: "
                + "; ".join(parts))
    if unevaluated:
        evidence += (f"; {len(unevaluated)} of {len(phases)} phases could not be evaluated: "
                     + ", ".join(unevaluated))
    return Finding("4.2-edges-thin", "4.2",
                   "Edges become thinner as speed grows, in all motion phases.", reproduced,
                   evidence, tuple(parts), (), tuple(unevaluated))


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

    In each trial every offset's window is checked against :data:`REVERSAL_SEQUENCE`. The
    sequence *appears* in a trial when every window shows all its claimed relations, and
    *largely appears* when every window shows at least half of them (the paper: "resembles",
    "largely present"); a claim that cannot be evaluated (no network, a signal left out of it,
    or a degenerate pair) counts as not shown, and the evidence says how many. ``"yes"`` when
    it appears in every trial, ``"partly"`` when it largely appears in at least one, ``"no"``
    otherwise, and ``"not evaluable"`` when no claim of any trial could be evaluated.

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


def design_effect(
    networks: Mapping[Any, Any],
    trials: pd.DataFrame,
    factor: str,
    *,
    label: Callable[[Any], str] = str,
) -> Finding:
    """How much the networks change with one factor of the design (TCP distance or step size).

    Beyond the paper (section 3.1 varies TCP distance and step size; section 4 reports neither).
    The trials are grouped by every other factor of ``trials`` (speed, step or TCP, and phase);
    in each group the relation of every pair is compared across the factor's levels. Reported:
    the share of pair relations identical across all levels, the same share across the speeds
    for scale, and the mean edge weight per level.

    Parameters
    ----------
    networks : mapping of (trial name, phase) -> FunctionalNetwork (or pairs table, or None)
        The main trials' networks.
    trials : pandas.DataFrame
        One row per trial: ``name, speed, tcp, step``.
    factor : {"tcp", "step"}
        The factor whose effect is measured.
    label : callable
        Formats a level for the evidence.

    Returns
    -------
    Finding
        ``reproduced="n/a"``; the evidence holds the counts.

    References
    ----------
    Paper section 3.1 and Table 1.
    """
    factors = ("speed", "tcp", "step")
    if factor not in factors:
        raise ParameterError(f"factor must be one of {factors}, not {factor!r}")
    by_name = trials.set_index("name")

    def share_identical(varied: str) -> tuple[int, int]:
        fixed = [f for f in factors if f != varied]
        groups: dict[tuple, dict[Any, Any]] = {}
        for (name, phase), net in networks.items():
            if net is None or name not in by_name.index:
                continue
            row = by_name.loc[name]
            groups.setdefault((*(row[f] for f in fixed), phase), {})[row[varied]] = net
        same = total = 0
        for nets in groups.values():
            if len(nets) < 2:
                continue
            tables = [_pairs(n) for n in nets.values()]
            for pair in tables[0].itertuples(index=False):
                kinds = {relation(t, pair.x, pair.y) for t in tables}
                total += 1
                same += len(kinds) == 1
        return same, total

    same, total = share_identical(factor)
    same_speed, total_speed = share_identical("speed")
    weights: dict[Any, list[float]] = {}
    for (name, _), net in networks.items():
        if net is not None and name in by_name.index:
            weights.setdefault(by_name.loc[name, factor], []).append(_mean_weight(net))
    levels = sorted(weights)
    means = ", ".join(f"{label(v)}: {np.mean(weights[v]):.3f}" for v in levels)
    name = {"tcp": "TCP distance", "step": "step size", "speed": "speed"}[factor]
    pct = 100 * same / total if total else float("nan")
    pct_speed = 100 * same_speed / total_speed if total_speed else float("nan")
    evidence = (f"pair relations identical across all {name} levels: {same}/{total} ({pct:.0f} %)"
                f"; across speeds, for comparison: {same_speed}/{total_speed} "
                f"({pct_speed:.0f} %); mean edge weight by {name}: {means}")
    statement = (f"Effect of {name} on the networks (main trials, every phase): not reported in "
                 "the paper; measured here.")
    return Finding(f"3.1-{factor}", "3.1", statement, "n/a", evidence)


# --------------------------------------------------------------------------------------------
# the analyses of the paper's section 4 on a plan of trials

#: Network parameters of :func:`run_paper_analyses`. The paper states RR = CR = μ = 0.05 and
#: min-max normalization (section 3.3-3.4) but not m and τ for the robot data; m = 3, τ = 10
#: samples (20 ms at 500 Hz) are its illustration's values (section 2.1), kept here.
PAPER_PARAMETERS: dict[str, Any] = {"dim": 3, "delay": 10, "rr": 0.05, "cr": 0.05, "mu": 0.05,
                                    "metric": "euclidean", "normalize": "minmax",
                                    "measure": "both", "rule": "funcnet", "theiler": 0}
PAPER_SIGNALS = PAPER_NODES
BASELINE_PHASES = (EARLY, LATE, CRUISE, BRAKING)


@dataclass(frozen=True)
class TrialAnalysis:
    """The networks of one trial's windows.

    Attributes
    ----------
    trial : str
        The trial's name (``manifest.csv``).
    path : str
        The trace read.
    data : pandas.DataFrame
        The analysed signals over the whole recording (V derived before windowing).
    phases : pandas.DataFrame
        The detected phases (``phase, start, stop``).
    windows : dict
        Key -> :class:`funcnet.robot.windows.Window` (key: phase name, offset in ms, or window
        centre in s).
    networks : dict
        Key -> :class:`funcnet.FunctionalNetwork`, or ``None`` where it could not be computed.
    errors : dict
        Key -> why there is no network.
    dropped : dict
        Key -> signals left out of that window's network because they are constant in it
        (min-max normalization needs a range; e.g. AP before the breakaway).
    """

    trial: str
    path: str
    data: pd.DataFrame
    phases: pd.DataFrame
    windows: dict[Any, Any]
    networks: dict[Any, Any]
    errors: dict[Any, str]
    dropped: dict[Any, tuple[str, ...]] = field(default_factory=dict)

    def window_data(self, key: Any) -> pd.DataFrame:
        """The analysed signals inside window ``key``, ``start <= time < stop``."""
        return _inside(self.data, self.windows[key])


def _inside(data: pd.DataFrame, window: Any) -> pd.DataFrame:
    return data.loc[(data.index >= window.start) & (data.index < window.stop)]


@dataclass(frozen=True)
class PaperAnalyses:
    """Everything :func:`run_paper_analyses` computed.

    Attributes
    ----------
    plan_dir : str
        The plan folder.
    parameters : dict
        Network parameters, signals, window lengths and caps used.
    trials : pandas.DataFrame
        The plan's manifest.
    baseline : TrialAnalysis or None
        The baseline trial's phase networks (section 4.1).
    velocity : dict
        ``"V1", "V35", "V175", "V350"`` -> fixed-window networks (section 4.2).
    reversal : dict
        Backlash trial -> networks keyed by offset in ms (section 4.3).
    main : dict
        Main trial -> fixed-window networks (TCP distance and step size, section 3.1).
    timeline : TrialAnalysis or None
        Sliding windows over the baseline trial, keyed by window centre (beyond the paper).
    findings : tuple of Finding
        The measured findings.
    inputs : dict
        File -> SHA-256 of every input read.
    warnings : dict
        Warning message -> how many networks raised it.
    elapsed : float
        Seconds spent.
    """

    plan_dir: str
    parameters: dict[str, Any]
    trials: pd.DataFrame
    baseline: TrialAnalysis | None
    velocity: dict[str, TrialAnalysis]
    reversal: dict[str, TrialAnalysis]
    main: dict[str, TrialAnalysis]
    timeline: TrialAnalysis | None
    findings: tuple[Finding, ...]
    inputs: dict[str, str]
    warnings: dict[str, int]
    elapsed: float

    def groups(self) -> dict[str, dict[str, TrialAnalysis]]:
        """The analyses by purpose, each trial once per purpose (for tables)."""
        single = {t.trial: t for t in (self.baseline,) if t is not None}
        v1 = {t.trial: t for k, t in self.velocity.items() if k == "V1"}
        timeline = {t.trial: t for t in (self.timeline,) if t is not None}
        return {"baseline phases (section 4.1)": single,
                "static-friction trial V1 (section 4.2)": v1,
                "main trials, fixed windows (sections 4.2, 3.1)": self.main,
                "backlash trials, reversal windows (section 4.3)": self.reversal,
                "baseline, sliding windows (beyond the paper)": timeline}


def _select(trials: pd.DataFrame, **where: Any) -> pd.DataFrame:
    mask = np.ones(len(trials), dtype=bool)
    for column, value in where.items():
        column_values = trials[column]
        if isinstance(value, bool):
            mask &= column_values.astype(str).str.lower().isin(["true", "1"]) == value
        elif isinstance(value, str):
            mask &= column_values.astype(str) == value
        else:
            mask &= np.isclose(column_values.astype(float), value)
    return trials[mask]


def main_move(phases: pd.DataFrame) -> pd.DataFrame:
    """The phases of a trial's longest motion (a run of phases between standstills).

    A trial of the plan is one motion (a backlash trial's reversal joins its forward and reverse
    moves into one); phase detection on a slow, quantized reference can add moves of a few ms
    at its ends, which are left out here.

    Parameters
    ----------
    phases : pandas.DataFrame
        ``phase, start, stop`` from :func:`funcnet.robot.detect_phases`.

    Returns
    -------
    pandas.DataFrame
        The rows of the longest run, standstill excluded.

    Examples
    --------
    >>> import pandas as pd
    >>> table = pd.DataFrame({"phase": ["cruise", "standstill", "early spin-up", "cruise"],
    ...                       "start": [0.0, 0.01, 0.5, 0.7], "stop": [0.01, 0.5, 0.7, 3.0]})
    >>> main_move(table)["phase"].tolist()
    ['early spin-up', 'cruise']
    """
    moving = (phases["phase"] != "standstill").to_numpy()
    run_id = np.cumsum(~moving)
    runs = [phases[moving & (run_id == k)] for k in np.unique(run_id[moving])]
    if not runs:
        return phases.iloc[:0]
    return max(runs, key=lambda run: float(run["stop"].max() - run["start"].min()))


def _analyse(name: str, path: Path, recording: Any,
             keyed_windows: Callable[[Any, pd.DataFrame], dict], signals: Sequence[str],
             parameters: Mapping[str, Any], warned: dict[str, int]) -> TrialAnalysis:
    """Detect a trial's phases, build its windows and compute one network per window."""
    import warnings

    from funcnet.errors import FuncnetError
    from funcnet.robot import detect_phases, phase_networks

    data = recording.data[list(signals)]
    windows: dict[Any, Any] = {}
    networks: dict[Any, Any] = {}
    errors: dict[Any, str] = {}
    dropped: dict[Any, tuple[str, ...]] = {}
    try:
        phases = detect_phases(recording)
        windows = keyed_windows(recording, main_move(phases))
    except FuncnetError as exc:
        return TrialAnalysis(name, str(path), data, pd.DataFrame(columns=["phase", "start",
                                                                          "stop"]),
                             {}, {}, {"windows": str(exc)})
    for key, window in windows.items():
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                (net,) = phase_networks(recording, [window], signals=signals, constant="drop",
                                        **parameters).values()
            except FuncnetError as exc:
                net = None
                errors[key] = str(exc)
        if net is not None and net.parameters["dropped"]:
            dropped[key] = tuple(net.parameters["dropped"])
        for w in caught:
            # Count by kind of warning: its first line (the windows it names are on the next).
            message = f"{w.category.__name__}: {str(w.message).splitlines()[0]}"
            warned[message] = warned.get(message, 0) + 1
        networks[key] = net
    return TrialAnalysis(name, str(path), data, phases, windows, networks, errors, dropped)


def run_paper_analyses(
    plan_dir: Any,
    *,
    progress: Callable[..., None] | None = None,
    signals: Sequence[str] = PAPER_SIGNALS,
    max_phase_length: float = 4.0,
    fixed_lengths: Mapping[str, float] | None = None,
    reversal_width: float | None = 0.2,
    timeline_width: float = 0.6,
    timeline_step: float = 0.2,
    **network_parameters: Any,
) -> PaperAnalyses:
    """The paper's section 4 analyses on a plan of trials, with every finding measured.

    Reads ``manifest.csv`` and the traces of ``plan_dir`` (:func:`funcnet.robot.write_plan`),
    derives V from AP (Eq. 11-12) over each whole recording, detects the phases from RP
    (:func:`funcnet.robot.detect_phases`) and computes (:func:`funcnet.robot.phase_networks`):

    - the baseline trial (35 °/min, 3°, TCP 1.6 m): one network per phase (early spin-up, late
      spin-up, cruise, braking; section 4.1), each phase window cut to ``max_phase_length``
      seconds from its start;
    - every main trial and the static-friction trial at TCP 1.6 m: fixed windows of 280 / 600 /
      600 ms anchored at spin-up, cruise and braking (section 4.2); V1 = 1 °/min (1°),
      V35 = the baseline, V175 = 175 °/min (3°), V350 = 350 °/min (10°), all at TCP 1.6 m;
    - every backlash trial: windows around the reversal shifted by -40, -20, 0, +20, +40 ms
      (section 4.3);
    - the baseline trial in sliding windows (beyond the paper);

    then measures the findings (:func:`baseline_findings`, :func:`velocity_findings`,
    :func:`reversal_findings`, :func:`design_effect` for TCP and step).

    Parameters
    ----------
    plan_dir : path-like
        Folder with ``manifest.csv`` and the traces it names.
    progress : callable, optional
        ``progress(done, total, description)``.
    signals : sequence of str
        The nodes (default the paper's RP, AP, MP, V, RC, AC).
    max_phase_length : float
        Longest baseline phase window in seconds (the cost of a network grows with the cube of
        its length; the paper's cruise is 4 s).
    fixed_lengths : mapping, optional
        Fixed window lengths by anchor; default 280 / 600 / 600 ms.
    reversal_width : float or None
        Width of the reversal windows in seconds, centred on the detected reversal phase's
        middle (``None``: the phase's own span). The paper does not state it; its Fig. 11b shows
        all five windows inside the 300 ms reversal region, so a window is at most 220 ms wide:
        200 ms (100 samples) by default.
    timeline_width, timeline_step : float
        Sliding windows of the timeline, seconds.
    **network_parameters
        Override :data:`PAPER_PARAMETERS` (``dim``, ``delay``, ``rr``, ``cr``, ``mu``,
        ``metric``, ``normalize``, ``measure``, ``rule``, ``theiler``).

    Returns
    -------
    PaperAnalyses
        Networks, findings, parameters, input hashes.

    Raises
    ------
    funcnet.errors.TraceError
        ``manifest.csv`` is missing or a trace cannot be read.
    funcnet.errors.ParameterError
        An unknown network parameter.

    Notes
    -----
    Only the phases of each trial's main motion are used (:func:`main_move`). A signal constant
    inside a window (AP before the breakaway, at low speed) cannot be min-max normalized: it is
    left out of that window's network (:func:`funcnet.robot.phase_networks` with
    ``constant="drop"``) and listed in ``dropped``; the findings count claims
    about it as not evaluable. Windows whose network cannot be computed at all (e.g. a window
    reaching past the recording) are kept as ``None`` with the reason. Nothing is tuned to the
    paper's results: the parameters are the paper's where it gives them and fixed beforehand
    where it does not.

    References
    ----------
    Paper sections 3.3-3.4 and 4 (Fig. 9, 10, 11); section 3.1 (Table 1).
    """
    import time

    from funcnet._io import file_sha256
    from funcnet.errors import TraceError
    from funcnet.robot.windows import (
        fixed_windows,
        phase_windows,
        reversal_windows,
        sliding_windows,
    )
    from funcnet.study import read_recording

    started = time.perf_counter()
    unknown = sorted(set(network_parameters) - set(PAPER_PARAMETERS))
    if unknown:
        raise ParameterError(f"unknown network parameters {unknown}; known: "
                             f"{sorted(PAPER_PARAMETERS)}")
    parameters = {**PAPER_PARAMETERS, **network_parameters}
    plan = Path(plan_dir)
    manifest = plan / "manifest.csv"
    if not manifest.is_file():
        raise TraceError(manifest, "no manifest.csv: not a plan written by funcnet simulate")
    trials = pd.read_csv(manifest)
    inputs = {"manifest.csv": file_sha256(manifest)}
    warned: dict[str, int] = {}

    loaded: dict[str, tuple[Path, Any]] = {}

    def load(row: Any) -> tuple[Path, Any]:
        """A trial's trace, with V derived over the whole recording; read and hashed once."""
        if row["name"] not in loaded:
            path = plan / str(row["file"])
            inputs[path.name] = file_sha256(path)
            loaded[row["name"]] = (path, read_recording(path, signals=signals))
        return loaded[row["name"]]

    def fixed(recording: Any, phases: pd.DataFrame) -> dict:
        return {w.label: w for w in fixed_windows(phases, fixed_lengths)}

    def by_phase(recording: Any, phases: pd.DataFrame) -> dict:
        windows = {}
        for w in phase_windows(phases, include=BASELINE_PHASES):
            stop = min(w.stop, w.start + max_phase_length)
            windows[w.label] = dataclasses.replace(w, stop=stop)
        return windows

    def reversal(recording: Any, phases: pd.DataFrame) -> dict:
        return {int(round(w.offset * 1000)): w
                for w in reversal_windows(phases, width=reversal_width)}

    main = _select(trials, group="main")
    baseline_rows = _select(main, speed=35, step=3, tcp=1.6)
    v1_rows = _select(trials, speed=1, tcp=1.6)
    backlash = _select(trials, reverse=True)
    total = len(main) + len(v1_rows) + len(backlash) + 2 * len(baseline_rows)
    done = 0

    def tick(description: str) -> None:
        nonlocal done
        if progress is not None:
            progress(done, total, description)
        done += 1

    main_analyses: dict[str, TrialAnalysis] = {}
    for _, row in main.iterrows():
        tick(f"main trial {row['name']}")
        main_analyses[row["name"]] = _analyse(row["name"], *load(row), fixed, signals,
                                              parameters, warned)
    baseline = timeline = None
    for _, row in baseline_rows.head(1).iterrows():
        tick(f"baseline phases {row['name']}")
        baseline = _analyse(row["name"], *load(row), by_phase, signals, parameters, warned)
        tick(f"baseline timeline {row['name']}")
        moving = baseline.phases[baseline.phases["phase"] != "standstill"]
        span = ((float(moving["start"].min()), float(moving["stop"].max()))
                if len(moving) else (None, None))

        def sliding(recording: Any, phases: pd.DataFrame, span: tuple = span) -> dict:
            return {round((w.start + w.stop) / 2, 6): w for w in
                    sliding_windows(recording, timeline_width, timeline_step, start=span[0],
                                    stop=span[1])}

        timeline = _analyse(row["name"], *load(row), sliding, signals, parameters, warned)
    velocity: dict[str, TrialAnalysis] = {}
    for _, row in v1_rows.head(1).iterrows():
        tick(f"static-friction trial {row['name']}")
        velocity["V1"] = _analyse(row["name"], *load(row), fixed, signals, parameters, warned)
    for label, speed, step in (("V35", 35, 3), ("V175", 175, 3), ("V350", 350, 10)):
        rows = _select(main, speed=speed, step=step, tcp=1.6)
        if len(rows):
            velocity[label] = main_analyses[rows["name"].iloc[0]]
    reversal_analyses: dict[str, TrialAnalysis] = {}
    for _, row in backlash.iterrows():
        tick(f"backlash trial {row['name']}")
        reversal_analyses[row["name"]] = _analyse(row["name"], *load(row), reversal, signals,
                                                  parameters, warned)
    velocity = {k: velocity[k] for k in VELOCITIES if k in velocity}

    findings = [
        *baseline_findings(baseline.networks if baseline is not None else {},
                           left_out=baseline.dropped if baseline is not None else {}),
        *velocity_findings({(label, phase): analysis.networks.get(phase)
                            for label, analysis in velocity.items()
                            for phase in VELOCITY_PHASES},
                           left_out={(label, phase): analysis.dropped.get(phase, ())
                                     for label, analysis in velocity.items()
                                     for phase in VELOCITY_PHASES}),
        *reversal_findings({name: a.networks for name, a in reversal_analyses.items()},
                           left_out={name: a.dropped for name, a in reversal_analyses.items()}),
    ]
    design_networks = {(name, phase): net for name, a in main_analyses.items()
                       for phase, net in a.networks.items()}
    design_trials = main[["name", "speed", "tcp", "step"]]
    findings.append(design_effect(design_networks, design_trials, "tcp",
                                  label=lambda v: f"{v:g} m"))
    findings.append(design_effect(design_networks, design_trials, "step",
                                  label=lambda v: f"{v:g}°"))
    if progress is not None:
        progress(total, total, "analyses done")
    recorded = {
        **parameters,
        "signals": ", ".join(signals),
        "dim, delay (choice)": ("the paper states neither for the robot data; its section 2.1 "
                                "illustration's m = 3, τ = 10 samples (20 ms at 500 Hz) are "
                                "used"),
        "phases": "detected from RP (funcnet.robot.detect_phases), main motion only",
        "baseline phase windows": f"detected phases, each cut to at most {max_phase_length:g} s",
        "fixed windows [s]": ", ".join(f"{k} {v:g}" for k, v in (
            fixed_lengths or {"spin-up": 0.28, "cruise": 0.6, "braking": 0.6}).items()),
        "reversal windows": ("shifts -40, -20, 0, +20, +40 ms; width "
                             + ("the detected reversal phase's span" if reversal_width is None
                                else f"{reversal_width:g} s")),
        "timeline windows": f"sliding, {timeline_width:g} s every {timeline_step:g} s",
    }
    return PaperAnalyses(str(plan), recorded, trials, baseline, velocity, reversal_analyses,
                         main_analyses, timeline, tuple(findings), inputs, warned,
                         time.perf_counter() - started)
