"""The direction's least squares in one BLAS thread (funcnet.network._blas): the same bits
as with BLAS's own threads, and the caller's thread limits back afterwards."""

from __future__ import annotations

import numpy as np
import pandas as pd
from threadpoolctl import threadpool_info

from funcnet.network._blas import one_blas_thread
from funcnet.network.direction import direction_columns
from funcnet.parameters import NetworkParameters


def _blas_threads() -> list[int]:
    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


def test_least_squares_in_one_thread_are_the_same_bits() -> None:
    # designs of the direction test's shape at the default lags 21 (22 and 43 columns) up to
    # 6,000 rows (a 48 s UR5 run). Larger designs (12,000 x 43, 3,200 x 61) differ in the last
    # bit with OpenBLAS's threads, whose split depends on the machine: one thread makes the
    # reading the same on every machine.
    rng = np.random.default_rng(0)
    for rows, columns in ((400, 5), (2000, 43), (3200, 22), (3200, 43), (6000, 43)):
        design = np.column_stack([np.ones(rows), rng.standard_normal((rows, columns - 1))
                                  .cumsum(axis=0)])
        target = rng.standard_normal(rows).cumsum()
        threaded = np.linalg.lstsq(design, target, rcond=None)[0]
        with one_blas_thread():
            assert set(_blas_threads()) <= {1}
            single = np.linalg.lstsq(design, target, rcond=None)[0]
        assert np.array_equal(threaded.view(np.int64), single.view(np.int64))


def test_limits_are_restored_and_the_direction_reading_is_unchanged() -> None:
    before = _blas_threads()
    rng = np.random.default_rng(2)
    x = rng.standard_normal(2000).cumsum()
    y = np.concatenate([[0.0], x[:-1]]) + rng.standard_normal(2000)
    z = rng.standard_normal(2000)
    pairs = pd.DataFrame({"x": ["A", "A", "B"], "y": ["B", "C", "C"], "degenerate": [False] * 3})
    signals = {"A": x, "B": y, "C": z}
    plain = direction_columns(pairs, signals, NetworkParameters())
    with one_blas_thread():
        single = direction_columns(pairs, signals, NetworkParameters())
    assert single == plain
    assert plain["direction"][0] == "x->y"  # the test reads what it should
    assert _blas_threads() == before
