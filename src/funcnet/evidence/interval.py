"""How sure the asymmetry is: half-sampling intervals for ``C_diff`` and ``T_diff``.

A resample keeps half of the window's states, chosen as whole blocks of consecutive states
without replacement, and recomputes ``C^XY``, ``C^YX``, ``T^XY``, ``T^YX`` on the sub-ISRN of
the kept states (the same time indices in X and Y; the thresholds, hence the recurrence
matrices, of the whole window). Why this design:

* **no duplicates**: a bootstrap with replacement repeats states, and a repeated state is
  recurrent with its copy and cross-recurrent with the same states, which inflates the
  clustering of exactly the repeated nodes; subsampling without replacement has no copies;
* **blocks** keep the serial dependence inside each block (block length ``ceil(sqrt(M))`` by
  default);
* **half of the blocks**: for a smooth statistic, the spread of a half-sample's value around
  the full-sample value estimates the spread of the full-sample value around the truth without
  a rate factor (the finite-population factor ``(1 - f) / f`` is 1 at ``f = 1/2``: the
  delete-half jackknife).

The interval is ``[d - (q_hi - med), d + (med - q_lo)]`` for the observed difference ``d`` and
the quantiles ``q_lo``, ``q_hi`` (levels ``(1 - level) / 2``, ``(1 + level) / 2``) and median
``med`` of the resampled differences: their spread around their own median, placed at ``d``.
Centring on the resamples' median and not on ``d`` removes the shift a half-sized network has
(fewer neighbours per node change the clustering of every node alike), and it makes the interval
contain ``d`` always. The fraction of resamples with the sign of ``d`` is a stability figure,
not a probability.

References
----------
D. N. Politis, J. P. Romano, M. Wolf, *Subsampling*, Springer (1999), chapters 2-3.
J. Shao, C. F. J. Wu, "A general theory for jackknife variance estimation", Ann. Stat. 17,
1176-1197 (1989) (delete-d jackknife, d = n/2).
H. R. Kuensch, "The jackknife and the bootstrap for general stationary observations", Ann.
Stat. 17, 1217-1241 (1989) (blocks).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from funcnet.errors import ParameterError
from funcnet.evidence._kernels import _sub_measures

__all__ = ["AsymmetryInterval", "half_samples", "asymmetry_interval", "interval_kind"]


@dataclass(frozen=True)
class AsymmetryInterval:
    """Resampling intervals of ``C_diff`` and ``T_diff`` of one pair.

    Attributes
    ----------
    c_diff, t_diff : float
        The observed differences (Eq. 10).
    c_diff_low, c_diff_high, t_diff_low, t_diff_high : float
        The interval bounds; ``low <= diff <= high`` always.
    c_sign_fraction, t_sign_fraction : float
        Fraction of resamples whose difference has the observed sign (a stability figure).
    level : float
        Nominal coverage.
    resamples : int
    """

    c_diff: float
    t_diff: float
    c_diff_low: float
    c_diff_high: float
    t_diff_low: float
    t_diff_high: float
    c_sign_fraction: float
    t_sign_fraction: float
    level: float
    resamples: int


def half_samples(n_states: int, resamples: int, *, block: int | None = None,
                 seed: int = 0) -> np.ndarray:
    """States kept by each resample: half of the blocks, without replacement, sorted.

    Parameters
    ----------
    n_states : int
        ``M``.
    resamples : int
        Number of resamples ``R``.
    block : int, optional
        Block length (default ``ceil(sqrt(M))``); the last block takes the remainder.
    seed : int

    Returns
    -------
    ndarray of int64, shape (R, n_kept)
        Every row holds the same number of states (blocks of equal length are drawn; the
        remainder block is never drawn when it is shorter).

    Raises
    ------
    ParameterError
        ``resamples < 1`` or fewer than two blocks.

    Examples
    --------
    >>> half_samples(20, 2, block=5, seed=0).shape
    (2, 10)
    """
    if isinstance(resamples, bool) or not isinstance(resamples, (int, np.integer)) or \
            resamples < 1:
        raise ParameterError.of("resamples", f"must be an integer >= 1, got {resamples!r}")
    length = math.ceil(math.sqrt(n_states)) if block is None else int(block)
    n_blocks = n_states // max(1, length)
    if n_blocks < 2:
        raise ParameterError.of(
            "block", f"gives {n_blocks} block(s) of {length} states in {n_states}; need 2"
        )
    rng = np.random.default_rng(seed)
    keep = n_blocks // 2
    # Blocks start at a random phase, so the remainder is not always the same tail.
    phase = rng.integers(0, n_states - n_blocks * length + 1, size=resamples)
    blocks = np.sort(np.argsort(rng.random((resamples, n_blocks)), axis=1)[:, :keep], axis=1)
    starts = phase[:, None] + blocks * length
    chosen = (starts[:, :, None] + np.arange(length)).reshape(resamples, keep * length)
    return chosen


def _bounds(observed: float, values: np.ndarray, level: float) -> tuple[float, float, float]:
    lo, med, hi = np.quantile(values, [(1 - level) / 2, 0.5, (1 + level) / 2])
    sign = np.sign(observed)
    same = float(np.mean(np.sign(values) == sign)) if sign != 0 else float(np.mean(values == 0))
    return observed - (hi - med), observed + (med - lo), same


def asymmetry_interval(a_x: np.ndarray, a_y: np.ndarray, cr_xy: np.ndarray, *,
                       c_diff: float, t_diff: float, resamples: int = 200,
                       level: float = 0.95, block: int | None = None,
                       seed: int = 0) -> AsymmetryInterval:
    """Half-sampling intervals of ``C_diff`` and ``T_diff`` (module notes).

    Parameters
    ----------
    a_x, a_y, cr_xy : ndarray of uint8, shape (M, M)
        Dense ``A_X``, ``A_Y``, ``CR_XY`` of the pair (``PackedRecurrence.to_dense()``).
    c_diff, t_diff : float
        The observed differences (from :func:`funcnet.measures.isrn_measures` on the same
        blocks).
    resamples : int
    level : float in (0, 1)
    block : int, optional
        Block length, default ``ceil(sqrt(M))``.
    seed : int

    Returns
    -------
    AsymmetryInterval

    Raises
    ------
    ParameterError
        Bad ``level``, ``resamples``, ``block`` or shapes.

    References
    ----------
    Politis, Romano and Wolf (1999); Shao and Wu (1989); Kuensch (1989).

    Examples
    --------
    >>> from funcnet.embedding import embed
    >>> from funcnet.measures import isrn_measures
    >>> from funcnet.recurrence import auto_recurrence, cross_recurrence
    >>> from funcnet.systems import logistic_pair
    >>> data = logistic_pair(300, 3.7, 4.0, seed=0)
    >>> xs, ys = embed(data[:, 0], 3, 1), embed(data[:, 1], 3, 1)
    >>> blocks = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    >>> cr = cross_recurrence(xs, ys, cr=0.05)
    >>> m = isrn_measures(*blocks, cr)
    >>> dense = [b.to_dense().astype(np.uint8) for b in (*blocks, cr)]
    >>> iv = asymmetry_interval(*dense, c_diff=m.c_diff, t_diff=m.t_diff, seed=0)
    >>> bool(0 < iv.c_diff_low <= m.c_diff <= iv.c_diff_high), iv.c_sign_fraction
    (True, 1.0)
    """
    if not 0.0 < level < 1.0:
        raise ParameterError.of("level", f"must be in (0, 1), got {level}")
    m = np.shape(a_x)[0]
    for name, matrix in (("a_x", a_x), ("a_y", a_y), ("cr_xy", cr_xy)):
        if np.shape(matrix) != (m, m):
            raise ParameterError.of(name, f"must have shape ({m}, {m}), got {np.shape(matrix)}")
    chosen = half_samples(m, resamples, block=block, seed=seed)
    cr = np.ascontiguousarray(cr_xy, dtype=np.uint8)
    values = _sub_measures(
        np.ascontiguousarray(a_x, dtype=np.uint8), np.ascontiguousarray(a_y, dtype=np.uint8),
        cr, np.ascontiguousarray(cr.T), chosen,
    )
    c_low, c_high, c_same = _bounds(c_diff, values[:, 0] - values[:, 1], level)
    t_low, t_high, t_same = _bounds(t_diff, values[:, 2] - values[:, 3], level)
    return AsymmetryInterval(
        c_diff=float(c_diff), t_diff=float(t_diff),
        c_diff_low=float(c_low), c_diff_high=float(c_high),
        t_diff_low=float(t_low), t_diff_high=float(t_high),
        c_sign_fraction=c_same, t_sign_fraction=t_same,
        level=float(level), resamples=int(resamples),
    )


def interval_kind(diff: float, low: float, high: float, mu: float) -> str:
    """The interval edge rule for one measure: directed only if the interval excludes 0 and
    ``|diff| >= mu``.

    Negative reads X -> Y, as the paper's rule (:func:`funcnet.network.rule.edge_kind`).

    Parameters
    ----------
    diff, low, high : float
        Observed difference and its interval.
    mu : float

    Returns
    -------
    str
        ``"x->y"``, ``"y->x"`` or ``"bidirectional"``.

    Examples
    --------
    >>> interval_kind(-0.08, -0.12, -0.03, 0.05), interval_kind(-0.08, -0.15, 0.01, 0.05)
    ('x->y', 'bidirectional')
    """
    if high < 0 and diff <= -mu:
        return "x->y"
    if low > 0 and diff >= mu:
        return "y->x"
    return "bidirectional"
