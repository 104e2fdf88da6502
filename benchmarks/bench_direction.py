"""Benchmark of the direction reading against what a recording fixes: nothing drives a set-point.

Run from the repository root::

    PYTHONPATH=src python -m benchmarks.bench_direction [--plan DIR] [--seed N] [--candidates]
        [--variants] [--contradicted] [--only WORD ...]

For every real recording -- the SINUMERIK trace (``../shared/data``, its phase windows), both
KUKA KR 300 runs (``examples/kuka-kr300-channels.toml``; every axis's phase windows, and the
whole robot as one network), the UR5 runs when their reader and ``examples/ur5-channels.toml``
are present -- and for a simulated plan (the paper's 36 trials, ``funcnet simulate``, moving
phases), the networks ``funcnet network`` computes with the defaults, and per recording and
pair type the arrows into and out of the set-point RP (and between two set-points), for the
paper's rule (``kind``) and for ``direction`` (:func:`funcnet.network.setpoint_check`).

The cost: each window's network is timed (``window_networks``, which reads the direction too)
and the direction reading alone on the same windows (``direction_columns``); the rule alone is
their difference, and the ratio (rule + direction) / rule is printed per recording, of wall and
of the process's CPU time (target: at most 2). The SINUMERIK trace is computed once untimed
first (compilation, caches).

``--variants`` adds, per recording, the set-point shares of the reading's variants: the gap
before the other signal's lags (0, 1 = the default, 2) and the time-reversal check (a reading
kept only where the time-reversed signals read the opposite way; Haufe et al. 2013, Winkler et
al. 2016), with and without the gap -- and the readings tried after the gap
(:data:`LATER_VARIANTS`): a rounding bound on the improvement, a pair left untested where a
signal's own past predicts it within its logged step, and (whole-robot networks) a signal of
another axis tested given the target axis's signals.

``--contradicted`` lists every arrow of ``direction`` that the recording contradicts (into a
set-point or between two), with the target's own-past prediction error in steps of the
precision it is logged with (:func:`funcnet.network.precision.logged_step`).

``--candidates`` adds the methods the direction was first chosen among (without the gap), over
the same set-point pairs: the prediction test at 3 and 10 lags beside the embedding span, and
the lead of the cross-map skill (lagged convergent cross mapping, Ye et al. 2015; lead = the
lag of the best skill, both ways agreeing, at least 2 samples).
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from benchmarks.bench_core import Run

REPO = Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"  # the SINUMERIK trace (no licence: not shipped)
SHIPPED = REPO / "data"
KUKA_CHANNELS = REPO / "examples" / "kuka-kr300-channels.toml"
UR5_CHANNELS = REPO / "examples" / "ur5-channels.toml"


def recordings(plan: Path) -> Iterator[tuple[str, str, Any]]:
    """(group, name, recording) of every recording, one axis at a time, then whole robots."""
    from funcnet.robot import read_recording

    yield "SINUMERIK", "axis 7", read_recording(DATA / "sinumerik" / "axis7-braking-trace.xml")
    for run in "AB":
        path = SHIPPED / "kuka-kr300" / f"kr300-run-{run}.mat"
        for axis in range(1, 7):
            yield f"KUKA run {run}", f"axis {axis}", read_recording(
                path, channels=KUKA_CHANNELS, axis=axis)
        yield f"KUKA run {run}", "robot", read_recording(path, channels=KUKA_CHANNELS)
    ur5 = SHIPPED / "ur5"
    if UR5_CHANNELS.exists():
        for folder in sorted(p for p in ur5.iterdir() if p.is_dir()):
            whole = read_recording(folder, channels=UR5_CHANNELS)
            for axis in whole.axes:
                yield f"UR5 {folder.name}", f"axis {axis}", read_recording(
                    folder, channels=UR5_CHANNELS, axis=axis)
            if _within_cost(whole):
                yield f"UR5 {folder.name}", "robot", whole
            else:
                print(f"UR5 {folder.name}, robot: over the command line's cost limit (a minute "
                      "or 4 GiB forecast; funcnet network refuses it without --force): not "
                      "computed", file=sys.stderr, flush=True)
    for path in sorted(plan.glob("*.xml")):
        yield "simulated plan", path.stem, read_recording(path)


def _within_cost(recording: Any) -> bool:
    """Whether ``funcnet network`` computes the recording's default network without --force."""
    from funcnet.cli.selection import check_cost
    from funcnet.errors import FuncnetError
    from funcnet.parameters import NetworkParameters

    try:
        check_cost(recording, windows_of(recording), None, NetworkParameters(), False)
    except FuncnetError:
        return False
    return True


