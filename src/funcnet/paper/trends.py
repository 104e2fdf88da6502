"""Trends across networks: edge thinning with speed, and the effect of the design's factors.

Statistics on sets of networks rather than single claims: the mean edge weight (Eq. 13) per
network, its rank correlation with speed (:func:`scipy.stats.spearmanr`), and how often pair
relations stay the same across the levels of one factor of the design.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 4.2
   and 5.1 (edges thin with speed) and section 3.1 (Table 1).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd
from scipy import stats

from funcnet.errors import ParameterError
from funcnet.network.schema import PAIR_KINDS
from funcnet.paper.claims import Finding
from funcnet.paper.relations import pairs_of, relation

if TYPE_CHECKING:
    from funcnet.network import FunctionalNetwork

__all__ = ["mean_edge_weight", "spearman", "edge_thinning", "design_effect"]

_CONFLICT = PAIR_KINDS[3]


def mean_edge_weight(net: FunctionalNetwork) -> float:
    """Mean weight (Eq. 13) of a network's edges: neither conflicts nor degenerate pairs.

    Parameters
    ----------
    net : FunctionalNetwork
        A network.

    Returns
    -------
    float
        0.0 for a network without edges.

    References
    ----------
    Paper Eq. 13 and section 4.2.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.network import FunctionalNetwork
    >>> pairs = pd.DataFrame({"x": ["A", "A", "B"], "y": ["B", "C", "C"],
    ...                       "kind": ["x->y", "conflict", "bidirectional"],
    ...                       "weight": [0.3, 0.9, 0.1], "degenerate": [False, False, True]})
    >>> mean_edge_weight(FunctionalNetwork.from_pairs(pairs))
    0.3
    """
    pairs = pairs_of(net)
    edge = pairs["kind"].ne(_CONFLICT).to_numpy(dtype=bool, copy=True)
    if "degenerate" in pairs.columns:
        # Degenerate pairs are no edges (the network's default); NaN from older rows is not.
        edge &= ~pairs["degenerate"].eq(True).to_numpy(dtype=bool)
    drawn = pairs.loc[edge, "weight"]
    return float(drawn.mean()) if len(drawn) else 0.0


def spearman(a: Sequence[float], b: Sequence[float]) -> float:
    """Spearman's rank correlation of two samples (:func:`scipy.stats.spearmanr`).

    Parameters
    ----------
    a, b : sequence of float
        Paired samples of equal length; ties get average ranks.

    Returns
    -------
    float
        ρ in [-1, 1]; 0.0 when either sample is constant (no ranking to correlate).

    Examples
    --------
    >>> spearman([1, 35, 175, 350], [0.4, 0.3, 0.2, 0.1])
    -1.0
    >>> spearman([1, 2, 3], [0.2, 0.2, 0.2])
    0.0
    """
    x = np.asarray(a, dtype=float)
    y = np.asarray(b, dtype=float)
    if x.size < 2 or np.ptp(x) == 0 or np.ptp(y) == 0:
        return 0.0  # scipy would return NaN with a warning
    return float(stats.spearmanr(x, y).statistic)


def edge_thinning(networks: Mapping[Any, Any], *,
                  speeds: Mapping[str, float] | None = None, rho: float = -0.8) -> Finding:
    """Section 4.2: "as velocity increases, the connections generally become thinner".

    Per phase, the mean edge weight (Eq. 13, :func:`mean_edge_weight`) of each speed's network
    is ranked against the speed (:func:`spearman`); a phase counts as thinning when
    ``ρ ≤ rho`` (with four speeds, -0.8 allows one swap of neighbours); a phase with fewer
    than two speeds' networks is not evaluable. Decided as ``"yes"`` when every phase was
    evaluated and thins, ``"partly"`` when some do, ``"no"`` when none of the evaluated phases
    does, ``"not evaluable"`` when no phase could be.

    Parameters
    ----------
    networks : mapping of (velocity, phase) -> FunctionalNetwork (or None)
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
    >>> from funcnet.network import FunctionalNetwork
    >>> def net(w):
    ...     return FunctionalNetwork.from_pairs(
    ...         pd.DataFrame({"x": ["A"], "y": ["B"], "kind": ["x->y"], "weight": [w]}))
    >>> nets = {(v, p): net(w) for p in ("spin-up", "cruise", "braking")
    ...         for v, w in (("V1", .4), ("V35", .3), ("V175", .2), ("V350", .1))}
    >>> edge_thinning(nets).reproduced
    'yes'
    """
    speeds = dict(speeds or {"V1": 1.0, "V35": 35.0, "V175": 175.0, "V350": 350.0})
    phases = list(dict.fromkeys(p for _, p in networks))
    thinning, parts, unevaluated = [], [], []
    for phase in phases:
        rows = [(speeds[v], mean_edge_weight(n)) for (v, p), n in networks.items()
                if p == phase and n is not None and v in speeds]
        if len(rows) < 2:
            unevaluated.append(f"{phase}: {len(rows)} speed(s) with a network")
            continue
        rows.sort()
        r = spearman([s for s, _ in rows], [w for _, w in rows])
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
    for scale, and the mean edge weight (:func:`mean_edge_weight`) per level.

    Parameters
    ----------
    networks : mapping of (trial name, phase) -> FunctionalNetwork (or None)
        The main trials' networks.
    trials : pandas.DataFrame
        One row per trial: ``name, speed, tcp, step``.
    factor : {"speed", "tcp", "step"}
        The factor whose effect is measured.
    label : callable
        Formats a level for the evidence.

    Returns
    -------
    Finding
        ``reproduced="n/a"``; the evidence holds the counts.

    Raises
    ------
    ParameterError
        ``factor`` is not one of the design's factors.

    References
    ----------
    Paper section 3.1 and Table 1.

    Examples
    --------
    >>> import pandas as pd
    >>> trials = pd.DataFrame({"name": ["a"], "speed": [35], "tcp": [1.6], "step": [3]})
    >>> design_effect({}, trials, "tcp").reproduced
    'n/a'
    """
    factors = ("speed", "tcp", "step")
    if factor not in factors:
        raise ParameterError(f"factor must be one of {factors}, not {factor!r}")
    by_name = trials.set_index("name")

    def share_identical(varied: str) -> tuple[int, int]:
        fixed = [f for f in factors if f != varied]
        groups: dict[tuple[Any, ...], dict[Any, Any]] = {}
        for (name, phase), net in networks.items():
            if net is None or name not in by_name.index:
                continue
            row = by_name.loc[name]
            groups.setdefault((*(row[f] for f in fixed), phase), {})[row[varied]] = net
        same = total = 0
        for nets in groups.values():
            if len(nets) < 2:
                continue
            members = list(nets.values())
            for pair in pairs_of(members[0]).itertuples(index=False):
                kinds = {relation(n, pair.x, pair.y) for n in members}
                total += 1
                same += len(kinds) == 1
        return same, total

    same, total = share_identical(factor)
    same_speed, total_speed = share_identical("speed")
    weights: dict[Any, list[float]] = {}
    for (name, _), net in networks.items():
        if net is not None and name in by_name.index:
            weights.setdefault(by_name.loc[name, factor], []).append(mean_edge_weight(net))
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
