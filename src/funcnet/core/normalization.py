"""Normalization of signals before a functional network is built (section 3.3).

The robot's signals live on different physical scales (degrees, amperes); without a common scale
one of them would dominate the phase-space distances of Eq. 2-3. The paper scales every signal to
[0, 1] (min-max) inside the analysis window; z-score is offered as the alternative its section 5.2
asks for. A constant signal has no range and no spread: it is an error that names the signal,
never a silent division by zero.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from funcnet.errors import ParameterError, SignalError
from funcnet.parameters import NORMALIZATIONS

__all__ = ["NORMALIZATIONS", "normalize"]

_LABEL = {"minmax": "min-max", "zscore": "z-score"}


def _signal_names(names: Any, n_signals: int, default: Sequence[str]) -> list[str]:
    if names is None:
        return list(default)
    if isinstance(names, str):
        names = [names]
    names = [str(name) for name in names]
    if len(names) != n_signals:
        raise ParameterError.of("names", f"has {len(names)} entries for {n_signals} signal(s)")
    return names


def _as_float_columns(x: Any, names: Any) -> tuple[np.ndarray, list[str]]:
    """``x`` as a 2-D float64 array (time x signals) and one name per column."""
    if isinstance(x, pd.DataFrame):
        names = _signal_names(names, x.shape[1], [str(column) for column in x.columns])
        values = np.empty(x.shape, dtype=np.float64)
        for i, name in enumerate(names):
            try:
                values[:, i] = x.iloc[:, i].to_numpy(dtype=np.float64)
            except (TypeError, ValueError) as error:
                raise SignalError(f"signal {name!r} is not numeric ({error})") from None
        return values, names
    array = np.asarray(x)
    if array.ndim not in (1, 2):
        raise SignalError(
            f"signals must be 1-D or 2-D (time x signals), got an array of shape {array.shape}"
        )
    table = array if array.ndim == 2 else array[:, np.newaxis]
    names = _signal_names(names, table.shape[1], [str(i) for i in range(table.shape[1])])
    if table.dtype.kind not in "biuf":
        raise SignalError(
            f"signals must be real numbers, got dtype {array.dtype} (signals {', '.join(names)})"
        )
    return table.astype(np.float64), names


def _check_normalization(method: Any) -> None:
    """Raise ParameterError unless ``method`` is one of :data:`NORMALIZATIONS`."""
    if method not in NORMALIZATIONS:
        raise ParameterError.of(
            "normalize", f"must be one of 'minmax', 'zscore' or None, got {method!r}"
        )


def normalize(x: Any, method: str | None = "minmax", *, names: Any = None) -> Any:
    """Scale each signal (column, time on axis 0) to a common range.

    Parameters
    ----------
    x : array_like, shape (N,) or (N, k), or pandas.DataFrame
        One signal, or ``k`` signals as columns. A DataFrame keeps its index and columns.
    method : {"minmax", "zscore", None}
        ``"minmax"``: ``(x - min) / (max - min)``, values in [0, 1] with both ends attained (the
        paper's choice, section 3.3); ``"zscore"``: ``(x - mean) / std`` with the population
        standard deviation (``ddof=0``); ``None``: the values unchanged (validated, as float64).
    names : str or sequence of str, optional
        How error messages call the signals; default the DataFrame's columns, else ``"0"``,
        ``"1"``, ... (the columns ``pandas.DataFrame(x)`` would get).

    Returns
    -------
    ndarray or pandas.DataFrame
        Float64, the shape (and for a DataFrame the index and columns) of ``x``.

    Raises
    ------
    ParameterError
        Unknown ``method``, or ``names`` of the wrong length.
    SignalError
        A signal is empty, not numeric, holds NaN or infinite values, or (``"minmax"``,
        ``"zscore"``) is constant or has a range beyond float64; the message names the signal.

    References
    ----------
    Section 3.3 (min-max scaling to [0, 1]) and section 5.2 (its limitation) of the paper.

    Examples
    --------
    >>> import numpy as np
    >>> normalize(np.array([[1.0, 10.0], [2.0, 30.0], [3.0, 20.0]]))
    array([[0. , 0. ],
           [0.5, 1. ],
           [1. , 0.5]])
    >>> normalize(np.array([1.0, 2.0, 3.0]), "zscore").round(4)
    array([-1.2247,  0.    ,  1.2247])
    >>> normalize(np.ones(4), names="AC")
    Traceback (most recent call last):
        ...
    funcnet.errors.SignalError: signal 'AC' is constant (value 1): min-max normalization needs ...
    """
    _check_normalization(method)
    values, names = _as_float_columns(x, names)
    if values.shape[0] == 0:
        raise SignalError(f"signals {', '.join(map(repr, names))} are empty")
    for i, name in enumerate(names):
        column = values[:, i]
        finite = np.isfinite(column)
        if not finite.all():
            bad = int(np.flatnonzero(~finite)[0])
            raise SignalError(
                f"signal {name!r} holds NaN or infinite values ({int((~finite).sum())} of "
                f"{column.size}, first at sample {bad}: {column[bad]})"
            )
        if method is None:
            continue
        low, high = column.min(), column.max()
        if low == high:
            # No range, no spread: scaling would divide by zero.
            raise SignalError(
                f"signal {name!r} is constant (value {low:.6g}): {_LABEL[method]} normalization "
                "needs a signal that varies inside the window; drop it or choose normalize=None"
            )
        if method == "minmax":
            with np.errstate(over="ignore"):  # an overflow is reported just below
                span = high - low
            if not np.isfinite(span):
                raise SignalError(f"signal {name!r} has a range beyond float64 ({low} .. {high})")
            values[:, i] = (column - low) / span
        else:
            std = column.std()
            if not np.isfinite(std) or std == 0.0:
                raise SignalError(
                    f"signal {name!r} has a standard deviation of {std}: cannot z-score it"
                )
            values[:, i] = (column - column.mean()) / std
    if isinstance(x, pd.DataFrame):
        return pd.DataFrame(values, index=x.index, columns=x.columns)
    return values.reshape(np.shape(x))
