"""Seeded generators of coupled test systems whose coupling is known.

Each generator returns the observed signals of one pair, time on axis 0: shape ``(n, 2)`` for
one integer ``seed`` (column 0 is X, column 1 is Y), or ``(n, len(seed), 2)`` for a sequence of
seeds (one independent realization per seed, integrated as one batch). A seed fixes the initial
conditions (and the noise, where there is noise) through :func:`numpy.random.default_rng`, so
every figure of the benchmark is reproducible. Only NumPy is used.

=============================  ====================================================  ============
generator                      system                                                truth
=============================  ====================================================  ============
:func:`henon_pair`             identical Henon maps, X drives Y with strength C      X -> Y (C>0)
:func:`rossler_pair`           Rossler oscillators, X drives Y diffusively (kappa)   X -> Y (k>0)
:func:`lorenz_pair`            two uncoupled Lorenz systems (the same oscillator)    none
:func:`logistic_pair`          logistic maps, r_x and r_y, X drives Y with c         X -> Y (c>0)
:func:`rough_driver_response`  Henon x and its first-order low-pass                  X -> Y
:func:`unrelated_low_pass`     Henon x and the low-pass of another Henon run         none
:func:`white_noise`            independent Gaussian white noise                      none
:func:`ar1_pair`               independent AR(1), ``phi = 0.95`` by default          none
:func:`common_driver`          a Henon map Z drives two Henon maps X and Y           dependent,
                                                                                     no X<->Y
=============================  ====================================================  ============

The Henon, Rossler and logistic generators reproduce, for the same seeds, the values of the
generators that fixed the direction convention (``tests/test_direction.py``).

References
----------
M. Henon, "A two-dimensional mapping with a strange attractor", Commun. Math. Phys. 50 (1976).
O. E. Rossler, "An equation for continuous chaos", Phys. Lett. A 57 (1976).
E. N. Lorenz, "Deterministic nonperiodic flow", J. Atmos. Sci. 20 (1963).
M. C. Romano, M. Thiel, J. Kurths, C. Grebogi, "Estimation of the direction of the coupling by
conditional probabilities of recurrence", Phys. Rev. E 76, 036211 (2007) (coupled Henon and
Rossler systems as benchmarks).

Examples
--------
>>> henon_pair(100, 0.4, seed=3).shape, henon_pair(100, 0.4, seed=[1, 2]).shape
((100, 2), (100, 2, 2))
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

__all__ = [
    "henon_pair",
    "rossler_pair",
    "lorenz_pair",
    "logistic_pair",
    "low_pass",
    "rough_driver_response",
    "unrelated_low_pass",
    "white_noise",
    "ar1_pair",
    "common_driver",
]

Seed = int | Sequence[int]


def _seeds(seed: Seed) -> tuple[list[int], bool]:
    """``(seeds, single)``: the list of seeds and whether one integer was given."""
    if isinstance(seed, bool):
        raise ValueError("seed must be an integer or a non-empty sequence of integers")
    if isinstance(seed, (int, np.integer)):
        return [int(seed)], True
    seeds = [int(s) for s in seed]
    if not seeds:
        raise ValueError("seed must be an integer or a non-empty sequence of integers")
    return seeds, False


def _shape(out: np.ndarray, single: bool) -> np.ndarray:
    """``(n, 2)`` for one seed, ``(n, k, 2)`` for k seeds."""
    return out[:, 0, :] if single else out


def _check_n(n: int) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    return int(n)


def henon_pair(n: int, coupling: float = 0.0, *, seed: Seed = 0,
               transient: int = 1000) -> np.ndarray:
    """Identical Henon maps (a = 1.4, b = 0.3); X drives Y with strength ``coupling``.

    ``x' = 1.4 - x^2 + 0.3 x_prev``, ``y' = 1.4 - (C x + (1 - C) y) y + 0.3 y_prev``; the
    x-components are observed. Initial ``(x, x_prev, y, y_prev)`` uniform in [0, 0.5).

    Parameters
    ----------
    n : int
        Samples kept after the transient.
    coupling : float
        ``C`` in [0, 1]; 0 gives two independent maps.
    seed : int or sequence of int
        One realization per seed.
    transient : int
        Iterations discarded first.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    References
    ----------
    Henon (1976); the unidirectional coupling of Romano et al. (2007), section IV.

    Examples
    --------
    >>> data = henon_pair(500, 0.0, seed=[0, 1])
    >>> data.shape, bool(np.all(np.abs(data) < 2.0))
    ((500, 2, 2), True)
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    start = np.array([np.random.default_rng(s).uniform(0.0, 0.5, 4) for s in seeds])

    def update(x: np.ndarray, x_prev: np.ndarray, y: np.ndarray,
               y_prev: np.ndarray) -> tuple[np.ndarray, ...]:
        return (1.4 - x * x + 0.3 * x_prev, x,
                1.4 - (coupling * x + (1.0 - coupling) * y) * y + 0.3 * y_prev, y)

    return _shape(_iterate(update, tuple(start.T), n, transient, (0, 2)), single)


