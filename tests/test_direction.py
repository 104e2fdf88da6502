"""The direction convention, fixed on systems whose coupling is known, and where it fails.

Convention (README "Direction", as in the code the paper used): a NEGATIVE ``C_diff`` /
``T_diff`` reads as X -> Y (pair kind ``x->y``). Every case below builds a two-node functional
network with the library's defaults (rr = cr = mu = 0.05, m = 3, min-max normalization, measure
"both") from N = 1500 samples after a discarded transient, over the seeds in ``SEEDS``, and
counts the pair kinds. The bounds were set after measuring seeds 0-19 with these same generators
(counts in the comments and in the README's "Direction" section) and leave a margin; the systems
were not tuned to pass.

Delays: tau = 1 for maps (one iterate); for the Rossler oscillators (sampled every 0.2 time
units, mean period about 6.3) tau = 8 samples, the first zero of the autocorrelation of x and the
first minimum of its auto mutual information (:func:`funcnet.core.recurrence.estimate_delay` gives
7-8).
"""

from __future__ import annotations

import warnings
from collections import Counter

import numpy as np
import pytest

from funcnet.errors import ThresholdWarning
from funcnet.network import functional_network

N = 1500
SEEDS = range(10)
MU = 0.05


def henon_pair(coupling, seeds, n=N, transient=1000):
    """Identical Henon maps (a = 1.4, b = 0.3), X drives Y with strength ``coupling``.

    ``x' = 1.4 - x^2 + 0.3 x_prev``; ``y' = 1.4 - (C x + (1 - C) y) y + 0.3 y_prev``. Returns an
    array (n, len(seeds), 2) of the x-components of X and Y.
    """
    start = np.array([np.random.default_rng(seed).uniform(0.0, 0.5, 4) for seed in seeds])
    x, x_prev, y, y_prev = start.T
    out = np.empty((n, len(start), 2))
    for i in range(transient + n):
        if i >= transient:
            out[i - transient, :, 0], out[i - transient, :, 1] = x, y
        x, x_prev, y, y_prev = (
            1.4 - x * x + 0.3 * x_prev,
            x,
            1.4 - (coupling * x + (1.0 - coupling) * y) * y + 0.3 * y_prev,
            y,
        )
    return out


def rossler_pair(coupling, w_x, w_y, seeds, n=N, step=0.1, every=2, transient=200.0):
    """x-components of two Rossler oscillators, X -> Y by diffusive coupling (fixed-step RK4).

    ``dx/dt = -w y - z (+ coupling (x_X - x_Y) for Y)``, ``dy/dt = w x + 0.15 y``,
    ``dz/dt = 0.2 + z (x - 10)``; one row of the batch per entry of ``seeds`` (``coupling``,
    ``w_x``, ``w_y`` broadcast). Sampled every ``every * step`` = 0.2 time units after
    ``transient`` time units. Returns (n, len(seeds), 2).
    """
    a, b, c = 0.15, 0.2, 10.0
    rows = len(seeds)
    coupling, w_x, w_y = (
        np.broadcast_to(np.asarray(v, float), (rows,)) for v in (coupling, w_x, w_y)
    )
    state = np.zeros((rows, 6))
    for row, seed in enumerate(seeds):
        state[row, [0, 1, 3, 4]] = np.random.default_rng(seed).uniform(-5.0, 5.0, 4)

    def field(s):
        x1, y1, z1, x2, y2, z2 = s.T
        return np.stack(
            [
                -w_x * y1 - z1,
                w_x * x1 + a * y1,
                b + z1 * (x1 - c),
                -w_y * y2 - z2 + coupling * (x1 - x2),
                w_y * x2 + a * y2,
                b + z2 * (x2 - c),
            ],
            axis=1,
        )

    def rk4(s):
        k1 = field(s)
        k2 = field(s + step / 2 * k1)
        k3 = field(s + step / 2 * k2)
        k4 = field(s + step * k3)
        return s + step / 6 * (k1 + 2 * k2 + 2 * k3 + k4)

    for _ in range(round(transient / step)):
        state = rk4(state)
    out = np.empty((n, rows, 2))
    for i in range(n):
        out[i] = state[:, [0, 3]]
        for _ in range(every):
            state = rk4(state)
    assert np.isfinite(out).all()
    return out