def windows_of(recording: Any) -> list[Any]:
    """The windows ``funcnet network`` takes by default: every phase of a move; a recording of
    several axes as one window (where every signal has a value)."""
    from funcnet.robot import complete_span, detect_phases, phase_windows

    if recording.axes:
        return [complete_span(recording)]
    return list(phase_windows(detect_phases(recording)))


def networks_and_cost(recording: Any) -> tuple[list[Any], np.ndarray, np.ndarray]:
    """The default networks of a recording, their time and the direction reading's (s, wall
    and CPU of the process: the rule's kernels run on every core, the reading on one)."""
    from funcnet.core.normalization import normalize
    from funcnet.network.direction import direction_columns
    from funcnet.network.precision import normalized_steps
    from funcnet.pipeline import channel_steps, window_networks, window_steps

    windows = windows_of(recording)
    start = _clocks()
    nets = window_networks(recording, windows, constant="drop", errors="collect")
    total = _clocks() - start
    start = _clocks()
    spans = {w.label: w for w in windows}
    channel = channel_steps(recording.data, list(recording.data.columns))  # as window_networks
    for label, net in nets.items():
        span = spans[label]
        part = recording.window(span.start, span.stop).data[list(net.nodes)]
        raw = part.to_numpy(np.float64)
        normalized = normalize(raw, net.parameters.normalize)
        steps = normalized_steps(list(window_steps(raw, net.nodes, channel).values()), raw,
                                 normalized)
        direction_columns(net.pairs, dict(zip(net.nodes, normalized.T, strict=True)),
                          net.parameters, steps=dict(zip(net.nodes, steps, strict=True)))
    return list(nets.values()), total, _clocks() - start


def _clocks() -> np.ndarray:
    return np.array([time.perf_counter(), time.process_time()])


def warm_up() -> None:
    """Compile the kernels and fill the caches once (the first recording, untimed), so the
    first recording's cost is not the compiler's."""
    from funcnet.robot import read_recording

    networks_and_cost(read_recording(DATA / "sinumerik" / "axis7-braking-trace.xml"))


def counts(nets: list[Any], column: str) -> dict[str, tuple[int, int, int]]:
    from funcnet.network.setpoint import setpoint_check

    check = setpoint_check(nets, column=column)
    return {c.pair_type: (c.into, c.out, c.undirected) for c in check.counts}


def _cell(into: int, out: int, pairs: int) -> str:
    return f"{into} / {out} of {pairs}" if pairs else "-"


def candidate_rows(nets: list[Any], recording: Any, windows: list[Any]) -> list[dict[str, Any]]:
    """Per set-point pair, the candidate methods' readings (``--candidates``)."""
    from funcnet.network.direction import direction_lags, read_direction
    from funcnet.network.setpoint import node_role

    spans = {w.label: w for w in windows}
    rows = []
    for net in nets:
        span = spans[net.label]
        part = recording.window(span.start, span.stop).data
        for x, y, flagged in zip(net.pairs["x"], net.pairs["y"], net.pairs["degenerate"],
                                 strict=True):
            roles = node_role(x), node_role(y)
            if flagged or "RP" not in roles or roles == ("RP", "RP"):
                continue
            setpoint, other = (x, y) if roles[0] == "RP" else (y, x)
            a = part[setpoint].to_numpy(np.float64)
            b = part[other].to_numpy(np.float64)
            row = {"type": node_role(other)}
            for lags in (3, 10, direction_lags(net.parameters)):
                reading = read_direction(a, b, lags, gap=0)[0]  # as the choice was made
                row[f"prediction, {lags} lags"] = {"x->y": "out", "y->x": "into"}.get(reading,
                                                                                    "none")
            row["cross-map lead"] = _ccm_lead(a, b, net.parameters.dim, net.parameters.delay)
            rows.append(row)
    return rows


