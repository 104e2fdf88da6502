"""Exception types of funcnet.

Every error funcnet raises on bad input derives from :class:`FuncnetError`, so a caller (and the
command line, which turns them into one line and exit status 2) can catch them all at once. The
subclasses also derive from the built-in type a Python user would expect (``ValueError`` for a bad
value, ``OSError`` is left to the operating system).
"""

from __future__ import annotations

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
    "StaircaseWarning",
]


class FuncnetError(Exception):
    """Base class of every error funcnet raises on bad input."""


class ParameterError(FuncnetError, ValueError):
    """A parameter is outside its domain; the message names the parameter."""


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
    """Base class of funcnet's warnings: the result is computed, but read it with care."""


class ThresholdWarning(FuncnetWarning):
    """``eps_XY`` is not below ``eps_X`` and ``eps_Y``, or ties pushed a rate above its target."""


class StaircaseWarning(FuncnetWarning):
    """A network is computed on a signal held constant between coarser native samples."""
