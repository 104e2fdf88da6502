"""Findings: the claim language and the yes / partly / no / not evaluable decisions."""

from __future__ import annotations

import dataclasses
import itertools
import random
import re

import pandas as pd
import pytest

from funcnet.errors import ParameterError
from funcnet.network import FunctionalNetwork
from funcnet.paper import (
    BASELINE,
    REVERSAL_SEQUENCE,
    Finding,
    FindingSpec,
    baseline_findings,
    design_effect,
    edge_thinning,
    relation,
    relation_holds,
    reversal_findings,
    reversal_sequence,
    velocity_findings,
)
from funcnet.paper.evaluate import evaluate

NODES = ("RP", "AP", "MP", "V", "RC", "AC")


def make_pairs(edges: dict[str, float] | list[str], nodes=NODES, default="bidirectional"):
    """A network over all node pairs: listed relations set, every other pair ``default``.

    ``edges`` holds ``"A->B"`` or ``"A<->B"`` or ``"A-/-B"`` (conflict), optionally with weights.
    """
    weights = edges if isinstance(edges, dict) else dict.fromkeys(edges, 0.1)
    kinds = {}
    for text, w in weights.items():
        for op, kind in (("<->", "bidirectional"), ("-/-", "conflict"), ("->", "directed")):
            if op in text:
                a, b = text.split(op)
                kinds[frozenset((a, b))] = (kind, a, b, w)
                break
    rows = []
    for x, y in itertools.combinations(nodes, 2):
        kind, a, b, w = kinds.get(frozenset((x, y)), (default, x, y, 0.01))
        if kind == "directed":
            kind = "x->y" if (a, b) == (x, y) else "y->x"
        rows.append({"x": x, "y": y, "kind": kind, "weight": w})
    return FunctionalNetwork.from_pairs(pd.DataFrame(rows), nodes=nodes)


def with_pairs(net, **columns):
    """The network of ``net``'s pairs table with ``columns`` replaced."""
    return FunctionalNetwork.from_pairs(net.pairs.assign(**columns), nodes=net.nodes)


def test_relation_reads_all_four_kinds_in_both_orders():
    pairs = make_pairs(["RP->AP", "MP->RP", "RC<->AC", "V-/-AP"])
    assert relation(pairs, "RP", "AP") == "RP->AP"
    assert relation(pairs, "AP", "RP") == "RP->AP"
    assert relation(pairs, "RP", "MP") == "MP->RP"
    assert relation(pairs, "AC", "RC") == "AC<->RC"
    assert relation(pairs, "AP", "V") == "AP-/-V"
    assert relation(pairs, "RP", "XX") is None


def test_relation_holds_operators():
    pairs = make_pairs(["RP->AP", "RC<->AC", "V-/-AP"])
    assert relation_holds(pairs, "RP->AP") == (True, "RP->AP")
    assert relation_holds(pairs, "AP->RP") == (False, "RP->AP")
    assert relation_holds(pairs, "RC<->AC")[0] is True
    assert relation_holds(pairs, "RP<->AP")[0] is False
    assert relation_holds(pairs, "RP!<->AP")[0] is True  # directed counts as "not bidirectional"
    assert relation_holds(pairs, "V!<->AP")[0] is True  # so does no edge (conflict)
    assert relation_holds(pairs, "RC!<->AC")[0] is False
    assert relation_holds(pairs, "RP->ZZ") == (None, None)
    with pytest.raises(ParameterError, match="claim"):
        relation_holds(pairs, "RP => AP")
    # a conflict can be claimed too, in the network's vocabulary
    assert relation_holds(pairs, "V-/-AP") == (True, "V-/-AP")
    assert relation_holds(pairs, "RP-/-AP") == (False, "RP->AP")


