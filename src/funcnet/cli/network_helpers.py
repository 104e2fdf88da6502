"""Helpers of ``funcnet network``: windows, signal checks, the printed pairs table, drawings.

Private to :mod:`funcnet.cli` (the command line's layer); kept apart so that each module stays
readable. Errors are raised as :class:`~funcnet.errors.FuncnetError` naming the command's flags;
the command turns them into its one-line messages.
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Annotated, Any

import typer

from funcnet.errors import ParameterError, WindowError
from funcnet.parameters import NetworkParameters

# Every network parameter's default, for the help texts: NetworkParameters owns them.
_DEFAULTS = NetworkParameters.defaults()


def _default(name: str) -> str:
    value = _DEFAULTS[name]
    return f"[default: {'none' if value is None else value}]"


# How the command spells the parameters it takes, for the messages of a bad value.
_FLAGS = {
    **{name: "--" + name.replace("_", "-") for name in NetworkParameters.names()},
    "degenerate": "--keep-degenerate",
    "resample": "--resample",
}
# Parameters the network command has no option for: explicit thresholds replace the rates.
_NO_OPTION = ("eps",)


@contextlib.contextmanager
def _spelled_as_options() -> Iterator[None]:
    """Re-spell a :class:`ParameterError` with the option's name (``--rr must be ...``)."""
    try:
        yield
    except ParameterError as exc:
        flag = _FLAGS.get(exc.parameter or "")
        if flag is None:
            raise
        raise ParameterError(exc.spelled(flag), parameter=flag, detail=exc.detail) from None


# --------------------------------------------------------------------------------------------
# options shared by the commands (one definition, one help text)

Channels = Annotated[
    Path | None,
    typer.Option("--channels", help="Channel map TOML: a [channels] table of 'signal name = "
                 "\"ROLE\"' pairs (a MATLAB field bare or with its struct path, quoted; the "
                 "role time names a MATLAB or HDF5 file's time), optional [units]. E.g. "
                 "examples/kuka-kr300-channels.toml."),
]
Axis = Annotated[
    int | None,
    typer.Option("--axis", help="Axis to read (1-based) from a trace of several axes. Without "
                 "it a MATLAB or HDF5 file with one row per axis is read whole, its nodes "
                 "named A1.RP, A2.MP, ..."),
]
Evidence = Annotated[
    bool,
    typer.Option(
        "--evidence", metavar="",
        help="Add each pair's evidence (funcnet.evidence): a coupling test on joint "
        "recurrences against time-shift surrogates (coupling_p, Benjamini-Hochberg adjusted; "
        "coupled), intervals of C_diff and T_diff, a direction index, and the reading "
        "'evidence' (coupled-directed, coupled, not-coupled, asymmetry-only = an arrow "
        "without coupling evidence, untestable = too few surrogates to reject at alpha "
        "whatever the data) with its evidence_reason. Off: the paper's network only.",
    ),
]
Surrogates = Annotated[
    int | None,
    typer.Option(
        "--surrogates", min=1, metavar="K",
        help="Surrogates of the coupling test (with --evidence). [default: 99, or more so "
        "that one discovery among the pairs can pass: m/alpha - 1 for m pairs]",
    ),
]
Alpha = Annotated[
    float,
    typer.Option("--alpha", help="Level of the coupling test (FDR over a network's pairs, "
                 "with --evidence)."),
]
EvidenceSeed = Annotated[
    int, typer.Option("--seed", min=0, help="Seed of the surrogates and resamples.")
]
Resamples = Annotated[
    int,
    typer.Option("--resamples", min=0, help="Resamples of the C_diff/T_diff intervals (with "
                 "--evidence; 0: no intervals, faster)."),
]
EdgeRule = Annotated[
    str,
    typer.Option(
        "--edge-rule", metavar="RULE",
        help="paper (the mu rule, as published) or interval (directed only when the "
        "difference's interval excludes 0 and |diff| >= mu; needs --evidence).",
    ),
]
SurrogateMethod = Annotated[
    str,
    typer.Option("--surrogate-method", metavar="METHOD",
                 help="Surrogates of the coupling test: shift (circular time shifts) or twin "
                 "(twin surrogates); with --evidence."),
]


def _parse_window(text: str) -> tuple[float, float]:
    start_text, sep, stop_text = text.partition(":")
    try:
        if not sep:
            raise ValueError
        start, stop = float(start_text), float(stop_text)
    except ValueError:
        raise ParameterError(
            f"--window must be START:STOP in seconds (e.g. 1.0:5.0), got {text!r}"
        ) from None
    if not start < stop:
        raise ParameterError(f"--window: START must be less than STOP, got {text!r}")
    return start, stop


