"""``funcnet network`` and ``funcnet stability``: the functional networks of a trace's windows,
and how stable their edges are over a grid of settings.

Both take the network options (:func:`funcnet.cli.options.network_options`) and the same
windows. The computations are :func:`funcnet.window_networks` and
:func:`funcnet.network.stability.edge_stability`; the figures :func:`funcnet.plot.save_network`
and :func:`funcnet.plot.plot_stability`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from funcnet.cli.messages import progress_bar, reported_errors
from funcnet.cli.network_output import (
    network_files,
    print_pairs,
    print_setpoint_check,
    write_network,
)
from funcnet.cli.options import (
    Alpha,
    Axis,
    Channels,
    EdgeRule,
    Evidence,
    EvidenceSeed,
    Intervals,
    NetworkOptions,
    Quiet,
    Resamples,
    SurrogateMethod,
    Surrogates,
    Trace,
    Verbose,
    evidence_settings,
    network_options,
    parse_size,
    signal_list,
    spelled_as_options,
    window_request,
)
from funcnet.cli.selection import check_cost, check_signals, chosen_windows, print_phases
from funcnet.errors import FuncnetError, ParameterError
from funcnet.parameters import NetworkParameters

__all__ = ["network", "stability", "parse_vary"]

_NETWORK_SUFFIXES = (".json", ".graphml", ".csv", ".png", ".svg")
_STABILITY_SUFFIXES = (".csv", ".parquet", ".png", ".svg")


# --------------------------------------------------------------------------------------------
# network


@network_options
def network(
    trace: Trace,
    *,
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
    network: NetworkOptions,
    channels: Channels = None,
    axis: Axis = None,
    drop_constant: Annotated[
        bool,
        typer.Option(
            "--drop-constant/--strict-constant",
            help="Leave a signal constant in a window out of that window's network, said in "
            "one line (the default: min-max needs a range); --strict-constant makes it an "
            "error.",
        ),
    ] = True,
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
    arrows: Annotated[
        str,
        typer.Option("--arrows", metavar="WHOSE",
                     help="Arrows of a drawing: direction (the direction reading: one "
                     "signal's past improves the other's prediction; undecided pairs pale "
                     "lines) or rule (the paper's mu rule, kind)."),
    ] = "direction",
    evidence: Evidence = False,
    surrogates: Surrogates = None,
    alpha: Alpha = 0.05,
    seed: EvidenceSeed = 0,
    resamples: Resamples = 200,
    edge_rule: EdgeRule = "paper",
    surrogate_method: SurrogateMethod = "shift",
    intervals: Intervals = "coupled",
    verbose: Verbose = False,
    quiet: Quiet = False,
) -> None:
    """Compute the functional networks of one trace: per phase, or of one window of it.

    Every pair of signals gets cross-clustering and cross-transitivity in both directions
    (Eq. 6-9), their differences (Eq. 10) and an edge by the mu rule with the weight of Eq. 13.
    A negative difference reads as X -> Y (kind x->y); it may reflect how differently the two
    signals fill their phase space rather than coupling (docs/guide/direction.md). Without -o the
    pairs table is printed: the main columns as a table on a terminal, every column as plain
    text when piped. First comes the set-point check: how often the rule's arrows and the
    direction reading point into the position set-point RP (which nothing drives) and out of
    it. Every pair also gets a direction (x->y, y->x or none, with its reason): whether one
    signal's past improves the prediction of the other beyond its own past
    (docs/guide/direction.md); a drawing (-o net.png) shows these arrows, --arrows rule the
    rule's. Degenerate pairs (too few distinct states) are flagged and are no edges unless
    --keep-degenerate.

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
    with reported_errors(verbose=verbose):
        inches = parse_size(size)
        evidence_keywords = evidence_settings(evidence, surrogates, alpha, seed, resamples,
                                              edge_rule, surrogate_method, intervals)
        if arrows not in ("direction", "rule"):
            raise ParameterError(f"--arrows must be direction or rule, got {arrows!r}")
        if output is not None and output.suffix.lower() not in _NETWORK_SUFFIXES:
            raise ParameterError(
                f"-o {output}: unknown format, use one of {', '.join(_NETWORK_SUFFIXES)}"
            )
        # Options are checked before the trace is read: a bad one is reported as itself, not
        # as whatever the computation would stumble on first.
        parameters = network.parameters()
        whole, bounds = window_request(phase, window)
        names = signal_list(signals)
        from funcnet.pipeline import window_evidence, window_networks
        from funcnet.robot import read_recording

        with progress_bar(quiet, "network") as progress:
            with spelled_as_options():
                recording = read_recording(
                    trace, signals=names, channels=channels, axis=axis, resample=resample
                )
            check_signals(names, recording, trace)
            if list_phases:
                print_phases(recording, trace)
                return
            from funcnet.core.embedding import min_samples

            chosen = chosen_windows(
                recording, trace, phase, whole, bounds,
                min_samples=min_samples(parameters.dim, parameters.delay),
            )
            check_cost(recording, chosen, names, parameters, force)
            nets = window_networks(
                recording, chosen, signals=names, parameters=parameters,
                constant="drop" if drop_constant else "error", progress=progress,
            )
            if evidence_keywords is not None:
                nets = window_evidence(recording, nets, chosen, **evidence_keywords)
        print_setpoint_check(list(nets.values()), tables=output is None)
        if output is None:
            for net in nets.values():
                print_pairs(net)
            return
        written = network_files(output, list(nets))
        for net, path in zip(nets.values(), written, strict=True):
            write_network(net, path, inches, trace, arrows=arrows)
    for path in written:
        typer.echo(f"wrote {path}")