def test_evaluate_yes_partly_no():
    spec = FindingSpec("t", "4.1", "RP drives AP and MP", {"early": ("RP->AP", "RP->MP")})
    assert evaluate(spec, {"early": make_pairs(["RP->AP", "RP->MP"])}).reproduced == "yes"
    partly = evaluate(spec, {"early": make_pairs(["RP->AP", "MP->RP"])})
    assert partly.reproduced == "partly"
    assert "1/2 relations hold" in partly.evidence
    assert "[early] MP->RP" in partly.edges_seen
    assert evaluate(spec, {"early": make_pairs(["AP->RP", "MP->RP"])}).reproduced == "no"


def test_nothing_measurable_is_not_evaluable_never_no():
    spec = FindingSpec("t", "4.1", "RP drives AP and MP", {"early": ("RP->AP", "RP->MP")})
    for networks in ({"early": None}, {}):
        missing = evaluate(spec, networks)
        assert missing.reproduced == "not evaluable"
        assert missing.evidence == ("0/1 networks show all claimed relations; 0/0 relations "
                                    "hold; 2 of 2 claims could not be evaluated: [early] RP->AP: "
                                    "no network, [early] RP->MP: no network")
    # AP and V constant in the window, so left out of its network (demo's 4.1-early-ap-v)
    ap_v = FindingSpec("t", "4.1", "AP <-> V", {"early spin-up": ("AP<->V",)})
    without = make_pairs(["RC<->AC"], nodes=("RP", "MP", "RC", "AC"))
    finding = evaluate(ap_v, {"early spin-up": without}, left_out={"early spin-up": ("AP", "V")})
    assert finding.reproduced == "not evaluable"
    assert finding.edges_seen == ()
    assert finding.not_evaluable == ("[early spin-up] AP<->V: AP, V constant in the window, "
                                     "left out of its network",)
    assert finding.evidence.endswith("1 of 1 claims could not be evaluated: "
                                     + finding.not_evaluable[0])
    # without that knowledge the reason is only what the network shows
    assert evaluate(ap_v, {"early spin-up": without}).not_evaluable == (
        "[early spin-up] AP<->V: AP, V not in the network",)
    # an empty spec has nothing to measure either
    assert evaluate(FindingSpec("t", "4.1", "nothing"), {}).reproduced == "not evaluable"


def test_claims_about_an_absent_node_are_not_evaluable_and_never_a_full_match():
    spec = FindingSpec("t", "4.1", "RP drives AP and MP", {"early": ("RP->AP", "RP->MP")})
    without_ap = make_pairs(["RP->MP"], nodes=("RP", "MP", "V"))
    finding = evaluate(spec, {"early": without_ap}, left_out={"early": ("AP",)})
    # every evaluable claim holds, one could not be evaluated: partly, never yes
    assert finding.reproduced == "partly"
    assert finding.evidence == ("0/1 networks show all claimed relations; 1/1 relations hold; "
                                "1 of 2 claims could not be evaluated: [early] RP->AP: AP "
                                "constant in the window, left out of its network")
    # the evaluable claim failing makes it "no", whatever could not be evaluated
    against = make_pairs(["MP->RP"], nodes=("RP", "MP", "V"))
    assert evaluate(spec, {"early": against}).reproduced == "no"


DEGENERATE = "degenerate recurrence structure (a signal barely moves in the window)"


def flag_degenerate(net, *relations):
    """The network with its pairs of ``relations`` flagged ``degenerate``, no other."""
    flagged = {frozenset(re.findall(r"\w+", r)) for r in relations}
    return with_pairs(net, degenerate=[frozenset(xy) in flagged for xy in
                                       zip(net.pairs["x"], net.pairs["y"], strict=True)])


