"""Thresholds and (cross-)recurrence structures of embedded states (paper section 2.1-2.2).

A signal of ``N`` samples becomes ``M = N - (dim - 1) * delay`` states (Eq. 1,
:mod:`funcnet.core.embedding`). Two states are recurrent when their distance is within a threshold
``eps`` (Eq. 2, 3, 5). The thresholds are usually fixed by a *rate*: the fraction of candidate
pairs that must be recurrent.

Threshold rule (``rule="funcnet"``, the default)
    * auto-recurrence of X (Eq. 5): the candidates are the ``P = (M - w)(M - w - 1)`` ordered pairs
      ``(i, j)`` with ``|i - j| > w`` (``w = theiler``; ``w = 0`` excludes only the diagonal, as the
      paper does). ``eps_X`` is the ``k``-th smallest of their distances,
      ``k = max(1, ceil(rr * P))`` computed exactly for the rate as written in decimal
      (``0.07``, not its float64 value); ``A_X[i, j] = 1`` iff ``|i - j| > w`` and
      ``d(x_i, x_j) <= eps_X``;
    * cross-recurrence (Eq. 3): the candidates are all ``P = M_X * M_Y`` pairs,
      ``k = max(1, ceil(cr * P))`` likewise; ``CR_XY[i, j] = 1`` iff ``d(x_i, y_j) <= eps_XY``.

    The order statistic is exact (not estimated from a sample) and reported in float64. Ties at the
    threshold can make more than ``k`` pairs recurrent; the achieved rate is reported next to each
    ``eps``, and the measures flag it (``rate_exceeded``, and ``degenerate`` when the threshold is
    0 or the rate more than twice its target).

Compatibility rule (``rule="pyunicorn"``)
    Reproduces pyunicorn 1.0.0's ``InterSystemRecurrenceNetwork``: the input series are cast to
    float32 (then embedded, and distances measured, in float64 from those values); ``eps`` is the
    element at index ``int(rate * (P - 1))`` (in float64, as pyunicorn computes it) of the sorted
    full distance matrix (diagonal included, ``P = M**2`` for auto-, ``M_X * M_Y`` for
    cross-recurrence); recurrence means ``d < eps`` (strict); the diagonal of ``A_X``, ``A_Y`` is
    zeroed, the cross block keeps its diagonal. An explicit ``eps`` is also compared strictly.
    ``theiler`` must be 0 in this mode. pyunicorn's own default metric is ``"supremum"``; here
    the metric is whatever the caller passes.

Achieved rates are reported as the fraction of candidate pairs that are recurrent (diagonal and
Theiler-excluded pairs are not candidates, under both rules).

Theiler window
    ``theiler = w`` excludes the pairs ``|i - j| <= w`` of one signal; ``w = 0`` excludes only
    the diagonal. pyrqa's and RecurrenceAnalysis.jl's window counts the diagonal: their
    ``theiler = 1`` excludes only the diagonal, so **theirs = ours + 1** (their ``w = 3`` is our
    ``theiler=2``). A cross-recurrence compares states of two systems and has no window.

Metrics
    ``"euclidean"`` (Eq. 2-3), ``"supremum"`` (alias ``"chebyshev"``) and ``"manhattan"``
    (alias ``"cityblock"``).

Parameters
    The functions take a :class:`funcnet.parameters.NetworkParameters` (``parameters=``) and
    keyword overrides of its fields. The single-block functions (:func:`auto_recurrence`,
    :func:`cross_recurrence`, :func:`recurrence_matrix`, :func:`cross_recurrence_matrix`) also
    take the block's own ``rr``/``cr`` and ``eps`` as plain numbers; without them the block's
    rate and threshold come from the parameters (``eps=(auto, cross)``).

Memory and speed: the ``M x M`` distance matrix is never stored, in any precision. Recurrence
structures are bit-packed rows (:class:`PackedRecurrence`, ``M^2 / 8`` bytes) built by compiled,
parallel kernels (:mod:`funcnet.core._isrn_kernels`) that compute one row of distances at a time;
the
exact order statistic (:mod:`funcnet.core.thresholds`) costs one pass over the pairs. At
M = 20000 one pair of signals needs about 0.4 GB. The kernels run many short parallel loops;
on a machine busy with other work, OpenMP's default of idle threads spinning between them can
make them several times slower (5 signals of 3000 samples on 2 shared cores: 1.8 s, against
0.53 s with ``OMP_WAIT_POLICY=PASSIVE``). Set that variable in the environment before Python
starts if it applies to you; the library never changes the environment.

Cost of a long window: :func:`estimate_cost` forecasts time and memory of one functional network
from the window's length before anything is computed (a rough model from measured constants),
so that an application can warn or refuse; the functions here never refuse on their own.

Length: over 600 lines because of the numpydoc of nine public names; the code is about 380.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, Unpack

import numba
import numpy as np

from funcnet.core._isrn_kernels import (
    _METRIC_CODE,
    _row_popcounts,
    _transpose_packed,
    _unpack,
)
from funcnet.core.embedding import MIN_STATES, signal_states
from funcnet.core.thresholds import (
    _auto_candidates,
    _auto_rank,
    _cross_rank,
    _unordered_rank,
    block_threshold,
    signal_thresholds,
    threshold_rows,
)
from funcnet.errors import ParameterError, SignalError
from funcnet.parameters import (
    METRICS,
    PAIR_FIELDS,
    RULES,
    BlockOverrides,
    NetworkParameters,
    ParameterOverrides,
    check_int,
    resolve,
)

__all__ = [
    "METRICS",
    "RULES",
    "CostEstimate",
    "PackedRecurrence",
    "auto_recurrence",
    "cross_recurrence",
    "recurrence_matrix",
    "cross_recurrence_matrix",
    "isrn_adjacency",
    "estimate_cost",
]


# --------------------------------------------------------------------------------------------
# packed recurrence structures


@dataclass(frozen=True, eq=False)
class PackedRecurrence:
    """A binary (cross-)recurrence matrix stored as bit-packed rows, with its threshold.

    Bit ``j`` of row ``i`` is word ``j // 64``, bit ``j % 64`` of ``rows[i]`` (little-endian
    bit order). Build it with :func:`auto_recurrence` or :func:`cross_recurrence`.

    Attributes
    ----------
    rows : ndarray of uint64, shape (n_rows, ceil(n_cols / 64))
        The packed rows.
    n_cols : int
        Number of columns.
    eps : float
        The threshold used (float64).
    rate : float
        Achieved rate: recurrent pairs / candidate pairs.
    target : float or None
        The requested rate, None when ``eps`` was given explicitly.
    n_recurrent : int
        Number of recurrent (ordered) pairs, i.e. of set bits.
    n_candidates : int
        Number of candidate (ordered) pairs the rate refers to.
    rank : int or None
        ``k``, the number of pairs the rule asked for (None with explicit ``eps``).
    rate_exceeded : bool
        True when ties at ``eps`` made more than ``k`` pairs recurrent (for an auto-recurrence,
        more than ``k`` rounded up to even: its pairs come in symmetric twins).
    constant : bool
        Every state is the same (an auto-recurrence of a constant signal): the structure is
        empty or complete whatever the threshold, and says nothing.

    Raises
    ------
    ParameterError
        ``rows`` is not a 2-D uint64 array of ``ceil(n_cols / 64)`` words per row.
    """

    rows: np.ndarray
    n_cols: int
    eps: float
    rate: float
    target: float | None
    n_recurrent: int
    n_candidates: int
    rank: int | None
    rate_exceeded: bool
    constant: bool = False

    def __post_init__(self) -> None:
        # The kernels index words without bounds checks: a wrong width would read past a row.
        rows = self.rows
        if (
            not isinstance(rows, np.ndarray)
            or rows.dtype != np.uint64
            or rows.ndim != 2
            or rows.shape[1] != (self.n_cols + 63) // 64
        ):
            raise ParameterError.of(
                "rows",
                f"must be a uint64 array of shape (n_rows, {(self.n_cols + 63) // 64}) for "
                f"n_cols={self.n_cols}, got {getattr(rows, 'dtype', type(rows).__name__)} "
                f"{getattr(rows, 'shape', '')}",
            )

    @property
    def shape(self) -> tuple[int, int]:
        """``(n_rows, n_cols)`` of the unpacked matrix."""
        return (self.rows.shape[0], self.n_cols)

    def to_dense(self) -> np.ndarray:
        """The matrix as a dense boolean array (for small sizes and figures)."""
        return np.asarray(_unpack(self.rows, self.n_cols))

    def row_sums(self) -> np.ndarray:
        """Number of recurrences of each row (the cross-degree of Eq. 7 for ``CR_XY``)."""
        return np.asarray(_row_popcounts(self.rows))

    def transposed(self) -> PackedRecurrence:
        """The transposed matrix (``CR_YX = CR_XY^T``), with the same threshold and counts."""
        return replace(
            self, rows=_transpose_packed(self.rows, self.n_cols), n_cols=self.rows.shape[0]
        )


# --------------------------------------------------------------------------------------------
# validation


def _check_states(states: Any, name: str) -> np.ndarray:
    array = np.ascontiguousarray(states, dtype=np.float64)
    if array.ndim != 2 or array.shape[0] < MIN_STATES or array.shape[1] < 1:
        raise SignalError(
            f"states of {name} must be a 2-D array (M >= {MIN_STATES} states, dim >= 1), got "
            f"shape {array.shape}"
        )
    if not np.isfinite(array).all():
        raise SignalError(f"states of {name} hold NaN or infinite values")
    return array


def _state_range(states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each coordinate's least and greatest value over the states (what
    :func:`_check_key_range` reads of a block)."""
    return states.min(axis=0), states.max(axis=0)


