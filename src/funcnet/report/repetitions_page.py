"""The repetitions page of an inspection: one motion repeated in the traces, tested per phase.

:func:`write_repetitions` renders :func:`funcnet.inspection.repeated.repetitions_of` the
inspected traces as ``repeated.html`` (``funcnet inspect ... --repeated``): the repetitions
found, per phase the repetition evidence (docs/validation/evidence.md, section 7), or how many
repetitions a decision needs.
"""

from __future__ import annotations

import os
from pathlib import Path

from funcnet._io import write_text_atomic
from funcnet.inspection.repeated import RepeatedInspection
from funcnet.report.html import escape, page, table

__all__ = ["REPETITIONS_NOTE", "write_repetitions"]

#: What the repetitions page says about its test (docs/validation/evidence.md, section 7).
REPETITIONS_NOTE = (
    "Moves of the same set-point profile, aligned on the set-point, are repetitions of one "
    "motion. Per phase, each pair is tested for coupling beyond the command: X of one "
    "repetition with Y of the same repetition against Y of the others (the signals minus their "
    "mean over the repetitions; coupling_statistic is the excess joint-recurrence correlation "
    "of the same-repetition pairings). With R repetitions no p-value is below 1/R!: fewer than "
    "4 leave every pair untestable. kind_share is the share of repetitions whose own network "
    "gives the pair its most common kind; the c_diff and t_diff intervals come from the spread "
    "across the repetitions."
)


#: The repetition table's columns on the page (the rest stay in the library's table).
_REPEATED_COLUMNS = ["x", "y", "coupling_statistic", "coupling_p", "evidence", "kind",
                     "kind_share", "c_diff_mean", "c_diff_low", "c_diff_high", "t_diff_mean",
                     "t_diff_low", "t_diff_high"]


def write_repetitions(found: RepeatedInspection | None, out_dir: str | os.PathLike[str]) -> Path:
    """Write ``repeated.html``: the repetitions of the inspected traces, read together.

    Parameters
    ----------
    found : RepeatedInspection or None
        :func:`funcnet.inspection.repetitions_of` the inspections; None when there was no
        single-axis trace to read.
    out_dir : path-like

    Returns
    -------
    pathlib.Path
    """
    body = ["<h1>funcnet inspect — repetitions</h1>"]
    if found is None:
        body.append("<p>No single-axis trace to read repetitions in.</p>")
        return write_text_atomic(Path(out_dir) / "repeated.html",
                                 page("funcnet inspect — repetitions", body))
    body += [f"<p>{escape(found.message)}.</p>", f"<p>{escape(REPETITIONS_NOTE)}</p>"]
    if len(found.moves):
        body.append(table(found.moves.round(4)))
    for label, frame in found.evidence.items():
        reason = frame.evidence_reason.iloc[0] if len(frame) else ""
        body += [f"<h2>{escape(label)}</h2>", f"<p>{escape(reason)}</p>",
                 table(frame[_REPEATED_COLUMNS].round(4))]
    for label, why in found.failures.items():
        body.append(f"<h2>{escape(label)}</h2><p>No test: {escape(why)}</p>")
    return write_text_atomic(Path(out_dir) / "repeated.html",
                             page("funcnet inspect — repetitions", body))
