"""Streaming, safe reader of SINUMERIK Solution Line trace XML (paper section 3.2-3.3).

A trace is a ``traceSession`` with capture and display setup sections (``traceCaptureSetup_V20``
and/or ``traceCaptureSetup``, the same for display) and ``traceData/dataFrame`` elements. A frame
holds a ``frameHeader`` (``startTime``, ``stopInc`` = duration in s), one ``dataSignal`` per signal
(``id="fN"``, ``interval``, ``name``, ``unitsType``, ``dataType``) and then sparse records
``<rec time="t" f4="..." f7="..."/>``: a value is written only when it changes.

How the records become a table (:func:`read_sinumerik`):

- The grid is uniform with the finest ``interval`` of the trace (2 ms on a 840D sl servo clock),
  starting at the first frame's start; every tick through the frame's ``stopInc`` is present.
- A signal's value at a tick is the last value written at or before it in the same frame; before
  its first record in a frame it is NaN (in the real trace the 4 ms IPO signals first appear at
  2 ms). Nothing is interpolated or shifted; a record off the grid is an error.
- A later frame is placed by its ``startTime`` relative to the first frame's (rounded to the grid:
  the controller writes ``startTime`` in whole milliseconds); without usable start times frames
  follow each other tick by tick. Ticks between frames are NaN; values are not carried across
  frames; overlapping frames are an error.

Safety: lxml's ``iterparse`` with ``resolve_entities=False``, ``no_network=True``,
``huge_tree=False`` (libxml2's limits on depth, text size and entity amplification stay on) and
``load_dtd=False``; any DOCTYPE is rejected before the first element is used (a trace never has
one), so neither billion laughs nor external entities are expanded. lxml rather than defusedxml
because it reports each element's source line (for error messages), and its C parser keeps the
45 s reference trace well under a second. Memory: every element is cleared at its end and its
finished siblings deleted, so the tree never holds more than the current path; the records are
kept as compact (tick, value) arrays, and the dense grid is built once at the end, after a check
that it is of a size the file can justify.
"""

from __future__ import annotations

import math
import os
from array import array
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path
from typing import BinaryIO

import numpy as np
from lxml import etree

from funcnet.errors import ChannelError, TraceFormatError
from funcnet.robot.signals import SignalInfo, select_axis

__all__ = ["SinumerikTrace", "read_sinumerik", "GRID_BYTES_FLOOR", "GRID_BYTES_PER_FILE_BYTE"]

#: The dense grid (ticks x signals x 8 bytes) may take at least this many bytes ...
GRID_BYTES_FLOOR = 256 * 2**20
#: ... or this many per byte of the file. A real trace needs less than one (each record stands
#: for at most a few ticks); a hostile file (``time="1e12"``) is refused instead of allocated.
GRID_BYTES_PER_FILE_BYTE = 16

# A record's time must lie within this fraction of a tick from the grid.
_GRID_TOLERANCE = 1e-3
_SKIP = -1


@dataclass(frozen=True)
class SinumerikTrace:
    """The signals of one trace on their common grid.

    Attributes
    ----------
    signals : tuple of SignalInfo
        One per column of ``values``, in the order of the first data frame.
    values : ndarray, shape (n_ticks, n_signals)
        float64, carried forward within each frame, NaN where no value is recorded yet.
    sample_period : float
        Grid interval in seconds (the finest ``interval``).
    start_time : str or None
        The first frame's ``startTime``.
    axis : int or None
        The axis read.
    """

    signals: tuple[SignalInfo, ...]
    values: np.ndarray
    sample_period: float
    start_time: str | None
    axis: int | None


@dataclass
class _Frame:
    number: int
    start_time: str | None = None
    stop_inc: float | None = None
    ids: dict[str, int] = field(default_factory=dict)  # dataSignal id -> index in declared
    declared: list[tuple[str, float | None, dict[str, str]]] = field(default_factory=list)
    columns: dict[str, int] = field(default_factory=dict)  # rec attribute -> column or _SKIP
    offset: int | None = None  # tick of the frame's time 0 on the common grid
    last_tick: int = -1
    records: int = 0