def _check_key_range(blocks: tuple[np.ndarray, ...], metric: str, label: str,
                     ranges: Sequence[tuple[np.ndarray, np.ndarray]] | None = None) -> None:
    """Raise unless every distance of the states in ``blocks`` is finite in float64.

    The bound uses each coordinate's full range, computed as the kernels compute keys; rounding
    is monotone, so a finite bound guarantees finite keys (it may refuse amplitudes within a
    factor ``dim`` of the overflow). ``ranges``: the blocks' :func:`_state_range`, when the
    caller has them (a signal in many pairs).
    """
    if ranges is None:
        ranges = [_state_range(b) for b in blocks]
    low = np.min([r[0] for r in ranges], axis=0)
    high = np.max([r[1] for r in ranges], axis=0)
    with np.errstate(over="ignore", invalid="ignore"):
        span = high - low
        if metric == "euclidean":
            bound = 0.0
            for value in span:
                bound += float(value) * float(value)
        elif metric == "supremum":
            bound = float(span.max())
        else:
            bound = 0.0
            for value in span:
                bound += float(value)
    if not math.isfinite(bound):
        raise SignalError(
            f"{label}: amplitudes too large to measure {metric} distances in float64 (a range "
            f"of {float(span.max()):.3g}); scale the signal down, e.g. normalize it"
        )




