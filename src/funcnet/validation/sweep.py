"""The backlash sweep: simulate, compute every indicator per trial, score them against the truth.

:func:`run_sweep` simulates a plan (:func:`funcnet.sim.plan.backlash_sweep_plan`) in
memory -- each trial's signals exactly as its trace file would hold them (six decimals, AP and
MP on their own logging grid) -- and computes the indicators of
:mod:`funcnet.diagnosis.indicators` at its reversal, next to the trial's ground truth;
:func:`folder_indicators` does the same from the traces and ``manifest.csv`` that ``funcnet
simulate`` wrote (the file's time stamps differ from the simulator's by 1e-15 s, which can move
an indicator's window edge by one tick: ``vibration`` then differs slightly, the FN features
not). Trials are spread over spawned worker processes in chunks; each worker loads the compiled
kernels once. :func:`score_indicators` gives, per speed and noise level, detection AUCs and
Spearman's rho with bootstrap intervals; :func:`calibration` the per-backlash quantiles that
:func:`funcnet.diagnosis.diagnose_backlash` reads a score on; :func:`lost_motion_accuracy` the
two-encoder lost motion against its truth.

Length: over 600 lines because running the sweep and scoring it against the truth share the
indicator table's columns.
"""

from __future__ import annotations

import math
import multiprocessing
import os
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy.stats import rankdata

from funcnet.diagnosis.indicators import (
    CONTACT_FEATURES,
    INDICATORS,
    reversal_indicators,
    with_contact_score,
)
from funcnet.diagnosis.reversal_error import fit_gear, reversal_error
from funcnet.diagnosis.reversals import find_direction_changes, motor_side_recording
from funcnet.errors import ParameterError, TraceError
from funcnet.robot.io.read import read_trace
from funcnet.robot.recording import Recording
from funcnet.robot.signals import SignalInfo
from funcnet.sim.axis import (
    AxisParameters,
    SimulatedTrial,
    real_axis_parameters,
    simulate_trial,
)
from funcnet.sim.plan import ARCMIN
from funcnet.sim.trial import Trial

__all__ = [
    "contact_reference",
    "simulated_recording",
    "trial_indicators",
    "trace_indicators",
    "folder_indicators",
    "run_sweep",
    "score_indicators",
    "calibration",
    "derive_calibration",
    "lost_motion_accuracy",
    "CONTRASTS",
]

#: Detection contrasts (arcmin): name -> (positive class test, negative class test).
CONTRASTS: dict[str, tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]]
CONTRASTS = {
    "auc_0.5_vs_0": (lambda b: b >= 0.5 - 1e-9, lambda b: b <= 1e-9),
    "auc_1_vs_0": (lambda b: b >= 1 - 1e-9, lambda b: b <= 1e-9),
    "auc_2_vs_0.5": (lambda b: b >= 2 - 1e-9, lambda b: b <= 0.5 + 1e-9),
}


_UNITS = {"RP": "posn", "AP": "posn", "MP": "posn", "RC": "current", "AC": "current"}


def simulated_recording(sim: SimulatedTrial) -> Recording:
    """A simulated trial as its trace file holds it: six decimals, AP and MP on their grid.

    Examples
    --------
    >>> from funcnet.sim import Trial, simulate_trial
    >>> sim = simulate_trial(Trial("q", "s", speed=350, tcp=1.2, step=1, sensors="real"))
    >>> rec = simulated_recording(sim)
    >>> rec.signals["MP"].interval, rec.signals["RC"].interval
    (0.004, 0.002)
    """
    p = sim.params
    data = sim.data.round(6) + 0.0
    info = {
        name: SignalInfo(
            name,
            _UNITS[name],
            "double",
            p.position_log_period if name in ("AP", "MP") else p.log_period,
        )
        for name in data.columns
    }
    return Recording(data, {}, info, source=f"{sim.trial.name}.xml", sample_period=p.log_period)


