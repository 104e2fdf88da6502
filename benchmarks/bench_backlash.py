"""The backlash sweep and its indicator table (docs/validation/backlash.md).

    .venv/bin/python benchmarks/bench_backlash.py            # full sweep, table, timings
    .venv/bin/python benchmarks/bench_backlash.py --calibrate  # also rewrite calibration.json
    .venv/bin/python benchmarks/bench_backlash.py --quick    # a small sweep (a minute)
    .venv/bin/python benchmarks/bench_backlash.py --compare  # real trace vs simulated
    .venv/bin/python benchmarks/bench_backlash.py --lost-motion  # the lost motion vs its truth
    .venv/bin/python benchmarks/bench_backlash.py --with-fn      # the whole sweep with FN features
    .venv/bin/python benchmarks/bench_backlash.py --with-fn --trials 500 --report /tmp/s.html
    .venv/bin/python benchmarks/bench_backlash.py --kuka         # the KUKA KR 300 runs' table

Simulates :func:`funcnet.sim.plan.backlash_sweep_plan` (1944 reversal trials: backlash x
speed x TCP x friction x stiffness x 3 seeds x noise 1 and 2, sensors and logging of the real
trace) and computes every physical indicator per trial; the functional-network features on a
subset (``--with-fn``: on the whole sweep, with the coupling test, about two minutes on two
workers); the same for the position loop closed on the motor
encoder, the elastic arm, and a held-out plan whose values the sweep does not contain. Prints
markdown tables: AUCs and Spearman's rho with 95 % bootstrap intervals per speed and noise.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy.signal import welch

from funcnet.diagnosis.diagnose import MOTOR_LOOP_SCORE, SCORE
from funcnet.diagnosis.indicators import FN_FEATURES, PHYSICAL, with_contact_score
from funcnet.robot import detect_phases, read_trace
from funcnet.sim.axis import simulate_trial
from funcnet.sim.plan import backlash_sweep_plan
from funcnet.sim.trial import Trial
from funcnet.validation.sweep import (
    contact_reference,
    derive_calibration,
    run_sweep,
    score_indicators,
    simulated_recording,
)

ROOT = Path(__file__).resolve().parents[1]
CALIBRATION = ROOT / "src" / "funcnet" / "diagnosis" / "calibration.json"
COLUMNS = ["auc_0.5_vs_0", "auc_1_vs_0", "auc_2_vs_0.5", "rho"]


def _fmt(row: pd.Series, name: str) -> str:
    value, low, high = row[name], row[name + "_low"], row[name + "_high"]
    return f"{value:.2f} [{low:.2f}, {high:.2f}]"


def table(scores: pd.DataFrame, title: str) -> str:
    """Markdown: one row per (speed, noise, indicator)."""
    head = "| speed | noise | indicator | n | AUC >=0.5 vs 0 | AUC >=1 vs 0 | AUC >=2 vs <=0.5 |"
    lines = [f"### {title}", "", head + " Spearman rho |", "|---|---|---|---|---|---|---|---|"]
    for _, row in scores.iterrows():
        cells = " | ".join(_fmt(row, c) for c in COLUMNS)
        noise = row.get("noise_scale", "")
        lines.append(f"| {row['speed']:g} | {noise} | {row['indicator']} | {row['n']} | {cells} |")
    return "\n".join(lines) + "\n"


class _Printer(list[str]):
    """Prints each part as it comes (a long run shows its tables early)."""

    def append(self, text: str) -> None:
        print(text, flush=True)
        super().append(text)


def _stretches(t: np.ndarray, rows: pd.DataFrame) -> list[np.ndarray]:
    return [(t >= row.start + 0.05) & (t < row.stop - 0.05) for row in rows.itertuples()]


REAL_TRACE = ROOT.parent / "shared" / "data" / "sinumerik" / "axis7-braking-trace.xml"


def _trace_figures(rec: Any) -> dict[str, float]:
    """Noise, resolution, update rates and following error of one recording."""
    phases = detect_phases(rec)
    t = rec.data.index.to_numpy()
    ac = rec.data["AC"].to_numpy(dtype=float)
    out: dict[str, float] = {}
    for phase in ("standstill", "cruise"):
        rows = phases[phases["phase"] == phase]
        if phase == "standstill":
            rows = rows[rows["stop"] - rows["start"] > 0.2]
        mask = np.zeros(t.size, dtype=bool)
        variances, diffs = [], []
        for row in rows.itertuples():  # each stretch about its own mean (moves differ in sign)
            part = (t >= row.start + 0.05) & (t < row.stop - 0.05)
            mask |= part
            if part.sum() > 2:
                variances.append(np.var(ac[part]))
                diffs.append(np.diff(ac[part]))
        out[f"AC sigma {phase} (A)"] = float(np.sqrt(np.mean(variances))) if variances else np.nan
        out[f"AC white sigma {phase} (A)"] = (
            float(np.std(np.concatenate(diffs)) / np.sqrt(2)) if diffs else np.nan
        )
        spectra = [welch(ac[part] - ac[part].mean(), fs=1 / rec.sample_period, nperseg=128)
                   for part in _stretches(t, rows) if part.sum() >= 128]  # fmt: skip
        if spectra:
            freqs = spectra[0][0]
            power = np.mean([p for _, p in spectra], axis=0)
            for lo, hi in ((0, 10), (10, 50), (50, 250)):
                band = (freqs >= lo) & (freqs < hi if hi < 250 else freqs <= hi)
                out[f"AC {phase}: share of power {lo}-{hi} Hz"] = float(
                    power[band].sum() / power.sum()
                )
        if phase == "cruise" and mask.any():
            rp, ap = rec.data["RP"].to_numpy(float), rec.data["AP"].to_numpy(float)
            v = np.abs(np.gradient(rp, rec.sample_period))[mask]
            out["following error / speed in cruise (ms)"] = float(
                np.median(np.abs(rp - ap)[mask] / v) * 1e3
            )
    duration = t[-1] - t[0]
    for name in ("AP", "MP"):
        x = rec.data[name].to_numpy(float)
        steps = np.abs(np.diff(x))
        out[f"smallest {name} step (deg)"] = float(steps[steps > 0].min())
        out[f"{name} updates per second"] = float((steps > 0).sum() / duration)
    return out


def compare_real() -> str:
    """Markdown: the real trace beside simulated traces (paper and real sensors)."""
    columns = {"real trace": _trace_figures(read_trace(REAL_TRACE))}
    for label, sensors in (("simulated, paper sensors", None), ("simulated, real sensors", "real")):
        sim = simulate_trial(Trial("cmp", "cmp", speed=175, tcp=1.6, step=10, sensors=sensors))
        columns[label] = _trace_figures(simulated_recording(sim))
    names = list(columns["real trace"])
    lines = ["| | " + " | ".join(columns) + " |", "|---" * (len(columns) + 1) + "|"]
    lines += [f"| {n} | " + " | ".join(f"{c.get(n, np.nan):.3g}" for c in columns.values()) + " |"
              for n in names]  # fmt: skip
    return "\n".join(lines) + "\n"


def figure(sweep: pd.DataFrame, path: Path) -> None:
    """Scatter of the score against the true backlash, and ROC curves (>= 0.5 arcmin vs 0)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    for col, speed in enumerate(sorted(sweep["speed"].unique())):
        part = sweep[sweep["speed"] == speed]
        ax = axes[0, col]
        for noise, marker in ((1.0, "o"), (2.0, "x")):
            sub = part[part["noise_scale"] == noise]
            ax.scatter(sub["backlash_arcmin"], sub[SCORE] * 60, s=6, marker=marker,
                       alpha=0.4, label=f"noise x{noise:g}")  # fmt: skip
        ax.set(xlabel="true backlash (arcmin)", ylabel=f"{SCORE} (arcmin)",
               title=f"{speed:g} deg/min")  # fmt: skip
        ax.legend()
        ax = axes[1, col]
        labels = part["backlash_arcmin"]
        keep = (labels >= 0.5) | (labels == 0)
        for name in (SCORE, "vibration", "current_step", "motor_travel", "lost_motion"):
            values = part.loc[keep, name].to_numpy(float)
            positive = (labels[keep] >= 0.5).to_numpy()
            order = np.argsort(-values)
            tpr = np.concatenate([[0], np.cumsum(positive[order]) / positive.sum()])
            fpr = np.concatenate([[0], np.cumsum(~positive[order]) / (~positive).sum()])
            ax.plot(fpr, tpr, label=name)
        ax.plot([0, 1], [0, 1], color="grey", lw=0.5)
        ax.set(xlabel="false positive rate", ylabel="true positive rate",
               title=f"ROC, >= 0.5 arcmin vs none, {speed:g} deg/min")  # fmt: skip
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    print(f"wrote {path}")