# --------------------------------------------------------------------------------------------
# one block



def auto_recurrence(
    states: Any,
    *,
    rr: float | None = None,
    eps: float | None = None,
    parameters: NetworkParameters | None = None,
    name: str = "x",
    **overrides: Unpack[BlockOverrides],
) -> PackedRecurrence:
    """Bit-packed recurrence adjacency ``A_X`` of embedded states (Eq. 2, 5).

    Parameters
    ----------
    states : array_like, shape (M, dim)
        Embedded states (:func:`funcnet.core.embedding.embed`, or
        :func:`funcnet.core.embedding.signal_states` for the rule's input cast), ``M >= 7``
        (:data:`funcnet.core.embedding.MIN_STATES`).
    rr : float in (0, 1), optional
        Target recurrence rate of this block.
    eps : float, optional
        Explicit threshold; overrides ``rr``. Without ``rr`` and ``eps`` the parameters' auto
        threshold (``eps=(auto, cross)``, one value) is used if set, else their ``rr``.
    parameters : NetworkParameters, optional
        Uses ``rr``, ``eps``, ``metric``, ``theiler``, ``rule`` (defaults: the paper's).
    name : str
        How error messages call the signal.
    **overrides
        ``metric`` (also ``chebyshev``, ``cityblock``), ``theiler`` (pairs ``|i - j| <= theiler``
        are neither recurrent nor candidates; pyrqa's and RecurrenceAnalysis.jl's window is
        ours + 1), ``rule``. Explicit ``rr``/``eps`` win over ``parameters``.

    Returns
    -------
    PackedRecurrence
        ``A_X`` without self-loops; ``rate`` is recurrent pairs over candidate pairs.

    Raises
    ------
    ParameterError
        Bad ``rr``, ``eps``, ``metric``, ``theiler`` (also: too large for M) or ``rule``; a
        per-signal ``rr`` or ``eps`` in ``parameters`` (pass this block's explicitly).
    SignalError
        ``states`` not a finite 2-D array with at least 7 rows, or amplitudes whose distances
        overflow float64.

    References
    ----------
    Eq. 2 and 5 (section 2.1-2.2).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.core.embedding import embed
    >>> states = embed(np.sin(np.linspace(0, 8 * np.pi, 251)), dim=3, delay=10)
    >>> a_x = auto_recurrence(states, rr=0.05)
    >>> a_x.rank, a_x.n_recurrent, a_x.n_candidates
    (2657, 2658, 53130)
    >>> round(a_x.eps, 6)
    0.188357
    """
    p = resolve(parameters, overrides, allowed=("metric", "theiler", "rule"))
    target, eps = block_threshold(p, rr, eps, auto=True)
    states = _check_states(states, name)
    _check_key_range((states,), p.metric, f"signal {name}")
    n_states = states.shape[0]
    theiler = p.theiler
    if theiler >= n_states - 1:
        raise ParameterError.of(
            "theiler", f"{theiler} excludes every pair of the {n_states} states of {name}"
        )
    pyunicorn = p.rule == "pyunicorn"
    n_candidates = _auto_candidates(n_states, theiler)
    # pyunicorn's rank 0 (an index among the diagonal's zeros): eps = 0, nothing recurrent.
    rank = None if target is None else _auto_rank(target, n_states, theiler, pyunicorn)
    threshold, rows, n_recurrent = threshold_rows(
        states,
        states,
        auto=True,
        theiler=theiler,
        metric=_METRIC_CODE[p.metric],
        rank=None if not rank else _unordered_rank(rank),
        n_pairs=n_candidates // 2,
        eps=0.0 if eps is None else eps,
        strict=pyunicorn,
    )
    return PackedRecurrence(
        rows=rows,
        n_cols=n_states,
        eps=threshold,
        rate=n_recurrent / n_candidates,
        target=target,
        n_recurrent=n_recurrent,
        n_candidates=n_candidates,
        rank=rank,
        rate_exceeded=rank is not None and n_recurrent > 2 * _unordered_rank(rank),
        constant=bool((states == states[0]).all()),
    )