# --------------------------------------------------------------------------------------------
# stability

_INTEGER_FIELDS = ("dim", "delay", "theiler")
_TEXT_FIELDS = ("metric", "rule", "normalize", "measure")
def _value(field: str, text: str) -> Any:
    """One value of ``--vary`` for ``field``: an int, a float, a name (``none``: None)."""
    text = text.strip()
    if field in _TEXT_FIELDS:
        return None if field == "normalize" and text.lower() == "none" else text
    try:
        return int(text) if field in _INTEGER_FIELDS else float(text)
    except ValueError:
        kind = "an integer" if field in _INTEGER_FIELDS else "a number"
        raise ParameterError(f"--vary {field}: {text!r} is not {kind}") from None


def parse_vary(items: list[str] | None) -> dict[str, tuple[Any, ...]] | None:
    """``--vary KEY=V1,V2`` (repeatable) as a grid; ``KEY`` a field or fields joined by ``+``.

    Examples
    --------
    >>> parse_vary(["mu=0.02,0.1", "rr+cr=0.1", "normalize=zscore,none"])
    {'mu': (0.02, 0.1), 'rr+cr': (0.1,), 'normalize': ('zscore', None)}
    >>> parse_vary(["mu"])
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: --vary must be KEY=V1,V2,... (e.g. mu=0.025,0.1), got 'mu'
    """
    if not items:
        return None
    grid: dict[str, tuple[Any, ...]] = {}
    for item in items:
        key, sep, text = item.partition("=")
        key = key.strip()
        values = [v for v in text.split(",") if v.strip()]
        if not sep or not key or not values:
            raise ParameterError(
                f"--vary must be KEY=V1,V2,... (e.g. mu=0.025,0.1), got {item!r}"
            )
        if key in grid:
            raise ParameterError(f"--vary {key} is given twice")
        # A joint key (rr+cr) takes one value for all its fields: parsed as its first field.
        grid[key] = tuple(_value(key.split("+")[0].strip(), v) for v in values)
    return grid


