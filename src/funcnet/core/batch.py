"""Many windows at once: the pairs numbers of a stack of analysis windows in one compiled pass.

A sliding timeline, a grid of windows or a set of resampled windows asks for thousands of small
functional networks. The per-window path (:func:`funcnet.core.measures.pairwise_cross_measures` on
each normalized window) pays Python, validation and result objects per pair per window;
:func:`batch_pairs` validates once, then computes every window's normalization, every signal's
recurrence adjacency (once per window) and every pair's cross-recurrence and cross measures in
compiled loops spread over the cores (:mod:`funcnet.core._batch_kernels`), and returns the numbers
as
arrays.

The numbers are those of the per-window path, bit for bit: window ``w`` of
``batch_pairs(stack, names=..., parameters=p)`` holds, per pair, exactly the ``c_xy`` ...
``degenerate_reason`` of ``functional_network(stack[w], names=..., parameters=p).pairs`` (the
same exact order statistics, key bounds, integer counts, NumPy's summation order, flags and
reasons). Windows with more than :data:`DIRECT_MAX_STATES` states, fewer than
:data:`~funcnet.core.embedding.MIN_STATES`, explicit thresholds (``eps``) or amplitudes near the
float64 limit go through the per-window path inside :func:`batch_pairs` (whose errors they then
raise, prefixed with the window's position).

This module returns numbers only (layer L3c: it knows nothing of networks); the pipeline
(:func:`funcnet.pipeline.window_networks`) builds pairs tables and networks from them with the
schema and the edge rule of :mod:`funcnet.network`. Nothing here warns: the flags
``eps_ordered``, ``rate_exceeded`` and ``degenerate`` are in the arrays
(:func:`funcnet.core.measures.threshold_warnings` of :meth:`BatchPairs.measures` builds the
warnings).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Unpack

import numpy as np

from funcnet.core import _batch_kernels
from funcnet.core._isrn_kernels import _METRIC_CODE
from funcnet.core.embedding import MIN_STATES
from funcnet.core.measures import (
    CrossMeasures,
    _block_labels,
    _degenerate_reason,
    pairwise_cross_measures,
)
from funcnet.core.normalization import normalize as normalize_signals
from funcnet.core.thresholds import (
    _auto_candidates,
    _auto_rank,
    _cross_rank,
    _unordered_rank,
)
from funcnet.errors import FuncnetError, ParameterError, SignalError
from funcnet.parameters import PAIR_FIELDS, NetworkParameters, ParameterOverrides, resolve

__all__ = ["DIRECT_MAX_STATES", "RESULT_FIELDS", "BatchPairs", "applies", "batch_pairs",
           "stacked_measures", "window_ranks", "windows_per_block", "batch_kernel_for"]

#: Largest number of embedded states M for which a window is computed by the batched kernels;
#: larger windows go through the per-window path
#: (:data:`funcnet.core._batch_kernels.DIRECT_MAX_STATES`).
DIRECT_MAX_STATES = _batch_kernels.DIRECT_MAX_STATES

#: The per-pair numbers of a window, in the order of a pairs table
#: (:data:`funcnet.network.schema.RESULT_COLUMNS`).
RESULT_FIELDS = (
    "c_xy", "c_yx", "t_xy", "t_yx", "c_diff", "t_diff", "eps_x", "eps_y", "eps_xy",
    "achieved_rr_x", "achieved_rr_y", "achieved_cr", "eps_ordered", "rate_exceeded",
    "degenerate", "degenerate_reason",
)

# Windows per call of the kernel (at most): bounds the memory of the packed adjacencies.
_BLOCK = 512
_BLOCK_BYTES = 32 << 20
# Fewer (window, pair) tasks than this run in the calling thread (a parallel region wakes the
# other threads, which on a busy machine outweighs a small batch).
_PARALLEL_TASKS = 4
_ALLOWED = (*PAIR_FIELDS, "normalize")


@dataclass(frozen=True, eq=False)
class BatchPairs:
    """The pairs numbers of many windows (:func:`batch_pairs`).

    Attributes
    ----------
    names : tuple of str
        Signal names, in column order.
    pairs : tuple of (str, str)
        The pairs ``(x, y)``, X before Y in column order (the rows of each window's table).
    n_samples : ndarray of int64, shape (n_windows,)
        Samples of each window.
    values : dict of str to ndarray, shape (n_windows, n_pairs)
        One array per name of :data:`RESULT_FIELDS`: float64, the flags bool,
        ``degenerate_reason`` object (str, ``""`` unless degenerate).
    parameters : NetworkParameters
        The parameters that produced the numbers.
    """

    names: tuple[str, ...]
    pairs: tuple[tuple[str, str], ...]
    n_samples: np.ndarray
    values: dict[str, np.ndarray] = field(repr=False)
    parameters: NetworkParameters

    def __len__(self) -> int:
        return int(self.n_samples.size)

    def __getitem__(self, name: str) -> np.ndarray:
        """The ``(n_windows, n_pairs)`` array of one of :data:`RESULT_FIELDS`."""
        return self.values[name]

    def measures(self, window: int,
                 only: Sequence[int] | None = None) -> dict[tuple[str, str], CrossMeasures]:
        """Window ``window``'s results as :func:`~funcnet.core.measures.pairwise_cross_measures`
        returns them with ``names``: ``{(x, y): CrossMeasures}``, equal field by field.

        Parameters
        ----------
        window : int
            Position of the window.
        only : sequence of int, optional
            The positions (in :attr:`pairs`) of the pairs wanted, in order; default all.

        Returns
        -------
        dict
        """
        p = self.parameters
        states = int(self.n_samples[window]) - (p.dim - 1) * p.delay
        position = {name: i for i, name in enumerate(self.names)}
        found = {}
        # Python values (as the per-window path stores them), one column at a time.
        columns = {name: self.values[name][window].tolist() for name in RESULT_FIELDS}
        for q in range(len(self.pairs)) if only is None else only:
            x, y = self.pairs[q]
            fields = {name: columns[name][q] for name in RESULT_FIELDS}
            found[(x, y)] = CrossMeasures(
                **fields, m_x=states, m_y=states,
                parameters=p.for_pair(position[x], position[y]),
            )
        return found


def applies(n_samples: int, parameters: NetworkParameters) -> bool:
    """Whether windows of ``n_samples`` go through the batched kernels (else the per-window
    path): rates, not explicit thresholds, and ``MIN_STATES <= M <= DIRECT_MAX_STATES`` with a
    Theiler window that leaves pairs.

    Examples
    --------
    >>> applies(150, NetworkParameters()), applies(2000, NetworkParameters())
    (True, False)
    """
    p = parameters
    m = n_samples - (p.dim - 1) * p.delay
    return p.eps is None and MIN_STATES <= m <= DIRECT_MAX_STATES and p.theiler < m - 1


# --------------------------------------------------------------------------------------------
# input


def _stack(values: Any, offsets: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(table, starts, stops)``: windows as row ranges of one float64 (rows, signals) table."""
    if offsets is not None:
        table = np.asarray(values)
        if table.ndim != 2:
            raise SignalError(
                f"with offsets, values must be 2-D (rows, signals), got shape {table.shape}"
            )
        offsets = np.asarray(offsets)
        if (
            offsets.ndim != 1 or offsets.size < 2 or offsets.dtype.kind not in "iu"
            or offsets[0] != 0 or offsets[-1] != table.shape[0] or (np.diff(offsets) <= 0).any()
        ):
            raise ParameterError.of(
                "offsets",
                "must be increasing integers from 0 to the number of rows "
                f"({table.shape[0]}), one more than the number of windows",
            )
        offsets = offsets.astype(np.int64)
        starts, stops = offsets[:-1], offsets[1:]
    elif isinstance(values, np.ndarray) and values.ndim == 3:
        n_windows, n_samples, n_signals = values.shape
        if n_windows == 0 or n_samples == 0:
            raise SignalError(f"no windows or empty windows, got shape {values.shape}")
        table = values.reshape(n_windows * n_samples, n_signals)
        starts = np.arange(n_windows, dtype=np.int64) * n_samples
        stops = starts + n_samples
    else:
        windows = [np.asarray(window) for window in values]
        if not windows:
            raise SignalError("no windows given")
        if any(window.ndim != 2 or window.shape[0] == 0 for window in windows):
            raise SignalError("every window must be a non-empty 2-D array (samples, signals)")
        if len({window.shape[1] for window in windows}) != 1:
            raise SignalError("every window must hold the same number of signals")
        lengths = np.array([window.shape[0] for window in windows], dtype=np.int64)
        stops = np.cumsum(lengths)
        starts = stops - lengths
        table = np.concatenate(windows, axis=0)
    if table.dtype.kind not in "biuf":
        raise SignalError(f"signals must be real numbers, got dtype {table.dtype}")
    return np.ascontiguousarray(table, dtype=np.float64), starts, stops


def _plain_windows(table: np.ndarray, starts: np.ndarray, p: NetworkParameters) -> np.ndarray:
    """Per window: finite, normalizable, and (unnormalized) far from the float64 limit, so
    that the kernels need no check; the others go through the per-window path, which raises."""
    finite = np.isfinite(table)
    ok = np.logical_and.reduceat(finite, starts, axis=0).all(axis=1)
    with np.errstate(invalid="ignore", over="ignore"):
        safe = np.where(finite, table, 0.0)
        low = np.minimum.reduceat(safe, starts, axis=0)
        high = np.maximum.reduceat(safe, starts, axis=0)
        if p.normalize is not None:
            # z-scores square deviations: keep far from the overflow.
            large = np.maximum.reduceat(np.abs(safe), starts, axis=0).max(axis=1) < 1e150
            ok &= large | (p.normalize == "minmax")
            return ok & (high > low).all(axis=1) & np.isfinite(high - low).all(axis=1)
        # A bound on every distance, wider than the per-window check's (every coordinate spans
        # at most the window's range; a pair spans the union of its two ranges).
        span = high.max(axis=1) - low.min(axis=1)
        bound = span * span * (p.dim * table.shape[1])
        ok &= np.isfinite(bound) & (np.abs(safe).max(initial=0.0) < 1e38)
    return ok


def window_ranks(p: NetworkParameters, n_states: np.ndarray,
           n_signals: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per window and signal the rank of A among its unordered candidates
    (:func:`~funcnet.core.thresholds._unordered_rank`) and the number of ordered ones; per
    window those of CR (as :func:`funcnet.core.recurrence.auto_recurrence` and
    :func:`~funcnet.core.recurrence.cross_recurrence` set them)."""
    rates = list(p.rr) if isinstance(p.rr, tuple) else [p.rr] * n_signals
    if len(rates) != n_signals:
        raise ParameterError.of(
            "rr", f"must be one rate or one per signal ({n_signals}), got {len(rates)}: {p.rr!r}"
        )
    pyunicorn = p.rule == "pyunicorn"
    n = n_states.size
    auto_rank = np.zeros((n, n_signals), dtype=np.int64)
    auto_candidates = np.zeros(n, dtype=np.int64)
    cross_rank = np.zeros(n, dtype=np.int64)
    for m in np.unique(n_states).tolist():
        at = n_states == m
        auto_candidates[at] = _auto_candidates(m, p.theiler)
        for s, rate in enumerate(rates):
            auto_rank[at, s] = _unordered_rank(_auto_rank(rate, m, p.theiler, pyunicorn))
        cross_rank[at] = _cross_rank(p.cr, m * m, pyunicorn)
    return auto_rank, auto_candidates, cross_rank, n_states.astype(np.int64) ** 2


# --------------------------------------------------------------------------------------------
# the engine


def windows_per_block(n_signals: int, n_states: int) -> int:
    """Windows per call of the kernel: their packed adjacencies (windows x signals x M x M / 64
    words) stay within _BLOCK_BYTES (e.g. 80 windows of 5 signals at M = 800)."""
    per_window = n_signals * n_states * ((n_states + 63) // 64) * 8
    return max(1, min(_BLOCK, _BLOCK_BYTES // per_window))


def batch_kernel_for(
    n_windows: int, n_pairs: int, n_signals: int
) -> Callable[..., tuple[Any, ...]]:
    """The batched kernel for a call on ``n_windows``: in the calling thread when it has fewer
    than _PARALLEL_TASKS tasks of (window, signal) or (window, pair)."""
    serial = n_windows * max(n_pairs, n_signals) < _PARALLEL_TASKS
    return _batch_kernels.batch_kernel_serial if serial else _batch_kernels.batch_kernel


def stacked_measures(table: np.ndarray, n_windows: int, width: int, n_states: int,
                     parameters: NetworkParameters, pair_x: np.ndarray,
                     pair_y: np.ndarray) -> np.ndarray:
    """The cross measures of windows already normalized, laid out as embedded states.

    The evidence's resamples (:mod:`funcnet.evidence.interval`) draw states, renormalize them
    and hand the stack here: one compiled pass gives what :func:`batch_pairs` gives for plain
    windows, bit for bit.

    Parameters
    ----------
    table : ndarray, shape (n_windows * n_states * width, n_signals)
        Window ``w``'s states are rows ``w * n_states * width`` on, each state's ``width``
        coordinates one after the other.
    n_windows, width, n_states : int
        Windows in the stack, coordinates per state (``dim`` times the channels), states per
        window (any number from ``MIN_STATES``: the kernel is exact at every size; it is the
        faster path up to about :data:`DIRECT_MAX_STATES` for plain windows, and further for
        the resamples of a network, whose signals serve many pairs).
    parameters : NetworkParameters
        Thresholds by rate (``eps`` None), metric, Theiler window and rule.
    pair_x, pair_y : ndarray of int64
        The pairs, as column indices of ``table``.

    Returns
    -------
    ndarray, shape (n_windows, n_pairs, 4)
        ``C_xy, C_yx, T_xy, T_yx`` of every window and pair (Eq. 6-9).
    """
    p = parameters
    n_signals = table.shape[1]
    auto_rank, _, cross_rank, _ = window_ranks(p, np.full(1, n_states, dtype=np.int64),
                                               n_signals)
    rows = n_states * width
    bounds = np.arange(n_windows + 1, dtype=np.int64) * rows
    pyunicorn = p.rule == "pyunicorn"
    measures: np.ndarray = batch_kernel_for(n_windows, pair_x.size, n_signals)(
        table, bounds[:-1], bounds[1:], bounds, 0, False, width, n_states,
        _METRIC_CODE[p.metric], p.theiler, pyunicorn,
        np.ascontiguousarray(np.repeat(auto_rank, n_windows, axis=0)),
        np.repeat(cross_rank, n_windows), pair_x, pair_y, n_states, _batch_kernels.DIRECT_PAIRS,
    )[4]
    return measures


def batch_pairs(
    values: Any,
    offsets: Any = None,
    *,
    names: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    **overrides: Unpack[ParameterOverrides],
) -> BatchPairs:
    """Pairs numbers of many windows in one compiled pass, as the per-window path gives them.

    Parameters
    ----------
    values : ndarray (n_windows, n_samples, n_signals), sequence of 2-D arrays, or 2-D array
        The windows, time on the first axis of each, one signal per column. Windows of
        different lengths: a sequence of ``(n_samples_w, n_signals)`` arrays, or one
        ``(rows, n_signals)`` array with ``offsets``.
    offsets : array_like of int, shape (n_windows + 1,), optional
        With a 2-D ``values``: window ``w`` is rows ``offsets[w]:offsets[w + 1]``.
    names : sequence of str, optional
        Signal names (default ``"0"``, ``"1"``, ...), used in ``degenerate_reason``.
    parameters : NetworkParameters, optional
        Uses ``dim``, ``delay``, ``rr`` (one or one per signal), ``cr``, ``eps``, ``metric``,
        ``rule``, ``theiler`` and ``normalize`` (per window, before the embedding).
    **overrides
        Those fields by name.

    Returns
    -------
    BatchPairs
        Per window and pair the numbers of a pairs table (``c_xy`` ... ``degenerate_reason``),
        bit-identical to :func:`funcnet.network.functional_network` on the window.

    Raises
    ------
    ParameterError
        A bad parameter, bad ``offsets`` or ``names``; a Theiler window that leaves no pair.
    SignalError
        Fewer than two signals; a window with NaN/inf, a constant signal (when normalizing), or
        too short for the embedding; the message starts with ``window w:``.

    References
    ----------
    Eq. 1-10 (section 2) and section 3.3-3.4 (per-window min-max normalization, rates 0.05).

    Examples
    --------
    >>> import numpy as np
    >>> from funcnet.core.measures import pairwise_cross_measures
    >>> from funcnet.core.normalization import normalize
    >>> stack = np.random.default_rng(0).random((4, 150, 3))
    >>> result = batch_pairs(stack, names=["a", "b", "c"])
    >>> result["c_diff"].shape
    (4, 3)
    >>> single = pairwise_cross_measures(normalize(stack[2]), names=["a", "b", "c"], warn=False)
    >>> result.measures(2) == single
    True
    """
    p = resolve(parameters, overrides, allowed=_ALLOWED)
    table, starts, stops = _stack(values, offsets)
    n_signals = table.shape[1]
    names = [str(i) for i in range(n_signals)] if names is None else [str(n) for n in names]
    if len(names) != n_signals:
        raise ParameterError.of("names", f"has {len(names)} entries for {n_signals} signals")
    if len(set(names)) != len(names):
        raise ParameterError.of("names", f"must be unique, got {names}")
    if n_signals < 2:
        raise SignalError(f"a functional network needs at least two signals, got {n_signals}")
    lengths = (stops - starts).astype(np.int64)
    n_states = lengths - (p.dim - 1) * p.delay
    auto_rank, auto_candidates, cross_rank, cross_candidates = window_ranks(p, n_states, n_signals)
    pair_x, pair_y = (index.astype(np.int64) for index in np.triu_indices(n_signals, k=1))
    n_windows, n_pairs = starts.size, pair_x.size

    auto_eps = np.zeros((n_windows, n_signals))
    auto_count = np.zeros((n_windows, n_signals), dtype=np.int64)
    constant = np.zeros((n_windows, n_signals), dtype=bool)
    cross_eps = np.zeros((n_windows, n_pairs))
    cross_count = np.zeros((n_windows, n_pairs), dtype=np.int64)
    measures = np.zeros((n_windows, n_pairs, 4))

    direct_ok = np.array([applies(int(n), p) for n in lengths]) & _plain_windows(table, starts, p)
    direct = np.flatnonzero(direct_ok)
    block_size = windows_per_block(n_signals, int(n_states[direct].max()) if direct.size else 1)
    pyunicorn = p.rule == "pyunicorn"
    for first in range(0, direct.size, block_size):
        block = direct[first : first + block_size]
        norm_offsets = np.zeros(block.size + 1, dtype=np.int64)
        np.cumsum(lengths[block], out=norm_offsets[1:])
        out = batch_kernel_for(block.size, n_pairs, n_signals)(
            table, starts[block], stops[block], norm_offsets,
            _batch_kernels.NORMALIZE_CODE[p.normalize],
            pyunicorn, p.dim, p.delay, _METRIC_CODE[p.metric], p.theiler, pyunicorn,
            np.ascontiguousarray(auto_rank[block]), cross_rank[block], pair_x, pair_y,
            int(n_states[block].max()), _batch_kernels.DIRECT_PAIRS,
        )
        auto_eps[block], auto_count[block], cross_eps[block], cross_count[block] = out[:4]
        measures[block], constant[block] = out[4], out[5]
    columns = _columns(p, names, (pair_x, pair_y), auto_eps, auto_count, constant, cross_eps,
                       cross_count, measures, auto_rank, auto_candidates, cross_rank,
                       cross_candidates)
    for w in np.flatnonzero(~direct_ok).tolist():
        _per_window(table[starts[w] : stops[w]], names, w, p, columns)
    return BatchPairs(
        names=tuple(names),
        pairs=tuple((names[i], names[j]) for i, j in zip(pair_x, pair_y, strict=True)),
        n_samples=lengths,
        values=columns,
        parameters=p,
    )


def _columns(p: NetworkParameters, names: list[str], pairs: tuple[np.ndarray, np.ndarray],
             auto_eps: np.ndarray, auto_count: np.ndarray, constant: np.ndarray,
             cross_eps: np.ndarray, cross_count: np.ndarray, measures: np.ndarray,
             auto_rank: np.ndarray, auto_candidates: np.ndarray, cross_rank: np.ndarray,
             cross_candidates: np.ndarray) -> dict[str, np.ndarray]:
    """The result arrays from the kernel's counts, with the flags and reasons of
    :func:`funcnet.core.measures.isrn_measures`."""
    pair_x, pair_y = pairs
    rates = np.array(p.rr if isinstance(p.rr, tuple) else [p.rr] * len(names))
    with np.errstate(invalid="ignore", divide="ignore"):  # too short: per-window path below
        auto_rate = auto_count / auto_candidates[:, None]
        cross_rate = cross_count / cross_candidates[:, None]
    auto_exceeded = auto_count > 2 * auto_rank
    cross_exceeded = cross_count > cross_rank[:, None]
    auto_degenerate = constant | (auto_eps == 0.0) | (auto_rate > 2 * rates)
    cross_degenerate = (cross_eps == 0.0) | (cross_rate > 2 * p.cr)
    c_xy, c_yx, t_xy, t_yx = (np.ascontiguousarray(measures[:, :, i]) for i in range(4))
    eps_x, eps_y = auto_eps[:, pair_x], auto_eps[:, pair_y]
    degenerate = auto_degenerate[:, pair_x] | auto_degenerate[:, pair_y] | cross_degenerate
    reasons = np.full(degenerate.shape, "", dtype=object)
    for w, q in np.argwhere(degenerate).tolist():
        i, j = int(pair_x[q]), int(pair_y[q])
        label_i, label_j, label_ij = _block_labels(names[i], names[j])
        found = [
            _degenerate_reason(label, bool(constant[w, s]), float(auto_eps[w, s]),
                               float(auto_rate[w, s]), float(rates[s]))
            for s, label in ((i, label_i), (j, label_j))
        ]
        found.append(_degenerate_reason(label_ij, False, float(cross_eps[w, q]),
                                        float(cross_rate[w, q]), p.cr))
        reasons[w, q] = "; ".join(reason for reason in found if reason)
    return {
        "c_xy": c_xy, "c_yx": c_yx, "t_xy": t_xy, "t_yx": t_yx,
        "c_diff": c_xy - c_yx, "t_diff": t_xy - t_yx,
        "eps_x": np.ascontiguousarray(eps_x), "eps_y": np.ascontiguousarray(eps_y),
        "eps_xy": cross_eps,
        "achieved_rr_x": np.ascontiguousarray(auto_rate[:, pair_x]),
        "achieved_rr_y": np.ascontiguousarray(auto_rate[:, pair_y]),
        "achieved_cr": cross_rate,
        "eps_ordered": cross_eps < np.minimum(eps_x, eps_y),
        "rate_exceeded": auto_exceeded[:, pair_x] | auto_exceeded[:, pair_y] | cross_exceeded,
        "degenerate": degenerate,
        "degenerate_reason": reasons,
    }


def _per_window(window: np.ndarray, names: list[str], w: int, p: NetworkParameters,
                columns: dict[str, np.ndarray]) -> None:
    """One window through the per-window path, into ``columns``; errors name the window."""
    try:
        values = normalize_signals(window, p.normalize, names=names)
        signals = [values[:, s] for s in range(len(names))]
        results = pairwise_cross_measures(signals, names=names, parameters=p, warn=False)
    except FuncnetError as error:
        error.args = (f"window {w}: {error}",)
        raise
    for q, result in enumerate(results.values()):
        for name in RESULT_FIELDS:
            columns[name][w, q] = getattr(result, name)
