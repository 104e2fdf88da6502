"""The backlash trend page: the diagnoses of several traces of one axis, in order.

The numbers are :func:`funcnet.diagnosis.trend_table`'s; this module only draws them: the table
and one plot of the score and the lost motion per trace, inline (SVG).
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.diagnosis.diagnose import MODEL_NOTE, MOTOR_LOOP_SCORE, SCORE, BacklashResult
from funcnet.diagnosis.results import trend_table
from funcnet.errors import ParameterError
from funcnet.report.html import escape, page

__all__ = ["write_backlash_page"]


def write_backlash_page(results: Sequence[BacklashResult], path: str | os.PathLike[str]) -> Path:
    """Write the trend of the diagnoses (table and plot) as one HTML page, atomically.

    Parameters
    ----------
    results : sequence of BacklashResult
        One per trace, in the order to draw them (one axis over time).
    path : path-like
        An ``.html`` file.

    Returns
    -------
    Path

    Raises
    ------
    ParameterError
        ``path`` does not end in ``.html``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = write_backlash_page([], pathlib.Path(tempfile.mkdtemp()) / "trend.html")
    >>> "Backlash diagnosis" in out.read_text()
    True
    """
    target = Path(path)
    if target.suffix.lower() != ".html":
        raise ParameterError.of("output", f"must be an .html file, got {str(path)!r}")
    trend = trend_table(results)
    table = trend.to_html(index=False, na_rep="", float_format="{:.5g}".format)
    body = [
        "<h1>Backlash diagnosis</h1>",
        f"<p>backlash_score: {escape(SCORE)} (deg) with AP, {escape(MOTOR_LOOP_SCORE)} "
        "(dimensionless) without; higher = more backlash. lost_motion: two-encoder lost motion "
        f"(deg). Readings are {escape(MODEL_NOTE)}. See docs/guide/backlash.md for how far each "
        "can be trusted.</p>",
        table,
        _trend_svg(trend),
    ]
    return write_text_atomic(target, page("funcnet backlash", body))


def _trend_svg(trend: pd.DataFrame) -> str:
    """The trend plot (score and lost motion per trace, in the given order) as inline SVG."""
    if len(trend) < 2:
        return ""
    from matplotlib.figure import Figure  # a bare Figure: no backend to choose

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
