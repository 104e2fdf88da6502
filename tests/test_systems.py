"""The generators of funcnet.validation.systems: shapes, determinism per seed, zero coupling, known
values."""

from __future__ import annotations

import numpy as np
import pytest

from funcnet.validation import systems

GENERATORS = [
    lambda n, s: systems.henon_pair(n, 0.4, seed=s),
    lambda n, s: systems.rossler_pair(n, 0.1, seed=s, transient=20.0),
    lambda n, s: systems.lorenz_pair(n, seed=s, transient=5.0),
    lambda n, s: systems.logistic_pair(n, 3.7, 4.0, 0.2, seed=s),
    lambda n, s: systems.rough_driver_response(n, seed=s),
    lambda n, s: systems.unrelated_low_pass(n, seed=s),
    lambda n, s: systems.white_noise(n, seed=s),
    lambda n, s: systems.ar1_pair(n, seed=s),
    lambda n, s: systems.common_driver(n, seed=s),
]


@pytest.mark.parametrize("make", GENERATORS)
def test_shapes_determinism_and_batches(make):
    one = make(120, 3)
    assert one.shape == (120, 2) and np.isfinite(one).all()
    np.testing.assert_array_equal(one, make(120, 3))  # the seed fixes everything
    assert not np.array_equal(one, make(120, 4))
    batch = make(120, [3, 4])
    assert batch.shape == (120, 2, 2)
    np.testing.assert_array_equal(batch[:, 0], one)  # a batch row is the single run


def test_zero_coupling_gives_independent_maps():
    # With C = 0, Y does not see X: changing X's start leaves Y's trajectory unchanged only if
    # Y's own start is the same -- check through the equations: Y is a plain Henon map.
    data = systems.henon_pair(50, 0.0, seed=7, transient=0)
    y = data[:, 1]
    start = np.random.default_rng(7).uniform(0.0, 0.5, 4)
    y_prev = start[3]
    for i in range(1, 50):
        expected = 1.4 - y[i - 1] ** 2 + 0.3 * y_prev
        assert y[i] == expected
        y_prev = y[i - 1]


def test_coupling_makes_the_response_follow_the_driver():
    # Identical Henon maps synchronize for strong coupling (C = 0.8): Y becomes X.
    data = systems.henon_pair(200, 0.8, seed=1)
    np.testing.assert_allclose(data[:, 0], data[:, 1], atol=1e-6)
    loose = systems.henon_pair(200, 0.0, seed=1)
    assert np.abs(loose[:, 0] - loose[:, 1]).max() > 0.5


def test_common_driver_responses_do_not_see_each_other():
    a = systems.common_driver(200, 0.0, seed=2)
    b = systems.henon_pair(200, 0.0, seed=2)
    assert a.shape == b.shape  # with C = 0 the responses are free Henon maps
    assert np.abs(a[:, 0] - a[:, 1]).max() > 0.5


def test_ar1_is_stationary_from_the_start():
    data = systems.ar1_pair(400, 0.95, seed=list(range(200)))
    # Stationary variance 1 / (1 - phi^2) = 10.26 at t = 0 and at the end.
    assert 7.0 < data[0].var() < 14.0
    assert 7.0 < data[-1].var() < 14.0


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="n must be"):
        systems.white_noise(0)
    with pytest.raises(ValueError, match="phi"):
        systems.ar1_pair(10, 1.0)
    with pytest.raises(ValueError, match="seed"):
        systems.white_noise(10, seed=[])
