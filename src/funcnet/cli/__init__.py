"""The ``funcnet`` command line: a thin layer over the library.

Commands: ``demo`` (simulate the paper's plan, analyse it, write the report), ``simulate``,
``network`` (the functional networks of one trace: one per phase, or of one window),
``inspect`` (the engineer's HTML report of traces), ``backlash`` (diagnose backlash in traces),
``study`` (a batch from a TOML file) and ``report`` (HTML report of a study's results).
``funcnet COMMAND --help`` is each command's reference.

Conventions:

* An error in the input (every :class:`~funcnet.errors.FuncnetError`, an operating-system error
  on a file, and a usage error: unknown option or command, missing argument, bad value) prints
  exactly one plain-text line, ``funcnet: error: MESSAGE``, on stderr and exits with status 2.
  Nothing is left half-written: outputs are written to a temporary file and renamed.
* Warnings of the library print as one line counting them per problem after the command
  succeeded (``--verbose``: one line each, ``funcnet: warning: MESSAGE``, once per distinct
  message); an error prints its one line only; ``demo`` and ``study`` count them per problem
  (in the report, in the summary lines).
* Progress bars go to stderr, only when stderr is a terminal and ``--quiet`` is not given.
* ``funcnet study`` exits with status 1 when it finished but some tasks could not be analysed
  (listed in ``study.json``), so that scripts notice.

Length: over 600 lines because each command's options and their help texts are the command
line's reference; every rule they apply lives in the library.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import warnings
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Annotated, Any

import typer

# typer vendors click: these are the classes it raises (not the separate ``click`` package's).
from typer._click.exceptions import ClickException, NoArgsIsHelpError
from typer.core import TyperCommand, TyperGroup

from funcnet import __version__
from funcnet.cli.backlash_report_command import register as _register_sweep_report
from funcnet.cli.network_helpers import (
    _FLAGS,  # noqa: F401  (the command's spelling of each parameter; tests read it here)
    _NO_OPTION,  # noqa: F401
    Alpha,
    Axis,
    Channels,
    EdgeRule,
    Evidence,
    EvidenceSeed,
    Resamples,
    SurrogateMethod,
    Surrogates,
    _check_cost,
    _check_signals,
    _chosen_windows,
    _default,
    _evidence_settings,
    _is_terminal,
    _network_files,
    _network_overrides,
    _parse_size,
    _print_pairs,
    _print_phases,
    _signal_list,
    _spelled_as_options,
    _window_request,
    _write_network,
)
from funcnet.cli.stability_command import register as _register_stability
from funcnet.errors import FuncnetError, FuncnetWarning, ParameterError, RecordingWarning
from funcnet.parameters import NetworkParameters

__all__ = ["app", "main"]


class _PlainErrorsGroup(TyperGroup):
    """The ``funcnet`` group, printing a usage error as one plain line (exit status 2).

    Typer's own handling prints the usage, a hint and the message in a rich box.
    """

    def main(
        self,
        args: Sequence[str] | None = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        windows_expand_args: bool = True,
        **extra: Any,
    ) -> Any:
        forwarded = dict(extra, windows_expand_args=windows_expand_args)
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **forwarded)
        try:
            # Not standalone, click raises its errors here and returns typer.Exit's status, or
            # the command's value (None) when it ends normally.
            status = super().main(args, prog_name, complete_var, False, **forwarded)
        except NoArgsIsHelpError as exc:
            sys.stdout.write(exc.ctx.get_help() + "\n")  # bare `funcnet`: the help
            sys.exit(exc.exit_code)
        except ClickException as exc:
            sys.stderr.write(f"funcnet: error: {_one_line(exc.format_message())}\n")
            sys.exit(exc.exit_code)
        except typer.Abort:
            sys.stderr.write("funcnet: error: aborted\n")
            sys.exit(1)
        sys.exit(status if isinstance(status, int) else 0)


class _PlainUsageCommand(TyperCommand):
    """A command whose usage line names its arguments in capitals (``TRACE...``), not in
    braces (typer writes a required argument as ``{trace}``)."""

    def collect_usage_pieces(self, ctx: Any) -> list[str]:
        return [piece.replace("{", "").replace("}", "").upper() if "{" in piece else piece
                for piece in super().collect_usage_pieces(ctx)]

    def get_help(self, ctx: Any) -> str:
        # typer shows a list argument's type as Python's "<list[Path]>"; say "<path>..."
        return _LIST_TYPE.sub(lambda m: f"<{m.group(1).lower()}>...", super().get_help(ctx))


_LIST_TYPE = re.compile(r"<list\[(\w+)\]>")


app = typer.Typer(
    cls=_PlainErrorsGroup,
    name="funcnet",
    help=(
        "Functional networks of robot-axis controller traces, from inter-system recurrence "
        "networks (El Dabett, Hansen & Geier). Start with `funcnet demo`."
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain click help: wrapped cleanly, no "<bool>" on flags
)

_EXIT_INPUT_ERROR = 2
_EXIT_TASKS_FAILED = 1
_NETWORK_SUFFIXES = (".json", ".graphml", ".csv", ".png", ".svg")


# --------------------------------------------------------------------------------------------
# errors, warnings and progress


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _os_error_message(exc: OSError) -> str:
    if exc.filename is not None and exc.strerror:
        return f"{exc.filename}: {exc.strerror}"
    return str(exc)


# Python spellings in library messages, and the command line's own for the same thing.
_RESPELLED = {
    "funcnet.robot.resample decimates or interpolates them":
        "--resample decimate or --resample interpolate brings them onto one grid",
    "normalize=None": "--normalize none",
}


def _respelled(text: str) -> str:
    for python, flag in _RESPELLED.items():
        text = text.replace(python, flag)
    return text


@contextlib.contextmanager
def _reported_errors(*, summarized: bool = False, verbose: bool = False) -> Iterator[None]:
    """Turn input errors into one plain line on stderr and exit status 2.

    Warnings are collected and reported when the command succeeds; a failed command prints its
    error line only. The library's warnings (:class:`FuncnetWarning`) are summarized in one
    line, counted per problem; ``verbose`` prints each distinct one instead. ``summarized``: the
    command reports the library's warnings itself (counted per problem), so they are not
    printed too.
    """
    messages: list[str] = []
    problems: dict[str, int] = {}

    def collect(message: Any, *_: Any, **__: Any) -> None:
        # What the reader left out or split is said in full: it is about the file, not a pair.
        if isinstance(message, FuncnetWarning) and not verbose and not isinstance(
            message, RecordingWarning
        ):
            problem = message.problem or type(message).__name__
            problems[problem] = problems.get(problem, 0) + 1
            return
        text = _respelled(_one_line(str(message)))
        if text not in messages:
            messages.append(text)

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        if summarized:
            warnings.simplefilter("ignore", FuncnetWarning)
            warnings.simplefilter("always", RecordingWarning)
        warnings.showwarning = collect
        try:
            yield
        except FuncnetError as exc:
            sys.stderr.write(f"funcnet: error: {_one_line(str(exc))}\n")
            raise typer.Exit(_EXIT_INPUT_ERROR) from None
        except OSError as exc:
            sys.stderr.write(f"funcnet: error: {_one_line(_os_error_message(exc))}\n")
            raise typer.Exit(_EXIT_INPUT_ERROR) from None
    if problems:
        total = sum(problems.values())
        counted = ", ".join(f"{name} ×{n}" for name, n in problems.items())
        sys.stderr.write(f"funcnet: warning: {total} warning(s) from the library ({counted}); "
                         "the pairs tables flag the pairs concerned; --verbose prints each\n")
    for text in messages:
        sys.stderr.write(f"funcnet: warning: {text}\n")


@contextlib.contextmanager
def _progress(quiet: bool, label: str) -> Iterator[Callable[..., None] | None]:
    """A rich progress bar on stderr, or ``None`` when quiet or stderr is not a terminal.

    Yields a callback ``progress(done, total, description=None)``, the protocol of the library's
    long-running functions.
    """
    if quiet or not _is_terminal(sys.stderr):
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeRemainingColumn

    with Progress(
        "[progress.description]{task.description}",
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
        console=Console(stderr=True),
        transient=True,
    ) as bar:
        task = bar.add_task(label, total=None)

        def update(done: int, total: int, description: str | None = None) -> None:
            text = label if description is None else f"{label}: {description}"
            bar.update(task, completed=done, total=total, description=text)

        yield update


def _version(value: bool) -> None:
    if value:
        typer.echo(f"funcnet {__version__}")
        raise typer.Exit()


@app.callback()
def _main_options(
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, metavar="", help="Print the version."
        ),
    ] = False,
) -> None:
    """Functional networks of robot-axis controller traces."""


Verbose = Annotated[
    bool,
    typer.Option("--verbose", "-v", metavar="",
                 help="Print every warning in full (by default: one line counting them)."),
]

# metavar="": a flag takes no value, so the help shows none (typer's default is "<bool>").
Quiet = Annotated[
    bool,
    typer.Option(
        "--quiet", "-q", metavar="", help="No progress bar (also off when not on a terminal)."
    ),
]


# --------------------------------------------------------------------------------------------
# demo, simulate


@app.command(cls=_PlainUsageCommand)
def demo(
    out: Annotated[
        Path, typer.Option("--out", help="Folder of the report (and of the simulated plan).")
    ] = Path("out"),
    quiet: Quiet = False,
) -> None:
    """Simulate the paper's plan of experiments, analyse it and write the HTML report.

    The 36 trials of the paper's Table 1 are simulated into OUT/plan (trials already there with
    the same parameters are kept), the analyses of the paper's section 4 run on them, and the
    report is written to OUT. The path of the report is printed.
    """
    # The report counts the analyses' warnings per problem: not printed once per trial here.
    with _reported_errors(summarized=True):
        from funcnet.report import build_demo_report
        from funcnet.robot import paper_plan, write_plan

        plan_dir = out / "plan"
        with _progress(quiet, "simulating") as progress:
            write_plan(paper_plan(), plan_dir, progress=progress)
        with _progress(quiet, "analysing") as progress:
            report = build_demo_report(plan_dir, out, progress=progress)
    typer.echo(f"report: {report}")


@app.command(cls=_PlainUsageCommand)
def simulate(
    out: Annotated[Path, typer.Option("--out", help="Folder of the traces (may exist).")],
    plan: Annotated[
        str,
        typer.Option(
            "--plan",
            help="'paper' (the 36 trials of the paper's Table 1), 'backlash-sweep' (reversal "
            "trials over backlash widths, speeds, TCPs and nuisances), 'continuous-sweep' "
            "(smooth set-points turning without a rest, with and without a gravity load) or a "
            "plan TOML file.",
        ),
    ] = "paper",
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seed of the noise.")] = 0,
    quiet: Quiet = False,
) -> None:
    """Simulate a plan of experiments on the model axis and write its traces.

    One SINUMERIK-format XML trace per trial and a manifest of every trial's parameters and
    ground truth are written to OUT. Trials already written with the same parameters are not
    simulated again. The same seed gives the same bytes.
    """
    with _reported_errors():
        from funcnet.robot import named_plan, paper_plan, read_plan, write_plan
        from funcnet.robot.sim import NAMED_PLANS

        if plan == "paper":
            trials = paper_plan()
        else:
            trials = named_plan(plan) if plan in NAMED_PLANS else read_plan(plan)
        traces = [out / f"{trial.name}.xml" for trial in trials]
        before = [_file_identity(path) for path in traces]
        with _progress(quiet, "simulating") as progress:
            manifest = write_plan(trials, out, seed=seed, progress=progress)
        # write_plan replaces a trace it simulates (atomic rename: a new file); one it skips
        # keeps its identity.
        skipped = sum(
            old is not None and old == _file_identity(path)
            for old, path in zip(before, traces, strict=True)
        )
    typer.echo(
        f"{len(trials)} traces and {manifest.name} in {manifest.parent}: "
        f"{len(trials) - skipped} simulated, {skipped} skipped (already there, same parameters)"
    )


def _file_identity(path: Path) -> tuple[int, int, int] | None:
    """(device, inode, modification time) of a file, ``None`` when there is none."""
    try:
        status = path.stat()
    except FileNotFoundError:
        return None
    return status.st_dev, status.st_ino, status.st_mtime_ns


# --------------------------------------------------------------------------------------------
# network

@app.command(cls=_PlainUsageCommand)
def network(
    trace: Annotated[Path, typer.Argument(
        help="Trace file: SINUMERIK XML, CSV, Parquet, MATLAB (.mat) or HDF5 (.h5).")],
    signals: Annotated[
        str | None,
        typer.Option(
            "--signals",
            help="Comma-separated nodes, e.g. RP,AP,MP,V,RC,AC. Default: every role the trace "
            "has plus V (velocity derived from AP, Eq. 11-12). FE (RP-AP) and TORSION (MP-AP) "
            "are derived too when named.",
        ),
    ] = None,
    phase: Annotated[
        str | None,
        typer.Option(
            "--phase",
            help="Analyse one detected motion phase (e.g. cruise, braking), by phase name or "
            "window label.",
        ),
    ] = None,
    window: Annotated[
        str | None,
        typer.Option("--window", help="Analyse START:STOP seconds, e.g. 1.0:5.0; 'all': the "
                     "whole recording (where every signal has a value) as one window."),
    ] = None,
    list_phases: Annotated[
        bool,
        typer.Option(
            "--list-phases",
            metavar="",
            help="Print the detected phases (label, phase, start, stop in seconds), to choose "
            "--phase or --window, and stop.",
        ),
    ] = False,
    resample: Annotated[
        str | None,
        typer.Option(
            "--resample",
            metavar="METHOD",
            help="Bring signals logged on a coarser grid (AP, MP: 4 ms IPO) to one grid first: "
            "decimate (keep the ticks where every signal is written) or interpolate (straight "
            "lines between their samples). Derived signals are computed after it. Without it "
            "such signals are staircases (a warning says so).",
        ),
    ] = None,
    dim: Annotated[
        int | None, typer.Option(help=f"Embedding dimension m (Eq. 1). {_default('dim')}")
    ] = None,
    delay: Annotated[
        int | None,
        typer.Option(help=f"Embedding delay tau in samples (Eq. 1). {_default('delay')}"),
    ] = None,
    rr: Annotated[
        float | None,
        typer.Option(help=f"Recurrence rate in each signal, fixes eps_X (Eq. 5). {_default('rr')}"),
    ] = None,
    cr: Annotated[
        float | None,
        typer.Option(help=f"Cross-recurrence rate, fixes eps_XY (Eq. 3). {_default('cr')}"),
    ] = None,
    mu: Annotated[
        float | None,
        typer.Option(help=f"Edge threshold on C_diff and T_diff (section 2.4). {_default('mu')}"),
    ] = None,
    mu_c: Annotated[
        float | None,
        typer.Option("--mu-c", help="Edge threshold on C_diff alone. [default: --mu]"),
    ] = None,
    mu_t: Annotated[
        float | None,
        typer.Option("--mu-t", help="Edge threshold on T_diff alone. [default: --mu]"),
    ] = None,
    metric: Annotated[
        str | None,
        typer.Option(
            help="Distance: euclidean, supremum (alias chebyshev) or manhattan (alias "
            f"cityblock). {_default('metric')}"
        ),
    ] = None,
    normalize: Annotated[
        str | None,
        typer.Option(
            help="Per-window normalization: minmax, zscore or none (signals as recorded). "
            f"{_default('normalize')}"
        ),
    ] = None,
    measure: Annotated[
        str | None,
        typer.Option(help=f"Edges from both, clustering or transitivity. {_default('measure')}"),
    ] = None,
    rule: Annotated[
        str | None,
        typer.Option(help=f"Threshold rule: funcnet or pyunicorn. {_default('rule')}"),
    ] = None,
    theiler: Annotated[
        int | None,
        typer.Option(
            help="Theiler window: exclude pairs with |i-j| <= THEILER (0 excludes only the "
            f"diagonal, as pyrqa's theiler=1). {_default('theiler')}"
        ),
    ] = None,
    keep_degenerate: Annotated[
        bool,
        typer.Option(
            "--keep-degenerate",
            metavar="",
            help="Keep pairs with a degenerate recurrence structure (too few distinct states) "
            "as edges, flagged degenerate; by default they are in the pairs table only.",
        ),
    ] = False,
    channels: Channels = None,
    axis: Axis = None,
    drop_constant: Annotated[
        bool,
        typer.Option(
            "--drop-constant",
            metavar="",
            help="Leave a signal constant in the window out of the network (min-max needs a "
            "range); by default it is an error.",
        ),
    ] = False,
    output: Annotated[
        Path | None,
        typer.Option(
            "--output",
            "-o",
            help="Write the network: .json (exact, reloadable), .graphml, .csv (the pairs "
            "table), or a drawing (.png, .svg) titled with the trace, window and parameters. "
            "Without it the pairs table is printed.",
        ),
    ] = None,
    size: Annotated[
        str,
        typer.Option("--size", metavar="WxH",
                     help="Size of a drawing in pixels (at 100 dpi), e.g. 900x900."),
    ] = "700x750",
    force: Annotated[
        bool,
        typer.Option("--force", metavar="",
                     help="Compute even when the forecast is over a minute or 4 GiB."),
    ] = False,
    evidence: Evidence = False,
    surrogates: Surrogates = None,
    alpha: Alpha = 0.05,
    seed: EvidenceSeed = 0,
    resamples: Resamples = 200,
    edge_rule: EdgeRule = "paper",
    surrogate_method: SurrogateMethod = "shift",
    verbose: Verbose = False,
    quiet: Quiet = False,
) -> None:
    """Compute the functional networks of one trace: per phase, or of one window of it.

    Every pair of signals gets cross-clustering and cross-transitivity in both directions
    (Eq. 6-9), their differences (Eq. 10) and an edge by the mu rule with the weight of Eq. 13.
    A negative difference reads as X -> Y (kind x->y); it may reflect how differently the two
    signals fill their phase space rather than coupling (README, "Direction"). Without -o the
    pairs table is printed: the main columns as a table on a terminal, every column as plain
    text when piped. Degenerate pairs (too few distinct states) are flagged and are no edges
    unless --keep-degenerate.

    Without --phase or --window: one network per detected phase of every move (standstill
    left out: the set-point is constant there), printed one after the other; with -o one file
    per phase, named after it (net-cruise-1.json). A network whose forecast cost is over a
    minute or 4 GiB (a long --window: the cost grows with the cube of its length) is refused
    unless --force.

    --evidence adds the evidence columns to every pairs table, file and drawing: whether the
    pair is coupled at all (a joint-recurrence test against time-shift surrogates; on short
    windows few shifts fit, and a pair that cannot reach the level is untestable, not
    uncoupled), intervals of C_diff and T_diff, and the reading 'evidence'. It multiplies the
    cost (about 10x on a 300-sample window with 6 signals).
    """
    with _reported_errors(verbose=verbose):
        inches = _parse_size(size)
        evidence_settings = _evidence_settings(evidence, surrogates, alpha, seed, resamples,
                                               edge_rule, surrogate_method)
        if output is not None and output.suffix.lower() not in _NETWORK_SUFFIXES:
            raise ParameterError(
                f"-o {output}: unknown format, use one of {', '.join(_NETWORK_SUFFIXES)}"
            )
        given = {
            "dim": dim,
            "delay": delay,
            "rr": rr,
            "cr": cr,
            "mu": mu,
            "mu_c": mu_c,
            "mu_t": mu_t,
            "metric": metric,
            "measure": measure,
            "rule": rule,
            "theiler": theiler,
        }
        overrides = _network_overrides(given, normalize, keep_degenerate)
        # Options are checked before the trace is read: a bad one is reported as itself, not
        # as whatever the computation would stumble on first.
        with _spelled_as_options():
            parameters = NetworkParameters(**overrides)
        whole, bounds = _window_request(phase, window)
        names = _signal_list(signals)
        from funcnet.pipeline import window_evidence, window_networks
        from funcnet.robot import read_recording

        with _progress(quiet, "network") as progress:
            with _spelled_as_options():
                recording = read_recording(
                    trace, signals=names, channels=channels, axis=axis, resample=resample
                )
            _check_signals(names, recording, trace)
            if list_phases:
                _print_phases(recording, trace)
                return
            chosen = _chosen_windows(recording, trace, phase, whole, bounds)
            _check_cost(recording, chosen, names, parameters, force)
            nets = window_networks(
                recording, chosen, signals=names, parameters=parameters,
                constant="drop" if drop_constant else "error", progress=progress,
            )
            if evidence_settings is not None:
                nets = window_evidence(recording, nets, chosen, **evidence_settings)
        if output is None:
            for net in nets.values():
                _print_pairs(net)
            return
        written = _network_files(output, list(nets))
        for net, path in zip(nets.values(), written, strict=True):
            _write_network(net, path, inches, trace)
    for path in written:
        typer.echo(f"wrote {path}")


# --------------------------------------------------------------------------------------------
# backlash

_BACKLASH_SUFFIXES = (".json", ".html")


@app.command(cls=_PlainUsageCommand)
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
    with _reported_errors():
        if output is not None and output.suffix.lower() not in _BACKLASH_SUFFIXES:
            raise ParameterError(
                f"-o {output}: unknown format, use one of {', '.join(_BACKLASH_SUFFIXES)}"
            )
        from funcnet.diagnosis import diagnose_backlash, write_results

        with _progress(quiet, "backlash"):
            results = diagnose_backlash(*traces, channels=channels, axis=axis)
        if output is not None:
            write_results(results, output)
    for result in results:
        where = result.path if result.axis is None else f"{result.path} axis {result.axis}"
        typer.echo(f"{where}: {_one_line(result.message)}")
        typer.echo(f"  {_backlash_numbers(result)}")
    if output is not None:
        typer.echo(f"wrote {output}")


def _backlash_numbers(result: Any) -> str:
    """Score and lost motion of one trace's diagnosis, on one line."""
    if result.backlash_score is None:
        score = f"backlash_score none ({result.score_indicator})"
    else:
        spread = "" if result.score_spread is None else f" ± {result.score_spread:.3g}"
        score = f"backlash_score {result.backlash_score:.4g}{spread} deg ({result.score_indicator})"
    if result.lost_motion is None:
        return f"{score}; lost_motion none ({result.lost_motion_reason or 'no AP'})"
    # Backlash is read in arcmin (1/60 deg); the JSON keeps degrees, as the manifest does.
    spread = "" if result.lost_motion_spread is None else f" ± {60 * result.lost_motion_spread:.2f}"
    return f"{score}; lost_motion {60 * result.lost_motion:.2f}{spread} arcmin"


