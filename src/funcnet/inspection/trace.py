"""The inspection of one trace: its moves, a functional network per phase of every move with
its evidence, what could not be computed, and the backlash diagnosis.

:func:`inspect_recording` computes; :class:`TraceInspection` holds what it found; the page is
:func:`funcnet.report.inspect.write_inspection`'s.

Defaults chosen for a real trace: the paper's nodes the trace has (``PAPER_NODES``, V derived
from AP), one window per detected phase of every move (standstill is summarized, not
networked: the set-point is constant there), signals sampled coarser than the grid (the 4 ms
IPO positions on the 2 ms servo grid) interpolated so that no node is a staircase
(:func:`funcnet.robot.prepare.prepare_recording`), signals constant in a window left out of that
window, and the evidence columns of :func:`funcnet.pipeline.window_evidence`. A window too short
for its network, or for a part of its evidence, is left out of that part and listed in
:attr:`TraceInspection.failures`: it never stops the inspection. A recording with gaps (missing
values) is read segment by segment (:func:`~funcnet.inspection.motion.segment_phases`): no
phase, move or window spans a gap, and :attr:`TraceInspection.gaps` says where they are.

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 3.3-3.4
   (preprocessing, parameters) and 4 (phases).
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Unpack

import numpy as np
import pandas as pd

from funcnet.errors import ChannelError, FuncnetError, RecordingWarning
from funcnet.inspection.motion import motion_summary, segment_phases, turns_across_gaps
from funcnet.network import FunctionalNetwork
from funcnet.network.edge_evidence import check_evidence_settings
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides, resolve
from funcnet.pipeline import WindowFailure, window_evidence, window_networks, window_warnings
from funcnet.robot import PAPER_NODES, Recording, Window, phase_windows
from funcnet.robot.phases import SetpointTurn
from funcnet.robot.prepare import prepare_recording
from funcnet.robot.preprocess import DERIVED_SIGNALS, staircase_signals

if TYPE_CHECKING:  # the diagnosis loads when it runs
    from funcnet.diagnosis.diagnose import BacklashResult

__all__ = ["TraceInspection", "inspect_recording", "DETRENDED_NODES"]

#: Detrended nodes (``funcnet inspect --detrended``): the positions' ramps replaced by the
#: following error FE = RP - AP and the torsion TORSION = MP - AP, with V and the currents.
#: In cruise the positions are ramps, which time-shift surrogates cannot treat as stationary
#: (docs/validation/evidence.md).
DETRENDED_NODES = ("FE", "TORSION", "V", "RC", "AC")

# Phases summarized, not networked: the set-point is constant there.
_NOT_NETWORKED = ("standstill",)


@dataclass(frozen=True)
class TraceInspection:
    """What :func:`inspect_recording` found in one trace.

    Attributes
    ----------
    source : str
        The trace's file (as given) or ``"<recording>"``.
    duration, sample_period : float
        Seconds.
    gaps : tuple of (float, float)
        The spans ``[start, stop)`` (seconds) where values are missing
        (:attr:`funcnet.robot.Recording.gaps`); () when none.
    segments : tuple of (float, float)
        The spans between the gaps (:attr:`funcnet.robot.Recording.segments`): no phase, move
        or window spans a gap.
    signals : tuple of str
        The nodes of the networks.
    phases : pandas.DataFrame
        :func:`funcnet.robot.detect_phases` of each segment with ``move`` (0 for standstill,
        else the move's number) and ``duration``
        (:func:`~funcnet.inspection.motion.segment_phases`).
    moves : pandas.DataFrame
        :func:`~funcnet.inspection.motion.motion_summary`: one row per move.
    turns : tuple of SetpointTurn
        The set-point's direction changes (:func:`funcnet.robot.direction_changes`), within a
        move (continuous motion) or after a rest.
    windows : tuple of Window
        One per phase of a move, labelled as the networks.
    networks : dict
        Window label -> FunctionalNetwork (with the evidence columns when ``evidence``, but for
        the windows whose evidence failed: see ``failures``).
    failures : tuple of WindowFailure
        The windows without a network (part ``"network"``), without evidence (``"evidence"``)
        or without the asymmetry intervals of their evidence (``"intervals"``), with why, in
        window order (:class:`funcnet.pipeline.WindowFailure`).
    problems : pandas.DataFrame
        The networks' flagged problems, counted: ``problem, windows, of, which, pairs
        (windows)``.
    backlash : BacklashResult or None
        The backlash diagnosis (:func:`funcnet.diagnosis.diagnose_recording`), or None.
    backlash_error : str
        Why there is no diagnosis ("" when there is one).
    parameters : NetworkParameters
    evidence : bool
    resampled : tuple of str
        The signals interpolated onto the grid (they were staircases).
    elapsed : float
        Seconds of computation.
    recording : Recording
        The recording the networks were computed on (interpolated, with V).
    turns_across_gaps : tuple of (float, float)
        The set-point's direction changes across a gap, which no segment holds
        (:func:`~funcnet.inspection.motion.turns_across_gaps`): the end of the move before and
        the start of the next, the other way.
    reversal_residual : ndarray or None
        Per sample of ``recording``, deg: ``MP - AP`` less the gear's wind-up and the encoders'
        skew (:func:`funcnet.diagnosis.reversal_error.unexplained` with the diagnosis's gear
        fit), what the reversal error steps at a direction change in continuous motion; None
        without a gear fit or without both encoders.
    """

    source: str
    duration: float
    sample_period: float
    gaps: tuple[tuple[float, float], ...]
    segments: tuple[tuple[float, float], ...]
    signals: tuple[str, ...]
    phases: pd.DataFrame
    moves: pd.DataFrame
    turns: tuple[SetpointTurn, ...]
    windows: tuple[Window, ...]
    networks: dict[str, FunctionalNetwork]
    failures: tuple[WindowFailure, ...]
    problems: pd.DataFrame
    backlash: BacklashResult | None
    backlash_error: str
    parameters: NetworkParameters
    evidence: bool
    resampled: tuple[str, ...]
    elapsed: float
    recording: Recording = dataclasses.field(repr=False)
    turns_across_gaps: tuple[tuple[float, float], ...] = ()
    reversal_residual: np.ndarray | None = dataclasses.field(default=None, repr=False,
                                                             compare=False)

    def failed(self, part: str) -> dict[str, str]:
        """Window label -> why, for the windows that lack ``part`` (``"network"``,
        ``"evidence"`` or ``"intervals"``)."""
        return {f.window: f.message for f in self.failures if f.part == part}


def _problems(networks: Mapping[str, FunctionalNetwork]) -> pd.DataFrame:
    """The flagged problems of the networks, one row per problem with its windows counted."""
    groups: dict[str, dict[str, Any]] = {}
    for warning in window_warnings(networks):
        key = str(warning.problem)
        entry = groups.setdefault(key, {"windows": [], "pairs": {}})
        entry["windows"].append(str(warning.window))
        for pair in warning.pairs:
            entry["pairs"][pair] = entry["pairs"].get(pair, 0) + 1
    rows = [{"problem": problem, "windows": len(entry["windows"]), "of": len(networks),
             "which": ", ".join(entry["windows"]),
             "pairs (windows)": ", ".join(f"{x}–{y} ({n})" for (x, y), n in
                                          entry["pairs"].items())}
            for problem, entry in groups.items()]
    return pd.DataFrame(rows, columns=["problem", "windows", "of", "which", "pairs (windows)"])


def _derivable(recording: Recording, signals: Sequence[str] | None) -> list[str]:
    """V (the motion's arm-side speed) and the derived nodes asked for, those whose inputs the
    recording has; a node that cannot be derived is left to the networks to name."""
    columns = set(recording.data.columns)
    return [name for name in ("V", *(signals or ()))
            if name not in DERIVED_SIGNALS or set(DERIVED_SIGNALS[name][0]) <= columns]


def _available_nodes(recording: Recording, signals: Sequence[str]) -> list[str]:
    """The nodes asked for, checked before anything is computed: of the detrended nodes
    (:data:`DETRENDED_NODES`) those the recording cannot give are left out, said in one line
    (TORSION needs the motor encoder MP); other nodes are left to the networks to name."""
    columns = set(recording.data.columns)

    def needs(name: str) -> list[str]:
        if name in columns:
            return []
        if name in DERIVED_SIGNALS:
            return [c for c in DERIVED_SIGNALS[name][0] if c not in columns]
        return [name]

    missing = {name: needs(name) for name in signals if needs(name)}
    if not missing or tuple(signals) != DETRENDED_NODES:
        return list(signals)
    said = "; ".join(
        f"{name} ({DERIVED_SIGNALS[name][1]}) needs {', '.join(inputs)}"
        if name in DERIVED_SIGNALS else f"{name} is not a column"
        for name, inputs in missing.items()
    )
    where = recording.source or "<recording>"
    kept = [name for name in signals if name not in missing]
    if len(kept) < 2:
        raise ChannelError(where, f"--detrended: {said}; fewer than two nodes are left")
    warnings.warn(RecordingWarning(
        f"{where}: detrended nodes left out, the recording lacks their inputs: {said}",
        problem="missing_signal", signals=tuple(missing)), stacklevel=3)
    return kept


def inspect_recording(
    recording: Recording,
    *,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    interpolate: bool = True,
    backlash: bool = True,
    progress: Callable[[int, int, str], None] | None = None,
    evidence_options: EvidenceSettings | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> TraceInspection:
    """Summarize a recording's motion and compute a functional network per phase of each move.

    Parameters
    ----------
    recording : Recording
        As :func:`funcnet.robot.read_trace` returns it (with RP; V is derived from AP here).
    signals : sequence of str, optional
        The nodes; default the paper's (RP, AP, MP, V, RC, AC) that the recording has. Derived
        signals named here (FE = RP - AP, TORSION = MP - AP, :data:`DETRENDED_NODES`) are
        computed from the recording.
    parameters : NetworkParameters, optional
        Network parameters (default :class:`~funcnet.NetworkParameters`'s).
    evidence : bool
        Add the evidence columns (coupling test, intervals, direction) to every network.
    interpolate : bool
        Interpolate signals coarser than the grid (staircases) onto it
        (:func:`funcnet.robot.resample` with ``method="interpolate"``) before the networks.
    backlash : bool
        Run :func:`funcnet.diagnosis.diagnose_recording` on the recording as read.
    progress : callable, optional
        ``progress(done, total, description)``.
    evidence_options : mapping, optional
        The evidence keywords of :func:`funcnet.functional_network` (``surrogates``,
        ``alpha``, ``seed``, ``resamples``, ``surrogate_method``, ``edge_rule``); default its
        defaults.
    **overrides
        Network parameters by name (``rr=0.1``).

    Returns
    -------
    TraceInspection

    Raises
    ------
    ParameterError
        A bad network parameter or evidence option (before any window is computed).
    ChannelError
        No RP, or a signal that is not in the recording.

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.robot import SignalInfo
    >>> import warnings
    >>> t = np.arange(0, 3, 0.002)
    >>> rp = 20 * (1 - np.cos(np.pi * np.clip((t - 0.5) / 2, 0, 1)))  # one smooth move
    >>> ap = rp - 0.01 * np.sin(40 * t) * (rp > 0)
    >>> data = pd.DataFrame({"RP": rp, "AP": ap}, index=pd.Index(t, name="time"))
    >>> info = {c: SignalInfo(c, "posn", "double", 0.002) for c in data}
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     found = inspect_recording(Recording(data, {}, info, sample_period=0.002),
    ...                               evidence=False, backlash=False, delay=5)
    >>> found.signals, len(found.moves), list(found.networks)
    (('RP', 'AP', 'V'), 1, ['late spin-up', 'cruise', 'braking'])
    >>> [(f.window, f.part) for f in found.failures]  # 4 samples: too short for a network
    [('early spin-up', 'network')]
    """
    started = time.perf_counter()
    p = resolve(parameters, overrides)
    if evidence:
        check_evidence_settings(**(evidence_options or EvidenceSettings()))
    where = recording.source or "<recording>"
    raw = recording
    if signals is not None:
        signals = _available_nodes(raw, signals)
    _step(progress, 0, 4, "phases")
    phases, turns = segment_phases(raw)  # a recording with gaps: segment by segment
    coarse = tuple(staircase_signals(raw)) if interpolate else ()
    # V always (the motion's speed), FE and TORSION (the detrended nodes) when asked for, from
    # the interpolated positions
    rec = prepare_recording(raw, signals=_derivable(raw, signals),
                            resample="interpolate" if coarse else None)
    if signals is None:
        signals = [s for s in PAPER_NODES if s in rec.data.columns]
    signals = list(signals)
    moves = motion_summary(rec, phases, turns)
    windows = tuple(w for w in phase_windows(phases[["phase", "start", "stop"]])
                    if w.phase not in _NOT_NETWORKED)
    total = 2 + len(windows) * (2 if evidence else 1)
    networks = window_networks(
        rec, windows, signals=signals, parameters=p, constant="drop", errors="collect",
        progress=lambda k, n, label: _step(progress, 1 + k, total, f"network {label}"))
    failures = list(networks.failures)
    if evidence:
        networks = window_evidence(
            rec, networks, windows, errors="collect",
            progress=lambda k, n, label: _step(progress, 1 + len(windows) + k, total,
                                               f"evidence {label}"),
            **(evidence_options or EvidenceSettings()))
        failures += networks.failures
    diagnosis, diagnosis_error = None, ""
    if backlash:
        try:
            from funcnet.diagnosis import diagnose_recording

            diagnosis = diagnose_recording(raw)
        except FuncnetError as error:
            diagnosis_error = str(error)
    _step(progress, total, total, "backlash diagnosis")
    order = {w.label: k for k, w in enumerate(windows)}
    index = rec.data.index
    return TraceInspection(
        source=where,
        duration=round(float(index[-1] - index[0]) + rec.sample_period, 6),
        sample_period=rec.sample_period,
        gaps=raw.gaps,
        segments=tuple(raw.segments),
        signals=tuple(signals),
        phases=phases,
        moves=moves,
        turns=turns,
        windows=windows,
        networks=dict(networks),
        failures=tuple(sorted(failures, key=lambda f: order[f.window])),
        problems=_problems(networks),
        backlash=diagnosis,
        backlash_error=diagnosis_error,
        parameters=p,
        evidence=evidence,
        resampled=coarse,
        elapsed=time.perf_counter() - started,
        recording=rec,
        turns_across_gaps=turns_across_gaps(moves, raw.gaps),
        reversal_residual=_reversal_residual(rec, diagnosis),
    )


def _reversal_residual(rec: Recording, diagnosis: BacklashResult | None) -> np.ndarray | None:
    """What the reversal error steps, on the recording the networks were computed on."""
    if diagnosis is None or diagnosis.gear is None or not {"AP", "MP"} <= set(rec.data.columns):
        return None
    from funcnet.diagnosis.reversal_error import unexplained

    return unexplained(rec, diagnosis.gear)


def _step(progress: Callable[[int, int, str], None] | None, done: int, total: int,
          description: str) -> None:
    if progress is not None:
        progress(done, total, description)
