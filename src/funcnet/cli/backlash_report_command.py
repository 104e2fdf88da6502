"""``funcnet backlash-report``: the backlash sweep's HTML report from simulated traces.

Private to :mod:`funcnet.cli` (registered there with one line, :func:`register`, as
``funcnet stability``); the options live here. The
input is a folder that ``funcnet simulate --plan backlash-sweep`` (or any reversal plan) wrote
-- traces and ``manifest.csv`` with the truth -- or an indicator table (``.csv``) saved from a
sweep; the output :func:`funcnet.report.sweep_report.write_sweep_report`'s page.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

__all__ = ["register"]


def backlash_report(
    source: Annotated[
        Path,
        typer.Argument(
            metavar="FOLDER",
            help="A folder written by `funcnet simulate` (traces and manifest.csv), e.g. "
            "--plan backlash-sweep; or an indicator table (.csv) written by this command.",
        ),
    ],
    output: Annotated[
        Path,
        typer.Option(
            "--output", "-o",
            help="The HTML page; figures go to figures/ beside it, the indicator table and "
            "the scores to STEM-indicators.csv and STEM-scores.csv.",
        ),
    ] = Path("sweep.html"),
    workers: Annotated[
        int, typer.Option("--workers", min=1, help="Processes analysing the traces.")
    ] = 1,
    no_fn: Annotated[
        bool,
        typer.Option(
            "--no-fn", metavar="",
            help="Physical indicators only: no functional-network features, no coupling test, "
            "no signature (faster).",
        ),
    ] = False,
    resamples: Annotated[
        int, typer.Option("--resamples", min=10, help="Bootstrap resamples of the intervals.")
    ] = 1000,
    quiet: Annotated[
        bool, typer.Option("--quiet", "-q", metavar="", help="No progress bar.")
    ] = False,
) -> None:
    """Score the backlash indicators of a simulated sweep against its truth: HTML report.

    Computes every indicator at each trial's first reversal (the functional-network features
    with the coupling test, without resampling intervals), then detection AUCs and Spearman's
    rho with bootstrap intervals per speed and noise level, ROC and scatter figures and the
    paper's signature per backlash width. The path of the page is printed.
    """
    with _HOOKS["reported_errors"](summarized=True):
        import pandas as pd

        from funcnet.diagnosis.sweep import folder_indicators
        from funcnet.errors import ParameterError
        from funcnet.report.sweep_report import write_sweep_report

        if output.suffix.lower() not in (".html", ".htm"):
            raise ParameterError(f"-o {output}: the report is an .html page")
        if source.is_file() and source.suffix.lower() == ".csv":
            table = pd.read_csv(source)
        else:
            with _HOOKS["progress"](quiet, "backlash sweep") as progress:
                table = folder_indicators(source, networks=not no_fn, evidence=not no_fn,
                                          workers=workers, progress=progress)  # fmt: skip
        report = write_sweep_report(table, output, resamples=resamples, source=str(source))
    typer.echo(f"backlash_score {report.score}; best FN feature {report.best_fn}")
    typer.echo(f"report: {report.path}")


# funcnet.cli's error handling and progress bar (set by register: funcnet.cli imports this
# module, which therefore cannot import it)
_HOOKS: dict[str, Callable[..., Any]] = {}


def register(app: typer.Typer, *, command_class: type[Any], reported_errors: Callable[..., Any],
             progress: Callable[..., Any]) -> None:  # fmt: skip
    """Add ``funcnet backlash-report`` to ``app`` (``funcnet.cli``'s group, its command class, its
    error handling and its progress bar)."""
    _HOOKS.update(reported_errors=reported_errors, progress=progress)
    app.command("backlash-report", cls=command_class)(backlash_report)
