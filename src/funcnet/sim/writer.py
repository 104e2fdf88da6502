"""Write signals as a SINUMERIK Solution Line trace (XML), as the controller's Trace exports it.

The layout follows a real 840D sl export (``data/sinumerik/axis7-braking-trace.xml``): a
``traceSession`` with the capture settings (``traceCaptureSetup_V20``: ``sampleRateSettings`` and
``signalSettings``) and one ``traceData/dataFrame`` holding a ``frameHeader`` (``startTime``,
``stopInc`` = duration), one ``dataSignal`` per signal (``id="fN"``, ``interval``,
``datapointCount``, ``name``, ``unitsType``, ``dataType``) and the records
``<rec time="..." f1="..." .../>``. Records are *sparse*, as the controller writes them: a value
appears only when it differs, at the written precision, from the last value written for that
signal, and a record in which nothing changed is left out. As in the real export the first and
the last record carry every signal. Numbers have six decimals (the real file's format: degrees
and amperes to 1e-6); times too.

The display settings (``traceDisplaySetup``) are optional in the format and not written.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import pandas as pd

from funcnet._io import atomic_path
from funcnet.errors import ParameterError, SignalError

__all__ = ["write_trace", "role_names", "SIGNALS", "DEFAULT_START_TIME"]

#: Role -> (SINUMERIK signal name without the ``[u1, axis]`` suffix, description, unitsType,
#: dataType): the names the default channel map of :mod:`funcnet.robot.io.channels` assigns.
SIGNALS: dict[str, tuple[str, str, str, str]] = {
    "RP": ("/Nck/!SD/nckServoDataCmdPos2ndEnc64", "Position setpoint (64 bit)", "posn", "double"),
    "AP": (
        "/Nck/!SEMA/measPos2",
        "Actual position value for measuring system 2.",
        "posn",
        "double",
    ),
    "MP": (
        "/Nck/!SEMA/measPos1",
        "Actual position value for measuring system 1.",
        "posn",
        "double",
    ),
    "RC": (
        "/Nck/!SD/nckServoDataCmdCurr32",
        "Torque-prod. Current setpoint i(q) (32 bit)",
        "current",
        "float",
    ),
    "AC": (
        "/Nck/!SD/nckServoDataActCurr32",
        "Torque-prod. Current act. Val. i(q) (32 bit)",
        "current",
        "float",
    ),
}

#: ``frameHeader@startTime`` of a trace whose wall-clock start does not matter (simulations):
#: fixed, so that the same input gives the same bytes.
DEFAULT_START_TIME = "2000-01-01T00:00:00.000Z"

_DECIMALS = 6


def _formatted(values: np.ndarray) -> list[str]:
    """Six-decimal strings; ``-0.000000`` is written as ``0.000000``."""
    rounded = np.round(values.astype(np.float64), _DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0
    return [f"{v:.6f}" for v in rounded.tolist()]


def _strides(data: pd.DataFrame, intervals: Mapping[str, float] | None,
             interval: float) -> dict[str, int]:
    """Each signal's own logging interval in ticks of the grid, checked."""
    strides = {}
    for name, own_interval in dict(intervals or {}).items():
        stride = own_interval / interval
        if name not in data.columns or not (stride >= 1 and abs(stride - round(stride)) < 1e-6):
            raise ParameterError(
                f"write_trace: intervals[{name!r}] must be a multiple of the grid's step "
                f"{interval:g} s for a column of data, got {own_interval!r}"
            )
        strides[name] = round(stride)
    return strides


def _records(times: Sequence[str], columns: Sequence[Sequence[str]],
             column_strides: Sequence[int]) -> list[str]:
    """The ``<rec>`` lines: a value only where it changed on its own grid, all at the end."""
    ids = [f" f{number}=" for number in range(1, len(columns) + 1)]
    last = len(times) - 1
    previous: list[str | None] = [None] * len(columns)
    lines = []
    for row, stamp in enumerate(times):
        fields = []
        for k, column in enumerate(columns):
            if row % column_strides[k] and row != last:
                continue  # not a tick of this signal's own grid
            value = column[row]
            if value != previous[k] or row == last:
                fields.append(f'{ids[k]}"{value}"')
                previous[k] = value
        if fields:
            lines.append(f'  <rec time="{stamp}"{"".join(fields)}/>')
    return lines