def _write(frames: list[Any], results: list[Any], labels: list[str], output: Path,
           trace: Path) -> list[Path]:
    from funcnet._io import atomic_path

    suffix = output.suffix.lower()
    if suffix in (".csv", ".parquet"):
        import pandas as pd

        table = pd.concat(frames, ignore_index=True)
        with atomic_path(output) as tmp:
            if suffix == ".csv":
                table.to_csv(tmp, index=False)
            else:
                table.to_parquet(tmp, index=False)
        return [output]
    from funcnet.plot import plot_stability

    written = network_files(output, labels)
    for result, label, path in zip(results, labels, written, strict=True):
        ax = plot_stability(result)
        title = ax.get_title()
        ax.set_title(f"{trace.name}, {label}\n{title}", fontsize=10)
        figure = ax.get_figure(root=True)
        assert figure is not None  # plot_stability draws on a figure of its own
        with atomic_path(path) as tmp:
            figure.savefig(tmp, dpi=100, format=suffix.lstrip("."))
    return written


@network_options
def stability(
    trace: Trace,
    *,
    signals: Annotated[
        str | None,
        typer.Option("--signals", help="Comma-separated nodes, e.g. RP,AP,MP,V,RC,AC. "
                     "Default: the paper's nodes the trace has."),
    ] = None,
    phase: Annotated[
        str | None,
        typer.Option("--phase", help="One detected motion phase (e.g. cruise), by phase "
                     "name or window label."),
    ] = None,
    window: Annotated[
        str | None,
        typer.Option("--window", help="START:STOP in seconds, or 'all' (the whole "
                     "recording). Default: every phase of every move."),
    ] = None,
    resample: Annotated[
        str | None,
        typer.Option("--resample", metavar="METHOD", help="decimate or interpolate signals "
                     "logged on a coarser grid (AP, MP) onto one grid first."),
    ] = None,
    network: NetworkOptions,
    vary: Annotated[
        list[str] | None,
        typer.Option("--vary", metavar="KEY=V1,V2",
                     help="Vary KEY over the values (repeatable), e.g. --vary mu=0.025,0.1 "
                     "--vary rr+cr=0.025,0.1 (rates together). Default grid: mu and the "
                     "rates x0.5, 0.75, 1.5, 2; dim +-1; delay /2, x2; the other metrics "
                     "and normalization."),
    ] = None,
    full: Annotated[
        bool,
        typer.Option("--full", metavar="",
                     help="Every combination of the --vary values (default: one at a time)."),
    ] = False,
    drop_constant: Annotated[
        bool,
        typer.Option("--drop-constant/--strict-constant", help="Leave a signal constant in "
                     "a window out of that window's table, said in one line (the default); "
                     "--strict-constant makes it an error."),
    ] = True,
    list_phases: Annotated[
        bool,
        typer.Option("--list-phases", metavar="", help="Print the detected phases and stop."),
    ] = False,
    channels: Annotated[
        Path | None, typer.Option("--channels", help="Channel map TOML.")
    ] = None,
    axis: Annotated[
        int | None, typer.Option("--axis", help="Axis of a trace of several axes.")
    ] = None,
    output: Annotated[
        Path | None,
        typer.Option("--output", "-o", help="Write the table (.csv, .parquet: one row per "
                     "window and pair) or the figure (.png, .svg: one per window). "
                     "Without it the table is printed."),
    ] = None,
    force: Annotated[
        bool,
        typer.Option("--force", metavar="", help="Compute even when one network's forecast "
                     "is over a minute or 4 GiB."),
    ] = False,
    verbose: Annotated[
        bool, typer.Option("--verbose", "-v", metavar="", help="Print every warning.")
    ] = False,
) -> None:
    """How stable each pair's edge kind is over a grid of settings, per window of a trace.

    For every window (by default every phase of every move) the networks' pairs are
    computed at the base settings (the options, else the defaults) and at each setting of
    the grid; per pair: its kind at the base, the fraction of settings that keep it, and
    that fraction per varied key. A pair that is degenerate at a setting has no edge there
    (kind 'degenerate') unless --keep-degenerate.
    """
    with reported_errors(verbose=verbose):
        if output is not None and output.suffix.lower() not in _STABILITY_SUFFIXES:
            raise ParameterError(
                f"-o {output}: unknown format, use one of {', '.join(_STABILITY_SUFFIXES)}"
            )
        overrides = network.overrides()
        grid = parse_vary(vary)
        if full and grid is None:
            raise ParameterError("--full needs --vary (the default grid is one at a time)")
        from funcnet.network.stability import check_grid

        with spelled_as_options():
            parameters = NetworkParameters(**overrides)
            check_grid(grid, parameters)  # every value checked before the trace is read
        whole, bounds = window_request(phase, window)
        names = signal_list(signals)
        from funcnet.robot import paper_nodes, read_recording

        with spelled_as_options():
            recording = read_recording(trace, signals=names, channels=channels, axis=axis,
                                       resample=resample)
        check_signals(names, recording, trace)
        if list_phases:
            print_phases(recording, trace)
            return
        from funcnet.core.embedding import min_samples

        chosen = chosen_windows(  # as funcnet network: phases the embedding cannot hold, said
            recording, trace, phase, whole, bounds,
            min_samples=min_samples(parameters.dim, parameters.delay),
        )
        nodes = names or paper_nodes(recording.data.columns)
        check_cost(recording, chosen, nodes, parameters, force)
        frames, results, labels = _compute(recording, chosen, nodes, parameters, grid,
                                           full, trace, drop_constant)
        if output is None:
            for frame, label in zip(frames, labels, strict=True):
                typer.echo(f"{trace.name}, window {label}:")
                typer.echo(frame.drop(columns=["window", "start", "stop"]).to_string(
                    index=False, float_format=lambda v: f"{v:.3g}"))
            return
        written = _write(frames, results, labels, output, trace)
    for path in written:
        typer.echo(f"wrote {path}")