#: The readings ``--variants`` compares: (gap, time-reversal check).
VARIANTS: dict[str, tuple[int, bool]] = {
    "gap 0": (0, False), "gap 1 (default)": (1, False), "gap 2": (2, False),
    "time reversal, gap 0": (0, True), "time reversal, gap 1": (1, True)}


def _decide(found: tuple[np.ndarray, np.ndarray], i: int, j: int, level: float) -> str:
    """The reading of nodes i (x), j (y) from a p-value matrix (``P[target, source]``) and
    the targets predicted within their logged step (``W[target, source]``)."""
    p, within = found
    forward, backward = p[j, i], p[i, j]
    if (np.isnan(forward) and not within[j, i]) or (np.isnan(backward) and not within[i, j]):
        return "none"
    fwd = forward <= level and not within[j, i]
    bwd = backward <= level and not within[i, j]
    return "x->y" if fwd and not bwd else "y->x" if bwd and not fwd else "none"


def variant_counts(nets: list[Any], recording: Any,
                   windows: list[Any], channel: dict[str, float]) -> dict[str, list[int]]:
    """Per variant, [into, out, pairs] over the set-point pairs (``--variants``). Time
    reversal (Haufe et al. 2013; Winkler et al. 2016): a reading is kept only where the
    time-reversed signals read the opposite way."""
    from funcnet.core.normalization import normalize
    from funcnet.network.direction import DIRECTION_ALPHA, _p_matrix, direction_lags
    from funcnet.network.precision import normalized_steps
    from funcnet.network.setpoint import node_role
    from funcnet.pipeline import window_steps

    spans = {w.label: w for w in windows}
    out = {name: [0, 0, 0] for name in VARIANTS}
    level = DIRECTION_ALPHA / 2
    for net in nets:
        span = spans[net.label]
        part = recording.window(span.start, span.stop).data[list(net.nodes)]
        raw = part.to_numpy(np.float64)
        signals = normalize(raw, net.parameters.normalize)
        steps = normalized_steps(list(window_steps(raw, net.nodes, channel).values()), raw,
                                 signals)
        column = {name: k for k, name in enumerate(net.nodes)}
        lags = direction_lags(net.parameters)
        for name, (gap, reverse) in VARIANTS.items():
            found = _p_matrix(signals, lags, gap, steps)
            back = _p_matrix(signals[::-1].copy(), lags, gap, steps) if reverse else None
            for x, y, flagged in zip(net.pairs["x"], net.pairs["y"], net.pairs["degenerate"],
                                     strict=True):
                x_set, y_set = node_role(x) == "RP", node_role(y) == "RP"
                if flagged or not (x_set or y_set):
                    continue
                reading = _decide(found, column[x], column[y], level)
                if back is not None and reading != "none":
                    flipped = {"x->y": "y->x", "y->x": "x->y"}[reading]
                    if _decide(back, column[x], column[y], level) != flipped:
                        reading = "none"
                counts = out[name]
                counts[2] += 1
                if reading == "none":
                    continue
                into = x_set and y_set or reading == ("x->y" if y_set else "y->x")
                counts[0 if into else 1] += 1
    return out


#: Readings tried after the gap (``--variants``): from the log's resolution, and from the axes
#: of a whole-robot network.
LATER_VARIANTS = ("without the precision rule", "rounding bound",
                  "pair untestable within a step", "target's axis conditioned")


def _lags(v: np.ndarray, k: int, first: int, p: int, span: int) -> np.ndarray:
    """Column k at lags ``first .. first + p - 1``, rows ``t = span .. N - 1``."""
    return np.column_stack([v[span - lag : len(v) - lag, k] for lag in range(first, first + p)])


