"""Independent computations side by side in threads, their results and warnings in a fixed
order (private).

The inspection of a robot is seven computations that share nothing but their inputs: the
robot network with its evidence, and each axis's own inspection. Their hot kernels release
the GIL (NumPy, BLAS, Numba's parallel kernels and those compiled ``nogil``), so threads of
one process keep two cores busy. :func:`run_in_order` runs them and gives back what each
returned, in the order given, whatever the scheduling.

Warnings are the one shared state: the filters and ``warnings.showwarning`` belong to the
process, and ``warnings.catch_warnings`` is not thread-safe (a thread entering it changes the
filters of every thread). While the threads run, one capture set up by the calling thread
records each warning beside the computation that raised it; once they are done, the warnings
are emitted again in the calling thread, computation by computation in the order given, under
the caller's own filters: what a caller catches or shows is what running the computations one
after the other gives. No computation run here may enter ``warnings.catch_warnings`` itself.
"""

from __future__ import annotations

import functools
import os
import sys
import threading
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from types import FrameType
from typing import Any, TypeVar

import numba

__all__ = ["run_in_order", "default_workers"]

# funcnet's own files: a warning "at the first frame outside funcnet" skips them
_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep

T = TypeVar("T")


@dataclass(frozen=True)
class _Caught:
    """One warning as ``warnings.warn_explicit`` takes it again."""

    message: Warning | str
    category: type[Warning]
    filename: str
    lineno: int
    module: str | None
    registry: dict[Any, Any] | None


#: Where a warning is attributed to: file, line, module name, warning registry.
_Place = tuple[str, int, "str | None", "dict[Any, Any] | None"]


class _Sink(threading.local):
    """The list the current thread's warnings go to (None: a thread not running a task), the
    frame of its task, and the caller's place, where the caller's thread would attribute a
    warning given "at the first frame outside funcnet"."""

    caught: list[_Caught] | None = None
    base: FrameType | None = None
    outside: _Place | None = None


_SINK = _Sink()


def default_workers() -> int:
    """The threads of a robot's inspection: the cores this process may use, at most 4; 1
    outside the main thread (a caller's own threads may warn meanwhile: the capture of
    :func:`run_in_order` would take their warnings).

    Examples
    --------
    >>> 1 <= default_workers() <= 4
    True
    """
    if threading.current_thread() is not threading.main_thread() or not threadsafe_layer():
        return 1
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on every platform
        cores = os.cpu_count() or 1
    return max(1, min(4, cores))


@numba.njit(parallel=True, cache=True)
def _one_region(n: int) -> int:  # pragma: no cover - compiled
    total = 0
    for k in numba.prange(n):
        total += k
    return total


@functools.cache
def threadsafe_layer() -> bool:
    """Whether two threads may enter Numba's parallel regions at once: its OpenMP and TBB
    threading layers allow it; its fallback, the workqueue (a machine without libgomp or
    TBB), stops the process when they do.

    Numba chooses its layer at the first parallel region, so one tiny region runs first.

    Examples
    --------
    >>> threadsafe_layer() in (True, False)
    True
    """
    _one_region(2)
    return numba.threading_layer() in ("omp", "tbb")


def _place(frame: FrameType) -> _Place:
    registry = frame.f_globals.setdefault("__warningregistry__", {})
    return frame.f_code.co_filename, frame.f_lineno, frame.f_globals.get("__name__"), registry


def _outside(frame: FrameType) -> _Place:
    """The place of the first frame outside funcnet from ``frame`` up
    (:func:`funcnet.errors.caller_stacklevel`)."""
    while frame.f_back is not None and frame.f_code.co_filename.startswith(_PACKAGE_DIR):
        frame = frame.f_back
    return _place(frame)