def cross_recurrence(
    x_states: Any,
    y_states: Any,
    *,
    cr: float | None = None,
    eps: float | None = None,
    parameters: NetworkParameters | None = None,
    names: tuple[str, str] = ("x", "y"),
    **overrides: Unpack[BlockOverrides],
) -> PackedRecurrence:
    """Bit-packed cross-recurrence matrix ``CR_XY`` of two sets of embedded states (Eq. 3).

    Parameters
    ----------
    x_states, y_states : array_like, shapes (M_X, dim) and (M_Y, dim)
        Embedded states of X and Y (same ``dim``; ``M_X`` and ``M_Y`` may differ, each >= 7).
    cr : float in (0, 1), optional
        Target cross-recurrence rate over all ``M_X * M_Y`` pairs.
    eps : float, optional
        Explicit threshold ``eps_XY``, overrides ``cr``. Without ``cr`` and ``eps`` the
        parameters' cross threshold is used if set, else their ``cr``.
    parameters : NetworkParameters, optional
        Uses ``cr``, ``eps``, ``metric``, ``rule``.
    names : (str, str)
        How error messages call X and Y.
    **overrides
        ``metric``, ``rule``. (No ``theiler``: the cross block compares two systems and keeps
        every pair, its diagonal included.)

    Returns
    -------
    PackedRecurrence
        ``CR_XY`` with ``M_X`` rows and ``M_Y`` columns.

    Raises
    ------
    ParameterError
        Bad ``cr``, ``eps``, ``metric`` or ``rule``.
    SignalError
        States not finite 2-D arrays of at least 7 rows, of different ``dim``, or with
        distances that overflow float64.

    References
    ----------
    Eq. 3 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.core.embedding import embed
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> cr_xy = cross_recurrence(embed(np.sin(t), 3, 10), embed(np.cos(t), 3, 10), cr=0.05)
    >>> cr_xy.shape, cr_xy.n_recurrent, cr_xy.rank
    ((231, 231), 2669, 2669)
    """
    p = resolve(parameters, overrides, allowed=("metric", "rule"))
    target, eps = block_threshold(p, cr, eps, auto=False)
    x_name, y_name = names
    return _cross_block(_check_states(x_states, x_name), _check_states(y_states, y_name),
                        target, eps, p, names)


