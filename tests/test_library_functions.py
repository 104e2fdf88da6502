"""Where funcnet calls a library for a textbook computation, it gives what the hand-written
step-by-step formula gives (written out here as the reference)."""

from __future__ import annotations

import numpy as np
import pytest

from funcnet.evidence import benjamini_hochberg


def _step_up(p: np.ndarray) -> np.ndarray:
    """Benjamini-Hochberg by its definition: min over j >= i of m p_(j) / j, capped at 1."""
    out = np.full(p.shape, np.nan)
    valid = np.flatnonzero(~np.isnan(p))
    m = valid.size
    for i in valid:
        later = [m * p[j] / (np.sum(p[valid] < p[j]) + np.sum(p[valid] == p[j]))
                 for j in valid if p[j] >= p[i]]
        out[i] = min(1.0, min(later))
    return out


@pytest.mark.parametrize("seed", range(6))
def test_benjamini_hochberg_is_the_step_up_rule(seed):
    rng = np.random.default_rng(seed)
    m = int(rng.integers(2, 60))
    p = rng.uniform(0, 1, m) ** 3
    p[rng.integers(0, m, m // 4)] = p[0]           # ties
    p[rng.integers(0, m, m // 6)] = np.nan          # not counted
    p[rng.integers(0, m, 2)] = 1.0 / 100            # the smallest p of 99 surrogates, twice
    got = benjamini_hochberg(p)
    want = _step_up(p)
    np.testing.assert_array_equal(np.isnan(got), np.isnan(p))
    # scipy multiplies by m / i where the former code divided m p by i: a few ulps apart
    np.testing.assert_allclose(got, want, rtol=1e-15, atol=0)


def test_benjamini_hochberg_edges():
    assert np.isnan(benjamini_hochberg([np.nan, np.nan])).all()
    assert benjamini_hochberg([0.03]).tolist() == [0.03]
    assert benjamini_hochberg([0.03, np.nan]).tolist()[0] == 0.03
    assert benjamini_hochberg(np.array([], dtype=float)).shape == (0,)
