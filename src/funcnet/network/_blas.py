"""One BLAS thread for the many small linear-algebra calls of a network.

The direction reading (:mod:`funcnet.network.direction`) solves two least-squares problems per
pair (thousands of rows, tens of columns). OpenBLAS spreads each over its threads; on two cores
shared with Numba's threads and other work, the wake-ups cost far more than the solve: 26 ms
instead of 3 ms per solve of 3,200 x 43, and 82 s of the 30-node network of a 26 s UR5 run
(benchmarks/RESULTS.md). The solutions are the same bits for the direction's designs up to
6,000 x 43 (tests/test_blas_threads.py); larger ones (12,000 x 43) differ in the last bit with
OpenBLAS's threads, whose split depends on the machine's cores: in one thread the reading no
longer does.
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from typing import Any

from threadpoolctl import threadpool_limits

__all__ = ["one_blas_thread"]


def one_blas_thread() -> AbstractContextManager[Any]:
    """A context in which BLAS/LAPACK (OpenBLAS, MKL) run in the calling thread only; the
    previous limits are restored on exit.

    Examples
    --------
    >>> import numpy as np
    >>> with one_blas_thread():
    ...     float(np.linalg.lstsq(np.eye(2), np.ones(2), rcond=None)[0].sum())
    2.0
    """
    return threadpool_limits(limits=1, user_api="blas")
