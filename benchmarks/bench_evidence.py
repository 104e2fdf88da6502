"""Benchmark of the edge evidence on systems with known coupling: prints the tables.

Usage::

    .venv/bin/python benchmarks/bench_evidence.py            # quick: 40 pairs per cell
    .venv/bin/python benchmarks/bench_evidence.py --full     # 500 pairs per uncoupled cell
    .venv/bin/python benchmarks/bench_evidence.py --pairs 100 --only timing

Every pair is a two-node :func:`funcnet.functional_network` with the library's defaults
(``dim = 3``, rr = cr = mu = 0.05, min-max) and ``evidence=True`` (99 surrogates, alpha = 0.05,
200 subsamples); delays: 1 for maps, noise and filtered maps, 3 for Lorenz (sampled every
0.05), 8 for Rossler (sampled every 0.2). Seeds start at 1000 (the tests use lower seeds).

Length: over 600 lines because the tables, the trend and robot runs and the peers' adapters
are one runnable script.

Tables:

1. false positives on uncoupled pairs, per system and length: the paper's rule (an arrow at mu),
   mu with the interval (an arrow under ``edge_rule="interval"``), the dependence test
   (``coupled``), the direction measure (``coupled`` with a direction), with the binomial
   standard error of the test's rate;
2. power on coupled pairs (arrow drawn / coupled / coupled with a direction) and direction
   accuracy (the right arrow; for the common driver "no direction" is right);
3. interval coverage: on pairs of independent realizations of one process the 95 % intervals
   should cover 0, and for logistic maps r = 3.7 vs 4.0 the mean ``C_diff`` of the cell;
4. timing of a 6-signal network over 300 samples, plain and with evidence;
1c. (``--only peers``) the peers alone on the uncoupled systems, for more pairs;
5. (``--only robot``) the dependence test on windows of the simulated axis and on trending
   synthetic pairs, with shift and with twin surrogates.

Tables 1 and 2 also carry the dependence test with twin surrogates
(``surrogate_method="twin"``) and the peers a user would pick instead, each with the decision
a user would make (:func:`ccm_decision`, :func:`pcmci_decision`): convergent cross mapping
(pyEDM) and PCMCI with partial correlation (tigramite). Both are optional test-only
dependencies (``pip install -e ".[test]"``); without them their columns are skipped with a
printed note (``--no-peers`` skips them on purpose).
"""

from __future__ import annotations

import argparse
import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from funcnet.core.embedding import embed
from funcnet.core.recurrence import auto_recurrence
from funcnet.evidence import decorrelation_time, dependence_test, interval_kind, shift_plan
from funcnet.evidence.surrogates import twin_groups
from funcnet.network import functional_network
from funcnet.network.rule import combine_kinds
from funcnet.validation import systems

try:  # optional peers (the `test` extra)
    import pyEDM
except ImportError:  # pragma: no cover - depends on the environment
    pyEDM = None
try:
    import tigramite.data_processing as tigramite_data
    from tigramite.independence_tests.parcorr import ParCorr
    from tigramite.pcmci import PCMCI
except ImportError:  # pragma: no cover
    tigramite_data = None

SEED0 = 1000
#: Half-samples per pair (``--resamples``; 0 skips the intervals: their columns read n/a).
RESAMPLES = 200
#: Surrogates of the CCM decision (the same non-circular shift lattice as the dependence test).
CCM_SURROGATES = 39


@dataclass(frozen=True)
class Case:
    name: str
    make: Callable[[int, list[int]], np.ndarray]
    delay: int
    truth: str  # "none", "x->y", "dependent" (common driver: no direction)