def _cross_block(
    x_states: np.ndarray, y_states: np.ndarray, target: float | None, eps: float | None,
    p: NetworkParameters, names: tuple[str, str],
    ranges: tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]] | None = None,
) -> PackedRecurrence:
    """:func:`cross_recurrence` of checked states (:func:`_check_states`) at the block's
    threshold (:func:`block_threshold`); ``ranges`` their :func:`_state_range` when known."""
    x_name, y_name = names
    if x_states.shape[1] != y_states.shape[1]:
        raise SignalError(
            f"states of {x_name} and {y_name} must have the same dim, got {x_states.shape[1]} "
            f"and {y_states.shape[1]}"
        )
    _check_key_range((x_states, y_states), p.metric, f"signals {x_name} and {y_name}", ranges)
    n_candidates = x_states.shape[0] * y_states.shape[0]
    pyunicorn = p.rule == "pyunicorn"
    rank = None if target is None else _cross_rank(target, n_candidates, pyunicorn)
    threshold, rows, n_recurrent = threshold_rows(
        x_states,
        y_states,
        auto=False,
        theiler=0,
        metric=_METRIC_CODE[p.metric],
        rank=rank,
        n_pairs=n_candidates,
        eps=0.0 if eps is None else eps,
        strict=pyunicorn,
    )
    return PackedRecurrence(
        rows=rows,
        n_cols=y_states.shape[0],
        eps=threshold,
        rate=n_recurrent / n_candidates,
        target=target,
        n_recurrent=n_recurrent,
        n_candidates=n_candidates,
        rank=rank,
        rate_exceeded=rank is not None and n_recurrent > rank,
    )


# --------------------------------------------------------------------------------------------
# signals -> ISRN blocks, and dense matrices for small N and figures




def _check_channels(states: list[np.ndarray], names: list[str], dim: int) -> None:
    """Raise unless every node has as many channels as the first (states of c * dim)."""
    first = states[0].shape[1] // dim
    for s, name in zip(states[1:], names[1:], strict=True):
        if s.shape[1] != states[0].shape[1]:
            raise SignalError(
                f"signals {names[0]} and {name} cannot be paired: {names[0]} has {first} "
                f"channels and {name} {s.shape[1] // dim}; a cross-recurrence compares states "
                "in one phase space"
            )


def _isrn_blocks(
    x: Any, y: Any, p: NetworkParameters
) -> tuple[PackedRecurrence, PackedRecurrence, PackedRecurrence]:
    """Validated ``(A_X, A_Y, CR_XY)`` of two signals (Eq. 4 blocks, packed)."""
    (block_x, block_y), (cr, eps_xy) = signal_thresholds(p, 2)
    x_states = signal_states(x, parameters=p, name="x")
    y_states = signal_states(y, parameters=p, name="y")
    _check_channels([x_states, y_states], ["x", "y"], p.dim)
    a_x = auto_recurrence(x_states, rr=block_x[0], eps=block_x[1], parameters=p, name="x")
    a_y = auto_recurrence(y_states, rr=block_y[0], eps=block_y[1], parameters=p, name="y")
    cr_xy = cross_recurrence(x_states, y_states, cr=cr, eps=eps_xy, parameters=p)
    return a_x, a_y, cr_xy


