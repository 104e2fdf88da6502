"""``funcnet stability``: how stable each edge of a trace's networks is over a grid of settings.

Private to :mod:`funcnet.cli`, which registers the command with :func:`register` (the command
line's error handling is passed in, so that this module does not import the one that imports
it). The computation is :func:`funcnet.network.stability.edge_stability`; the figure
:func:`funcnet.plot.plot_stability`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Annotated, Any

import typer

from funcnet.cli.network_helpers import (
    _check_cost,
    _check_signals,
    _chosen_windows,
    _network_files,
    _network_overrides,
    _signal_list,
    _window_request,
)
from funcnet.errors import FuncnetError, ParameterError
from funcnet.parameters import NetworkParameters

__all__ = ["register", "parse_vary"]

_SUFFIXES = (".csv", ".parquet", ".png", ".svg")
_INTEGER_FIELDS = ("dim", "delay", "theiler")
_TEXT_FIELDS = ("metric", "rule", "normalize", "measure")
_FLAGS = {
    **{name: "--" + name.replace("_", "-") for name in NetworkParameters.names()},
    "degenerate": "--keep-degenerate",
    "resample": "--resample",
}


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


@contextlib.contextmanager
def _spelled() -> Iterator[None]:
    """A :class:`ParameterError` with the option's name (``--rr must be ...``, ``--vary``)."""
    try:
        yield
    except ParameterError as exc:
        text = str(exc)
        if text.startswith("grid"):
            raise ParameterError("--vary" + text.removeprefix("grid")) from None
        flag = _FLAGS.get(exc.parameter or "")
        if flag is None:
            raise
        raise ParameterError(exc.spelled(flag), parameter=flag, detail=exc.detail) from None


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
    import matplotlib

    matplotlib.use("Agg")
    from funcnet.plot import plot_stability

    written = _network_files(output, labels)
    for result, label, path in zip(results, labels, written, strict=True):
        ax = plot_stability(result)
        title = ax.get_title()
        ax.set_title(f"{trace.name}, {label}\n{title}", fontsize=10)
        figure = ax.get_figure(root=True)
        assert figure is not None  # plot_stability draws on a figure of its own
        with atomic_path(path) as tmp:
            figure.savefig(tmp, dpi=100, format=suffix.lstrip("."))
    return written


def _command(reported_errors: Callable[..., Any]) -> Callable[..., None]:
    """The command, with the command line's error handling."""

    def stability(
        trace: Annotated[Path, typer.Argument(
        help="Trace file: SINUMERIK XML, CSV, Parquet, MATLAB (.mat) or HDF5 (.h5).")],
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
        dim: Annotated[int | None, typer.Option(help="Base embedding dimension m.")] = None,
        delay: Annotated[int | None, typer.Option(help="Base embedding delay tau.")] = None,
        rr: Annotated[float | None, typer.Option(help="Base recurrence rate.")] = None,
        cr: Annotated[float | None, typer.Option(help="Base cross-recurrence rate.")] = None,
        mu: Annotated[float | None, typer.Option(help="Base edge threshold mu.")] = None,
        metric: Annotated[str | None, typer.Option(help="Base distance.")] = None,
        normalize: Annotated[
            str | None, typer.Option(help="Base normalization: minmax, zscore or none.")
        ] = None,
        measure: Annotated[
            str | None, typer.Option(help="Edges from both, clustering or transitivity.")
        ] = None,
        mu_c: Annotated[
            float | None, typer.Option("--mu-c", help="Base threshold on C_diff alone.")
        ] = None,
        mu_t: Annotated[
            float | None, typer.Option("--mu-t", help="Base threshold on T_diff alone.")
        ] = None,
        rule: Annotated[
            str | None, typer.Option(help="Threshold rule: funcnet or pyunicorn.")
        ] = None,
        theiler: Annotated[int | None, typer.Option(help="Theiler window.")] = None,
        keep_degenerate: Annotated[
            bool,
            typer.Option("--keep-degenerate", metavar="",
                         help="Count a degenerate pair by its kind (by default it is no edge, "
                         "kind 'degenerate')."),
        ] = False,
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
            typer.Option("--drop-constant", metavar="", help="Leave a signal constant in a "
                         "window out of its table (by default it is an error)."),
        ] = False,
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
            if output is not None and output.suffix.lower() not in _SUFFIXES:
                raise ParameterError(
                    f"-o {output}: unknown format, use one of {', '.join(_SUFFIXES)}"
                )
            given = {"dim": dim, "delay": delay, "rr": rr, "cr": cr, "mu": mu, "mu_c": mu_c,
                     "mu_t": mu_t, "metric": metric, "measure": measure, "rule": rule,
                     "theiler": theiler}
            overrides = _network_overrides(given, normalize, keep_degenerate)
            grid = parse_vary(vary)
            if full and grid is None:
                raise ParameterError("--full needs --vary (the default grid is one at a time)")
            from funcnet.network.stability import check_grid

            with _spelled():
                parameters = NetworkParameters(**overrides)
                check_grid(grid, parameters)  # every value checked before the trace is read
            whole, bounds = _window_request(phase, window)
            names = _signal_list(signals)
            from funcnet.robot import paper_nodes, read_recording

            with _spelled():
                recording = read_recording(trace, signals=names, channels=channels, axis=axis,
                                           resample=resample)
            _check_signals(names, recording, trace)
            if list_phases:
                from funcnet.cli.network_helpers import _print_phases

                _print_phases(recording, trace)
                return
            chosen = _chosen_windows(recording, trace, phase, whole, bounds)
            nodes = names or paper_nodes(recording.data.columns)
            _check_cost(recording, chosen, nodes, parameters, force)
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

    return stability


def _compute(recording: Any, chosen: list[Any], nodes: list[str], parameters: NetworkParameters,
             grid: Any, full: bool, trace: Path,
             drop_constant: bool = False) -> tuple[list[Any], list[Any], list[str]]:
    """Per window: its table (window, start, stop first), the result, its label."""
    import warnings

    from funcnet.errors import StaircaseWarning
    from funcnet.network.stability import edge_stability
    from funcnet.robot.preprocess import staircase_signals

    staircases = staircase_signals(recording, nodes)
    if staircases:  # as funcnet network says it (funcnet.pipeline.window_networks)
        warnings.warn(StaircaseWarning(
            f"{trace}: {staircases} are staircases on the {recording.sample_period * 1e3:g} ms "
            "grid (logged on a coarser one); --resample decimate or --resample interpolate "
            "brings them onto one grid", problem="staircase", signals=tuple(staircases),
        ), stacklevel=2)
    frames, results, labels = [], [], []
    for chosen_window in chosen:
        part = recording.window(chosen_window.start, chosen_window.stop).data[list(nodes)]
        if drop_constant and parameters.normalize is not None:
            # as funcnet network --drop-constant: a constant signal cannot be normalized
            part = part.loc[:, (part.max() > part.min()).to_numpy()]
        try:
            result = edge_stability(part, parameters=parameters, grid=grid, full=full)
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
    return frames, results, labels


def register(app: typer.Typer, *, command_class: type[Any],
             reported_errors: Callable[..., Any]) -> None:
    """Add ``funcnet stability`` to ``app`` (``funcnet.cli``'s group, its command class and its
    error handling)."""
    app.command("stability", cls=command_class)(_command(reported_errors))