def trial_indicators(
    trial: Trial, networks: bool = True, seed: int = 0, evidence: bool = False,
    intervals: int = 0,
) -> dict[str, Any]:
    """Simulate one trial and compute its indicators at its first reversal, with its truth.

    Parameters
    ----------
    trial : Trial
        A forward-then-reverse trial.
    networks : bool
        Compute the functional-network features too.
    seed : int
        Noise seed when the trial has none of its own.
    evidence : bool
        Build the motor-side networks with the coupling test (``fn_coupled``).
    intervals : int
        With ``evidence``: subsamples of the resampling intervals (0: none; see
        :func:`~funcnet.diagnosis.indicators.reversal_indicators`).

    Returns
    -------
    dict
        The trial's name, speed, tcp, knobs and options, ``backlash_arcmin``, the true
        ``lost_motion`` (deg), ``peak_speed`` (deg/min the set-point reaches), and every
        indicator of
        :data:`~funcnet.diagnosis.indicators.INDICATORS` (NaN without a reversal).
    """
    sim = simulate_trial(trial, seed=seed if trial.seed is None else trial.seed)
    p = sim.params
    row: dict[str, Any] = {
        "name": trial.name,
        "speed": trial.speed,
        "tcp": trial.tcp,
        "backlash": p.backlash,
        "backlash_arcmin": round(p.backlash / ARCMIN, 9),
        "friction_scale": p.friction_scale,
        "stiffness_scale": p.stiffness_scale,
        "noise_scale": p.noise_scale,
        "seed": trial.seed,
        "sensors": trial.sensors or "paper",
        "arm_model": p.arm_model,
        "position_feedback": p.position_feedback,
        "arm_load": p.arm_load,
        "profile": trial.profile or "step",
        "true_lost_motion": sim.truth["lost_motion"],
    }
    # the speed the set-point reaches (a short step at a high speed never cruises): what a
    # trace shows, and what the calibration is keyed by
    row["peak_speed"] = round(float(np.abs(sim.data["RP"].diff()).max() / p.log_period * 60), 1)
    row.update(_first_reversal(simulated_recording(sim), networks, evidence, intervals))
    return row


def _first_reversal(recording: Recording, networks: bool, evidence: bool, intervals: int = 0
                    ) -> dict[str, Any]:  # fmt: skip
    """The indicators at a recording's first reversal (NaN without one)."""
    rec = motor_side_recording(recording)
    found = find_direction_changes(rec)
    changes = [c for c in found if c.kind == "reversal"]
    if changes:
        return reversal_indicators(rec, changes[0], networks=networks, evidence=evidence,
                                   intervals=intervals)  # fmt: skip
    row = dict.fromkeys(("turn_time", *INDICATORS), math.nan)
    turns = [c for c in found if c.kind == "continuous"]
    if turns and "AP" in rec.data.columns:  # continuous motion: the mean reversal error
        gear = fit_gear(rec)
        errors = [reversal_error(rec, c, gear, resamples=0).lost_motion for c in turns]
        turn = turns[0].turn if turns[0].turn is not None else turns[0].stop
        row.update(turn_time=turn, lost_motion=float(np.mean(errors)))
    return row


def trace_indicators(
    path: str | os.PathLike[str], truth: Mapping[str, Any], networks: bool = True,
    evidence: bool = False,
) -> dict[str, Any]:  # fmt: skip
    """One written trial's indicators at its first reversal, beside its manifest row's truth.

    Parameters
    ----------
    path : path-like
        The trace (as ``funcnet simulate`` writes it).
    truth : mapping
        Its ``manifest.csv`` row (:data:`~funcnet.sim.plan.MANIFEST_COLUMNS`).
    networks, evidence : bool
        As :func:`trial_indicators`.

    Returns
    -------
    dict
        The columns of :func:`trial_indicators`; ``backlash_arcmin`` from the manifest's
        ``backlash`` (deg), ``true_lost_motion`` its ``lost_motion``, ``peak_speed`` from the
        trace's RP.
    """
    row: dict[str, Any] = {name: truth[name] for name in _TRUTH if name in truth}
    row["backlash_arcmin"] = round(float(truth["backlash"]) / ARCMIN, 9)
    row["true_lost_motion"] = float(truth["lost_motion"])
    for name in ("arm_model", "position_feedback", "sensors"):
        row.setdefault(name, truth.get(name, ""))
    # a manifest has these only when a trial sets them (the continuous sweep)
    row["arm_load"] = float(truth.get("arm_load") or 0.0)
    row["profile"] = str(truth.get("profile") or "step")
    rec = read_trace(path)
    rp = rec.data["RP"].to_numpy(dtype=np.float64)
    row["peak_speed"] = round(float(np.nanmax(np.abs(np.diff(rp))) / rec.sample_period * 60), 1)
    row.update(_first_reversal(rec, networks, evidence))
    return row


