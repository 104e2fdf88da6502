"""``funcnet study`` and ``funcnet report``: a batch of networks from a TOML description, and
the HTML report of its results."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from funcnet.cli.messages import EXIT_TASKS_FAILED, one_line, progress_bar, reported_errors
from funcnet.cli.options import Quiet

__all__ = ["study", "report"]


def study(
    study_file: Annotated[Path, typer.Argument(help="Study description (TOML).")],
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", help="Results folder. [default: out/<STUDY_FILE's name without .toml>]"
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="Run on a Dask cluster: tcp://HOST:PORT of a running scheduler, or "
            "'local-cluster' to start one on this machine. Default: local processes.",
        ),
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option(
            "--workers",
            min=0,
            help="Worker processes of the local run or local cluster; 0 runs the tasks in this "
            "process. [default: 2]",
        ),
    ] = None,
    quiet: Quiet = False,
) -> None:
    """Run a batch study: recordings x windows x network parameters (see examples/study.toml).

    Each (recording, window, parameter set) is an independent task; its rows (one per pair of
    signals) are written to OUT/rows/<key>.parquet, keyed by content, so a re-run computes only
    what is new and a killed run resumes where it stopped. OUT/study.json keeps the study and its
    provenance. Exit status 1 when some windows could not be analysed (see study.json);
    a window that cannot be analysed because the axis stands still in it is skipped and
    listed, not failed.
    """
    # Warnings are counted per problem over the tasks (printed below), wherever they ran.
    with reported_errors(summarized=True):
        from funcnet.study import load_study, run_study

        described = load_study(study_file)
        target = out if out is not None else Path("out") / study_file.stem
        with progress_bar(quiet, "study") as progress:
            result = run_study(
                described, target, scheduler=scheduler, workers=workers, progress=progress
            )
    typer.echo(
        f"{result.tasks} tasks: {result.computed} computed, {result.cached} already done, "
        f"{len(result.failures)} failed"
        + (f", {len(result.skipped)} skipped" if result.skipped else "")
        + f"; rows in {result.out_dir / 'rows'}"
    )
    if result.skipped:
        listed = [f"{s.recording} [{s.window}]" for s in result.skipped]
        shown = ", ".join(listed[:6]) + (f" and {len(listed) - 6} more" if len(listed) > 6
                                         else "")
        sys.stderr.write(f"funcnet: skipped: {len(listed)} window(s) where the axis stands "
                         f"still, nothing to analyse: {shown} (listed in study.json)\n")
    for category, (count, example) in result.warnings.items():
        sys.stderr.write(
            f"funcnet: warning: {category} in {count} of {result.computed} networks computed, "
            f"e.g. {one_line(example)}\n"
        )
    varied = [name for name, values in described.parameters if len(values) > 1]
    # One line per cause, its tasks counted and the first few named (not one line per task).
    causes: dict[str, list[str]] = {}
    for failure in result.failures:
        setting = "".join(
            f" {k}={failure.parameters[k]}" for k in varied if k in failure.parameters
        )
        message = one_line(failure.message)
        # the same cause in another file or window: the message without its location
        cause = message.split(": ", 1)[-1] if message.startswith(failure.recording) else message
        causes.setdefault(cause, []).append(f"{failure.recording} [{failure.window}]{setting}")
    for cause, where in causes.items():
        shown = ", ".join(where[:3]) + (f" and {len(where) - 3} more" if len(where) > 3 else "")
        sys.stderr.write(f"funcnet: failed: {len(where)} task(s) ({shown}): {cause}\n")
    if result.failures:
        raise typer.Exit(EXIT_TASKS_FAILED)


def report(
    results_dir: Annotated[Path, typer.Argument(help="Folder written by `funcnet study`.")],
    out: Annotated[
        Path | None, typer.Option("--out", help="Report folder. [default: RESULTS_DIR/report]")
    ] = None,
    quiet: Quiet = False,
) -> None:
    """Write the static HTML report of a study's results (figures, tables, provenance).

    For each recording and parameter set: its windows' networks, an edge timeline over the
    windows, every pairs table; then the run counts, failures and provenance. The path of
    index.html is printed.
    """
    with reported_errors():
        from funcnet.report import write_report

        with progress_bar(quiet, "report") as progress:
            written = write_report(results_dir, out, progress=progress)
    typer.echo(f"report: {written}")
