"""Type stub of funcnet.sim: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.sim.axis import (
    MAX_TRIAL_DURATION as MAX_TRIAL_DURATION,
    AxisParameters as AxisParameters,
    SimulatedTrial as SimulatedTrial,
    effective_parameters as effective_parameters,
    real_axis_parameters as real_axis_parameters,
    setpoint_profile as setpoint_profile,
    simulate_trial as simulate_trial,
    trial_duration as trial_duration,
)
from funcnet.sim.plan import (
    ARCMIN as ARCMIN,
    MANIFEST_COLUMNS as MANIFEST_COLUMNS,
    NAMED_PLANS as NAMED_PLANS,
    OPTIONAL_MANIFEST_COLUMNS as OPTIONAL_MANIFEST_COLUMNS,
    backlash_sweep_plan as backlash_sweep_plan,
    continuous_sweep_plan as continuous_sweep_plan,
    named_plan as named_plan,
    paper_plan as paper_plan,
    read_plan as read_plan,
    write_plan as write_plan,
)
from funcnet.sim.trial import FAULT_KNOBS as FAULT_KNOBS, Trial as Trial
from funcnet.sim.writer import role_names as role_names, write_trace as write_trace

__all__: list[str]