#: The manifest's columns a row of :func:`folder_indicators` keeps (its order of
#: :func:`trial_indicators`' columns).
_TRUTH = ("name", "speed", "tcp", "backlash", "friction_scale", "stiffness_scale", "noise_scale",
          "seed", "sensors", "arm_model", "position_feedback")


def folder_indicators(
    folder: str | os.PathLike[str],
    *,
    networks: bool = True,
    evidence: bool = True,
    workers: int = 1,
    progress: Callable[[int, int, str], None] | None = None,
) -> pd.DataFrame:
    """Every trial's indicators and truth from a folder ``funcnet simulate`` wrote.

    Parameters
    ----------
    folder : path-like
        Traces and their ``manifest.csv`` (e.g. ``funcnet simulate --plan backlash-sweep``).
    networks, evidence : bool
        The functional-network features, and the coupling test in them (on by default: the
        sweep's analysis without the resampling intervals).
    workers : int
        Processes (spawned); 1 runs here.
    progress : callable, optional
        ``progress(done, total, name)`` after each chunk of trials.

    Returns
    -------
    DataFrame
        One row per manifest row (:func:`trace_indicators`), in the manifest's order.

    Raises
    ------
    TraceError
        No ``manifest.csv``, a manifest without the truth's columns, or a trace that cannot be
        read (the message names the file).
    ParameterError
        ``workers`` not a positive integer.
    """
    folder = Path(folder)
    path = folder / "manifest.csv"
    if not path.is_file():
        raise TraceError(path, "no manifest.csv (write the traces with funcnet simulate)")
    manifest = pd.read_csv(path, keep_default_na=False)
    missing = [c for c in ("name", "file", "speed", "backlash", "lost_motion")
               if c not in manifest.columns]  # fmt: skip
    if missing:
        raise TraceError(path, f"has no column(s) {missing}")
    tasks = [(folder / str(r["file"]), r) for r in manifest.to_dict(orient="records")]
    return pd.DataFrame(
        _map_chunks(_trace_rows, tasks, workers, progress, (networks, evidence),
                    [str(r["name"]) for _, r in tasks])  # fmt: skip
    )


def _trace_rows(
    chunk: Sequence[tuple[Path, dict[str, Any]]], networks: bool, evidence: bool
) -> list[dict[str, Any]]:
    return [trace_indicators(path, truth, networks, evidence) for path, truth in chunk]