def test_claims_about_a_degenerate_pair_are_not_evaluable_like_an_absent_signal():
    spec = FindingSpec("t", "4.1", "RP drives AP and MP", {"early": ("RP->AP", "RP->MP")})
    shown = make_pairs(["RP->AP", "RP->MP"])
    assert relation_holds(flag_degenerate(shown, "AP->RP"), "RP->AP") == (None, None)
    assert relation_holds(flag_degenerate(shown, "AP->RP"), "RP->MP") == (True, "RP->MP")
    # the degenerate arrow holds, but is not counted: partly, never yes
    finding = evaluate(spec, {"early": flag_degenerate(shown, "RP->AP")})
    assert finding.reproduced == "partly"
    assert finding.edges_seen == ("[early] RP->MP",)
    assert finding.not_evaluable == (f"[early] RP->AP: {DEGENERATE}",)
    assert finding.evidence == ("0/1 networks show all claimed relations; 1/1 relations hold; "
                                f"1 of 2 claims could not be evaluated: [early] RP->AP: "
                                f"{DEGENERATE}")
    # a failing degenerate arrow is not evidence against either
    against = flag_degenerate(make_pairs(["AP->RP", "RP->MP"]), "RP->AP")
    assert evaluate(spec, {"early": against}).reproduced == "partly"
    both = evaluate(spec, {"early": flag_degenerate(shown, "RP->AP", "RP->MP")})
    assert both.reproduced == "not evaluable"
    assert both.evidence.endswith(f"2 of 2 claims could not be evaluated: [early] RP->AP: "
                                  f"{DEGENERATE}, [early] RP->MP: {DEGENERATE}")
    # no degenerate pair, or rows with gaps from mixing older results, are evaluated
    assert evaluate(spec, {"early": shown}).reproduced == "yes"
    mixed = with_pairs(shown, degenerate=[None] * len(shown.pairs))
    assert evaluate(spec, {"early": mixed}).reproduced == "yes"
    assert evaluate(spec, {"early": flag_degenerate(shown)}).reproduced == "yes"


def test_a_missing_network_among_trials_forbids_yes():
    spec = FindingSpec("t", "4.3", "V drives RP", {f"T{k}": ("V->RP",) for k in range(6)},
                       unit="trials")
    nets = {f"T{k}": make_pairs(["V->RP"]) for k in range(5)}
    finding = evaluate(spec, nets)
    assert finding.reproduced == "partly"
    assert finding.evidence == ("5/6 trials show all claimed relations; 5/5 relations hold; "
                                "1 of 6 claims could not be evaluated: [T5] V->RP: no network")
    assert evaluate(spec, {**nets, "T5": make_pairs(["V->RP"])}).reproduced == "yes"


def reference_verdict(claims, networks):
    """The module's rule written out claim by claim, independently of evaluate."""
    outcomes = {}  # (key, claim) -> True / False / None (not evaluable)
    for key, cs in claims.items():
        net = networks.get(key)
        nodes = set() if net is None else {*net.pairs["x"], *net.pairs["y"]}
        for claim in cs:
            a, b = claim.split("->")
            if a not in nodes or b not in nodes:
                outcomes[(key, claim)] = None
                continue
            table = net.pairs
            row = table[((table["x"] == a) & (table["y"] == b))
                        | ((table["x"] == b) & (table["y"] == a))]
            kind = row["kind"].iloc[0]
            outcomes[(key, claim)] = kind == ("x->y" if row["x"].iloc[0] == a else "y->x")
    evaluated = [v for v in outcomes.values() if v is not None]
    if not evaluated:
        return "not evaluable"
    if all(v is True for v in outcomes.values()):
        return "yes"
    full_network = any(all(outcomes[(k, c)] is True for c in cs) for k, cs in claims.items())
    if full_network or 2 * sum(evaluated) >= len(evaluated):
        return "partly"
    return "no"


