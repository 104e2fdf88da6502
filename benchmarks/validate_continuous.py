"""Why the reversal error at a continuous turn misses the simulator's truth: a decomposition.

Prints the table of docs/validation/backlash.md, section 5.1: on the continuous sweep
(:func:`funcnet.sim.plan.continuous_sweep_plan`, 216 trials) the share of trials whose
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

Then the dead zone told from friction (:func:`~funcnet.diagnosis.dead_zone.gear_parts`)
per speed and backlash width, and the AUC of ">= 0.5 arcmin against none" for the two-encoder
estimate and for a motor-side reading -- the same estimate with the set-point RP in the arm
encoder's place (``MP - RP``: the wind-up, the loop's lag, which the speed term takes, and the
dead zone) -- on this plan and on
a held-out plan the sweep does not contain (backlash 0, 0.5, 1, 2 arcmin, load 0 and 1000 N m,
70 and 120 deg/min, TCP 1.4 and 1.8 m, friction 0.85 and 1.2, seed 11: 64 trials), positives
by the backlash width and by the truth (the dead zone crossed: a loaded gear never crosses it).

    PYTHONPATH=src python benchmarks/validate_continuous.py [--workers 2]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

from funcnet.diagnosis.dead_zone import gear_parts
from funcnet.diagnosis.reversal_error import fit_gear, reversal_error
from funcnet.diagnosis.reversals import find_direction_changes, motor_side_recording
from funcnet.robot.phases import move_threshold
from funcnet.robot.preprocess import velocity
from funcnet.sim import Trial, simulate_trial
from funcnet.sim.plan import continuous_sweep_plan
from funcnet.validation.sweep import simulated_recording

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
    fast = np.flatnonzero(np.abs(vm) > move_threshold(vm))
    flank = fast[np.abs(tau[fast]) > FLANK]
    gear = fit_gear(rec)
    n, fs = p.gear_ratio, p.friction_scale
    motor_speed = np.radians(vm) * n  # rad/s on the motor shaft
    own = p.motor_inertia * _mean(np.gradient(motor_speed, rec.sample_period)) + fs * (
        p.motor_coulomb * np.sign(motor_speed) + p.motor_viscous * motor_speed
    )
    estimated = n * (p.torque_constant * _mean(current) - own)
    on_flank = fast[np.abs(estimated[fast]) > 3 * FLANK]
    library = [reversal_error(rec, c, gear, resamples=0).lost_motion for c in turns]
    parts = gear_parts(rec, resamples=0)
    motor_rec = dataclasses.replace(rec, data=rec.data.assign(AP=rec.data["RP"]))
    motor_gear = fit_gear(motor_rec)
    motor_side = [reversal_error(motor_rec, c, motor_gear, resamples=0).lost_motion
                  for c in turns]  # fmt: skip
    return {
        "name": trial.name,
        "backlash": p.backlash * 60,
        "load": p.arm_load,
        "friction": p.friction_scale,
        "speed": trial.speed,
        "truth": sim.truth["lost_motion"] * 60,
        "encoder_step": 360 / p.arm_encoder_counts * 60,
        "library": float(np.mean(library)) * 60,
        "motor side": float(np.mean(motor_side)) * 60,
        "dead zone": math.nan if parts.dead_zone is None else parts.dead_zone * 60,
        "true torque, linear fit": _step(t, turns, _fitted(d, tau, vm, fast, np.sign(vm))),
        "true torque, dead-zone fit": _step(t, turns, _fitted(d, tau, vm, flank, np.sign(tau))),
        "true torque and stiffness": _step(t, turns, d - tau / stiffness),
        "current less motor, dead-zone fit": _step(
            t, turns, _fitted(d, estimated, vm, on_flank, np.sign(estimated))
        ),
        "torque_rms": float(np.sqrt(np.mean((estimated - tau)[fast] ** 2))),
        "compliance_ratio": (gear.compliance if gear else math.nan)
        / (n * p.torque_constant / stiffness),
        "current x catalogue": _step(
            t, turns, d - p.gear_ratio * p.torque_constant * current / stiffness
        ),
    }


def held_out_plan() -> list[Trial]:
    """Continuous trials on values and a seed the sweep does not contain (64)."""
    return continuous_sweep_plan(
        backlash_arcmin=(0, 0.5, 1, 2), speeds=(70, 120), tcps=(1.4, 1.8),
        friction_scales=(0.85, 1.2), seeds=(11,), group="held-out",
    )  # fmt: skip


def auc(score: pd.Series, positive: pd.Series, negative: pd.Series) -> float:
    """P(a positive's score > a negative's), ties counted half."""
    pos = score[positive].to_numpy()[:, None]
    neg = score[negative].to_numpy()[None, :]
    return float(np.mean((pos > neg) + 0.5 * (pos == neg)))


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
        "backlash, torque keeps its sign (2 steps)": (df["load"] == 0)
        & (df["backlash"] > 0)
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
    print(
        "\nthe motor's own torque's share of the step (current x catalogue less true torque), "
        "arcmin, median [min, max] per friction scale:"
    )
    for scale, part in motor.groupby(df["friction"]):
        print(f"  friction {scale}: {part.median():+.3f} [{part.min():+.3f}, {part.max():+.3f}]")
    for column, text in (
        ("compliance_ratio", "fitted compliance / N kt / stiffness"),
        ("torque_rms", "gear torque from current less motor, RMS error, N m"),
    ):
        print(
            f"{text}: median {df[column].median():.2f} [{df[column].min():.2f}, "
            f"{df[column].max():.2f}]; without backlash and load "
            f"{df[column][(df['backlash'] == 0) & (df['load'] == 0)].median():.2f}, "
            f"4 arcmin without load "
            f"{df[column][(df['backlash'] == 4) & (df['load'] == 0)].median():.2f}"
        )
    crossings = df[groups["dead zone crossed (within 5 %)"]]
    within = (crossings["library"] - crossings["truth"]).abs() <= 0.05 * crossings["truth"]
    print("\nthe library per speed: crossings within 5 %, no-backlash estimates (arcmin):")
    for v in sorted(df["speed"].unique()):
        none = df[(df["backlash"] == 0) & (df["speed"] == v)]["library"]
        print(
            f"  {v:g} deg/min: {100 * within[crossings['speed'] == v].mean():.1f} % of "
            f"{int((crossings['speed'] == v).sum())}; without backlash {none.min():+.3f} "
            f"to {none.max():+.3f}"
        )
    print("\nmedian truth / estimates per backlash without a load (arcmin):")
    print(
        df[df["load"] == 0].groupby("backlash")[["truth", *ESTIMATES]].median().round(3).to_string()
    )
    print("\nthe dead zone told from friction (gear_parts), trials without a load: told apart "
          "/ trials, and the term's range (arcmin):")
    for (v, width), part in df[df["load"] == 0].groupby(["speed", "backlash"]):
        told = part["dead zone"].dropna()
        span = f"{told.min():.2f}-{told.max():.2f}" if len(told) else "-"
        print(f"  {v:g} deg/min, backlash {width:g}: {len(told)}/{len(part)}, {span}")
    print(f"  with the load: told apart on {int(df[df['load'] > 0]['dead zone'].notna().sum())} "
          f"of {int((df['load'] > 0).sum())}")
    with ProcessPoolExecutor(args.workers) as pool:
        held = pd.DataFrame(pool.map(trial_row, held_out_plan(), chunksize=4))
    print("\nAUC, >= 0.5 arcmin against none (n positive / n negative):")
    print("| plan | positives | two-encoder | motor side (RP for AP) |")
    print("|---|---|---|---|")
    for plan_name, frame in (("sweep", df), ("held-out", held)):
        none = frame["backlash"] == 0
        for label, positive in (
            ("backlash >= 0.5, any load", frame["backlash"] >= 0.5),
            ("backlash >= 0.5, no load", (frame["backlash"] >= 0.5) & (frame["load"] == 0)),
            ("backlash >= 0.5, load", (frame["backlash"] >= 0.5) & (frame["load"] > 0)),
            ("truth >= 0.5", frame["truth"] >= 0.5),
            *(
                (f"truth >= 0.5, {v:g} deg/min", (frame["truth"] >= 0.5) & (frame["speed"] == v))
                for v in sorted(frame["speed"].unique())
            ),
        ):
            negative = none
            if "load" in label and "any" not in label:
                negative = none & ((frame["load"] > 0) == label.endswith(", load"))
            if "deg/min" in label:
                negative = none & (frame["speed"] == float(label.split(", ")[1].split()[0]))
            counts = f"{int(positive.sum())}/{int(negative.sum())}"
            print(
                f"| {plan_name} | {label} ({counts}) | "
                f"{auc(frame['library'], positive, negative):.3f} | "
                f"{auc(frame['motor side'], positive, negative):.3f} |"
            )


if __name__ == "__main__":
    main()
