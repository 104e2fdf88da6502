"""Which program a run is a run of: its set-point path, without its timing.

A program's signature is, per axis, the positions at which its set-point turns (the
:func:`funcnet.robot.direction_changes` of each segment, :func:`funcnet.inspection.motion.
segment_phases`), those within :data:`PROGRAM_TOLERANCE` of each other counted once: the path's
ends, whatever its speed (a program run at 90 % of its speed is the same program), however many
cycles the recording holds and wherever in a cycle it starts. An axis that never turns is
signed by its first and last set-point. Two runs are of one program when every axis has as many
turning positions and each lies within the tolerance of the other's (:func:`same_program`).

Examples
--------
>>> a = [[45.79, 124.94], [-174.95, -122.37]]
>>> same_program(a, [[45.77, 124.93], [-174.96, -122.37]]), same_program(a, [[45.7, 72.5]])
(True, False)
>>> program_name(a)
'P-41a9f6e4'
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence

import numpy as np

from funcnet.inspection.motion import segment_phases
from funcnet.robot.recording import Recording

__all__ = ["PROGRAM_TOLERANCE", "program_signature", "same_program", "program_name"]

#: deg: turning positions closer than this are one; two runs' must agree within it.
PROGRAM_TOLERANCE = 0.1


def _clusters(values: Sequence[float], tolerance: float) -> list[float]:
    """Sorted values, those within ``tolerance`` of their neighbour merged into their mean."""
    groups: list[list[float]] = []
    for v in sorted(values):
        if groups and v - groups[-1][-1] <= tolerance:
            groups[-1].append(v)
        else:
            groups.append([v])
    return [round(float(np.mean(g)), 3) for g in groups]


def program_signature(recording: Recording, *, tolerance: float = PROGRAM_TOLERANCE
                      ) -> list[list[float]]:
    """Per axis (in axis order), the set-point's distinct turning positions (module notes).

    Parameters
    ----------
    recording : Recording
        One axis or several, positions in degrees (:func:`funcnet.robot.units.in_degrees`).
    tolerance : float
        deg.

    Returns
    -------
    list of list of float
    """
    records = ([recording.for_axis(a) for a in recording.axes] if recording.axes
               else [recording])
    signature = []
    for rec in records:
        rp = rec.data["RP"].to_numpy(dtype=np.float64)
        times = rec.data.index.to_numpy(dtype=np.float64)
        _, turns = segment_phases(rec)
        at = np.clip(np.searchsorted(times, [t.time for t in turns]), 0, len(rp) - 1)
        positions = rp[at] if len(turns) else rp[np.isfinite(rp)][[0, -1]]
        signature.append(_clusters([float(p) for p in positions], tolerance))
    return signature


def same_program(a: Sequence[Sequence[float]], b: Sequence[Sequence[float]], *,
                 tolerance: float = PROGRAM_TOLERANCE) -> bool:
    """Whether two signatures are of one program (module notes)."""
    if len(a) != len(b):
        return False
    return all(len(x) == len(y) and all(abs(p - q) <= tolerance for p, q in zip(x, y,
                                                                                strict=True))
               for x, y in zip(a, b, strict=True))


def program_name(signature: Sequence[Sequence[float]]) -> str:
    """A short stable name of a program: ``P-`` and a hash of its signature to 0.1 deg."""
    rounded = [[round(p, 1) + 0.0 for p in axis] for axis in signature]
    return "P-" + hashlib.sha256(json.dumps(rounded).encode()).hexdigest()[:8]
