"""The one schema of a functional network's tables, and the one vocabulary of its kinds.

Every table of pairs or edges that funcnet writes or reads -- :attr:`FunctionalNetwork.pairs
<funcnet.network.FunctionalNetwork.pairs>`, its JSON and GraphML files, a study's Parquet rows,
the report and the command line's table -- has the columns named here, in this order, with these
dtypes. Code elsewhere imports the names from this module instead of listing columns by hand.

**Pairs** (one row per unordered pair (X, Y), X before Y in node order):

======================================  =======  ==============================================
columns                                 dtype    meaning
======================================  =======  ==============================================
``x``, ``y``                            str      the two nodes
``c_xy``, ``c_yx``, ``t_xy``, ``t_yx``  float64  cross-clustering, cross-transitivity (Eq. 6-9)
``c_diff``, ``t_diff``                  float64  ``C^XY - C^YX``, ``T^XY - T^YX`` (Eq. 10)
``eps_x``, ``eps_y``, ``eps_xy``        float64  thresholds of ``A_X``, ``A_Y``, ``CR_XY``
``achieved_rr_x``, ``achieved_rr_y``    float64  achieved rates (the targets are the
``achieved_cr``                         float64  parameters ``rr``, ``cr``)
``eps_ordered``                         bool     ``eps_xy < min(eps_x, eps_y)`` (section 2.2)
``rate_exceeded``                       bool     ties pushed an achieved rate above its target
``degenerate``                          bool     too few distinct states: no arrow to read
``degenerate_reason``                   str      why (``""`` if not degenerate)
``c_kind``, ``t_kind``                  str      kind from ``C_diff``, ``T_diff`` alone
``kind``                                str      kind under the network's measure
``weight``                              float64  ``(|C_diff| + |T_diff|) / 2`` (Eq. 13)
``direction``                           str      ``"x->y"``, ``"y->x"`` or ``"none"``: whether
                                                 one past improves the other's prediction
                                                 (:mod:`funcnet.network.direction`)
``direction_reason``                    str      why, in one sentence
======================================  =======  ==============================================

**Evidence** (only in networks built with ``evidence=True``; :data:`EVIDENCE_COLUMNS`, after the
pairs columns, in this order; :mod:`funcnet.evidence`):

======================================  =======  ==============================================
columns                                 dtype    meaning
======================================  =======  ==============================================
``coupling_statistic``                  float64  joint-recurrence correlation ``phi``
``coupling_p``                          float64  its surrogate p-value, BH-adjusted (NaN: the
                                                 window is too short to test)
``coupled``                             bool     ``coupling_p <= alpha``
``surrogates``                          int64    surrogates used (0: not tested)
``c_diff_low``, ``c_diff_high``         float64  half-sampling interval of ``C_diff``
``t_diff_low``, ``t_diff_high``         float64  half-sampling interval of ``T_diff``
``c_sign_fraction``, ``t_sign_fraction``  float64  resamples with the observed sign
``evidence``                            str      one of :data:`EVIDENCE_LABELS`
                                                 (``untestable``: the test could not have
                                                 rejected at ``alpha``)
``evidence_reason``                     str      why, in one sentence (``K=4 surrogates:
                                                 smallest p 0.2 > alpha 0.05``)
======================================  =======  ==============================================

**Edges** (one row per directed edge or bidirectional pair): ``source``, ``target`` (str),
``weight`` (float64), ``kind`` (str), ``degenerate`` (bool).

**Kinds.** A pair's kind is one of :data:`PAIR_KINDS`: ``"x->y"`` (X drives Y), ``"y->x"``,
``"bidirectional"`` (symmetric coupling *or none*) or ``"conflict"`` (the two measures point in
opposite directions: no edge). An edge's kind is one of :data:`EDGE_KINDS`: ``"directed"`` (from
``source`` to ``target``) or ``"bidirectional"``.

References
----------
Eq. 6-10 and 13, sections 2.2 and 2.4 of the paper.

Examples
--------
>>> PAIR_COLUMNS[:8]
('x', 'y', 'c_xy', 'c_yx', 't_xy', 't_yx', 'c_diff', 't_diff')
>>> empty_edges().dtypes.astype(str).tolist()
['str', 'str', 'float64', 'str', 'bool']
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError
from funcnet.evidence.pairs import EVIDENCE_LABELS
from funcnet.network.direction import DIRECTIONS

__all__ = [
    "PAIR_KINDS",
    "MEASURE_KINDS",
    "EDGE_KINDS",
    "MEASURE_COLUMNS",
    "RESULT_COLUMNS",
    "RULE_COLUMNS",
    "DIRECTION_COLUMNS",
    "PAIR_COLUMNS",
    "PAIR_DTYPES",
    "EVIDENCE_LABELS",
    "EVIDENCE_COLUMNS",
    "EVIDENCE_DTYPES",
    "EDGE_COLUMNS",
    "EDGE_DTYPES",
    "empty_pairs",
    "empty_edges",
    "pairs_frame",
    "edges_frame",
    "check_pairs",
    "check_edges",
    "typed_frame",
]

#: Kinds of a pair (the ``kind`` column of the pairs table).
PAIR_KINDS: tuple[str, ...] = ("x->y", "y->x", "bidirectional", "conflict")
#: Kinds of one measure alone (the ``c_kind`` and ``t_kind`` columns): no conflict there.
MEASURE_KINDS: tuple[str, ...] = PAIR_KINDS[:3]
#: Kinds of an edge (the ``kind`` column of the edges table).
EDGE_KINDS: tuple[str, ...] = ("directed", "bidirectional")

#: The float columns a pair's cross measures give (Eq. 6-10, thresholds, achieved rates).
MEASURE_COLUMNS: tuple[str, ...] = (
    "c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff", "eps_x", "eps_y", "eps_xy",
    "achieved_rr_x", "achieved_rr_y", "achieved_cr",
)  # fmt: skip
#: Every column taken from a pair's :class:`funcnet.core.measures.CrossMeasures`, by field name.
RESULT_COLUMNS: tuple[str, ...] = (
    *MEASURE_COLUMNS, "eps_ordered", "rate_exceeded", "degenerate", "degenerate_reason",
)  # fmt: skip
#: The columns the edge rule computes (:func:`funcnet.network.rule.pair_kinds`).
RULE_COLUMNS: tuple[str, ...] = ("c_kind", "t_kind", "kind", "weight")
#: The direction reading's columns (:func:`funcnet.network.direction.direction_columns`).
DIRECTION_COLUMNS: tuple[str, ...] = ("direction", "direction_reason")

_PAIR_DTYPES: dict[str, str] = {
    "x": "str",
    "y": "str",
    **dict.fromkeys(MEASURE_COLUMNS, "float64"),
    "eps_ordered": "bool",
    "rate_exceeded": "bool",
    "degenerate": "bool",
    "degenerate_reason": "str",
    "c_kind": "str",
    "t_kind": "str",
    "kind": "str",
    "weight": "float64",
    "direction": "str",
    "direction_reason": "str",
}
#: Column name -> pandas dtype of the pairs table, in column order.
PAIR_DTYPES: Mapping[str, str] = MappingProxyType(_PAIR_DTYPES)
#: The columns of the pairs table, in order.
PAIR_COLUMNS: tuple[str, ...] = tuple(_PAIR_DTYPES)

_EVIDENCE_DTYPES: dict[str, str] = {
    "coupling_statistic": "float64",
    "coupling_p": "float64",
    "coupled": "bool",
    "surrogates": "int64",
    "c_diff_low": "float64",
    "c_diff_high": "float64",
    "t_diff_low": "float64",
    "t_diff_high": "float64",
    "c_sign_fraction": "float64",
    "t_sign_fraction": "float64",
    "evidence": "str",
    "evidence_reason": "str",
}
#: Column name -> dtype of the evidence group, in column order (after :data:`PAIR_COLUMNS`).
EVIDENCE_DTYPES: Mapping[str, str] = MappingProxyType(_EVIDENCE_DTYPES)
#: The evidence columns of the pairs table, present only with ``evidence=True``.
EVIDENCE_COLUMNS: tuple[str, ...] = tuple(_EVIDENCE_DTYPES)
_FULL_DTYPES: dict[str, str] = {**_PAIR_DTYPES, **_EVIDENCE_DTYPES}

_EDGE_DTYPES: dict[str, str] = {
    "source": "str",
    "target": "str",
    "weight": "float64",
    "kind": "str",
    "degenerate": "bool",
}
#: Column name -> pandas dtype of the edges table, in column order.
EDGE_DTYPES: Mapping[str, str] = MappingProxyType(_EDGE_DTYPES)
#: The columns of the edges table, in order.
EDGE_COLUMNS: tuple[str, ...] = tuple(_EDGE_DTYPES)

# Which columns may hold which kinds.
_VOCABULARY: dict[str, tuple[str, ...]] = {
    "kind": PAIR_KINDS,
    "c_kind": MEASURE_KINDS,
    "t_kind": MEASURE_KINDS,
    "direction": DIRECTIONS,
}
_EVIDENCE_VOCABULARY: dict[str, tuple[str, ...]] = {
    **_VOCABULARY,
    "evidence": EVIDENCE_LABELS,
}


def _frame(columns: Mapping[str, Sequence[Any]], dtypes: Mapping[str, str],
           table: str) -> pd.DataFrame:
    missing = [name for name in dtypes if name not in columns]
    extra = [str(name) for name in columns if name not in dtypes]
    if missing or extra:
        raise ParameterError.of(
            table,
            "must have exactly the columns " + ", ".join(dtypes)
            + (f"; missing: {', '.join(missing)}" if missing else "")
            + (f"; unknown: {', '.join(extra)}" if extra else ""),
        )
    given = {name: _sized(columns[name]) for name in dtypes}
    lengths = {name: len(values) for name, values in given.items()}
    if len(set(lengths.values())) > 1:
        raise ParameterError.of(
            table, "must have equally long columns, got "
            + ", ".join(f"{name} {n}" for name, n in lengths.items()))
    return typed_frame(given, dtypes)


def typed_frame(columns: Mapping[str, Any], dtypes: Mapping[str, str],
                index: pd.Index | None = None) -> pd.DataFrame:
    """The table of ``columns`` in the order and dtypes of ``dtypes``, built in one step.

    Each column becomes one array of its dtype before the frame is made (no Series to align,
    no conversion after), the array ``pd.Series(list(values), dtype=dtype)`` would hold: a
    1-d NumPy array already of its dtype as it is (the frame copies it), a string column
    straight to a string array; any other sequence through that Series.

    Parameters
    ----------
    columns : mapping of str to sequence
        At least the columns of ``dtypes``, equally long (not checked here: the callers of
        :func:`pairs_frame` and :func:`edges_frame` are checked there).
    dtypes : mapping of str to str
        Column name -> dtype (:data:`PAIR_DTYPES`, :data:`EVIDENCE_DTYPES`,
        :data:`EDGE_DTYPES`).
    index : pandas.Index, optional
        The rows' index (default a range).

    Returns
    -------
    pandas.DataFrame

    Examples
    --------
    >>> import numpy as np
    >>> table = typed_frame({"source": np.array(["A"], dtype=object), "target": ["B"],
    ...                      "weight": np.array([0.2]), "kind": np.array(["directed"]),
    ...                      "degenerate": np.array([False])}, EDGE_DTYPES)
    >>> table.dtypes.astype(str).tolist()
    ['str', 'str', 'float64', 'str', 'bool']
    """
    return pd.DataFrame({name: _column(columns[name], dtype) for name, dtype in dtypes.items()},
                        index=index)


def _sized(values: Any) -> Any:
    return values if hasattr(values, "__len__") else list(values)


#: The NumPy dtype of each non-string dtype of the schema.
_NUMPY = {"float64": np.dtype(np.float64), "bool": np.dtype(np.bool_),
          "int64": np.dtype(np.int64)}
_STR = pd.api.types.pandas_dtype("str")


def _column(values: Any, dtype: str) -> Any:
    """The array ``pd.Series(list(values), dtype=dtype)`` holds, without the Series where it
    can: a 1-d NumPy array of the column's dtype as it is (the frame copies it), a string
    array as it is, other strings straight to a string array (the same conversion); any other
    sequence through the Series."""
    if isinstance(values, pd.Series):
        values = values.array if dtype == "str" else values.to_numpy()
    if dtype == "str":
        if isinstance(values, pd.api.extensions.ExtensionArray) and values.dtype == _STR:
            return values
        plain = isinstance(values, list) or isinstance(values, np.ndarray) and values.ndim == 1
        return pd.array(values if plain else list(values), dtype=_STR)
    if isinstance(values, np.ndarray) and values.ndim == 1 and values.dtype == _NUMPY[dtype]:
        return values
    return pd.Series(list(values), dtype=dtype).to_numpy()


def pairs_frame(columns: Mapping[str, Sequence[Any]]) -> pd.DataFrame:
    """A pairs table in the schema's column order and dtypes.

    Parameters
    ----------
    columns : mapping of str to sequence
        One equally long sequence per column of :data:`PAIR_COLUMNS`, in any order; or per
        column of :data:`PAIR_COLUMNS` and :data:`EVIDENCE_COLUMNS` (a network with evidence).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`PAIR_COLUMNS` (then :data:`EVIDENCE_COLUMNS` if given) with dtypes
        :data:`PAIR_DTYPES` (:data:`EVIDENCE_DTYPES`), a default index.

    Raises
    ------
    ParameterError
        A column is missing or not part of the schema (the message names it).

    Examples
    --------
    >>> columns = dict.fromkeys(PAIR_COLUMNS, [])
    >>> pairs_frame(columns).shape
    (0, 24)
    >>> pairs_frame({"x": []})
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: pairs must have exactly the columns x, y, ...; missing: ...
    """
    if any(name in columns for name in EVIDENCE_COLUMNS):
        return _frame(columns, _FULL_DTYPES, "pairs")
    return _frame(columns, PAIR_DTYPES, "pairs")


def edges_frame(columns: Mapping[str, Sequence[Any]]) -> pd.DataFrame:
    """An edges table in the schema's column order and dtypes (see :func:`pairs_frame`).

    Parameters
    ----------
    columns : mapping of str to sequence
        One sequence per column of :data:`EDGE_COLUMNS`.

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    ParameterError
        A column is missing or not part of the schema.

    Examples
    --------
    >>> edges_frame({"source": ["A"], "target": ["B"], "weight": [0.2], "kind": ["directed"],
    ...              "degenerate": [False]})
      source target  weight      kind  degenerate
    0      A      B     0.2  directed       False
    """
    return _frame(columns, EDGE_DTYPES, "edges")


def empty_pairs() -> pd.DataFrame:
    """A pairs table without rows (every column, every dtype).

    Returns
    -------
    pandas.DataFrame

    Examples
    --------
    >>> list(empty_pairs().columns) == list(PAIR_COLUMNS)
    True
    """
    return pairs_frame(dict.fromkeys(PAIR_COLUMNS, ()))


def empty_edges() -> pd.DataFrame:
    """An edges table without rows.

    Returns
    -------
    pandas.DataFrame

    Examples
    --------
    >>> list(empty_edges().columns)
    ['source', 'target', 'weight', 'kind', 'degenerate']
    """
    return edges_frame(dict.fromkeys(EDGE_COLUMNS, ()))


def _check(frame: Any, dtypes: Mapping[str, str], table: str,
           vocabulary: Mapping[str, tuple[str, ...]]) -> pd.DataFrame:
    if not isinstance(frame, pd.DataFrame):
        raise ParameterError.of(table, f"must be a pandas.DataFrame, got {type(frame).__name__}")
    names = [str(name) for name in frame.columns]
    if names != list(dtypes):
        missing = [name for name in dtypes if name not in names]
        extra = [name for name in names if name not in dtypes]
        detail = "must have the columns " + ", ".join(dtypes) + " in this order"
        if missing:
            detail += f"; missing: {', '.join(missing)}"
        if extra:
            detail += f"; unknown: {', '.join(extra)}"
        raise ParameterError.of(table, detail)
    for name, dtype in dtypes.items():
        if str(frame[name].dtype) != dtype:
            raise ParameterError.of(
                table, f"column {name} must have dtype {dtype}, got {frame[name].dtype}"
            )
    for name, allowed in vocabulary.items():
        bad = sorted(set(frame[name]) - set(allowed))
        if bad:
            raise ParameterError.of(
                table,
                f"column {name} holds {', '.join(map(repr, bad))}; kinds are "
                f"{', '.join(allowed)}",
            )
    return frame


def check_pairs(pairs: Any) -> pd.DataFrame:
    """``pairs`` itself if it follows the schema: columns, order, dtypes and kinds.

    A table with evidence has :data:`EVIDENCE_COLUMNS` after :data:`PAIR_COLUMNS`.

    Parameters
    ----------
    pairs : pandas.DataFrame

    Returns
    -------
    pandas.DataFrame
        ``pairs``, unchanged.

    Raises
    ------
    ParameterError
        The first difference: a missing, unknown or misplaced column, a dtype, or a kind outside
        :data:`PAIR_KINDS` (``kind``) or :data:`MEASURE_KINDS` (``c_kind``, ``t_kind``).

    Examples
    --------
    >>> check_pairs(empty_pairs()).empty
    True
    >>> check_pairs(empty_pairs().drop(columns="weight"))
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: pairs must have the columns x, ... in this order; missing: weight
    """
    if isinstance(pairs, pd.DataFrame) and len(pairs.columns) > len(PAIR_COLUMNS):
        return _check(pairs, _FULL_DTYPES, "pairs", _EVIDENCE_VOCABULARY)
    return _check(pairs, PAIR_DTYPES, "pairs", _VOCABULARY)


def check_edges(edges: Any) -> pd.DataFrame:
    """``edges`` itself if it follows the schema: columns, order, dtypes, kinds.

    Parameters
    ----------
    edges : pandas.DataFrame

    Returns
    -------
    pandas.DataFrame
        ``edges``, unchanged.

    Raises
    ------
    ParameterError
        The first difference from :data:`EDGE_DTYPES`, or a kind outside :data:`EDGE_KINDS`.

    Examples
    --------
    >>> check_edges(empty_edges()).empty
    True
    """
    return _check(edges, EDGE_DTYPES, "edges", {"kind": EDGE_KINDS})
