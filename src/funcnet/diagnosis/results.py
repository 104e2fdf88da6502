"""The backlash diagnoses written: JSON, and the trend over traces as a table and a page.

:func:`write_results` writes the :class:`~funcnet.diagnosis.diagnose.BacklashResult` of each
trace as JSON, or :func:`trend_table` (one row per trace, in order: one axis over time) as a
plain HTML page with its plot.
"""

from __future__ import annotations

import html
import json
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.diagnosis.diagnose import MODEL_NOTE, MOTOR_LOOP_SCORE, SCORE, BacklashResult
from funcnet.errors import ParameterError

__all__ = ["trend_table", "write_results"]


def trend_table(results: Sequence[BacklashResult]) -> pd.DataFrame:
    """One row per trace, in the given order (the monitoring use: one axis over time).

    Returns
    -------
    DataFrame
        ``path``, ``reversals`` (count), ``score_indicator``, ``backlash_score``,
        ``score_spread``,
        ``lost_motion``, ``arcmin_low``, ``arcmin_high``, ``message``.

    Examples
    --------
    >>> trend_table([]).columns.tolist()[:4]
    ['path', 'reversals', 'score_indicator', 'backlash_score']
    """
    columns = ["path", "reversals", "score_indicator", "backlash_score", "score_spread",
               "lost_motion",
               "arcmin_low", "arcmin_high", "message"]  # fmt: skip
    rows = [
        {
            "path": r.path,
            "reversals": sum(x.change.kind == "reversal" for x in r.reversals),
            "score_indicator": r.score_indicator,
            "backlash_score": r.backlash_score,
            "score_spread": r.score_spread,
            "lost_motion": r.lost_motion,
            "arcmin_low": r.reading["arcmin_low"] if r.reading else None,
            "arcmin_high": r.reading["arcmin_high"] if r.reading else None,
            "message": r.message,
        }
        for r in results
    ]
    return pd.DataFrame(rows, columns=columns)


def write_results(results: Sequence[BacklashResult], path: str | os.PathLike[str]) -> Path:
    """Write ``{"traces": [...]}`` as JSON (or the trend table as HTML), atomically.

    Parameters
    ----------
    results : sequence of BacklashResult
    path : path-like
        A ``.json`` file (one entry per trace: ``path`` as given, ``backlash_score``,
        ``lost_motion``, ``reversals``, ...) or an ``.html`` page (the trend table).

    Returns
    -------
    Path

    Raises
    ------
    ParameterError
        ``path`` does not end in ``.json`` or ``.html``.

    Examples
    --------
    >>> import tempfile, pathlib, json
    >>> out = write_results([], pathlib.Path(tempfile.mkdtemp()) / "r.json")
    >>> json.loads(out.read_text())["traces"]
    []
    """
    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in (".json", ".html"):
        raise ParameterError.of("output", f"must be a .json or .html file, got {str(path)!r}")
    if suffix == ".html":
        return write_text_atomic(target, _html(results))
    payload = {"traces": [r.to_dict() for r in results], "note": MODEL_NOTE}
    return write_text_atomic(target, json.dumps(payload, indent=2, allow_nan=False) + "\n")


def _html(results: Sequence[BacklashResult]) -> str:
    """A plain page: the trend table (one row per trace, in order) and what to read it as."""
    table = trend_table(results).to_html(index=False, na_rep="", float_format="{:.5g}".format)
    return (
        "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>funcnet backlash</title>"
        "</head><body>\n<h1>Backlash diagnosis</h1>\n"
        f"<p>backlash_score: {html.escape(SCORE)} (deg) with AP, "
        f"{html.escape(MOTOR_LOOP_SCORE)} (dimensionless) without; higher = more backlash. "
        "lost_motion: "
        "two-encoder lost motion (deg). Readings are "
        f"{html.escape(MODEL_NOTE)}. See docs/backlash.md for how far each can be trusted.</p>\n"
        f"{table}\n{_trend_svg(results)}\n</body></html>\n"
    )


def _trend_svg(results: Sequence[BacklashResult]) -> str:
    """The trend plot (score and lost motion per trace, in the given order) as inline SVG."""
    trend = trend_table(results)
    if len(trend) < 2:
        return ""
    import io

    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 3.2))
    ax = fig.subplots()
    x = np.arange(len(trend))

    def column(name: str, scale: float = 60.0) -> np.ndarray:
        return pd.to_numeric(trend[name], errors="coerce").to_numpy(dtype=float) * scale

    lost = column("lost_motion")
    if np.isfinite(lost).any():
        ax.plot(x, lost, marker="o", label="lost_motion (arcmin)")
    for indicator, unit, scale in ((SCORE, "arcmin", 60.0), (MOTOR_LOOP_SCORE, "z", 1.0)):
        mine = (trend["score_indicator"] == indicator).to_numpy()
        score = np.where(mine, column("backlash_score", scale), np.nan)
        if np.isfinite(score).any():  # one line per score (their units differ)
            spread = column("score_spread", scale)
            ax.plot(x, score, marker="s", label=f"backlash_score: {indicator} ({unit})")
            ax.fill_between(x, score - spread, score + spread, alpha=0.2)
    ax.set_xticks(x, [Path(p).name for p in trend["path"]], rotation=20, fontsize=7)
    ax.set_ylabel("arcmin (or z)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    buffer = io.StringIO()
    fig.savefig(buffer, format="svg")
    text = buffer.getvalue()
    return text[text.index("<svg") :]
