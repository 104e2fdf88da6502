"""The input of :func:`funcnet.network.functional_network`: columns, their names, the nodes.

A node is one column or a group of columns (a multichannel signal, embedded jointly); every
problem is named: the column, the node, or the ``names``/``nodes`` argument.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from funcnet.core.normalization import normalize as normalize_signals
from funcnet.errors import ParameterError, SignalError
from funcnet.network.precision import checked_steps, logged_step, normalized_steps

__all__ = ["column_names", "float_columns", "node_groups", "PreparedSignals", "prepared_signals"]


def column_names(data: Any, names: Any) -> list[str]:
    """One name per column of ``data`` (a DataFrame's columns, ``names``, or "0", "1", ...)."""
    if isinstance(data, pd.DataFrame):
        count, default = data.shape[1], [str(column) for column in data.columns]
    else:
        array = np.asarray(data)
        if array.ndim not in (1, 2):
            raise SignalError(
                f"signals must be 1-D or 2-D (time x signals), got an array of shape "
                f"{array.shape}"
            )
        count = 1 if array.ndim == 1 else array.shape[1]
        default = [str(i) for i in range(count)]
    if names is None:
        columns = default
    else:
        columns = [str(name) for name in ([names] if isinstance(names, str) else names)]
        if len(columns) != count:
            raise ParameterError.of("names", f"has {len(columns)} entries for {count} signal(s)")
    repeated = sorted({name for name in columns if columns.count(name) > 1})
    if repeated:
        if names is None:
            raise ParameterError(
                f"the columns of data must be unique; repeated: {', '.join(repeated)}"
            )
        raise ParameterError.of("names", f"must be unique; repeated: {', '.join(repeated)}")
    return columns


def float_columns(data: Any, used: Sequence[int], columns: Sequence[str]) -> np.ndarray:
    """The columns ``used`` of ``data`` as one float64 array (time x columns)."""
    if isinstance(data, pd.DataFrame):
        kinds = data.dtypes.tolist()
        if all(isinstance(kinds[i], np.dtype) and kinds[i].kind in "biuf" for i in used):
            # plain NumPy columns: converted in one step, element by element as one by one
            # (a fresh C-ordered array, as below: the frame's may be a read-only view)
            whole = list(used) == list(range(len(kinds)))
            table = data if whole else data.iloc[:, list(used)]
            return np.array(table.to_numpy(dtype=np.float64), order="C")
        values = np.empty((data.shape[0], len(used)), dtype=np.float64)
        for k, i in enumerate(used):
            try:
                values[:, k] = data.iloc[:, i].to_numpy(dtype=np.float64)
            except (TypeError, ValueError) as error:
                raise SignalError(f"signal {columns[i]!r} is not numeric ({error})") from None
        return values
    array = np.asarray(data)
    table = array if array.ndim == 2 else array[:, np.newaxis]
    if table.dtype.kind not in "biuf":
        raise SignalError(
            f"signals must be real numbers, got dtype {array.dtype} "
            f"(signals {', '.join(columns[i] for i in used)})"
        )
    return table[:, list(used)].astype(np.float64)


def node_groups(nodes: Any, columns: Sequence[str]) -> tuple[list[str], list[list[int]]]:
    """Node names and, per node, the indices of its columns."""
    if nodes is None:
        return list(columns), [[i] for i in range(len(columns))]
    if not isinstance(nodes, Mapping):
        raise ParameterError.of(
            "nodes",
            f"must be a mapping node name -> column or list of columns, got "
            f"{type(nodes).__name__}",
        )
    index = {name: i for i, name in enumerate(columns)}
    names: list[str] = []
    groups: list[list[int]] = []
    owner: dict[str, str] = {}
    for node, members in nodes.items():
        name = str(node)
        if name in names:
            raise ParameterError.of("nodes", f"names node {name!r} twice")
        listed = [members] if isinstance(members, str) else members
        if not isinstance(listed, Sequence) or isinstance(listed, bytes) or not listed:
            raise ParameterError.of(
                "nodes", f"node {name!r} must be a column or a non-empty list of columns, "
                f"got {members!r}"
            )
        listed = [str(column) for column in listed]
        unknown = [column for column in listed if column not in index]
        if unknown:
            raise ParameterError.of(
                "nodes",
                f"node {name!r} names unknown column(s) {', '.join(map(repr, unknown))} "
                f"(columns: {', '.join(columns)})",
            )
        for column in listed:
            if column in owner:
                raise ParameterError.of(
                    "nodes",
                    f"column {column!r} is in node {owner[column]!r} and in node {name!r}",
                )
            owner[column] = name
        names.append(name)
        groups.append([index[column] for column in listed])
    sizes = {len(group) for group in groups}
    if len(sizes) > 1:
        # CR_XY compares states of X with states of Y: they must live in one space.
        shown = ", ".join(f"{name!r} {len(g)}" for name, g in zip(names, groups, strict=True))
        raise ParameterError.of(
            "nodes",
            f"must give every node the same number of columns (a cross-recurrence compares "
            f"states of equal dimension); got {shown}",
        )
    return names, groups


@dataclass(frozen=True)
class PreparedSignals:
    """The nodes' signals as the network reads them: normalized, one array per node.

    Attributes
    ----------
    names : tuple of str
        Node names, in node order.
    columns : tuple of str
        Every column's name.
    groups : tuple of tuple of int
        Per node, the indices of its columns.
    signals : tuple of ndarray
        Per node, its normalized samples: (N,) for a one-column node, (N, c) for a group.
    n_samples : int
        Samples per signal (``N``).
    steps : tuple of float
        Per node, the precision its column is logged with, in the normalized unit
        (:func:`~funcnet.network.precision.logged_step`; 0 for a group or without a grid).
    """

    names: tuple[str, ...]
    columns: tuple[str, ...]
    groups: tuple[tuple[int, ...], ...]
    signals: tuple[np.ndarray, ...]
    n_samples: int
    steps: tuple[float, ...] = ()


def prepared_signals(data: Any, names: Any, nodes: Any, normalize: str | None,
                     steps: Mapping[str, float] | None = None) -> PreparedSignals:
    """Columns named, grouped into nodes and normalized per column (every check named).

    Parameters
    ----------
    data : pandas.DataFrame or array_like, shape (N, k)
    names : sequence of str or None
        Column names (default the DataFrame's columns, else "0", "1", ...).
    nodes : mapping or None
        Node name -> column name(s); default one node per column.
    normalize : {"minmax", "zscore"} or None
    steps : mapping of str to float, optional
        Column name -> the precision it is logged with, in its unit (a whole channel's, when
        ``data`` is a window of it); a column not named: read from ``data``.

    Returns
    -------
    PreparedSignals

    Raises
    ------
    ParameterError
        Bad ``names``, ``nodes`` or ``steps``.
    SignalError
        Fewer than two nodes; a column not numeric, with NaN/inf, or constant under a
        normalization.

    Examples
    --------
    >>> import numpy as np
    >>> data = np.arange(16.0).reshape(4, 4) ** 2
    >>> prepared = prepared_signals(data, ["a1", "a2", "b1", "b2"],
    ...                             {"A": ["a1", "a2"], "B": ["b1", "b2"]}, "minmax")
    >>> prepared.names, prepared.groups, [s.shape for s in prepared.signals]
    (('A', 'B'), ((0, 1), (2, 3)), [(4, 2), (4, 2)])
    """
    columns = column_names(data, names)
    node_names, groups = node_groups(nodes, columns)
    if len(node_names) < 2:
        raise SignalError(
            f"a functional network needs at least two signals, got {len(node_names)}"
        )
    used = [i for group in groups for i in group]
    raw = float_columns(data, used, columns)
    values = normalize_signals(raw, normalize, names=[columns[i] for i in used])
    position = {i: k for k, i in enumerate(used)}
    known = checked_steps(steps, columns)
    node_steps = normalized_steps([known[columns[i]] if columns[i] in known
                                   else logged_step(raw[:, k]) for k, i in enumerate(used)],
                                  raw, values)
    # A one-column node is a 1-D signal (bit for bit the numbers of a plain column); a group
    # is an (N, c) multichannel signal.
    signals = tuple(
        values[:, position[group[0]]] if len(group) == 1
        else values[:, [position[i] for i in group]]
        for group in groups
    )
    return PreparedSignals(tuple(node_names), tuple(columns),
                           tuple(tuple(group) for group in groups), signals,
                           int(values.shape[0]),
                           tuple(float(node_steps[position[group[0]]]) if len(group) == 1
                                 else 0.0 for group in groups))
