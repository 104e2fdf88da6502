"""Why the reversal error at a continuous turn misses the simulator's truth: a decomposition.

Prints the table of docs/backlash.md, section 5.1: on the continuous sweep
(:func:`funcnet.robot.sim.plan.continuous_sweep_plan`, 216 trials) the share of trials whose
mean reversal error lies within 5 % of the truth (the dead zone crossed) or within two
arm-encoder steps of it (no backlash; a load keeping the gear on one flank; a turn whose gear
torque keeps its sign), for the library's estimate and for the same step measured with what a
recording does not hold -- the simulator's gear torque (noise-free state) and its stiffness:

- ``library``: :func:`~funcnet.diagnosis.reversal_error.fit_gear` and
  :func:`~funcnet.diagnosis.reversal_error.reversal_error` (what the sweep reports);
- ``true torque, linear fit``: the same fit and step with the gear torque in the current's place;
- ``true torque, dead-zone fit``: ``MP - AP`` on a constant, the gear torque, the motor speed and
  ``sign(gear torque)``, over the samples with ``|gear torque| > 20 N m`` (on a flank);
- ``true torque and stiffness``: the step of ``MP - AP - gear torque / stiffness`` (nothing
  fitted: what the truth measures, from the encoders' readings);
- ``current less motor, dead-zone fit``: the dead-zone fit on the gear torque estimated from the
  current with the simulator's own motor constants (``N (kt AC - J_m a_m - friction)``, current
  and acceleration as moving means over 40 ms): what knowing the motor would buy;
- ``current x catalogue``: the step of ``MP - AP - N kt AC / stiffness`` (the motor current
  taken for the gear torque with the simulator's own constants: its difference from the row
  above is the motor's own torque, inertia and friction, which the current carries and the gear
  does not).

    PYTHONPATH=src python benchmarks/validate_continuous.py [--workers 2]
"""

from __future__ import annotations

import argparse
import math
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

from funcnet.diagnosis.reversal_error import fit_gear, reversal_error
from funcnet.diagnosis.reversals import find_direction_changes, motor_side_recording
from funcnet.diagnosis.sweep import simulated_recording
from funcnet.robot.preprocess import velocity
from funcnet.robot.sim import Trial, simulate_trial
from funcnet.robot.sim.plan import continuous_sweep_plan

WINDOW = 0.25  # s, the stretches beside the turn (the estimator's and the truth's)
FLANK = 20.0  # N m: a sample on a flank of the dead zone
ESTIMATES = (
    "library",
    "true torque, linear fit",
    "true torque, dead-zone fit",
    "true torque and stiffness",
    "current x catalogue",
    "current less motor, dead-zone fit",
)
SMOOTH = 10  # samples (40 ms at 4 ms): the moving mean of gear_torque


def _step(t: np.ndarray, turns: list, rest: np.ndarray) -> float:
    """Mean over the turns of the step of ``rest`` across each (old direction's sign), arcmin."""
    steps = []
    for c in turns:
        before = (t >= c.stop - WINDOW) & (t < c.stop)
        after = (t >= c.start) & (t < c.start + WINDOW)
        steps.append(-c.direction * (rest[before].mean() - rest[after].mean()))
    return float(np.mean(steps)) * 60


def _fitted(d: np.ndarray, torque: np.ndarray, vm: np.ndarray, rows: np.ndarray,
            zone: np.ndarray) -> np.ndarray:  # fmt: skip
    """``d`` less the fitted wind-up and skew (least squares with ``zone`` as the last term)."""
    x = np.column_stack([np.ones(rows.size), torque[rows], vm[rows], zone[rows]])
    coef, *_ = np.linalg.lstsq(x, d[rows], rcond=None)
    return d - coef[1] * torque - coef[2] * vm