# --------------------------------------------------------------------------------------------
# inspect


@app.command(cls=_PlainUsageCommand)
def inspect(
    traces: Annotated[
        list[Path], typer.Argument(metavar="TRACE", help="Trace files: SINUMERIK XML, CSV, "
                                   "Parquet, MATLAB (.mat) or HDF5 (.h5).")
    ],
    out: Annotated[
        Path, typer.Option("--out", "-o", help="Report folder (one sub-folder per trace when "
                           "there are several, and an index).")
    ] = Path("inspect"),
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
    is printed.
    """
    with _reported_errors(verbose=verbose):
        names = _signal_list(signals)
        from funcnet.inspection import DETRENDED_NODES
        from funcnet.report.inspect import inspect_trace

        if detrended:
            if names is not None:
                raise ParameterError("give --signals or --detrended, not both")
            names = list(DETRENDED_NODES)
        # the same evidence options, checks and messages as funcnet network's
        options = _evidence_settings(evidence, surrogates, alpha, seed, resamples, "paper",
                                     surrogate_method)

        with _progress(quiet, "inspect") as progress:
            page = inspect_trace(*traces, out_dir=out, signals=names, evidence=evidence,
                                 channels=channels, axis=axis, progress=progress,
                                 evidence_options=options)
    typer.echo(f"report: {page}")


# --------------------------------------------------------------------------------------------
# study, report


@app.command(cls=_PlainUsageCommand)
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
    provenance. Exit status 1 when some windows could not be analysed (see study.json).
    """
    # Warnings are counted per problem over the tasks (printed below), wherever they ran.
    with _reported_errors(summarized=True):
        from funcnet.study import load_study, run_study

        described = load_study(study_file)
        target = out if out is not None else Path("out") / study_file.stem
        with _progress(quiet, "study") as progress:
            result = run_study(
                described, target, scheduler=scheduler, workers=workers, progress=progress
            )
    typer.echo(
        f"{result.tasks} tasks: {result.computed} computed, {result.cached} already done, "
        f"{len(result.failures)} failed; rows in {result.out_dir / 'rows'}"
    )
    for category, (count, example) in result.warnings.items():
        sys.stderr.write(
            f"funcnet: warning: {category} in {count} of {result.computed} networks computed, "
            f"e.g. {_one_line(example)}\n"
        )
    varied = [name for name, values in described.parameters if len(values) > 1]
    # One line per cause, its tasks counted and the first few named (not one line per task).
    causes: dict[str, list[str]] = {}
    for failure in result.failures:
        setting = "".join(
            f" {k}={failure.parameters[k]}" for k in varied if k in failure.parameters
        )
        message = _one_line(failure.message)
        # the same cause in another file or window: the message without its location
        cause = message.split(": ", 1)[-1] if message.startswith(failure.recording) else message
        causes.setdefault(cause, []).append(f"{failure.recording} [{failure.window}]{setting}")
    for cause, where in causes.items():
        shown = ", ".join(where[:3]) + (f" and {len(where) - 3} more" if len(where) > 3 else "")
        sys.stderr.write(f"funcnet: failed: {len(where)} task(s) ({shown}): {cause}\n")
    if result.failures:
        raise typer.Exit(_EXIT_TASKS_FAILED)


@app.command(cls=_PlainUsageCommand)
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
    with _reported_errors():
        from funcnet.report import write_report

        with _progress(quiet, "report") as progress:
            written = write_report(results_dir, out, progress=progress)
    typer.echo(f"report: {written}")


_register_stability(app, command_class=_PlainUsageCommand, reported_errors=_reported_errors)
_register_sweep_report(app, command_class=_PlainUsageCommand, reported_errors=_reported_errors,
                       progress=_progress)


def main() -> None:
    """Entry point of the ``funcnet`` command."""
    # An application's choice, not the library's: idle OpenMP threads that spin instead of
    # sleeping made the kernels ~3x slower on a loaded 2-core machine.
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    app(prog_name="funcnet")