def _origin(filename: str, lineno: int) -> _Place:
    """The place of a warning as ``warnings.warn`` found it, on the emitting thread's stack;
    one attributed to the thread's own machinery (a warning of "the first frame outside
    funcnet", seen from a task) is the caller's, as in the caller's thread."""
    frame: FrameType | None = sys._getframe(2)
    while frame is not None and frame is not _SINK.base:
        if frame.f_code.co_filename == filename and frame.f_lineno == lineno:
            return _place(frame)
        frame = frame.f_back
    if _SINK.base is not None and _SINK.outside is not None:
        return _SINK.outside
    return filename, lineno, None, None


def _record(stray: list[_Caught]) -> Callable[..., None]:
    """The ``showwarning`` of the capture: each warning into its thread's sink."""

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: Any = None, line: str | None = None) -> None:
        caught = _SINK.caught if _SINK.caught is not None else stray
        caught.append(_Caught(message, category, *_origin(filename, lineno)))

    return show


def _replay(caught: Sequence[_Caught]) -> None:
    """The warnings emitted again, in order, under the filters now in force."""
    for w in caught:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, module=w.module,
                               registry=w.registry)


def _task(job: Callable[[], T], numba_threads: int,
          outside: _Place) -> tuple[list[_Caught], Any, bool]:
    """Run ``job`` in this thread with its own sink: (its warnings, result or error, ok)."""
    caught: list[_Caught] = []
    _SINK.caught, _SINK.base, _SINK.outside = caught, sys._getframe(), outside
    # Numba's thread count is per calling thread: each job has the caller's (a parallel
    # region of the robot network, the longest job, keeps every core it can get).
    numba.set_num_threads(numba_threads)
    try:
        return caught, job(), True
    except BaseException as error:  # raised again in the caller's thread, in its turn
        return caught, error, False
    finally:
        _SINK.caught, _SINK.base, _SINK.outside = None, None, None


def run_in_order(jobs: Sequence[Callable[[], T]], workers: int,
                 done: Callable[[int], None] | None = None) -> list[T]:
    """Each job's result, in the order of ``jobs``; up to ``workers`` jobs at a time.

    Parameters
    ----------
    jobs : sequence of callable
        Computations without arguments that share no mutable state.
    workers : int
        Threads; 1 runs every job in the calling thread, one after the other, as a loop would
        (the warnings then go straight to the caller's filters).
    done : callable, optional
        ``done(k)`` in the calling thread once job ``k`` and those before it are done, in the
        order of ``jobs`` (for a progress bar); not for a job that raised.

    Returns
    -------
    list
        The results in the order of ``jobs``. The first job (in that order) that raised
        raises its error here, after the warnings of the jobs before it and its own.

    Examples
    --------
    >>> def job(k):
    ...     def run():
    ...         warnings.warn(f"job {k}")
    ...         return k * k
    ...     return run
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     results = run_in_order([job(k) for k in range(4)], workers=2)
    >>> results, [str(w.message) for w in caught]
    ([0, 1, 4, 9], ['job 0', 'job 1', 'job 2', 'job 3'])
    """
    if workers <= 1 or len(jobs) <= 1 or not threadsafe_layer():
        results = []
        for k, job in enumerate(jobs):
            results.append(job())
            if done is not None:
                done(k)
        return results
    workers = min(workers, len(jobs))
    share = numba.get_num_threads()
    stray: list[_Caught] = []
    outcomes = []
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # every warning recorded; the caller's filters decide
        warnings.showwarning = _record(stray)  # type: ignore[assignment]
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="funcnet") as pool:
            outside = _outside(sys._getframe(1))
            futures = [pool.submit(_task, job, share, outside) for job in jobs]
            try:
                for k, future in enumerate(futures):
                    outcomes.append(future.result())
                    if done is not None and outcomes[-1][2]:
                        done(k)
            except BaseException:  # an interrupt: the jobs not started yet are not run
                for future in futures:
                    future.cancel()
                raise
    _replay(stray)
    results = []
    for caught, value, ok in outcomes:
        _replay(caught)
        if not ok:
            raise value
        results.append(value)
    return results