def _mean(x: np.ndarray) -> np.ndarray:
    """Moving mean over :data:`SMOOTH` samples."""
    padded = np.pad(x, (SMOOTH // 2, SMOOTH - 1 - SMOOTH // 2), mode="edge")
    return np.convolve(padded, np.ones(SMOOTH) / SMOOTH, mode="valid")


def trial_row(trial: Trial) -> dict[str, float | str]:
    """Truth and the five estimates of one trial (arcmin)."""
    sim = simulate_trial(trial, seed=trial.seed or 0)
    p = sim.params
    rec = motor_side_recording(simulated_recording(sim))
    turns = [c for c in find_direction_changes(rec) if c.kind == "continuous"]
    t = rec.data.index.to_numpy(dtype=np.float64)
    mp = rec.data["MP"].to_numpy(dtype=np.float64)
    d = mp - rec.data["AP"].to_numpy(dtype=np.float64)
    vm = velocity(mp, rec.sample_period)
    current = rec.data["AC"].to_numpy(dtype=np.float64)
    tau = sim.states["gear_torque"].reindex(rec.data.index, method="nearest").to_numpy()
    stiffness = p.gear_stiffness * p.stiffness_scale * math.pi / 180  # N m per deg
    # the library's samples: the motor faster than 1 deg/s, or half its peak on a slow trial
    fast = np.flatnonzero(np.abs(vm) > min(1.0, 0.5 * float(np.abs(vm).max())))
    flank = fast[np.abs(tau[fast]) > FLANK]
    gear = fit_gear(rec)
    n, fs = p.gear_ratio, p.friction_scale
    motor_speed = np.radians(vm) * n  # rad/s on the motor shaft
    own = (p.motor_inertia * _mean(np.gradient(motor_speed, rec.sample_period))
           + fs * (p.motor_coulomb * np.sign(motor_speed) + p.motor_viscous * motor_speed))
    estimated = n * (p.torque_constant * _mean(current) - own)
    on_flank = fast[np.abs(estimated[fast]) > 3 * FLANK]
    library = [reversal_error(rec, c, gear, resamples=0).lost_motion for c in turns]
    return {
        "name": trial.name,
        "backlash": p.backlash * 60,
        "load": p.arm_load,
        "friction": p.friction_scale,
        "truth": sim.truth["lost_motion"] * 60,
        "encoder_step": 360 / p.arm_encoder_counts * 60,
        "library": float(np.mean(library)) * 60,
        "true torque, linear fit": _step(t, turns, _fitted(d, tau, vm, fast, np.sign(vm))),
        "true torque, dead-zone fit": _step(t, turns, _fitted(d, tau, vm, flank, np.sign(tau))),
        "true torque and stiffness": _step(t, turns, d - tau / stiffness),
        "current less motor, dead-zone fit": _step(
            t, turns, _fitted(d, estimated, vm, on_flank, np.sign(estimated))),
        "torque_rms": float(np.sqrt(np.mean((estimated - tau)[fast] ** 2))),
        "compliance_ratio": (gear.compliance if gear else math.nan)
        / (n * p.torque_constant / stiffness),
        "current x catalogue": _step(
            t, turns, d - p.gear_ratio * p.torque_constant * current / stiffness),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    plan = continuous_sweep_plan()
    t0 = time.perf_counter()
    with ProcessPoolExecutor(args.workers) as pool:
        df = pd.DataFrame(pool.map(trial_row, plan, chunksize=4))
    seconds = time.perf_counter() - t0
    step = df["encoder_step"].iloc[0]
    crossed = (df["load"] == 0) & (df["backlash"] > 0) & (df["truth"] > 0.5 * df["backlash"])
    groups = {
        "dead zone crossed (within 5 %)": crossed,
        "backlash, load on one flank (2 steps)": (df["load"] > 0) & (df["backlash"] > 0),
        "backlash, torque keeps its sign (2 steps)": (df["load"] == 0) & (df["backlash"] > 0)
        & ~crossed,
        "no backlash (2 steps)": df["backlash"] == 0,
    }
    print(f"{len(df)} trials in {seconds:.0f} s; arm-encoder step {step:.5f} arcmin")
    print("| estimate | " + " | ".join(f"{g} n={int(m.sum())}" for g, m in groups.items()) + " |")
    print("|---" * (len(groups) + 1) + "|")
    for name in ESTIMATES:
        error = (df[name] - df["truth"]).abs()
        cells = []
        for group, mask in groups.items():
            hit = error[mask] <= (0.05 * df["truth"][mask] if "5 %" in group else 2 * step)
            cells.append(f"{100 * hit.mean():.1f} %" if mask.any() else "-")
        print(f"| {name} | " + " | ".join(cells) + " |")
    motor = df["current x catalogue"] - df["true torque and stiffness"]
    print("\nthe motor's own torque's share of the step (current x catalogue less true torque), "
          "arcmin, median [min, max] per friction scale:")
    for scale, part in motor.groupby(df["friction"]):
        print(f"  friction {scale}: {part.median():+.3f} [{part.min():+.3f}, {part.max():+.3f}]")
    for column, text in (("compliance_ratio", "fitted compliance / N kt / stiffness"),
                         ("torque_rms", "gear torque from current less motor, RMS error, N m")):
        print(f"{text}: median {df[column].median():.2f} [{df[column].min():.2f}, "
              f"{df[column].max():.2f}]; without backlash and load "
              f"{df[column][(df['backlash'] == 0) & (df['load'] == 0)].median():.2f}, "
              f"4 arcmin without load "
              f"{df[column][(df['backlash'] == 4) & (df['load'] == 0)].median():.2f}")
    print("\nmedian truth / estimates per backlash without a load (arcmin):")
    print(df[df["load"] == 0].groupby("backlash")[["truth", *ESTIMATES]].median().round(3)
          .to_string())


if __name__ == "__main__":
    main()
