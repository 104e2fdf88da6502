"""Simulated histories of one axis: many healthy runs of one program, then its backlash growing.

Every run is the simulated axis (:func:`funcnet.sim.simulate_trial`) moving 8 deg out and back
(long enough to reach the programmed speed), one run a day, 0.4 s logged after it arrives. From
day to day a healthy machine varies: its friction and its gear's stiffness (scales drawn around 1
with :class:`Nuisance`'s relative spreads), and the program's speed (the override an operator
sets). The healthy backlash is 0.5 arcmin; worn runs follow with their own (by default 0.57, 1.5
and 3 arcmin). Each run is written as the controller would write it, a SINUMERIK trace whose
``startTime`` is its day (:func:`funcnet.sim.write_trace`), so that a history is read exactly as
real runs are (``funcnet track add``).

Examples
--------
>>> [round(b, 2) for _, b in history_trials(0, healthy=2)]
[0.5, 0.5, 0.57, 1.5, 3.0]
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import dataclass
from datetime import UTC, datetime, timedelta
from pathlib import Path

import numpy as np

from funcnet.robot.recording import Recording
from funcnet.sim.plan import ARCMIN
from funcnet.sim.trial import Trial

__all__ = ["HEALTHY_ARCMIN", "WORN_ARCMIN", "Nuisance", "history_trials", "write_history",
           "history_recordings"]

#: arcmin, the healthy axis's backlash.
HEALTHY_ARCMIN = 0.5
#: arcmin, the worn runs' backlash, in order.
WORN_ARCMIN = (0.57, 1.5, 3.0)
#: s logged after the set-point arrives (the axis's default 1.5 s only makes the trace longer).
SETTLE = 0.4
#: The first run's day.
FIRST_DAY = datetime(2026, 1, 5, 8, 0, tzinfo=UTC)


@dataclass(frozen=True)
class Nuisance:
    """Relative spreads (standard deviations) of the day-to-day variation of a healthy axis."""

    friction: float = 0.05
    stiffness: float = 0.05
    speed: float = 0.03


def history_trials(seed: int, *, healthy: int = 24, worn: tuple[float, ...] = WORN_ARCMIN,
                   nuisance: Nuisance = Nuisance(), speed: float = 350.0
                   ) -> list[tuple[Trial, float]]:
    """The runs of one history: ``(trial, backlash in arcmin)``, in order (module notes)."""
    rng = np.random.default_rng(seed)
    backlash = [HEALTHY_ARCMIN] * healthy + list(worn)
    out = []
    for day, width in enumerate(backlash):
        friction, stiffness, override = 1.0 + rng.normal(0.0, [nuisance.friction,
                                                              nuisance.stiffness,
                                                              nuisance.speed])
        trial = Trial(f"s{seed}-day{day:03d}", "track", speed=speed * max(override, 0.5),
                      tcp=1.2, step=8.0, reverse=True, backlash=width * ARCMIN,
                      friction_scale=max(friction, 0.1), stiffness_scale=max(stiffness, 0.1),
                      seed=int(rng.integers(2**31)))
        out.append((trial, width))
    return out


def write_history(folder: str | os.PathLike[str], seed: int, **options: object) -> list[Path]:
    """Simulate a history and write one trace per run into ``folder``; their paths, in order.

    ``options`` are :func:`history_trials`'s.
    """
    from funcnet.sim import AxisParameters, simulate_trial, write_trace

    paths = []
    for day, (trial, _) in enumerate(history_trials(seed, **options)):  # type: ignore[arg-type]
        sim = simulate_trial(trial, AxisParameters(settle_time=SETTLE), seed=seed)
        start = (FIRST_DAY + timedelta(days=day)).isoformat()
        paths.append(write_trace(Path(folder) / f"{trial.name}.xml", sim.data.round(6),
                                 start_time=start))
    return paths


def history_recordings(seed: int, **options: object) -> Iterator[Recording]:
    """The runs of a history as recordings, without files (``options``: :func:`history_trials`'s).
    """
    from funcnet.sim import AxisParameters, simulate_trial
    from funcnet.validation.sweep import simulated_recording

    for trial, _ in history_trials(seed, **options):  # type: ignore[arg-type]
        yield simulated_recording(simulate_trial(trial, AxisParameters(settle_time=SETTLE),
                                                 seed=seed))
