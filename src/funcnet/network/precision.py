"""The precision a signal is logged with: the step of its grid, or single precision's spacing.

A log writes a fixed number of decimals, an encoder counts, a file stores single-precision
floats: every sample then lies on a grid, and whatever the prediction of a signal gains below
one step of it the log cannot show (:mod:`funcnet.network.direction` reads no improvement of a
signal its own past predicts to within its step). The step is read from the values themselves
(any unit conversion or normalization is affine and keeps the grid), on a whole channel where
one is at hand (:func:`funcnet.pipeline.channel_steps`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from funcnet.errors import ParameterError

__all__ = ["logged_step", "single_spacing", "checked_steps", "normalized_steps"]

_EPS = float(np.finfo(np.float64).eps)


def logged_step(values: Any) -> float:
    """The precision a signal is logged with: the step of its grid (0 when it has none).

    A log that writes a fixed number of decimals, or an encoder's counts, puts every sample on
    a grid ``offset + k q``, and any affine scaling (a unit conversion, a normalization) keeps
    it: ``q`` is the greatest common step of the differences between the distinct values
    (Euclid's algorithm, each difference within 1 % of a step of a multiple, the step
    sharpened on the small multiples first so that a large multiple does not magnify the
    rounding a remainder carries). Values stored in single precision have its spacing, root
    mean square over the values, where that is coarser. Read it on a whole channel: a window
    that moves thousands of steps per sample may hide the grid (then 0).

    Parameters
    ----------
    values : array_like
        The samples as recorded (NaN ignored).

    Returns
    -------
    float
        ``q`` in the values' unit; 0 for fewer than two distinct values or no grid (values
        computed in floating point).

    Examples
    --------
    >>> logged_step(np.round(np.linspace(0.0, 1.0, 50) ** 2, 3))
    0.001
    >>> radians = np.round(np.sin(np.arange(40.0)), 6)  # six decimals, then in degrees
    >>> float(logged_step(np.degrees(radians)) / np.degrees(1e-6))
    1.0
    >>> single = np.float32(np.random.default_rng(1).uniform(0.1, 1.9, 100)).astype(float)
    >>> bool(2.0**-27 < logged_step(single) < 2.0**-23)  # float32's spacing there
    True
    >>> logged_step(np.random.default_rng(0).standard_normal(50))
    0.0
    """
    finite = np.asarray(values, dtype=np.float64).ravel()
    finite = finite[np.isfinite(finite)]
    distinct = np.unique(finite)
    if distinct.size < 2:
        return 0.0
    single = single_spacing(finite)
    tolerance = 64 * _EPS * float(np.abs(distinct).max())  # the representation, not the log
    with np.errstate(over="ignore"):
        steps = np.diff(distinct)
    if not np.isfinite(steps).all():  # values spanning beyond float64's range: no grid read
        return single
    steps = steps[steps > tolerance]
    q = float(steps.min()) if steps.size else 0.0
    while q >= 1e3 * tolerance:  # a step within a thousand roundings of the values: none
        q, remainder = _grid(steps, q, tolerance)
        if remainder == 0.0:
            return max(q, single)
        q = remainder
    return single


def single_spacing(values: Any) -> float:
    """Single precision's spacing at the values, root mean square, when every value is one a
    float32 holds (a file that stores floats); else 0.

    Examples
    --------
    >>> single_spacing(np.float32([1.0, 1.5, 1.75]).astype(float)) == 2.0**-23
    True
    >>> single_spacing([0.1, 0.2])
    0.0
    """
    finite = np.asarray(values, dtype=np.float64).ravel()
    finite = finite[np.isfinite(finite)]
    if finite.size == 0 or not np.array_equal(finite.astype(np.float32).astype(np.float64),
                                               finite):
        return 0.0
    spacing = np.spacing(np.abs(finite).astype(np.float32)).astype(np.float64)
    return float(np.sqrt(np.mean(spacing**2)))


def _grid(steps: np.ndarray, q: float, tolerance: float) -> tuple[float, float]:
    """``(q, 0)`` sharpened on the differences when every one is a multiple of ``q`` (within
    1 % of a step), else ``(q, r)`` with Euclid's next remainder ``r``. The small multiples
    come first: each pass reads the multiples with the step as it stands and sharpens the step
    on them before checking (a step found as a remainder carries the values' rounding, which
    the larger multiples would magnify past the 1 %)."""
    limit = 8.0 * float(steps.min())
    while True:
        use = steps <= limit
        multiple = np.rint(steps[use] / q)
        sharp = float(steps[use].sum() / multiple.sum())
        off = np.abs(steps[use] - multiple * sharp)
        wrong = off > 0.01 * sharp + 16 * tolerance
        if wrong.any():
            rest = np.abs(steps[use] - multiple * q)  # Euclid's remainders of the candidate
            rest = rest[rest > 0.01 * q + 16 * tolerance]
            return q, float(rest.min() if rest.size else off[wrong].min())
        q = sharp
        if use.all():
            return q, 0.0
        limit *= 8.0


def checked_steps(steps: Mapping[str, float] | None, names: Sequence[str]) -> dict[str, float]:
    """``steps`` as a dict, each a finite step >= 0 of one of ``names``.

    Raises
    ------
    ParameterError
        A step of a name not among ``names``, negative, NaN or infinite.

    Examples
    --------
    >>> checked_steps({"RP": 1e-6}, ["RP", "AC"])
    {'RP': 1e-06}
    """
    found = {str(name): float(step) for name, step in (steps or {}).items()}
    unknown = sorted(set(found) - {str(name) for name in names})
    if unknown:
        raise ParameterError.of("steps", f"names {unknown}, not among the signals "
                                         f"{[str(name) for name in names]}")
    bad = {name: step for name, step in found.items() if not (np.isfinite(step) and step >= 0)}
    if bad:
        raise ParameterError.of("steps", f"must be finite and >= 0, got {bad}")
    return found


def normalized_steps(steps: Sequence[float], raw: np.ndarray,
                     normalized: np.ndarray) -> np.ndarray:
    """Logged steps (:func:`logged_step`) of the columns of ``raw``, in the unit of their
    affine normalization ``normalized`` (min-max, z-score or none): each scaled as its column's
    range is.

    Parameters
    ----------
    steps : sequence of float
        One step per column of ``raw``, in its unit.
    raw, normalized : ndarray, shape (N, k)
        The columns before and after the normalization.

    Returns
    -------
    ndarray, shape (k,)
        The steps in the normalized unit (0 for a constant column).

    Examples
    --------
    >>> raw = np.array([[0.0, 5.0], [2.0, 5.5], [4.0, 6.0]])
    >>> normalized_steps([1.0, 0.5], raw, raw / np.ptp(raw, axis=0)).tolist()
    [0.25, 0.5]
    """
    spread = np.ptp(raw, axis=0)
    scale = np.divide(np.ptp(normalized, axis=0), spread, out=np.zeros(spread.shape),
                      where=spread > 0)
    return np.asarray(steps, dtype=np.float64) * scale
