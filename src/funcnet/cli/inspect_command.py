"""``funcnet inspect``: the engineer's HTML report of traces: the inspection, then the page.

:func:`funcnet.inspection.inspect_files` reads and inspects each trace,
:func:`funcnet.report.inspect.write_inspections` draws it (:func:`funcnet.inspect_trace` in one).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from funcnet.cli.messages import progress_bar, reported_errors
from funcnet.cli.options import (
    Alpha,
    Axis,
    Channels,
    EvidenceSeed,
    Intervals,
    NetworkOptions,
    Quiet,
    Resamples,
    SurrogateMethod,
    Surrogates,
    Verbose,
    evidence_settings,
    network_options,
    signal_list,
)
from funcnet.errors import ParameterError

__all__ = ["inspect"]


@network_options
def inspect(
    traces: Annotated[
        list[Path], typer.Argument(metavar="TRACE", help="Trace files: SINUMERIK XML, CSV, "
                                   "Parquet, MATLAB (.mat), HDF5 (.h5), a ROS bag.")
    ],
    out: Annotated[
        Path, typer.Option("--out", "-o", help="Report folder (one sub-folder per trace when "
                           "there are several, and an index).")
    ] = Path("inspect"),
    *,
    signals: Annotated[
        str | None,
        typer.Option(
            "--signals",
            help="Comma-separated nodes. Default: the paper's nodes the trace has (RP, AP, MP, "
            "RC, AC) plus V derived from AP.",
        ),
    ] = None,
    detrended: Annotated[
        bool,
        typer.Option(
            "--detrended", metavar="",
            help="Detrended nodes instead: FE (following error RP-AP), TORSION (MP-AP), V, RC, "
            "AC. Positions are ramps in cruise; their differences are not, which the coupling "
            "test's time-shift surrogates need. Not with --signals.",
        ),
    ] = False,
    network: NetworkOptions,
    evidence: Annotated[
        bool,
        typer.Option(
            "--evidence/--no-evidence",
            help="Test each pair's coupling and direction (surrogates; about half the run "
            "time).",
        ),
    ] = True,
    surrogates: Surrogates = None,
    alpha: Alpha = 0.05,
    seed: EvidenceSeed = 0,
    resamples: Resamples = 200,
    surrogate_method: SurrogateMethod = "shift",
    intervals: Intervals = "coupled",
    repeated: Annotated[
        bool,
        typer.Option(
            "--repeated", metavar="",
            help="Also test every pair across the repetitions of the most repeated motion in "
            "the traces together (moves of one set-point profile, aligned on the set-point): "
            "coupling beyond the command, per phase, in repeated.html; with too few "
            "repetitions it says how many a decision needs.",
        ),
    ] = False,
    channels: Channels = None,
    axis: Axis = None,
    verbose: Verbose = False,
    quiet: Quiet = False,
) -> None:
    """Write a readable HTML report of what an axis does in each trace.

    First a plain summary of the motion (moves, phases with their times, speeds, peak currents,
    following error, lost motion at direction changes when both encoders are recorded), then
    one functional network per phase of every move with its evidence, the edge timeline, the
    backlash diagnosis, and what an arrow does and does not say. The path of the page to open
    is printed. A file of several axes (MATLAB, HDF5) without --axis: the robot's page (each
    axis summarized and linked to its own report, one network of all axes with its pairs told
    apart within and between axes); --axis N: the report of axis N.
    """
    with reported_errors(verbose=verbose):
        names = signal_list(signals)
        from funcnet.inspection import DETRENDED_NODES
        from funcnet.inspection.run import inspect_files
        from funcnet.report.inspect import write_inspections

        if detrended:
            if names is not None:
                raise ParameterError("give --signals or --detrended, not both")
            names = list(DETRENDED_NODES)
        # the same evidence options, checks and messages as funcnet network's
        options = evidence_settings(evidence, surrogates, alpha, seed, resamples, "paper",
                                    surrogate_method, intervals)
        parameters = network.parameters()

        with progress_bar(quiet, "inspect") as progress:
            inspections = inspect_files(*traces, signals=names, parameters=parameters,
                                        evidence=evidence, channels=channels, axis=axis,
                                        progress=progress, evidence_options=options,
                                        repeated=repeated)
            page = write_inspections(inspections, out, progress=progress)
    typer.echo(f"report: {page}")
    if repeated:
        typer.echo(f"repetitions: {out / 'repeated.html'}")
