"""The backlash sweep's report: scores with intervals, ROC and scatter figures, the signature.

From a sweep's indicator table -- one row per trial with its truth, from
:func:`funcnet.validation.sweep.run_sweep` or from the traces and ``manifest.csv`` that
``funcnet simulate --plan backlash-sweep`` writes
(:func:`~funcnet.validation.sweep.folder_indicators`) -- :func:`write_sweep_report` writes one
HTML page: the honest reading first (which indicator the sweep supports, the
functional-network features' place), then the score table (detection AUCs and Spearman's rho
with bootstrap intervals, :func:`~funcnet.validation.sweep.score_indicators`, per speed and
noise level) for the ``backlash_score`` indicator, the baselines and the best
functional-network feature, ROC curves, score-vs-true-backlash scatters, and how often the
paper's signature appears at each backlash width. Figures go to ``figures/`` beside the page,
the indicator table and the scores beside it as CSV; every file is written atomically.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.diagnosis.diagnose import MOTOR_LOOP_SCORE, SCORE, load_calibration
from funcnet.diagnosis.indicators import FN_FEATURES, PHYSICAL, with_contact_score
from funcnet.errors import ParameterError
from funcnet.report.html import contents, escape, figure_html, page, table as html_table
from funcnet.validation.sweep import lost_motion_accuracy, score_indicators

__all__ = ["SweepReport", "sweep_scores", "write_sweep_report", "roc_curve"]

#: The score columns of the table, with their headings.
_HEADINGS = {"auc_0.5_vs_0": "AUC >=0.5 vs 0 arcmin", "auc_1_vs_0": "AUC >=1 vs 0",
             "auc_2_vs_0.5": "AUC >=2 vs <=0.5", "rho": "Spearman rho"}  # fmt: skip
#: The baselines drawn in the ROC figure beside the score and the best FN feature.
_DRAWN = ("motor_contact", "motor_hysteresis", "vibration", "current_step", "lost_motion")


@dataclass(frozen=True)
class SweepReport:
    """What :func:`write_sweep_report` wrote and found.

    Attributes
    ----------
    path : pathlib.Path
        The HTML page.
    score : str
        The ``backlash_score`` indicator (:data:`funcnet.diagnosis.SCORE`, or
        :data:`~funcnet.diagnosis.MOTOR_LOOP_SCORE` for a sweep whose position loop reads the
        motor encoder).
    best_fn : str or None
        The functional-network feature with the highest mean ``auc_0.5_vs_0`` (None: not
        computed).
    scores : DataFrame
        :func:`~funcnet.validation.sweep.score_indicators` of the reported indicators.
    signature : DataFrame
        Per speed and backlash width: ``trials`` with a signature value and ``signature`` (how
        many show the paper's signature).
    files : tuple of pathlib.Path
        Every file written (page, figures, CSV tables).
    """

    path: Path
    score: str
    best_fn: str | None
    scores: pd.DataFrame
    signature: pd.DataFrame
    files: tuple[Path, ...]


def roc_curve(values: Any, positive: Any) -> tuple[np.ndarray, np.ndarray]:
    """False and true positive rates at every threshold (higher value = positive).

    Parameters
    ----------
    values : array_like
        Scores (NaN left out).
    positive : array_like of bool
        The class of each score.

    Returns
    -------
    (fpr, tpr) : ndarray
        From (0, 0) to (1, 1); tied scores move both rates at once (the area under the curve
        is then the Mann-Whitney AUC with ties counted one half).

    Examples
    --------
    >>> fpr, tpr = roc_curve([0.1, 0.4, 0.35, 0.8], [False, False, True, True])
    >>> float(np.trapezoid(tpr, fpr))
    0.75
    """
    x = np.asarray(values, dtype=np.float64)
    y = np.asarray(positive, dtype=bool)
    keep = np.isfinite(x)
    x, y = x[keep], y[keep]
    order = np.argsort(-x, kind="stable")
    x, y = x[order], y[order]
    last = np.r_[np.flatnonzero(np.diff(x) != 0), x.size - 1]  # the end of each tie group
    tp, fp = np.cumsum(y)[last], np.cumsum(~y)[last]
    with np.errstate(invalid="ignore", divide="ignore"):
        return (np.r_[0.0, fp / max(int((~y).sum()), 1)], np.r_[0.0, tp / max(int(y.sum()), 1)])


def _with_contact(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with ``motor_contact`` against the shipped calibration's no-backlash reference
    (what :func:`funcnet.diagnosis.diagnose_backlash` reads)."""
    needed = ("peak_speed", "motor_travel", "current_step")
    if MOTOR_LOOP_SCORE in table or not all(c in table for c in needed):
        return table
    return with_contact_score(table, load_calibration()["motor_loop"]["reference"])


def _group_columns(table: pd.DataFrame) -> list[str]:
    return [c for c in ("speed", "noise_scale") if c in table.columns]


def sweep_scores(
    table: pd.DataFrame, *, resamples: int = 1000, seed: int = 0
) -> tuple[pd.DataFrame, str, str | None]:
    """The reported indicators' scores, the ``backlash_score`` indicator and the best FN feature.

    Parameters
    ----------
    table : DataFrame
        A sweep's indicator table (``speed``, ``backlash_arcmin`` and indicator columns;
        ``noise_scale`` and ``position_feedback`` when present).
    resamples : int
        Bootstrap resamples of the intervals.
    seed : int
        Of the bootstrap.

    Returns
    -------
    (scores, score, best_fn)
        ``scores`` as :func:`~funcnet.validation.sweep.score_indicators` (by speed and noise
        level) for the score, the physical baselines, ``motor_contact`` and every computed FN
        feature and ``signature``; ``score`` the ``backlash_score`` indicator; ``best_fn``
        the FN feature with the highest mean ``auc_0.5_vs_0`` over the groups (None when no
        FN feature was computed).

    Raises
    ------
    ParameterError
        The table lacks ``speed`` or ``backlash_arcmin``, or has no trial.
    """
    missing = [c for c in ("speed", "backlash_arcmin") if c not in table.columns]
    if missing or table.empty:
        raise ParameterError.of("table", f"must have trials with columns speed and "
                                f"backlash_arcmin; missing {missing or 'rows'}")  # fmt: skip
    table = _with_contact(table)
    motor_loop = "position_feedback" in table and (table["position_feedback"] == "motor").all()
    score = MOTOR_LOOP_SCORE if motor_loop else SCORE
    computed = [c for c in (*PHYSICAL, MOTOR_LOOP_SCORE, *FN_FEATURES, "signature")
                if c in table and np.isfinite(table[c].to_numpy(float)).any()]  # fmt: skip
    ordered = [score] + [c for c in computed if c != score]
    scores = score_indicators(table, ordered, by=_group_columns(table), resamples=resamples,
                              seed=seed)  # fmt: skip
    fn = scores[scores["indicator"].isin(FN_FEATURES)]
    best = fn.groupby("indicator")["auc_0.5_vs_0"].mean().dropna()
    return scores, score, (str(best.idxmax()) if not best.empty else None)


def _cell(row: pd.Series, name: str) -> str:
    value, low, high = row[name], row[name + "_low"], row[name + "_high"]
    if not math.isfinite(value):
        return "n/a"
    return f"{value:.2f} [{low:.2f}, {high:.2f}]"


def _score_table(scores: pd.DataFrame, score: str) -> str:
    rows = pd.DataFrame({
        **{c: scores[c] for c in _group_columns(scores)},
        "indicator": scores["indicator"],
        "n": scores["n"].astype(int),
        **{head: [_cell(r, c) for _, r in scores.iterrows()] for c, head in _HEADINGS.items()},
    })  # fmt: skip
    return html_table(rows, classes={"indicator": lambda v: "yes" if v == score else ""})


def _ranges(scores: pd.DataFrame, name: str, column: str = "auc_0.5_vs_0") -> str:
    part = scores.loc[scores["indicator"] == name]
    values, lows = part[column].to_numpy(float), part[column + "_low"].to_numpy(float)
    if not np.isfinite(values).any():
        return "n/a"
    return (f"{np.nanmin(values):.2f}-{np.nanmax(values):.2f} (lowest lower bound "
            f"{np.nanmin(lows):.2f})")  # fmt: skip


def _at_chance(scores: pd.DataFrame, name: str) -> bool:
    """Every group's ``auc_0.5_vs_0`` interval covers 0.5 (or the feature is constant)."""
    part = scores.loc[scores["indicator"] == name]
    low, high = part["auc_0.5_vs_0_low"].to_numpy(float), part["auc_0.5_vs_0_high"].to_numpy(float)
    return bool(np.all(~np.isfinite(low) | ((low <= 0.5) & (high >= 0.5))))


def _reading(table: pd.DataFrame, scores: pd.DataFrame, score: str, best_fn: str | None,
             signature: pd.DataFrame) -> str:  # fmt: skip
    """The honest reading, in sentences made of the measured numbers."""
    groups = ", ".join(f"{c} {sorted(table[c].unique().tolist())}" for c in _group_columns(table))
    items = [f"{len(table)} trials ({groups}); every other knob (TCP, friction, stiffness, seeds) "
             "varies inside each group. Detection: backlash >= 0.5 arcmin vs none."]  # fmt: skip
    worst = (scores.groupby("indicator")["auc_0.5_vs_0"].min().drop(
        ["lost_motion", "signature"], errors="ignore").dropna())  # fmt: skip
    items.append(f"<b>backlash_score</b> = <code>{escape(score)}</code>: AUC "
                 f"{_ranges(scores, score)}, Spearman rho {_ranges(scores, score, 'rho')}.")
    if not worst.empty:
        top = str(worst.idxmax())
        items.append(f"The motor-side indicator this sweep supports best (highest worst-group "
                     f"AUC): <code>{escape(top)}</code>, {worst[top]:.2f} in its worst group"
                     + ("" if top == score else f" (the score: {worst.get(score, math.nan):.2f})")
                     + ".")  # fmt: skip
    if "lost_motion" in set(scores["indicator"]):
        items.append("The two-encoder lost motion (needs the arm encoder AP: the upper bound): "
                     f"AUC {_ranges(scores, 'lost_motion')}.")
    fn = [f for f in FN_FEATURES if f in set(scores["indicator"])]
    if not fn:
        items.append("The functional-network features were not computed.")
    else:
        chance = [f for f in fn if _at_chance(scores, f)]
        part = scores[scores["indicator"].isin(fn)]
        below = int((part["auc_0.5_vs_0_high"] < 0.5).sum())
        text = (f"Functional-network features: the best by mean AUC, "
                f"<code>{escape(str(best_fn))}</code>, reaches AUC "
                f"{_ranges(scores, str(best_fn))}; the highest AUC of any of them in any group "
                f"is {np.nanmax(part['auc_0.5_vs_0'].to_numpy(float)):.2f}; ")  # fmt: skip
        text += ("every one is at chance (each group's interval covers 0.5 or the feature is "
                 "constant)" if len(chance) == len(fn) else
                 f"at chance in every group: {', '.join(chance) or 'none'}")  # fmt: skip
        if below:
            text += (f"; in {below} (feature, group) cells the AUC lies below 0.5 with its "
                     "interval: the feature's sign changes with the conditions")
        if best_fn is not None and not worst.empty and worst.idxmax() not in FN_FEATURES:
            text += f"; a plain baseline (<code>{escape(str(worst.idxmax()))}</code>) beats them"
        items.append(text + ".")
    if not signature.empty:
        shown, total = int(signature["signature"].sum()), int(signature["trials"].sum())
        items.append(f"The paper's signature (V drives every node, MP -> AP -> RP) appeared in "
                     f"{shown} of {total} reversal windows.")
    items.append("Everything here is measured on the simulated axis (model-based), not on a "
                 "real one.")
    return "<ul>" + "".join(f"<li>{item}</li>" for item in items) + "</ul>"


def _lost_motion_html(table: pd.DataFrame) -> str:
    """The two-encoder lost motion's accuracy per motion, load and speed (``step``: a rest at
    the turn; ``smooth``: the reversal error at turns in continuous motion)."""
    if "true_lost_motion" not in table or not np.isfinite(table["lost_motion"]).any():
        return "<p>Not computed (no AP).</p>"
    accuracy = lost_motion_accuracy(table)
    shown = accuracy.assign(
        within_5_percent=[f"{v:.1%}" if math.isfinite(v) else "-"
                          for v in accuracy["within_5_percent"]],
        within_2_steps=[f"{v:.1%}" if math.isfinite(v) else "-"
                        for v in accuracy["within_2_steps"]],
    ).round({"median_error_percent": 2, "median_error_steps": 2})  # fmt: skip
    return ("<p>Where the truth is the dead zone crossed (<code>crossed</code>: backlash, and a "
            "true lost motion above half its width) the share of trials whose "
            "<code>lost_motion</code> lies within 5 % of it; elsewhere (no backlash, or the gear "
            "kept on one flank by a load or the arm's inertia: a truth of about nothing) within "
            "two arm-encoder steps. A trial without an estimate counts as a miss. At a "
            "continuous turn (<code>smooth</code>) the truth is the step of the gear's torsion "
            "that the gear torque does not explain, which the motor current only approximates "
            "(docs/validation/backlash.md, section 5.1).</p>"
            + html_table(shown))


def _signature_rates(table: pd.DataFrame) -> pd.DataFrame:
    if "signature" not in table or not np.isfinite(table["signature"].to_numpy(float)).any():
        return pd.DataFrame(columns=["speed", "backlash_arcmin", "trials", "signature"])
    found = table[np.isfinite(table["signature"].to_numpy(float))]
    rates = found.groupby(["speed", "backlash_arcmin"])["signature"].agg(["size", "sum"])
    rates = rates.reset_index().rename(columns={"size": "trials", "sum": "signature"})
    return rates.astype({"trials": int, "signature": int})


def _figures(table: pd.DataFrame, scores: pd.DataFrame, score: str, best_fn: str | None,
             out_dir: Path, stem: str) -> list[tuple[str, Path]]:  # fmt: skip
    """ROC grid (noise level x speed) and scatter grid (indicator x speed); their elements."""
    import matplotlib.pyplot as plt

    speeds = sorted(table["speed"].unique())
    noises = sorted(table["noise_scale"].unique()) if "noise_scale" in table else [None]
    drawn = [score, *[c for c in _DRAWN if c != score], *([best_fn] if best_fn else [])]
    drawn = [c for c in drawn if c in set(scores["indicator"])]
    out: list[tuple[str, Path]] = []

    def finish(fig: Any, name: str, caption: str) -> None:
        # saved under figures/, its element and file listed, the figure freed
        fig.tight_layout()
        out.append((figure_html(out_dir, name, fig, caption), out_dir / "figures" / f"{name}.png"))
        plt.close(fig)

    fig, axes = plt.subplots(len(noises), len(speeds), figsize=(5 * len(speeds),
                             4.2 * len(noises)), squeeze=False)  # fmt: skip
    for i, noise in enumerate(noises):
        for j, speed in enumerate(speeds):
            ax = axes[i, j]
            part = table[(table["speed"] == speed)
                         & ((table["noise_scale"] == noise) if noise is not None else True)]
            truth = part["backlash_arcmin"].to_numpy(float)
            keep = (truth >= 0.5 - 1e-9) | (truth <= 1e-9)
            for name in drawn:
                values = part[name].to_numpy(float)[keep]
                if not np.isfinite(values).any():  # not computed here (a continuous turn)
                    continue
                fpr, tpr = roc_curve(values, truth[keep] >= 0.5 - 1e-9)
                style = "-" if name in (score, best_fn) else "--"
                ax.plot(fpr, tpr, style, lw=2 if name == score else 1, label=name)
            ax.plot([0, 1], [0, 1], color="grey", lw=0.5)
            title = f"{speed:g} deg/min" + ("" if noise is None else f", noise x{noise:g}")
            ax.set(xlabel="false positive rate", ylabel="true positive rate", title=title)
            ax.legend(fontsize=7, loc="lower right")
    finish(fig, f"{stem}-roc", "ROC curves, backlash >= 0.5 arcmin vs none (solid: "
           "backlash_score and the best FN feature)")
    shown = [score, *([best_fn] if best_fn else [])]
    fig, axes = plt.subplots(len(shown), len(speeds), figsize=(5 * len(speeds),
                             4 * len(shown)), squeeze=False)  # fmt: skip
    rng = np.random.default_rng(0)  # horizontal jitter only, to see overlapping trials
    for i, indicator in enumerate(shown):
        for j, speed in enumerate(speeds):
            ax = axes[i, j]
            part = table[table["speed"] == speed]
            for noise, marker in zip(noises, "oxs^v", strict=False):
                sub = part if noise is None else part[part["noise_scale"] == noise]
                x = sub["backlash_arcmin"].to_numpy(float)
                ax.scatter(x + rng.uniform(-0.06, 0.06, x.size), sub[indicator], s=8,
                           marker=marker, alpha=0.5,
                           label="" if noise is None else f"noise x{noise:g}")  # fmt: skip
            ax.set(xlabel="true backlash (arcmin)", ylabel=indicator, title=f"{speed:g} deg/min")
            if noises != [None]:
                ax.legend(fontsize=7)
    finish(fig, f"{stem}-scatter", "Indicator against the true backlash, per trial "
           "(backlash_score above, the best FN feature below)")
    return out


def write_sweep_report(
    table: pd.DataFrame,
    path: str | os.PathLike[str],
    *,
    resamples: int = 1000,
    seed: int = 0,
    source: str | None = None,
) -> SweepReport:
    """Write the sweep's HTML report (figures in ``figures/`` beside it; CSV tables too).

    Parameters
    ----------
    table : DataFrame
        The sweep's indicator table (:func:`funcnet.validation.sweep.run_sweep`,
        :func:`~funcnet.validation.sweep.folder_indicators`).
    path : path-like
        The page (``.html``). Beside it: ``figures/STEM-roc.png``, ``figures/STEM-scatter.png``,
        ``STEM-indicators.csv`` (the table) and ``STEM-scores.csv`` (the scores, full
        precision).
    resamples : int
        Bootstrap resamples of the score intervals.
    seed : int
        Of the bootstrap.
    source : str, optional
        Where the table comes from (shown on the page).

    Returns
    -------
    SweepReport

    Raises
    ------
    ParameterError
        ``path`` not ending in ``.html``, or a table without trials (:func:`sweep_scores`).
    """
    path = Path(path)
    if path.suffix.lower() not in (".html", ".htm"):
        raise ParameterError.of("path", f"must end in .html, got {str(path)!r}")
    scores, score, best_fn = sweep_scores(table, resamples=resamples, seed=seed)
    table = _with_contact(table)
    out_dir, stem = path.parent, path.stem
    signature = _signature_rates(table)
    figures = _figures(table, scores, score, best_fn, out_dir, stem)
    shown = scores[scores["indicator"].isin(
        [score, *PHYSICAL, MOTOR_LOOP_SCORE, *([best_fn] if best_fn else [])])]  # fmt: skip
    sections = [("reading", "Reading"), ("scores", "Scores"), ("figures", "Figures"),
                ("lost-motion", "Lost motion against its truth"),
                ("signature", "The paper's signature"), ("all", "Every indicator")]  # fmt: skip
    body = [
        "<h1>Backlash sweep: indicators against the true backlash</h1>",
        f'<p class="note">{escape(source or "indicator table")}: {len(table)} trials. Scores: '
        f"AUC (Mann-Whitney, ties one half) and Spearman rho with the true backlash, 95 % "
        f"percentile bootstrap intervals ({resamples} resamples of trials), per "
        f"{' and '.join(_group_columns(table))}.</p>",
        contents(sections),
        '<h2 id="reading">Reading</h2>',
        f'<div class="verdict">{_reading(table, scores, score, best_fn, signature)}</div>',
        '<h2 id="scores">Scores</h2>',
        f"<p>backlash_score (<code>{escape(score)}</code>, highlighted), the baselines and the "
        f"best functional-network feature (<code>{escape(str(best_fn))}</code>).</p>",
        _score_table(shown, score),
        '<h2 id="figures">Figures</h2>',
        *(html for html, _ in figures),
        '<h2 id="lost-motion">Lost motion against its truth</h2>',
        _lost_motion_html(table),
        '<h2 id="signature">The paper\'s signature</h2>',
        "<p>Reversal windows (nodes RP, AP, MP, V, RC, AC) in which V has a directed edge to "
        "every other node and MP -> AP -> RP, per speed and backlash width.</p>",
        html_table(signature) if not signature.empty
        else "<p>Not computed (no AP, or no networks).</p>",
        '<h2 id="all">Every indicator</h2>',
        _score_table(scores, score),
        f'<p>Tables: <a href="{escape(stem)}-indicators.csv">{escape(stem)}-indicators.csv</a> '
        f'(one row per trial), <a href="{escape(stem)}-scores.csv">{escape(stem)}-scores.csv'
        "</a>.</p>",
    ]
    written = [write_text_atomic(out_dir / f"{stem}-indicators.csv", table.to_csv(index=False)),
               write_text_atomic(out_dir / f"{stem}-scores.csv", scores.to_csv(index=False))]
    written += [p for _, p in figures]
    write_text_atomic(path, page("Backlash sweep", body))
    return SweepReport(path=path, score=score, best_fn=best_fn, scores=scores,
                       signature=signature, files=(path, *written))  # fmt: skip
