"""A run of a program compared with earlier runs of it: what changed, and when.

:func:`compare_runs` aligns RUN on every reference by the position set-points of all axes
(:func:`~funcnet.comparison.align.align_on_setpoints`), refuses a reference whose set-points
do not match RUN's (another program), builds the references' band of every residual signal of
every axis (:func:`~funcnet.comparison.band.reference_band`) and reports the intervals where
RUN departs beyond it (:func:`~funcnet.comparison.intervals.find_intervals`). The residuals:

``CR``
    the current residual, measured current minus its set-point, ``AC - RC``;
``FE``
    the following error, set-point minus measured position, ``RP - AP`` (``RP - MP`` when the
    recording has no AP).

The functional networks' measures over sliding windows are the other reading
(:mod:`funcnet.comparison.networks`); ``readings`` says which carry the intervals
(docs/guide/compare.md: on the UR5 runs with a force sensor, the current residual does).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from funcnet.comparison.align import SETPOINT_TOLERANCE, Alignment, _runs, align_on_setpoints
from funcnet.comparison.band import Band, reference_band
from funcnet.comparison.intervals import Interval, find_intervals
from funcnet.comparison.networks import NetworkComparison, compare_networks
from funcnet.errors import ParameterError, SignalError
from funcnet.parameters import NetworkParameters
from funcnet.robot.axes import qualified
from funcnet.robot.recording import Recording

__all__ = ["Comparison", "compare_runs", "program_phases", "RESIDUALS", "READINGS", "MATCHED"]

#: The residual signals: name -> (minuend, subtrahend roles, in order of preference).
RESIDUALS = {"CR": (("AC",), ("RC",)), "FE": (("RP",), ("AP", "MP"))}
#: What each residual is, for pages and messages.
RESIDUAL_NAMES = {"CR": "current residual AC - RC", "FE": "following error RP - AP"}
#: The readings that can carry the intervals.
READINGS = ("residuals", "networks")
#: Smallest fraction of RUN a reference's set-points must match: less is another program.
MATCHED = 0.5


@dataclass(frozen=True)
class Comparison:
    """What :func:`compare_runs` found.

    Attributes
    ----------
    run : str
        RUN's source.
    references : tuple of str
        The references' sources.
    times : ndarray
        RUN's seconds per tick.
    covered : ndarray of bool
        Per tick of RUN: some reference covers it (compared).
    coverage : tuple of float
        Per reference, the fraction of RUN its set-points match.
    bands : dict of (str, int) to Band
        Per residual signal and axis.
    units : dict of str to str or None
        Per residual signal.
    intervals : tuple of Interval
        Where RUN departs beyond ``threshold`` spreads, from the readings in ``readings``.
    residual_intervals, network_intervals : tuple of Interval
        Each reading's own intervals (reported whether it carries the result or not).
    networks : NetworkComparison or None
        The networks' reading; None when not computed.
    readings : tuple of str
        The readings that carry ``intervals``.
    threshold : float
        Departure, in spreads, beyond which RUN counts as changed.
    within_run : bool
        One reference: the spread is that of its cycles, within one run.
    phases : tuple of (str, float, float)
        The moves of RUN's program (:func:`program_phases`), RUN's seconds.
    notes : tuple of str
        What was assumed or left out, one sentence each.
    """

    run: str
    references: tuple[str, ...]
    times: np.ndarray = field(repr=False)
    covered: np.ndarray = field(repr=False)
    coverage: tuple[float, ...]
    bands: dict[tuple[str, int], Band] = field(repr=False)
    units: dict[str, str | None]
    intervals: tuple[Interval, ...]
    residual_intervals: tuple[Interval, ...]
    network_intervals: tuple[Interval, ...]
    networks: NetworkComparison | None = field(repr=False)
    readings: tuple[str, ...]
    threshold: float
    within_run: bool
    phases: tuple[tuple[str, float, float], ...]
    notes: tuple[str, ...]

    @property
    def compared(self) -> float:
        """Fraction of RUN compared with at least one reference."""
        return float(self.covered.mean()) if self.covered.size else 0.0

    @property
    def compared_seconds(self) -> float:
        """Seconds of RUN compared."""
        period = float(self.times[1] - self.times[0]) if self.times.size > 1 else 0.0
        return round(float(self.covered.sum()) * period, 6)

    @property
    def changed_seconds(self) -> float:
        """Seconds of RUN inside the intervals."""
        return round(sum(i.stop - i.start for i in self.intervals), 6)


def _axes(recording: Recording) -> tuple[int, ...]:
    return recording.axes or (recording.axis or 1,)


def _column(recording: Recording, axis: int, role: str) -> str | None:
    name = qualified(axis, role) if recording.axes else role
    return name if name in recording.data.columns else None


def _setpoints(recording: Recording, axes: Sequence[int]) -> np.ndarray:
    columns = [_column(recording, a, "RP") for a in axes]
    missing = [a for a, c in zip(axes, columns, strict=True) if c is None]
    if missing:
        raise SignalError(f"{recording.source}: no position set-point RP for axis "
                          f"{', '.join(map(str, missing))}: runs are aligned on it")
    return recording.data[[c for c in columns if c is not None]].to_numpy(dtype=np.float64)


def _residual(recording: Recording, axis: int, name: str) -> tuple[np.ndarray, str | None] | None:
    """The residual ``name`` of one axis and its unit; None when a signal is missing."""
    plus, minus = RESIDUALS[name]
    a = next((c for r in plus if (c := _column(recording, axis, r))), None)
    b = next((c for r in minus if (c := _column(recording, axis, r))), None)
    if a is None or b is None:
        return None
    values = (recording.data[a] - recording.data[b]).to_numpy(dtype=np.float64)
    return values, recording.signals[a].unit


def compare_runs(
    run: Recording,
    references: Sequence[Recording],
    *,
    signals: Sequence[str] = ("CR", "FE"),
    readings: Sequence[str] = ("residuals",),
    threshold: float = 6.0,
    merge: float = 0.5,
    min_duration: float = 0.05,
    tolerance: float = SETPOINT_TOLERANCE,
    smooth: float = 0.5,
    networks: bool = True,
    window: float = 1.0,
    step: float = 0.25,
    parameters: NetworkParameters | None = None,
) -> Comparison:
    """Compare RUN with references of the same program (module notes).

    Parameters
    ----------
    run : Recording
        The run to compare: one axis, or several (columns ``A1.RP``, ...).
    references : sequence of Recording
        Earlier runs of the same program, same axes and sample period; any length, gaps
        allowed (no match spans one).
    signals : sequence of str
        Residuals of :data:`RESIDUALS` to compare.
    readings : sequence of str
        Which readings carry the intervals: ``"residuals"``, ``"networks"`` or both.
    threshold : float
        Departure, in multiples of the references' spread, beyond which RUN has changed.
    merge, min_duration : float
        Seconds: departures closer than ``merge`` are one interval; shorter ones are dropped.
    tolerance : float
        Largest RMS set-point difference of an alignment match (the set-points' unit).
    smooth : float
        Seconds along the program over which the references' spread is averaged.
    networks : bool
        Compute the networks' reading (needed when ``readings`` holds ``"networks"``).
    window, step : float
        Seconds: the networks' sliding windows.
    parameters : NetworkParameters, optional
        The networks' parameters.

    Returns
    -------
    Comparison

    Raises
    ------
    ParameterError
        No reference; another sample period; an unknown signal or reading.
    SignalError
        A reference whose set-points match less than half of RUN: another program (the one
        line names it and the set-point difference); no residual signal in common.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import SignalInfo
    >>> def run(seed, push=False):
    ...     t = np.arange(0, 8, 0.01)
    ...     rp = np.sin(2 * np.pi * t / 2)                  # a program of 2 s, four cycles
    ...     ac = np.cos(2 * np.pi * t / 2) + np.random.default_rng(seed).normal(0, .05, t.size)
    ...     if push:
    ...         ac[450:480] += 1.0
    ...     data = pd.DataFrame({"RP": rp, "AC": ac, "RC": np.cos(2 * np.pi * t / 2)},
    ...                         index=pd.Index(t.round(9), name="time"))
    ...     return Recording(data, {}, {c: SignalInfo(c, None, None, .01, "A") for c in data},
    ...                      sample_period=0.01)
    >>> c = compare_runs(run(0, push=True), [run(1), run(2)], networks=False)
    >>> [(i.start, i.stop, i.signals) for i in c.intervals], c.compared
    ([(4.5, 4.8, ('CR',))], 1.0)
    """
    refs = list(references)
    _check_arguments(run, refs, signals, readings, networks)
    axes = _axes(run)
    period = run.sample_period
    run_rp = _setpoints(run, axes)
    alignments, coverage = _alignments(run, refs, axes, run_rp, tolerance)
    covered = np.any([a.covered for a in alignments], axis=0)
    times = run.data.index.to_numpy(dtype=np.float64)
    notes: list[str] = []
    bands, units = _bands(run, refs, axes, signals, alignments, smooth, notes)
    within = len(refs) == 1
    if within:
        notes.append("one reference: the band's spread is that of the reference's cycles, "
                     "within one run; what differs between runs (another day, warm-up, "
                     "payload) is not in it, so the band is narrower and more of RUN reads as "
                     "changed than with two or more references")
    filled = max(b.filled for b in bands.values())
    if filled > 0:
        notes.append(f"{filled:.0%} of the compared ticks had a single reference value nearby: "
                     "there the spread is the signal's median spread along the program")
    residual_intervals = find_intervals(
        {k: b.size for k, b in bands.items()},
        {k: b.run - b.centre for k, b in bands.items()}, units, times=times,
        threshold=threshold, merge=merge, min_duration=min_duration)
    net: NetworkComparison | None = None
    network_intervals: tuple[Interval, ...] = ()
    if networks:
        net = compare_networks(run, refs, alignments, axes=axes, window=window, step=step,
                               parameters=parameters, smooth=smooth)
        network_intervals = net.intervals(threshold=threshold, merge=merge)
    chosen = [*(residual_intervals if "residuals" in readings else ()),
              *(network_intervals if "networks" in readings else ())]
    intervals = _union(chosen, merge) if len(readings) > 1 else tuple(chosen)
    missing = ~np.isfinite(run_rp).all(axis=1)
    if missing.any():
        notes.append(f"{missing.sum() * period:.3g} s of RUN have no set-point (gaps): not "
                     "compared, no interval there")
    uncovered = int((~covered & ~missing).sum())
    if uncovered:
        notes.append(f"{uncovered * period:.3g} s of RUN matched no reference's set-points: "
                     "not compared, no interval there")
    return Comparison(
        run=str(run.source), references=tuple(str(r.source) for r in refs), times=times,
        covered=covered, coverage=tuple(coverage), bands=bands, units=units,
        intervals=intervals, residual_intervals=residual_intervals,
        network_intervals=network_intervals, networks=net, readings=tuple(readings),
        threshold=threshold, within_run=within,
        phases=tuple(program_phases(run_rp, period, t0=float(times[0]) if times.size else 0.0)),
        notes=tuple(notes))


def _check_arguments(run: Recording, refs: Sequence[Recording], signals: Sequence[str],
                     readings: Sequence[str], networks: bool) -> None:
    """Refuse what :func:`compare_runs` cannot compare, in one line naming the argument."""
    if not refs:
        raise ParameterError.of("references", "holds no recording: compare with at least one")
    unknown = [s for s in signals if s not in RESIDUALS]
    if unknown:
        raise ParameterError.of("signals", f"{unknown} are not residuals "
                                f"({', '.join(RESIDUALS)})")
    bad = [r for r in readings if r not in READINGS]
    if bad or not readings:
        raise ParameterError.of("readings", f"must be among {', '.join(READINGS)}, got "
                                f"{list(readings)}")
    if "networks" in readings and not networks:
        raise ParameterError.of("readings", "networks carry the intervals: compute them")
    period = run.sample_period
    for ref in refs:
        if abs(ref.sample_period - period) > 1e-9 * period:
            raise ParameterError.of("references", f"{ref.source}: sample period "
                                    f"{ref.sample_period:g} s, RUN's is {period:g} s")
    axes = _axes(run)
    for ref in refs:
        if _axes(ref) != axes:
            raise SignalError(f"{ref.source}: axes {list(_axes(ref))}, RUN ({run.source}) has "
                              f"{list(axes)}: not runs of one program")


def _alignments(run: Recording, refs: Sequence[Recording], axes: tuple[int, ...],
                run_rp: np.ndarray, tolerance: float) -> tuple[list[Alignment], list[float]]:
    """Each reference aligned on RUN's set-points, and the share of RUN it covers; a reference
    of another program refused."""
    alignments: list[Alignment] = []
    coverage = []
    for ref in refs:
        alignment = align_on_setpoints(run_rp, _setpoints(ref, axes), period=run.sample_period,
                                       tolerance=tolerance)
        share = float(alignment.covered.mean())
        if share < MATCHED:
            finite = alignment.distance[np.isfinite(alignment.distance)]
            closest = float(np.median(finite)) if finite.size else float("nan")
            rp = _column(run, axes[0], "RP")
            unit = run.signals[rp].unit if rp is not None else None
            raise SignalError(
                f"{ref.source}: its set-points do not match those of {run.source}: "
                f"{share:.0%} of the run matched (at least {MATCHED:.0%} needed), typical "
                f"set-point difference {closest:.3g} {unit or '(unit unknown)'} (tolerance "
                f"{tolerance:g}): not a run of the same program")
        alignments.append(alignment)
        coverage.append(share)
    return alignments, coverage


def _bands(run: Recording, refs: Sequence[Recording], axes: tuple[int, ...],
           signals: Sequence[str], alignments: Sequence[Alignment], smooth: float,
           notes: list[str]) -> tuple[dict[tuple[str, int], Band], dict[str, str | None]]:
    """The references' band of each residual and axis, and the residuals' units; a residual
    missing somewhere is said in ``notes``."""
    bands: dict[tuple[str, int], Band] = {}
    units: dict[str, str | None] = {}
    for name in signals:
        for axis in axes:
            own = _residual(run, axis, name)
            theirs = [_residual(ref, axis, name) for ref in refs]
            if own is None or any(t is None for t in theirs):
                notes.append(f"{RESIDUAL_NAMES[name]} of axis {axis}: a signal is missing in "
                             "RUN or a reference; not compared")
                continue
            units[name] = own[1]
            bands[(name, axis)] = reference_band(
                own[0], [t[0] for t in theirs if t is not None], alignments,
                period=run.sample_period, smooth=smooth)
    if not bands:
        raise SignalError(f"{run.source}: no residual ({', '.join(signals)}) in RUN and every "
                          "reference: nothing to compare")
    return bands, units


def _union(intervals: Sequence[Interval], merge: float) -> tuple[Interval, ...]:
    """Intervals of several readings as one list: overlapping or close ones joined."""
    out: list[Interval] = []
    for item in sorted(intervals, key=lambda i: i.start):
        if out and item.start - out[-1].stop < merge:
            last = out[-1]
            parts = tuple(sorted(last.differences + item.differences, key=lambda d: -d.size))
            out[-1] = Interval(last.start, max(last.stop, item.stop),
                               tuple(sorted(set(last.axes) | set(item.axes))),
                               tuple(dict.fromkeys(last.signals + item.signals)),
                               max(last.size, item.size), parts)
        else:
            out.append(item)
    return tuple(out)


def program_phases(setpoints: np.ndarray, period: float, *, t0: float = 0.0,
                   relative: float = 0.2, min_duration: float = 0.1
                   ) -> list[tuple[str, float, float]]:
    """The moves of a program: stretches where some axis' set-point moves fast.

    A robot program often never stops all axes at once; its moves are told apart by the slow
    stretches between them (every axis below ``relative`` of its peak speed).

    Parameters
    ----------
    setpoints : ndarray, shape (n, axes)
        Position set-points.
    period : float
        Sample period (s).
    t0 : float
        Seconds of the first tick.
    relative : float
        An axis moves fast when its set-point speed exceeds this fraction of its peak.
    min_duration : float
        Slow stretches shorter than this (s) are part of the move around them.

    Returns
    -------
    list of (str, float, float)
        ``("move k", start, stop)`` in seconds, in time order.

    Examples
    --------
    >>> rp = np.r_[np.zeros(100), np.linspace(0, 1, 100), np.ones(100)][:, None]
    >>> program_phases(rp, 0.01)
    [('move 1', 1.0, 2.0)]
    """
    rp = np.asarray(setpoints, dtype=np.float64)
    speed = np.abs(np.gradient(rp, axis=0)) / period if len(rp) > 1 else np.zeros_like(rp)
    peak = np.nanmax(speed, axis=0, initial=0.0)
    moving = (speed > relative * np.where(peak > 0, peak, np.inf)).any(axis=1)
    spans: list[list[int]] = []
    for a, b in _runs(np.asarray(moving)):
        if spans and (a - spans[-1][1]) * period < min_duration:
            spans[-1][1] = b
        else:
            spans.append([a, b])
    return [(f"move {k + 1}", round(t0 + a * period, 6), round(t0 + b * period, 6))
            for k, (a, b) in enumerate(spans)]