def write_trace(
    path: str | os.PathLike[str],
    data: pd.DataFrame,
    *,
    axis: int = 1,
    session_name: str = "funcnet",
    start_time: str = DEFAULT_START_TIME,
    drive_period: float | None = None,
    intervals: Mapping[str, float] | None = None,
) -> Path:
    """Write role signals to ``path`` as a SINUMERIK Solution Line trace (XML), atomically.

    Parameters
    ----------
    path : path-like
        The ``.xml`` file to write (its directory is created).
    data : pandas.DataFrame
        Index: time in s on a uniform grid (the sampling interval is its step); columns: a
        subset of RP, AP, MP (deg), RC, AC (A), written under the SINUMERIK names of
        :data:`SIGNALS` for ``axis``, in the order given.
    axis : int
        Machine axis number of the ``[u1, axis]`` suffix.
    session_name : str
        ``sessionSettings@sessionName`` (escaped as XML).
    start_time : str
        ``frameHeader@startTime`` (ISO 8601).
    drive_period : float, optional
        s, written as ``sampleRateSettings@driveSampleRate1`` when given.
    intervals : mapping, optional
        Role -> its own logging interval in s, a multiple of the grid's step (the IPO signals
        ``measPos1/2`` every 4 ms in a real trace): written as that signal's ``interval``, and
        its values only at the ticks of its own grid (counted from the first tick).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ParameterError
        A column is not a role, the index is not a uniform time grid, or ``axis`` < 1.
    SignalError
        A column holds NaN or infinity.

    References
    ----------
    .. [1] El Dabett, Hansen & Geier, section 3.2-3.3: 500 Hz XML traces of the SINUMERIK
       840D sl, whose numeric fields are kept.

    Examples
    --------
    >>> import tempfile, pathlib, pandas as pd
    >>> frame = pd.DataFrame({"RP": [0.0, 0.0, 0.5], "AC": [1.0, 1.25, 1.25]},
    ...                      index=pd.Index([0.0, 0.002, 0.004], name="time"))
    >>> out = write_trace(pathlib.Path(tempfile.mkdtemp()) / "t.xml", frame)
    >>> for line in out.read_text().splitlines():
    ...     if "<rec" in line:
    ...         print(line.strip())
    <rec time="0.000000" f1="0.000000" f2="1.000000"/>
    <rec time="0.002000" f2="1.250000"/>
    <rec time="0.004000" f1="0.500000" f2="1.250000"/>
    """
    unknown = [c for c in data.columns if c not in SIGNALS]
    if unknown or data.shape[1] == 0:
        raise ParameterError(f"write_trace: columns must be among {list(SIGNALS)}, got {unknown}")
    if not isinstance(axis, int) or axis < 1:
        raise ParameterError(f"write_trace: axis must be a positive integer, got {axis!r}")
    time = np.asarray(data.index, dtype=np.float64)
    steps = np.diff(time)
    if time.size < 2 or steps[0] <= 0 or not np.allclose(steps, steps[0], rtol=0, atol=1e-9):
        raise ParameterError("write_trace: the index must be a uniform, increasing time grid (s)")
    interval = float(steps[0])
    strides = _strides(data, intervals, interval)
    columns = []
    for name in data.columns:
        values = data[name].to_numpy(dtype=np.float64)
        if not np.isfinite(values).all():
            raise SignalError(f"write_trace: signal {name!r} holds NaN or infinity")
        columns.append(_formatted(values))
    times = [f"{t:.6f}" for t in time.tolist()]

    lines = [
        '<?xml version="1.0" encoding="utf-8" ?>',
        "<!--XML file written by funcnet in the SINUMERIK Solution Line Trace format-->",
        '<traceSession version="01.00.03.02">',
        "<traceCaptureSetup_V20>",
        f" <sessionSettings sessionName={quoteattr(session_name)}/>",
        " <sampleRateSettings"
        + (f' driveSampleRate1="{drive_period:.8f}"' if drive_period else "")
        + f' servoSampleRate="{interval:g}" ipo2SampleRate="{2 * interval:g}"'
        f' ipo1SampleRate="{2 * interval:g}"/>',
        " <signalSettings>",
    ]
    names = role_names(axis)
    signal_attrs = []
    for number, name in enumerate(data.columns, start=1):
        _, description, units, dtype = SIGNALS[name]
        full = names[name]
        stride = strides.get(name, 1)
        signal_attrs.append((number, full, description, units, dtype, stride))
        lines.append(
            f'  <signal domain="NCU_1" event="255" description={quoteattr(description)}'
            f' displayRes="5" eventChannel="1" key="s{number}" name={quoteattr(full)}'
            f' unitsType="{units}" dataType="{dtype}"/>'
        )
    lines += [
        " </signalSettings>",
        "</traceCaptureSetup_V20>",
        "",
        '<traceData dataFrames="1">',
        " <dataFrame>",
        '  <frameHeader stopTriggerInc="0.000000" startTriggerInc="0.000000" dropOuts="0"'
        f' startTime={quoteattr(start_time)} stopInc="{time[-1] - time[0]:.6f}"/>',
    ]
    for number, full, description, units, dtype, stride in signal_attrs:
        lines.append(
            f'  <dataSignal domain="NCU_1" interval="{interval * stride:.6f}" id="f{number}"'
            f' event="255" description={quoteattr(description)} displayRes="5"'
            f' eventChannel="1" datapointCount="{(time.size + stride - 1) // stride}"'
            f' key="s{number}" name={quoteattr(full)} unitsType="{units}" dataType="{dtype}"/>'
        )
    lines += _records(times, columns, [attrs[5] for attrs in signal_attrs])
    lines += [" </dataFrame>", "</traceData>", "</traceSession>", ""]

    target = Path(path)
    with atomic_path(target) as tmp:
        tmp.write_bytes("\n".join(lines).encode("utf-8"))
    return target


def role_names(axis: int = 1) -> Mapping[str, str]:
    """Role -> full SINUMERIK signal name (with ``[u1, axis]``) as :func:`write_trace` writes.

    Examples
    --------
    >>> role_names(1)["AP"]
    '/Nck/!SEMA/measPos2 [u1, 1]'
    """
    return {role: f"{spec[0]} [u1, {axis}]" for role, spec in SIGNALS.items()}
