"""The backlash diagnoses as data: JSON, and the trend over traces as a table.

:func:`write_results` writes the :class:`~funcnet.diagnosis.diagnose.BacklashResult` of each
trace as JSON; :func:`trend_table` is one row per trace, in order (one axis over time). The
trend's page is drawn by :func:`funcnet.report.write_backlash_page`.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from funcnet._io import write_text_atomic
from funcnet.diagnosis.diagnose import MODEL_NOTE, BacklashResult
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
    """Write ``{"traces": [...]}`` as JSON, atomically.

    Parameters
    ----------
    results : sequence of BacklashResult
    path : path-like
        A ``.json`` file (one entry per trace: ``path`` as given, ``backlash_score``,
        ``lost_motion``, ``reversals``, ...). The trend page (``.html``) is
        :func:`funcnet.report.write_backlash_page`'s.

    Returns
    -------
    Path

    Raises
    ------
    ParameterError
        ``path`` does not end in ``.json``.

    Examples
    --------
    >>> import tempfile, pathlib, json
    >>> out = write_results([], pathlib.Path(tempfile.mkdtemp()) / "r.json")
    >>> json.loads(out.read_text())["traces"]
    []
    """
    target = Path(path)
    suffix = target.suffix.lower()
    if suffix != ".json":
        hint = " (the trend page: funcnet.report.write_backlash_page)" if suffix == ".html" else ""
        raise ParameterError.of("output", f"must be a .json file, got {str(path)!r}{hint}")
    payload = {"traces": [r.to_dict() for r in results], "note": MODEL_NOTE}
    return write_text_atomic(target, json.dumps(payload, indent=2, allow_nan=False) + "\n")