def _fit(design: np.ndarray, y: np.ndarray) -> tuple[float, np.ndarray]:
    beta = np.linalg.lstsq(design, y, rcond=None)[0]
    return float(((y - design @ beta) ** 2).sum()), beta


def _axis(name: str) -> str | None:
    head, dot, _ = str(name).partition(".")
    return head if dot and head[:1] == "A" and head[1:].isdigit() else None


def later_variant_counts(nets: list[Any], recording: Any,
                         windows: list[Any], channel: dict[str, float]) -> dict[str, list[int]]:
    """[into, out, pairs] over the set-point pairs for :data:`LATER_VARIANTS`, each test by
    least squares (gap 1), each reading without the precision rule of the default but for its
    own change:

    * without the precision rule: the reading before it (any significant improvement counts);
    * rounding bound: an improvement of a target logged on a grid of step ``q`` counts only
      beyond ``n (q^2 / 12) |a|^2``, ``a`` its own-past coefficients -- the rounding error
      those coefficients carry into the residual, which a signal following the target's true
      value takes back without acting on it (a first-order bound);
    * pair untestable within a step: a pair reads ``none`` where either signal's own past
      predicts it to within its logged step (the default instead shows no improvement of that
      signal and still reads what its past improves);
    * target's axis conditioned (whole-robot networks): a signal of another axis is tested
      for what it adds to the target axis's other signals (conditional Granger, Geweke 1984).
    """
    from funcnet.network.direction import DIRECTION_ALPHA, DIRECTION_GAP, direction_lags
    from funcnet.network.setpoint import node_role
    from funcnet.pipeline import window_steps

    spans = {w.label: w for w in windows}
    out = {name: [0, 0, 0] for name in LATER_VARIANTS}
    for net in nets:
        window = spans[net.label]
        part = recording.window(window.start, window.stop).data[list(net.nodes)]
        raw = part.to_numpy(np.float64)
        spread = raw.std(axis=0)
        scale = np.where(spread > 0, spread, 1.0)
        v = (raw - raw.mean(axis=0)) / scale  # the reading standardizes (any normalization)
        steps = np.array(list(window_steps(raw, net.nodes, channel).values())) / scale
        p = direction_lags(net.parameters)
        short = len(v) - p - DIRECTION_GAP - 2 * p - 1 < 1
        test = _window_tests(v, steps, list(net.nodes), p, DIRECTION_GAP, DIRECTION_ALPHA / 2)
        column = {name: k for k, name in enumerate(net.nodes)}
        for x, y, flagged in zip(net.pairs["x"], net.pairs["y"], net.pairs["degenerate"],
                                 strict=True):
            x_set, y_set = node_role(x) == "RP", node_role(y) == "RP"
            if flagged or not (x_set or y_set):
                continue
            if short or spread[column[x]] == 0 or spread[column[y]] == 0:
                for name in LATER_VARIANTS:  # none, as the reading says
                    out[name][2] += 1
                continue
            forward, backward = test(x, y), test(y, x)
            readings = {
                "without the precision rule": (forward[0], backward[0]),
                "rounding bound": (forward[1], backward[1]),
                "pair untestable within a step": ((False, False) if forward[2] or backward[2]
                                                  else (forward[0], backward[0])),
                "target's axis conditioned": (forward[3], backward[3]),
            }
            for name, (fwd, bwd) in readings.items():
                counts = out[name]
                counts[2] += 1
                if fwd == bwd:
                    continue
                into = x_set and y_set or (fwd if y_set else bwd)
                counts[0 if into else 1] += 1
    return out