def recurrence_matrix(
    x: Any,
    *,
    rr: float | None = None,
    eps: float | None = None,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[BlockOverrides],
) -> np.ndarray:
    """Dense recurrence adjacency ``A_X`` of a signal (Eq. 2, 5), for small N and figures.

    Parameters
    ----------
    x : array_like, shape (N,) or (N, c)
        The signal (or a multichannel node), used as given.
    rr : float in (0, 1), optional
        Target recurrence rate over the ``(M - w)(M - w - 1)`` candidate pairs.
    eps : float, optional
        Explicit threshold; overrides ``rr``. Without either, the parameters' (default: rate
        0.05).
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay``, ``rr``, ``eps``, ``metric``, ``theiler``, ``rule``.
    **overrides
        ``dim``, ``delay``, ``metric``, ``theiler`` (``w``: pairs with ``|i - j| <= w`` are
        excluded; 0 excludes the diagonal only), ``rule``.

    Returns
    -------
    ndarray of bool, shape (M, M)
        ``A_X``: symmetric, no self-loops (Eq. 5). Add ``np.eye(M, dtype=bool)`` for the
        recurrence plot ``R`` of Eq. 2.

    Raises
    ------
    ParameterError, SignalError
        See :func:`auto_recurrence` and :func:`funcnet.core.embedding.signal_states`.

    References
    ----------
    Eq. 1, 2 and 5 (section 2.1-2.2).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.sin(np.linspace(0, 8 * np.pi, 251))
    >>> a_x = recurrence_matrix(x, dim=3, delay=10, eps=0.15)
    >>> a_x.shape, int(a_x.sum()), bool((a_x == a_x.T).all())
    ((231, 231), 1944, True)
    """
    p = resolve(parameters, overrides, allowed=("dim", "delay", "metric", "theiler", "rule"))
    states = signal_states(x, parameters=p, name="x")
    return auto_recurrence(states, rr=rr, eps=eps, parameters=p).to_dense()


def cross_recurrence_matrix(
    x: Any,
    y: Any,
    *,
    cr: float | None = None,
    eps: float | None = None,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[BlockOverrides],
) -> np.ndarray:
    """Dense cross-recurrence matrix ``CR_XY`` of two signals (Eq. 3).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,), or (N, c) multichannel nodes
        The signals, used as given (no normalization); their lengths may differ.
    cr : float in (0, 1), optional
        Target cross-recurrence rate over the ``M_X * M_Y`` pairs.
    eps : float, optional
        Explicit threshold ``eps_XY``; overrides ``cr``. Without either, the parameters'
        (default: rate 0.05).
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay``, ``cr``, ``eps``, ``metric``, ``rule``.
    **overrides
        ``dim``, ``delay``, ``metric``, ``rule``. There is no ``theiler``: ``CR_XY`` compares
        states of two systems and keeps its diagonal.

    Returns
    -------
    ndarray of bool, shape (M_X, M_Y)

    Raises
    ------
    ParameterError, SignalError
        See :func:`cross_recurrence` and :func:`funcnet.core.embedding.signal_states`.

    References
    ----------
    Eq. 3 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x = np.sin(t)
    >>> cr_xy = cross_recurrence_matrix(x, np.sin(1.5 * t) + 0.3 * x, eps=0.15)
    >>> cr_xy.shape, int(cr_xy.sum())
    ((231, 231), 64)
    """
    p = resolve(parameters, overrides, allowed=("dim", "delay", "metric", "rule"))
    x_states = signal_states(x, parameters=p, name="x")
    y_states = signal_states(y, parameters=p, name="y")
    _check_channels([x_states, y_states], ["x", "y"], p.dim)
    return cross_recurrence(x_states, y_states, cr=cr, eps=eps, parameters=p).to_dense()


