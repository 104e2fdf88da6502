"""What the command line prints besides results: errors, warnings and progress.

An input error (every :class:`~funcnet.errors.FuncnetError` and an operating-system error on a
file) is one plain line, ``funcnet: error: MESSAGE``, on stderr and exit status 2; the library's
warnings are counted per problem after the command succeeded (``--verbose``: one line each);
a progress bar goes to stderr when it is a terminal.
"""

from __future__ import annotations

import contextlib
import sys
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import typer

from funcnet.errors import FuncnetError, FuncnetWarning, RecordingWarning

__all__ = ["EXIT_INPUT_ERROR", "EXIT_TASKS_FAILED", "is_terminal", "one_line", "progress_bar",
           "reported_errors"]

EXIT_INPUT_ERROR = 2
EXIT_TASKS_FAILED = 1


def one_line(text: str) -> str:
    return " ".join(str(text).split())


def is_terminal(stream: Any) -> bool:
    return bool(getattr(stream, "isatty", lambda: False)())


def _os_error_message(exc: OSError) -> str:
    if exc.filename is not None and exc.strerror:
        return f"{exc.filename}: {exc.strerror}"
    return str(exc)


# Python spellings in library messages, and the command line's own for the same thing.
_RESPELLED = {
    "funcnet.robot.resample decimates or interpolates them":
        "--resample decimate or --resample interpolate brings them onto one grid",
    "normalize=None": "--normalize none",
    "constant='error' makes it an error": "--strict-constant makes it an error",
}


def _respelled(text: str) -> str:
    for python, flag in _RESPELLED.items():
        text = text.replace(python, flag)
    return text


@contextlib.contextmanager
def reported_errors(*, summarized: bool = False, verbose: bool = False) -> Iterator[None]:
    """Turn input errors into one plain line on stderr and exit status 2.

    Warnings are collected and reported when the command succeeds; a failed command prints its
    error line only. The library's warnings (:class:`FuncnetWarning`) are summarized in one
    line, counted per problem; ``verbose`` prints each distinct one instead. ``summarized``: the
    command reports the library's warnings itself (counted per problem), so they are not
    printed too.
    """
    messages: list[str] = []
    problems: dict[str, int] = {}

    def collect(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                file: object = None, line: str | None = None) -> None:
        # What the reader left out or split is said in full: it is about the file, not a pair.
        if isinstance(message, FuncnetWarning) and not verbose and not isinstance(
            message, RecordingWarning
        ):
            problem = message.problem or type(message).__name__
            problems[problem] = problems.get(problem, 0) + 1
            return
        text = _respelled(one_line(str(message)))
        if text not in messages:
            messages.append(text)

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        if summarized:
            warnings.simplefilter("ignore", FuncnetWarning)
            warnings.simplefilter("always", RecordingWarning)
        warnings.showwarning = collect
        try:
            yield
        except FuncnetError as exc:
            sys.stderr.write(f"funcnet: error: {one_line(str(exc))}\n")
            raise typer.Exit(EXIT_INPUT_ERROR) from None
        except OSError as exc:
            sys.stderr.write(f"funcnet: error: {one_line(_os_error_message(exc))}\n")
            raise typer.Exit(EXIT_INPUT_ERROR) from None
    if problems:
        total = sum(problems.values())
        counted = ", ".join(f"{name} ×{n}" for name, n in problems.items())
        sys.stderr.write(f"funcnet: warning: {total} warning(s) from the library ({counted}); "
                         "the pairs tables flag the pairs concerned; --verbose prints each\n")
    for text in messages:
        sys.stderr.write(f"funcnet: warning: {text}\n")


@contextlib.contextmanager
def progress_bar(quiet: bool, label: str) -> Iterator[Callable[..., None] | None]:
    """A rich progress bar on stderr, or ``None`` when quiet or stderr is not a terminal.

    Yields a callback ``progress(done, total, description=None)``, the protocol of the library's
    long-running functions.
    """
    if quiet or not is_terminal(sys.stderr):
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeRemainingColumn

    with Progress(
        "[progress.description]{task.description}",
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
        console=Console(stderr=True),
        transient=True,
    ) as bar:
        task = bar.add_task(label, total=None)

        def update(done: int, total: int, description: str | None = None) -> None:
            text = label if description is None else f"{label}: {description}"
            bar.update(task, completed=done, total=total, description=text)

        yield update
