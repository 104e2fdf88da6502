"""The reading of a network's pairs: whether each test could have rejected, its label, and why.

A pair's coupling test has ``K`` surrogates, and no p-value is below ``1 / (K + 1)``
(:mod:`funcnet.evidence.dependence`). Its ``coupling_p`` is that p-value adjusted by
Benjamini-Hochberg across the network's tested pairs, and the adjustment never lowers a p-value.
The smallest ``coupling_p`` a pair could reach whatever the data is therefore the adjustment of
every tested pair's smallest p-value, ``1 / (K_j + 1)``, read at the pair
(:func:`smallest_p_values`; BH's adjusted p-values only grow when any p-value grows, so this is
the least each can get, and it is reached when every pair's observed statistic exceeds all its
surrogates). When that exceeds ``alpha``, or the pair has no surrogate at all (``K = 0``: too
few states to test), the test could not have rejected: the pair is *untestable*
(:func:`untestable`). With equal ``K`` everywhere this is ``1 / (K + 1) > alpha``; with mixed
``K`` a pair with many surrogates among pairs with few is untestable too (one pair of ``K =
28`` among nine of ``K = 4``: ``1/29 = 0.034``, but 0.2 after the adjustment over ten pairs).

The labels (the ``evidence`` column, :data:`funcnet.evidence.EVIDENCE_LABELS`), and the
``evidence_reason`` column that says why (:func:`evidence_readings`):

=====================  ===================================================================
``coupled-directed``   ``coupling_p <= alpha``, the direction index is significant and
                       agrees with the network's ``kind``
``coupled``            ``coupling_p <= alpha``, no direction supported
``untestable``         the test could not have rejected at ``alpha`` (above); it takes
                       precedence over the two labels below, whatever the ``kind``
``asymmetry-only``     tested, not rejected, yet the network's rule draws an arrow: the
                       arrow rests on a difference of character only
``not-coupled``        tested, not rejected, no arrow
=====================  ===================================================================

Only the labels read these rules; every number of the test (``coupling_p``, ``surrogates``)
stays what the test gave.

References
----------
Y. Benjamini, Y. Hochberg, "Controlling the false discovery rate", J. R. Stat. Soc. B 57,
289-300 (1995). docs/validation/evidence.md (why short robot windows hold few surrogates).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from funcnet.evidence.dependence import benjamini_hochberg
from funcnet.evidence.pairs import evidence_label

__all__ = ["smallest_p_values", "untestable", "evidence_readings"]


def _surrogate_counts(surrogates: Any) -> np.ndarray:
    """``K`` per pair as floats, 0 where missing (NaN or None: not tested)."""
    k = np.array([np.nan if s is None else s for s in np.ravel(surrogates)], dtype=np.float64)
    return np.where(np.isnan(k), 0.0, k)


def smallest_p_values(surrogates: Any) -> np.ndarray:
    """The smallest ``coupling_p`` each pair of one network could reach, whatever the data.

    Benjamini-Hochberg applied to ``1 / (K + 1)`` of every tested pair (module notes).

    Parameters
    ----------
    surrogates : array_like of int
        ``K`` of every pair of one network (its ``surrogates`` column); 0 (or NaN): not tested.

    Returns
    -------
    ndarray of float
        Per pair, in the input order; NaN where ``K = 0``.

    References
    ----------
    Benjamini and Hochberg (1995).

    Examples
    --------
    >>> smallest_p_values([99, 99, 0]).tolist()
    [0.01, 0.01, nan]
    >>> smallest_p_values([28, 4, 4]).round(3).tolist()  # 1/29 = 0.034 alone, 0.103 adjusted
    [0.103, 0.2, 0.2]
    """
    k = _surrogate_counts(surrogates)
    with np.errstate(divide="ignore"):
        least = np.where(k > 0, 1.0 / (k + 1.0), np.nan)
    return benjamini_hochberg(least)


def untestable(surrogates: Any, alpha: float) -> np.ndarray:
    """Whether each pair's coupling test could not have rejected at ``alpha``, whatever the data.

    Parameters
    ----------
    surrogates : array_like of int
        ``K`` of every pair of one network (its ``surrogates`` column; 0: not tested).
    alpha : float
        The level of the coupling decision.

    Returns
    -------
    ndarray of bool
        True where the pair has no surrogate or its smallest reachable ``coupling_p``
        (:func:`smallest_p_values`) exceeds ``alpha``.

    Examples
    --------
    >>> untestable([12], 0.05).tolist(), untestable([19, 0], 0.05).tolist()  # 1/13, 1/20
    ([True], [False, True])
    >>> untestable([19, 19], 0.05).tolist()  # 1/20 stays 0.05 when both can reach it ...
    [False, False]
    >>> untestable([19, 12], 0.05).tolist()  # ... not beside a pair that cannot
    [True, True]
    >>> untestable([28, 4, 4], 0.05).tolist()  # 1/29 alone, 0.103 after the adjustment
    [True, True, True]
    """
    least = smallest_p_values(surrogates)
    return ~(least <= float(alpha))  # NaN (no surrogate) compares False


def _g(value: float) -> str:
    return f"{value:.3g}"


def evidence_readings(coupled: Sequence[bool], coupling_p: Sequence[float],
                      surrogates: Sequence[int], direction: Sequence[str],
                      kind: Sequence[str], alpha: float) -> tuple[list[str], list[str]]:
    """The ``evidence`` label and its ``evidence_reason`` of every pair of one network.

    Parameters
    ----------
    coupled : sequence of bool
        ``coupling_p <= alpha`` per pair.
    coupling_p : sequence of float
        The BH-adjusted p-values (NaN: not tested).
    surrogates : sequence of int
        ``K`` per pair (0: not tested).
    direction : sequence of str
        The conditional-recurrence direction, ``"x->y"``, ``"y->x"`` or ``""``.
    kind : sequence of str
        The network's pair kinds.
    alpha : float
        The level the test was decided at.

    Returns
    -------
    (list of str, list of str)
        The labels (:data:`~funcnet.evidence.EVIDENCE_LABELS`, module notes) and one sentence
        per pair saying why.

    Examples
    --------
    >>> labels, reasons = evidence_readings(
    ...     [False, False, True], [0.48, 0.5, 0.01], [4, 99, 99], ["", "", "x->y"],
    ...     ["x->y", "x->y", "x->y"], 0.05)
    >>> labels
    ['untestable', 'asymmetry-only', 'coupled-directed']
    >>> reasons[0]
    'K=4 surrogates: smallest p 0.2 > alpha 0.05'
    >>> reasons[1].split("; ")  # 0.015: 1/100 after the adjustment over three pairs
    ['coupling_p 0.5 > alpha 0.05 (tested: smallest reachable p 0.015)', \
'the arrow rests on the asymmetry alone']
    """
    alpha = float(alpha)
    k = _surrogate_counts(surrogates)
    least = smallest_p_values(k)
    m = int(np.count_nonzero(k > 0))
    labels: list[str] = []
    reasons: list[str] = []
    for is_coupled, p, k_i, least_i, arrow, kind_i in zip(
            coupled, coupling_p, k, least, direction, kind, strict=True):
        blind = not least_i <= alpha
        # A coupled pair was testable (BH never lowers a p-value); the guard keeps the label
        # honest even if a table said otherwise.
        label = evidence_label(bool(is_coupled), str(arrow), str(kind_i),
                               untestable=blind and not bool(is_coupled))
        labels.append(label)
        if label == "untestable":
            if k_i == 0:
                reason = "no surrogate: too few states to test"
            elif 1.0 / (k_i + 1.0) > alpha:
                reason = (f"K={int(k_i)} surrogates: smallest p {_g(1.0 / (k_i + 1.0))} > "
                          f"alpha {_g(alpha)}")
            else:
                reason = (f"K={int(k_i)} surrogates: smallest p {_g(1.0 / (k_i + 1.0))}, "
                          f"{_g(least_i)} after Benjamini-Hochberg over {m} tested pairs > "
                          f"alpha {_g(alpha)}")
        elif label.startswith("coupled"):
            reason = f"coupling_p {_g(p)} <= alpha {_g(alpha)}"
            if label == "coupled-directed":
                reason += f"; the direction index agrees with the kind {kind_i}"
            elif arrow:
                reason += f"; the direction index ({arrow}) disagrees with the kind {kind_i}"
            else:
                reason += "; no direction supported"
        else:
            reason = (f"coupling_p {_g(p)} > alpha {_g(alpha)} (tested: smallest reachable p "
                      f"{_g(least_i)})")
            if label == "asymmetry-only":
                reason += "; the arrow rests on the asymmetry alone"
        reasons.append(reason)
    return labels, reasons