def _write_calibration(sweep: pd.DataFrame, motor: pd.DataFrame, source: str) -> None:
    """calibration.json: SCORE on the main sweep, MOTOR_LOOP_SCORE on the motor-loop sweep."""
    tables = []
    for table_ in (sweep, motor):
        if "peak_speed" not in table_:  # tables saved before the column existed: a 1 deg step
            table_ = table_.assign(peak_speed=np.minimum(table_["speed"], round(60 / 0.85, 1)))
        tables.append(table_)
    cal = derive_calibration(
        tables[0], tables[1],
        source=(f"benchmarks/bench_backlash.py --calibrate: {source}, {len(sweep)} trials, "
                "noise 1 and 2 pooled, quantiles over TCP, friction, stiffness and seeds"),
        motor_source=(f"backlash_sweep_plan(position_feedback='motor', seeds=(1,)), "
                      f"{len(motor)} trials"),
    )
    CALIBRATION.write_text(json.dumps(cal, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {CALIBRATION}")


def motor_contact_tables(folder: Path, resamples: int, out: list[str]) -> None:
    """motor_contact on the motor-loop sweep and on the held-out plan (reference: the sweep)."""
    sweep = pd.read_csv(folder / "sweep_motor.csv")
    held = pd.read_csv(folder / "heldout_motor.csv")
    for frame in (sweep, held):
        if "peak_speed" not in frame:
            frame["peak_speed"] = np.minimum(frame["speed"], round(60 / 0.85, 1))
    reference = contact_reference(sweep)
    names = [MOTOR_LOOP_SCORE, "motor_travel", "current_step"]
    for label, frame in (("position loop on the motor encoder: motor_contact", sweep),
                         ("held-out plan, motor-encoder loop: motor_contact (reference: the "
                          "sweep's no-backlash trials)", held)):  # fmt: skip
        scored = with_contact_score(frame, reference)
        out.append(table(score_indicators(scored, names, resamples=resamples), label))


def _fn_section(args: argparse.Namespace, out: list[str]) -> pd.DataFrame:
    """The functional-network subset (with the coupling test): table and signature rates."""
    start = time.perf_counter()
    fn_plan = backlash_sweep_plan(seeds=(1,), noise_scales=(1.0,), stiffness_scales=(1.0,),
                                  tcps=(1.2, 2.0), friction_scales=(0.7, 1.4))  # fmt: skip
    if args.quick:
        fn_plan = backlash_sweep_plan(seeds=(1,), noise_scales=(1.0,), tcps=(1.6,),
                                      friction_scales=(1.0,), stiffness_scales=(1.0,))  # fmt: skip
    fn = run_sweep(fn_plan, networks=True, workers=args.workers, evidence=True)
    elapsed = time.perf_counter() - start
    out.append(f"functional-network subset (with the coupling test of funcnet.evidence): "
               f"{len(fn_plan)} trials in {elapsed:.0f} s\n")  # fmt: skip
    out.append(table(score_indicators(fn, [SCORE, "vibration", *FN_FEATURES, "signature"],
                                      resamples=args.resamples),
                     "Functional-network features (seed 1, noise 1, stiffness 1, TCP 1.2/2.0, "
                     "friction 0.7/1.4)"))  # fmt: skip
    rate = fn.groupby(["speed", "backlash_arcmin"])["signature"].mean().unstack()
    lines = ["| speed | " + " | ".join(f"{b:g} arcmin" for b in rate.columns) + " |",
             "|---" * (len(rate.columns) + 1) + "|"]  # fmt: skip
    lines += [f"| {v:g} | " + " | ".join(f"{x:.2f}" for x in row) + " |"
              for v, row in zip(rate.index, rate.to_numpy(), strict=True)]  # fmt: skip
    out.append("paper's signature (V drives all, MP -> AP -> RP), share of trials:\n\n"
               + "\n".join(lines) + "\n")  # fmt: skip
    return fn


def with_fn(args: argparse.Namespace, out: list[str]) -> pd.DataFrame:
    """The main sweep (or ``--trials`` of it) simulated and analysed with every indicator: the
    FN features with the coupling test (no resampling intervals), timed; their tables."""
    plan = backlash_sweep_plan()
    if args.trials is not None and args.trials < len(plan):
        # a random subset (seed 0) keeps every part of the grid; the plan's order would not
        keep = np.sort(np.random.default_rng(0).choice(len(plan), args.trials, replace=False))
        plan = [plan[i] for i in keep]
    start = time.perf_counter()
    sweep = run_sweep(plan, networks=True, evidence=True, workers=args.workers,
                      intervals=args.intervals)  # fmt: skip
    elapsed = time.perf_counter() - start
    extra = f" and resampling intervals ({args.intervals} subsamples)" if args.intervals else ""
    out.append(f"sweep with FN features and the coupling test{extra}: {len(plan)} trials "
               f"simulated and analysed in {elapsed:.0f} s with {args.workers} workers\n")
    names = [SCORE, "vibration", *FN_FEATURES, "signature"]
    out.append(table(score_indicators(sweep, names, resamples=args.resamples),
                     f"Functional-network features on {len(plan)} trials of the main sweep"))
    rate = sweep.groupby(["speed", "backlash_arcmin"])["signature"].agg(["sum", "size"])
    out.append("paper's signature (V drives all, MP -> AP -> RP), trials with it: "
               + ", ".join(f"{v:g} deg/min {b:g} arcmin {int(r['sum'])}/{int(r['size'])}"
                           for (v, b), r in rate.iterrows()) + "\n")  # fmt: skip
    if args.save:
        args.save.mkdir(parents=True, exist_ok=True)
        sweep.to_csv(args.save / "sweep_with_fn.csv", index=False)
    if args.report:
        from funcnet.validation.sweep_report import write_sweep_report

        report = write_sweep_report(sweep, args.report, resamples=args.resamples,
                                    source=f"backlash_sweep_plan(), {len(plan)} trials")
        out.append(f"wrote {report.path}")
    return sweep


def lost_motion_summary(sweep: pd.DataFrame) -> str:
    """The two-encoder lost motion against the manifest's truth: the 5 % target, per width.

    Parameters
    ----------
    sweep : DataFrame
        From :func:`run_sweep` (``lost_motion``, ``true_lost_motion``, ``backlash_arcmin``).

    Returns
    -------
    str
        One line for the target, then one markdown row per backlash width.
    """
    step = 360 / 2**22  # the arm encoder's step (real sensors), deg
    rel = (sweep["lost_motion"] / sweep["true_lost_motion"] - 1).abs()
    steps = (sweep["lost_motion"] - sweep["true_lost_motion"]).abs() / step
    signed = (sweep["lost_motion"] - sweep["true_lost_motion"]) / step
    with_b = sweep["backlash_arcmin"] > 0
    lines = [
        f"two-encoder lost motion, backlash > 0: within 5 % on {(rel[with_b] <= 0.05).mean():.1%} "
        f"of {int(with_b.sum())} trials (median |error| {rel[with_b].median():.1%}, 90th "
        f"percentile {rel[with_b].quantile(0.9):.1%}); backlash 0: within two encoder steps on "
        f"{(steps[~with_b] <= 2).mean():.1%} of {int((~with_b).sum())} (median "
        f"{steps[~with_b].median():.1f} steps)",
        "",
        "| backlash (arcmin) | n | within 5 % | within 2 steps | median error (%) "
        "| median error (steps) | 90th pct. abs error (%) |",
        "|---|---|---|---|---|---|---|",
    ]
    for width, part in sweep.groupby("backlash_arcmin"):
        idx = part.index
        signed_rel = part["lost_motion"] / part["true_lost_motion"] - 1
        lines.append(
            f"| {width:g} | {len(part)} | {(rel[idx] <= 0.05).mean():.1%} | "
            f"{(steps[idx] <= 2).mean():.1%} | {100 * signed_rel.median():+.2f} | "
            f"{signed[idx].median():+.2f} | {100 * rel[idx].quantile(0.9):.1f} |"
        )
    return "\n".join(lines) + "\n"


def _lost_motion_other_sweeps(args: argparse.Namespace, out: list[str]) -> None:
    """The lost motion against its truth on the other sweeps of ``--save`` (one seed each:
    the first of ``--seeds``, or 1; the held-out plan its own)."""
    seed = (args.seeds[0],) if args.seeds else (1,)
    held = backlash_sweep_plan(backlash_arcmin=(0.0, 0.75, 1.5, 3.0), tcps=(1.4, 1.8),
                               friction_scales=(0.85, 1.2), stiffness_scales=(0.85, 1.2),
                               seeds=(7,), noise_scales=(1.5,), group="held-out")  # fmt: skip
    plans = {
        "motor": backlash_sweep_plan(seeds=seed, position_feedback="motor"),
        "elastic": backlash_sweep_plan(seeds=seed, arm_model="elastic"),
        "heldout": held,
        "heldout_motor": [
            dataclasses.replace(t, name=t.name + "-m", position_feedback="motor") for t in held
        ],
    }
    for key, plan in plans.items():
        part = run_sweep(plan, networks=False, workers=args.workers)
        out.append(f"lost motion, {key} sweep ({len(plan)} trials):\n")
        out.append(lost_motion_summary(part))
        if args.save:
            part.to_csv(args.save / f"lost_motion_{key}.csv", index=False)


def _kuka_recording(rec: Any, axis: int) -> Any:
    """One axis (1-based) of a KUKA run's ``rec`` struct: RP, MP, AP (axes 1-3), torque as AC."""
    from funcnet.robot import Recording, SignalInfo

    t = np.asarray(rec.time_cont, dtype=np.float64)
    columns = {"RP": rec.ref_pos_deg, "MP": rec.act_pos_mot_deg, "AC": rec.act_torque_abs_nm}
    if axis <= 3:
        columns["AP"] = rec.act_pos_se_deg
    data = pd.DataFrame({k: np.asarray(v[axis - 1], dtype=np.float64) for k, v in columns.items()},
                        index=pd.Index(t, name="time"))  # fmt: skip
    info = {c: SignalInfo(c, "torque" if c == "AC" else "posn", None, 0.004) for c in data}
    return Recording(data, {}, info, source=f"axis {axis}", sample_period=0.004)


def _parts_cell(parts: Any) -> str:
    """Dead zone and friction with their intervals (arcmin), or why they are not told apart."""
    if parts is None:
        return "-"
    if parts.dead_zone is None:
        return ("none (torque keeps one sign)" if "one sign" in parts.reason
                else f"none (torque and direction differ on {parts.disagreeing:.1%})")
    return (f"{60 * parts.dead_zone:+.2f} [{60 * parts.dead_zone_low:+.2f}, "
            f"{60 * parts.dead_zone_high:+.2f}]; {60 * parts.friction:+.2f} "
            f"[{60 * parts.friction_low:+.2f}, {60 * parts.friction_high:+.2f}]")


def kuka_table() -> str:
    """Per run and axis (1-3) of the KUKA KR 300 runs: the direction changes against the
    set-point's (stretches faster than 1 deg/s), the lost motion at each with its interval and
    ``traversed`` (also with the motor inertia of the runs' identification, ``para.J_mr`` times
    the gear ratio ``para.u``), the axis's lost motion, the plain least squares (MP - AP on a
    constant, the torque and the direction; motor faster than 1 deg/s), the same with the
    motor speed and with AP read at the time shift that fits best, and the gear's fit."""
    import scipy.io

    from funcnet.diagnosis import diagnose_recording
    from funcnet.diagnosis.reversal_error import torque_traversed
    from funcnet.diagnosis.reversals import motor_side_recording

    lines = ["| run | axis | set-point changes | found | turn (s) | lost motion (arcmin) [95 %] "
             "| traversed (with J_m) | axis lost_motion | plain LS | LS with speed "
             "| LS, encoders aligned (shift ms) | skew (ms) | compliance (arcsec/N m) | reading "
             "| dead zone; friction [95 %] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]  # fmt: skip
    for run in ("A", "B"):
        path = ROOT / "data" / "kuka-kr300" / f"kr300-run-{run}.mat"
        mat = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)
        rec, para = mat["rec"], mat["para"]
        for axis in (1, 2, 3):
            recording = _kuka_recording(rec, axis)
            t = recording.data.index.to_numpy()
            v = np.gradient(recording.data["RP"].to_numpy(), t)
            fast = np.sign(v) * (np.abs(v) > 1.0)
            signs = [s for i, s in enumerate(fast) if s and (i == 0 or s != fast[i - 1])]
            expected = sum(a != b for a, b in zip(signs, signs[1:], strict=False))
            result = diagnose_recording(recording, f"{run}{axis}")
            inertia = float(para.J_mr[axis - 1] * para.u[axis - 1] * np.pi / 180)
            moving = motor_side_recording(recording)
            plain = []
            mp, ap = recording.data["MP"].to_numpy(), recording.data["AP"].to_numpy()
            torque, vm = recording.data["AC"].to_numpy(), np.gradient(mp, t)
            use = np.abs(vm) > 1.0
            for with_speed in (False, True):
                x = np.column_stack([np.ones(use.sum()), torque[use]]
                                    + ([vm[use]] if with_speed else []) + [np.sign(vm[use])])
                coef, *_ = np.linalg.lstsq(x, (mp - ap)[use], rcond=None)
                plain.append(2 * coef[-1] * 60)
            # the plain fit again, AP read at the time shift (+-8 ms) that leaves the least residual
            fits = []
            for shift in np.linspace(-8e-3, 8e-3, 321):
                d = (mp - np.interp(t - shift, t, ap))[use]
                coef, *_ = np.linalg.lstsq(x[:, [0, 1, 3]], d, rcond=None)
                fits.append((float(np.sum((d - x[:, [0, 1, 3]] @ coef) ** 2)), shift, coef[-1]))
            _, shift, half = min(fits)
            aligned = f"{120 * half:+.2f} ({1e3 * shift:+.2f})"
            for i, r in enumerate(result.reversals):
                with_j = torque_traversed(moving, r.change, motor_inertia=inertia)
                head = (f"| {run} | {axis} | {expected} | {len(result.reversals)} "
                        if i == 0 else "| | | | ")  # fmt: skip
                tail = (f"| {60 * result.lost_motion:+.2f} | {plain[0]:+.2f} | {plain[1]:+.2f} "
                        f"| {aligned} | {1e3 * result.gear.skew:.2f} "
                        f"| {3600 * result.gear.compliance:.1f} "
                        f"| {'none' if result.reading is None else result.reading['text']} "
                        f"| {_parts_cell(result.gear_parts)} |"
                        if i == 0 else "| | | | | | | | |")  # fmt: skip
                lines.append(
                    f"{head}| {r.change.turn:.2f} | {60 * r.lost_motion:+.2f} "
                    f"[{60 * r.lost_motion_low:+.2f}, {60 * r.lost_motion_high:+.2f}] "
                    f"| {str(r.traversed).lower()} ({str(with_j).lower()}) {tail}"
                )
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a small sweep")
    parser.add_argument("--calibrate", action="store_true", help="rewrite calibration.json")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--resamples", type=int, default=1000)
    parser.add_argument(
        "--calibrate-from",
        type=Path,
        default=None,
        help="rewrite calibration.json from a "
        "sweep table saved with --save (sweep.csv) without simulating again",
    )
    parser.add_argument(
        "--figure",
        type=Path,
        default=None,
        help="draw docs/validation/backlash.png (scatter and ROC) "
        "from a sweep table saved with --save (sweep.csv)",
    )
    parser.add_argument(
        "--motor-contact",
        type=Path,
        default=None,
        help="score motor_contact on the tables "
        "saved with --save (a folder): the motor-loop sweep and the held-out plan",
    )
    parser.add_argument("--fn-only", action="store_true", help="only the FN-feature subset")
    parser.add_argument(
        "--lost-motion",
        action="store_true",
        help="only the two-encoder lost motion against the truth: the main sweep (and its "
        "scores), then the motor-loop, elastic-arm and held-out sweeps",
    )
    parser.add_argument("--compare", action="store_true", help="only the real-vs-sim table")
    parser.add_argument("--kuka", action="store_true", help="only the KUKA KR 300 runs' table")
    parser.add_argument(
        "--with-fn",
        action="store_true",
        help="only the main sweep with every indicator (FN features, coupling test), timed",
    )
    parser.add_argument(
        "--trials", type=int, default=None, help="with --with-fn: a random subset of N trials"
    )
    parser.add_argument(
        "--report", type=Path, default=None, help="with --with-fn: write the HTML report here"
    )
    parser.add_argument(
        "--intervals", type=int, default=0,
        help="with --with-fn: also the resampling intervals (N subsamples; timing only)",
    )
    parser.add_argument(
        "--seeds", type=int, nargs="+", default=None,
        help="the main sweep's noise seeds (default 1 2 3): other seeds validate on fresh "
        "trials; with --lost-motion the motor-loop and elastic sweeps take the first",
    )
    parser.add_argument("--save", type=Path, default=None, help="folder for the tables (CSV)")
    args = parser.parse_args()
    if args.kuka:
        print(kuka_table())
        return
    if args.compare:
        print(compare_real())
        return
    if args.figure:
        figure(pd.read_csv(args.figure), ROOT / "docs" / "validation" / "backlash.png")
        return
    if args.motor_contact:
        motor_contact_tables(args.motor_contact, args.resamples, _Printer())
        return
    if args.fn_only:
        _fn_section(args, _Printer())
        return
    if args.with_fn:
        with_fn(args, _Printer())
        return
    if args.calibrate_from:
        folder = args.calibrate_from
        _write_calibration(pd.read_csv(folder / "sweep.csv"),
                           pd.read_csv(folder / "sweep_motor.csv"), str(folder))  # fmt: skip
        return
    small: dict[str, Any] = {}
    if args.quick:
        small = {"seeds": (1,), "friction_scales": (1.0,), "stiffness_scales": (0.7, 1.4)}
    if args.seeds:
        small["seeds"] = tuple(args.seeds)
    physical = list(PHYSICAL)
    out = _Printer()

    start = time.perf_counter()
    main_plan = backlash_sweep_plan(**small)
    sweep = run_sweep(main_plan, networks=False, workers=args.workers)
    elapsed = time.perf_counter() - start
    out.append(f"main sweep: {len(main_plan)} trials simulated and analysed (physical "
               f"indicators) in {elapsed:.0f} s with {args.workers} workers\n")  # fmt: skip
    out.append(table(score_indicators(sweep, physical, resamples=args.resamples),
                     "Main sweep (arm-encoder position loop, rigid arm)"))  # fmt: skip
    out.append(lost_motion_summary(sweep))
    if args.lost_motion:
        out.append(table(score_indicators(sweep, ["lost_motion"], resamples=args.resamples),
                         "Main sweep: lost_motion"))  # fmt: skip
        if args.save:
            args.save.mkdir(parents=True, exist_ok=True)
            sweep.to_csv(args.save / "sweep_lost_motion.csv", index=False)
        _lost_motion_other_sweeps(args, out)
        return

    fn = _fn_section(args, out)

    extras: tuple[tuple[str, dict[str, Any]], ...] = (
        ("position loop on the motor encoder", {"position_feedback": "motor"}),
        ("elastic arm (third mass)", {"arm_model": "elastic"}),
    )
    parts = {}
    for label, extra in extras:
        plan = backlash_sweep_plan(
            seeds=(1,), **extra, **{k: v for k, v in small.items() if k != "seeds"}
        )
        part = run_sweep(plan, networks=False, workers=args.workers)
        parts[next(iter(extra.values()))] = part
        out.append(table(score_indicators(part, physical, resamples=args.resamples), label))

    held = backlash_sweep_plan(backlash_arcmin=(0.0, 0.75, 1.5, 3.0), tcps=(1.4, 1.8),
                               friction_scales=(0.85, 1.2), stiffness_scales=(0.85, 1.2),
                               seeds=(7,), noise_scales=(1.5,), group="held-out")  # fmt: skip
    part = run_sweep(held, networks=False, workers=args.workers)
    out.append(table(score_indicators(part, [SCORE, "motor_travel", "vibration"],
                                      resamples=args.resamples),
                     "held-out plan (backlash 0/0.75/1.5/3 arcmin, TCP 1.4/1.8, friction and "
                     "stiffness 0.85/1.2, noise 1.5, seed 7)"))  # fmt: skip
    held_motor = [dataclasses.replace(t, name=t.name + "-m", position_feedback="motor")
                  for t in held]  # fmt: skip
    part_motor = run_sweep(held_motor, networks=False, workers=args.workers)
    part_motor = with_contact_score(part_motor, contact_reference(parts["motor"]))
    out.append(table(score_indicators(part_motor, [SCORE, MOTOR_LOOP_SCORE, "vibration"],
                                      resamples=args.resamples),
                     "held-out plan, position loop on the motor encoder"))  # fmt: skip
    if args.save:
        args.save.mkdir(parents=True, exist_ok=True)
        sweep.to_csv(args.save / "sweep.csv", index=False)
        fn.to_csv(args.save / "sweep_fn.csv", index=False)
        for key, frame in parts.items():
            frame.to_csv(args.save / f"sweep_{key}.csv", index=False)
        part.to_csv(args.save / "heldout.csv", index=False)
        part_motor.to_csv(args.save / "heldout_motor.csv", index=False)
    if args.calibrate:
        _write_calibration(sweep, parts["motor"], "backlash_sweep_plan()")


if __name__ == "__main__":
    main()
