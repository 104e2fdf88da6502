"""The kind of a pair from its asymmetries: the edge rule's core (section 2.4, Eq. 10).

A difference ``C_diff`` or ``T_diff`` becomes ``"x->y"`` (``diff <= -mu``), ``"y->x"``
(``diff >= mu``) or ``"bidirectional"``; the two measures' kinds combine into the pair's kind
(``"conflict"`` for opposite directions). The direction convention and the table-level rule
(weights, edges, the pairs table) are those of :mod:`funcnet.network.rule`, which builds on
these functions; they live below the network so that the evidence layer reads kinds of its own
resampled or repeated networks with the same rule.
"""

from __future__ import annotations

import numpy as np

from funcnet.parameters import NetworkParameters

__all__ = ["edge_kind", "combine_kinds", "diff_kinds", "combined_kinds", "measure_kinds"]


def edge_kind(diff: float, mu: float) -> str:
    """Kind of one asymmetry measure under the threshold ``mu`` (section 2.4).

    Parameters
    ----------
    diff : float
        ``C_diff`` or ``T_diff`` of the pair (X, Y) (Eq. 10).
    mu : float
        Bidirectionality threshold, ``>= 0``.

    Returns
    -------
    str
        ``"x->y"`` if ``diff <= -mu``, ``"y->x"`` if ``diff >= mu``, else ``"bidirectional"``
        (which covers "no coupling" too); a difference of exactly 0 (or NaN) is bidirectional.

    References
    ----------
    Eq. 10 and section 2.4 of the paper; docs/guide/direction.md for the sign.

    Examples
    --------
    >>> edge_kind(-0.08, 0.05), edge_kind(0.05, 0.05), edge_kind(0.01, 0.05)
    ('x->y', 'y->x', 'bidirectional')
    """
    if diff < 0 and diff <= -mu:
        return "x->y"
    if diff > 0 and diff >= mu:
        return "y->x"
    return "bidirectional"


def combine_kinds(c_kind: str, t_kind: str) -> str:
    """Intersect the clustering and transitivity kinds of a pair (section 2.4).

    Parameters
    ----------
    c_kind, t_kind : {"x->y", "y->x", "bidirectional"}
        Kinds from ``C_diff`` and ``T_diff`` (:func:`edge_kind`).

    Returns
    -------
    str
        The common kind; a direction where the other measure is bidirectional; ``"conflict"``
        (no edge) for opposite directions.

    References
    ----------
    Section 2.4 of the paper (the intersection is what the code the paper ran does).

    Examples
    --------
    >>> combine_kinds("x->y", "bidirectional"), combine_kinds("x->y", "y->x")
    ('x->y', 'conflict')
    """
    if c_kind == t_kind:
        return c_kind
    if c_kind == "bidirectional":
        return t_kind
    if t_kind == "bidirectional":
        return c_kind
    return "conflict"


def diff_kinds(diffs: np.ndarray, mu: float) -> np.ndarray:
    """:func:`edge_kind` of every element (the same float64 comparisons), an object array."""
    return np.select(
        [(diffs < 0) & (diffs <= -mu), (diffs > 0) & (diffs >= mu)],
        ["x->y", "y->x"],
        "bidirectional",
    ).astype(object)


def combined_kinds(c_kinds: np.ndarray, t_kinds: np.ndarray) -> np.ndarray:
    """:func:`combine_kinds` of every element, an object array."""
    return np.where(
        c_kinds == t_kinds,
        c_kinds,
        np.where(
            c_kinds == "bidirectional",
            t_kinds,
            np.where(t_kinds == "bidirectional", c_kinds, "conflict"),
        ),
    ).astype(object)


def measure_kinds(c_diff: np.ndarray, t_diff: np.ndarray, parameters: NetworkParameters
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The per-measure kinds and the kind under ``parameters.measure`` of arrays of differences.

    Parameters
    ----------
    c_diff, t_diff : ndarray of float64
        ``C_diff`` and ``T_diff`` (Eq. 10), one per pair.
    parameters : NetworkParameters
        ``mu_clustering`` judges ``C_diff``, ``mu_transitivity`` ``T_diff``; ``measure``
        chooses the kind.

    Returns
    -------
    (ndarray, ndarray, ndarray)
        ``c_kind``, ``t_kind``, ``kind``, object arrays of str.

    Examples
    --------
    >>> p = NetworkParameters(mu=0.05)
    >>> [k.tolist() for k in measure_kinds(np.array([-0.08]), np.array([0.06]), p)]
    [['x->y'], ['y->x'], ['conflict']]
    """
    c_kinds = diff_kinds(c_diff, parameters.mu_clustering)
    t_kinds = diff_kinds(t_diff, parameters.mu_transitivity)
    if parameters.measure == "clustering":
        return c_kinds, t_kinds, c_kinds
    if parameters.measure == "transitivity":
        return c_kinds, t_kinds, t_kinds
    return c_kinds, t_kinds, combined_kinds(c_kinds, t_kinds)
