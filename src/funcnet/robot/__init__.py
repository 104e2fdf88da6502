"""Robot-axis controller traces: reading, preprocessing, phases, windows and a simulated axis."""

from __future__ import annotations

from importlib import import_module
from typing import Any

_EXPORTS = {
    "Recording": "funcnet.robot.recording",
    "read_trace": "funcnet.robot.recording",
    "SignalInfo": "funcnet.robot.channels",
    "ChannelMap": "funcnet.robot.channels",
    "DEFAULT_CHANNEL_MAP": "funcnet.robot.channels",
    "velocity": "funcnet.robot.preprocess",
    "add_derived_signals": "funcnet.robot.preprocess",
    "trim": "funcnet.robot.preprocess",
    "resample": "funcnet.robot.preprocess",
    "PHASES": "funcnet.robot.phases",
    "detect_phases": "funcnet.robot.phases",
    "phase_table": "funcnet.robot.phases",
    "PAPER_NODES": "funcnet.robot.windows",
    "Window": "funcnet.robot.windows",
    "phase_windows": "funcnet.robot.windows",
    "fixed_windows": "funcnet.robot.windows",
    "reversal_windows": "funcnet.robot.windows",
    "sliding_windows": "funcnet.robot.windows",
    "span_window": "funcnet.robot.windows",
    "phase_networks": "funcnet.robot.windows",
    "AxisParameters": "funcnet.robot.simulate",
    "SimulatedTrial": "funcnet.robot.simulate",
    "simulate_trial": "funcnet.robot.simulate",
    "write_trace": "funcnet.robot.writer",
    "Trial": "funcnet.robot.plan",
    "paper_plan": "funcnet.robot.plan",
    "read_plan": "funcnet.robot.plan",
    "write_plan": "funcnet.robot.plan",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'funcnet.robot' has no attribute {name!r}") from None
    value = getattr(import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
