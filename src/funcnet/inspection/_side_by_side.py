"""Independent computations side by side, in processes or threads, their results and
warnings in a fixed order (private).

The inspection of a robot is seven computations that share nothing but their inputs: the
robot network with its evidence, and each axis's own inspection. :func:`run_in_order` runs them
and gives back what each returned, in the order given, whatever the scheduling.

Processes where they can be forked safely: much of a computation is Python and pandas, which
hold the GIL, so only processes keep two cores busy. A forked child inherits the jobs (nothing
is pickled on the way in); its result and warnings come back pickled. Forking is safe on
Linux while Numba's thread pool has not started in this process (its OpenMP layer cannot
start again in a forked child), which is the case for a command reading a recording and
inspecting it: the pool starts in the children. Otherwise threads: their hot kernels release
the GIL (NumPy, BLAS, Numba's parallel kernels and those compiled ``nogil``).

Warnings are the one shared state: the filters and ``warnings.showwarning`` belong to the
process, and ``warnings.catch_warnings`` is not thread-safe (a thread entering it changes the
filters of every thread). While the jobs run, a capture (in each child, or one set up by the
calling thread for all threads) records each warning beside the computation that raised it;
once they are done, the warnings are emitted again in the calling thread, computation by
computation in the order given, under the caller's own filters: what a caller catches or shows
is what running the computations one after the other gives. No computation run here may enter
``warnings.catch_warnings`` itself.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
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

__all__ = ["run_in_order", "default_workers", "forkable"]

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
    """The jobs of a robot's inspection at once: the cores this process may use, at most 4; 1
    outside the main thread (a caller's own threads may warn meanwhile: the capture of
    :func:`run_in_order` would take their warnings).

    Examples
    --------
    >>> 1 <= default_workers() <= 4
    True
    """
    if threading.current_thread() is not threading.main_thread():
        return 1
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on every platform
        cores = os.cpu_count() or 1
    return max(1, min(4, cores))


def forkable() -> bool:
    """Whether jobs may run in forked processes: on Linux (macOS forks, but its system
    libraries, BLAS among them, are not promised to work in a forked child), while Numba's
    thread pool has not started in this process (a child forked from a process whose OpenMP
    pool runs hangs in its first parallel region).

    Examples
    --------
    >>> forkable() in (True, False)
    True
    """
    import multiprocessing

    from numba.np.ufunc import parallel

    return (sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()
            and not getattr(parallel, "_is_initialized", True))


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


def _registry(module: str | None) -> dict[Any, Any] | None:
    """The warning registry of a module of this process (a child's copy does not come back)."""
    found = sys.modules.get(module) if module is not None else None
    return None if found is None else vars(found).setdefault("__warningregistry__", {})


def _task(job: Callable[[], T], numba_threads: int,
          outside: _Place) -> tuple[list[_Caught], Any, bool]:
    """Run ``job`` in this thread with its own sink: (its warnings, result or error, ok)."""
    caught: list[_Caught] = []
    _SINK.caught, _SINK.base, _SINK.outside = caught, sys._getframe(), outside
    # Numba's thread count is per calling thread (and per child): each job has what it is given.
    numba.set_num_threads(numba_threads)
    try:
        return caught, job(), True
    except BaseException as error:  # raised again in the caller's thread, in its turn
        return caught, error, False
    finally:
        _SINK.caught, _SINK.base, _SINK.outside = None, None, None


_Outcome = tuple[list[_Caught], Any, bool]

#: The jobs of each call in processes, set before its children fork: they inherit them.
_FORKED: dict[int, tuple[Sequence[Callable[[], Any]], int, _Place]] = {}
_CALLS = itertools.count()


def _forked_task(call: int, k: int) -> _Outcome:
    """Job ``k`` of ``call`` in a forked child, under the child's own capture; its warnings
    go back without their registries (the caller's are found again by module)."""
    jobs, numba_threads, outside = _FORKED[call]
    stray: list[_Caught] = []
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = _record(stray)  # type: ignore[assignment]
        caught, value, ok = _task(jobs[k], numba_threads, outside)
    return [dataclasses.replace(w, registry=None) for w in [*caught, *stray]], value, ok


def _collect(futures: Sequence[Any], done: Callable[[int], None] | None) -> list[_Outcome]:
    """The futures' outcomes in order, ``done(k)`` after each that did not raise."""
    outcomes = []
    try:
        for k, future in enumerate(futures):
            outcomes.append(future.result())
            if done is not None and outcomes[-1][2]:
                done(k)
    except BaseException:  # an interrupt: the jobs not started yet are not run
        for future in futures:
            future.cancel()
        raise
    return outcomes


def _in_processes(jobs: Sequence[Callable[[], T]], workers: int, outside: _Place,
                  done: Callable[[int], None] | None) -> tuple[list[_Caught], list[_Outcome]]:
    """The jobs in forked children: (no stray warning, the outcomes in order)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    call = next(_CALLS)
    # Each child keeps every core (the longest job, a robot network, runs alone at the end);
    # numba.get_num_threads() would start the pool here: the configured count instead.
    threads = numba.config.NUMBA_NUM_THREADS  # type: ignore[attr-defined]
    _FORKED[call] = (jobs, threads, outside)
    try:
        with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
            with warnings.catch_warnings():
                # Python >= 3.12 warns of a fork beside other threads: those here (BLAS's,
                # the allocator's) are idle and fork-safe. The children fork on first submit.
                warnings.filterwarnings("ignore", ".*fork", DeprecationWarning)
                futures = [pool.submit(_forked_task, call, k) for k in range(len(jobs))]
            outcomes = _collect(futures, done)
    finally:
        del _FORKED[call]
    return [], [([dataclasses.replace(w, registry=_registry(w.module)) for w in caught], value,
                  ok) for caught, value, ok in outcomes]


def _in_threads(jobs: Sequence[Callable[[], T]], workers: int, outside: _Place,
                done: Callable[[int], None] | None) -> tuple[list[_Caught], list[_Outcome]]:
    """The jobs in threads: (the warnings of no job's thread, the outcomes in order)."""
    share = numba.get_num_threads()
    stray: list[_Caught] = []
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # every warning recorded; the caller's filters decide
        warnings.showwarning = _record(stray)  # type: ignore[assignment]
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="funcnet") as pool:
            # the longest job (the first: a robot network) keeps every core it can get
            futures = [pool.submit(_task, job, share, outside) for job in jobs]
            outcomes = _collect(futures, done)
    return stray, outcomes


def run_in_order(jobs: Sequence[Callable[[], T]], workers: int,
                 done: Callable[[int], None] | None = None, *,
                 processes: bool | None = None) -> list[T]:
    """Each job's result, in the order of ``jobs``; up to ``workers`` jobs at a time.

    Parameters
    ----------
    jobs : sequence of callable
        Computations without arguments that share no mutable state.
    workers : int
        Processes or threads; 1 runs every job in the calling thread, one after the other, as
        a loop would (the warnings then go straight to the caller's filters).
    done : callable, optional
        ``done(k)`` in the calling thread once job ``k`` and those before it are done, in the
        order of ``jobs`` (for a progress bar); not for a job that raised.
    processes : bool, optional
        Forked processes (each job's result and error must pickle), or threads; default
        processes where :func:`forkable`.

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
    forked = forkable() if processes is None else processes
    if workers <= 1 or len(jobs) <= 1 or not (forked or threadsafe_layer()):
        results = []
        for k, job in enumerate(jobs):
            results.append(job())
            if done is not None:
                done(k)
        return results
    run = _in_processes if forked else _in_threads
    stray, outcomes = run(jobs, min(workers, len(jobs)), _outside(sys._getframe(1)), done)
    _replay(stray)
    results = []
    for caught, value, ok in outcomes:
        _replay(caught)
        if not ok:
            raise value
        results.append(value)
    return results
