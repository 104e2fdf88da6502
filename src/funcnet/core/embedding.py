"""Delay embedding (paper Eq. 1) and the estimation of its parameters from the data.

A signal ``x`` of ``N`` samples becomes ``M = N - (dim - 1) * delay`` states
``x_i = [x(t_i), x(t_i + delay), ..., x(t_i + (dim - 1) * delay)]`` (Eq. 1). :func:`embed` is the
plain definition; :func:`signal_states` gives the states the measures use: it validates the
signal (finite values, at least :data:`MIN_STATES` states), applies the ``rule="pyunicorn"``
float32 cast, and embeds a multichannel node -- a signal given as an ``(N, c)`` array -- by
embedding each channel with the same ``(dim, delay)`` and concatenating the states (dimension
``c * dim``, channel by channel).

:func:`estimate_delay` (first minimum of the auto mutual information) and
:func:`estimate_dimension` (false nearest neighbours or Cao) suggest ``delay`` and ``dim``.
"""

from __future__ import annotations

import math
import numbers
from typing import Any, Unpack

import numpy as np

from funcnet.errors import ParameterError, SignalError
from funcnet.parameters import (
    NetworkParameters,
    ParameterOverrides,
    check_eps_value,
    check_int,
    resolve,
)

__all__ = [
    "MIN_STATES",
    "min_samples",
    "embed",
    "signal_states",
    "thinning",
    "thinned",
    "estimate_delay",
    "estimate_dimension",
]

#: The fewest embedded states a signal may give to the measures: with 7 states the paper's rate
#: 0.05 selects 3 of the 42 ordered pairs of ``A_X`` (2 unordered: more than one pair) and 3 of
#: the 49 pairs of ``CR_XY``; with fewer, one pair or none decides a whole structure.
MIN_STATES = 7


def min_samples(dim: int, delay: int) -> int:
    """The fewest samples a signal needs to give :data:`MIN_STATES` states at ``dim``, ``delay``.

    Examples
    --------
    >>> min_samples(3, 10)
    27
    """
    return (dim - 1) * delay + MIN_STATES


# --------------------------------------------------------------------------------------------
# validation


def _first_bad(values: np.ndarray, name: str) -> None:
    bad = ~np.isfinite(values)
    if bad.any():
        first = int(np.flatnonzero(bad)[0])
        raise SignalError(
            f"signal {name} has {int(bad.sum())} NaN or infinite value(s), the first at index "
            f"{first}"
        )


def _check_signal(x: Any, name: str) -> np.ndarray:
    """Return ``x`` as a 1-D float64 array of finite values, or raise naming it."""
    array = np.asarray(x)
    if array.ndim == 2 and array.shape[1] == 1:
        array = array[:, 0]
    if array.ndim != 1:
        raise SignalError(f"signal {name} must be one-dimensional, got shape {array.shape}")
    if array.dtype.kind not in "biuf":
        raise SignalError(f"signal {name} must be real-valued, got dtype {array.dtype}")
    array = array.astype(np.float64, copy=False)
    _first_bad(array, name)
    return array


def _check_node(x: Any, name: str) -> np.ndarray:
    """``x`` as a 2-D float64 array ``(N, channels)`` of finite values (1-D: one channel)."""
    array = np.asarray(x)
    if array.ndim == 1:
        array = array[:, np.newaxis]
    if array.ndim != 2 or array.shape[1] < 1:
        raise SignalError(
            f"signal {name} must be 1-D (N,) or 2-D (N, channels), got shape {array.shape}"
        )
    if array.dtype.kind not in "biuf":
        raise SignalError(f"signal {name} must be real-valued, got dtype {array.dtype}")
    array = array.astype(np.float64, copy=False)
    for channel in range(array.shape[1]):
        label = name if array.shape[1] == 1 else f"{name} (channel {channel})"
        _first_bad(array[:, channel], label)
    return array


def _n_states(n_samples: int, dim: int, delay: int, name: str, minimum: int) -> int:
    n_states = n_samples - (dim - 1) * delay
    if n_states < minimum:
        raise SignalError(
            f"signal {name} is too short for the embedding: {n_samples} samples with dim={dim}, "
            f"delay={delay} give {max(n_states, 0)} state(s), at least {minimum} needed "
            f"(N >= {(dim - 1) * delay + minimum})"
        )
    return n_states


# --------------------------------------------------------------------------------------------
# embedding


def _delay_rows(signal: np.ndarray, dim: int, delay: int, n_states: int) -> np.ndarray:
    states = np.empty((n_states, dim), dtype=np.float64)
    for column in range(dim):
        states[:, column] = signal[column * delay : column * delay + n_states]
    return states