def test_rule_matches_a_claim_by_claim_reference_on_random_networks():
    rng = random.Random(5)
    seen = set()
    for _ in range(300):
        claims = {k: tuple(rng.sample(["RP->AP", "AP->MP", "V->RC", "RC->AC", "MP->V"],
                                      rng.randint(1, 3))) for k in ("a", "b")}
        networks = {}
        for key in claims:
            if rng.random() < 0.15:
                continue  # no network for this key
            nodes = rng.sample(NODES, rng.choice([2, 4, 5, 6, 6, 6]))  # signals left out
            edges = [f"{x}->{y}" if rng.random() < 0.5 else f"{y}->{x}"
                     for x, y in itertools.combinations(nodes, 2)]
            networks[key] = make_pairs(edges, nodes=nodes)
        finding = evaluate(FindingSpec("t", "4.1", "random", claims), networks)
        assert finding.reproduced == reference_verdict(claims, networks), (claims, finding)
        seen.add(finding.reproduced)
    assert seen == {"yes", "partly", "no", "not evaluable"}


def test_evaluate_counts_trials_fully_matching():
    spec = FindingSpec("t", "4.3", "V drives RP", {f"T{k}": ("V->RP",) for k in range(6)},
                       unit="trials")
    nets = {f"T{k}": make_pairs(["V->RP"] if k < 4 else ["RP->V"]) for k in range(6)}
    finding = evaluate(spec, nets)
    assert finding.reproduced == "partly"
    assert finding.evidence.startswith("4/6 trials show all claimed relations")
    assert evaluate(spec, {f"T{k}": make_pairs(["RP->V"]) for k in range(6)}).reproduced == "no"


def test_finding_rejects_unknown_verdict():
    with pytest.raises(ParameterError, match="reproduced"):
        Finding("x", "4.1", "s", "maybe", "e")


def paper_baseline():
    """Networks drawn exactly as section 4.1 describes them."""
    early = make_pairs(["RP->AP", "RP->MP", "AP<->V", "RC<->AC",
                        *(f"{c}->{m}" for c in ("RC", "AC") for m in ("RP", "AP", "MP", "V"))])
    cluster = ["RP<->AP", "RP<->MP", "AP<->MP",
               *(f"{p}->{t}" for p in ("RP", "AP", "MP") for t in ("V", "RC", "AC"))]
    braking = make_pairs([*(f"{c}->{m}" for c in ("RC", "AC") for m in ("RP", "AP", "MP", "V")),
                          "AP->MP", "AP->RP"])
    return {"early spin-up": early, "late spin-up": make_pairs(cluster),
            "cruise": make_pairs(cluster), "braking": braking}


def test_baseline_as_in_the_paper_is_reproduced_and_its_opposite_is_not():
    networks = paper_baseline()
    found = baseline_findings(networks)
    assert [f.id for f in found] == [s.id for s in BASELINE]
    assert all(f.reproduced == "yes" for f in found), [(f.id, f.evidence) for f in found]
    # every edge flipped: no directed claim holds, bidirectional ones become directed
    flipped = {k: with_pairs(v, kind=v.pairs["kind"].map({"x->y": "y->x", "y->x": "x->y",
                                                          "bidirectional": "x->y"}))
               for k, v in networks.items()}
    assert all(f.reproduced == "no" for f in baseline_findings(flipped))


def test_velocity_findings_on_paper_like_networks():
    nets = {}
    for v in ("V1", "V35", "V175", "V350"):
        for p in ("spin-up", "cruise", "braking"):
            nets[(v, p)] = make_pairs(["RC<->AC"])
    nets[("V175", "spin-up")] = make_pairs(["RC<->AC", "V->AP"])
    nets[("V350", "spin-up")] = make_pairs(["RC<->AC", "AP->V"])
    found = {f.id: f for f in velocity_findings(nets)}
    assert found["4.2-spinup-ap-v"].reproduced == "yes"
    assert found["4.2-rc-ac-everywhere"].reproduced == "yes"
    assert "12/12 conditions" in found["4.2-rc-ac-everywhere"].evidence
    # everything bidirectional: one big cluster, not two (6 of 15 claimed relations hold)
    assert found["4.2-v1-two-clusters"].reproduced == "no"
    assert "6/15 relations hold" in found["4.2-v1-two-clusters"].evidence
    assert found["4.2-v1-braking-mp-ap"].reproduced == "no"
    # all weights equal: no thinning
    assert found["4.2-edges-thin"].reproduced == "no"
    # a single speed per phase: thinning cannot be measured at all
    only_v35 = {k: v for k, v in nets.items() if k[0] == "V35"}
    thin = edge_thinning(only_v35)
    assert thin.reproduced == "not evaluable"
    assert "3 of 3 phases could not be evaluated: spin-up: 1 speed(s)" in thin.evidence


