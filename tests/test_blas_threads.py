"""The direction reading runs in one BLAS thread (funcnet.network.direction) and gives the
caller its thread limits back afterwards."""

from __future__ import annotations

import numpy as np
import pandas as pd
from threadpoolctl import threadpool_info, threadpool_limits

from funcnet.network.direction import direction_columns
from funcnet.parameters import NetworkParameters


def _blas_threads() -> list[int]:
    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


def test_limits_are_restored_and_the_reading_does_not_depend_on_the_callers_threads() -> None:
    before = _blas_threads()
    rng = np.random.default_rng(2)
    x = rng.standard_normal(2000).cumsum()
    y = np.concatenate([[0.0, 0.0], x[:-2]]) + rng.standard_normal(2000)  # y follows x by 2
    z = rng.standard_normal(2000)
    pairs = pd.DataFrame({"x": ["A", "A", "B"], "y": ["B", "C", "C"], "degenerate": [False] * 3})
    signals = {"A": x, "B": y, "C": z}
    plain = direction_columns(pairs, signals, NetworkParameters())
    assert _blas_threads() == before
    with threadpool_limits(limits=1, user_api="blas"):
        single = direction_columns(pairs, signals, NetworkParameters())
    assert single == plain
    assert plain["direction"][0] == "x->y"  # the test reads what it should (p 0 and 0.82)
    assert _blas_threads() == before