def embed(x: Any, dim: int, delay: int) -> np.ndarray:
    """Delay embedding of a scalar signal (Eq. 1).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal, finite real values, time on axis 0.
    dim : int
        Embedding dimension ``m >= 1``.
    delay : int
        Delay ``tau >= 1`` in samples.

    Returns
    -------
    ndarray, shape (N - (dim - 1) * delay, dim), float64
        Row ``i`` is ``[x[i], x[i + delay], ..., x[i + (dim - 1) * delay]]``.

    Raises
    ------
    ParameterError
        ``dim`` or ``delay`` is not a positive integer.
    SignalError
        ``x`` is not 1-D, holds NaN or inf, or is too short to give one state.

    References
    ----------
    Eq. 1 of El Dabett, Hansen & Geier (section 2.1).

    Examples
    --------
    >>> embed([0, 1, 2, 3, 4, 5], dim=3, delay=2)
    array([[0., 2., 4.],
           [1., 3., 5.]])
    """
    dim = check_int(dim, "dim", 1)
    delay = check_int(delay, "delay", 1)
    signal = _check_signal(x, "x")
    return _delay_rows(signal, dim, delay, _n_states(signal.size, dim, delay, "x", 1))


def thinning(n_states: int, max_states: int | None) -> int:
    """``d``: keep every ``d``-th of ``n_states`` states so that at most ``max_states`` are kept
    (every state when ``max_states`` is None); ``max_states`` is at least :data:`MIN_STATES`.

    Examples
    --------
    >>> thinning(5306, 1500), thinning(1500, 1500), thinning(899_980, 1500), thinning(80, None)
    (4, 1, 600, 1)
    """
    if max_states is None:
        return 1
    return max(1, math.ceil(n_states / check_int(max_states, "max_states", MIN_STATES)))


def thinned(parameters: NetworkParameters, step: int) -> NetworkParameters:
    """The parameters on every ``step``-th state: the Theiler window, in samples, spans
    ``ceil(theiler / step)`` thinned states.

    Examples
    --------
    >>> thinned(NetworkParameters(theiler=5), 2).theiler
    3
    """
    step = check_int(step, "step", 1)
    if step == 1 or parameters.theiler == 0:
        return parameters
    return parameters.replace(theiler=math.ceil(parameters.theiler / step))


def signal_states(
    x: Any,
    *,
    parameters: NetworkParameters | None = None,
    name: str = "x",
    step: int = 1,
    **overrides: Unpack[ParameterOverrides],
) -> np.ndarray:
    """Validated embedded states of one node, as the measures use them.

    Each channel of ``x`` is embedded with ``(dim, delay)`` (Eq. 1) and the states of the
    channels are concatenated: a 1-D signal gives ``dim`` coordinates, an ``(N, c)``
    multichannel node ``c * dim`` (channel 0's ``dim`` coordinates first). Under
    ``rule="pyunicorn"`` the values are cast to float32 first (then embedded in float64), as
    pyunicorn 1.0.0 does.

    Parameters
    ----------
    x : array_like, shape (N,) or (N, c)
        The signal, or a multichannel node (one channel per column), time on axis 0.
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay`` and ``rule``; defaults from :class:`NetworkParameters`.
    name : str
        How error messages call the signal.
    step : int
        Keep every ``step``-th state (the first included): a long window thinned to a bounded
        number of states (:func:`thinning`), each state embedded at the full rate.
    **overrides
        ``dim``, ``delay``, ``rule``: replace those of ``parameters``.

    Returns
    -------
    ndarray, shape (M, c * dim), float64, C-contiguous
        ``M = ceil((N - (dim - 1) * delay) / step)``; the states before thinning number at
        least ``MIN_STATES``.

    Raises
    ------
    ParameterError
        Bad ``dim``, ``delay`` or ``rule``, or another override.
    SignalError
        Not real, not finite, amplitudes beyond float32 under ``rule="pyunicorn"``, or fewer
        than :data:`MIN_STATES` states; the message names the signal.

    References
    ----------
    Eq. 1 (section 2.1); docs/guide/method.md, "pyunicorn compatibility", for the cast.

    Examples
    --------
    >>> float(signal_states([0.1, 0.2, 0.3, 0.4] * 2, dim=2, delay=1, rule="pyunicorn")[0, 0])
    0.10000000149011612
    >>> signal_states(np.arange(20.0).reshape(10, 2), dim=2, delay=3)[0]
    array([0., 6., 1., 7.])
    >>> signal_states(np.arange(10.0), dim=2, delay=3, step=3)
    array([[0., 3.],
           [3., 6.],
           [6., 9.]])
    """
    step = check_int(step, "step", 1)
    states = _signal_states(x, resolve(parameters, overrides, allowed=("dim", "delay", "rule")),
                            name)
    return states if step == 1 else np.ascontiguousarray(states[::step])


