"""The inspection of a recording of several axes: each axis on its own, and the robot as one
network.

A file of several axes read without choosing one (:mod:`funcnet.robot.axes`: columns ``A1.RP``,
``A2.MP``, ...) is inspected twice over. Each axis is inspected as a one-axis trace
(:func:`funcnet.inspection.inspect_recording` of :meth:`Recording.for_axis`): its moves, a
network per phase of every move, its backlash diagnosis. And the whole robot is one functional
network over each segment of the recording (the whole of it when nothing is missing) whose nodes
are every axis's signals, grouped per axis -- the multilayer view the paper names as future work
(section 6), each axis a layer. Its pairs table says of every pair whether it lies within one
axis or between two (:func:`pair_scope`): an edge within an axis is the axis's own dynamics, one
between axes a coupling of their motions (a common trajectory, the arm's inertia and weight
felt by the other axis).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Unpack

import pandas as pd

from funcnet.errors import FuncnetError
from funcnet.evidence.segment import SEGMENT_MAX_STATES, segment_tests
from funcnet.inspection._side_by_side import default_workers, run_in_order
from funcnet.inspection.trace import TraceInspection, _step, inspect_recording
from funcnet.network import FunctionalNetwork
from funcnet.network._inputs import prepared_signals
from funcnet.network.edge_evidence import check_evidence_settings
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides, resolve
from funcnet.pipeline import WindowFailure, WindowNetworks, window_evidence, window_networks
from funcnet.robot import Recording, Window, paper_nodes
from funcnet.robot.axes import split_qualified
from funcnet.robot.windows import span_window

__all__ = ["RobotInspection", "inspect_robot", "pair_scope", "robot_windows", "WITHIN_AXIS",
           "BETWEEN_AXES", "ROBOT_MAX_STATES", "ROBOT_NETWORK_STATES", "ROBOT_MAX_WINDOWS"]

#: The ``scope`` of a pair of one axis's signals.
WITHIN_AXIS = "within-axis"
#: The ``scope`` of a pair of two axes' signals.
BETWEEN_AXES = "between-axes"
#: Most states of one robot-network window. A network's cost grows about as the cube of its
#: states (the triangle counts of Eq. 6-7) and its intervals' resamples grow with it: a longer
#: segment is cut into equal consecutive parts of at most this many states, so the cost per
#: recorded second and the peak memory stay bounded. A cut is a last resort: the direction
#: reading of a shorter window is weaker, and cut at 2,500 states UR5 run No9 (no disturbance)
#: read 19 of its 153 set-point pairs into a set-point, against none whole. 4,500 keeps every
#: shipped recording whole (the longest, UR5 No9 with the force sensor, has 4,276 states).
ROBOT_MAX_STATES = 4500
#: Most states a robot network reads: a longer window's measures and evidence read every
#: ``d``-th state, ``d = ceil(M / ROBOT_NETWORK_STATES)``, each still embedded at the full rate
#: (the direction reading keeps every sample). The measures cost about the cube of the
#: states: the network of UR5 run No5 with disturbance (4,012 states, 30 nodes) with its
#: evidence took 60 CPU s on every state and 8 on one in three, 97.7 % of its pairs (all
#: those with a clear asymmetry) of the same kind (docs/validation/evidence.md section 10).
#: Every state of a window of up to 2,000 (UR5 No8, the MCS500 cycles) is read.
ROBOT_NETWORK_STATES = 2000
#: Most robot-network windows of one page: a recording that needs more parts (at the default
#: embedding, over about 12 x 4,520 samples) gets this many, spread evenly over it, and the
#: page says which; each axis's own report still covers its every move.
ROBOT_MAX_WINDOWS = 12


def pair_scope(pairs: pd.DataFrame) -> pd.DataFrame:
    """A pairs table with the axis of each node and whether the pair lies within one axis.

    Parameters
    ----------
    pairs : DataFrame
        With ``x`` and ``y`` named ``A<axis>.<signal>`` (a signal common to every axis has no
        axis).

    Returns
    -------
    DataFrame
        A copy with ``axis_x``, ``axis_y`` (nullable integers) and ``scope``:
        :data:`WITHIN_AXIS`, :data:`BETWEEN_AXES`, or ``"common"`` when a node belongs to no
        axis.

    Examples
    --------
    >>> pairs = pd.DataFrame({"x": ["A1.RP", "A1.RP", "A1.MP"], "y": ["A1.MP", "A2.RP", "t"]})
    >>> pair_scope(pairs)[["axis_x", "axis_y", "scope"]].values.tolist()
    [[1, 1, 'within-axis'], [1, 2, 'between-axes'], [1, <NA>, 'common']]
    """
    out = pairs.copy()
    axis_x = [split_qualified(str(x))[0] for x in out["x"]]
    axis_y = [split_qualified(str(y))[0] for y in out["y"]]
    out["axis_x"] = pd.array(axis_x, dtype="Int64")
    out["axis_y"] = pd.array(axis_y, dtype="Int64")
    out["scope"] = [
        "common" if a is None or b is None else WITHIN_AXIS if a == b else BETWEEN_AXES
        for a, b in zip(axis_x, axis_y, strict=True)
    ]
    return out


def _parts(start: float, stop: float, period: float, lag: int) -> list[tuple[float, float]]:
    """A segment cut into equal consecutive spans of at most ``ROBOT_MAX_STATES`` states."""
    samples = int(round((stop - start) / period))
    count = max(1, math.ceil(samples / (ROBOT_MAX_STATES + lag)))
    if count == 1:
        return [(start, stop)]
    edges = [start + round(k * samples / count) * period for k in range(count)] + [stop]
    return list(zip(edges[:-1], edges[1:], strict=True))


def robot_windows(recording: Recording,
                  parameters: NetworkParameters | None = None) -> tuple[tuple[Window, ...], str]:
    """The robot network's windows: each segment whole, or in parts of bounded size.

    A segment of at most :data:`ROBOT_MAX_STATES` states (at the parameters' embedding) is
    one window, labelled ``whole recording A-B s``. A longer one is cut into the fewest equal
    consecutive parts that each hold at most that many states (``part k of n: A-B s``). When
    the parts of all segments number more than :data:`ROBOT_MAX_WINDOWS`, that many are kept,
    spread evenly over the recording (the first and the last among them).

    Parameters
    ----------
    recording : Recording
    parameters : NetworkParameters, optional
        Their ``dim`` and ``delay`` give the states of a span (default parameters).

    Returns
    -------
    (tuple of Window, str)
        The windows, and one sentence for the page saying how the recording was cut (empty
        when every segment is one window).

    Examples
    --------
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"A1.RP": 0.0}, index=pd.Index([k / 100 for k in range(12000)],
    ...                     name="time"))
    >>> info = {"A1.RP": SignalInfo("A1.RP", None, None, 0.01)}
    >>> windows, note = robot_windows(Recording(data, {}, info, sample_period=0.01))
    >>> [w.label for w in windows]
    ['part 1 of 3: 0-40 s', 'part 2 of 3: 40-80 s', 'part 3 of 3: 80-120 s']
    """
    p = parameters if parameters is not None else NetworkParameters()
    lag = (p.dim - 1) * p.delay
    period = recording.sample_period
    spans = [_parts(a, b, period, lag) for a, b in recording.segments]
    if all(len(parts) == 1 for parts in spans):
        return tuple(dataclasses.replace(span_window(a, b), label=f"whole recording {a:g}-{b:g} s")
                     for (a, b), in spans), ""
    flat = [span for parts in spans for span in parts]
    chosen = sorted({round(k * (len(flat) - 1) / (ROBOT_MAX_WINDOWS - 1))
                     for k in range(ROBOT_MAX_WINDOWS)}) if len(flat) > ROBOT_MAX_WINDOWS \
        else list(range(len(flat)))
    windows = tuple(dataclasses.replace(span_window(*flat[k]),
                                        label=f"part {k + 1} of {len(flat)}: "
                                              f"{flat[k][0]:g}-{flat[k][1]:g} s")
                    for k in chosen)
    longest = max(b - a for a, b in flat)
    note = (f"A network over more than {ROBOT_MAX_STATES:,} states costs minutes: the "
            f"recording is cut into {len(flat)} consecutive parts of at most "
            f"{ROBOT_MAX_STATES:,} states ({longest:.1f} s) each, one network per part")
    if len(chosen) < len(flat):
        note += (f"; {len(chosen)} of them, spread evenly over the recording, are computed "
                 "here (each axis's own report covers its every move)")
    return windows, note + "."


def _cut_segments(recording: Recording, windows: Sequence[Window],
                  p: NetworkParameters) -> dict[tuple[float, float], list[str]]:
    """Each segment cut into parts (:func:`robot_windows`) -> the labels of its windows."""
    lag = (p.dim - 1) * p.delay
    return {(a, b): [w.label for w in windows if a <= w.start and w.stop <= b]
            for a, b in recording.segments
            if len(_parts(a, b, recording.sample_period, lag)) > 1}


def _segment_tests(recording: Recording, networks: WindowNetworks, windows: Sequence[Window],
                   nodes: Sequence[str], p: NetworkParameters, settings: EvidenceSettings,
                   ) -> tuple[dict[str, Mapping[tuple[str, str], Any]], str]:
    """The coupling test of each cut segment, run once on its thinned states
    (:func:`funcnet.evidence.segment.segment_tests`), by the label of each of its parts; and
    the sentence for the page. A segment whose test fails leaves its parts to their own."""
    from funcnet.errors import FuncnetError

    tests: dict[str, Mapping[tuple[str, str], Any]] = {}
    said: list[str] = []
    failed: list[str] = []
    for (a, b), labels in _cut_segments(recording, windows, p).items():
        labels = [label for label in labels if label in networks]
        # in the robot's order, of which each part's nodes are a subsequence (a node left
        # out of one part as constant may be in another): each pair keyed as its parts key it
        kept = [n for n in nodes if any(n in networks[label].nodes for label in labels)]
        if len(kept) < 2:
            continue
        span = recording.window(a, b).data[kept]
        try:
            prepared = prepared_signals(span, None, None, p.normalize)
            found, step = segment_tests(list(prepared.signals), names=list(prepared.names),
                                        parameters=p, surrogates=settings.get("surrogates"),
                                        alpha=settings.get("alpha", 0.05))
        except FuncnetError as error:
            failed.append(f"{a:g}-{b:g} s ({error})")
            continue
        tests.update({label: found for label in labels})
        ks = [t.surrogates for t in found.values() if t is not None]
        said.append(f"{a:g}-{b:g} s: one state in {step} of its {len(span):,} samples, "
                    f"K = {min(ks, default=0)}-{max(ks, default=0)}")
    unrun = (f" The test of a whole segment could not run, its parts test themselves: "
             f"{'; '.join(failed)}.") if failed else ""
    if not said:
        return tests, unrun.lstrip()
    drawn = "" if settings.get("edge_rule", "paper") == "interval" else (
        " The parts' asymmetry intervals are not drawn (`funcnet network` on a window draws "
        "them).")
    return tests, ("The coupling test of each part is its whole segment's, run once on at most "
                   f"{SEGMENT_MAX_STATES:,} states taken evenly over it ({'; '.join(said)}): "
                   f"a part alone holds too few surrogates to decide.{drawn}{unrun}")


def _evidence(recording: Recording, networks: WindowNetworks, windows: Sequence[Window],
              nodes: Sequence[str], p: NetworkParameters, settings: EvidenceSettings,
              ) -> tuple[WindowNetworks, str]:
    """Each window's evidence; the parts of a cut segment read its segment's coupling test
    and, but under the interval rule, draw no interval (their cost is the page's)."""
    tests, note = ({}, "") if settings.get("surrogate_method", "shift") != "shift" else \
        _segment_tests(recording, networks, windows, nodes, p, settings)
    own = WindowNetworks({k: v for k, v in networks.items() if k not in tests})
    cut = WindowNetworks({k: v for k, v in networks.items() if k in tests})
    found = window_evidence(recording, own, windows, errors="collect", **settings)
    failures = list(found.failures)
    if cut:
        parts = EvidenceSettings(**settings)
        if parts.get("edge_rule", "paper") != "interval":
            parts["resamples"] = 0
        more = window_evidence(recording, cut, windows, errors="collect", tests=tests, **parts)
        found.update(more)
        failures += more.failures
    order = {label: k for k, label in enumerate(networks)}
    return WindowNetworks({k: found[k] for k in networks if k in found},
                          sorted(failures, key=lambda f: order.get(f.window, 0))), note


def _ready(recording: Recording) -> None:
    """The recording's time index with its lookup tables built, before threads share it:
    pandas builds them on first use, which two threads must not do at once."""
    index = recording.data.index
    if len(index):
        index.get_loc(index[0])
        _ = index.is_monotonic_increasing, index.is_unique


def _robot_network(recording: Recording, windows: Sequence[Window], nodes: Sequence[str],
                   p: NetworkParameters, evidence: bool, settings: EvidenceSettings,
                   ) -> tuple[WindowNetworks, list[WindowFailure], str]:
    """The robot network of each window, with its evidence when asked: the networks, the
    windows that failed, and the sentence of the evidence for the page."""
    networks = window_networks(recording, windows, signals=nodes, parameters=p,
                               constant="drop", errors="collect",
                               max_states=ROBOT_NETWORK_STATES)
    failures = list(networks.failures)
    tested = ""
    if evidence:
        networks, tested = _evidence(recording, networks, windows, nodes, p, settings)
        failures += networks.failures
    return networks, failures, " ".join(filter(None, [_thinned_note(networks, p), tested]))


def _thinned_note(networks: Mapping[str, FunctionalNetwork], p: NetworkParameters) -> str:
    """The sentence for the page on the windows whose networks read every ``d``-th state."""
    lag = (p.dim - 1) * p.delay
    thinned = [f"{label}: one in {net.state_step} of its {net.n_samples - lag:,} states"
               for label, net in networks.items() if net.state_step > 1]
    if not thinned:
        return ""
    return (f"A robot network over more than {ROBOT_NETWORK_STATES:,} states costs minutes "
            "(about the cube of its states): its measures, coupling test and intervals read "
            f"states taken evenly, each embedded at the full rate ({'; '.join(thinned)}); its "
            "direction reading reads every sample.")


@dataclass(frozen=True)
class RobotInspection:
    """What :func:`inspect_robot` found in a recording of several axes.

    Attributes
    ----------
    source : str
        The file.
    axes : dict
        Axis -> its :class:`~funcnet.inspection.TraceInspection`.
    axis_errors : dict
        Axis -> why it could not be inspected (e.g. an axis that never moves).
    signals : tuple of str
        The robot network's nodes, grouped per axis.
    windows : tuple of Window
        The robot network's windows: one per segment of the recording.
    networks : dict
        Window label -> the robot network (its pairs table with the evidence columns when
        asked for).
    pairs : dict
        Window label -> the network's pairs table with ``axis_x``, ``axis_y``, ``scope``
        (:func:`pair_scope`), derived from ``networks`` when first read.
    failures : tuple of WindowFailure
        Windows without their robot network or a part of its evidence.
    windows_note : str
        How the recording was cut into windows (:func:`robot_windows`; empty when each
        segment is one window).
    parameters : NetworkParameters
    evidence : bool
    elapsed : float
        Seconds.
    recording : Recording
    """

    source: str
    axes: dict[int, TraceInspection]
    axis_errors: dict[int, str]
    signals: tuple[str, ...]
    windows: tuple[Window, ...]
    networks: dict[str, FunctionalNetwork]
    failures: tuple[WindowFailure, ...]
    parameters: NetworkParameters
    evidence: bool
    elapsed: float
    recording: Recording = dataclasses.field(repr=False)
    windows_note: str = ""

    @functools.cached_property
    def pairs(self) -> dict[str, pd.DataFrame]:
        """Window label -> the network's pairs table with its scope (:func:`pair_scope`)."""
        return {label: pair_scope(net.pairs) for label, net in self.networks.items()}


def inspect_robot(
    recording: Recording,
    *,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    backlash: bool = True,
    progress: Callable[[int, int, str], None] | None = None,
    evidence_options: EvidenceSettings | None = None,
    workers: int | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> RobotInspection:
    """Inspect each axis of a recording of several axes, and the robot as one network.

    Parameters
    ----------
    recording : Recording
        Of several axes (:attr:`Recording.axes`), as :func:`funcnet.robot.read_trace` reads a
        MATLAB or HDF5 file without ``axis``.
    signals : sequence of str, optional
        The robot network's nodes (``A1.RP``, ...); default every axis's paper nodes
        (:func:`funcnet.robot.paper_nodes`: RP, AP, MP, RC, AC as recorded). Each axis's own
        inspection takes its defaults.
    parameters, evidence, backlash, evidence_options, **overrides
        As :func:`~funcnet.inspection.inspect_recording`, for every network.
    progress : callable, optional
        ``progress(done, total, description)``, called in the calling thread.
    workers : int, optional
        Computations side by side: the robot network with its evidence and each axis's
        inspection are independent. In forked processes where this process may fork (on Linux,
        Numba's thread pool not started here yet, as in a command that reads a recording and
        inspects it), in threads otherwise. Default the cores this process may use, at most 4,
        in the main thread (1 in any other); 1 computes them one after the other in the
        calling thread.
        The results are the same bit for bit, and so are the warnings and their order (each
        computation's, in the order robot network, axis 1, axis 2, ...): those of the others
        are emitted once they are done. No callback may enter ``warnings.catch_warnings``.

    Returns
    -------
    RobotInspection

    Raises
    ------
    ParameterError
        The recording has no axes, or a bad parameter (before anything is computed).
    ChannelError
        A signal that is not in the recording.
    """
    from funcnet.errors import ParameterError

    started = time.perf_counter()
    if not recording.axes:
        raise ParameterError.of("recording", "holds one axis: use inspect_recording")
    p = resolve(parameters, overrides)
    if evidence:
        check_evidence_settings(**(evidence_options or EvidenceSettings()))
    nodes = list(signals) if signals is not None else paper_nodes(recording.data.columns)
    windows, note = robot_windows(recording, p)
    axes = list(recording.axes)
    total = len(axes) + 2
    _step(progress, 0, total, "robot network")

    def robot() -> tuple[WindowNetworks, list[WindowFailure], str]:
        return _robot_network(recording, windows, nodes, p, evidence,
                              evidence_options or EvidenceSettings())

    _ready(recording)
    parts = {axis: recording.for_axis(axis) for axis in axes}

    def axis_job(axis: int) -> Callable[[], TraceInspection | str]:
        def job() -> TraceInspection | str:
            try:
                return inspect_recording(parts[axis], parameters=p,
                                         evidence=evidence, backlash=backlash,
                                         evidence_options=evidence_options)
            except FuncnetError as error:
                return str(error)
        return job

    def done(k: int) -> None:  # the steps of a loop over the jobs, in their order
        if k < len(axes):
            _step(progress, 1 + k, total, f"axis {axes[k]}")

    found: list[Any] = run_in_order([robot, *map(axis_job, axes)],
                                    default_workers() if workers is None else workers, done)
    computed: tuple[WindowNetworks, list[WindowFailure], str] = found[0]
    networks, failures, tested = computed
    note = " ".join(filter(None, [note, tested]))
    inspected = dict(zip(axes, found[1:], strict=True))
    _step(progress, total, total, "done")
    return RobotInspection(
        source=recording.source or "<recording>",
        axes={a: v for a, v in inspected.items() if isinstance(v, TraceInspection)},
        axis_errors={a: v for a, v in inspected.items() if isinstance(v, str)},
        signals=tuple(nodes),
        windows=windows,
        networks=dict(networks),
        failures=tuple(failures),
        parameters=p,
        evidence=evidence,
        elapsed=time.perf_counter() - started,
        recording=recording,
        windows_note=note,
    )