def _window_tests(v: np.ndarray, steps: np.ndarray, nodes: list[str], p: int, gap: int,
                  level: float) -> Any:
    """``test(source, target)`` on one window's standardized signals: (significant, beyond
    the rounding bound, target within a step, significant given the target axis's signals)."""
    from scipy import stats

    column = {name: k for k, name in enumerate(nodes)}
    span = p + gap
    n = len(v) - span
    own: dict[str, tuple[np.ndarray, float, np.ndarray, float]] = {}

    def own_model(target: str) -> tuple[np.ndarray, float, np.ndarray, float]:
        if target not in own:
            k = column[target]
            design = np.column_stack([np.ones(n), _lags(v, k, 1, p, span)])
            rss, beta = _fit(design, v[span:, k])
            own[target] = design, rss, beta, float(steps[k])
        return own[target]

    def f_test(rss_r: float, rss_f: float, dfd: int) -> bool:
        return dfd > 0 and rss_f > 0 and stats.f.sf((rss_r - rss_f) / p / (rss_f / dfd), p,
                                                    dfd) <= level

    def test(source: str, target: str) -> tuple[bool, bool, bool, bool]:
        design, rss_r, beta, q = own_model(target)
        y = v[span:, column[target]]
        if not rss_r > 1e-24 * float(y @ y):  # predicted exactly: nothing to test
            return False, False, True, False
        x = _lags(v, column[source], 1 + gap, p, span)
        rss_f = _fit(np.column_stack([design, x]), y)[0]
        significant = f_test(rss_r, rss_f, n - 2 * p - 1)
        beyond = rss_r - rss_f > n * q**2 / 12 * float(beta[1:] @ beta[1:])
        conditioned = significant
        axis = _axis(target)
        if axis is not None and _axis(source) != axis:
            mates = [_lags(v, column[m], 1 + gap, p, span) for m in nodes
                     if _axis(m) == axis and m != target]
            base = np.column_stack([design, *mates])
            conditioned = f_test(_fit(base, y)[0], _fit(np.column_stack([base, x]), y)[0],
                                 n - base.shape[1] - p)
        return significant, significant and beyond, rss_r / n <= q**2, conditioned

    return test


def contradicted_rows(nets: list[Any], recording: Any,
                      windows: list[Any], channel: dict[str, float]) -> list[dict[str, Any]]:
    """Every ``direction`` arrow into a set-point or between two (``--contradicted``): the
    window, the arrow, its reason's p-values, and the target's own-past root mean square
    prediction error (least squares, the reading's lags) in steps of its logged precision."""
    from funcnet.network.direction import DIRECTION_GAP, direction_lags
    from funcnet.network.setpoint import node_role
    from funcnet.pipeline import window_steps

    spans = {w.label: w for w in windows}
    rows = []
    for net in nets:
        pairs = net.pairs
        arrows = pairs[pairs["direction"] != "none"]
        if arrows.empty:
            continue
        window = spans[net.label]
        raw = recording.window(window.start, window.stop).data[list(net.nodes)]
        p = direction_lags(net.parameters)
        span = p + DIRECTION_GAP
        for x, y, arrow, reason in arrows[["x", "y", "direction", "direction_reason"]].itertuples(
                index=False):
            source, target = (x, y) if arrow == "x->y" else (y, x)
            if node_role(target) != "RP":
                continue
            values = raw[target].to_numpy(np.float64)
            design = np.column_stack([np.ones(len(values) - span),
                                      _lags(values[:, None], 0, 1, p, span)])
            rss = _fit(design, values[span:])[0]
            step = window_steps(values[:, None], [target], channel)[target]
            error = np.sqrt(rss / design.shape[0])
            rows.append({"window": net.label, "arrow": f"{source} -> {target}",
                         "reason": reason,
                         "own-past error (steps)": error / step if step else float("inf"),
                         "step": step})
    return rows


def _embed(x: np.ndarray, m: int, tau: int) -> np.ndarray:
    n = x.size - (m - 1) * tau
    return np.column_stack([x[(m - 1 - k) * tau:(m - 1 - k) * tau + n] for k in range(m)])


