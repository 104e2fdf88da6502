"""A recording made ready for analysis: on the wanted grid, with the derived signals it needs.

:func:`prepare_recording` is the one place that decides which derived signals (V, FE, TORSION) a
selection of nodes needs, that computes them on the whole recording before any window is cut,
and that recomputes them from the resampled inputs after a resampling. The steps themselves are
:mod:`funcnet.robot.preprocess`'s; :func:`funcnet.robot.read_recording` reads a file and
prepares it -- the study, the paper's analyses and the command line all read traces through it.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import replace

import pandas as pd

from funcnet.errors import ParameterError
from funcnet.robot.axes import qualified, split_qualified
from funcnet.robot.preprocess import DERIVED_SIGNALS, add_derived_signals, resample as resampled
from funcnet.robot.recording import Recording

__all__ = ["prepare_recording", "derived_signals_needed", "check_resample", "RESAMPLE_METHODS"]

#: The ``resample`` methods of :func:`prepare_recording` and :func:`funcnet.robot.read_recording`
#: (:func:`funcnet.robot.resample`'s).
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


def check_resample(resample: str | None) -> None:
    """Refuse a ``resample`` that is not one of :data:`RESAMPLE_METHODS` (None is none)."""
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

    What :func:`funcnet.robot.read_recording` does after reading the file.

    Parameters
    ----------
    recording : Recording
        As :func:`~funcnet.robot.read_trace` returns it.
    signals, resample
        As :func:`funcnet.robot.read_recording`.

    Returns
    -------
    Recording
        With the derived signals as its last columns (per axis in a recording of several axes,
        as :func:`funcnet.robot.read_recording`).

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
    check_resample(resample)
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