def ccm_decision(x: np.ndarray, y: np.ndarray, *, dim: int = 3, delay: int = 1,
                 alpha: float = 0.05, surrogates: int = CCM_SURROGATES) -> dict[str, object]:
    """Convergent cross mapping (pyEDM) as a user would decide on it.

    Cross-map skill ``rho`` at the full library (``pyEDM.CCM``, ``E = dim``, ``tau = -delay``,
    ``Tp = 0``): Y's shadow manifold estimating X (``rho_xy``, evidence for X -> Y, Sugihara et
    al. 2012) and X's estimating Y (``rho_yx``). Each skill is compared with its values on the
    non-circular shift surrogates of the dependence test (the same lattice, ``surrogates``
    asked: the lattice holds an even number, fewer in short windows); a direction is
    significant when its one-sided surrogate p-value is at most ``alpha / 2`` (Bonferroni over
    the two directions). Coupled: either direction; direction: exactly one of them.
    """
    n = len(x)
    span = (dim - 1) * delay + 1
    s0 = max(decorrelation_time(x), decorrelation_time(y), span)
    try:
        plan = shift_plan(n, surrogates, min_shift=s0)
    except Exception:
        return {"coupled": False, "direction": "", "rho_xy": math.nan, "rho_yx": math.nan,
                "k": 0}
    starts_x = [plan.observed, *plan.starts_x.tolist()]
    starts_y = [plan.observed, *plan.starts_y.tolist()]
    length = plan.length
    skills = np.empty((len(starts_x), 2))
    for k, (a, b) in enumerate(zip(starts_x, starts_y, strict=True)):
        frame = pd.DataFrame({"time": np.arange(1, length + 1),
                              "x": x[a:a + length], "y": y[b:b + length]})
        out = pyEDM.CCM(dataFrame=frame, columns="x", target="y",
                        libSizes=[length - span + 1], sample=1, E=dim, tau=-delay, Tp=0,
                        seed=0, parallel=False)
        # "y:x": Y's manifold cross-maps X, i.e. X drives Y.
        skills[k] = (float(out["y:x"].iloc[-1]), float(out["x:y"].iloc[-1]))
    skills = np.nan_to_num(skills, nan=-np.inf)
    k = plan.surrogates
    p = (1 + np.count_nonzero(skills[1:] >= skills[0], axis=0)) / (k + 1)
    forward, backward = bool(p[0] <= alpha / 2), bool(p[1] <= alpha / 2)
    direction = "x->y" if forward and not backward else "y->x" if backward and not forward \
        else ""
    return {"coupled": forward or backward, "direction": direction,
            "rho_xy": float(skills[0, 0]), "rho_yx": float(skills[0, 1]), "k": k}


