"""``funcnet compare``: a run of a program against earlier runs of it
(:func:`funcnet.comparison.compare_runs`): what changed, and when."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Annotated

import typer

from funcnet.cli.messages import reported_errors
from funcnet.cli.options import Axis, Channels, Quiet, Verbose
from funcnet.errors import ParameterError

__all__ = ["compare"]


def compare(
    run: Annotated[
        Path, typer.Argument(metavar="RUN", help="The run to compare: a trace file or a log "
                             "folder read through --channels.")
    ],
    against: Annotated[
        list[Path], typer.Option("--against", metavar="REF", help="An earlier run of the same "
                                 "program (give it once per reference; two or more let the "
                                 "band learn how runs differ).")
    ],
    out: Annotated[
        Path, typer.Option("--out", "-o", help="Folder of index.html and changes.json.")
    ] = Path("compare"),
    *,
    threshold: Annotated[
        float, typer.Option("--threshold", help="Departure, in multiples of the references' "
                            "spread, beyond which RUN has changed.")
    ] = 6.0,
    networks: Annotated[
        bool, typer.Option("--networks/--no-networks", help="Also read the functional "
                           "networks over sliding windows (shown beside the residuals).")
    ] = True,
    channels: Channels = None,
    axis: Axis = None,
    verbose: Verbose = False,
    quiet: Quiet = False,
) -> None:
    """Compare RUN with earlier runs of its program: the intervals where it departs.

    The runs are aligned on their position set-points cycle by cycle (another start, more
    cycles, a local slow-down); a reference whose set-points do not match is refused. The
    references' band (how much runs differ, per signal, per axis, along the program) of the
    current residual AC - RC and the following error RP - AP gives the intervals: start, stop,
    axes, signals, size in spreads and the physical difference. Writes OUT/index.html and
    OUT/changes.json; prints their paths.
    """
    del quiet  # no progress bar: a comparison takes seconds
    with reported_errors(verbose=verbose):
        if not threshold > 0:
            raise ParameterError("--threshold must be > 0")
        from funcnet.comparison import compare_runs
        from funcnet.report.compare_page import write_comparison
        from funcnet.robot.io.channels import channel_map
        from funcnet.robot.io.read import read_trace

        # named by the paths given: a Parquet recording keeps the source it was written from
        recording, *references = (replace(read_trace(path, channels=channels, axis=axis),
                                          source=str(path)) for path in (run, *against))
        result = compare_runs(recording, references, threshold=threshold, networks=networks)
        page = write_comparison(result, out, axis_label=channel_map(channels).axis_label)
    typer.echo(f"report: {page}")
    typer.echo(f"changes: {out / 'changes.json'} ({len(result.intervals)} interval(s), "
               f"{result.compared:.0%} of RUN compared)")