def logistic_pair(r_x, r_y, seeds, n=N, transient=1000):
    """Two UNCOUPLED logistic maps ``x' = r x (1 - x)``; returns (n, len(seeds), 2)."""
    x, y = np.array([np.random.default_rng(seed).uniform(0.1, 0.9, 2) for seed in seeds]).T
    out = np.empty((n, len(x), 2))
    for i in range(transient + n):
        if i >= transient:
            out[i - transient, :, 0], out[i - transient, :, 1] = x, y
        x, y = r_x * x * (1.0 - x), r_y * y * (1.0 - y)
    return out


def low_pass(x, alpha=0.9):
    """First-order filter ``y[i+1] = alpha y[i] + (1 - alpha) x[i]`` (time constant ~10)."""
    y = np.empty_like(x)
    y[0] = x[0]
    for i in range(len(x) - 1):
        y[i + 1] = alpha * y[i] + (1.0 - alpha) * x[i]
    return y


def pair_rows(signal_pairs, delay):
    """The pairs-table row of the two-node network of each (x, y) array, thresholds warnings off.

    eps_xy >= eps_x, eps_y is common at rr = cr = 0.05; the warning is tested in test_network.
    """
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ThresholdWarning)
        for data in signal_pairs:
            rows.append(functional_network(data, names=["x", "y"], delay=delay).pairs.iloc[0])
    return rows


def kinds(rows):
    return Counter(row["kind"] for row in rows)


def columns(batch):
    return [batch[:, seed] for seed in range(batch.shape[1])]


# --- where the convention is fixed: identical Henon maps, X drives Y -------------------------


@pytest.mark.parametrize("coupling", [0.2, 0.6])
def test_henon_x_driving_y_reads_as_negative_differences(coupling):
    # Measured on 20 seeds: x->y in 20/20 at C = 0.2 and at C = 0.6 (both diffs <= -0.044).
    rows = pair_rows(columns(henon_pair(coupling, SEEDS)), delay=1)
    assert kinds(rows)["x->y"] >= 8
    assert sum(row["c_diff"] < 0 and row["t_diff"] < 0 for row in rows) >= 8
    assert np.median([row["c_diff"] for row in rows]) <= -MU


def test_swapping_the_signals_mirrors_every_number():
    data = henon_pair(0.6, [0])[:, 0]
    (forward,) = pair_rows([data], delay=1)
    (backward,) = pair_rows([data[:, ::-1]], delay=1)
    assert forward["kind"] == "x->y" and backward["kind"] == "y->x"
    for xy, yx in (("c_xy", "c_yx"), ("t_xy", "t_yx"), ("eps_x", "eps_y")):
        assert backward[xy] == forward[yx] and backward[yx] == forward[xy]
    np.testing.assert_allclose(
        backward[["c_diff", "t_diff"]].to_numpy(float),
        -forward[["c_diff", "t_diff"]].to_numpy(float),
        atol=1e-15,
    )


def test_uncoupled_identical_henon_maps_show_no_arrow():
    # Measured: bidirectional in 20/20 seeds, |diff| <= 0.021.
    rows = pair_rows(columns(henon_pair(0.0, SEEDS)), delay=1)
    assert kinds(rows)["bidirectional"] >= 8
    assert np.median([abs(row["t_diff"]) for row in rows]) < MU / 2


def test_henon_direction_is_not_monotonic_in_the_coupling():
    # Measured at C = 0.4: C_diff > 0 (reads Y -> X) in 20/20 seeds while T_diff < 0; the
    # combined network said y->x in 13/20, x->y in 3/20. A coupling strength between the two
    # working ones above gives the wrong arrow.
    rows = pair_rows(columns(henon_pair(0.4, SEEDS)), delay=1)
    assert sum(row["c_diff"] > 0 for row in rows) >= 8
    assert sum(row["t_diff"] < 0 for row in rows) >= 8
    assert kinds(rows)["x->y"] <= 3


# --- Rossler oscillators with slightly different frequencies ---------------------------------


@pytest.fixture(scope="module")
def rossler():
    """Three configurations x SEEDS in one integration: faster driver, slower driver, uncoupled."""
    configs = {
        "faster driver": (0.07, 1.015, 0.985),
        "slower driver": (0.07, 0.985, 1.015),
        "uncoupled": (0.0, 1.015, 0.985),
    }
    seeds = list(SEEDS)
    batch = rossler_pair(
        [c for c, _, _ in configs.values() for _ in seeds],
        [w for _, w, _ in configs.values() for _ in seeds],
        [w for _, _, w in configs.values() for _ in seeds],
        seeds * len(configs),
    )
    return {
        name: pair_rows(columns(batch[:, k * len(seeds) : (k + 1) * len(seeds)]), delay=8)
        for k, name in enumerate(configs)
    }