def _iterate(update: Callable[..., tuple[np.ndarray, ...]], state: tuple[np.ndarray, ...],
             n: int, transient: int, observed: tuple[int, int]) -> np.ndarray:
    """A map iterated on every realization at once: ``(n, realizations, 2)``, the two
    ``observed`` components of the state after ``transient`` iterations."""
    out = np.empty((n, len(state[0]), 2))
    for i in range(transient + n):
        if i >= transient:
            out[i - transient, :, 0] = state[observed[0]]
            out[i - transient, :, 1] = state[observed[1]]
        state = update(*state)
    return out


def _integrate(field: Callable[[np.ndarray], np.ndarray], state: np.ndarray, n: int,
               step: float, every: int, transient: float) -> np.ndarray:
    """Two oscillators of three variables each integrated on every realization at once
    (fixed-step RK4): ``(n, realizations, 2)``, their x components every ``every`` steps
    after ``transient`` time units."""
    for _ in range(round(transient / step)):
        state = _rk4(field, state, step)
    out = np.empty((n, len(state), 2))
    for i in range(n):
        out[i] = state[:, [0, 3]]
        for _ in range(every):
            state = _rk4(field, state, step)
    return out


def _rk4(field: Callable[[np.ndarray], np.ndarray], state: np.ndarray,
         step: float) -> np.ndarray:
    k1 = field(state)
    k2 = field(state + step / 2 * k1)
    k3 = field(state + step / 2 * k2)
    k4 = field(state + step * k3)
    return state + step / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def rossler_pair(n: int, coupling: float = 0.0, w_x: float = 1.015, w_y: float = 0.985, *,
                 seed: Seed = 0, step: float = 0.1, every: int = 2,
                 transient: float = 200.0) -> np.ndarray:
    """x-components of two Rossler oscillators, X -> Y by diffusive coupling (fixed-step RK4).

    ``dx/dt = -w y - z (+ kappa (x_X - x_Y) for Y)``, ``dy/dt = w x + 0.15 y``,
    ``dz/dt = 0.2 + z (x - 10)``. With the defaults X is the faster oscillator; swap ``w_x`` and
    ``w_y`` for a slower driver, set them equal for two copies of the same oscillator.

    Parameters
    ----------
    n : int
        Samples kept, one every ``every * step`` time units (0.2 by default: about 31 samples
        per mean period).
    coupling : float
        ``kappa`` >= 0.
    w_x, w_y : float
        Natural frequencies.
    seed : int or sequence of int
        Initial ``x, y`` of both oscillators uniform in [-5, 5), ``z = 0``.
    step, every, transient : float, int, float
        Integration step, steps per sample, time discarded first.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    References
    ----------
    Rossler (1976); Romano et al. (2007), section V.

    Examples
    --------
    >>> rossler_pair(50, 0.1, seed=0, transient=20.0).shape
    (50, 2)
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    a, b, c = 0.15, 0.2, 10.0
    state = np.zeros((len(seeds), 6))
    for row, s in enumerate(seeds):
        state[row, [0, 1, 3, 4]] = np.random.default_rng(s).uniform(-5.0, 5.0, 4)

    def field(s: np.ndarray) -> np.ndarray:
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

    return _shape(_integrate(field, state, n, step, every, transient), single)


def lorenz_pair(n: int, *, seed: Seed = 0, step: float = 0.01, every: int = 5,
                transient: float = 50.0) -> np.ndarray:
    """x-components of two uncoupled Lorenz systems (sigma 10, rho 28, beta 8/3): no coupling.

    Two independent copies of the same oscillator: both recur at the same lags, which makes
    circularly shifted surrogates invalid.

    Parameters
    ----------
    n : int
        Samples kept, one every ``every * step`` = 0.05 time units.
    seed : int or sequence of int
        Initial states uniform in [-10, 10)^2 x [10, 30).
    step, every, transient : float, int, float
        RK4 step, steps per sample, time discarded first.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    References
    ----------
    Lorenz (1963).

    Examples
    --------
    >>> data = lorenz_pair(200, seed=4)
    >>> data.shape, bool(np.abs(data).max() < 30)
    ((200, 2), True)
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    state = np.empty((len(seeds), 6))
    for row, s in enumerate(seeds):
        low = np.array([-10.0, -10.0, 10.0] * 2)
        state[row] = low + np.random.default_rng(s).uniform(0.0, 1.0, 6) * np.array(
            [20.0, 20.0, 20.0] * 2
        )

    def field(s: np.ndarray) -> np.ndarray:
        out = np.empty_like(s)
        for k in (0, 3):
            x, y, z = s[:, k], s[:, k + 1], s[:, k + 2]
            out[:, k] = 10.0 * (y - x)
            out[:, k + 1] = x * (28.0 - z) - y
            out[:, k + 2] = x * y - 8.0 / 3.0 * z
        return out

    return _shape(_integrate(field, state, n, step, every, transient), single)