def isrn_adjacency(
    x: Any,
    y: Any,
    *,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> np.ndarray:
    """Dense adjacency matrix of the inter-system recurrence network (Eq. 4).

    Parameters
    ----------
    x, y : array_like, shapes (N_X,) and (N_Y,), or (N, c) multichannel nodes
        The signals, used as given.
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay``, ``rr`` (one rate or ``(rr_x, rr_y)``), ``cr``, ``eps``
        (``(auto, cross)``: ``auto`` one threshold or ``(eps_x, eps_y)``; a None entry keeps its
        rate), ``metric``, ``theiler`` (of ``A_X`` and ``A_Y``; the cross block has none),
        ``rule``.
    **overrides
        Any of those fields.

    Returns
    -------
    ndarray of bool, shape (M_X + M_Y, M_X + M_Y)
        ``[[A_X, CR_XY], [CR_XY^T, A_Y]]``; X's states first.

    Raises
    ------
    ParameterError, SignalError
        Bad parameters, or a signal that is not finite or too short; the message names it.

    References
    ----------
    Eq. 4 and 5 (section 2.2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 8 * np.pi, 251)
    >>> x, y = np.sin(t), np.sin(1.5 * t) + 0.3 * np.sin(t)
    >>> adjacency = isrn_adjacency(x, y, eps=(0.15, 0.05))
    >>> adjacency.shape, bool((adjacency == adjacency.T).all())
    ((462, 462), True)
    """
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    a_x, a_y, cr_xy = _isrn_blocks(x, y, p)
    cross = cr_xy.to_dense()
    return np.block([[a_x.to_dense(), cross], [cross.T, a_y.to_dense()]])


# --------------------------------------------------------------------------------------------
# cost of a long window, before computing it

# CPU seconds per candidate pair of one threshold pass (auto: M^2 / 2 pairs, cross: M^2) and
# per unit of cr * M^3 of the triangle counts, and the resident size of an interpreter with
# NumPy, Numba and the kernels loaded: measured at M = 22,686 on the real 45 s trace
# (benchmarks/bench_long.py, AMD EPYC, 2 threads). Triangle costs vary about 2x with the data.
_CPU_PER_AUTO_PAIR = 1.5e-9
_CPU_PER_CROSS_PAIR = 1.2e-9
_CPU_PER_TRIANGLE_UNIT = 1.8e-12
_CPU_PER_PAIR_CALL = 2e-4
_BASE_BYTES = 200 * 2**20
_BAND_SAMPLE_MAX, _BAND_SAMPLE_MIN = 1 << 18, 1 << 14


@dataclass(frozen=True)
class CostEstimate:
    """A rough forecast of one functional network over a long window (:func:`estimate_cost`).

    Attributes
    ----------
    seconds : float
        Wall time on ``threads`` otherwise idle cores (a machine busy with other work takes
        longer: the CPU seconds do not change much, the wall time does).
    cpu_seconds : float
        CPU time of all threads.
    bytes : int
        Peak resident memory of the process: the interpreter (with NumPy, Numba and the
        kernels, about 200 MiB), every signal's packed ``A_X`` (held for all its pairs) and the
        largest transient of one pair (its ``CR_XY`` with the candidate band of its threshold,
        or ``CR_XY`` with its transpose).
    held_bytes : int
        The packed recurrence matrices held for the whole computation (``n_signals`` of them).
    pair_bytes : int
        The transient of one pair, freed before the next.
    n_states : int
        ``M = n_samples - (dim - 1) * delay``.
    n_pairs : int
        Pairs of signals, ``n_signals * (n_signals - 1) / 2``.
    threads : int
        Threads the forecast assumes.
    """

    seconds: float
    cpu_seconds: float
    bytes: int
    held_bytes: int
    pair_bytes: int
    n_states: int
    n_pairs: int
    threads: int

    def __str__(self) -> str:
        return (
            f"about {self.seconds:.2g} s on {self.threads} thread(s) ({self.cpu_seconds:.2g} "
            f"CPU s) and {self.bytes / 2**30:.2f} GiB peak for {self.n_pairs} pair(s) of "
            f"M = {self.n_states:,} states"
        )


def _band_bytes(n_pairs: int, rate: float) -> int:
    """Bytes the exact threshold of one block touches beside its rows: the candidate keys and
    positions inside the sampled bracket, their concatenation and the partial sort's copy."""
    if n_pairs <= 1 << 18:
        return 40 * n_pairs
    size = min(_BAND_SAMPLE_MAX, max(_BAND_SAMPLE_MIN, n_pairs >> 10))
    share = 16.0 * (math.sqrt(size * rate * (1.0 - rate)) + 1.0) / size
    return int(40 * min(1.0, share) * n_pairs)


def estimate_cost(
    n_samples: int,
    n_signals: int,
    parameters: NetworkParameters | None = None,
    *,
    threads: int | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> CostEstimate:
    """Forecast time and memory of one functional network of ``n_signals`` signals.

    A rough model from constants measured on the real 45 s trace (22,706 samples, 5 signals):
    each signal's threshold pass over its ``M^2 / 2`` pairs, each pair's over ``M^2``, the
    triangle counts growing as ``cr * M^3``; memory ``n_signals`` packed ``M x M`` bit
    matrices (``M^2 / 8`` bytes each) held throughout plus one pair's transient. Use it to warn
    or refuse before a long computation (the CLI does, above a limit); the computation itself
    never asks. Expect the time within a factor of about 2 to 3 (it depends on the data and on
    the machine), the memory within about 30 %.

    Parameters
    ----------
    n_samples : int
        Samples per signal (the window's length).
    n_signals : int
        Number of signals (nodes), at least 2; a multichannel node counts as one (its longer
        states make the threshold passes somewhat slower than forecast).
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay``, ``rr`` and ``cr`` (the largest when given per signal).
    threads : int, optional
        Threads to assume; default Numba's current number of threads.
    **overrides
        Fields of ``parameters``.

    Returns
    -------
    CostEstimate

    Raises
    ------
    ParameterError
        ``n_samples``, ``n_signals`` or ``threads`` not a positive integer (``n_signals`` < 2),
        a bad parameter, or a window shorter than the embedding.

    References
    ----------
    Eq. 1 (``M``), Eq. 5 and 3 (the threshold passes), Eq. 6-9 (triangle counts).

    Examples
    --------
    >>> cost = estimate_cost(22_706, 5, threads=2)
    >>> cost.n_states, cost.n_pairs, round(cost.held_bytes / 2**20)
    (22686, 10, 307)
    >>> cost.bytes < 2**30 < estimate_cost(45_000, 5, threads=2).bytes
    True
    """
    p = resolve(parameters, overrides, allowed=PAIR_FIELDS)
    n_samples = check_int(n_samples, "n_samples", minimum=1)
    n_signals = check_int(n_signals, "n_signals", minimum=2)
    if threads is None:
        threads = numba.get_num_threads()
    threads = check_int(threads, "threads", minimum=1)
    n_states = n_samples - (p.dim - 1) * p.delay
    if n_states < MIN_STATES:
        raise ParameterError.of(
            "n_samples",
            f"{n_samples} samples give {n_states} states with dim={p.dim}, delay={p.delay}; "
            f"at least {MIN_STATES} are needed",
        )
    rr = max(p.rr) if isinstance(p.rr, tuple) else float(p.rr)
    n_pairs = n_signals * (n_signals - 1) // 2
    squares = float(n_states) * n_states
    cpu = (
        n_signals * _CPU_PER_AUTO_PAIR * squares / 2
        + n_pairs * (
            _CPU_PER_CROSS_PAIR * squares
            + _CPU_PER_TRIANGLE_UNIT * p.cr * squares * n_states
            + _CPU_PER_PAIR_CALL
        )
    )
    packed = n_states * ((n_states + 63) // 64) * 8
    pair = max(2 * packed, packed + _band_bytes(n_states * n_states, p.cr))
    auto = packed + max(packed, _band_bytes(n_states * (n_states - 1) // 2, rr))
    transient = max(pair, auto)
    held = n_signals * packed
    return CostEstimate(
        seconds=cpu / threads,
        cpu_seconds=cpu,
        bytes=_BASE_BYTES + held + transient,
        held_bytes=held,
        pair_bytes=pair,
        n_states=n_states,
        n_pairs=n_pairs,
        threads=threads,
    )
