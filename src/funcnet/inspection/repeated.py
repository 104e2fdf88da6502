"""The repetitions of an inspection: one motion repeated in a trace or across traces, per phase.

:func:`inspect_repetitions` finds the repetitions of the most repeated motion in the inspected
recordings (:func:`funcnet.robot.find_repetitions`) and reads every pair per phase with the
repetition test (:func:`funcnet.repetition_evidence`): coupling beyond the command, which one
short window cannot test (docs/validation/evidence.md, sections 5 and 7). With too few repetitions
it says how many a decision needs.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import pandas as pd

from funcnet.errors import FuncnetError
from funcnet.evidence.repetitions import repetition_evidence, repetitions_needed
from funcnet.parameters import EvidenceSettings, NetworkParameters
from funcnet.robot import Recording, find_repetitions

if TYPE_CHECKING:
    from funcnet.inspection.trace import TraceInspection

__all__ = ["RepeatedInspection", "inspect_repetitions", "repetitions_of"]


@dataclass(frozen=True)
class RepeatedInspection:
    """What the repetitions of the inspected recordings say, per phase.

    Attributes
    ----------
    moves : pandas.DataFrame
        The repetitions (:attr:`funcnet.robot.Repetitions.moves`); empty when none was found.
    evidence : dict of str to pandas.DataFrame
        Phase label -> :func:`funcnet.repetition_evidence`'s table.
    failures : dict of str to str
        Phase label -> why it has no table.
    message : str
        One sentence: how many repetitions, and how many a decision needs.
    """

    moves: pd.DataFrame
    evidence: dict[str, pd.DataFrame] = field(repr=False)
    failures: dict[str, str]
    message: str


def inspect_repetitions(recordings: Sequence[Recording], signals: Sequence[str], *,
                        parameters: NetworkParameters | None = None, alpha: float = 0.05,
                        seed: int = 0, mirror: bool = False) -> RepeatedInspection:
    """The repetition evidence per phase of the most repeated motion in ``recordings``.

    Parameters
    ----------
    recordings : sequence of Recording
        The inspected recordings (one sample period).
    signals : sequence of str
        The nodes; those every recording has are used.
    parameters : NetworkParameters, optional
    alpha, seed
        As :func:`funcnet.repetition_evidence`.
    mirror : bool
        Count mirrored moves (:func:`funcnet.robot.find_repetitions`).

    Returns
    -------
    RepeatedInspection
        A phase whose test fails (e.g. too short for the embedding) is in ``failures``; no
        repetition at all gives empty tables and the message says so.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import SignalInfo
    >>> t = np.arange(0, 4, 0.01)
    >>> u = np.clip((t - 0.5) / 2, 0, 1)
    >>> data = pd.DataFrame({"RP": u - np.sin(2 * np.pi * u) / (2 * np.pi), "AC": np.sin(t)},
    ...                     index=pd.Index(t.round(9), name="time"))
    >>> rec = Recording(data, {}, {c: SignalInfo(c, None, None, 0.01) for c in data},
    ...                 sample_period=0.01)
    >>> inspect_repetitions([rec], ["RP", "AC"]).message
    'one repetition of the motion: a decision needs 4 for one pair, 4 for the 1 pairs of 2 nodes'
    """
    items = list(recordings)
    nodes = [s for s in signals if all(s in r.data.columns for r in items)]
    m = len(nodes) * (len(nodes) - 1) // 2
    needed = (f"a decision needs {repetitions_needed(1, alpha)} for one pair, "
              f"{repetitions_needed(m, alpha)} for the {m} pairs of {len(nodes)} nodes")
    try:
        found = find_repetitions(items, signals=nodes, mirror=mirror)
    except FuncnetError as error:
        return RepeatedInspection(pd.DataFrame(), {}, {}, f"no repetitions: {error}")
    why = _left_out_sentence(found.left_out)
    if len(found) < 2:
        return RepeatedInspection(found.moves, {}, {},
                                  f"one repetition of the motion: {needed}{why}")
    tables, failures = {}, {}
    for label, windows in found.windows.items():
        try:
            tables[label] = repetition_evidence(windows, parameters=parameters, alpha=alpha,
                                                seed=seed)
        except FuncnetError as error:
            failures[label] = str(error)
    r = len(found)
    message = (f"{r} repetitions of the motion ({found.others} other move(s) left out); "
               f"{needed}{why}")
    return RepeatedInspection(found.moves, tables, failures, message)


def _left_out_sentence(left_out: Sequence[str], limit: int = 6) -> str:
    """"; not taken: recording 2 move 1: ..." for the moves that are no repetition."""
    if not left_out:
        return ""
    shown = "; ".join(left_out[:limit])
    more = f"; and {len(left_out) - limit} more" if len(left_out) > limit else ""
    return f"; not taken: {shown}{more}"


def repetitions_of(inspections: Sequence[TraceInspection],
                   evidence_options: EvidenceSettings | None = None) -> RepeatedInspection | None:
    """:func:`inspect_repetitions` of inspected traces, with their nodes and parameters.

    Parameters
    ----------
    inspections : sequence of TraceInspection
        The single-axis inspections to read together; the first one's nodes and parameters
        are used.
    evidence_options : EvidenceSettings, optional
        ``alpha`` and ``seed`` are used (default 0.05 and 0).

    Returns
    -------
    RepeatedInspection or None
        None when there is no inspection to read.
    """
    if not inspections:
        return None
    options = evidence_options or EvidenceSettings()
    first = inspections[0]
    return inspect_repetitions([ins.recording for ins in inspections], first.signals,
                               parameters=first.parameters,
                               alpha=float(options.get("alpha", 0.05)),
                               seed=int(options.get("seed", 0)))