def _window_request(phase: str | None, window: str | None
                    ) -> tuple[bool, tuple[float, float] | None]:
    """``--phase``/``--window`` checked before the trace is read: ``(whole, bounds)``."""
    if phase is not None and window is not None:
        raise ParameterError("give --phase or --window, not both")
    whole = window is not None and window.strip().lower() == "all"
    return whole, None if window is None or whole else _parse_window(window)


def _chosen_windows(recording: Any, trace: Path, phase: str | None, whole: bool,
                    bounds: tuple[float, float] | None) -> list[Any]:
    """The windows asked for: ``--window all`` one window where every signal has a value,
    ``--phase``/``--window START:STOP`` that one, neither every phase of a move (for a
    recording of several axes, whose phases are each axis's own, the whole recording)."""
    if recording.axes:
        if phase is not None:
            _one_axis_for_phases(recording, trace)
        if bounds is None:
            return [_select_window(recording, None, None, trace)]
    if whole:
        return [_select_window(recording, None, None, trace)]
    if phase is None and bounds is None:
        return _moving_phases(recording, trace)
    return [_select_window(recording, phase, bounds, trace)]


def _network_overrides(given: dict[str, Any], normalize: str | None,
                       keep_degenerate: bool) -> dict[str, Any]:
    """The network options given on the command line, as NetworkParameters overrides."""
    overrides = {k: v for k, v in given.items() if v is not None}
    if normalize is not None:
        overrides["normalize"] = None if normalize.lower() == "none" else normalize
    if keep_degenerate:
        overrides["degenerate"] = "keep"
    return overrides


def _select_window(
    recording: Any, phase: str | None, bounds: tuple[float, float] | None, trace: Path
) -> Any:
    """The analysis window the options ask for (default: the whole recording)."""
    from funcnet.robot import span_window

    if bounds is not None:
        return span_window(*bounds)
    if phase is None:
        return _whole_recording(recording, trace)
    windows = _phase_windows(recording)
    by_label = [w for w in windows if w.label == phase]
    by_phase = by_label or [w for w in windows if w.phase == phase]
    if len(by_phase) == 1:
        return by_phase[0]
    if not by_phase:
        labels = ", ".join(repr(w.label) for w in windows) or "none"
        raise WindowError(
            f"{trace}: no phase {phase!r} detected (phases: {labels}; --list-phases shows them)"
        )
    choices = ", ".join(f"{w.label!r} ({w.start:g}-{w.stop:g} s)" for w in by_phase)
    raise WindowError(
        f"{trace}: phase {phase!r} occurs {len(by_phase)} times; give one of {choices}"
    )


def _whole_recording(recording: Any, trace: Path) -> Any:
    """The span where every signal has a recorded value (funcnet.robot.complete_span)."""
    from funcnet.robot import complete_span

    try:
        return complete_span(recording)
    except WindowError:
        raise WindowError(f"{trace}: no tick where every signal has a recorded value") from None


def _phase_windows(recording: Any) -> list[Any]:
    """Every detected phase as a window, standstill included (as detect_phases returns it)."""
    from funcnet.robot import PHASES, detect_phases, phase_windows

    return list(phase_windows(detect_phases(recording), include=PHASES))


def _one_axis_for_phases(recording: Any, trace: Path) -> None:
    """Phases are those of one axis: asking for them on a recording of several is an error."""
    if recording.axes:
        axes = recording.axes
        raise WindowError(
            f"{trace}: holds axes {axes[0]}-{axes[-1]}; the phases are each axis's own: "
            f"give --axis N (one of {', '.join(map(str, axes))}), or --window"
        )


def _print_phases(recording: Any, trace: Path) -> None:
    """The detected phases as plain text: label, phase, start, stop (seconds)."""
    import pandas as pd

    _one_axis_for_phases(recording, trace)

    table = pd.DataFrame(
        [(w.label, w.phase, w.start, w.stop) for w in _phase_windows(recording)],
        columns=["label", "phase", "start", "stop"],
    )
    typer.echo(table.to_string(index=False, float_format=lambda value: f"{value:.6g}"))



def _write_network(net: Any, output: Path, inches: tuple[float, float], trace: Path) -> None:
    suffix = output.suffix.lower()
    if suffix in (".json", ".graphml"):
        net.write(output)
        return
    if suffix == ".csv":  # the pairs table, every column (the evidence's too)
        from funcnet._io import write_text_atomic

        write_text_atomic(output, net.pairs.to_csv(index=False))
        return
    import matplotlib

    matplotlib.use("Agg")
    from funcnet.plot import network_title, save_network

    save_network(net, output, size=inches, title=network_title(net, source=str(trace)))