def _skill_by_lag(target: np.ndarray, source: np.ndarray, m: int, tau: int,
                  lags: range) -> np.ndarray:
    """Simplex cross-map skill of ``target(t + l)`` from ``source``'s shadow manifold at t."""
    from scipy.spatial import cKDTree

    states = _embed(source, m, tau)
    t = np.arange((m - 1) * tau, source.size)
    distance, index = cKDTree(states).query(states, k=m + 2)
    distance, index = distance[:, 1:], index[:, 1:]
    weights = np.exp(-distance / np.maximum(distance[:, :1], 1e-12))
    weights /= weights.sum(axis=1, keepdims=True)
    skill = np.full(len(lags), np.nan)
    for k, lag in enumerate(lags):
        at, near = t + lag, t[index] + lag
        good = (at >= 0) & (at < target.size) & np.all((near >= 0) & (near < target.size), 1)
        if good.sum() >= 10:
            estimate = (weights[good] * target[near[good]]).sum(axis=1)
            observed = target[at[good]]
            if estimate.std() > 0 and observed.std() > 0:
                skill[k] = np.corrcoef(estimate, observed)[0, 1]
    return skill


def _ccm_lead(setpoint: np.ndarray, other: np.ndarray, m: int, tau: int) -> str:
    """out: the set-point leads by >= 2 samples both ways; into: it lags; none otherwise."""
    tau = tau if setpoint.size > 20 * tau else 1
    lags = range(-20, 21)
    try:
        back = _skill_by_lag(setpoint, other, m, tau, lags)  # best at -lead
        ahead = _skill_by_lag(other, setpoint, m, tau, lags)  # best at +lead
    except ValueError:
        return "none"
    if np.isnan(back).all() or np.isnan(ahead).all():
        return "none"
    lead_a = -lags[int(np.nanargmax(back))]
    lead_b = lags[int(np.nanargmax(ahead))]
    if lead_a >= 2 and lead_b >= 2:
        return "out"
    if lead_a <= -2 and lead_b <= -2:
        return "into"
    return "none"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plan", type=Path, default=Path("/tmp/funcnet-direction-plan"),
                        help="folder of the simulated plan (written when missing)")
    parser.add_argument("--seed", type=int, default=0, help="noise seed of the simulated plan")
    parser.add_argument("--candidates", action="store_true",
                        help="also the candidate methods over the set-point pairs")
    parser.add_argument("--variants", action="store_true",
                        help="also the gap and time-reversal variants, per recording")
    parser.add_argument("--contradicted", action="store_true",
                        help="also list the direction's arrows the recording contradicts")
    parser.add_argument("--only", nargs="+", default=None, metavar="WORD",
                        help="only the recordings whose group names one of these words "
                        "(SINUMERIK, KUKA, UR5, simulated)")
    args = parser.parse_args(argv)
    from funcnet.pipeline import channel_steps
    from funcnet.sim import paper_plan, write_plan

    run = Run()
    run.header("Direction against the set-point: rule vs direction, per recording")
    write_plan(paper_plan(), args.plan, seed=args.seed, workers=1)
    groups: dict[str, dict[str, Any]] = {}
    candidates: list[dict[str, Any]] = []
    contradicted: list[dict[str, Any]] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        warm_up()
        for group, name, recording in recordings(args.plan):
            if args.only and not any(word in group for word in args.only):
                continue
            nets, total, direction = networks_and_cost(recording)
            windows = windows_of(recording)  # once: the phases are detected again otherwise
            channel = channel_steps(recording.data, list(recording.data.columns))
            print(f"{group}, {name}: {len(nets)} networks, {total[0]:.1f} s", file=sys.stderr,
                  flush=True)
            scope = "robot" if name == "robot" else "axes"
            entry = groups.setdefault(f"{group} ({scope})", {"nets": [], "total": np.zeros(2),
                                                              "direction": np.zeros(2)})
            entry["nets"] += nets
            entry["total"] += total
            entry["direction"] += direction
            if args.variants:
                found = variant_counts(nets, recording, windows, channel)
                found |= later_variant_counts(nets, recording, windows, channel)
                for variant, numbers in found.items():
                    kept = entry.setdefault("variants", {}).setdefault(variant, [0, 0, 0])
                    for k in range(3):
                        kept[k] += numbers[k]
            if args.contradicted:
                for row in contradicted_rows(nets, recording, windows, channel):
                    contradicted.append({"recording": f"{group}, {name}", **row})
            if args.candidates and scope == "axes":
                for row in candidate_rows(nets, recording, windows):
                    candidates.append({"group": "simulated" if group == "simulated plan"
                                       else "real", **row})
    print("\n| recording | networks | set-point pairs | rule: into / out | direction: into / "
          "out | rule: into by pair type | direction: into / out by pair type | cost "
          "(rule + direction) / rule, wall (CPU) |")
    print("|---|---|---|---|---|---|---|---|")
    for label, entry in groups.items():
        nets = entry["nets"]
        rule, direction = counts(nets, "kind"), counts(nets, "direction")
        pairs = sum(sum(v) for v in rule.values())
        rule_in, rule_out = (sum(v[i] for v in rule.values()) for i in (0, 1))
        dir_in, dir_out = (sum(v[i] for v in direction.values()) for i in (0, 1))
        by_type_rule = ", ".join(f"{k} {v[0]}/{v[1]}" for k, v in rule.items())
        by_type_dir = ", ".join(f"{k} {v[0]}/{v[1]}" for k, v in direction.items())
        rule_only = entry["total"] - entry["direction"]
        ratio = np.divide(entry["total"], rule_only, out=np.full(2, np.nan),
                          where=rule_only > 0)
        print(f"| {label} | {len(nets)} | {pairs} | {_cell(rule_in, rule_out, pairs)} | "
              f"{_cell(dir_in, dir_out, pairs)} ({dir_in / max(pairs, 1):.1%} into, "
              f"{dir_out / max(pairs, 1):.1%} out) | {by_type_rule} | {by_type_dir} | "
              f"{ratio[0]:.3f} ({ratio[1]:.3f}) ({entry['total'][0]:.1f} s) |")
    if args.variants:
        print("\nVariants over the set-point pairs (into / out share of the pairs; time "
              "reversal keeps a reading only where the reversed signals read the opposite "
              "way):\n")
        names = [*VARIANTS, *LATER_VARIANTS]
        print("| recording | pairs | " + " | ".join(names) + " |")
        print("|---|---|" + "---|" * len(names))
        for label, entry in groups.items():
            found = entry["variants"]
            pairs = next(iter(found.values()))[2]
            cells = [f"{v[0] / max(v[2], 1):.1%} / {v[1] / max(v[2], 1):.1%}"
                     + (f" of {v[2]}" if v[2] != pairs else "") for v in found.values()]
            print(f"| {label} | {pairs} | " + " | ".join(cells) + " |")
    if contradicted:
        print("\nArrows of direction the recordings contradict (target's own-past root mean "
              "square prediction error in steps of its logged precision):\n")
        print("| recording | window | arrow | own-past error (steps) | step | reason |")
        print("|---|---|---|---|---|---|")
        for row in contradicted:
            print(f"| {row['recording']} | {row['window']} | {row['arrow']} | "
                  f"{row['own-past error (steps)']:.3g} | {row['step']:.3g} | {row['reason']} |")
    if candidates:
        frame = pd.DataFrame(candidates)
        methods = [c for c in frame.columns if c not in ("group", "type")]
        print("\nCandidates over the set-point pairs of the axes' phase windows (into / out "
              "share of the pairs):\n")
        print("| data | pairs | " + " | ".join(methods) + " |")
        print("|---|---|" + "---|" * len(methods))
        for group, part in frame.groupby("group"):
            cells = [f"{(part[m] == 'into').mean():.1%} / {(part[m] == 'out').mean():.1%}"
                     for m in methods]
            print(f"| {group} | {len(part)} | " + " | ".join(cells) + " |")
    run.footer("PYTHONPATH=src python -m benchmarks.bench_direction"
               + (" --candidates" if args.candidates else "")
               + (" --variants" if args.variants else "")
               + (" --contradicted" if args.contradicted else "")
               + (" --only " + " ".join(args.only) if args.only else "")
               + (f" --seed {args.seed}" if args.seed else ""))


if __name__ == "__main__":
    main()
