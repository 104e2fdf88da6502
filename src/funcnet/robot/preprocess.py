"""Preprocessing of a robot recording before the networks (paper section 3.3).

Velocity from the arm-side position (Eq. 11-12), an encoder's step, derived signals (V,
following error, torsion), trimming to the motion or a time range, and resampling of mixed-rate
signals to a common grid.
Normalization per analysis window is the network's job
(:func:`funcnet.core.normalization.normalize`, called by :func:`funcnet.functional_network`),
not done here.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import replace

import numpy as np

from funcnet.errors import ChannelError, ParameterError, SignalError, StaircaseWarning
from funcnet.robot.recording import Recording
from funcnet.robot.signals import SignalInfo

__all__ = [
    "velocity",
    "segment_velocity",
    "segment_ticks",
    "reference_speed",
    "encoder_step",
    "add_derived_signals",
    "trim",
    "resample",
    "staircase_signals",
    "staircase_warning",
    "DERIVED_SIGNALS",
]

#: Derived signals :func:`add_derived_signals` knows: column -> (inputs, description).
DERIVED_SIGNALS = {
    "V": (("AP",), "velocity of AP, Eq. 11-12"),
    "FE": (("RP", "AP"), "RP - AP"),
    "TORSION": (("MP", "AP"), "MP - AP"),
    "VM": (("MP",), "velocity of MP (motor side), Eq. 11-12 applied to MP"),
}

# Tolerance, in ticks, for intervals that should be whole multiples of the grid.
_TICK_TOLERANCE = 1e-6


def velocity(ap: np.ndarray, sample_period: float) -> np.ndarray:
    """Velocity from a position signal: central difference (Eq. 11) and 3-point average (Eq. 12).

    Parameters
    ----------
    ap : array_like, shape (N,)
        Position samples (the arm-side position AP in the paper), N >= 2, uniform in time.
    sample_period : float
        Δt in seconds (1/500 s for the SINUMERIK servo clock).

    Returns
    -------
    ndarray, shape (N,)
        Smoothed velocity in position units per second.

    Notes
    -----
    Interior: ``v[i] = (x[i+1] - x[i-1]) / (2 Δt)`` (Eq. 11) and
    ``v̄[i] = (v[i-1] + v[i] + v[i+1]) / 3`` (Eq. 12). The two ends have one neighbour only, so
    each uses what exists: ``v[0] = (x[1] - x[0]) / Δt`` and ``v[N-1] = (x[N-1] - x[N-2]) / Δt``
    (one-sided differences, as :func:`numpy.gradient`), then ``v̄[0] = (v[0] + v[1]) / 2`` and
    ``v̄[N-1] = (v[N-2] + v[N-1]) / 2``. The output therefore has the input's length, and a
    straight line gives its exact slope everywhere, ends included. A NaN spreads to its
    neighbours (two on each side). On a 4 ms staircase sampled at 2 ms the central difference
    always spans exactly one step, so V is not a staircase itself.

    Raises
    ------
    SignalError
        Fewer than two samples or not one-dimensional.
    ParameterError
        ``sample_period`` not positive.

    References
    ----------
    Paper section 3.3, Eq. 11 (central difference, Δt = 1/500 s) and Eq. 12 (moving average).

    Examples
    --------
    >>> velocity([0.0, 1.0, 2.0, 3.0], 0.5)
    array([2., 2., 2., 2.])
    >>> velocity([0.0, 0.0, 1.0, 1.0, 1.0], 1.0)
    array([0.25      , 0.33333333, 0.33333333, 0.16666667, 0.        ])
    """
    x = np.asarray(ap, dtype=np.float64)
    if x.ndim != 1 or x.size < 2:
        raise SignalError(f"ap: needs a 1-D signal of at least 2 samples, got shape {x.shape}")
    if not (sample_period > 0 and math.isfinite(sample_period)):
        raise ParameterError(f"sample_period: must be > 0, got {sample_period}")
    raw = np.gradient(x, sample_period)  # Eq. 11 inside, one-sided differences at the ends
    smooth = np.empty_like(raw)
    smooth[1:-1] = (raw[:-2] + raw[1:-1] + raw[2:]) / 3.0  # Eq. 12
    smooth[0] = (raw[0] + raw[1]) / 2.0
    smooth[-1] = (raw[-2] + raw[-1]) / 2.0
    return smooth


def segment_velocity(recording: Recording, values: np.ndarray) -> np.ndarray:
    """:func:`velocity` of a recording's signal within each of its segments.

    Parameters
    ----------
    recording : Recording
        Its :attr:`~funcnet.robot.Recording.gaps` split it into segments.
    values : ndarray, shape (N,)
        A position signal on the recording's grid.

    Returns
    -------
    ndarray, shape (N,)
        Without gaps, :func:`velocity` of ``values``. With gaps, the velocity of each segment
        on its own (a value across a gap is no neighbour, so no NaN of the gap spreads into a
        segment) and NaN in the gaps and in a segment of one tick.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import SignalInfo
    >>> x = np.array([0.0, 1.0, 2.0, np.nan, 10.0, 11.0, 12.0])
    >>> data = pd.DataFrame({"AP": x}, index=pd.Index(np.arange(7.0), name="time"))
    >>> rec = Recording(data, {}, {"AP": SignalInfo("AP", None, None, 1.0)}, sample_period=1.0,
    ...                 gaps=((3.0, 4.0),))
    >>> segment_velocity(rec, x).tolist()
    [1.0, 1.0, 1.0, nan, 1.0, 1.0, 1.0]
    """
    values = np.asarray(values, dtype=np.float64)
    dt = recording.sample_period
    if not recording.gaps:
        return velocity(values, dt)
    out = np.full(values.shape, np.nan)
    for first, last in segment_ticks(recording):
        if last - first >= 2:
            out[first:last] = velocity(values[first:last], dt)
    return out


def segment_ticks(recording: Recording) -> list[tuple[int, int]]:
    """The tick ranges ``[first, stop)`` of a recording's segments (row positions).

    A tick belongs to the segment whose span (:attr:`~funcnet.robot.Recording.segments`) holds
    its time; on a grid coarser than the gaps' (a decimated recording) a tick in a gap belongs
    to none.

    Parameters
    ----------
    recording : Recording

    Returns
    -------
    list of (int, int)
        ``[(0, len(recording.data))]`` without gaps.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import SignalInfo
    >>> data = pd.DataFrame({"AP": np.arange(7.0)}, index=pd.Index(np.arange(7.0), name="time"))
    >>> rec = Recording(data, {}, {"AP": SignalInfo("AP", None, None, 1.0)}, sample_period=1.0,
    ...                 gaps=((3.0, 4.0),))
    >>> [(int(a), int(b)) for a, b in segment_ticks(rec)]
    [(0, 3), (4, 7)]
    """
    if not recording.gaps:
        return [(0, len(recording.data))]
    # the gaps' times lie on the grid they were found on (to the nanosecond)
    tolerance = _TICK_TOLERANCE * recording.sample_period
    index = recording.data.index.to_numpy(dtype=np.float64)
    return [
        (int(first), int(last))
        for first, last in (np.searchsorted(index, [start - tolerance, stop - tolerance])
                            for start, stop in recording.segments)
    ]


def _column(recording: Recording, column: str, purpose: str) -> np.ndarray:
    if column not in recording.data.columns:
        raise ChannelError(
            recording.source or "<recording>",
            f"{purpose} needs the column {column!r}; the recording has "
            f"{list(recording.data.columns)}",
        )
    return recording.data[column].to_numpy(dtype=np.float64)


def reference_speed(recording: Recording, reference: str = "RP") -> np.ndarray:
    """Speed ``|v|`` of the reference motion, by :func:`velocity` (Eq. 11-12) on ``reference``.

    Raises
    ------
    ChannelError
        No such column.
    SignalError
        The reference has NaN values (it is not recorded over the whole recording).

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0, 0.0, 1.0, 2.0]},
    ...                     index=pd.Index([0.0, 0.5, 1.0, 1.5], name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.5)}, sample_period=0.5)
    >>> reference_speed(rec)
    array([0.5       , 1.        , 1.66666667, 2.        ])
    """
    position = _column(recording, reference, "the reference motion")
    if np.isnan(position).any():
        first = recording.data.index[int(np.argmax(np.isnan(position)))]
        raise SignalError(
            f"{recording.source or '<recording>'}: {reference} has no value at {first:g} s; "
            "trim the recording to where it is recorded"
        )
    return np.abs(velocity(position, recording.sample_period))


def encoder_step(positions: np.ndarray) -> float:
    """An encoder's step (its resolution): the least change between its readings.

    Parameters
    ----------
    positions : ndarray
        The encoder's readings (AP or MP), in time order; NaN readings are no change.

    Returns
    -------
    float
        The least nonzero ``|difference|`` of consecutive readings; 1e-9 when the readings
        never change.

    Examples
    --------
    >>> encoder_step(np.array([0.0, 0.0, 0.25, 0.75, 0.5]))
    0.25
    """
    steps = np.abs(np.diff(positions))
    return float(steps[steps > 0].min()) if np.any(steps > 0) else 1e-9


def add_derived_signals(
    recording: Recording, signals: Iterable[str] = ("V", "FE", "TORSION")
) -> Recording:
    """Add derived signals as columns: V, VM, following error FE, torsion / lost motion TORSION.

    Parameters
    ----------
    recording : Recording
    signals : iterable of str
        Any of ``"V"`` (:func:`velocity` of AP, Eq. 11-12), ``"FE"`` (following error
        ``RP - AP``), ``"TORSION"`` (``MP - AP``: motor- minus arm-side position, the twist of
        the gear and its lost motion; both encoders on the joint side) and ``"VM"`` (the motor
        velocity: Eq. 11-12 applied to MP, for a robot without the arm-side encoder). A column
        of the same name is recomputed where it stands.

    Returns
    -------
    Recording
        With the new columns appended. Their :class:`SignalInfo` names the formula; V has the
        grid's interval, FE and TORSION the coarser interval of their inputs (a staircase input
        makes a staircase). Compute derived signals before windowing, so V has no window ends;
        V and VM are computed within each segment of a recording with gaps
        (:func:`segment_velocity`).

    Raises
    ------
    ChannelError
        An input column is missing.
    ParameterError
        An unknown derived signal.

    References
    ----------
    Paper section 3.3, Eq. 11-12 (V); section 4 (V as a node of every network).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0, 1.0, 2.0], "AP": [0.0, 0.5, 1.5]},
    ...                     index=pd.Index([0.0, 0.002, 0.004], name="time"))
    >>> info = {c: SignalInfo(c, "posn", "double", 0.002) for c in data}
    >>> rec = add_derived_signals(Recording(data, {}, info), ["FE", "V"])
    >>> rec.data["FE"].tolist(), rec.data["V"].round(1).tolist()
    ([0.0, 0.5, 0.5], [312.5, 375.0, 437.5])
    """
    data = recording.data.copy()
    infos = dict(recording.signals)
    dt = recording.sample_period
    for name in signals:
        if name not in DERIVED_SIGNALS:
            raise ParameterError(f"signals: {name!r} is not one of {sorted(DERIVED_SIGNALS)}")
        inputs, description = DERIVED_SIGNALS[name]
        columns = [_column(recording, column, name) for column in inputs]
        if name in ("V", "VM"):
            values, interval, units = segment_velocity(recording, columns[0]), dt, "velo"
        else:
            values = columns[0] - columns[1]
            interval = max(recording.signals[column].interval for column in inputs)
            units = "posn"
        data[name] = values  # an existing column is replaced in place
        given = recording.signals[inputs[0]].unit if inputs[0] in recording.signals else None
        unit = None if given is None else f"{given}/s" if name in ("V", "VM") else given
        infos[name] = SignalInfo(description, units, "double", interval, unit)
    data = data[list(infos)]
    return replace(recording, data=data, signals=infos)


def trim(
    recording: Recording,
    *,
    start: float | None = None,
    stop: float | None = None,
    margin: float = 0.2,
    reference: str = "RP",
    standstill: float = 1e-4,
) -> Recording:
    """Cut a recording to a time range, or to its motion with a margin.

    Parameters
    ----------
    recording : Recording
    start, stop : float, optional
        A time range in seconds (``start <= time < stop``); either end may be left out. Given
        either, the motion is not looked at.
    margin : float
        Seconds kept before the first and after the last moving tick (clipped to the recording).
    reference : str
        The column whose motion counts (the position set-point RP).
    standstill : float
        A tick moves when the reference speed (:func:`reference_speed`) exceeds this fraction
        of its maximum; the same rule as :func:`funcnet.robot.detect_phases`.

    Returns
    -------
    Recording

    Raises
    ------
    SignalError
        The reference never moves.
    WindowError
        The range is not inside the recording.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> rp = np.concatenate([np.zeros(10), np.arange(1.0, 11.0), np.full(10, 10.0)])
    >>> data = pd.DataFrame({"RP": rp}, index=pd.Index(np.arange(30) * 0.1, name="time"))
    >>> rec = Recording(data, {}, {"RP": SignalInfo("RP", None, None, 0.1)}, sample_period=0.1)
    >>> moving = trim(rec, margin=0.2)
    >>> float(moving.data.index[0]), float(moving.data.index[-1])
    (0.7, 2.2)
    >>> trim(rec, start=1.0, stop=1.5).data.index.tolist()
    [1.0, 1.1, 1.2, 1.3, 1.4]
    """
    if margin < 0 or not math.isfinite(margin):
        raise ParameterError(f"margin: must be >= 0 seconds, got {margin}")
    index = recording.data.index
    t0, end = float(index[0]), float(index[0]) + recording.duration
    if start is not None or stop is not None:
        return recording.window(t0 if start is None else start, end if stop is None else stop)
    speed = reference_speed(recording, reference)
    moving = np.flatnonzero(speed > standstill * speed.max())
    if moving.size == 0:
        raise SignalError(f"{recording.source or '<recording>'}: {reference} never moves")
    first = float(index[moving[0]]) - margin
    last = float(index[moving[-1]]) + recording.sample_period + margin
    return recording.window(max(first, t0), min(last, end))


def staircase_signals(recording: Recording, columns: Sequence[str] | None = None) -> list[str]:
    """Columns whose native interval is coarser than the grid: staircases on it.

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0, 1.0], "AP": [0.0, 0.0]},
    ...                     index=pd.Index([0.0, 0.002], name="time"))
    >>> info = {"RP": SignalInfo("RP", None, None, 0.002),
    ...         "AP": SignalInfo("AP", None, None, 0.004)}
    >>> staircase_signals(Recording(data, {}, info))
    ['AP']
    """
    columns = list(recording.data.columns) if columns is None else list(columns)
    period = recording.sample_period
    return [
        column
        for column in columns
        if column in recording.signals
        and recording.signals[column].interval > period * (1 + _TICK_TOLERANCE)
    ]


def staircase_warning(recording: Recording, columns: Sequence[str] | None = None,
                      where: str | None = None) -> StaircaseWarning | None:
    """The warning that ``columns`` are staircases on the grid (:func:`staircase_signals`), in
    the one wording the library, the study and the command line give it; ``None`` if none is.

    ``where`` names the recording (default: its source).

    Examples
    --------
    >>> import pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0, 1.0], "AP": [0.0, 0.0]},
    ...                     index=pd.Index([0.0, 0.002], name="time"))
    >>> info = {"RP": SignalInfo("RP", None, None, 0.002),
    ...         "AP": SignalInfo("AP", None, None, 0.004)}
    >>> print(staircase_warning(Recording(data, {}, info), where="t.xml"))
    t.xml: AP change at most every 4 ms but are analysed on the 2 ms grid (staircases); \