def _signal_states(x: Any, p: NetworkParameters, name: str) -> np.ndarray:
    """:func:`signal_states` of every state."""
    node = _check_node(x, name)
    if p.rule == "pyunicorn":
        with np.errstate(over="ignore"):  # reported just below
            node = node.astype(np.float32).astype(np.float64)
        if not np.isfinite(node).all():
            raise SignalError(
                f"signal {name} has amplitudes beyond float32 (about 3.4e38), the precision "
                "rule='pyunicorn' casts to"
            )
    n_states = _n_states(node.shape[0], p.dim, p.delay, name, MIN_STATES)
    if node.shape[1] == 1:
        return _delay_rows(node[:, 0], p.dim, p.delay, n_states)
    return np.ascontiguousarray(
        np.hstack([_delay_rows(node[:, c], p.dim, p.delay, n_states) for c in range(node.shape[1])])
    )


# --------------------------------------------------------------------------------------------
# embedding parameters from the data


def _mutual_information(a: np.ndarray, b: np.ndarray, edges: np.ndarray, smoothing: float) -> float:
    from scipy.ndimage import gaussian_filter

    joint, _, _ = np.histogram2d(a, b, bins=(edges, edges))
    if smoothing > 0:
        joint = gaussian_filter(joint, smoothing, mode="constant")
    joint /= joint.sum()
    expected = np.outer(joint.sum(axis=1), joint.sum(axis=0))
    nonzero = joint > 0
    return float((joint[nonzero] * np.log(joint[nonzero] / expected[nonzero])).sum())


def estimate_delay(
    x: Any, *, max_delay: int | None = None, bins: int = 64, smoothing: float = 4.0
) -> int:
    """Embedding delay: the first local minimum of the auto mutual information (Fraser-Swinney).

    ``I(tau)`` between ``x[t]`` and ``x[t + tau]`` is estimated from a 2-D histogram with
    ``bins`` equal-width bins over the range of ``x``, smoothed with a Gaussian kernel of
    ``smoothing`` bins (a kernel density estimate: a plain histogram makes ``I(tau)`` jagged, and
    its first "minimum" an artefact of the binning, on smooth or periodic signals).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal.
    max_delay : int, optional
        Largest delay tried (default ``N // 4``).
    bins : int
        Histogram bins per axis (default 64).
    smoothing : float
        Standard deviation of the smoothing kernel, in bins (default 4; 0 for none).

    Returns
    -------
    int
        The smallest ``tau >= 1`` with ``I(tau - 1) > I(tau) <= I(tau + 1)``.

    Raises
    ------
    ParameterError
        Bad ``max_delay``, ``bins`` or ``smoothing``.
    SignalError
        ``x`` not finite, constant, too short, or without a minimum up to ``max_delay``.

    References
    ----------
    Eq. 1 (the embedding the delay is for); A. M. Fraser and H. L. Swinney, Phys. Rev. A 33,
    1134 (1986).

    Examples
    --------
    A sine of period 100 samples: a quarter period.

    >>> import numpy as np
    >>> estimate_delay(np.sin(2 * np.pi * np.arange(2000) / 100))
    25
    """
    signal = _check_signal(x, "x")
    bins = check_int(bins, "bins", 2)
    if isinstance(smoothing, bool) or not isinstance(smoothing, numbers.Real) or not (
        0 <= smoothing < math.inf
    ):
        raise ParameterError.of("smoothing", f"must be a finite number >= 0, got {smoothing!r}")
    if max_delay is None:
        max_delay = signal.size // 4
    max_delay = check_int(max_delay, "max_delay", 1)
    if signal.size < max_delay + 3:
        raise SignalError(
            f"signal x is too short ({signal.size} samples) for max_delay={max_delay}"
        )
    if signal.min() == signal.max():
        raise SignalError("signal x is constant: its mutual information has no minimum")
    edges = np.linspace(signal.min(), signal.max(), bins + 1)

    def information(tau: int) -> float:
        return _mutual_information(signal[: signal.size - tau], signal[tau:], edges, smoothing)

    previous, current = information(0), information(1)
    for tau in range(1, max_delay + 1):
        following = information(tau + 1)
        if previous > current <= following:
            return tau
        previous, current = current, following
    raise SignalError(
        f"the auto mutual information of x has no minimum up to max_delay={max_delay}"
    )