def logistic_pair(n: int, r_x: float = 3.7, r_y: float = 4.0, coupling: float = 0.0, *,
                  seed: Seed = 0, transient: int = 1000) -> np.ndarray:
    """Logistic maps ``f_r(u) = r u (1 - u)``; X drives Y with strength ``coupling``.

    ``x' = f_{r_x}(x)``, ``y' = f_{r_y}((1 - c) y + c x)``; ``c = 0`` gives two uncoupled maps
    (with ``r_x != r_y`` the paper's asymmetry shows a "direction" there).

    Parameters
    ----------
    n : int
        Samples kept.
    r_x, r_y : float
        Map parameters in (0, 4].
    coupling : float
        ``c`` in [0, 1].
    seed : int or sequence of int
        Initial ``x, y`` uniform in [0.1, 0.9).
    transient : int
        Iterations discarded first.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    References
    ----------
    R. M. May, "Simple mathematical models with very complicated dynamics", Nature 261 (1976).

    Examples
    --------
    >>> data = logistic_pair(300, seed=0)
    >>> bool(((data > 0) & (data < 1)).all())
    True
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    start = np.array([np.random.default_rng(s).uniform(0.1, 0.9, 2) for s in seeds])

    def update(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, ...]:
        if coupling == 0.0:
            return r_x * x * (1.0 - x), r_y * y * (1.0 - y)
        u = (1.0 - coupling) * y + coupling * x
        return r_x * x * (1.0 - x), r_y * u * (1.0 - u)

    return _shape(_iterate(update, tuple(start.T), n, transient, (0, 1)), single)


def low_pass(x: np.ndarray, alpha: float = 0.9) -> np.ndarray:
    """First-order filter ``y[i+1] = alpha y[i] + (1 - alpha) x[i]``, ``y[0] = x[0]``, on axis 0.

    Parameters
    ----------
    x : ndarray, shape (n, ...)
    alpha : float
        Pole in [0, 1): time constant about ``1 / (1 - alpha)`` samples (10 by default).

    Returns
    -------
    ndarray
        Same shape as ``x``.

    Examples
    --------
    >>> low_pass(np.array([1.0, 0.0, 0.0]), alpha=0.5).tolist()
    [1.0, 1.0, 0.5]
    """
    x = np.asarray(x, dtype=np.float64)
    y = np.empty_like(x)
    y[0] = x[0]
    for i in range(len(x) - 1):
        y[i + 1] = alpha * y[i] + (1.0 - alpha) * x[i]
    return y


def rough_driver_response(n: int, *, seed: Seed = 0, alpha: float = 0.9,
                          settle: int = 100) -> np.ndarray:
    """A rough driver (Henon x) and its smooth low-pass response: X -> Y.

    Parameters
    ----------
    n : int
        Samples kept (after ``settle`` samples of the filter are dropped).
    seed : int or sequence of int
        The Henon map's seed (:func:`henon_pair` with C = 0, its X).
    alpha : float
        Filter pole (:func:`low_pass`).
    settle : int
        Samples discarded while the filter forgets its start.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    Examples
    --------
    >>> rough_driver_response(200, seed=1).shape
    (200, 2)
    """
    seeds, single = _seeds(seed)
    drivers = henon_pair(_check_n(n) + settle, 0.0, seed=seeds)[:, :, 0]
    out = np.stack([drivers, low_pass(drivers, alpha)], axis=-1)[settle:]
    return _shape(out, single)


def unrelated_low_pass(n: int, *, seed: Seed = 0, alpha: float = 0.9,
                       settle: int = 100) -> np.ndarray:
    """A rough signal (Henon x) and the low-pass of an unrelated Henon run: no coupling.

    The second run uses seed ``seed + 100003`` (the same map, independent initial conditions).

    Parameters
    ----------
    n, seed, alpha, settle
        As :func:`rough_driver_response`.

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    Examples
    --------
    >>> unrelated_low_pass(200, seed=[1, 2]).shape
    (200, 2, 2)
    """
    seeds, single = _seeds(seed)
    length = _check_n(n) + settle
    drivers = henon_pair(length, 0.0, seed=seeds)[:, :, 0]
    others = henon_pair(length, 0.0, seed=[s + 100003 for s in seeds])[:, :, 0]
    out = np.stack([drivers, low_pass(others, alpha)], axis=-1)[settle:]
    return _shape(out, single)


def white_noise(n: int, *, seed: Seed = 0) -> np.ndarray:
    """Two independent standard Gaussian white noises.

    Parameters
    ----------
    n : int
    seed : int or sequence of int

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    Examples
    --------
    >>> bool(np.array_equal(white_noise(10, seed=5), white_noise(10, seed=5)))
    True
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    out = np.stack([np.random.default_rng(s).standard_normal((n, 2)) for s in seeds], axis=1)
    return _shape(out, single)


