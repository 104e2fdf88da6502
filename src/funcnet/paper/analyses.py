"""The paper's section 4 analyses on a plan of simulated trials, every finding measured.

:func:`run_paper_analyses` reads a plan (:func:`funcnet.sim.write_plan`), cuts each trial
into the paper's windows, computes the networks with :func:`funcnet.pipeline.window_networks`
under one :class:`~funcnet.parameters.NetworkParameters` (:data:`PAPER_PARAMETERS` by default)
and measures the findings (:mod:`funcnet.paper.evaluate`).

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections
   3.3-3.4 and 4 (Fig. 9, 10, 11); section 3.1 (Table 1).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Unpack

import numpy as np
import pandas as pd

from funcnet.errors import FuncnetError, TraceError
from funcnet.paper.claims import BASELINE_PHASES, VELOCITIES, VELOCITY_PHASES, Finding
from funcnet.paper.evaluate import (
    baseline_findings,
    design_effect,
    reversal_findings,
    velocity_findings,
)
from funcnet.parameters import NetworkParameters, ParameterOverrides, resolve
from funcnet.robot.windows import PAPER_NODES

#: Cuts a trial's windows from its recording and phases, keyed as the findings look them up.
Keyed = Callable[[Any, pd.DataFrame], dict[Any, Any]]

__all__ = [
    "PAPER_PARAMETERS",
    "PAPER_SIGNALS",
    "TrialAnalysis",
    "PaperAnalyses",
    "main_move",
    "network_problems",
    "run_paper_analyses",
]

#: Width (s) of the reversal windows, the same default as a study's ``reversal`` windows
#: (``funcnet.study.spec.REVERSAL_WIDTH``; the two packages are siblings, a test keeps them equal).
REVERSAL_WIDTH = 0.2

#: Network parameters of :func:`run_paper_analyses`. The paper states RR = CR = μ = 0.05 and
#: min-max normalization (sections 3.3-3.4) but not m and τ for the robot data; m = 3, τ = 10
#: samples (20 ms at 500 Hz) are its illustration's values (section 2.1), kept here.
PAPER_PARAMETERS = NetworkParameters(dim=3, delay=10, rr=0.05, cr=0.05, mu=0.05,
                                     metric="euclidean", normalize="minmax", measure="both",
                                     rule="funcnet", theiler=0)
#: The paper's nodes (section 4.1).
PAPER_SIGNALS = PAPER_NODES

# What each problem flagged in a pairs table means (funcnet.pipeline.window_warnings' keys).
_PROBLEMS = {
    "eps_order": "eps_xy is not below eps_x and eps_y",
    "rate_exceeded": "ties at a threshold pushed an achieved rate above its target",
    "degenerate": "degenerate recurrence structure (too few distinct states)",
    "staircase": "signals analysed on a finer grid than they change on (staircases)",
}


@dataclass(frozen=True)
class TrialAnalysis:
    """The networks of one trial's windows.

    Attributes
    ----------
    trial : str
        The trial's name (``manifest.csv``).
    path : str
        The trace read.
    data : pandas.DataFrame
        The analysed signals over the whole recording (V derived before windowing).
    phases : pandas.DataFrame
        The detected phases (``phase, start, stop``).
    windows : dict
        Key -> :class:`funcnet.robot.Window` (key: phase name, offset in ms, or window centre
        in s).
    networks : dict
        Key -> :class:`funcnet.FunctionalNetwork`, or ``None`` where it could not be computed.
    errors : dict
        Key -> why there is no network.
    dropped : dict
        Key -> signals left out of that window's network because they are constant in it
        (min-max normalization needs a range; e.g. AP before the breakaway).
    """

    trial: str
    path: str
    data: pd.DataFrame
    phases: pd.DataFrame
    windows: dict[Any, Any]
    networks: dict[Any, Any]
    errors: dict[Any, str]
    dropped: dict[Any, tuple[str, ...]] = field(default_factory=dict)

    def window_data(self, key: Any) -> pd.DataFrame:
        """The analysed signals inside window ``key``, ``start <= time < stop``."""
        window = self.windows[key]
        index = self.data.index
        return self.data.loc[(index >= window.start) & (index < window.stop)]


@dataclass(frozen=True)
class PaperAnalyses:
    """Everything :func:`run_paper_analyses` computed.

    Attributes
    ----------
    plan_dir : str
        The plan folder.
    parameters : NetworkParameters
        The network parameters of every network.
    settings : dict
        The other choices made (signals, window lengths and caps), for the report.
    trials : pandas.DataFrame
        The plan's manifest.
    baseline : TrialAnalysis or None
        The baseline trial's phase networks (section 4.1).
    velocity : dict
        ``"V1", "V35", "V175", "V350"`` -> fixed-window networks (section 4.2).
    reversal : dict
        Backlash trial -> networks keyed by offset in ms (section 4.3).
    main : dict
        Main trial -> fixed-window networks (TCP distance and step size, section 3.1).
    timeline : TrialAnalysis or None
        Sliding windows over the baseline trial, keyed by window centre (beyond the paper).
    findings : tuple of Finding
        The measured findings.
    inputs : dict
        File -> SHA-256 of every input read.
    warnings : dict
        Problem (warning class and what it means) -> how many networks have it.
    elapsed : float
        Seconds spent.
    """

    plan_dir: str
    parameters: NetworkParameters
    settings: dict[str, str]
    trials: pd.DataFrame
    baseline: TrialAnalysis | None
    velocity: dict[str, TrialAnalysis]
    reversal: dict[str, TrialAnalysis]
    main: dict[str, TrialAnalysis]
    timeline: TrialAnalysis | None
    findings: tuple[Finding, ...]
    inputs: dict[str, str]
    warnings: dict[str, int]
    elapsed: float

    def groups(self) -> dict[str, dict[str, TrialAnalysis]]:
        """The analyses by purpose, each trial once per purpose (for tables)."""
        single = {t.trial: t for t in (self.baseline,) if t is not None}
        v1 = {t.trial: t for k, t in self.velocity.items() if k == "V1"}
        timeline = {t.trial: t for t in (self.timeline,) if t is not None}
        return {"baseline phases (section 4.1)": single,
                "static-friction trial V1 (section 4.2)": v1,
                "main trials, fixed windows (sections 4.2, 3.1)": self.main,
                "backlash trials, reversal windows (section 4.3)": self.reversal,
                "baseline, sliding windows (beyond the paper)": timeline}

    def velocity_cells(self) -> dict[tuple[str, str], tuple[pd.DataFrame, Any]]:
        """(velocity, phase) -> (the window's signals, its network or None), for Fig. 10."""
        return {(label, phase): (trial.window_data(phase), net)
                for label, trial in self.velocity.items()
                for phase, net in trial.networks.items()}

    def example_reversal(self) -> TrialAnalysis | None:
        """The backlash trial closest to the baseline (35 °/min, TCP 1.6 m), for Fig. 11."""
        if not self.reversal:
            return None
        trials = self.trials.set_index("name")
        return min(self.reversal.values(),
                   key=lambda a: (abs(float(trials.loc[a.trial, "speed"]) - 35),
                                  abs(float(trials.loc[a.trial, "tcp"]) - 1.6)))


def _select(trials: pd.DataFrame, **where: float | str | bool) -> pd.DataFrame:
    mask = np.ones(len(trials), dtype=bool)
    for column, value in where.items():
        column_values = trials[column]
        if isinstance(value, bool):
            mask &= column_values.astype(str).str.lower().isin(["true", "1"]) == value
        elif isinstance(value, str):
            mask &= column_values.astype(str) == value
        else:
            mask &= np.isclose(column_values.astype(float), value)
    return trials[mask]


def main_move(phases: pd.DataFrame) -> pd.DataFrame:
    """The phases of a trial's longest motion (a run of phases between standstills).

    A trial of the plan is one motion (a backlash trial's reversal joins its forward and reverse
    moves into one); phase detection on a slow, quantized reference can add moves of a few ms
    at its ends, which are left out here.

    Parameters
    ----------
    phases : pandas.DataFrame
        ``phase, start, stop`` from :func:`funcnet.robot.detect_phases`.

    Returns
    -------
    pandas.DataFrame
        The rows of the longest run, standstill excluded.

    References
    ----------
    Paper section 3.1 (one motion per trial) and Fig. 9.

    Examples
    --------
    >>> import pandas as pd
    >>> table = pd.DataFrame({"phase": ["cruise", "standstill", "early spin-up", "cruise"],
    ...                       "start": [0.0, 0.01, 0.5, 0.7], "stop": [0.01, 0.5, 0.7, 3.0]})
    >>> main_move(table)["phase"].tolist()
    ['early spin-up', 'cruise']
    """
    moving = (phases["phase"] != "standstill").to_numpy()
    run_id = np.cumsum(~moving)
    runs = [phases[moving & (run_id == k)] for k in np.unique(run_id[moving])]
    if not runs:
        return phases.iloc[:0]
    return max(runs, key=lambda run: float(run["stop"].max() - run["start"].min()))


def network_problems(networks: Mapping[Any, Any], *,
                     staircases: Sequence[str] = ()) -> dict[str, int]:
    """What the networks' pairs tables flag, counted by problem: one per network having it.

    Built from the flags (:func:`funcnet.pipeline.window_warnings`), never from warning text,
    so it is safe with threads.

    Parameters
    ----------
    networks : mapping of key -> FunctionalNetwork or None
        The networks (``None`` entries are skipped).
    staircases : sequence of str
        Signals that are staircases on the analysis grid; every network with one of them as a
        node counts once for ``StaircaseWarning``.

    Returns
    -------
    dict
        ``"WarningClass: what it means"`` -> number of networks.

    Examples
    --------
    >>> network_problems({})
    {}
    """
    from funcnet.pipeline import window_warnings

    computed = {str(key): net for key, net in networks.items() if net is not None}
    counts: dict[str, int] = {}
    for warning in window_warnings(computed):
        problem = str(warning.problem)
        key = f"{type(warning).__name__}: {_PROBLEMS.get(problem, problem)}"
        counts[key] = counts.get(key, 0) + 1
    stairs = sum(bool(set(staircases) & set(net.nodes)) for net in computed.values())
    if stairs:
        key = f"StaircaseWarning: {_PROBLEMS['staircase']}"
        counts[key] = counts.get(key, 0) + stairs
    return counts


def _analyse(name: str, path: Any, recording: Any,
             keyed_windows: Callable[[Any, pd.DataFrame], dict[Any, Any]],
             signals: Sequence[str], parameters: NetworkParameters,
             warned: dict[str, int]) -> TrialAnalysis:
    """Detect a trial's phases, build its windows and compute one network per window."""
    from funcnet.pipeline import WindowNetworks, window_networks
    from funcnet.robot import detect_phases
    from funcnet.robot.preprocess import staircase_signals

    data = recording.data[list(signals)]
    try:
        phases = detect_phases(recording)
        windows = keyed_windows(recording, main_move(phases))
    except FuncnetError as exc:
        return TrialAnalysis(name, str(path), data,
                             pd.DataFrame(columns=["phase", "start", "stop"]), {}, {},
                             {"windows": str(exc)})
    try:
        # One call for the whole trial: its warnings are summarized once, not per window.
        by_label = window_networks(recording, list(windows.values()), signals=signals,
                                   parameters=parameters, constant="drop", errors="collect")
        failed = {f.window: f.message for f in by_label.failures}
    except FuncnetError as exc:  # the trial itself (a signal it lacks): no window has one
        by_label, failed = WindowNetworks(), {w.label: str(exc) for w in windows.values()}
    networks: dict[Any, Any] = {key: by_label.get(w.label) for key, w in windows.items()}
    errors = {key: failed[w.label] for key, w in windows.items() if w.label in failed}
    dropped = {key: tuple(net.window["dropped"]) for key, net in networks.items()
               if net is not None and net.window and net.window.get("dropped")}
    problems = network_problems(networks, staircases=staircase_signals(recording, signals))
    for key, count in problems.items():
        warned[key] = warned.get(key, 0) + count
    return TrialAnalysis(name, str(path), data, phases, windows, networks, errors, dropped)


def _read_manifest(plan: Path) -> tuple[pd.DataFrame, dict[str, str]]:
    """A plan's trials, and the manifest's hash as the first of the inputs."""
    from funcnet._io import file_sha256

    manifest = plan / "manifest.csv"
    if not manifest.is_file():
        raise TraceError(manifest, "no manifest.csv: not a plan written by funcnet simulate")
    return pd.read_csv(manifest), {"manifest.csv": file_sha256(manifest)}


def _keyed_windows(fixed_lengths: Mapping[str, float] | None, max_phase_length: float,
                   reversal_width: float | None) -> tuple[Keyed, Keyed, Keyed]:
    """How a trial's windows are cut and keyed: fixed lengths by label, the baseline's phases
    by label (each cut to ``max_phase_length``), reversal shifts by milliseconds."""
    from funcnet.robot import fixed_windows, phase_windows, reversal_windows

    def fixed(recording: Any, phases: pd.DataFrame) -> dict[Any, Any]:
        return {w.label: w for w in fixed_windows(phases, fixed_lengths)}

    def by_phase(recording: Any, phases: pd.DataFrame) -> dict[Any, Any]:
        windows = {}
        for w in phase_windows(phases, include=BASELINE_PHASES):
            stop = min(w.stop, w.start + max_phase_length)
            windows[w.label] = dataclasses.replace(w, stop=stop)
        return windows

    def reversal(recording: Any, phases: pd.DataFrame) -> dict[Any, Any]:
        return {int(round(w.offset * 1000)): w
                for w in reversal_windows(phases, width=reversal_width)}

    return fixed, by_phase, reversal


def _findings(baseline: TrialAnalysis | None, velocity: Mapping[str, TrialAnalysis],
              reversal_analyses: Mapping[str, TrialAnalysis],
              main_analyses: Mapping[str, TrialAnalysis], main: pd.DataFrame) -> list[Finding]:
    """Every finding of section 4 measured on the analyses, then the design's effects."""
    findings = [
        *baseline_findings(baseline.networks if baseline is not None else {},
                           left_out=baseline.dropped if baseline is not None else {}),
        *velocity_findings({(label, phase): analysis.networks.get(phase)
                            for label, analysis in velocity.items()
                            for phase in VELOCITY_PHASES},
                           left_out={(label, phase): analysis.dropped.get(phase, ())
                                     for label, analysis in velocity.items()
                                     for phase in VELOCITY_PHASES}),
        *reversal_findings({name: a.networks for name, a in reversal_analyses.items()},
                           left_out={name: a.dropped for name, a in reversal_analyses.items()}),
    ]
    design_networks = {(name, phase): net for name, a in main_analyses.items()
                       for phase, net in a.networks.items()}
    design_trials = main[["name", "speed", "tcp", "step"]]
    findings.append(design_effect(design_networks, design_trials, "tcp",
                                  label=lambda v: f"{v:g} m"))
    findings.append(design_effect(design_networks, design_trials, "step",
                                  label=lambda v: f"{v:g}°"))
    return findings


def _settings(signals: Sequence[str], max_phase_length: float,
              fixed_lengths: Mapping[str, float] | None, reversal_width: float | None,
              timeline_width: float, timeline_step: float) -> dict[str, str]:
    """The analyses' settings, said in words for the report."""
    return {
        "signals": ", ".join(signals),
        "dim, delay (choice)": ("the paper states neither for the robot data; its section 2.1 "
                                "illustration's m = 3, τ = 10 samples (20 ms at 500 Hz) are "
                                "used"),
        "phases": "detected from RP (funcnet.robot.detect_phases), main motion only",
        "baseline phase windows": f"detected phases, each cut to at most {max_phase_length:g} s",
        "fixed windows [s]": ", ".join(f"{k} {v:g}" for k, v in (
            fixed_lengths or {"spin-up": 0.28, "cruise": 0.6, "braking": 0.6}).items()),
        "reversal windows": ("shifts -40, -20, 0, +20, +40 ms; width "
                             + ("the detected reversal phase's span" if reversal_width is None
                                else f"{reversal_width:g} s")),
        "timeline windows": f"sliding, {timeline_width:g} s every {timeline_step:g} s",
    }


class AnalysisOptions(ParameterOverrides, total=False):
    """The keywords of :func:`run_paper_analyses` besides the plan and the progress callback,
    for functions that pass them on (:func:`funcnet.paper.demo.build_demo_report`)."""

    parameters: NetworkParameters | None
    signals: Sequence[str]
    max_phase_length: float
    fixed_lengths: Mapping[str, float] | None
    reversal_width: float | None
    timeline_width: float
    timeline_step: float


def run_paper_analyses(
    plan_dir: Any,
    *,
    parameters: NetworkParameters | None = None,
    progress: Callable[[int, int, str], None] | None = None,
    signals: Sequence[str] = PAPER_SIGNALS,
    max_phase_length: float = 4.0,
    fixed_lengths: Mapping[str, float] | None = None,
    reversal_width: float | None = REVERSAL_WIDTH,
    timeline_width: float = 0.6,
    timeline_step: float = 0.2,
    **overrides: Unpack[ParameterOverrides],
) -> PaperAnalyses:
    """The paper's section 4 analyses on a plan of trials, with every finding measured.

    Reads ``manifest.csv`` and the traces of ``plan_dir`` (:func:`funcnet.sim.write_plan`),
    derives V from AP (Eq. 11-12) over each whole recording
    (:func:`funcnet.robot.read_recording`), detects the phases from RP
    (:func:`funcnet.robot.detect_phases`) and computes (:func:`funcnet.window_networks`):

    - the baseline trial (35 °/min, 3°, TCP 1.6 m): one network per phase (early spin-up, late
      spin-up, cruise, braking; section 4.1), each phase window cut to ``max_phase_length``
      seconds from its start;
    - every main trial and the static-friction trial at TCP 1.6 m: fixed windows of 280 / 600 /
      600 ms anchored at spin-up, cruise and braking (section 4.2); V1 = 1 °/min (1°),
      V35 = the baseline, V175 = 175 °/min (3°), V350 = 350 °/min (10°), all at TCP 1.6 m;
    - every backlash trial: windows around the reversal shifted by -40, -20, 0, +20, +40 ms
      (section 4.3);
    - the baseline trial in sliding windows (beyond the paper);

    then measures the findings (:func:`~funcnet.paper.evaluate.baseline_findings`,
    :func:`~funcnet.paper.evaluate.velocity_findings`,
    :func:`~funcnet.paper.evaluate.reversal_findings`,
    :func:`~funcnet.paper.evaluate.design_effect` for TCP and step).

    Parameters
    ----------
    plan_dir : path-like
        Folder with ``manifest.csv`` and the traces it names.
    parameters : NetworkParameters, optional
        The network parameters; default :data:`PAPER_PARAMETERS`.
    progress : callable, optional
        ``progress(done, total, description)``.
    signals : sequence of str
        The nodes (default the paper's RP, AP, MP, V, RC, AC).
    max_phase_length : float
        Longest baseline phase window in seconds (the cost of a network grows with the cube of
        its length; the paper's cruise is 4 s).
    fixed_lengths : mapping, optional
        Fixed window lengths by anchor; default 280 / 600 / 600 ms.
    reversal_width : float or None
        Width of the reversal windows in seconds, centred on the detected reversal phase's
        middle (``None``: the phase's own span). The paper does not state it; its Fig. 11b shows
        all five windows inside the 300 ms reversal region, so a window is at most 220 ms wide:
        200 ms (100 samples) by default.
    timeline_width, timeline_step : float
        Sliding windows of the timeline, seconds.
    **overrides
        Network parameters by name (``dim``, ``rr``, ``mu``, ...), applied to ``parameters``.

    Returns
    -------
    PaperAnalyses
        Networks, findings, parameters, input hashes.

    Raises
    ------
    funcnet.errors.ParameterError
        A bad or unknown network parameter (before anything is read).
    funcnet.errors.TraceError
        ``manifest.csv`` is missing or a trace cannot be read.

    Warns
    -----
    funcnet.errors.FuncnetWarning
        What :func:`funcnet.window_networks` says, once per trial and kind of problem; the
        same problems are counted per network in ``warnings`` (:func:`network_problems`).

    Notes
    -----
    Only the phases of each trial's main motion are used (:func:`main_move`). A signal constant
    inside a window (AP before the breakaway, at low speed) cannot be min-max normalized: it is
    left out of that window's network (``constant="drop"``) and listed in ``dropped``; the
    findings count claims about it as not evaluable. Windows whose network cannot be computed
    at all (e.g. a window reaching past the recording) are kept as ``None`` with the reason.
    Nothing is tuned to the paper's results: the parameters are the paper's where it gives them
    and fixed beforehand where it does not.

    References
    ----------
    Paper sections 3.3-3.4 and 4 (Fig. 9, 10, 11); section 3.1 (Table 1).
    """
    from funcnet._io import file_sha256
    from funcnet.robot import read_recording, sliding_windows

    started = time.perf_counter()
    network = resolve(PAPER_PARAMETERS if parameters is None else parameters, overrides)
    plan = Path(plan_dir)
    trials, inputs = _read_manifest(plan)
    warned: dict[str, int] = {}
    loaded: dict[str, tuple[Path, Any]] = {}

    def load(row: Any) -> tuple[Path, Any]:
        """A trial's trace, with V derived over the whole recording; read and hashed once."""
        if row["name"] not in loaded:
            path = plan / str(row["file"])
            inputs[path.name] = file_sha256(path)
            loaded[row["name"]] = (path, read_recording(path, signals=signals))
        return loaded[row["name"]]

    def analyse(row: Any, keyed: Keyed) -> TrialAnalysis:
        return _analyse(row["name"], *load(row), keyed, signals, network, warned)

    fixed, by_phase, reversal = _keyed_windows(fixed_lengths, max_phase_length, reversal_width)

    main = _select(trials, group="main")
    baseline_rows = _select(main, speed=35, step=3, tcp=1.6)
    v1_rows = _select(trials, speed=1, tcp=1.6)
    backlash = _select(trials, reverse=True)
    total = len(main) + len(v1_rows) + len(backlash) + 2 * len(baseline_rows.head(1))
    done = 0

    def tick(description: str) -> None:
        nonlocal done
        if progress is not None:
            progress(done, total, description)
        done += 1

    main_analyses: dict[str, TrialAnalysis] = {}
    for _, row in main.iterrows():
        tick(f"main trial {row['name']}")
        main_analyses[row["name"]] = analyse(row, fixed)
    baseline = timeline = None
    for _, row in baseline_rows.head(1).iterrows():
        tick(f"baseline phases {row['name']}")
        baseline = analyse(row, by_phase)
        tick(f"baseline timeline {row['name']}")
        moving = baseline.phases[baseline.phases["phase"] != "standstill"]
        span = ((float(moving["start"].min()), float(moving["stop"].max()))
                if len(moving) else (None, None))

        def sliding(recording: Any, phases: pd.DataFrame,
                    span: tuple[Any, Any] = span) -> dict[Any, Any]:
            return {round((w.start + w.stop) / 2, 6): w for w in
                    sliding_windows(recording, timeline_width, timeline_step, start=span[0],
                                    stop=span[1])}

        timeline = analyse(row, sliding)
    velocity: dict[str, TrialAnalysis] = {}
    for _, row in v1_rows.head(1).iterrows():
        tick(f"static-friction trial {row['name']}")
        velocity["V1"] = analyse(row, fixed)
    for label, speed, step in (("V35", 35, 3), ("V175", 175, 3), ("V350", 350, 10)):
        rows = _select(main, speed=speed, step=step, tcp=1.6)
        if len(rows):
            velocity[label] = main_analyses[rows["name"].iloc[0]]
    reversal_analyses: dict[str, TrialAnalysis] = {}
    for _, row in backlash.iterrows():
        tick(f"backlash trial {row['name']}")
        reversal_analyses[row["name"]] = analyse(row, reversal)
    velocity = {k: velocity[k] for k in VELOCITIES if k in velocity}

    findings = _findings(baseline, velocity, reversal_analyses, main_analyses, main)
    if progress is not None:
        progress(total, total, "analyses done")
    settings = _settings(signals, max_phase_length, fixed_lengths, reversal_width,
                         timeline_width, timeline_step)
    return PaperAnalyses(str(plan), network, settings, trials, baseline, velocity,
                         reversal_analyses, main_analyses, timeline, tuple(findings), inputs,
                         warned, time.perf_counter() - started)