def pcmci_decision(x: np.ndarray, y: np.ndarray, *, tau_max: int = 3,
                   alpha: float = 0.05) -> dict[str, object]:
    """PCMCI with partial correlation (tigramite) as a user would decide on it.

    ``run_pcmci(tau_max, pc_alpha=0.2)`` on the two signals, p-values adjusted by
    Benjamini-Hochberg over all links (``fdr_method="fdr_bh"``); X -> Y when some lagged link
    ``X(t - tau) -> Y(t)``, ``1 <= tau <= tau_max``, has an adjusted p-value at most ``alpha``.
    Coupled: a lagged link either way; direction: exactly one way.
    """
    frame = tigramite_data.DataFrame(np.column_stack([x, y]), var_names=["x", "y"])
    pcmci = PCMCI(dataframe=frame, cond_ind_test=ParCorr(), verbosity=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = pcmci.run_pcmci(tau_max=tau_max, pc_alpha=0.2, fdr_method="fdr_bh")
    p = result["q_matrix"] if result.get("q_matrix") is not None else result["p_matrix"]
    forward = bool(np.nanmin(p[0, 1, 1:]) <= alpha)
    backward = bool(np.nanmin(p[1, 0, 1:]) <= alpha)
    direction = "x->y" if forward and not backward else "y->x" if backward and not forward \
        else ""
    return {"coupled": forward or backward, "direction": direction}


PEERS = {"ccm": pyEDM is not None, "pcmci": tigramite_data is not None}


def peer_note() -> None:
    missing = [name for name, ok in (("pyEDM (CCM)", PEERS["ccm"]),
                                     ("tigramite (PCMCI)", PEERS["pcmci"])) if not ok]
    if missing:
        print(f"\nnote: {', '.join(missing)} not installed: their columns are skipped "
              "(pip install -e \".[test]\").")


def twin_share(signal: np.ndarray, delay: int, dim: int = 3) -> float:
    """Share of the states of ``signal`` with a twin at the network's rate (rr = 0.05)."""
    a = auto_recurrence(embed(signal, dim, delay), rr=0.05).to_dense()
    labels = twin_groups(a)
    return float(np.mean(np.bincount(labels)[labels] > 1))


UNCOUPLED = [
    Case("white noise", lambda n, s: systems.white_noise(n, seed=s), 1, "none"),
    Case("AR(1) phi=0.95", lambda n, s: systems.ar1_pair(n, seed=s), 1, "none"),
    Case("Henon C=0", lambda n, s: systems.henon_pair(n, 0.0, seed=s), 1, "none"),
    Case("logistic 3.7/4.0", lambda n, s: systems.logistic_pair(n, 3.7, 4.0, seed=s), 1, "none"),
    Case("Lorenz copies", lambda n, s: systems.lorenz_pair(n, seed=s), 3, "none"),
    Case("Rossler equal w", lambda n, s: systems.rossler_pair(n, 0.0, 1.0, 1.0, seed=s), 8,
         "none"),
    Case("Rossler w 1.015/0.985", lambda n, s: systems.rossler_pair(n, 0.0, seed=s), 8, "none"),
    Case("low-pass of unrelated", lambda n, s: systems.unrelated_low_pass(n, seed=s), 1, "none"),
]


def coupled_cases() -> list[tuple[Case, int]]:
    cases: list[tuple[Case, int]] = []
    for c in (0.2, 0.4, 0.6):
        cases.append((Case(f"Henon C={c}", lambda n, s, c=c: systems.henon_pair(n, c, seed=s),
                           1, "x->y"), 500))
    for kappa in (0.05, 0.1, 0.2):
        for n in (500, 2000):
            cases.append((Case(f"Rossler faster drives k={kappa}",
                               lambda n, s, k=kappa: systems.rossler_pair(n, k, seed=s),
                               8, "x->y"), n))
            cases.append((Case(f"Rossler slower drives k={kappa}",
                               lambda n, s, k=kappa: systems.rossler_pair(
                                   n, k, 0.985, 1.015, seed=s), 8, "x->y"), n))
    cases.append((Case("logistic 3.7->4.0 c=0.2",
                       lambda n, s: systems.logistic_pair(n, 3.7, 4.0, 0.2, seed=s), 1, "x->y"),
                  500))
    cases.append((Case("rough driver -> low-pass",
                       lambda n, s: systems.rough_driver_response(n, seed=s), 1, "x->y"), 500))
    cases.append((Case("common driver (C=0.4)",
                       lambda n, s: systems.common_driver(n, 0.4, seed=s), 1, "dependent"),
                  500))
    return cases


def readings(case: Case, n: int, pairs: int, peers: bool = True) -> list[dict[str, object]]:
    """One dict per pair: the paper's kind, the interval kind, coupled, direction, diffs, and
    the twin test and the peers (``peers``: when installed)."""
    seeds = list(range(SEED0, SEED0 + pairs))
    batch = case.make(n, seeds)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(pairs):
            network = functional_network(batch[:, k], names=["x", "y"], delay=case.delay,
                                         evidence=True, surrogates=99, seed=k,
                                         resamples=RESAMPLES)
            twin = functional_network(batch[:, k], names=["x", "y"], delay=case.delay,
                                      evidence=True, surrogates=99, seed=k, resamples=0,
                                      surrogate_method="twin").pairs.iloc[0]
            x, y = batch[:, k, 0], batch[:, k, 1]
            extra: dict[str, object] = {
                "twin": bool(twin["coupled"]), "twin_direction": twin["direction"],
                "twin_share": twin_share(y, case.delay),
            }
            if peers and PEERS["ccm"]:
                ccm = ccm_decision(x, y, delay=case.delay)
                extra.update(ccm=ccm["coupled"], ccm_direction=ccm["direction"])
            if peers and PEERS["pcmci"]:
                pc = pcmci_decision(x, y, tau_max=max(3, case.delay))
                extra.update(pcmci=pc["coupled"], pcmci_direction=pc["direction"])
            row = network.pairs.iloc[0]
            mu = network.parameters.mu
            c = interval_kind(row["c_diff"], row["c_diff_low"], row["c_diff_high"], mu)
            t = interval_kind(row["t_diff"], row["t_diff_low"], row["t_diff_high"], mu)
            rows.append({
                "kind": row["kind"], "interval": combine_kinds(c, t),
                "coupled": bool(row["coupled"]), "direction": row["direction"],
                "label": row["evidence"],
                "surrogates": int(row["surrogates"]),
                "c_diff": row["c_diff"], "t_diff": row["t_diff"],
                "c_cover0": row["c_diff_low"] <= 0 <= row["c_diff_high"],
                "t_cover0": row["t_diff_low"] <= 0 <= row["t_diff_high"],
                "c_low": row["c_diff_low"], "c_high": row["c_diff_high"],
                **extra,
            })
    return rows


def arrow(kind: object) -> bool:
    return kind in ("x->y", "y->x")


def rate(flags: list[bool]) -> float:
    return float(np.mean(flags)) if flags else float("nan")


def interval_rate(flags: list[bool]) -> str:
    """A rate of an interval reading, "n/a" when the run skipped the intervals."""
    return "n/a" if RESAMPLES == 0 else f"{rate(flags):.3f}"


def peer_columns(peers: bool) -> list[str]:
    return [name for name in ("ccm", "pcmci") if peers and PEERS[name]]


def table_false_positives(pairs: int, lengths: tuple[int, ...],
                          peers: bool = True) -> dict[tuple[str, int], list]:
    print(f"\n## 1. False positives on uncoupled pairs ({pairs} pairs per cell, alpha = 0.05)\n")
    shown = peer_columns(peers)
    titles = {"ccm": "CCM (pyEDM)", "pcmci": "PCMCI (tigramite)"}
    print("| system | N | paper mu rule | mu + interval | dependence test (SE) | direction "
          "measure | surrogates | twin test | twin share |"
          + "".join(f" {titles[c]} |" for c in shown))
    print("|---|---|---|---|---|---|---|---|---|" + "---|" * len(shown))
    found: dict[tuple[str, int], list] = {}
    pooled: list[bool] = []
    for case in UNCOUPLED:
        for n in lengths:
            start = time.perf_counter()
            rows = readings(case, n, pairs, peers)
            found[(case.name, n)] = rows
            test = [r["coupled"] for r in rows]
            pooled += test
            fp = rate(test)
            se = math.sqrt(0.05 * 0.95 / len(rows))
            flag = "" if fp <= 0.05 + 3 * se else " **over 3 SE**"
            print(f"| {case.name} | {n} | {rate([arrow(r['kind']) for r in rows]):.3f} | "
                  f"{interval_rate([arrow(r['interval']) for r in rows])} | {fp:.3f} ({se:.3f})"
                  f"{flag} | {rate([bool(r['direction']) for r in rows]):.3f} | "
                  f"{int(np.median([r['surrogates'] for r in rows]))} | "
                  f"{rate([r['twin'] for r in rows]):.3f} | "
                  f"{np.mean([r['twin_share'] for r in rows]):.2f} |"
                  + "".join(f" {rate([r[c] for r in rows]):.3f} |" for c in shown),
                  flush=True)
            del start
    se = math.sqrt(0.05 * 0.95 / len(pooled))
    print(f"\npooled dependence-test false-positive rate: {rate(pooled):.4f} over {len(pooled)} "
          f"pairs (0.05 + 2 SE = {0.05 + 2 * se:.4f})")
    for column in ("twin", *shown):
        flags = [r[column] for rows in found.values() for r in rows]
        print(f"pooled false-positive rate, {column}: {rate(flags):.4f} over {len(flags)} pairs")
    peer_note()
    return found


def peer_scores(rows: list[dict[str, object]], column: str, truth: str) -> str:
    """``coupled / right direction / wrong direction`` of one tool over a cell's pairs."""
    coupled = rate([bool(r[column]) for r in rows])
    direction = [r[f"{column}_direction"] for r in rows]
    if truth == "dependent":
        right = rate([bool(r[column]) and not d for r, d in zip(rows, direction, strict=True)])
        wrong = rate([bool(d) for d in direction])
    else:
        right = rate([d == truth for d in direction])
        wrong = rate([bool(d) and d != truth for d in direction])
    return f"{coupled:.2f} / {right:.2f} / {wrong:.2f}"


def table_power(pairs: int, peers: bool = True) -> None:
    print(f"\n## 2. Power and direction on coupled pairs ({pairs} pairs per cell)\n")
    shown = peer_columns(peers)
    titles = {"ccm": "CCM (pyEDM)", "pcmci": "PCMCI (tigramite)"}
    print("| system | N | arrow (paper) | right arrow (paper) | right arrow (mu + interval) | "
          "coupled (test) | coupled + right direction (measure) | wrong direction (measure) | "
          "coupled-directed right (label) | coupled-directed wrong (label) | twin test: "
          "coupled / right / wrong |"
          + "".join(f" {titles[c]}: coupled / right / wrong |" for c in shown))
    print("|---|---|---|---|---|---|---|---|---|---|---|" + "---|" * len(shown))
    for case, n in coupled_cases():
        rows = readings(case, n, pairs, peers)
        if case.truth == "dependent":
            right_paper = rate([not arrow(r["kind"]) for r in rows])
            right_interval = interval_rate([not arrow(r["interval"]) for r in rows])
            right_measure = rate([r["coupled"] and not r["direction"] for r in rows])
            wrong = rate([bool(r["direction"]) for r in rows])
            label_right = rate([r["label"] == "coupled" for r in rows])
            label_wrong = rate([r["label"] == "coupled-directed" for r in rows])
        else:
            right_paper = rate([r["kind"] == case.truth for r in rows])
            right_interval = interval_rate([r["interval"] == case.truth for r in rows])
            right_measure = rate([r["coupled"] and r["direction"] == case.truth for r in rows])
            wrong = rate([bool(r["direction"]) and r["direction"] != case.truth for r in rows])
            label_right = rate([r["label"] == "coupled-directed" and r["kind"] == case.truth
                                for r in rows])
            label_wrong = rate([r["label"] == "coupled-directed" and r["kind"] != case.truth
                                for r in rows])
        print(f"| {case.name} | {n} | {rate([arrow(r['kind']) for r in rows]):.2f} | "
              f"{right_paper:.2f} | {right_interval} | {rate([r['coupled'] for r in rows]):.2f}"
              f" | {right_measure:.2f} | {wrong:.2f} | {label_right:.2f} | {label_wrong:.2f} | "
              f"{peer_scores(rows, 'twin', case.truth)} |"
              + "".join(f" {peer_scores(rows, c, case.truth)} |" for c in shown),
              flush=True)
    print("\nFor the common driver the right answer is 'no direction': its 'right' columns count "
          "pairs without an arrow (paper, interval), coupled without a direction (measure), "
          "labelled 'coupled' (label); 'wrong' counts a direction or 'coupled-directed'. "
          "Twin test, CCM, PCMCI: 'right' counts the right direction alone ('coupled' without a "
          "direction for the common driver), 'wrong' another direction (any, common driver).")
    peer_note()


def table_coverage(found: dict[tuple[str, int], list], lengths: tuple[int, ...]) -> None:
    print("\n## 3. Interval coverage (nominal 95 %; target 90-99 %)\n")
    print("| system | N | pairs | C_diff interval covers 0 | T_diff interval covers 0 |")
    print("|---|---|---|---|---|")
    for name in ("white noise", "Henon C=0", "Lorenz copies", "Rossler equal w"):
        for n in lengths:
            rows = found[(name, n)]
            print(f"| {name} | {n} | {len(rows)} | {rate([r['c_cover0'] for r in rows]):.3f} | "
                  f"{rate([r['t_cover0'] for r in rows]):.3f} |")
    print("\n| logistic 3.7 vs 4.0 | N | pairs | mean C_diff | interval covers the mean |")
    print("|---|---|---|---|---|")
    for n in lengths:
        rows = found[("logistic 3.7/4.0", n)]
        mean = float(np.mean([r["c_diff"] for r in rows]))
        cover = rate([r["c_low"] <= mean <= r["c_high"] for r in rows])
        print(f"| logistic | {n} | {len(rows)} | {mean:.4f} | {cover:.3f} |")


def table_timing(repeat: int = 3) -> None:
    print("\n## 4. Timing: 6 signals, 300 samples, 99 surrogates, 200 subsamples\n")
    data = np.column_stack([
        systems.henon_pair(300, 0.6, seed=1), systems.white_noise(300, seed=2),
        systems.logistic_pair(300, seed=3),
    ])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        functional_network(data, delay=1, evidence=True, surrogates=99)  # compile
        plain, full = [], []
        for _ in range(repeat):
            start = time.perf_counter()
            functional_network(data, delay=1)
            plain.append(time.perf_counter() - start)
            start = time.perf_counter()
            functional_network(data, delay=1, evidence=True, surrogates=99, resamples=200)
            full.append(time.perf_counter() - start)
    print(f"plain network {min(plain):.3f} s, with evidence {min(full):.3f} s "
          f"(best of {repeat}); ratio {min(full) / min(plain):.1f}; target <= 5 s")


def table_peer_false_positives(pairs: int, lengths: tuple[int, ...]) -> None:
    """The peers alone on the uncoupled systems (``--only peers``): more pairs, same seeds."""
    if not all(PEERS.values()):
        peer_note()
        return
    print(f"\n## 1c. Peers' false positives ({pairs} pairs per cell, alpha = 0.05)\n")
    print("| system | N | CCM (pyEDM) | PCMCI (tigramite) |")
    print("|---|---|---|---|")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for case in UNCOUPLED:
            for n in lengths:
                batch = case.make(n, list(range(SEED0, SEED0 + pairs)))
                ccm, pc = [], []
                for k in range(pairs):
                    x, y = batch[:, k, 0], batch[:, k, 1]
                    ccm.append(ccm_decision(x, y, delay=case.delay)["coupled"])
                    pc.append(pcmci_decision(x, y, tau_max=max(3, case.delay))["coupled"])
                print(f"| {case.name} | {n} | {rate(ccm):.3f} | {rate(pc):.3f} |", flush=True)


def trend_pair(kind: str, n: int, seed: int) -> np.ndarray:
    """Two independent trending signals, shape (n, 2): ``"walk"`` (random walks) or ``"ramp"``
    (a ramp of slope 1 per window plus AR(1) noise, phi = 0.8, unit innovation variance)."""
    rng = np.random.default_rng([seed, 17])
    e = rng.standard_normal((n, 2))
    if kind == "walk":
        return np.cumsum(e, axis=0)
    noise = np.zeros((n, 2))
    for t in range(1, n):
        noise[t] = 0.8 * noise[t - 1] + e[t]
    return np.linspace(0.0, 1.0, n)[:, None] * 4.0 * noise.std(axis=0) + noise


def detrended(data: np.ndarray) -> np.ndarray:
    """Each column minus its least-squares line."""
    t = np.arange(data.shape[0], dtype=float)
    design = np.column_stack([np.ones_like(t), t])
    coef, *_ = np.linalg.lstsq(design, data, rcond=None)
    return data - design @ coef


def table_trends(pairs: int) -> None:
    from funcnet.evidence import pairwise_evidence

    print(f"\n## 5a. Trending windows: false positives ({pairs} independent pairs per cell, "
          "dim 3, delay 1, alpha = 0.05)\n")
    print("| pair | N | nodes | shift: FP | shift: median K | shift, s0 = span: FP | twin: FP | "
          "twin share |")
    print("|---|---|---|---|---|---|---|---|")
    for kind, title in (("ramp", "ramp + AR(1) 0.8"), ("walk", "random walks")):
        for n in (140, 300):
            for nodes in ("raw", "detrended"):
                fp: dict[str, list[bool]] = {"shift": [], "twin": []}
                dense_lattice: list[bool] = []
                ks: list[int] = []
                shares: list[float] = []
                for k in range(pairs):
                    data = trend_pair(kind, n, SEED0 + k)
                    if nodes == "detrended":
                        data = detrended(data)
                    data = (data - data.min(axis=0)) / (data.max(axis=0) - data.min(axis=0))
                    for method in fp:
                        e = pairwise_evidence([data[:, 0], data[:, 1]], delay=1, resamples=0,
                                              surrogates=99, surrogate_method=method)[(0, 1)]
                        fp[method].append(e.coupled)
                        if method == "shift":
                            ks.append(e.surrogates)
                    shares.append(twin_share(data[:, 1], 1))
                    # The lattice without the decorrelation rule (s0 = the embedding span, 3):
                    # are shifted windows of a trend draws of the observed window's law?
                    a_x, a_y = (auto_recurrence(embed(data[:, c], 3, 1), rr=0.05).to_dense()
                                .astype(np.uint8) for c in (0, 1))
                    test = dependence_test(a_x, a_y, shift_plan(a_x.shape[0], 99, min_shift=3))
                    dense_lattice.append(test.p_value <= 0.05)
                print(f"| {title} | {n} | {nodes} | {rate(fp['shift']):.3f} | "
                      f"{int(np.median(ks))} | {rate(dense_lattice):.3f} | "
                      f"{rate(fp['twin']):.3f} | "
                      f"{np.mean(shares):.2f} |", flush=True)


def span_lattice(normalized: np.ndarray, delay: int, dim: int = 3,
                 alpha: float = 0.05) -> list[tuple[bool, int, str]]:
    """The dependence test of every pair of columns on a shift lattice spaced by the embedding
    span alone (no decorrelation rule), BH-adjusted: ``(coupled, K, "")`` per pair."""
    from funcnet.evidence import benjamini_hochberg, default_surrogates

    matrices = [auto_recurrence(embed(normalized[:, c], dim, delay), rr=0.05).to_dense()
                .astype(np.uint8) for c in range(normalized.shape[1])]
    m = matrices[0].shape[0]
    pairs = [(i, j) for i in range(len(matrices)) for j in range(i + 1, len(matrices))]
    plan = shift_plan(m, default_surrogates(len(pairs), alpha),
                      min_shift=(dim - 1) * delay + 1)
    p = [dependence_test(matrices[i], matrices[j], plan).p_value for i, j in pairs]
    return [(bool(q <= alpha), plan.surrogates, "") for q in benjamini_hochberg(p)]


#: Phases of the robot table, each with the time its windows start at (see table_robot).
ROBOT_PHASES = ("spin-up", "cruise", "braking", "reversal")


def robot_windows(phases: pd.DataFrame) -> dict[str, float]:
    """Anchor time of each phase's windows: spin-up at the first early spin-up, cruise and
    braking at their first start (windows start there), the reversal at the middle of the
    reversal phase (its windows are centred there)."""
    first = phases.groupby("phase", sort=False).first()
    out: dict[str, float] = {}
    if "early spin-up" in first.index:
        out["spin-up"] = float(first.loc["early spin-up", "start"])
    for name in ("cruise", "braking"):
        if name in first.index:
            out[name] = float(first.loc[name, "start"])
    if "reversal" in first.index:
        out["reversal"] = float((first.loc["reversal", "start"] + first.loc["reversal", "stop"])
                                / 2)
    return out


def table_robot(speeds: tuple[float, ...] = (35.0, 175.0, 350.0),
                seeds: tuple[int, ...] = (0, 1, 2, 3, 4),
                delays: tuple[int, ...] = (10, 1)) -> None:
    """The dependence test on the simulated axis (closed loop: every pair is coupled), with
    the library's delay 10 and with delay 1 (a shorter embedding span lets the shift lattice
    hold more offsets)."""
    from funcnet.robot import detect_phases
    from funcnet.robot.preprocess import add_derived_signals
    from funcnet.sim import Trial, simulate_trial
    from funcnet.validation.sweep import simulated_recording

    node_sets = {"raw RP AP MP RC AC": ["RP", "AP", "MP", "RC", "AC"],
                 "detrended FE TORSION RC AC": ["FE", "TORSION", "RC", "AC"],
                 "linear-detrended RP AP MP RC AC": ["RP", "AP", "MP", "RC", "AC"]}
    cells: dict[tuple[str, int, str, int, str], list[tuple[bool, int, str]]] = {}
    shares: dict[tuple[str, int, str, int], list[float]] = {}
    for speed in speeds:
        for seed in seeds:
            trial = Trial(f"t{int(speed)}", "main", speed=speed, tcp=1.6, step=3.0, reverse=True)
            rec = add_derived_signals(simulated_recording(simulate_trial(trial, seed=seed)),
                                      ["FE", "TORSION"])
            anchors = robot_windows(detect_phases(rec))
            data = rec.data
            for phase, anchor in anchors.items():
                for length in (140, 300):
                    start = int(round(anchor / rec.sample_period))
                    if phase == "reversal":
                        start -= length // 2
                    start = max(0, min(start, len(data) - length))
                    window = data.iloc[start:start + length]
                    for label, nodes, delay in ((lb, nd, d) for lb, nd in node_sets.items()
                                                for d in delays):
                        frame = window[nodes]
                        if label.startswith("linear"):
                            frame = pd.DataFrame(detrended(frame.to_numpy()), columns=nodes)
                        normalized = frame.to_numpy()
                        span = normalized.max(axis=0) - normalized.min(axis=0)
                        if np.all(span > 0):
                            normalized = (normalized - normalized.min(axis=0)) / span
                            shares.setdefault((phase, length, label, delay), []).extend(
                                twin_share(normalized[:, c], delay) for c in range(len(nodes)))
                            cells.setdefault((phase, length, label, delay, "shift, s0 = span"),
                                             []).extend(span_lattice(normalized, delay))
                        for method in ("shift", "twin"):
                            cell = cells.setdefault((phase, length, label, delay, method), [])
                            try:
                                with warnings.catch_warnings():
                                    warnings.simplefilter("ignore")
                                    net = functional_network(
                                        frame, warn=False, evidence=True, resamples=0,
                                        surrogate_method=method, seed=seed, delay=delay)
                            except Exception as exc:  # a constant node in the window
                                print(f"  skipped {phase} {length} {label} {delay} {method}: "
                                      f"{type(exc).__name__}", flush=True)
                                continue
                            for _, row in net.pairs.iterrows():
                                cell.append((bool(row["coupled"]), int(row["surrogates"]),
                                             str(row["evidence"])))
    print(f"\n## 5b. Simulated axis (speeds {speeds} deg/min, TCP 1.6 m, 3 deg forward + "
          f"reverse, seeds {seeds}; library defaults (dim 3, rr = cr = 0.05), delays {delays}; "
          "K from the pairs, alpha = 0.05 after BH)\n")
    print("| phase | N | nodes | delay | surrogates | pairs | median K | coupled | "
          "asymmetry-only | twin share |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (phase, length, label, delay, method), found in sorted(
            cells.items(), key=lambda item: (ROBOT_PHASES.index(item[0][0]), *item[0][1:])):
        if not found:
            continue
        print(f"| {phase} | {length} | {label} | {delay} | {method} | {len(found)} | "
              f"{int(np.median([f[1] for f in found]))} | {rate([f[0] for f in found]):.2f} | "
              + ("n/a | " if method.startswith("shift, s0") else
                 f"{rate([f[2] == 'asymmetry-only' for f in found]):.2f} | ")
              + f"{np.mean(shares.get((phase, length, label, delay), [np.nan])):.2f} |",
              flush=True)
    print("\nIn the closed loop every pair is coupled: 'coupled' is the power, 1 - it the misses. "
          "Twin share: states with a twin, mean over the window's nodes (rr = 0.05).")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="500 pairs per uncoupled cell")
    parser.add_argument("--pairs", type=int, default=None, help="pairs per cell")
    parser.add_argument("--only", choices=("fp", "power", "timing", "robot", "peers"),
                        default=None)
    parser.add_argument("--resamples", type=int, default=200,
                        help="subsamples per pair; 0 skips the intervals (faster)")
    parser.add_argument("--no-peers", action="store_true", help="skip the CCM/PCMCI columns")
    args = parser.parse_args()
    peers = not args.no_peers
    global RESAMPLES
    RESAMPLES = args.resamples
    pairs = args.pairs or (500 if args.full else 40)
    lengths = (140, 300, 1000)
    if args.only in (None, "timing"):
        table_timing()
    if args.only in (None, "fp"):
        found = table_false_positives(pairs, lengths, peers)
        if RESAMPLES:
            table_coverage(found, lengths)
    if args.only in (None, "power"):
        table_power(min(pairs, 100) if args.full else pairs, peers)
    if args.only == "peers":
        table_peer_false_positives(pairs, lengths)
    if args.only == "robot":
        table_trends(args.pairs or 100)
        table_robot()


if __name__ == "__main__":
    main()