def test_rossler_faster_driver_reads_the_true_direction(rossler):
    # X (w = 1.015) -> Y (w = 0.985), coupling 0.07. Measured: x->y in 20/20 seeds.
    assert kinds(rossler["faster driver"])["x->y"] >= 8


def test_rossler_arrow_follows_the_faster_oscillator_not_the_coupling(rossler):
    # Uncoupled, X the faster one: measured x->y in 18/20 (C_diff about -0.10 without coupling).
    assert kinds(rossler["uncoupled"])["x->y"] >= 7
    # X the SLOWER one drives Y (coupling 0.07): measured y->x (wrong) in 17/20, x->y in 0/20.
    slower = kinds(rossler["slower driver"])
    assert slower["y->x"] >= 6
    assert slower["x->y"] <= 2


# --- where an arrow means roughness, not coupling --------------------------------------------


def test_rough_driver_and_smooth_signal_read_alike_coupled_or_not():
    # X: Henon x (rough). Coupled: Y = low_pass(X); uncoupled: Y = low_pass(another Henon run).
    # Measured: x->y in 20/20 for both, |diffs| of the same size (~0.05-0.15).
    drivers = henon_pair(0.0, SEEDS, n=N + 100)[:, :, 0]
    others = henon_pair(0.0, [seed + 100 for seed in SEEDS], n=N + 100)[:, :, 0]
    coupled = pair_rows([np.column_stack([d, low_pass(d)])[100:] for d in drivers.T], delay=1)
    unrelated = pair_rows(
        [np.column_stack([d, low_pass(o)])[100:] for d, o in zip(drivers.T, others.T, strict=True)],
        delay=1,
    )
    assert kinds(coupled)["x->y"] >= 8
    assert kinds(unrelated)["x->y"] >= 8
    assert sum(max(abs(row["c_diff"]), abs(row["t_diff"])) >= MU for row in unrelated) >= 8


def test_smooth_driver_of_a_rough_response_reads_backwards():
    # X: low-pass-filtered Henon (smooth, min-max scaled); Y: logistic map whose parameter X
    # modulates, r = 3.6 + 0.4 X, so X -> Y. Measured: y->x (wrong) in 17/20, x->y in 0/20.
    rows = []
    for driver in henon_pair(0.0, SEEDS, n=N + 100)[:, :, 0].T:
        x = low_pass(driver)
        x = (x - x.min()) / (x.max() - x.min())
        y = np.empty_like(x)
        y[0] = 0.3
        for i in range(len(x) - 1):
            y[i + 1] = (3.6 + 0.4 * x[i]) * y[i] * (1.0 - y[i])
        rows.append(np.column_stack([x, y])[100:])
    counts = kinds(pair_rows(rows, delay=1))
    assert counts["y->x"] >= 6
    assert counts["x->y"] <= 1


def test_uncoupled_logistic_maps_show_a_direction():
    # r = 3.7 (X) and r = 4.0 (Y), no coupling at all. Measured over 20 seeds: C_diff in
    # [0.278, 0.304], T_diff in [0.175, 0.232]: y->x every time, far beyond mu.
    rows = pair_rows(columns(logistic_pair(3.7, 4.0, SEEDS)), delay=1)
    assert kinds(rows)["y->x"] == len(SEEDS)
    assert all(row["c_diff"] >= 0.2 and row["t_diff"] >= 0.1 for row in rows)


def test_the_papers_fig2_sine_pair_reads_backwards():
    # x = sin(t) drives y = sin(1.5 t) + 0.3 x (N = 251, m = 3, tau = 10, the paper's Fig. 2):
    # C_diff = +0.11 reads Y -> X, T_diff = -0.03 stays below mu; the combined edge is y -> x.
    # The two-frequency response is the "richer" signal.
    t = np.linspace(0, 8 * np.pi, 251)
    (row,) = pair_rows([np.column_stack([np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)])], delay=10)
    assert row["c_diff"] >= MU and abs(row["t_diff"]) < MU
    assert row["kind"] == "y->x"