def test_edge_thinning_partly_and_weights():
    weights = {"V1": 0.4, "V35": 0.3, "V175": 0.2, "V350": 0.1}
    nets = {}
    for p in ("spin-up", "cruise", "braking"):
        for v, w in weights.items():
            grow = p == "braking"
            nets[(v, p)] = make_pairs({"RP->AP": 0.5 - w if grow else w}, default="conflict")
    finding = edge_thinning(nets)
    assert finding.reproduced == "partly"
    assert finding.evidence.startswith("2/3 phases thin")
    assert "350°/min 0.100" in finding.evidence
    # every evaluated phase thins but one phase has a single speed: partly, not yes
    thin = {k: v for k, v in nets.items() if k[1] != "braking" or k[0] == "V1"}
    finding = edge_thinning(thin)
    assert finding.reproduced == "partly"
    assert finding.evidence.startswith("2/2 phases thin")
    assert finding.evidence.endswith("1 of 3 phases could not be evaluated: braking: 1 speed(s) "
                                     "with a network")


def sequence_networks(shown: dict[int, list[str]]):
    return {o: make_pairs(shown.get(o, list(REVERSAL_SEQUENCE[o])), default="conflict")
            for o in REVERSAL_SEQUENCE}


def test_reversal_signature_and_sequence_counts():
    as_paper = {o: [c.replace("!<->", "->") for c in cs] for o, cs in REVERSAL_SEQUENCE.items()}
    trials = {f"B{k}": sequence_networks(as_paper) for k in range(4)}
    trials["B4"] = sequence_networks({0: ["RP->V"], 20: ["RP->V"]})  # no signature at all
    trials["B5"] = sequence_networks({**as_paper, -20: ["V<->RC"]})  # half of -20 ms
    found = {f.id: f for f in reversal_findings(trials)}
    assert found["4.3-v-drives"].reproduced == "partly"
    assert found["4.3-v-drives"].evidence.startswith("5/6 trials")
    assert found["4.3-position-chain"].evidence.startswith("5/6 trials")
    seq = found["4.3-sequence"]
    assert seq.reproduced == "partly"
    assert seq.evidence.startswith("whole sequence in 4/6 trials, at least half of each "
                                   "window's claims in 5/6")
    assert "-40 ms 6/6, -20 ms 5/6, +0 ms 5/6, +20 ms 5/6, +40 ms 6/6" in seq.evidence
    assert reversal_sequence({k: sequence_networks(as_paper) for k in "ab"}).reproduced == "yes"
    # no trial, or no network in any window: nothing measured
    assert reversal_sequence({}).reproduced == "not evaluable"
    empty = reversal_sequence({"a": dict.fromkeys(REVERSAL_SEQUENCE)})  # 8+2+8+8+5 claims
    assert empty.reproduced == "not evaluable"
    assert empty.evidence.endswith("31 of 31 claims could not be evaluated (no network, a "
                                   "signal constant in the window and left out, or a degenerate "
                                   "recurrence structure)")
    # a window without a network counts against the sequence, never for it
    one_missing = sequence_networks(as_paper)
    one_missing[-40] = None
    assert reversal_sequence({"a": one_missing}).reproduced == "no"