def _parse_size(text: str) -> tuple[float, float]:
    """``--size WxH`` in pixels -> inches at 100 dpi."""
    width, sep, height = text.lower().partition("x")
    try:
        if not sep:
            raise ValueError
        w, h = int(width), int(height)
    except ValueError:
        raise ParameterError(f"--size must be WIDTHxHEIGHT in pixels (e.g. 900x900), got "
                             f"{text!r}") from None
    if not (100 <= w <= 10_000 and 100 <= h <= 10_000):
        raise ParameterError(f"--size: each side must be 100 to 10000 pixels, got {text!r}")
    return w / 100, h / 100


def _signal_list(text: str | None) -> list[str] | None:
    """``--signals A,B,C`` as a list; a name given twice is an error naming the flag."""
    if text is None:
        return None
    names = [s.strip() for s in text.split(",") if s.strip()]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ParameterError(f"--signals names {', '.join(twice)} more than once")
    if not names:
        raise ParameterError("--signals is empty")
    return names


def _check_signals(names: list[str] | None, recording: Any, trace: Path) -> None:
    """Every --signals name is a column; else one line naming what the trace has and what
    can be derived from it."""
    if names is None:
        return
    from funcnet.robot.preprocess import DERIVED_SIGNALS

    columns = list(recording.data.columns)
    missing = [n for n in names if n not in columns]
    if not missing:
        return
    derivable = [f"{name} ({description})" for name, (inputs, description)
                 in DERIVED_SIGNALS.items() if name not in columns]
    raise ParameterError(
        f"--signals: {', '.join(missing)} not in {trace.name}; it has {', '.join(columns)}"
        + (f"; derivable: {', '.join(derivable)}" if derivable else "")
    )


# The pairs-table columns shown on a terminal; piped output and -o .json hold them all.
_MAIN_COLUMNS = ("x", "y", "kind", "weight", "c_diff", "t_diff")
_WIDE_COLUMNS = ("c_xy", "c_yx", "t_xy", "t_yx", "eps_ordered", "rate_exceeded")
_FLAG_COLUMN = "degenerate"
# With --evidence, the terminal also shows the coupling test's p-value and each pair's reading.
_EVIDENCE_SHOWN = ("coupling_p", "evidence")
_PAIRS_CAPTION = (
    "negative diff reads as x->y (an asymmetry, not proof of a driver); degenerate pairs are "
    "{degenerate}; -o net.json keeps every column"
)
_DEGENERATE_CAPTION = {"drop": "no edges", "keep": "flagged edges"}
_EVIDENCE_CAPTION = (
    "coupling_p: the coupling test's adjusted p-value (it cannot be below 1/(surrogates+1)); "
    "untestable = the test could not have rejected whatever the data (few surrogates: not "
    "uncoupled, evidence_reason says why); asymmetry-only = a tested arrow without coupling "
    "evidence"
)


def _is_terminal(stream: Any) -> bool:
    return bool(getattr(stream, "isatty", lambda: False)())


def _shown_columns(narrow: bool, evidence: bool = False) -> list[str]:
    """The columns of a terminal's table (all names of funcnet.network.schema's pairs, and
    with ``evidence`` two of its evidence columns)."""
    groups = (_MAIN_COLUMNS, () if narrow else _WIDE_COLUMNS, (_FLAG_COLUMN,),
              _EVIDENCE_SHOWN if evidence else ())
    return [name for group in groups for name in group]


def _pairs_table(net: Any, columns: Sequence[str], number_format: str) -> Any:
    from rich.table import Table

    pairs = net.pairs
    caption = _PAIRS_CAPTION.format(degenerate=_DEGENERATE_CAPTION[net.parameters.degenerate])
    if "evidence" in pairs.columns:
        caption += "; " + _EVIDENCE_CAPTION
    table = Table(title=net.label, caption=caption)
    for column in columns:
        numeric = pairs[column].dtype.kind == "f"
        table.add_column(column, justify="right" if numeric else "left", no_wrap=True)
    for row in pairs[list(columns)].itertuples(index=False):
        table.add_row(*(format(v, number_format) if isinstance(v, float) else str(v) for v in row))
    return table