def _compute(recording: Any, chosen: list[Any], nodes: list[str], parameters: NetworkParameters,
             grid: Any, full: bool, trace: Path,
             drop_constant: bool = True) -> tuple[list[Any], list[Any], list[str]]:
    """Per window: its table (window, start, stop first), the result, its label."""
    import warnings

    from funcnet.errors import RecordingWarning
    from funcnet.network.stability import edge_stability, fitting_grid
    from funcnet.pipeline import constant_signals, constant_warning
    from funcnet.robot.preprocess import staircase_warning

    staircase = staircase_warning(recording, nodes, str(trace))
    if staircase is not None:
        warnings.warn(staircase, stacklevel=2)
    frames, results, labels = [], [], []
    dropped: dict[str, tuple[str, ...]] = {}
    short: dict[str, str] = {}
    for chosen_window in chosen:
        part = recording.window(chosen_window.start, chosen_window.stop).data[list(nodes)]
        # as funcnet network: a missing value is an error, naming the signal
        flat = constant_signals(part, f"{trace}: window {chosen_window.label!r}")
        if drop_constant and parameters.normalize is not None:
            # as funcnet network: a constant signal cannot be normalized
            dropped[str(chosen_window.label)] = flat
            part = part.drop(columns=list(flat))
        # a short window is read over the settings whose embedding it holds
        fitted, left_out = fitting_grid(grid, parameters, len(part))
        if left_out:
            short[str(chosen_window.label)] = f"{len(part)} samples: {', '.join(left_out)}"
        try:
            # (no value fits: the grid as given, and its error)
            result = edge_stability(part, parameters=parameters, grid=fitted or grid, full=full)
        except FuncnetError as error:
            error.args = (f"{trace}: window {chosen_window.label!r}: {error}",)
            raise
        frame = result.table.copy()
        frame.insert(0, "stop", float(chosen_window.stop))
        frame.insert(0, "start", float(chosen_window.start))
        frame.insert(0, "window", str(chosen_window.label))
        frames.append(frame)
        results.append(result)
        labels.append(str(chosen_window.label))
    constant = constant_warning(str(trace), dropped, len(chosen))
    if constant is not None:
        warnings.warn(constant, stacklevel=2)
    if short:
        listed = "; ".join(f"{label!r} ({why})" for label, why in short.items())
        warnings.warn(RecordingWarning(
            f"{trace}: settings whose embedding a window is too short for ((dim - 1) * delay "
            f"+ 7 samples) left out of its grid: {listed}", problem="short_setting"),
            stacklevel=2)
    return frames, results, labels
