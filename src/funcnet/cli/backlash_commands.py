"""``funcnet backlash`` and ``funcnet backlash-report``: backlash diagnosed in traces, and the
simulated sweep that calibrates it scored against its truth.

``backlash-report`` reads a folder that ``funcnet simulate --plan backlash-sweep`` (or any
reversal plan) wrote -- traces and ``manifest.csv`` with the truth -- or an indicator table
(``.csv``) saved from a sweep, and writes
:func:`funcnet.validation.sweep_report.write_sweep_report`'s page.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from funcnet.cli.messages import one_line, progress_bar, reported_errors
from funcnet.cli.options import Axis, Channels, Quiet
from funcnet.errors import ParameterError

__all__ = ["backlash", "backlash_report"]

_BACKLASH_SUFFIXES = (".json", ".html")


def backlash(
    traces: Annotated[
        list[Path],
        typer.Argument(
            metavar="TRACE",
            help="Traces of one axis (SINUMERIK XML, CSV, Parquet, MATLAB, HDF5), oldest first "
            "for a trend; a file of several axes without --axis: each axis on its own.",
        ),
    ],
    channels: Channels = None,
    axis: Axis = None,
    output: Annotated[
        Path | None,
        typer.Option(
            "--output",
            "-o",
            help="Write the results: .json (one entry per trace: path, backlash_score, "
            "lost_motion, reversals, ...) or .html (the trend table and plot).",
        ),
    ] = None,
    quiet: Quiet = False,
) -> None:
    """Diagnose backlash at the direction changes of each trace.

    Prints one line per trace: what was found, the motor-side backlash score (higher = more
    backlash) with its reading on the simulated sweep, and the two-encoder lost motion when the
    trace has AP. Readings are model-based: the calibration comes from the simulated axis, not
    from this machine. A trace without a direction change is a result, not an error.
    """
    with reported_errors():
        if output is not None and output.suffix.lower() not in _BACKLASH_SUFFIXES:
            raise ParameterError(
                f"-o {output}: unknown format, use one of {', '.join(_BACKLASH_SUFFIXES)}"
            )
        from funcnet.diagnosis import diagnose_backlash, write_results
        from funcnet.robot.io.channels import channel_map

        with progress_bar(quiet, "backlash"):
            results = diagnose_backlash(*traces, channels=channels, axis=axis)
        if output is not None and output.suffix.lower() == ".html":
            from funcnet.report import write_backlash_page

            write_backlash_page(results, output)
        elif output is not None:
            write_results(results, output)
        cmap = channel_map(channels)
    for result in results:
        number = result.axis if result.axis is not None else axis
        # a map that names the axes names them here; else the line reads as it always did
        where = (result.path if number is None or (result.axis is None and not cmap.axis_names)
                 else f"{result.path} {cmap.axis_label(number)}")
        typer.echo(f"{where}: {one_line(result.message)}")
        typer.echo(f"  {_backlash_numbers(result)}")
    if output is not None:
        typer.echo(f"wrote {output}")


def _backlash_numbers(result: Any) -> str:
    """Score and lost motion of one trace's diagnosis, on one line (arcmin on a rotary axis,
    um on a linear one)."""
    if result.score_indicator == "none":  # one encoder: neither can be computed
        return "backlash_score none; lost_motion none (one encoder per joint)"
    if result.backlash_score is None:
        score = f"backlash_score none ({result.score_indicator})"
    else:
        spread = "" if result.score_spread is None else f" ± {result.score_spread:.3g}"
        score = (f"backlash_score {result.backlash_score:.4g}{spread} {result.score_unit} "
                 f"({result.score_indicator})")
    k, unit = (1000.0, "um") if result.position_unit == "mm" else (60.0, "arcmin")
    if result.lost_motion is None:
        line = f"{score}; lost_motion none ({result.lost_motion_reason or 'no AP'})"
        if result.lost_motion_high is None:  # nothing measured: no gear either
            return line
    else:
        # Backlash is read in arcmin (1/60 deg) or um; the JSON keeps degrees, as the manifest
        # does, or um
        spread = ("" if result.lost_motion_spread is None
                  else f" ± {k * result.lost_motion_spread:.2f}")
        line = f"{score}; lost_motion {k * result.lost_motion:.2f}{spread} {unit}"
    parts = result.gear_parts
    if parts is not None and parts.dead_zone is not None:
        line += (f" (over the run, where the torque changes sign: dead zone "
                 f"{k * parts.dead_zone:.2f} [{k * parts.dead_zone_low:.2f}, "
                 f"{k * parts.dead_zone_high:.2f}], friction {k * parts.friction:.2f} "
                 f"[{k * parts.friction_low:.2f}, {k * parts.friction_high:.2f}] {unit})")
    return line


# --------------------------------------------------------------------------------------------
# backlash-report


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
    with reported_errors(summarized=True):
        import pandas as pd

        from funcnet.validation.sweep import folder_indicators
        from funcnet.validation.sweep_report import write_sweep_report

        if output.suffix.lower() not in (".html", ".htm"):
            raise ParameterError(f"-o {output}: the report is an .html page")
        if source.is_file() and source.suffix.lower() == ".csv":
            table = pd.read_csv(source)
        else:
            with progress_bar(quiet, "backlash sweep") as progress:
                table = folder_indicators(source, networks=not no_fn, evidence=not no_fn,
                                          workers=workers, progress=progress)  # fmt: skip
        report = write_sweep_report(table, output, resamples=resamples, source=str(source))
    typer.echo(f"backlash_score {report.score}; best FN feature {report.best_fn}")
    typer.echo(f"report: {report.path}")
