"""Where funcnet calls a library for a textbook computation, it gives what the hand-written
step-by-step formula gives (written out here as the reference)."""

from __future__ import annotations

import numpy as np
import pytest

from funcnet.evidence import benjamini_hochberg
from funcnet.validation.sweep import _auc, _auc_point, _spearman, _spearman_point


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


def _sample(seed: int, n: int = 30) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    truth = rng.choice([0.0, 0.5, 1.0, 2.0], n)
    scores = np.round(truth + rng.normal(0, 0.8, n), 1)  # rounded: ties
    scores[rng.integers(0, n, 3)] = np.nan
    return scores, truth, truth >= 1, truth <= 0


@pytest.mark.parametrize("seed", range(5))
def test_the_bootstraps_vectorized_auc_and_rho_are_scipys_per_draw(seed):
    scores, truth, positive, negative = _sample(seed)
    draws = np.random.default_rng(seed).integers(0, scores.size, (40, scores.size))
    aucs = _auc(scores[draws], positive[draws], negative[draws])
    want = [_auc_point(scores[d], positive[d], negative[d]) for d in draws]
    np.testing.assert_allclose(aucs, want, rtol=1e-12, equal_nan=True)
    x, y = scores[np.isfinite(scores)], truth[np.isfinite(scores)]
    draws = np.random.default_rng(seed).integers(0, x.size, (40, x.size))
    rhos = _spearman(x[draws], y[draws])
    want = [_spearman_point(x[d], y[d]) for d in draws]
    np.testing.assert_allclose(rhos, want, rtol=1e-12, equal_nan=True)


@pytest.mark.parametrize("seed", range(5))
def test_the_point_estimates_are_the_former_formulas(seed):
    scores, truth, positive, negative = _sample(seed)
    # scipy's U and rho against the rank formulas funcnet used: equal to a few ulps
    np.testing.assert_allclose(_auc_point(scores, positive, negative),
                               _auc(scores[None], positive[None], negative[None])[0], rtol=1e-14)
    ok = np.isfinite(scores)
    np.testing.assert_allclose(_spearman_point(scores[ok], truth[ok]),
                               _spearman(scores[ok][None], truth[ok][None])[0], rtol=1e-14)
    assert np.isnan(_auc_point(scores, positive, np.zeros_like(negative)))
    assert np.isnan(_spearman_point(np.ones(5), np.arange(5.0)))