def test_reversal_findings_say_which_signal_was_left_out():
    as_paper = {o: [c.replace("!<->", "->") for c in cs] for o, cs in REVERSAL_SEQUENCE.items()}
    nets = sequence_networks(as_paper)
    pairs = nets[0].pairs
    nets[0] = FunctionalNetwork.from_pairs(pairs[(pairs["x"] != "RP") & (pairs["y"] != "RP")])
    found = {f.id: f for f in reversal_findings({"B0": nets}, left_out={"B0": {0: ("RP",)}})}
    chain = found["4.3-position-chain"]
    # MP->AP holds; MP->RP and AP->RP cannot be evaluated
    assert chain.reproduced == "partly"
    assert chain.not_evaluable == (
        "[B0] MP->RP: RP constant in the window, left out of its network",
        "[B0] AP->RP: RP constant in the window, left out of its network")
    assert "2 of 3 claims could not be evaluated" in chain.evidence


def test_reversal_findings_do_not_count_degenerate_arrows():
    # the arm stands still while the motor crosses the backlash: AP and V barely move
    as_paper = {o: [c.replace("!<->", "->") for c in cs] for o, cs in REVERSAL_SEQUENCE.items()}
    nets = sequence_networks(as_paper)
    nets[0] = flag_degenerate(nets[0], "V->AP", "MP->AP", "AP->RP")
    found = {f.id: f for f in reversal_findings({"B0": nets})}
    assert found["4.3-v-drives"].reproduced == "partly"
    assert found["4.3-v-drives"].not_evaluable == (f"[B0] V->AP: {DEGENERATE}",)
    chain = found["4.3-position-chain"]
    assert chain.reproduced == "partly"
    assert chain.not_evaluable == (f"[B0] MP->AP: {DEGENERATE}", f"[B0] AP->RP: {DEGENERATE}")
    assert "[B0] MP->AP" not in chain.edges_seen
    seq = found["4.3-sequence"]
    # 0 ms shows 5 of its 8 claims: the sequence largely appears, not wholly
    assert seq.reproduced == "partly"
    assert "+0 ms 0/1" in seq.evidence
    assert "3 of 31 claims could not be evaluated" in seq.evidence
    assert not any(s.startswith("[B0 · +0 ms] MP->AP") for s in seq.edges_seen)


def test_design_effect_counts_identical_relations():
    trials = pd.DataFrame({"name": ["a", "b", "c", "d"], "speed": [35, 35, 175, 175],
                           "tcp": [1.2, 1.6, 1.2, 1.6], "step": [3, 3, 3, 3]})
    nets = {("a", "cruise"): make_pairs(["RP->AP"]), ("b", "cruise"): make_pairs(["RP->AP"]),
            ("c", "cruise"): make_pairs(["AP->RP"]), ("d", "cruise"): make_pairs(["RP<->AP"])}
    finding = design_effect(nets, trials, "tcp")
    assert finding.reproduced == "n/a"
    # speed 35: 15/15 identical; speed 175: 14/15 (RP-AP differs)
    assert "identical across all TCP distance levels: 29/30" in finding.evidence
    # across speeds (tcp 1.2: a vs c differ on one pair; tcp 1.6: b vs d likewise)
    assert "across speeds, for comparison: 28/30" in finding.evidence
    with pytest.raises(ParameterError, match="factor"):
        design_effect(nets, trials, "colour")