class _Reader:
    """State of one pass over a trace file."""

    def __init__(self, path: Path, axis: int | None) -> None:
        self.path = path
        self.axis = axis
        self.axis_chosen = False
        self.servo_period: float | None = None
        self.setup_signals: dict[str, dict[str, str]] = {}
        self.columns: dict[str, int] = {}  # full signal name -> column
        self.infos: list[SignalInfo] = []
        self.ticks: list[array] = []
        self.values: list[array] = []
        self.frames: list[_Frame] = []
        self.frame: _Frame | None = None
        self.period: float | None = None
        self.first_start: datetime | None = None
        self.end_tick = -1  # last tick of the previous frames on the common grid

    def error(self, message: str, line: int | None = None) -> TraceFormatError:
        where = "" if line is None else f"line {line}: "
        return TraceFormatError(self.path, where + message)

    def doctype_refused(self, found: str, line: int | None, detail: str = "") -> TraceFormatError:
        at = "" if line is None else f" at line {line}"
        return TraceFormatError(
            self.path,
            f"{found}{at} refused: a trace has none (entity expansion is never done{detail})",
        )

    def number(self, element: etree._Element, key: str, *, positive: bool = False) -> float:
        text = element.get(key)
        try:
            value = float(text)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            value = math.nan
        if not math.isfinite(value) or (positive and value <= 0):
            kind = "a positive number" if positive else "a number"
            raise self.error(f"<{element.tag} {key}={text!r}> must be {kind}", element.sourceline)
        return value

    # -- elements -------------------------------------------------------------------------------

    def check_root(self, element: etree._Element) -> None:
        tree = element.getroottree()
        dtd = tree.docinfo.internalDTD
        if tree.docinfo.doctype or dtd is not None:
            entities = [] if dtd is None else [entity.name for entity in dtd.iterentities()]
            found = "DOCTYPE declaration" + (
                f" with entity declarations ({', '.join(entities[:3])}"
                f"{', ...' if len(entities) > 3 else ''})"
                if entities
                else ""
            )
            raise self.doctype_refused(found, _doctype_line(self.path))
        root = tree.getroot()
        if root.tag != "traceSession":
            raise self.error(
                f"not a SINUMERIK trace: the root element is <{root.tag}>, not <traceSession>",
                root.sourceline,
            )

    def setup_element(self, element: etree._Element) -> None:
        if element.tag == "sampleRateSettings" and element.get("servoSampleRate") is not None:
            if self.servo_period is None:
                self.servo_period = self.number(element, "servoSampleRate", positive=True)
        elif element.tag == "signal" and element.get("name"):
            self.setup_signals.setdefault(element.get("name"), dict(element.attrib))

    def open_frame(self) -> _Frame:
        if self.frame is None:
            self.frame = _Frame(number=len(self.frames) + 1)
        return self.frame

    def frame_header(self, element: etree._Element) -> None:
        frame = self.open_frame()
        if frame.declared or frame.records:
            raise self.error("<frameHeader> must come first in its <dataFrame>", element.sourceline)
        frame.start_time = element.get("startTime")
        if element.get("stopInc") is not None:
            frame.stop_inc = self.number(element, "stopInc")

    def data_signal(self, element: etree._Element) -> None:
        frame = self.open_frame()
        if frame.records:
            raise self.error("<dataSignal> after the frame's records", element.sourceline)
        key, name = element.get("id"), element.get("name")
        if not key or not name:
            raise self.error("<dataSignal> needs an id and a name", element.sourceline)
        if key == "time" or key in frame.ids:
            raise ChannelError(
                self.path, f"line {element.sourceline}: data signal id {key!r} is declared twice"
            )
        if any(name == other for other, _, _ in frame.declared):
            raise ChannelError(
                self.path, f"line {element.sourceline}: signal {name!r} is declared twice"
            )
        interval = None
        if element.get("interval") is not None:
            interval = self.number(element, "interval", positive=True)
        frame.ids[key] = len(frame.declared)
        frame.declared.append(
            (name, interval, {**self.setup_signals.get(name, {}), **dict(element.attrib)})
        )

    def start_records(self, element: etree._Element) -> None:
        """Bind the frame's signal ids to columns; place the frame on the grid."""
        frame = self.frame
        assert frame is not None
        if element.getparent().tag != "dataFrame":
            raise self.error("<rec> outside a <dataFrame>", element.sourceline)
        if not frame.declared:
            raise self.error(
                f"data frame {frame.number} has records but no <dataSignal>", element.sourceline
            )
        names = [name for name, _, _ in frame.declared]
        if not self.axis_chosen:
            _, self.axis = select_axis(names, self.axis, self.path)
            self.axis_chosen = True
        keep, _ = select_axis(names, self.axis, self.path)
        if self.period is None:
            intervals = [
                interval
                for (_, interval, _), kept in zip(frame.declared, keep, strict=True)
                if kept and interval is not None
            ]
            self.period = min(intervals) if intervals else self.servo_period
            if self.period is None:
                raise self.error("no signal interval and no servoSampleRate: no time grid")
        frame.columns = {"time": _SKIP}
        for key, index in frame.ids.items():
            name, interval, attrs = frame.declared[index]
            if not keep[index]:
                frame.columns[key] = _SKIP
                continue
            if name not in self.columns:
                self.columns[name] = len(self.infos)
                self.infos.append(
                    SignalInfo(
                        name=name,
                        units_type=attrs.get("unitsType"),
                        data_type=attrs.get("dataType"),
                        interval=self.period if interval is None else interval,
                    )
                )
                self.ticks.append(array("q"))
                self.values.append(array("d"))
            frame.columns[key] = self.columns[name]
        frame.offset = self.frame_offset(frame, element.sourceline)

    def frame_offset(self, frame: _Frame, line: int) -> int:
        assert self.period is not None
        start = None
        if frame.start_time:
            try:
                start = datetime.fromisoformat(frame.start_time)
            except ValueError:
                raise self.error(
                    f"frame {frame.number}: startTime {frame.start_time!r} is not an ISO time"
                ) from None
        if not self.frames:
            self.first_start = start
            return 0
        if start is None or self.first_start is None:
            return self.end_tick + 1
        try:
            offset = round((start - self.first_start).total_seconds() / self.period)
        except TypeError:  # one start time with a time zone, the other without
            raise self.error(
                f"data frame {frame.number}: startTime {frame.start_time!r} and the first "
                "frame's cannot be compared (time zone given in one only)",
                line,
            ) from None
        if offset <= self.end_tick:
            raise self.error(
                f"data frame {frame.number} starts at {frame.start_time}, before the previous "
                "frame ends",
                line,
            )
        return offset

    def record(self, element: etree._Element) -> None:
        frame = self.frame
        if frame is None or frame.offset is None:
            frame = self.open_frame()
            self.start_records(element)
        assert self.period is not None and frame.offset is not None
        text = element.get("time")
        try:
            position = float(text) / self.period  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise self.error(f"<rec time={text!r}> must be a number", element.sourceline) from None
        if not math.isfinite(position) or position < 0:
            raise self.error(f"<rec time={text!r}> must be a time >= 0", element.sourceline)
        local = round(position)
        if abs(position - local) > _GRID_TOLERANCE:
            raise self.error(
                f"<rec time={text!r}> is not on the {self.period * 1e3:g} ms grid",
                element.sourceline,
            )
        tick = frame.offset + local
        if tick <= frame.last_tick:
            raise self.error(
                f"time goes backwards or repeats: <rec time={text!r}> after "
                f"{(frame.last_tick - frame.offset) * self.period:.6f} s",
                element.sourceline,
            )
        frame.last_tick = tick
        frame.records += 1
        columns = frame.columns
        ticks, values = self.ticks, self.values
        for key, value in element.items():
            column = columns.get(key)
            if column is None:
                raise ChannelError(
                    self.path,
                    f"line {element.sourceline}: <rec> refers to {key!r}, which no <dataSignal> "
                    f"of data frame {frame.number} declares",
                )
            if column == _SKIP:
                continue
            try:
                values[column].append(float(value))
            except ValueError:
                raise self.error(
                    f"signal {self.infos[column].name!r}: {value!r} is not a number",
                    element.sourceline,
                ) from None
            ticks[column].append(tick)

    def close_frame(self, element: etree._Element) -> None:
        frame = self.frame
        if frame is None or frame.records == 0:
            number = len(self.frames) + 1
            raise self.error(f"data frame {number} has no records", element.sourceline)
        if element.getparent() is None or element.getparent().tag != "traceData":
            raise self.error("<dataFrame> outside <traceData>", element.sourceline)
        assert self.period is not None and frame.offset is not None
        if frame.stop_inc is not None:
            stop = frame.offset + round(frame.stop_inc / self.period)
            if frame.last_tick > stop + 1:
                raise self.error(
                    f"data frame {frame.number} has records after its stopInc {frame.stop_inc:g} s",
                    element.sourceline,
                )
            frame.last_tick = max(frame.last_tick, stop)
        self.end_tick = frame.last_tick
        self.frames.append(frame)
        self.frame = None

    # -- the pass -------------------------------------------------------------------------------

    def parse(self) -> None:
        # The file is opened here, not by lxml, so that it is closed however the pass ends
        # (lxml keeps a file it opened itself until its iterator is exhausted).
        with open(self.path, "rb") as source:
            self._parse(source)

    def _parse(self, source: BinaryIO) -> None:
        if os.fstat(source.fileno()).st_size == 0:
            raise self.error("empty file: not a trace")
        context = etree.iterparse(
            source,
            events=("end",),
            resolve_entities=False,
            no_network=True,
            huge_tree=False,
            load_dtd=False,
            remove_comments=True,
            remove_pis=True,
        )
        first = True
        try:
            for _, element in context:
                if first:
                    self.check_root(element)
                    first = False
                tag = element.tag
                if tag == "rec":
                    self.record(element)
                elif tag == "frameHeader":
                    self.frame_header(element)
                elif tag == "dataSignal":
                    self.data_signal(element)
                elif tag == "dataFrame":
                    self.close_frame(element)
                elif tag in ("sampleRateSettings", "signal"):
                    self.setup_element(element)
                element.clear()
                while element.getprevious() is not None:
                    del element.getparent()[0]
        except etree.XMLSyntaxError as exc:
            line = exc.position[0] if exc.position else exc.lineno
            message = (exc.msg or str(exc)).split(", line ")[0]
            # An entity libxml2 refused to expand (external, amplified) stops the parse before
            # the first element could reach check_root: report the DOCTYPE that declared it.
            doctype = _doctype_line(self.path) if "entit" in message.lower() else None
            if doctype is not None:
                raise self.doctype_refused(
                    "DOCTYPE declaration", doctype, f"; at line {line}: {message.rstrip('.')}"
                ) from None
            # libxml2 says line 0 when there is no line to point at (an empty document).
            raise self.error(f"not well-formed XML: {message}", line or None) from None
        if self.frame is not None:
            raise self.error(f"data frame {self.frame.number} is not closed by </dataFrame>")
        if not self.frames:
            raise self.error("no <traceData>/<dataFrame> with records: not a trace, or empty")

    def result(self) -> SinumerikTrace:
        assert self.period is not None
        n_ticks = self.end_tick + 1
        n_signals = len(self.infos)
        grid_bytes = n_ticks * max(n_signals, 1) * 8
        budget = max(GRID_BYTES_FLOOR, GRID_BYTES_PER_FILE_BYTE * os.path.getsize(self.path))
        if grid_bytes > budget:
            raise self.error(
                f"the records span {n_ticks * self.period:g} s ({n_ticks} ticks of "
                f"{self.period:g} s), more than a file of this size can hold; refused"
            )
        values = np.full((n_ticks, n_signals), np.nan)
        for column in range(n_signals):
            ticks = np.frombuffer(self.ticks[column], dtype=np.int64)
            if ticks.size == 0:
                raise ChannelError(
                    self.path, f"signal {self.infos[column].name!r} is declared but never recorded"
                )
            recorded = np.frombuffer(self.values[column], dtype=np.float64)
            bad = ~np.isfinite(recorded)
            if bad.any():
                first = int(np.argmax(bad))
                raise self.error(
                    f"signal {self.infos[column].name!r}: {recorded[first]} at "
                    f"{ticks[first] * self.period:.6f} s is not a finite number"
                )
            values[ticks, column] = recorded
            self.ticks[column] = self.values[column] = array("d")  # free as we go
        for frame in self.frames:
            assert frame.offset is not None
            _carry_forward(values[frame.offset : frame.last_tick + 1])
        return SinumerikTrace(
            signals=tuple(self.infos),
            values=values,
            sample_period=self.period,
            start_time=self.frames[0].start_time,
            axis=self.axis,
        )