def ar1_pair(n: int, phi: float = 0.95, *, seed: Seed = 0) -> np.ndarray:
    """Two independent stationary AR(1) processes ``u[t] = phi u[t-1] + e[t]``.

    The first value is drawn from the stationary law (variance ``1 / (1 - phi^2)``), so there
    is no transient.

    Parameters
    ----------
    n : int
    phi : float
        In (-1, 1).
    seed : int or sequence of int

    Returns
    -------
    ndarray
        ``(n, 2)``, or ``(n, len(seed), 2)``.

    Examples
    --------
    >>> ar1_pair(1000, seed=0).shape
    (1000, 2)
    """
    n = _check_n(n)
    if not -1.0 < phi < 1.0:
        raise ValueError(f"phi must be in (-1, 1), got {phi}")
    seeds, single = _seeds(seed)
    out = np.empty((n, len(seeds), 2))
    for k, s in enumerate(seeds):
        noise = np.random.default_rng(s).standard_normal((n, 2))
        u = noise[0] / np.sqrt(1.0 - phi * phi)
        for t in range(n):
            if t:
                u = phi * u + noise[t]
            out[t, k] = u
    return _shape(out, single)


def common_driver(n: int, coupling: float = 0.4, *, seed: Seed = 0,
                  transient: int = 1000) -> np.ndarray:
    """Two Henon maps X and Y, each driven by a third one Z, not by each other.

    ``x' = 1.4 - (C z + (1 - C) x) x + 0.3 x_prev``, likewise for ``y``. X and Y are dependent
    (a common cause) but neither drives the other: a dependence test should find them, a
    direction measure should find no direction.

    Parameters
    ----------
    n : int
    coupling : float
        ``C`` of both responses.
    seed : int or sequence of int
        Initial states of Z, X, Y uniform in [0, 0.5).
    transient : int

    Returns
    -------
    ndarray
        ``(n, 2)`` (X, Y), or ``(n, len(seed), 2)``; Z is not returned.

    Examples
    --------
    >>> common_driver(100, seed=0).shape
    (100, 2)
    """
    n = _check_n(n)
    seeds, single = _seeds(seed)
    start = np.array([np.random.default_rng(s).uniform(0.0, 0.5, 6) for s in seeds])

    def update(z: np.ndarray, z_prev: np.ndarray, x: np.ndarray, x_prev: np.ndarray,
               y: np.ndarray, y_prev: np.ndarray) -> tuple[np.ndarray, ...]:
        return (1.4 - z * z + 0.3 * z_prev, z,
                1.4 - (coupling * z + (1.0 - coupling) * x) * x + 0.3 * x_prev, x,
                1.4 - (coupling * z + (1.0 - coupling) * y) * y + 0.3 * y_prev, y)

    return _shape(_iterate(update, tuple(start.T), n, transient, (2, 4)), single)
