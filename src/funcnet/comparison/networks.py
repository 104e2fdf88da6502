"""The functional networks' reading of a comparison: measures over sliding windows, per axis.

Per axis, the nodes are the current set-point RC, the measured current AC and the following
error FE = RP - AP (positions are ramps while moving; their difference is not). RUN is cut into
windows of ``window`` seconds every ``step`` seconds; each RUN window is matched with the
reference windows that start where the alignment puts its first tick (one per reference and
cycle). Per pair and measure -- ``c_diff`` and ``t_diff`` (the cross-clustering and
cross-transitivity asymmetries, the arrows of the network) and ``coupling`` (the mean
cross-clustering, ``(c_xy + c_yx) / 2``) -- the references' windows give a centre and a spread
along the program, and RUN's departure is in multiples of that spread, as for the residuals
(:mod:`funcnet.comparison.band`). A window in which a node is constant (a current at zero in a
standstill) has no network: its measures are NaN, never guessed.

Examples
--------
>>> NODES, MEASURES
(('RC', 'AC', 'FE'), ('c_diff', 't_diff', 'coupling'))
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from funcnet.comparison.align import Alignment
from funcnet.comparison.band import SPREAD_FLOOR, _rolling_mean
from funcnet.comparison.intervals import Interval, find_intervals
from funcnet.core.batch import batch_pairs
from funcnet.parameters import NetworkParameters
from funcnet.robot.axes import qualified
from funcnet.robot.recording import Recording

__all__ = ["NetworkComparison", "compare_networks", "phase_summary", "NODES", "MEASURES"]

#: The nodes of each axis' network.
NODES = ("RC", "AC", "FE")
#: The measures compared per pair.
MEASURES = ("c_diff", "t_diff", "coupling")


@dataclass(frozen=True)
class NetworkComparison:
    """RUN's windowed network measures against the references' (module notes).

    Attributes
    ----------
    starts : ndarray
        RUN's seconds at the start of each window.
    window, step : float
        Seconds.
    times : ndarray
        RUN's seconds per tick (to place the windows).
    run, centre, spread, size : dict of (int, str, str) to ndarray
        Per ``(axis, pair, measure)`` (pair written ``"AC-FE"``) and window: RUN's value, the
        references' mean and spread, and RUN's departure in spreads (NaN: no network).
    windows : int
        RUN's windows.
    missing : int
        Windows of RUN (over all axes) without a network: a constant node, or no reference
        window.
    """

    starts: np.ndarray = field(repr=False)
    window: float
    step: float
    times: np.ndarray = field(repr=False)
    run: dict[tuple[int, str, str], np.ndarray] = field(repr=False)
    centre: dict[tuple[int, str, str], np.ndarray] = field(repr=False)
    spread: dict[tuple[int, str, str], np.ndarray] = field(repr=False)
    size: dict[tuple[int, str, str], np.ndarray] = field(repr=False)
    windows: int
    missing: int

    def per_tick(self, key: tuple[int, str, str], values: np.ndarray) -> np.ndarray:
        """A per-window array on RUN's ticks: each window's value over its central ``step``."""
        out = np.full(self.times.size, np.nan)
        period = float(self.times[1] - self.times[0]) if self.times.size > 1 else 1.0
        half = int(round(self.step / period / 2))
        for start, value in zip(self.starts, values, strict=True):
            centre = int(round((start - self.times[0] + self.window / 2) / period))
            out[max(centre - half, 0):centre + half] = value
        return out

    def intervals(self, *, threshold: float, merge: float,
                  min_duration: float = 0.05) -> tuple[Interval, ...]:
        """The intervals where a measure of a pair departs beyond ``threshold`` spreads."""
        sizes = {(f"{m}({p})", a): self.per_tick((a, p, m), s)
                 for (a, p, m), s in self.size.items()}
        diffs = {(f"{m}({p})", a): self.per_tick((a, p, m), self.run[(a, p, m)]
                                                  - self.centre[(a, p, m)])
                 for (a, p, m) in self.size}
        return find_intervals(sizes, diffs, {name: "1" for name, _ in sizes}, times=self.times,
                              threshold=threshold, merge=merge, min_duration=min_duration)


def _nodes(recording: Recording, axis: int) -> np.ndarray | None:
    def col(role: str) -> str | None:
        name = qualified(axis, role) if recording.axes else role
        return name if name in recording.data.columns else None

    rc, ac, rp = col("RC"), col("AC"), col("RP")
    ap = col("AP") or col("MP")
    if None in (rc, ac, rp, ap):
        return None
    d = recording.data
    return np.c_[d[rc].to_numpy(), d[ac].to_numpy(), (d[rp] - d[ap]).to_numpy()]


def _usable(block: np.ndarray) -> bool:
    return bool(np.isfinite(block).all() and (np.ptp(block, axis=0) > 0).all())


def compare_networks(
    run: Recording,
    references: Sequence[Recording],
    alignments: Sequence[Alignment],
    *,
    axes: Sequence[int],
    window: float = 1.0,
    step: float = 0.25,
    parameters: NetworkParameters | None = None,
    smooth: float = 0.5,
) -> NetworkComparison:
    """The networks' reading of RUN against its references (module notes).

    Parameters
    ----------
    run, references : Recording
        As :func:`funcnet.comparison.compare_runs`.
    alignments : sequence of Alignment
        RUN aligned on each reference.
    axes : sequence of int
    window, step : float
        Seconds.
    parameters : NetworkParameters, optional
    smooth : float
        Seconds along the program over which the references' spread is averaged.

    Returns
    -------
    NetworkComparison
    """
    period = run.sample_period
    width = int(round(window / period))
    hop = max(int(round(step / period)), 1)
    n = len(run.data)
    firsts = np.arange(0, max(n - width + 1, 0), hop)
    times = run.data.index.to_numpy(dtype=np.float64)
    pairs = [(i, j) for i in range(len(NODES)) for j in range(i + 1, len(NODES))]
    labels = [f"{NODES[i]}-{NODES[j]}" for i, j in pairs]
    out: dict[str, dict[tuple[int, str, str], np.ndarray]] = {
        k: {} for k in ("run", "centre", "spread", "size")}
    missing = 0
    spread_width = max(int(round(smooth / step)), 1)
    for axis in axes:
        own = _nodes(run, axis)
        theirs = [_nodes(r, axis) for r in references]
        if own is None or any(t is None for t in theirs):
            missing += firsts.size
            continue
        blocks: list[np.ndarray] = []
        owner: list[tuple[int, bool]] = []  # (RUN window, is RUN's own)
        for w, first in enumerate(firsts):
            block = own[first:first + width]
            if not _usable(block):
                continue
            blocks.append(block)
            owner.append((w, True))
            for values, alignment in zip(theirs, alignments, strict=True):
                assert values is not None
                for j in alignment.matches[first]:
                    if j < 0 or j + width > len(values):
                        continue
                    other = values[j:j + width]
                    if _usable(other):
                        blocks.append(other)
                        owner.append((w, False))
        result = None
        if blocks:
            result = batch_pairs(np.stack(blocks), names=list(NODES), parameters=parameters)
        for q, label in enumerate(labels):
            for measure in MEASURES:
                mine = np.full(firsts.size, np.nan)
                total = np.zeros(firsts.size)
                squares = np.zeros(firsts.size)
                count = np.zeros(firsts.size)
                if result is not None:
                    if measure == "coupling":
                        values = 0.5 * (result["c_xy"][:, q] + result["c_yx"][:, q])
                    else:
                        values = result[measure][:, q]
                    for (w, is_run), value in zip(owner, values, strict=True):
                        if is_run:
                            mine[w] = value
                        elif np.isfinite(value):
                            total[w] += value
                            squares[w] += value * value
                            count[w] += 1
                with np.errstate(invalid="ignore", divide="ignore"):
                    centre = np.where(count > 0, total / count, np.nan)
                    variance = np.where(count >= 2, (squares - count * centre ** 2)
                                        / (count - 1), np.nan)
                spread = np.sqrt(np.maximum(_rolling_mean(variance, spread_width), 0.0))
                typical = np.nanmedian(spread) if np.isfinite(spread).any() else np.nan
                spread = np.where(np.isfinite(spread) | (count == 0), spread, typical)
                if np.isfinite(typical) and typical > 0:
                    spread = np.maximum(spread, SPREAD_FLOOR * typical)
                with np.errstate(invalid="ignore", divide="ignore"):
                    size = np.abs(mine - centre) / (spread * np.sqrt(1 + 1 / np.maximum(count, 1)))
                key = (axis, label, measure)
                out["run"][key], out["centre"][key] = mine, centre
                out["spread"][key], out["size"][key] = spread, np.where(spread > 0, size, np.nan)
        own_windows = {w for w, is_run in owner if is_run}
        missing += firsts.size - len(own_windows)
    return NetworkComparison(
        starts=times[firsts] if firsts.size else np.array([]), window=window, step=step,
        times=times, run=out["run"], centre=out["centre"], spread=out["spread"],
        size=out["size"], windows=int(firsts.size), missing=missing)


def _mean(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(finite.mean()) if finite.size else float("nan")


def phase_summary(networks: NetworkComparison, phases: Sequence[tuple[str, float, float]],
                  *, threshold: float) -> pd.DataFrame:
    """Per phase, axis and pair: the references' and RUN's mean measures side by side.

    Parameters
    ----------
    networks : NetworkComparison
    phases : sequence of (str, float, float)
        ``(label, start, stop)`` in RUN's seconds; a window belongs to the phase its centre
        lies in.
    threshold : float
        Departure (spreads) beyond which a measure of a pair has moved.

    Returns
    -------
    pandas.DataFrame
        ``phase``, ``start``, ``stop``, ``axis``, ``pair``, ``<measure> refs`` and
        ``<measure> RUN`` per measure, and ``beyond`` (the measures that moved beyond the
        references' spread in some window of the phase, with the largest departure; "" when
        none).

    Examples
    --------
    >>> net = NetworkComparison(np.array([0.0, 0.5]), 1.0, 0.5, np.arange(200) * 0.01,
    ...     {(1, "RC-AC", "c_diff"): np.array([0.1, 0.5])},
    ...     {(1, "RC-AC", "c_diff"): np.array([0.1, 0.1])},
    ...     {(1, "RC-AC", "c_diff"): np.array([0.02, 0.02])},
    ...     {(1, "RC-AC", "c_diff"): np.array([0.0, 14.1])}, 2, 0)
    >>> phase_summary(net, [("move 1", 0.0, 2.0)], threshold=6.0).iloc[0]["beyond"]
    'c_diff (14.1)'
    """
    centres = networks.starts + networks.window / 2
    rows = []
    keys = sorted(networks.run)
    for label, start, stop in phases:
        inside = (centres >= start) & (centres < stop)
        if not inside.any():
            continue
        for axis, pair in dict.fromkeys((a, p) for a, p, _ in keys):
            row: dict[str, object] = {"phase": label, "start": start, "stop": stop,
                                      "axis": axis, "pair": pair}
            beyond = []
            for m in MEASURES:
                key = (axis, pair, m)
                if key not in networks.run:
                    continue
                row[f"{m} refs"] = round(_mean(networks.centre[key][inside]), 3)
                row[f"{m} RUN"] = round(_mean(networks.run[key][inside]), 3)
                sizes = networks.size[key][inside]
                sizes = sizes[np.isfinite(sizes)]
                if sizes.size and sizes.max() > threshold:
                    beyond.append(f"{m} ({sizes.max():.1f})")
            row["beyond"] = ", ".join(beyond)
            rows.append(row)
    return pd.DataFrame(rows)