def _doctype_line(path: Path) -> int | None:
    """The line of the file's ``<!DOCTYPE``, read in chunks; None if not found as bytes."""
    marker = b"<!DOCTYPE"
    line, tail = 1, b""
    with open(path, "rb") as source:
        while chunk := source.read(1 << 16):
            data = tail + chunk
            found = data.find(marker)
            if found >= 0:
                return line + data.count(b"\n", 0, found)
            keep = len(marker) - 1  # a marker split across two chunks
            line += data.count(b"\n", 0, len(data) - keep)
            tail = data[len(data) - keep :]
    return None  # e.g. a UTF-16 file


def _carry_forward(block: np.ndarray) -> None:
    """Replace each NaN by the last value above it in its column, in place."""
    if block.shape[0] == 0:
        return
    rows = np.arange(block.shape[0])
    for column in range(block.shape[1]):
        values = block[:, column]
        last = np.where(np.isnan(values), 0, rows)
        np.maximum.accumulate(last, out=last)
        block[:, column] = values[last]


def read_sinumerik(path: str | os.PathLike[str], *, axis: int | None = None) -> SinumerikTrace:
    """Read a SINUMERIK Solution Line trace XML file onto its uniform grid.

    Parameters
    ----------
    path : path-like
        The ``.xml`` trace.
    axis : int, optional
        The axis to read (the ``N`` of the ``[u1, N]`` suffix). Needed when the trace holds
        several axes; signals that name no axis are always read.

    Returns
    -------
    SinumerikTrace
        Signals in the order the first data frame declares them, values carried forward on the
        grid of the finest interval (see the module documentation for the rules).

    Raises
    ------
    TraceFormatError
        Malformed or truncated XML, a DOCTYPE or entity declaration, not a ``traceSession``, no or
        an empty data frame, time not increasing or off the grid, text where a number belongs.
        The message contains the path and, where it helps, the line and the signal.
    ChannelError
        A record refers to an undeclared signal, a signal is declared twice or never recorded,
        several axes and none chosen.

    References
    ----------
    Paper section 3.2 (500 Hz SINUMERIK 840D sl recordings) and 3.3 (XML log files).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> xml = '''<traceSession><traceData><dataFrame>
    ...  <frameHeader startTime="2026-01-01T00:00:00.000Z" stopInc="0.008"/>
    ...  <dataSignal id="f1" interval="0.002" name="/Nck/!SD/nckServoDataActCurr32 [u1, 1]"
    ...   unitsType="current" dataType="float"/>
    ...  <dataSignal id="f2" interval="0.004" name="/Nck/!SEMA/measPos2 [u1, 1]"
    ...   unitsType="posn" dataType="double"/>
    ...  <rec time="0.000" f1="1.5"/>
    ...  <rec time="0.002" f2="10.0"/>
    ...  <rec time="0.006" f1="2.5" f2="10.5"/>
    ... </dataFrame></traceData></traceSession>'''
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tiny.xml"
    >>> _ = path.write_text(xml)
    >>> trace = read_sinumerik(path)
    >>> trace.sample_period, trace.axis, [s.interval for s in trace.signals]
    (0.002, 1, [0.002, 0.004])
    >>> trace.values
    array([[ 1.5,  nan],
           [ 1.5, 10. ],
           [ 1.5, 10. ],
           [ 2.5, 10.5],
           [ 2.5, 10.5]])
    """
    reader = _Reader(Path(path), axis)
    reader.parse()
    return reader.result()
