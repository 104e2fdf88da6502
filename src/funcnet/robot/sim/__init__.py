"""A simulated robot base axis: the axis model, plans of experiments and the trace writer.

It stands in for the paper's machine and gives ground truth: :mod:`~funcnet.robot.sim.trial`
(one motion, :class:`Trial`), :mod:`~funcnet.robot.sim.axis` (the drivetrain and control
cascade, :func:`simulate_trial`), :mod:`~funcnet.robot.sim.plan` (the paper's Table 1 and TOML
plans, :func:`write_plan`) and :mod:`~funcnet.robot.sim.writer` (SINUMERIK trace XML,
:func:`write_trace`). The names are imported lazily: ``import funcnet.robot.sim`` does not
compile the kernel.

Examples
--------
>>> from funcnet.robot.sim import Trial
>>> Trial("quick", "main", speed=350, tcp=1.2, step=1).step
1.0
"""

from __future__ import annotations

from funcnet._lazy import attach

_EXPORTS = {
    "Trial": "funcnet.robot.sim.trial",
    "FAULT_KNOBS": "funcnet.robot.sim.trial",
    "AxisParameters": "funcnet.robot.sim.axis",
    "SimulatedTrial": "funcnet.robot.sim.axis",
    "simulate_trial": "funcnet.robot.sim.axis",
    "setpoint_profile": "funcnet.robot.sim.axis",
    "effective_parameters": "funcnet.robot.sim.axis",
    "trial_duration": "funcnet.robot.sim.axis",
    "MAX_TRIAL_DURATION": "funcnet.robot.sim.axis",
    "paper_plan": "funcnet.robot.sim.plan",
    "read_plan": "funcnet.robot.sim.plan",
    "write_plan": "funcnet.robot.sim.plan",
    "MANIFEST_COLUMNS": "funcnet.robot.sim.plan",
    "OPTIONAL_MANIFEST_COLUMNS": "funcnet.robot.sim.plan",
    "real_axis_parameters": "funcnet.robot.sim.axis",
    "backlash_sweep_plan": "funcnet.robot.sim.plan",
    "continuous_sweep_plan": "funcnet.robot.sim.plan",
    "named_plan": "funcnet.robot.sim.plan",
    "NAMED_PLANS": "funcnet.robot.sim.plan",
    "ARCMIN": "funcnet.robot.sim.plan",
    "write_trace": "funcnet.robot.sim.writer",
    "role_names": "funcnet.robot.sim.writer",
}

__getattr__, __dir__, __all__ = attach(__name__, _EXPORTS)