@pytest.mark.filterwarnings("ignore::funcnet.errors.FuncnetWarning")
def test_analyse_leaves_constant_signals_out_through_window_networks():
    import numpy as np

    from funcnet.network import functional_network
    from funcnet.paper.analyses import _analyse
    from funcnet.parameters import NetworkParameters
    from funcnet.robot.recording import Recording, SignalInfo
    from funcnet.robot.windows import Window

    t = np.arange(0, 3, 0.002)
    data = pd.DataFrame({"RP": np.sin(5 * t), "AP": np.sin(5 * t - 0.3),
                         "AC": np.where(t < 1, 0.25, np.cos(7 * t))},
                        index=pd.Index(t, name="time"))
    info = {name: SignalInfo(name, None, None, 0.002) for name in data}
    recording = Recording(data, {}, info, source="synthetic.csv", sample_period=0.002)
    windows = {"still": Window("still", 0.2, 0.8), "moving": Window("moving", 1.2, 1.8),
               "late": Window("late", 1.8, 2.4)}
    parameters = NetworkParameters(delay=5, normalize="minmax")
    warned: dict[str, int] = {}
    analysis = _analyse("synthetic", "synthetic.csv", recording, lambda rec, phases: windows,
                        ["RP", "AP", "AC"], parameters, warned)
    assert analysis.dropped == {"still": ("AC",)} and not analysis.errors
    assert analysis.networks["still"].nodes == ("RP", "AP")
    assert analysis.networks["moving"].nodes == ("RP", "AP", "AC")
    reference = functional_network(data.loc[(t >= 0.2 - 1e-9) & (t < 0.8 - 1e-9), ["RP", "AP"]],
                                   delay=5, warn=False)
    pd.testing.assert_frame_equal(analysis.networks["still"].pairs, reference.pairs)
    # Problems are counted by kind, one per window that has it, from the pairs tables' flags.
    assert warned and all("pair(s)" not in m and "synthetic.csv" not in m for m in warned)
    assert all(1 <= n <= len(windows) for n in warned.values())
    # A window left with one signal is an error that names the constant ones; the others
    # still get their network.
    lone = _analyse("synthetic", "synthetic.csv", recording, lambda rec, phases: windows,
                    ["RP", "AC"], parameters, {})
    assert "['AC']" in lone.errors["still"] and lone.networks["still"] is None
    assert lone.networks["moving"].nodes == ("RP", "AC")


def test_claims_are_written_in_the_network_kind_vocabulary():
    from funcnet.network.schema import PAIR_KINDS
    from funcnet.paper import parse_claim
    from funcnet.paper.claims import OPERATORS, REVERSAL_AT_ZERO, VELOCITY

    assert set(OPERATORS.values()) <= set(PAIR_KINDS)
    assert [parse_claim(c).kind for c in ("A->B", "A<->B", "A-/-B")] == [
        "x->y", "bidirectional", "conflict"]
    assert parse_claim("A!<->B").negated
    specs = [*BASELINE, *VELOCITY]
    claims = [c for spec in specs for cs in spec.claims.values() for c in cs]
    claims += [c for _, cs in REVERSAL_AT_ZERO.values() for c in cs]
    claims += [c for cs in REVERSAL_SEQUENCE.values() for c in cs]
    assert all(parse_claim(c).kind in PAIR_KINDS for c in claims)
    # relation() reads a pair's kind from either end
    from funcnet.paper import pair_kind

    pairs = make_pairs(["RP->AP"])
    assert pair_kind(pairs, "RP", "AP") == "x->y" and pair_kind(pairs, "AP", "RP") == "y->x"


def hand_written_spearman(a, b):
    """The Spearman this package computed before it used SciPy's."""
    import numpy as np

    ra = pd.Series(a).rank().to_numpy()
    rb = pd.Series(b).rank().to_numpy()
    if np.std(ra) == 0 or np.std(rb) == 0:
        return 0.0
    return float(np.corrcoef(ra, rb)[0, 1])


