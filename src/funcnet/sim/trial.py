"""One trial of the simulated axis: its motion and optional fault knobs.

:class:`Trial` is what the axis model (:mod:`funcnet.sim.axis`) simulates and what a plan
(:mod:`funcnet.sim.plan`) lists; it lives apart from both so that neither imports the
other's module for it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from funcnet.errors import ParameterError

__all__ = ["Trial", "FAULT_KNOBS", "NAME_PATTERN", "OPTIONS"]

#: Fields of :class:`~funcnet.sim.axis.AxisParameters` a :class:`Trial` may override.
FAULT_KNOBS = ("backlash", "friction_scale", "stiffness_scale", "noise_scale", "arm_load")

#: Worded options of a :class:`Trial` and their words (the first is what None means): the
#: sensors and logging (``"paper"``: the default :class:`~funcnet.sim.axis.AxisParameters`;
#: ``"real"``: :func:`~funcnet.sim.axis.real_axis_parameters`), the arm model and the
#: encoder the position loop reads, and the set-point's profile (``"step"``: a jerk-limited step
#: and back if ``reverse``; ``"smooth"``: out and back twice along ``(1 - cos) / 2`` curves, three
#: direction changes without a rest, as a robot's smooth trajectories).
OPTIONS = {
    "sensors": ("paper", "real"),
    "arm_model": ("rigid", "elastic"),
    "position_feedback": ("arm", "motor"),
    "profile": ("step", "smooth"),
}

#: A trial's or a plan group's name: safe as a file name.
NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9._-]*")


@dataclass(frozen=True)
class Trial:
    """One motion of the simulated axis.

    Parameters
    ----------
    name : str
        Unique within a plan; the trace's file name without ``.xml`` (letters, digits, ``.``,
        ``_``, ``-``).
    group : str
        The experiment group, e.g. ``"main"``, ``"static-friction"``, ``"backlash"``.
    speed : float
        Programmed joint speed in deg/min (> 0).
    tcp : float
        TCP distance from the axis in m (> 0); sets the arm inertia.
    step : float
        Step size in deg (non-zero; the sign is the direction of the forward move).
    reverse : bool
        Whether the axis returns to its start right after the forward move (same trace).
    backlash, friction_scale, stiffness_scale, noise_scale, arm_load : float or None
        Fault knobs overriding :class:`~funcnet.sim.axis.AxisParameters` (None keeps
        the axis's value; ``arm_load`` is a gravity load on the arm, N m).
    sensors, arm_model, position_feedback, profile : str or None
        Options (:data:`OPTIONS`); None keeps the axis's own.
    seed : int or None
        The trial's own noise seed (a plan group's ``seeds``); None: the plan's seed.

    Examples
    --------
    >>> Trial("main-v35-p16-s3", "main", speed=35, tcp=1.6, step=3).reverse
    False
    """

    name: str
    group: str
    speed: float
    tcp: float
    step: float
    reverse: bool = False
    backlash: float | None = None
    friction_scale: float | None = None
    stiffness_scale: float | None = None
    noise_scale: float | None = None
    sensors: str | None = None
    arm_model: str | None = None
    position_feedback: str | None = None
    seed: int | None = None
    arm_load: float | None = None
    profile: str | None = None

    def __post_init__(self) -> None:
        for option, words in OPTIONS.items():
            value = getattr(self, option)
            if value is not None and value not in words:
                raise ParameterError(
                    f"Trial {self.name}: {option} must be one of {words}: {value!r}"
                )
        if self.seed is not None and (
            isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0
        ):
            raise ParameterError(f"Trial {self.name}: seed must be an integer >= 0: {self.seed!r}")
        if not isinstance(self.name, str) or not NAME_PATTERN.fullmatch(self.name):
            raise ParameterError(f"Trial.name must be a file-name-safe string: {self.name!r}")
        for key in ("speed", "tcp", "step"):
            value = getattr(self, key)
            if (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not math.isfinite(value)
            ):
                raise ParameterError(f"Trial {self.name}: {key} must be a finite number: {value!r}")
            object.__setattr__(self, key, float(value))  # 35 and 35.0: one trial, one fingerprint
        if self.speed <= 0 or self.tcp <= 0 or self.step == 0:
            raise ParameterError(
                f"Trial {self.name}: speed and tcp must be positive and step non-zero "
                f"(speed={self.speed}, tcp={self.tcp}, step={self.step})"
            )
        if not isinstance(self.reverse, bool):
            raise ParameterError(f"Trial {self.name}: reverse must be a bool: {self.reverse!r}")
        for knob in FAULT_KNOBS:
            value = getattr(self, knob)
            if value is not None and (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not math.isfinite(value)
                or value < 0
                or (value == 0 and knob not in ("backlash", "noise_scale", "arm_load"))
            ):
                raise ParameterError(f"Trial {self.name}: {knob} out of range: {value!r}")
            if value is not None:
                object.__setattr__(self, knob, float(value))
