"""A simulated robot base axis: the axis model, plans of experiments and the trace writer.

It stands in for the paper's machine and gives ground truth: :mod:`~funcnet.sim.trial`
(one motion, :class:`Trial`), :mod:`~funcnet.sim.axis` (the drivetrain and control
cascade, :func:`simulate_trial`), :mod:`~funcnet.sim.plan` (the paper's Table 1 and TOML
plans, :func:`write_plan`) and :mod:`~funcnet.sim.writer` (SINUMERIK trace XML,
:func:`write_trace`). The names are imported lazily: ``import funcnet.sim`` does not
compile the kernel.

Examples
--------
>>> from funcnet.sim import Trial
>>> Trial("quick", "main", speed=350, tcp=1.2, step=1).step
1.0
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "Trial": "funcnet.sim.trial",
    "FAULT_KNOBS": "funcnet.sim.trial",
    "AxisParameters": "funcnet.sim.axis",
    "SimulatedTrial": "funcnet.sim.axis",
    "simulate_trial": "funcnet.sim.axis",
    "setpoint_profile": "funcnet.sim.axis",
    "effective_parameters": "funcnet.sim.axis",
    "trial_duration": "funcnet.sim.axis",
    "MAX_TRIAL_DURATION": "funcnet.sim.axis",
    "paper_plan": "funcnet.sim.plan",
    "read_plan": "funcnet.sim.plan",
    "write_plan": "funcnet.sim.plan",
    "MANIFEST_COLUMNS": "funcnet.sim.plan",
    "OPTIONAL_MANIFEST_COLUMNS": "funcnet.sim.plan",
    "real_axis_parameters": "funcnet.sim.axis",
    "backlash_sweep_plan": "funcnet.sim.plan",
    "continuous_sweep_plan": "funcnet.sim.plan",
    "named_plan": "funcnet.sim.plan",
    "NAMED_PLANS": "funcnet.sim.plan",
    "ARCMIN": "funcnet.sim.plan",
    "write_trace": "funcnet.sim.writer",
    "role_names": "funcnet.sim.writer",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
