"""The paper's section 4 findings as data: a small claim language and the claims made in it.

A *claim* names two signals and the relation the paper reports between them, in the network's
own kind vocabulary (:data:`funcnet.network.schema.PAIR_KINDS`), read with ``A`` as ``x`` and
``B`` as ``y``:

=============  ===================  ==================================================
claim          pair kind            meaning
=============  ===================  ==================================================
``A->B``       ``x->y``             A drives B (a directed edge A → B)
``A<->B``      ``bidirectional``    a bidirectional edge (coupling both ways, or none)
``A-/-B``      ``conflict``         C_diff and T_diff disagree: no edge
``A!<->B``     anything but         not bidirectional: directed either way, or no edge
               ``bidirectional``
=============  ===================  ==================================================

The same arrows are used for what a network shows between two signals
(:func:`funcnet.paper.evaluate.relation`), so a claim and a seen relation read alike.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", section 4
   (4.1 baseline, Fig. 9; 4.2 velocity, Fig. 10; 4.3 backlash, Fig. 11) and section 3.1
   (Table 1, the design of experiments).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from funcnet.errors import ParameterError
from funcnet.network.schema import PAIR_KINDS

__all__ = [
    "REPRODUCED",
    "OPERATORS",
    "Claim",
    "parse_claim",
    "Finding",
    "FindingSpec",
    "POSITIONS",
    "CURRENTS",
    "MOTION",
    "EARLY",
    "LATE",
    "CRUISE",
    "BRAKING",
    "SPIN_UP",
    "BASELINE_PHASES",
    "BASELINE",
    "VELOCITIES",
    "VELOCITY_PHASES",
    "VELOCITY",
    "REVERSAL_AT_ZERO",
    "REVERSAL_SEQUENCE",
]

#: The verdicts of a finding (see :mod:`funcnet.paper.evaluate` for the rule).
REPRODUCED = ("yes", "partly", "no", "not evaluable", "n/a")

_X_Y, _Y_X, _BIDIRECTIONAL, _CONFLICT = PAIR_KINDS
#: Claim operator -> the pair kind it claims (``!<->``: any kind but bidirectional).
OPERATORS: Mapping[str, str] = {"->": _X_Y, "<->": _BIDIRECTIONAL, "-/-": _CONFLICT,
                                "!<->": _BIDIRECTIONAL}
_CLAIM = re.compile(r"^\s*(\w+)\s*(!<->|<->|-/-|->)\s*(\w+)\s*$")

POSITIONS = ("RP", "AP", "MP")
CURRENTS = ("RC", "AC")
MOTION = ("RP", "AP", "MP", "V")


@dataclass(frozen=True)
class Claim:
    """One claimed relation between signals ``a`` and ``b``.

    Attributes
    ----------
    a, b : str
        The signals, in the order written (``a`` plays ``x``).
    kind : str
        The claimed pair kind of (a, b), one of :data:`funcnet.network.schema.PAIR_KINDS`.
    negated : bool
        True for ``A!<->B``: the claim holds when the kind is anything *but* ``kind``.
    """

    a: str
    b: str
    kind: str
    negated: bool = False

    def holds(self, seen: str) -> bool:
        """Whether the pair kind ``seen`` of (a, b) is what the claim says."""
        return (seen != self.kind) if self.negated else (seen == self.kind)


def parse_claim(text: str) -> Claim:
    """A claim written ``A->B``, ``A<->B``, ``A-/-B`` or ``A!<->B``.

    Parameters
    ----------
    text : str
        The claim (spaces around the operator are allowed).

    Returns
    -------
    Claim

    Raises
    ------
    ParameterError
        ``text`` is not of one of the four forms.

    Examples
    --------
    >>> parse_claim("RP->AP")
    Claim(a='RP', b='AP', kind='x->y', negated=False)
    >>> parse_claim("V!<->RC").holds("y->x")
    True
    >>> parse_claim("RP => AP")
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: claim 'RP => AP' is not of the form A->B, A<->B, A-/-B or A!<->B
    """
    match = _CLAIM.match(text)
    if match is None:
        raise ParameterError(
            f"claim {text!r} is not of the form A->B, A<->B, A-/-B or A!<->B")
    a, op, b = match.groups()
    return Claim(a, b, OPERATORS[op], negated=op == "!<->")


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
        ``"yes"``, ``"partly"``, ``"no"``, ``"not evaluable"`` or ``"n/a"``
        (:mod:`funcnet.paper.evaluate` states the rule).
    evidence : str
        Counts, e.g. ``"4/6 trials show all claimed relations; 26/30 relations hold"``.
    edges_seen : tuple of str
        The relations actually seen where the claim was checked, ``"[where] RP->AP"``.
    expected : tuple of str
        The claimed relations, ``"[where] RP->AP"``.
    not_evaluable : tuple of str
        The claims that could not be evaluated and why, ``"[where] AP<->V: AP, V constant in
        the window, left out of its network"``.

    Raises
    ------
    ParameterError
        ``reproduced`` is not one of :data:`REPRODUCED`.

    Examples
    --------
    >>> Finding("x", "4.1", "s", "maybe", "e")
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: reproduced must be one of ('yes', 'partly', 'no', \
'not evaluable', 'n/a'), not 'maybe'
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
        For each network key (a phase, ``(velocity, phase)``, an offset, ...) the claims the
        paper makes there (:func:`parse_claim`).
    unit : str
        What a key is, for the evidence text (``"networks"``, ``"trials"``, ``"conditions"``).
    """

    id: str
    section: str
    statement: str
    claims: Mapping[Any, tuple[str, ...]] = field(default_factory=dict)
    unit: str = "networks"


def _drive(sources: Sequence[str], targets: Sequence[str]) -> tuple[str, ...]:
    return tuple(f"{s}->{t}" for s in sources for t in targets if s != t)


def _cluster(nodes: Sequence[str]) -> tuple[str, ...]:
    return tuple(f"{a}<->{b}" for k, a in enumerate(nodes) for b in nodes[k + 1:])


# Phase keys used by the specs; funcnet.paper.analyses maps detected phases onto them.
EARLY, LATE, CRUISE, BRAKING, SPIN_UP = ("early spin-up", "late spin-up", "cruise", "braking",
                                         "spin-up")
BASELINE_PHASES = (EARLY, LATE, CRUISE, BRAKING)

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
REVERSAL_AT_ZERO: Mapping[str, tuple[str, tuple[str, ...]]] = {
    "4.3-v-drives": ("Reversal (0 ms): velocity is the dominant driver, with outward edges to "
                     "all other parameters.", _drive(["V"], ["RP", "AP", "MP", *CURRENTS])),
    "4.3-position-chain": ("Reversal (0 ms): MP projects to AP and RP, AP projects to RP.",
                           ("MP->AP", "MP->RP", "AP->RP")),
}

_AT_ZERO = REVERSAL_AT_ZERO["4.3-v-drives"][1] + REVERSAL_AT_ZERO["4.3-position-chain"][1]
#: Section 4.3: what each shifted window shows, by offset in ms.
REVERSAL_SEQUENCE: Mapping[int, tuple[str, ...]] = {
    -40: _drive(CURRENTS, MOTION),
    -20: ("V<->RC", "V<->AC"),
    0: _AT_ZERO,
    20: _AT_ZERO,
    40: ("AP<->RP", "MP->AP", "MP->RP", "V<->RC", "V<->AC"),
}
