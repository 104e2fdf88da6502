"""Which windows and signals of a recording the options select, checked against it.

The windows (``--phase``, ``--window``, or every phase of every move), the detected phases
(``--list-phases``), the ``--signals`` the recording has, and the cost forecast that refuses a
network over a minute or 4 GiB unless ``--force``. Errors name the trace and the option.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import typer

from funcnet.errors import ParameterError, WindowError

__all__ = ["COST_LIMIT_BYTES", "COST_LIMIT_SECONDS", "check_cost", "check_signals",
           "chosen_windows", "print_phases"]


def chosen_windows(recording: Any, trace: Path, phase: str | None, whole: bool,
                    bounds: tuple[float, float] | None, *, min_samples: int = 0) -> list[Any]:
    """The windows asked for: ``--window all`` one window where every signal has a value,
    ``--phase``/``--window START:STOP`` that one, neither every phase of a move (for a
    recording of several axes, whose phases are each axis's own, the whole recording).

    Of every phase, those shorter than ``min_samples`` (what the embedding needs) are left
    out, said in one :class:`~funcnet.RecordingWarning` (``problem="short_phase"``)."""
    if recording.axes:
        if phase is not None:
            _one_axis_for_phases(recording, trace)
        if bounds is None:
            return [_select_window(recording, None, None, trace)]
    if whole:
        return [_select_window(recording, None, None, trace)]
    if phase is None and bounds is None:
        return _long_enough(_moving_phases(recording, trace), recording, trace, min_samples)
    return [_select_window(recording, phase, bounds, trace)]


def _long_enough(windows: list[Any], recording: Any, trace: Path, min_samples: int) -> list[Any]:
    """The phase windows the embedding can use; the others named in one warning."""
    import warnings

    from funcnet.errors import RecordingWarning

    dt = recording.sample_period
    length = {w.label: int(round((w.stop - w.start) / dt)) for w in windows}
    short = [w for w in windows if length[w.label] < min_samples]
    if not short:
        return windows
    if len(short) == len(windows):
        raise WindowError(
            f"{trace}: every phase is shorter than the {min_samples} samples the embedding "
            "needs ((dim - 1) * delay + 7); give --window START:STOP, or a smaller --dim or "
            "--delay"
        )
    listed = ", ".join(f"{w.label!r} ({length[w.label]} samples)" for w in short)
    warnings.warn(RecordingWarning(
        f"{trace}: phases shorter than the {min_samples} samples the embedding needs "
        f"((dim - 1) * delay + 7) left out: {listed}", problem="short_phase",
    ), stacklevel=2)
    return [w for w in windows if length[w.label] >= min_samples]


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


def print_phases(recording: Any, trace: Path) -> None:
    """The detected phases as plain text: label, phase, start, stop (seconds)."""
    import pandas as pd

    _one_axis_for_phases(recording, trace)

    table = pd.DataFrame(
        [(w.label, w.phase, w.start, w.stop) for w in _phase_windows(recording)],
        columns=["label", "phase", "start", "stop"],
    )
    typer.echo(table.to_string(index=False, float_format=lambda value: f"{value:.6g}"))



def check_signals(names: list[str] | None, recording: Any, trace: Path) -> None:
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


#: Above either, one network is refused unless --force (a forecast, not a promise).
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


def check_cost(recording: Any, windows: Sequence[Any], names: Sequence[str] | None,
                parameters: Any, force: bool) -> None:
    """Refuse, before computing, a network forecast over a minute or 4 GiB (unless --force)."""
    from funcnet.core.recurrence import estimate_cost
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