def _print_pairs(net: Any) -> None:
    """The pairs table: a rich table on a terminal, every column as plain text otherwise.

    A terminal too narrow for the main columns gets fewer of them, at 3 significant digits,
    rather than every number cut short. The ``degenerate`` flag is always shown.
    """
    from funcnet.network.schema import EVIDENCE_COLUMNS, PAIR_COLUMNS

    evidence = "evidence" in net.pairs.columns
    if not _is_terminal(sys.stdout):
        columns = [*PAIR_COLUMNS, *(EVIDENCE_COLUMNS if evidence else ())]
        typer.echo(net.pairs.loc[:, columns].to_string(index=False))
        return
    from rich.console import Console

    console = Console()
    table = _pairs_table(net, _shown_columns(narrow=False, evidence=evidence), ".4f")
    # Measured without the terminal's limit: the width the table needs to show every number.
    if console.measure(table, options=console.options.update_width(10_000)).maximum > console.width:
        table = _pairs_table(net, _shown_columns(narrow=True, evidence=evidence), ".3g")
    console.print(table)


#: Above either, one network is refused unless --force (issue 9: a forecast, not a promise).
COST_LIMIT_SECONDS = 60.0
COST_LIMIT_BYTES = 4 * 2**30


def _moving_phases(recording: Any, trace: Path) -> list[Any]:
    """The windows of ``funcnet network TRACE`` without --window/--phase: every phase of a
    move; one line saying how to give a window when none can be detected."""
    from funcnet.errors import FuncnetError
    from funcnet.robot import detect_phases, phase_windows

    try:
        windows = list(phase_windows(detect_phases(recording)))
    except FuncnetError as exc:
        raise WindowError(f"{trace}: no phases can be detected ({exc}); give --window "
                          "START:STOP in seconds") from None
    if not windows:
        raise WindowError(f"{trace}: the set-point never moves, so there is no phase of a "
                          "move; give --window START:STOP in seconds")
    return windows


def _check_cost(recording: Any, windows: Sequence[Any], names: Sequence[str] | None,
                parameters: Any, force: bool) -> None:
    """Refuse, before computing, a network forecast over a minute or 4 GiB (unless --force)."""
    from funcnet.recurrence import estimate_cost
    from funcnet.robot import paper_nodes

    if force:
        return
    nodes = len(names) if names is not None else len(paper_nodes(recording.data.columns))
    dt = recording.sample_period
    for window in windows:
        n_samples = int(round((window.stop - window.start) / dt))
        if nodes < 2 or n_samples < 2:
            continue
        try:
            cost = estimate_cost(n_samples, nodes, parameters)
        except ParameterError:
            continue  # too short for the embedding: window_networks says so, naming it
        if cost.seconds > COST_LIMIT_SECONDS or cost.bytes > COST_LIMIT_BYTES:
            raise ParameterError(
                f"window {window.label!r} ({n_samples} samples, {nodes} signals): {cost}; "
                "over a minute or 4 GiB: choose a shorter --window or --phase, or add --force"
            )


def _network_files(output: Path, labels: Sequence[str]) -> list[Path]:
    """-o for one network is the file; for several, one file per window named after it."""
    if len(labels) == 1:
        return [output]
    slugs = ["-".join("".join(c if c.isalnum() else " " for c in str(label)).split())
             for label in labels]
    return [output.with_name(f"{output.stem}-{slug}{output.suffix}") for slug in slugs]


def _evidence_settings(evidence: bool, surrogates: int | None, alpha: float, seed: int,
                       resamples: int, edge_rule: str,
                       surrogate_method: str) -> dict[str, Any] | None:
    """The evidence keywords of :func:`funcnet.functional_network`, checked and spelled as the
    command's flags; ``None`` without ``--evidence``."""
    from funcnet.evidence import EDGE_RULES, check_evidence_arguments

    if edge_rule not in EDGE_RULES:
        raise ParameterError(f"--edge-rule must be one of {', '.join(EDGE_RULES)}, got "
                             f"{edge_rule!r}")
    if not evidence:
        if edge_rule == "interval":
            raise ParameterError("--edge-rule interval needs --evidence (it reads the "
                                 "intervals of the evidence)")
        return None
    if edge_rule == "interval" and resamples == 0:
        raise ParameterError("--edge-rule interval needs intervals: --resamples must be >= 1")
    try:
        check_evidence_arguments(surrogates, alpha, resamples, surrogate_method)
    except ParameterError as exc:
        flag = "--" + str(exc.parameter or "evidence").replace("_", "-")
        raise ParameterError(exc.spelled(flag), parameter=flag, detail=exc.detail) from None
    return {"surrogates": surrogates, "alpha": alpha, "seed": seed, "resamples": resamples,
            "edge_rule": edge_rule, "surrogate_method": surrogate_method}