def _map_chunks(
    function: Callable[..., list[dict[str, Any]]],
    items: Sequence[Any],
    workers: int,
    progress: Callable[[int, int, str], None] | None,
    arguments: tuple[Any, ...],
    names: Sequence[str],
) -> list[dict[str, Any]]:
    """``function(chunk, *arguments)`` over chunks of ``items``, in ``workers`` spawned
    processes (each compiles or loads the kernels once and keeps them for its chunks)."""
    if not isinstance(workers, int) or workers < 1:
        raise ParameterError.of("workers", f"must be a positive integer, got {workers!r}")
    size = max(1, min(25, len(items) // (4 * workers) or 1))
    chunks = [items[i : i + size] for i in range(0, len(items), size)]
    rows: list[dict[str, Any]] = []
    if workers > 1 and len(chunks) > 1:
        spawn = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=workers, mp_context=spawn) as pool:
            futures = [pool.submit(function, chunk, *arguments) for chunk in chunks]
            for future in futures:
                rows += future.result()
                if progress:
                    progress(len(rows), len(items), names[len(rows) - 1])
    else:
        for chunk in chunks:
            rows += function(chunk, *arguments)
            if progress:
                progress(len(rows), len(items), names[len(rows) - 1])
    return rows


def _rows(
    chunk: Sequence[Trial], networks: bool, seed: int, evidence: bool, intervals: int
) -> list[dict[str, Any]]:
    return [trial_indicators(t, networks, seed, evidence, intervals) for t in chunk]


def run_sweep(
    trials: Sequence[Trial],
    *,
    networks: bool = True,
    workers: int = 1,
    seed: int = 0,
    evidence: bool = False,
    intervals: int = 0,
    progress: Callable[[int, int, str], None] | None = None,
) -> pd.DataFrame:
    """Every trial's indicators and truth, one row per trial (see :func:`trial_indicators`).

    Parameters
    ----------
    trials : sequence of Trial
    networks : bool
        Compute the functional-network features (most of the time goes there).
    workers : int
        Processes (spawned); 1 runs here.
    seed : int
        Noise seed for trials without their own.
    evidence : bool
        With ``networks``: the coupling test too (``fn_coupled``).
    intervals : int
        With ``evidence``: subsamples of the resampling intervals too (0: none; they cost
        time and change no indicator).
    progress : callable, optional
        ``progress(done, total, name)`` after each chunk.

    Returns
    -------
    DataFrame

    Examples
    --------
    >>> from funcnet.sim.plan import backlash_sweep_plan
    >>> plan = backlash_sweep_plan(backlash_arcmin=(0, 2), speeds=(175,), tcps=(1.6,),
    ...                            friction_scales=(1,), stiffness_scales=(1,), seeds=(1,),
    ...                            noise_scales=(1,))
    >>> table = run_sweep(plan, networks=False)
    >>> bool(table.loc[1, "lost_motion"] > table.loc[0, "lost_motion"])
    True
    """
    trials = list(trials)
    return pd.DataFrame(
        _map_chunks(_rows, trials, workers, progress, (networks, seed, evidence, intervals),
                    [t.name for t in trials])  # fmt: skip
    )


def _auc(scores: np.ndarray, positive: np.ndarray, negative: np.ndarray) -> np.ndarray:
    """AUC of ``scores`` (resamples x n) between the boolean classes (same shape).

    The bootstrap's AUCs, all draws in one ranking: each draw equals :func:`_auc_point` (the
    Mann-Whitney U of :mod:`scipy.stats`), which would take a call per draw.

    Members of neither class (or with a NaN score) are set below every score: they take the
    lowest ranks, which shifts each positive's rank by their number, taken off again.
    """
    used = (positive | negative) & np.isfinite(scores)
    positive = positive & used
    ranks = rankdata(np.where(used, scores, -np.inf), axis=-1)
    n1 = positive.sum(axis=-1)
    n0 = (negative & used).sum(axis=-1)
    excluded = (~used).sum(axis=-1)
    u = (ranks * positive).sum(axis=-1) - n1 * (n1 + 1) / 2 - n1 * excluded
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.asarray(u / (n1 * n0), dtype=np.float64)


def _spearman(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Spearman's rho of each row (the bootstrap's draws at once); each equals
    :func:`scipy.stats.spearmanr` of the row, which is not vectorized over draws."""
    if x.shape[-1] == 0:  # an indicator not computed in this group (a continuous turn)
        return np.full(x.shape[:-1], math.nan)
    rx, ry = rankdata(x, axis=-1), rankdata(y, axis=-1)
    rx = rx - rx.mean(axis=-1, keepdims=True)
    ry = ry - ry.mean(axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.asarray(
            (rx * ry).sum(axis=-1) / np.sqrt((rx**2).sum(axis=-1) * (ry**2).sum(axis=-1)),
            dtype=np.float64,
        )


def _auc_point(scores: np.ndarray, positive: np.ndarray, negative: np.ndarray) -> float:
    """AUC of one sample: the Mann-Whitney U of the positives' scores over the negatives',
    divided by the number of pairs (NaN without a member of either class)."""
    from scipy.stats import mannwhitneyu

    used = np.isfinite(scores)
    high, low = scores[positive & used], scores[negative & used]
    if high.size == 0 or low.size == 0:
        return math.nan
    return float(mannwhitneyu(high, low).statistic / (high.size * low.size))


def _spearman_point(x: np.ndarray, y: np.ndarray) -> float:
    """Spearman's rho of one sample (NaN when either is constant or empty)."""
    from scipy.stats import spearmanr

    if x.size < 2 or np.ptp(x) == 0 or np.ptp(y) == 0:
        return math.nan
    return float(spearmanr(x, y).statistic)


def score_indicators(
    table: pd.DataFrame,
    indicators: Sequence[str] = INDICATORS,
    *,
    by: Sequence[str] = ("speed", "noise_scale"),
    resamples: int = 500,
    level: float = 0.95,
    seed: int = 0,
) -> pd.DataFrame:
    """Detection AUCs and Spearman's rho of each indicator, with bootstrap intervals.

    Parameters
    ----------
    table : DataFrame
        From :func:`run_sweep` (``backlash_arcmin`` and the indicator columns).
    indicators : sequence of str
        Columns to score (higher = more backlash).
    by : sequence of str
        Columns to score separately (every other column -- friction, stiffness, TCP, seeds --
        varies inside a group).
    resamples : int
        Bootstrap resamples (trials drawn with replacement within the group).
    level : float
        Interval coverage (percentile intervals).
    seed : int
        Of the bootstrap.

    Returns
    -------
    DataFrame
        One row per group and indicator: ``n``, for each contrast of :data:`CONTRASTS` its AUC
        with ``_low`` and ``_high``, ``rho`` with ``rho_low`` and ``rho_high`` (Spearman with
        the true backlash), and ``signature_rate`` per backlash width for ``signature``.

    Examples
    --------
    >>> t = pd.DataFrame({"speed": [35.0] * 4, "noise_scale": [1.0] * 4,
    ...                   "backlash_arcmin": [0, 0, 1, 2], "x": [0.1, 0.2, 0.3, 0.4]})
    >>> row = score_indicators(t, ["x"], resamples=50).iloc[0]
    >>> float(row["auc_1_vs_0"]), round(float(row["rho"]), 12)
    (1.0, 0.948683298051)
    """
    rng = np.random.default_rng(seed)
    alpha = (1 - level) / 2
    out = []
    for key, group in table.groupby(list(by), sort=True):
        truth = group["backlash_arcmin"].to_numpy(dtype=np.float64)
        n = truth.size
        draws = rng.integers(0, n, size=(resamples, n))
        for name in indicators:
            values = group[name].to_numpy(dtype=np.float64)
            ok = np.isfinite(values)
            row: dict[str, Any] = dict(
                zip(by, key if isinstance(key, tuple) else (key,), strict=True)
            )
            row.update(indicator=name, n=int(ok.sum()))
            for contrast, (pos, neg) in CONTRASTS.items():
                positive, negative = pos(truth), neg(truth)
                point = _auc_point(values, positive, negative)
                boot = _auc(values[draws], positive[draws], negative[draws])
                boot = boot[np.isfinite(boot)]
                row[contrast] = point
                row[contrast + "_low"], row[contrast + "_high"] = (
                    np.quantile(boot, [alpha, 1 - alpha]) if boot.size else (math.nan, math.nan)
                )
            row["rho"] = _spearman_point(values[ok], truth[ok])
            boot = _spearman(values[draws], truth[draws])  # NaN where a draw holds a NaN
            boot = boot[np.isfinite(boot)]
            row["rho_low"], row["rho_high"] = (
                np.quantile(boot, [alpha, 1 - alpha]) if boot.size else (math.nan, math.nan)
            )
            out.append(row)
    return pd.DataFrame(out)


def calibration(
    table: pd.DataFrame,
    indicator: str,
    *,
    by: str = "peak_speed",
    quantiles: Sequence[float] = (0.1, 0.5, 0.9),
) -> dict[str, Any]:
    """Per speed and backlash width, the quantiles of an indicator on the sweep.

    Parameters
    ----------
    table : DataFrame
        From :func:`run_sweep`.
    indicator : str
        The column to calibrate.
    by : str
        The speed column: ``peak_speed`` (deg/min the set-point reaches; a 1 deg step at 175
        deg/min peaks at 70.6 deg/min) by default, as a trace shows it.
    quantiles : sequence of float
        Of the indicator at each backlash width.

    Returns
    -------
    dict
        ``{"indicator", "quantiles", "by", "levels": {speed: {backlash_arcmin: [q...]}}}``,
        JSON-ready.

    Examples
    --------
    >>> t = pd.DataFrame({"peak_speed": [35.0] * 4, "backlash_arcmin": [0, 0, 1, 1],
    ...                   "x": [0.1, 0.2, 0.3, 0.4]})
    >>> calibration(t, "x", quantiles=(0.5,))["levels"]["35"]
    {'0': [0.15], '1': [0.35]}
    """
    levels: dict[str, dict[str, list[float]]] = {}
    for speed, group in table.groupby(by, sort=True):
        levels[f"{speed:g}"] = {
            f"{b:g}": [float(q) for q in np.nanquantile(g[indicator].to_numpy(float), quantiles)]
            for b, g in group.groupby("backlash_arcmin", sort=True)
        }
    return {"indicator": indicator, "quantiles": list(quantiles), "by": by, "levels": levels}


def derive_calibration(sweep: pd.DataFrame, motor: pd.DataFrame, *, source: str = "",
                       motor_source: str = "") -> dict[str, Any]:
    """The calibration the diagnosis ships (``diagnosis/calibration.json``), from two sweeps.

    Parameters
    ----------
    sweep : DataFrame
        The main sweep (:func:`run_sweep` of :func:`funcnet.sim.backlash_sweep_plan`): the
        arm-side score's levels.
    motor : DataFrame
        The sweep of an axis whose position loop reads the motor encoder: the motor-side
        score's levels and its no-backlash reference.
    source, motor_source : str
        How each sweep was made (kept in the file).

    Returns
    -------
    dict
        :func:`calibration` of :data:`~funcnet.diagnosis.diagnose.SCORE` with ``source``, and
        under ``motor_loop`` that of :data:`~funcnet.diagnosis.diagnose.MOTOR_LOOP_SCORE` with
        its ``reference`` (:func:`contact_reference`) and ``source``: JSON-ready.
    """
    from funcnet.diagnosis.diagnose import MOTOR_LOOP_SCORE, SCORE

    cal = calibration(sweep, SCORE)
    cal["source"] = source
    reference = contact_reference(motor)
    cal["motor_loop"] = calibration(with_contact_score(motor, reference), MOTOR_LOOP_SCORE)
    cal["motor_loop"]["reference"] = reference
    cal["motor_loop"]["source"] = motor_source
    return cal


def contact_reference(table: pd.DataFrame, *, by: str = "peak_speed") -> dict[str, Any]:
    """Median and interquartile range of :data:`CONTACT_FEATURES` without backlash, per speed.

    Parameters
    ----------
    table : DataFrame
        A sweep (:func:`run_sweep`) with trials of backlash 0.
    by : str
        The speed column.

    Returns
    -------
    dict
        ``{speed: {feature: [median, iqr]}}`` (speeds as ``f"{speed:g}"``), JSON-ready.

    Examples
    --------
    >>> t = pd.DataFrame({"peak_speed": 35.0, "backlash_arcmin": [0, 0, 0, 1],
    ...                   "motor_travel": [1.0, 2.0, 3.0, 9.0], "current_step": 0.5})
    >>> contact_reference(t)["35"]["motor_travel"]
    [2.0, 1.0]
    """
    reference: dict[str, Any] = {}
    healthy = table[table["backlash_arcmin"] == 0]
    for speed, group in healthy.groupby(by, sort=True):
        reference[f"{speed:g}"] = {
            name: [
                float(group[name].median()),
                float(group[name].quantile(0.75) - group[name].quantile(0.25)),
            ]
            for name in CONTACT_FEATURES
        }
    return reference




def lost_motion_accuracy(table: pd.DataFrame) -> pd.DataFrame:
    """The two-encoder ``lost_motion`` against its truth, per kind of motion, load and speed.

    The validation of the sweep's targets. A trial whose truth is the dead zone crossed
    (backlash, and a true lost motion above half its width) is judged by 5 % of the truth; every
    other (no backlash; a load or the arm's inertia keeping the gear on one flank, the truth
    then about nothing) by two arm-encoder steps (the step of the trial's sensors: ``"real"``
    the 840D sl trace's encoder, else the simulator's default). A missing estimate is a miss.

    Parameters
    ----------
    table : DataFrame
        A sweep's indicator table (:func:`run_sweep`, :func:`folder_indicators`): ``speed``,
        ``backlash_arcmin``, ``lost_motion`` and ``true_lost_motion`` (deg); ``profile``,
        ``arm_load`` and ``sensors`` when present.

    Returns
    -------
    DataFrame
        One row per (``profile``, ``arm_load``, ``speed``) present: ``n``; ``crossed`` (trials
        judged by 5 %), ``within_5_percent`` (their share), ``median_error_percent`` (signed);
        ``not_crossed``, ``within_2_steps``, ``median_error_steps`` (signed); NaN where a group
        has no such trial.

    Raises
    ------
    ParameterError
        A column the comparison needs is missing.

    Examples
    --------
    >>> t = pd.DataFrame({"speed": [35.0] * 3, "backlash_arcmin": [0.0, 1.0, 2.0],
    ...                   "lost_motion": [0.0, 1.02 / 60, 1.8 / 60],
    ...                   "true_lost_motion": [0.0, 1 / 60, 2 / 60]})
    >>> row = lost_motion_accuracy(t).iloc[0]
    >>> int(row["crossed"]), float(row["within_5_percent"]), float(row["within_2_steps"])
    (2, 0.5, 1.0)
    """
    needed = ("speed", "backlash_arcmin", "lost_motion", "true_lost_motion")
    missing = [c for c in needed if c not in table.columns]
    if missing:
        raise ParameterError.of("table", f"has no column(s) {missing}")
    table = table.assign(
        profile=table["profile"] if "profile" in table else "step",
        arm_load=table["arm_load"] if "arm_load" in table else 0.0,
    )
    counts = {"real": real_axis_parameters().arm_encoder_counts}
    default = AxisParameters().arm_encoder_counts
    sensors = table["sensors"] if "sensors" in table else pd.Series("", index=table.index)
    step = 360.0 / sensors.map(lambda s: counts.get(s, default)).astype(float)
    truth = table["true_lost_motion"]
    error = table["lost_motion"] - truth
    crossed = (table["backlash_arcmin"] > 0) & (truth > 0.5 * table["backlash_arcmin"] * ARCMIN)
    rows = []
    for key, part in table.groupby(["profile", "arm_load", "speed"], sort=True):
        judged = part.index[crossed[part.index]]
        other = part.index[~crossed[part.index]]
        relative = (error[judged] / truth[judged]).to_numpy()
        steps = (error[other] / step[other]).to_numpy()
        rows.append({
            "profile": key[0], "arm_load": key[1], "speed": key[2], "n": len(part),
            "crossed": len(judged),
            "within_5_percent": _share(np.abs(relative) <= 0.05),
            "median_error_percent": 100 * _median(relative),
            "not_crossed": len(other),
            "within_2_steps": _share(np.abs(steps) <= 2),
            "median_error_steps": _median(steps),
        })  # fmt: skip
    return pd.DataFrame(rows)


def _share(hits: np.ndarray) -> float:
    return float(hits.mean()) if hits.size else math.nan


def _median(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(np.median(finite)) if finite.size else math.nan
