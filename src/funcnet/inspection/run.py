"""The inspection step of ``funcnet inspect``: trace files read and inspected, one at a time.

:func:`inspect_file` is what ``funcnet inspect FILE`` computes before anything is drawn: it reads
the file (:func:`funcnet.robot.read_trace`) and hands the recording to
:func:`~funcnet.inspection.inspect_recording`, or, for a recording of several axes read without
``axis``, to :func:`~funcnet.inspection.inspect_robot`. :func:`inspect_files` does it for every
file of the command, each when its turn comes (:class:`FileInspections`), so that its page is
written before the next file is read; the report (:func:`funcnet.report.inspect.write_inspections`)
draws them.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any, Unpack

from funcnet.errors import ParameterError
from funcnet.inspection.repeated import RepeatedInspection, repetitions_of
from funcnet.inspection.robot import RobotInspection, inspect_robot
from funcnet.inspection.trace import TraceInspection, inspect_recording
from funcnet.parameters import EvidenceSettings, NetworkParameters, ParameterOverrides, resolve
from funcnet.robot import read_trace
from funcnet.robot.io.channels import ChannelMap, channel_map
from funcnet.robot.units import in_axis_units

__all__ = ["inspect_file", "inspect_files", "FileInspections"]


def inspect_file(
    path: str | os.PathLike[str],
    *,
    channels: Any = None,
    axis: int | None = None,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    progress: Callable[[int, int, str], None] | None = None,
    evidence_options: EvidenceSettings | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> TraceInspection | RobotInspection:
    """Read one trace file and inspect it: one axis, or a robot of several.

    Parameters
    ----------
    path : path-like
        A trace file (:func:`funcnet.robot.read_trace`: SINUMERIK XML, CSV, Parquet, MATLAB,
        HDF5).
    channels, axis
        As :func:`funcnet.robot.read_trace`. A file of several axes read without ``axis`` is
        inspected as a robot (``signals`` then names the robot network's nodes, ``A1.RP``, ...).
    signals, parameters, evidence, progress, evidence_options, **overrides
        As :func:`~funcnet.inspection.inspect_recording`.

    Returns
    -------
    TraceInspection or RobotInspection

    Raises
    ------
    TraceError
        The file cannot be read.
    ParameterError
        A bad network parameter or evidence option.

    Examples
    --------
    >>> inspect_file("missing.xml")
    Traceback (most recent call last):
        ...
    funcnet.errors.TraceError: missing.xml: no such file
    """
    # Thresholds, arcmin and arcsec are in degrees: angles in rad converted (said); a
    # set-point that never moves is kept, for the page of an axis at rest.
    recording, _ = in_axis_units(read_trace(path, channels=channels, axis=axis,
                                         keep_setpoint=True))
    if recording.axes:
        return inspect_robot(recording, signals=signals, parameters=parameters,
                             evidence=evidence, progress=progress,
                             evidence_options=evidence_options, **overrides)
    return inspect_recording(recording, signals=signals, parameters=parameters,
                             evidence=evidence, progress=progress,
                             evidence_options=evidence_options, **overrides)


class FileInspections:
    """Trace files inspected one after the other, each when iteration reaches it.

    Iterating gives ``(path, inspection)`` per file, in the order given: the file is read and
    inspected (:func:`inspect_file`) only then, and nothing of it is kept unless ``repeated``,
    so a caller that draws each page before asking for the next holds one file at a time.
    Made by :func:`inspect_files`; iterate it once.

    Attributes
    ----------
    paths : tuple of pathlib.Path
        The trace files, in order.
    channels : ChannelMap
        The channel map the files are read with (its ``axis_names`` name the axes on pages).
    axis : int or None
        The axis read from each file, or None (a file of several axes: a robot).
    repeated : bool
        Whether :meth:`repetitions` is asked for: the single-axis inspections are kept for it.
    """

    def __init__(self, paths: Sequence[Path], *, channels: ChannelMap, axis: int | None,
                 repeated: bool, evidence_options: EvidenceSettings | None,
                 inspect: Callable[[Path], TraceInspection | RobotInspection]) -> None:
        self.paths = tuple(paths)
        self.channels = channels
        self.axis = axis
        self.repeated = repeated
        self._evidence_options = evidence_options
        self._inspect = inspect
        self._kept: list[TraceInspection] = []

    def __iter__(self) -> Iterator[tuple[Path, TraceInspection | RobotInspection]]:
        for path in self.paths:
            found = self._inspect(path)
            if self.repeated and isinstance(found, TraceInspection):
                self._kept.append(found)
            yield path, found

    def repetitions(self) -> RepeatedInspection | None:
        """The repetitions of the single-axis traces read together, once they are iterated.

        :func:`funcnet.inspection.repetitions_of` the inspections iteration gave (a robot's
        are not among them); None when there is none.
        """
        return repetitions_of(self._kept, self._evidence_options)


def inspect_files(
    *paths: str | os.PathLike[str],
    channels: Any = None,
    axis: int | None = None,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    evidence: bool = True,
    progress: Callable[[int, int, str], None] | None = None,
    evidence_options: EvidenceSettings | None = None,
    repeated: bool = False,
    **overrides: Unpack[ParameterOverrides],
) -> FileInspections:
    """Trace files to be read and inspected one after the other (:func:`inspect_file` each).

    The arguments are checked now, before any file is read; each file is read when the result
    is iterated.

    Parameters
    ----------
    *paths : path-like
        Trace files (:func:`funcnet.robot.read_trace`: SINUMERIK XML, CSV, Parquet, MATLAB,
        HDF5).
    channels, axis, signals, parameters, evidence, progress, evidence_options, **overrides
        As :func:`inspect_file`.
    repeated : bool
        Keep the single-axis inspections for :meth:`FileInspections.repetitions`.

    Returns
    -------
    FileInspections

    Raises
    ------
    ParameterError
        No trace, or a bad parameter.
    ChannelError
        The channel map cannot be read.

    Examples
    --------
    >>> inspect_files()
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: paths must name at least one trace file
    """
    if not paths:
        raise ParameterError.of("paths", "must name at least one trace file")
    p = resolve(parameters, overrides)
    cmap = channel_map(channels)

    def inspect(path: Path) -> TraceInspection | RobotInspection:
        return inspect_file(path, channels=channels, axis=axis, signals=signals, parameters=p,
                            evidence=evidence, progress=progress,
                            evidence_options=evidence_options)

    return FileInspections([Path(path) for path in paths], channels=cmap, axis=axis,
                           repeated=repeated, evidence_options=evidence_options, inspect=inspect)