def _nearest_neighbours(states: np.ndarray, p: float) -> tuple[np.ndarray, np.ndarray]:
    # Nearest other state of every state (p-norm); states at distance 0 are skipped by asking
    # for a few neighbours and taking the first at a positive distance.
    from scipy.spatial import cKDTree

    distances, indices = cKDTree(states).query(states, k=min(8, states.shape[0]), p=p)
    positive = distances > 0
    first = np.argmax(positive, axis=1)
    rows = np.arange(states.shape[0])
    found = positive[rows, first]
    return np.where(found, indices[rows, first], -1), np.where(found, distances[rows, first], 0.0)


def estimate_dimension(
    x: Any,
    *,
    delay: int,
    max_dim: int = 10,
    method: str = "fnn",
    rtol: float = 15.0,
    atol: float = 2.0,
    fraction: float = 0.01,
    saturation: float = 0.9,
) -> int:
    """Embedding dimension by false nearest neighbours (Kennel) or Cao's method.

    ``"fnn"``: the nearest neighbour of each state in dimension ``d`` is *false* when adding the
    coordinate ``d + 1`` stretches their distance ``R_d`` by more than ``rtol * R_d`` or makes it
    exceed ``atol`` times the signal's standard deviation; the answer is the first ``d`` whose
    fraction of false neighbours is below ``fraction``.
    ``"cao"``: ``E1(d) = E(d + 1) / E(d)`` with ``E(d)`` the mean stretch of supremum-norm nearest
    neighbour distances from ``d`` to ``d + 1``; the answer is the first ``d`` with
    ``E1(d) >= saturation`` (``E1`` approaching 1 means an added coordinate stops unfolding).

    Parameters
    ----------
    x : array_like, shape (N,)
        The signal.
    delay : int
        Embedding delay (e.g. from :func:`estimate_delay`).
    max_dim : int
        Largest dimension tried (default 10); returned when no smaller one qualifies.
    method : {"fnn", "cao"}
        The criterion.
    rtol, atol, fraction : float
        FNN thresholds (Kennel et al.'s 15 and 2, and the accepted fraction 1 %).
    saturation : float
        Cao threshold on ``E1``.

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        Bad ``delay``, ``max_dim``, ``method`` or thresholds.
    SignalError
        ``x`` not finite, constant or too short for ``max_dim + 1`` coordinates.

    References
    ----------
    Eq. 1; M. B. Kennel, R. Brown, H. D. I. Abarbanel, Phys. Rev. A 45, 3403 (1992);
    L. Cao, Physica D 110, 43 (1997).

    Examples
    --------
    The Henon map needs two dimensions:

    >>> import numpy as np
    >>> u, v = 0.1, 0.1
    >>> series = []
    >>> for _ in range(3000):
    ...     u, v = 1 - 1.4 * u * u + v, 0.3 * u
    ...     series.append(u)
    >>> estimate_dimension(series[100:], delay=1)
    2
    """
    signal = _check_signal(x, "x")
    delay = check_int(delay, "delay", 1)
    max_dim = check_int(max_dim, "max_dim", 1)
    if method not in ("fnn", "cao"):
        raise ParameterError.of("method", f"must be 'fnn' or 'cao', got {method!r}")
    for value, name in (
        (rtol, "rtol"),
        (atol, "atol"),
        (fraction, "fraction"),
        (saturation, "saturation"),
    ):
        check_eps_value(value, name)
    std = float(signal.std())
    if std == 0.0:
        raise SignalError("signal x is constant: no embedding dimension can be estimated")
    n_states = _n_states(signal.size, max_dim + 2, delay, "x", 10)
    stretch = []
    # Cao's E1(d) needs E(d + 1): one dimension more than the FNN test.
    for d in range(1, max_dim + (2 if method == "cao" else 1)):
        states = _delay_rows(signal, d, delay, n_states)
        following = signal[d * delay : d * delay + n_states]
        neighbour, distance = _nearest_neighbours(states, 2.0 if method == "fnn" else np.inf)
        valid = neighbour >= 0
        gap = np.abs(following[valid] - following[neighbour[valid]])
        if method == "fnn":
            false = (gap > rtol * distance[valid]) | (np.hypot(distance[valid], gap) > atol * std)
            if false.mean() < fraction:
                return d
        else:
            stretched = np.maximum(distance[valid], gap)
            stretch.append(float((stretched / distance[valid]).mean()))
            if len(stretch) >= 2 and stretch[-1] / stretch[-2] >= saturation:
                return d - 1
    return max_dim
