"""Exception types of funcnet.

Every error funcnet raises on bad input derives from :class:`FuncnetError`, so a caller (and the
command line, which turns them into one line and exit status 2) can catch them all at once. The
subclasses also derive from the built-in type a Python user would expect (``ValueError`` for a bad
value, ``OSError`` is left to the operating system).
"""

from __future__ import annotations

import os
import sys
from typing import Any

__all__ = [
    "FuncnetError",
    "ParameterError",
    "SignalError",
    "TraceError",
    "TraceFormatError",
    "ChannelError",
    "WindowError",
    "StudyError",
    "FuncnetWarning",
    "ThresholdWarning",
    "DegenerateWarning",
    "StaircaseWarning",
    "RecordingWarning",
    "caller_stacklevel",
]

# The package's folder: frames there are funcnet's own, the first frame outside is the user's.
_PACKAGE = sys.modules[__name__.partition(".")[0]]
_PACKAGE_DIR = os.path.dirname(os.path.abspath(str(_PACKAGE.__file__))) + os.sep


def caller_stacklevel() -> int:
    """``stacklevel`` of the first frame outside funcnet, seen from this function's caller.

    A warning given with it points at the user's line, whether funcnet was called directly or
    through a network, a study or the command line.

    Examples
    --------
    >>> caller_stacklevel()  # called from outside the package: the caller's own frame
    1
    """
    frame, level = sys._getframe(1), 1
    while frame.f_back is not None and frame.f_code.co_filename.startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    return level


class FuncnetError(Exception):
    """Base class of every error funcnet raises on bad input."""


class ParameterError(FuncnetError, ValueError):
    """A parameter is outside its domain; the message names the parameter.

    Raised as ``ParameterError("rr must be in (0, 1), got 2.0")`` or, where an entry point may
    re-spell the parameter's name (``--rr`` on the command line, a TOML key and its file),
    as ``ParameterError.of("rr", "must be in (0, 1), got 2.0")``: then :attr:`parameter` and
    :attr:`detail` hold the two parts and :meth:`spelled` renames the parameter.
    """

    def __init__(self, message: str, *, parameter: str | None = None,
                 detail: str | None = None) -> None:
        self.parameter = parameter
        self.detail = detail
        super().__init__(message)

    @classmethod
    def of(cls, parameter: str, detail: str) -> ParameterError:
        """The error for ``parameter`` with ``detail`` (``"must be ..., got ..."``)."""
        return cls(f"{parameter} {detail}", parameter=parameter, detail=detail)

    def spelled(self, name: str, prefix: str = "") -> str:
        """The message with the parameter named ``name`` (``prefix`` before it, e.g. a file)."""
        if self.parameter is None or self.detail is None:
            return f"{prefix}{self}"
        return f"{prefix}{name} {self.detail}"


class SignalError(FuncnetError, ValueError):
    """A signal cannot be analysed (too short, NaN/inf, constant, unequal length); names it."""


class TraceError(FuncnetError):
    """A recording cannot be read; the message always contains the file's path."""

    def __init__(self, path: object, message: str) -> None:
        self.path = str(path)
        super().__init__(f"{self.path}: {message}")


class TraceFormatError(TraceError, ValueError):
    """The file is not a well-formed trace (malformed XML, entities, missing parts, bad numbers)."""


class ChannelError(TraceError, KeyError):
    """A channel is missing, duplicated, or cannot be mapped to a role."""

    def __str__(self) -> str:  # KeyError would quote the message
        return Exception.__str__(self)


class WindowError(FuncnetError, ValueError):
    """An analysis window does not fit the recording."""


class StudyError(FuncnetError, ValueError):
    """A study description is invalid; the message names the file and the key."""


class FuncnetWarning(UserWarning):
    """Base class of funcnet's warnings: the result is computed, but read it with care.

    A warning carries its data, so that code collecting warnings never parses their text:
    ``problem`` (a short key), ``signals`` and ``pairs`` (names) and ``window`` (a window's
    label, or None). :meth:`located` returns the same warning for a named window.
    """

    def __init__(self, message: str, *, problem: str | None = None,
                 signals: tuple[str, ...] = (), pairs: tuple[tuple[str, str], ...] = (),
                 window: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.problem = problem
        self.signals = tuple(signals)
        self.pairs = tuple(pairs)
        self.window = window

    def __str__(self) -> str:
        return self.message if self.window is None else f"{self.window}: {self.message}"

    def located(self, window: str) -> FuncnetWarning:
        """The same warning (class, data) for the window labelled ``window``."""
        return type(self)(self.message, problem=self.problem, signals=self.signals,
                          pairs=self.pairs, window=window)

    def __reduce__(self) -> tuple[Any, ...]:  # picklable across processes with its data
        return (_rebuild_warning, (type(self), self.message, self.problem, self.signals,
                                   self.pairs, self.window))


def _rebuild_warning(cls: type[FuncnetWarning], message: str, problem: str | None,
                     signals: tuple[str, ...], pairs: tuple[tuple[str, str], ...],
                     window: str | None) -> FuncnetWarning:
    return cls(message, problem=problem, signals=signals, pairs=pairs, window=window)


class ThresholdWarning(FuncnetWarning):
    """``eps_XY`` is not below ``eps_X`` and ``eps_Y`` (``problem="eps_order"``), or ties
    pushed a rate above its target (``problem="rate_exceeded"``)."""


class DegenerateWarning(ThresholdWarning):
    """A recurrence structure is degenerate (``problem="degenerate"``): threshold 0 or a rate
    above twice its target -- too few distinct states, e.g. a signal that barely moves."""


class StaircaseWarning(FuncnetWarning):
    """A network is computed on a signal held constant between coarser native samples."""


class RecordingWarning(FuncnetWarning):
    """A recording was read, but part of it is not usable as it stands; the message names the
    file and what was done. ``problem`` is ``"gap"`` (missing values: the recording is split
    into segments), ``"constant"`` (a channel constant over the whole recording, or inside a
    window, left out of it) or ``"duplicate"`` (a column name given twice, both left out);
    ``signals`` names them."""
