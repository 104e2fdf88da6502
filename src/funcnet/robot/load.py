"""A recording ready for analysis: read, on the wanted grid, with the derived signals it needs.

:func:`read_recording` is the one place that decides which derived signals (V, FE, TORSION) a
selection of nodes needs, that computes them on the whole recording before any window is cut,
and that recomputes them from the resampled inputs after a resampling -- the study, the paper's
analyses and the command line all read traces through it.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace

import pandas as pd

from funcnet.errors import ParameterError
from funcnet.robot.axes import qualified, split_qualified
from funcnet.robot.channels import ChannelMap
from funcnet.robot.preprocess import DERIVED_SIGNALS, add_derived_signals, resample as resampled
from funcnet.robot.recording import Recording, read_trace
from funcnet.robot.units import in_axis_units

__all__ = ["read_recording", "prepare_recording", "derived_signals_needed", "RESAMPLE_METHODS"]

#: The ``resample`` methods of :func:`read_recording` (:func:`funcnet.robot.resample`'s).
RESAMPLE_METHODS = ("decimate", "interpolate")


def derived_signals_needed(
    signals: Sequence[str] | None, columns: Iterable[str]
) -> tuple[str, ...]:
    """The derived signals a selection of nodes needs that a recording does not have.

    Parameters
    ----------
    signals : sequence of str or None
        The nodes that will be used; None means the default nodes, which include V when AP is
        there to derive it from.
    columns : iterable of str
        The recording's columns.

    Returns
    -------
    tuple of str
        In the order of :data:`funcnet.robot.preprocess.DERIVED_SIGNALS`.

    Examples
    --------
    >>> derived_signals_needed(None, ["RP", "AP"])
    ('V',)
    >>> derived_signals_needed(["RP", "TORSION", "FE"], ["RP", "AP", "MP"])
    ('FE', 'TORSION')
    >>> derived_signals_needed(["V"], ["AP", "V"])
    ()
    """
    present = set(columns)
    if signals is None:
        signals = ("V",) if "AP" in present else ()
    return tuple(s for s in DERIVED_SIGNALS if s in signals and s not in present)


def read_recording(
    path: str | os.PathLike[str],
    *,
    signals: Sequence[str] | None = None,
    channels: ChannelMap | Mapping[str, str] | str | os.PathLike[str] | None = None,
    axis: int | None = None,
    resample: str | None = None,
) -> Recording:
    """Read a trace and add the derived signals a selection needs (V by default).

    Parameters
    ----------
    path : path-like
        Trace file: SINUMERIK XML, CSV or Parquet (:func:`~funcnet.robot.read_trace`).
    signals : sequence of str, optional
        The nodes that will be used; the derived ones among them (V, FE, TORSION,
        :func:`~funcnet.robot.add_derived_signals`) are computed on the whole recording, before
        any windowing, so that no window loses samples at its ends. Default: V, when the trace
        has AP.
    channels, axis
        Passed to :func:`~funcnet.robot.read_trace`.
    resample : {"decimate", "interpolate"}, optional
        Bring the signals onto one grid without staircases (:func:`~funcnet.robot.resample`
        with its default period); the derived signals are then recomputed from the resampled
        inputs, so that V is the velocity of the decimated or interpolated AP. ``"interpolate"``
        also puts time stamps that are off their grid onto it (``off_grid="interpolate"`` of
        :func:`~funcnet.robot.read_trace`).

    Returns
    -------
    Recording
        Angles stated in rad converted to degrees (:func:`funcnet.robot.units.in_axis_units`,
        said in one warning). With the derived signals as its last columns. In a recording of
        several axes (columns
        ``A1.RP``, ...) a derived signal is named with its axis (``A1.V``) and computed from
        that axis's inputs; none is derived unless named.

    Raises
    ------
    ParameterError
        ``resample`` is not one of :data:`RESAMPLE_METHODS` (checked before the file is read),
        or a derived signal is unknown.
    TraceError
        The file cannot be read (see :func:`~funcnet.robot.read_trace`).
    ChannelError
        A derived signal's input is not in the trace.

    References
    ----------
    Paper section 3.3, Eq. 11-12 (V from AP).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "trace.csv"
    >>> _ = path.write_text("time,AP,RP\\n0,0,0\\n0.002,1,1\\n0.004,3,2\\n0.006,6,3\\n")
    >>> read_recording(path).data.columns.tolist()
    ['AP', 'RP', 'V']
    >>> read_recording(path, signals=["RP", "FE"]).data["FE"].tolist()
    [0.0, 0.0, -1.0, -3.0]
    """
    _check_resample(resample)
    off_grid = "interpolate" if resample == "interpolate" else "error"
    # A set-point that never moves is kept: where the axis rests is said, not a missing RP.
    recording = read_trace(path, channels=channels, axis=axis, off_grid=off_grid,
                           keep_setpoint=True)
    # Phases and thresholds are in degrees: angles in rad converted, each said.
    recording, _ = in_axis_units(recording)
    return prepare_recording(recording, signals=signals, resample=resample)


def _check_resample(resample: str | None) -> None:
    if resample is not None and resample not in RESAMPLE_METHODS:
        raise ParameterError.of(
            "resample", f"must be one of {', '.join(RESAMPLE_METHODS)}; got {resample!r}"
        )


def prepare_recording(
    recording: Recording,
    *,
    signals: Sequence[str] | None = None,
    resample: str | None = None,
) -> Recording:
    """A recording already read, with the derived signals a selection needs, on one grid.

    What :func:`read_recording` does after reading the file.

    Parameters
    ----------
    recording : Recording
        As :func:`~funcnet.robot.read_trace` returns it.
    signals, resample
        As :func:`read_recording`.

    Returns
    -------
    Recording
        With the derived signals as its last columns (per axis in a recording of several axes,
        as :func:`read_recording`).

    Raises
    ------
    ParameterError
        ``resample`` is not one of :data:`RESAMPLE_METHODS`, or a derived signal is unknown.
    ChannelError
        A derived signal's input is not in the recording.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from funcnet.robot import Recording, SignalInfo
    >>> data = pd.DataFrame({"RP": [0.0, 1.0, 2.0, 3.0], "AP": [0.0, 0.0, 2.0, 2.0]},
    ...                     index=pd.Index([0.0, 0.002, 0.004, 0.006], name="time"))
    >>> info = {"RP": SignalInfo("RP", None, None, 0.002),
    ...         "AP": SignalInfo("AP", None, None, 0.004)}
    >>> ready = prepare_recording(Recording(data, {}, info), signals=["RP", "FE"],
    ...                           resample="interpolate")
    >>> ready.data["AP"].tolist(), ready.data["FE"].tolist()
    ([0.0, 1.0, 2.0, 2.0], [0.0, 0.0, 0.0, 1.0])
    """
    _check_resample(resample)
    if recording.axes:
        derived = tuple(
            name for name in signals or ()
            if split_qualified(name)[1] in DERIVED_SIGNALS and name not in recording.data
        )
    else:
        derived = derived_signals_needed(signals, recording.data.columns)
    if derived:
        recording = _derive(recording, list(derived))
    if resample is None:
        return recording
    # Every derived column (added here or stored in the file by an earlier run) is recomputed
    # from the resampled inputs; a column that is a role is the controller's, kept as recorded.
    again = [
        c for c in recording.data.columns
        if split_qualified(c)[1] in DERIVED_SIGNALS and c not in recording.roles
    ]
    return _derive(resampled(recording, method=resample), again)


def _derive(recording: Recording, names: list[str]) -> Recording:
    """:func:`add_derived_signals`, per axis for the qualified names of a multi-axis recording."""
    if not recording.axes:
        return add_derived_signals(recording, names)
    per_axis: dict[int, list[str]] = {}
    for name in names:
        number, base = split_qualified(name)
        if number is None or number not in recording.axes:
            # Not derivable on its own: the same error as a one-axis recording gives.
            return add_derived_signals(recording, names)
        per_axis.setdefault(number, []).append(base)
    columns = {}
    signals = dict(recording.signals)
    for number, bases in per_axis.items():
        one = add_derived_signals(recording.for_axis(number), bases)
        for base in bases:
            columns[qualified(number, base)] = one.data[base]
            signals[qualified(number, base)] = one.signals[base]
    data = pd.concat([recording.data, pd.DataFrame(columns)], axis=1)
    return replace(recording, data=data, signals=signals)
