"""rule="pyunicorn" reproduces pyunicorn 1.0.0's InterSystemRecurrenceNetwork.

pyunicorn's own dim=/tau= arguments fail in 1.0.0, so the signals are embedded first (with
funcnet.embed, Eq. 1) and the embedded arrays passed to pyunicorn, with the same metric and
recurrence_rate=(rr, rr, cr) or threshold=(eps_x, eps_y, eps_xy). Sizes stay at M <= 300 because
pyunicorn's dense triple loops are slow.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from pyunicorn import timeseries as pyunicorn_timeseries  # a test dependency: never skipped

from funcnet.core.embedding import embed
from funcnet.core.measures import cross_degree, cross_measures, local_cross_clustering
from funcnet.errors import ThresholdWarning


def fig2_pair():
    t = np.linspace(0, 8 * np.pi, 251)
    x = np.sin(t)
    return x, np.sin(1.5 * t) + 0.3 * x


def henon_pair(n, coupling, seed):
    rng = np.random.default_rng(seed)
    x, y = rng.uniform(0, 0.5, size=(2, 2))
    xs, ys = [], []
    for _ in range(n + 200):
        x = np.array([1.4 - x[0] ** 2 + 0.3 * x[1], x[0]])
        drive = coupling * x[0] + (1 - coupling) * y[0]
        y = np.array([1.4 - drive * y[0] + 0.3 * y[1], y[0]])
        xs.append(x[0])
        ys.append(y[0])
    return np.array(xs[200:]), np.array(ys[200:])


def random_pair(n_x, n_y, seed):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.normal(size=n_x))
    y = np.round(3 * np.sin(np.arange(n_y) / 7.0) + rng.normal(size=n_y), 1)
    return x, y


def signals(case):
    if case == "fig2":
        return fig2_pair()
    if case == "henon":
        return henon_pair(260, 0.3, 1)
    if case == "random":
        return random_pair(240, 300, 2)
    raise ValueError(case)


CASES = [
    # (signals, dim, delay, metric, rates or None, explicit thresholds or None)
    ("fig2", 3, 10, "supremum", (0.05, 0.05), None),
    ("fig2", 3, 10, "euclidean", (0.05, 0.05), None),
    ("fig2", 3, 10, "manhattan", (0.05, 0.05), None),
    ("fig2", 3, 10, "supremum", (0.1, 0.02), None),
    ("fig2", 3, 10, "euclidean", (0.1, 0.02), None),
    ("fig2", 3, 10, "manhattan", (0.03, 0.01), None),
    ("fig2", 3, 10, "supremum", (0.2, 0.1), None),
    ("fig2", 3, 10, "euclidean", None, (0.15, 0.15, 0.05)),
    ("fig2", 3, 10, "supremum", None, (0.15, 0.15, 0.05)),
    ("fig2", 3, 10, "manhattan", None, (0.3, 0.25, 0.1)),
    ("fig2", 2, 5, "euclidean", (0.05, 0.05), None),
    ("henon", 2, 1, "supremum", (0.05, 0.05), None),
    ("henon", 2, 1, "euclidean", (0.05, 0.03), None),
    ("henon", 3, 1, "manhattan", (0.08, 0.04), None),
    ("henon", 2, 1, "euclidean", None, (0.2, 0.2, 0.1)),
    ("random", 3, 2, "supremum", (0.05, 0.05), None),
    ("random", 3, 2, "euclidean", (0.05, 0.05), None),
    ("random", 2, 4, "manhattan", (0.1, 0.03), None),
    ("random", 1, 1, "supremum", (0.05, 0.05), None),
    ("random", 1, 1, "euclidean", (0.12, 0.07), None),
    ("random", 3, 2, "euclidean", None, (2.0, 1.5, 1.0)),
    ("random", 2, 3, "supremum", None, (1.0, 0.6, 0.4)),
]


@pytest.mark.parametrize(("case", "dim", "delay", "metric", "rates", "thresholds"), CASES)
def test_rule_pyunicorn_reproduces_pyunicorn(case, dim, delay, metric, rates, thresholds):
    x, y = signals(case)
    x_states, y_states = embed(x, dim, delay), embed(y, dim, delay)
    if rates is not None:
        rr, cr = rates
        network = pyunicorn_timeseries.InterSystemRecurrenceNetwork(
            x_states, y_states, metric=metric, recurrence_rate=(rr, rr, cr), silence_level=3
        )
        common = {"rr": rr, "cr": cr}
    else:
        network = pyunicorn_timeseries.InterSystemRecurrenceNetwork(
            x_states, y_states, metric=metric, threshold=thresholds, silence_level=3
        )
        common = {"eps": (thresholds[:2], thresholds[2])}
    common.update(dim=dim, delay=delay, metric=metric, rule="pyunicorn")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        result = cross_measures(x, y, **common)
    assert result.c_xy == pytest.approx(network.cross_global_clustering_xy(), abs=1e-9)
    assert result.c_yx == pytest.approx(network.cross_global_clustering_yx(), abs=1e-9)
    assert result.t_xy == pytest.approx(network.cross_transitivity_xy(), abs=1e-9)
    assert result.t_yx == pytest.approx(network.cross_transitivity_yx(), abs=1e-9)
    assert result.achieved_cr == pytest.approx(network.cross_recurrence_rate(), abs=1e-12)
    # pyunicorn's internal rates count the diagonal; funcnet's count off-diagonal candidates.
    m_x, m_y = x_states.shape[0], y_states.shape[0]
    rr_x, rr_y = network.internal_recurrence_rates()
    assert result.achieved_rr_x * m_x * (m_x - 1) == pytest.approx(rr_x * m_x**2 - m_x, abs=1e-6)
    assert result.achieved_rr_y * m_y * (m_y - 1) == pytest.approx(rr_y * m_y**2 - m_y, abs=1e-6)


@pytest.mark.parametrize("metric", ["supremum", "euclidean"])
def test_rule_pyunicorn_reproduces_local_values(metric):
    x, y = fig2_pair()
    x_states, y_states = embed(x, 3, 10), embed(y, 3, 10)
    network = pyunicorn_timeseries.InterSystemRecurrenceNetwork(
        x_states, y_states, metric=metric, recurrence_rate=(0.05, 0.05, 0.05), silence_level=3
    )
    nodes_x = np.arange(x_states.shape[0])
    nodes_y = np.arange(x_states.shape[0], x_states.shape[0] + y_states.shape[0])
    common = {"dim": 3, "delay": 10, "metric": metric, "rule": "pyunicorn"}
    c_xy, c_yx = local_cross_clustering(x, y, **common)
    np.testing.assert_allclose(c_xy, network.cross_local_clustering(nodes_x, nodes_y), atol=1e-12)
    np.testing.assert_allclose(c_yx, network.cross_local_clustering(nodes_y, nodes_x), atol=1e-12)
    k_xy, k_yx = cross_degree(x, y, **common)
    np.testing.assert_array_equal(k_xy, network.cross_degree(nodes_x, nodes_y))
    np.testing.assert_array_equal(k_yx, network.cross_degree(nodes_y, nodes_x))