def test_spearman_is_scipys_and_decides_as_the_hand_written_one():
    import numpy as np
    from scipy.stats import spearmanr

    from funcnet.paper import spearman

    rng = np.random.default_rng(1)
    for n in (2, 3, 4, 5, 8):
        for _ in range(50):
            a = np.sort(rng.choice([1.0, 35.0, 175.0, 350.0, 700.0, 1400.0, 2800.0, 5600.0],
                                   n, replace=False))
            b = rng.integers(0, 4, n) * 0.1  # ties included
            expected = (0.0 if np.ptp(b) == 0 else float(spearmanr(a, b).statistic))
            assert spearman(a, b) == expected
            old = hand_written_spearman(a, b)
            assert spearman(a, b) == pytest.approx(old, abs=1e-12)
            assert (spearman(a, b) <= -0.8) == (old <= -0.8)
            assert f"{spearman(a, b):+.2f}" == f"{old:+.2f}"
    # every ranking of four speeds: the same verdicts as before (-0.8 is one swap)
    for order in itertools.permutations(range(4)):
        weights = [0.1 * (k + 1) for k in order]
        old = hand_written_spearman([1, 35, 175, 350], weights)
        assert (spearman([1, 35, 175, 350], weights) <= -0.8) == (old <= -0.8)
    assert spearman([1, 2, 3], [0.5, 0.5, 0.5]) == 0.0


def test_degenerate_pairs_do_not_count_in_the_mean_edge_weight():
    from funcnet.paper import mean_edge_weight

    pairs = make_pairs({"RP->AP": 0.4, "RP->MP": 0.9}, nodes=("RP", "AP", "MP"),
                       default="conflict")
    assert mean_edge_weight(pairs) == pytest.approx(0.65)
    assert mean_edge_weight(flag_degenerate(pairs, "RP->MP")) == pytest.approx(0.4)
    gaps = with_pairs(pairs, degenerate=[None] * len(pairs.pairs))
    assert mean_edge_weight(gaps) == pytest.approx(0.65)



# --------------------------------------------------------------------------------------------
# coupling evidence of the claimed relations


def test_pair_reading_tells_coupled_from_untestable_on_real_networks():
    from funcnet import functional_network
    from funcnet.evidence import untestable
    from funcnet.paper.coupling import pair_reading
    from funcnet.validation.systems import henon_pair

    x = henon_pair(800, 0.6, seed=1)
    data = pd.DataFrame({"X": x[:, 0], "Y": x[:, 1]})
    long = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, warn=False)
    assert pair_reading(long.pairs, "Y", "X", 0.05) == ("coupled", int(long.pairs["surrogates"][0]))
    # the same coupled pair with 9 surrogates asked: p >= 1/11 > 0.05, whatever the data
    short = functional_network(data, dim=2, delay=1, evidence=True, resamples=0, surrogates=9,
                               warn=False)
    row = short.pairs.iloc[0]
    assert untestable(short.pairs["surrogates"], 0.05).tolist() == [True]
    assert row["evidence"] == "untestable" and not row["coupled"]
    assert pair_reading(short.pairs, "X", "Y", 0.05)[0] == "untestable"
    assert pair_reading(short.pairs, "X", "Z", 0.05)[0] == "untested"


def test_claims_coupling_counts_every_claimed_relation_once():
    from funcnet.paper import PaperAnalyses, TrialAnalysis
    from funcnet.paper.claims import REVERSAL_SEQUENCE
    from funcnet.paper.coupling import claimed_windows, claims_coupling

    empty = PaperAnalyses("plan", None, {}, pd.DataFrame(), None, {}, {}, {}, None, (), {}, {},
                          0.0)
    found = claims_coupling(empty)
    # nothing computed: every claimed relation is counted, as untested, none as "not coupled"
    assert found["4.1-early-rp-drives"].relations == 2
    assert found["4.1-early-rp-drives"].untested == 2
    assert "not shown coupled" not in found["4.1-early-rp-drives"].text
    assert found["4.3-sequence"].relations == 0  # no backlash trial, no claimed window
    trial = TrialAnalysis("B1", "b.xml", pd.DataFrame(), pd.DataFrame(), {}, {}, {})
    with_trial = dataclasses.replace(empty, reversal={"B1": trial})
    sites = claimed_windows(with_trial)
    assert len(sites["4.3-sequence"]) == sum(len(c) for c in REVERSAL_SEQUENCE.values())
    assert claims_coupling(with_trial)["4.3-sequence"].untested == len(sites["4.3-sequence"])
