"""Where a study's tasks run: this process, local processes, or a Dask cluster.

Dask is an optional extra (``pip install funcnet[dask]``): ``dask`` and ``distributed`` are
imported only here, only when a scheduler is asked for, and their absence is one line naming
the extra.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
import warnings
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from funcnet.errors import FuncnetWarning, ParameterError, StudyError

__all__ = ["DEFAULT_WORKERS", "Backend", "check_execution", "require_dask"]

#: Local worker processes when the caller gives no number.
DEFAULT_WORKERS = 2


def require_dask(scheduler: str) -> None:
    """Raise a :class:`StudyError` naming the extra if ``distributed`` cannot be imported.

    Parameters
    ----------
    scheduler : str
        The scheduler asked for (named in the message).

    Raises
    ------
    StudyError
        One line: ``install funcnet[dask]``.

    Examples
    --------
    >>> import sys
    >>> saved = sys.modules.get("distributed")
    >>> sys.modules["distributed"] = None  # as if not installed
    >>> require_dask("local-cluster")
    Traceback (most recent call last):
        ...
    funcnet.errors.StudyError: scheduler 'local-cluster' needs Dask, an optional extra: \
install funcnet[dask] (pip install 'funcnet[dask]')
    >>> if saved is None: del sys.modules["distributed"]
    ... else: sys.modules["distributed"] = saved
    """
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise StudyError(
            f"scheduler {scheduler!r} needs Dask, an optional extra: install funcnet[dask] "
            "(pip install 'funcnet[dask]')"
        ) from None


def check_execution(scheduler: str | None, workers: int | None) -> int:
    """Validate ``scheduler`` and ``workers``; return the number of local workers.

    Parameters
    ----------
    scheduler : str, optional
        ``None``, ``"local-cluster"`` or ``"tcp://HOST:PORT"``.
    workers : int, optional
        Local worker processes; ``None`` means :data:`DEFAULT_WORKERS`.

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        Naming ``scheduler`` or ``workers``.

    Examples
    --------
    >>> check_execution(None, None), check_execution(None, 0)
    (2, 0)
    >>> check_execution("localhost:8786", None)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: scheduler must be 'tcp://HOST:PORT' or 'local-cluster', \
got 'localhost:8786'
    """
    n_workers = DEFAULT_WORKERS if workers is None else workers
    if isinstance(n_workers, bool) or not isinstance(n_workers, int) or n_workers < 0:
        raise ParameterError.of("workers", f"must be an integer >= 0, got {workers!r}")
    if scheduler is not None and scheduler != "local-cluster":
        host, _, port = scheduler.removeprefix("tcp://").rpartition(":")
        if not scheduler.startswith("tcp://") or not host or not port.isdigit():
            raise ParameterError.of(
                "scheduler", f"must be 'tcp://HOST:PORT' or 'local-cluster', got {scheduler!r}"
            )
    return n_workers


def _start_worker(parent: int) -> None:
    """Initializer of the local worker processes (and of a local cluster's workers).

    funcnet's warnings are counted from the networks' flags by the study, so a worker does not
    print them; the filter is set once, before the process runs any task (so no thread races
    with it). A worker whose parent was killed (SIGKILL leaves no chance to shut the pool
    down) exits instead of waiting forever for tasks.
    """
    warnings.simplefilter("ignore", FuncnetWarning)

    def watch() -> None:
        while True:
            if os.getppid() != parent:
                os._exit(1)
            threading.Event().wait(0.5)

    threading.Thread(target=watch, name="funcnet-parent-watch", daemon=True).start()


def _quiet_worker() -> None:
    warnings.simplefilter("ignore", FuncnetWarning)


class Backend:
    """Run task functions in this process, on local processes or on a Dask cluster.

    Nothing is started until the first :meth:`map_unordered`: a run with nothing to compute
    starts no process and connects to no scheduler.

    Parameters
    ----------
    scheduler : str, optional
        ``None`` (local processes), ``"local-cluster"`` or ``"tcp://HOST:PORT"``.
    workers : int, optional
        Local processes (default :data:`DEFAULT_WORKERS`); 0 runs in this process.

    Examples
    --------
    >>> with contextlib.closing(Backend(None, 0)) as backend:
    ...     sorted(backend.map_unordered(abs, [-2, 1]))
    [1, 2]
    """

    def __init__(self, scheduler: str | None, workers: int | None) -> None:
        self._scheduler = scheduler
        self._workers = check_execution(scheduler, workers)
        self._stack = contextlib.ExitStack()
        self._started = False
        self._client: Any = None
        self._pool: Any = None

    def _start(self) -> None:
        self._started = True
        if self._scheduler is not None:
            self._start_dask(self._scheduler)
        elif self._workers > 0:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            # spawn: the caller may run threads (progress bars, Dask) that fork must not copy.
            self._pool = ProcessPoolExecutor(
                max_workers=self._workers,
                mp_context=multiprocessing.get_context("spawn"),
                initializer=_start_worker,
                initargs=(os.getpid(),),
            )
            # On an error or Ctrl-C, tasks not yet started are dropped rather than awaited.
            self._stack.callback(self._pool.shutdown, wait=True, cancel_futures=True)

    def _start_dask(self, scheduler: str) -> None:
        require_dask(scheduler)
        from distributed import Client, LocalCluster

        if scheduler == "local-cluster":
            cluster = LocalCluster(
                n_workers=max(self._workers, 1),
                threads_per_worker=1,
                processes=True,
                host="127.0.0.1",
                dashboard_address=None,
                # On a busy machine the workers log "event loop unresponsive" warnings to
                # stderr; the command line's output is one line per error, nothing else.
                silence_logs=logging.ERROR,
            )
            self._stack.enter_context(cluster)
            self._client = self._stack.enter_context(Client(cluster))
            # Our own workers, before any task: the same quiet as the local processes.
            self._client.run(_quiet_worker)
            return
        try:
            self._client = self._stack.enter_context(Client(scheduler, timeout="30s"))
        except OSError as exc:
            raise StudyError(f"scheduler {scheduler}: cannot connect: {exc}") from None

    def map_unordered(self, fn: Callable[[Any], Any], tasks: Sequence[Any]) -> Iterator[Any]:
        """Run ``fn`` on every task; yield the results as they finish."""
        if not tasks:
            return
        if not self._started:
            self._start()
        if self._client is not None:
            from distributed import as_completed

            futures = [
                self._client.submit(fn, task, key=f"funcnet-{task.key}", pure=False)
                for task in tasks
            ]
            for future in as_completed(futures):
                yield future.result()
        elif self._pool is not None:
            import concurrent.futures

            pending = [self._pool.submit(fn, task) for task in tasks]
            for future in concurrent.futures.as_completed(pending):
                yield future.result()
        else:
            for task in tasks:
                yield fn(task)

    def close(self) -> None:
        """Stop what :meth:`map_unordered` started."""
        self._stack.close()
