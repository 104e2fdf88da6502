"""``funcnet track add`` and ``funcnet track show``: a robot's runs kept in a store, their
health figures trended, alarms when the machine changes (:mod:`funcnet.track`)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from funcnet.cli.messages import progress_bar, reported_errors
from funcnet.cli.options import Axis, Channels, Quiet, Verbose

__all__ = ["track_app"]

track_app = typer.Typer(
    name="track", help="A robot's health over weeks: keep its runs (add), trend them (show).",
    no_args_is_help=True, add_completion=False, pretty_exceptions_enable=False,
    rich_markup_mode=None)

Store = Annotated[Path, typer.Option("--store", help="The store of runs (one SQLite file, "
                                     "created by the first add).")]


@track_app.command("add")
def add(
    runs: Annotated[list[Path], typer.Argument(metavar="RUN", help="Trace files or log "
                                               "folders (read as inspect reads them).")],
    store: Store,
    robot: Annotated[str, typer.Option("--robot", help="The robot they are runs of.")],
    *,
    time: Annotated[
        str | None, typer.Option("--time", help="ISO 8601 time of the runs. Default: the "
                                 "file's own start time where it has one, else its "
                                 "modification time (said).")
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", min=0, help="Local processes reading the runs; 0 reads "
                          "them here.")
    ] = 0,
    scheduler: Annotated[
        str | None, typer.Option("--scheduler", help="Read them on a Dask cluster: "
                                 "tcp://HOST:PORT, or 'local-cluster'.")
    ] = None,
    channels: Channels = None,
    axis: Axis = None,
    verbose: Verbose = False,
    quiet: Quiet = False,
) -> None:
    """Add runs to ROBOT's history: per axis their health figures, their program, their
    departure from the program's earlier runs. A run the robot already holds (same content) is
    not counted twice. Prints one line per run: kept or not, its time and where it came from,
    its program. A run that cannot be read is one error line and is not kept (the others are);
    the exit status is then 2."""
    with reported_errors(verbose=verbose):
        from funcnet.track.add import add_runs

        with progress_bar(quiet, "track add") as progress:
            done = add_runs(runs, store, robot, channels=str(channels) if channels else None,
                            axis=axis, time=time, workers=workers, scheduler=scheduler,
                            progress=progress)
    for item in done:
        if item.error:
            typer.echo(f"funcnet: error: {item.source}: {item.notes[0]}", err=True)
            continue
        if not item.added:
            typer.echo(f"{item.source}: already kept for {robot}, not counted again")
            continue
        typer.echo(f"{item.source}: kept for {robot}, time {item.time} ({_said(item.time_from)}),"
                   f" program {item.program}; " + "; ".join(item.notes))
    if any(item.error for item in done):
        raise typer.Exit(2)


def _said(time_from: str) -> str:
    return {"given": "given", "file": "the file's own start time",
            "mtime": "the file's modification time"}.get(time_from, time_from)


@track_app.command("show")
def show(
    store: Store,
    out: Annotated[Path, typer.Option("--out", "-o", help="Folder of index.html, alarms.json "
                                      "and runs.json.")] = Path("track"),
    *,
    robot: Annotated[
        str | None, typer.Option("--robot", help="One robot (default: every robot).")
    ] = None,
    pages: Annotated[
        Path | None, typer.Option("--pages", help="Folder of run pages: a run links to "
                                  "PAGES/<its file name>/index.html where that exists.")
    ] = None,
    verbose: Verbose = False,
) -> None:
    """Write the trend page: per robot, program and axis each figure over time with its healthy
    band and the alarms; alarms.json and runs.json beside it."""
    with reported_errors(verbose=verbose):
        from funcnet.report.track_page import write_trends
        from funcnet.track.trend import robot_trends

        trends = robot_trends(store, robot)
        index = write_trends(trends, out, pages=pages)
    typer.echo(f"report: {index}")
    typer.echo(f"alarms: {out / 'alarms.json'} ({len(trends.alarms)} alarm(s) over "
               f"{len(trends.runs)} run(s))")