funcnet.robot.resample decimates or interpolates them
    """
    staircases = staircase_signals(recording, columns)
    if not staircases:
        return None
    where = (recording.source or "<recording>") if where is None else where
    coarsest = max(recording.signals[s].interval for s in staircases)
    return StaircaseWarning(
        f"{where}: {', '.join(staircases)} change at most every {coarsest * 1e3:g} ms but are "
        f"analysed on the {recording.sample_period * 1e3:g} ms grid (staircases); "
        "funcnet.robot.resample decimates or interpolates them",
        problem="staircase",
        signals=tuple(staircases),
    )


def _ticks(interval: float, period: float, name: str) -> int:
    ratio = interval / period
    ticks = round(ratio)
    if ticks < 1 or abs(ratio - ticks) > _TICK_TOLERANCE * max(ratio, 1):
        raise ParameterError(
            f"{name}: {interval:g} s is not a whole multiple of the grid's {period:g} s"
        )
    return ticks


def _phase(values: np.ndarray, step: int) -> int:
    """The grid phase of a signal native every ``step`` ticks: where its first value is."""
    recorded = np.flatnonzero(~np.isnan(values))
    return int(recorded[0] % step) if recorded.size else 0


def resample(
    recording: Recording, period: float | None = None, *, method: str = "decimate"
) -> Recording:
    """Bring signals of mixed native rates onto one grid without staircases.

    Parameters
    ----------
    recording : Recording
    period : float, optional
        The new grid interval in seconds, a whole multiple of ``recording.sample_period``.
        Default: the coarsest native interval for ``"decimate"`` (4 ms in a trace with IPO
        signals), the current grid for ``"interpolate"``.
    method : {"decimate", "interpolate"}
        ``"decimate"`` keeps every k-th tick (no filtering: each kept value is a recorded one),
        on the ticks where the coarsest signals are written (in the real trace the IPO signals
        are written at 2, 6, 10, ... ms, so those ticks are kept). ``"interpolate"`` first
        replaces each staircase by straight lines between its native samples (held after the
        last one, NaN before the first), then keeps every k-th tick of the requested period.

    Returns
    -------
    Recording
        ``sample_period`` = ``period``; each signal's interval becomes ``max(interval, period)``
        (``period`` for the interpolated ones), so :func:`staircase_signals` is empty when every
        native interval divides ``period``.

    Raises
    ------
    ParameterError
        Unknown method, or a period / native interval that is not a whole multiple of the grid.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot.recording import Recording, SignalInfo
    >>> data = pd.DataFrame({"AC": [1.0, 2.0, 3.0, 4.0, 5.0],
    ...                      "AP": [np.nan, 10.0, 10.0, 12.0, 12.0]},
    ...                     index=pd.Index([0.0, 0.002, 0.004, 0.006, 0.008], name="time"))
    >>> info = {"AC": SignalInfo("AC", None, None, 0.002),
    ...         "AP": SignalInfo("AP", None, None, 0.004)}
    >>> rec = Recording(data, {}, info)
    >>> resample(rec).data
              AC    AP
    time
    0.002  2.0  10.0
    0.006  4.0  12.0
    >>> resample(rec, method="interpolate").data["AP"].tolist()
    [nan, 10.0, 11.0, 12.0, 12.0]
    """
    if method not in ("decimate", "interpolate"):
        raise ParameterError(f"method: {method!r} is not 'decimate' or 'interpolate'")
    grid = recording.sample_period
    intervals = {column: info.interval for column, info in recording.signals.items()}
    if period is None:
        period = max(intervals.values(), default=grid) if method == "decimate" else grid
    step = _ticks(period, grid, "period")
    data = recording.data.copy()
    infos = {}
    coarsest, phase = grid, 0
    for column, interval in intervals.items():
        native = _ticks(interval, grid, f"signal {column!r} interval")
        values = data[column].to_numpy(dtype=np.float64)
        if native > 1 and method == "interpolate":
            samples = np.arange(_phase(values, native), len(values), native)
            samples = samples[~np.isnan(values[samples])]
            if samples.size:
                ticks = np.arange(len(values))
                filled = np.interp(ticks, samples, values[samples])
                filled[: samples[0]] = np.nan
                data[column] = filled
            interval = grid
        elif interval > coarsest:
            coarsest, phase = interval, _phase(values, native) % step
        infos[column] = replace(recording.signals[column], interval=max(interval, period))
    kept = data.iloc[phase::step]
    return replace(recording, data=kept, signals=infos, sample_period=period)
