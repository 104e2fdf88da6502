"""The edge rule: pure functions of a pairs table (section 2.4, Eq. 10 and 13).

Each asymmetry ``C_diff = C^XY - C^YX``, ``T_diff = T^XY - T^YX`` (Eq. 10) becomes a kind under
its threshold (``mu_c`` for ``C_diff``, ``mu_t`` for ``T_diff``; ``mu`` sets both):

======================  =================  ===================================================
difference              kind               meaning
======================  =================  ===================================================
``diff <= -mu``         ``x->y``           X -> Y (the convention of the code the paper used)
``diff >= mu``          ``y->x``           Y -> X
``|diff| < mu``         ``bidirectional``  symmetric coupling **or no coupling at all**
======================  =================  ===================================================

A difference of exactly 0 is bidirectional, even with ``mu = 0``. ``measure="both"`` (the
default, as in the code the paper used) intersects the two per-measure graphs
(:func:`combine_kinds`): the same direction twice, or a direction and a bidirectional relation,
give that direction; two bidirectional relations a bidirectional edge; opposite directions no
edge, recorded as ``conflict``. The weight is ``(|C_diff| + |T_diff|) / 2`` (Eq. 13), whatever
the measure.

**Direction convention.** A *negative* difference reads as X -> Y. Section 2.4 of the paper
states both signs; the convention here is that of the code the paper ran, checked by
``tests/test_direction.py`` on systems whose coupling direction is known. The asymmetry follows
the relative roughness of the two signals as much as the coupling (docs/guide/direction.md).

**Degenerate pairs** (too few distinct states; ``degenerate`` in the pairs table) get a kind like
any pair, but :func:`edges_from_pairs` leaves them out unless asked to keep them, flagged.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable
from typing import Any, Unpack

import numpy as np
import pandas as pd

from funcnet.core.kinds import combine_kinds, combined_kinds, edge_kind, measure_kinds
from funcnet.errors import ParameterError
from funcnet.network.schema import PAIR_COLUMNS, PAIR_DTYPES, edges_frame, typed_frame
from funcnet.parameters import NetworkParameters, ParameterOverrides, resolve

__all__ = ["edge_kind", "combine_kinds", "pair_kinds", "rule_columns", "kinds_for",
           "edges_from_pairs"]

#: The parameters the rule depends on (what :func:`pair_kinds` accepts as overrides).
RULE_FIELDS = ("mu", "mu_c", "mu_t", "measure")


def _require(pairs: Any, columns: Iterable[str], what: str) -> None:
    if not isinstance(pairs, pd.DataFrame):
        raise ParameterError.of("pairs", f"must be a pandas.DataFrame, got {type(pairs).__name__}")
    missing = [name for name in columns if name not in pairs.columns]
    if missing:
        raise ParameterError.of(
            "pairs", f"needs the column(s) {', '.join(missing)} for {what}"
        )


def _measure(measure: Any) -> str:
    # The one check of the measure's name is NetworkParameters'.
    return NetworkParameters(measure=measure).measure


def kinds_for(pairs: pd.DataFrame, measure: str) -> pd.Series:
    """The kind of every pair under ``measure``, from its per-measure kinds.

    Parameters
    ----------
    pairs : pandas.DataFrame
        At least the columns ``c_kind`` and ``t_kind``.
    measure : {"both", "clustering", "transitivity"}
        ``"clustering"``: ``c_kind``; ``"transitivity"``: ``t_kind``; ``"both"``: their
        intersection (:func:`combine_kinds`).

    Returns
    -------
    pandas.Series
        Of dtype str, indexed as ``pairs``.

    Raises
    ------
    ParameterError
        Unknown ``measure``, or a column missing.

    References
    ----------
    Section 2.4 of the paper.

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"c_kind": ["x->y", "x->y"], "t_kind": ["y->x", "bidirectional"]})
    >>> kinds_for(pairs, "both").tolist()
    ['conflict', 'x->y']
    """
    measure = _measure(measure)
    _require(pairs, ("c_kind", "t_kind"), f"measure={measure!r}")
    if measure == "clustering":
        values = pairs["c_kind"].to_numpy(dtype=object)
    elif measure == "transitivity":
        values = pairs["t_kind"].to_numpy(dtype=object)
    else:
        values = combined_kinds(
            pairs["c_kind"].to_numpy(dtype=object), pairs["t_kind"].to_numpy(dtype=object)
        )
    return pd.Series(values, index=pairs.index, dtype="str", name="kind")


def pair_kinds(pairs: pd.DataFrame, parameters: NetworkParameters | None = None,
               **overrides: Unpack[ParameterOverrides]) -> pd.DataFrame:
    """The pairs table with the rule's columns ``c_kind``, ``t_kind``, ``kind``, ``weight``.

    Parameters
    ----------
    pairs : pandas.DataFrame
        At least ``c_diff`` and ``t_diff``; the rule's columns are (re)computed.
    parameters : NetworkParameters, optional
        Its ``mu_clustering`` (``mu_c``, else ``mu``) judges ``C_diff``, ``mu_transitivity``
        (``mu_t``, else ``mu``) ``T_diff``, and ``measure`` sets ``kind``.
    **overrides
        ``mu``, ``mu_c``, ``mu_t`` or ``measure``, applied to ``parameters``.

    Returns
    -------
    pandas.DataFrame
        A new table: ``pairs`` with the four columns set; in the schema's order and dtypes
        (:data:`funcnet.network.schema.PAIR_COLUMNS`) when it has every column of it,
        otherwise with the four columns at its end.

    Raises
    ------
    ParameterError
        A bad override (named), or ``c_diff``/``t_diff`` missing.

    References
    ----------
    Eq. 10 (differences), section 2.4 (``mu``, direction, intersection), Eq. 13 (weight).

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["A"], "y": ["B"], "c_diff": [-0.08], "t_diff": [0.02]})
    >>> pair_kinds(pairs, mu_c=0.05, mu_t=0.01)
       x  y  c_diff  t_diff c_kind t_kind      kind  weight
    0  A  B   -0.08    0.02   x->y   y->x  conflict    0.05
    """
    p = resolve(parameters, overrides, allowed=RULE_FIELDS)
    _require(pairs, ("c_diff", "t_diff"), "the edge rule")
    rule = rule_columns(pairs["c_diff"].to_numpy(dtype=np.float64),
                        pairs["t_diff"].to_numpy(dtype=np.float64), p)
    if set(PAIR_COLUMNS) <= set(pairs.columns):
        return _in_schema(pairs, rule)
    out = pairs.copy()
    for name in ("c_kind", "t_kind", "kind"):
        out[name] = pd.Series(rule[name], index=pairs.index, dtype="str")
    out["weight"] = pd.Series(rule["weight"], index=pairs.index)
    return out


def rule_columns(c_diff: np.ndarray, t_diff: np.ndarray,
                 parameters: NetworkParameters) -> dict[str, np.ndarray]:
    """The rule's columns of :func:`pair_kinds` from the differences alone, as arrays.

    Parameters
    ----------
    c_diff, t_diff : ndarray of float64
        ``C_diff`` and ``T_diff`` of each pair (Eq. 10).
    parameters : NetworkParameters
        Its thresholds and ``measure``, as :func:`pair_kinds` reads them.

    Returns
    -------
    dict
        ``c_kind``, ``t_kind``, ``kind`` (object arrays of str) and ``weight`` (float64).

    Examples
    --------
    >>> found = rule_columns(np.array([-0.08]), np.array([0.02]), NetworkParameters(mu=0.01))
    >>> [found[name].tolist() for name in ("c_kind", "t_kind", "kind", "weight")]
    [['x->y'], ['y->x'], ['conflict'], [0.05]]
    """
    c_kinds, t_kinds, kinds = measure_kinds(c_diff, t_diff, parameters)
    # abs is exact and /2 too: the same bits as (|c| + |t|) / 2 in Python floats.
    weight = (np.abs(c_diff) + np.abs(t_diff)) / 2
    return {"c_kind": c_kinds, "t_kind": t_kinds, "kind": kinds, "weight": weight}


def _in_schema(pairs: pd.DataFrame, rule: dict[str, np.ndarray]) -> pd.DataFrame:
    """``pairs`` with the ``rule`` columns, its schema's columns in order and dtypes, built
    once: a column already of its dtype is taken as it is, another converted alone."""
    arrays: dict[str, Any] = {}
    for name, dtype in PAIR_DTYPES.items():
        column = rule[name] if name in rule else pairs[name]
        if isinstance(column, pd.Series) and column.dtype != pd.api.types.pandas_dtype(dtype):
            column = column.astype(dtype)
        arrays[name] = column
    out = typed_frame(arrays, PAIR_DTYPES, index=pairs.index)
    out.attrs = copy.deepcopy(pairs.attrs)
    return out


def edges_from_pairs(pairs: pd.DataFrame, *, measure: str | None = None,
                     degenerate: str = "drop") -> pd.DataFrame:
    """The edges of a pairs table: directed edges point source -> target; no conflicts.

    Parameters
    ----------
    pairs : pandas.DataFrame
        At least ``x``, ``y``, ``weight``, ``degenerate`` and ``kind`` (or, with ``measure``,
        ``c_kind`` and ``t_kind``): a :attr:`FunctionalNetwork.pairs
        <funcnet.network.FunctionalNetwork.pairs>` table, or one window's rows of a study.
    measure : {"both", "clustering", "transitivity"}, optional
        Recompute each pair's kind under this measure (:func:`kinds_for`); by default the
        table's ``kind`` column, i.e. the measure the network was built with.
    degenerate : {"drop", "keep"}
        ``"drop"`` (default): a pair flagged ``degenerate`` is not an edge; ``"keep"``: it is,
        with ``degenerate=True`` on the edge.

    Returns
    -------
    pandas.DataFrame
        Columns ``source, target, weight, kind, degenerate``
        (:data:`funcnet.network.schema.EDGE_COLUMNS`): one row per directed edge (``kind``
        ``"directed"``, from driver to driven) or bidirectional pair (``"bidirectional"``, from
        ``x`` to ``y``), in the order of the pairs; a conflict is no edge.

    Raises
    ------
    ParameterError
        Unknown ``measure`` or ``degenerate``, or a column missing.

    References
    ----------
    Section 2.4 (edges) and Eq. 13 (weights) of the paper.

    Examples
    --------
    >>> import pandas as pd
    >>> pairs = pd.DataFrame({"x": ["A", "A", "B", "B"], "y": ["B", "C", "C", "D"],
    ...                       "kind": ["y->x", "bidirectional", "conflict", "x->y"],
    ...                       "weight": [0.2, 0.01, 0.3, 0.4],
    ...                       "degenerate": [False, False, False, True]})
    >>> edges_from_pairs(pairs)
      source target  weight           kind  degenerate
    0      B      A    0.20       directed       False
    1      A      C    0.01  bidirectional       False
    >>> edges_from_pairs(pairs, degenerate="keep")["degenerate"].tolist()
    [False, False, True]
    """
    policy = NetworkParameters(degenerate=degenerate).degenerate
    if measure is None:
        _require(pairs, ("x", "y", "weight", "degenerate", "kind"), "the edges")
        kinds = pairs["kind"].to_numpy(dtype=object)
    else:
        _require(pairs, ("x", "y", "weight", "degenerate"), "the edges")
        kinds = kinds_for(pairs, measure).to_numpy(dtype=object)
    flagged = pairs["degenerate"].to_numpy(dtype=bool)
    keep = kinds != "conflict"
    if policy == "drop":
        keep &= ~flagged
    x = pairs["x"].to_numpy(dtype=object)[keep]
    y = pairs["y"].to_numpy(dtype=object)[keep]
    kinds = kinds[keep]
    backward = kinds == "y->x"
    columns = {
        "source": np.where(backward, y, x),
        "target": np.where(backward, x, y),
        "weight": pairs["weight"].to_numpy(dtype=np.float64)[keep],
        "kind": np.where(kinds == "bidirectional", "bidirectional", "directed"),
        "degenerate": flagged[keep],
    }
    return edges_frame(columns)
