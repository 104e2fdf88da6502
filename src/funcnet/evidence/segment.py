"""The coupling test of a long segment at a bounded cost: the shift lattice on thinned states.

A robot network over more states than its bound is computed in parts
(:func:`funcnet.inspection.robot.robot_windows`), and the coupling test of a part holds few
surrogates: the shift lattice (:mod:`funcnet.evidence.dependence`) caps ``K`` at
``2 floor(M / (2 s0))``, the number of decorrelation times ``s0`` in half the window. Two parts
of a quiet 42.6 s arm hold K = 22 each for the position signals (``s0`` about 0.9 s), which
no adjustment over 435 pairs lets decide. ``K`` grows with the span tested, not with the
states in it, so the test is run once over the whole segment, on every ``d``-th state:

* **Thinning**: each signal is embedded at the network's ``(dim, delay)`` over the whole
  segment and every ``d``-th state is kept, ``d = ceil(M / max_states)``; the recurrences are
  thresholded by rate on the kept states. The lattice is spaced by ``ceil(s0 / d)`` kept
  states (``s0`` the larger decorrelation time of the two signals in samples, at least the
  embedding span, as unthinned), so every offset is at least ``s0`` samples, and ``K`` is
  that of the whole segment, up to rounding.
* **Validity**: thinned, two independent stationary signals stay independent and stationary,
  so every shifted window is a draw of the observed window's law, the argument of the
  unthinned lattice; measured on uncoupled systems at the nominal level
  (``benchmarks/validate_segment_test.py``, docs/validation/evidence.md section 8).
* **Cost**: ``K`` (at most ``max_surrogates``) windows of at most ``max_states`` kept states
  per pair, whatever the segment's length; the dense matrices of all signals are
  ``n_signals * max_states**2`` bytes, and a signal's states over the whole segment are held
  one signal at a time (:func:`segment_test_bytes`).

References
----------
M. C. Romano, M. Thiel, J. Kurths, W. von Bloh, "Multivariate recurrence plots", Phys. Lett. A
330, 214-223 (2004).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from funcnet.core.embedding import signal_states, thinned, thinning
from funcnet.core.recurrence import auto_recurrence
from funcnet.core.thresholds import signal_thresholds
from funcnet.errors import ParameterError
from funcnet.evidence._kernels import _flipped_windows
from funcnet.evidence.dependence import (
    DependenceResult,
    _result,
    decorrelation_time,
    default_surrogates,
    dependence_test,
    recurrent_pairs,
    shift_plan,
)
from funcnet.parameters import NetworkParameters

__all__ = ["SEGMENT_MAX_STATES", "SEGMENT_MAX_SURROGATES", "BYTES_PER_SAMPLE",
           "BYTES_PER_KEPT_CELL", "thinning", "segment_test_bytes",
           "segment_tests"]

#: Most kept states of a segment's coupling test (:func:`segment_tests`).
SEGMENT_MAX_STATES = 1500
#: Most surrogates of a segment's coupling test: ``1 / 200`` is reached when at least a tenth
#: of the pairs are at their smallest p-value (Benjamini-Hochberg at 0.05).
SEGMENT_MAX_SURROGATES = 199
#: Bytes per sample of one signal over the whole segment, held one signal at a time: its
#: decorrelation time's autocorrelation (an FFT padded to at most 4 N: the padded signal, its
#: half spectrum, their product and the inverse, about 104 bytes per sample) or its embedded
#: states (24 bytes per sample at ``dim = 3``), whichever is held.
BYTES_PER_SAMPLE = 128
#: Bytes per cell of one signal's kept states while its recurrence is thresholded by rate:
#: the float64 distances and the copies the selection of the rate's quantile makes.
BYTES_PER_KEPT_CELL = 24


def segment_test_bytes(n_signals: int, n_samples: int,
                       max_states: int = SEGMENT_MAX_STATES) -> int:
    """Bytes the largest arrays of :func:`segment_tests` hold at once, an upper bound.

    The kept states' dense recurrence matrices of every signal (``uint8``) and their
    recurrent-pair lists (at most ``rr`` of the cells, counted here as a fifth: two int64 per
    pair); the thresholding of one signal's kept states (its distances and their selection,
    :data:`BYTES_PER_KEPT_CELL`); and what one signal over the whole segment needs at a time
    (:data:`BYTES_PER_SAMPLE`).

    Examples
    --------
    >>> round(segment_test_bytes(30, 5326) / 2**20)   # the standing arm: 30 nodes
    129
    >>> round(segment_test_bytes(24, 900_000) / 2**20)  # one hour at 250 Hz, 24 nodes
    223
    """
    kept = min(n_samples, max_states)
    dense = n_signals * kept * kept
    recurrent = n_signals * (kept * kept // 2 // 5) * 16 // 8
    return dense + recurrent + kept * kept * BYTES_PER_KEPT_CELL + n_samples * BYTES_PER_SAMPLE


def segment_tests(signals: Sequence[Any], *, names: Sequence[str],
                  parameters: NetworkParameters | None = None, surrogates: int | None = None,
                  alpha: float = 0.05, max_states: int = SEGMENT_MAX_STATES,
                  max_surrogates: int = SEGMENT_MAX_SURROGATES,
                  ) -> tuple[dict[tuple[str, str], DependenceResult | None], int]:
    """The dependence test of every pair of a long segment, on its thinned states.

    Parameters
    ----------
    signals : sequence of array_like (N,) or (N, c)
        The nodes' signals over the whole segment, normalized as the network's.
    names : sequence of str
        Node names; the result's keys are their pairs ``(names[i], names[j])``, ``i < j``.
    parameters : NetworkParameters, optional
        ``dim``, ``delay``, ``rr``, ``eps``, ``metric``, ``theiler``, ``rule``.
    surrogates : int, optional
        ``K`` asked; default :func:`~funcnet.evidence.dependence.default_surrogates` of the
        pairs; never more than ``max_surrogates``.
    alpha : float
        The level the default ``K`` is computed for.
    max_states, max_surrogates : int
        The bounds of the cost (module notes).

    Returns
    -------
    (dict, int)
        ``{(x, y): DependenceResult}`` (None where the thinned segment is too short for one
        offset), and the thinning ``d``.

    Examples
    --------
    >>> from funcnet.validation.systems import henon_pair
    >>> data = henon_pair(6000, 0.6, seed=0)
    >>> tests, step = segment_tests([data[:, 0], data[:, 1]], names=["x", "y"],
    ...                             parameters=NetworkParameters(delay=1))
    >>> step, tests[("x", "y")].surrogates, round(tests[("x", "y")].p_value, 3)
    (4, 100, 0.01)
    """
    p = parameters if parameters is not None else NetworkParameters()
    n = len(signals)
    n_samples = int(np.shape(signals[0])[0])
    n_states = n_samples - (p.dim - 1) * p.delay
    step = thinning(n_states, max_states)
    asked = default_surrogates(n * (n - 1) // 2, alpha) if surrogates is None else surrogates
    k = min(int(asked), int(max_surrogates))
    thresholds, _ = signal_thresholds(p, n)
    on_kept = thinned(p, step)
    theiler = on_kept.theiler
    dense = []
    for signal, name, (rate, eps) in zip(signals, names, thresholds, strict=True):
        kept = signal_states(signal, parameters=p, name=repr(str(name)), step=step)
        dense.append(auto_recurrence(kept, rr=rate, eps=eps, parameters=on_kept,
                                     name=repr(str(name))).to_dense().astype(np.uint8))
    # a signal recurrent on most of its candidate pairs (a set-point at rest: its thinned
    # states tie at distance 0) is visited through its complement, the few pairs it lacks
    flipped = [_mostly_recurrent(a, theiler) for a in dense]
    recurrent = [recurrent_pairs(_complement(a, theiler) if flip else a)
                 for a, flip in zip(dense, flipped, strict=True)]
    decorrelation = [decorrelation_time(s) for s in signals]
    span = (p.dim - 1) * p.delay + 1
    out: dict[tuple[str, str], DependenceResult | None] = {}
    for i in range(n):
        for j in range(i + 1, n):
            s0 = math.ceil(max(decorrelation[i], decorrelation[j], span) / step)
            try:
                plan = shift_plan(dense[i].shape[0], k, min_shift=s0)
            except ParameterError:
                out[(names[i], names[j])] = None
                continue
            if not (flipped[i] or flipped[j]):
                out[(names[i], names[j])] = dependence_test(
                    dense[i], dense[j], plan, theiler=theiler,
                    recurrent=(recurrent[i], recurrent[j]))
                continue
            out[(names[i], names[j])] = _flipped_test(
                dense[j], recurrent[i], recurrent[j], plan, theiler, flipped[i], flipped[j])
    return out, step


def _mostly_recurrent(a: np.ndarray, theiler: int) -> bool:
    """Whether more than half of a matrix's candidate pairs (beyond the Theiler band) recur."""
    m = a.shape[0]
    candidates = max(0, m - theiler - 1) * max(0, m - theiler) // 2
    return bool(np.count_nonzero(np.triu(a, theiler + 1)) * 2 > candidates)


def _complement(a: np.ndarray, theiler: int) -> np.ndarray:
    """The candidate pairs (beyond the Theiler band) that do not recur, as a dense matrix."""
    out = np.triu(1 - a, theiler + 1).astype(np.uint8)
    return out + out.T


def _flipped_test(a_y: np.ndarray, pairs_x: np.ndarray, pairs_y: np.ndarray, plan: Any,
                  theiler: int, flip_x: bool, flip_y: bool) -> DependenceResult:
    """:func:`~funcnet.evidence.dependence.dependence_test` on the shift lattice with X or Y
    read through its complement (:func:`funcnet.evidence._kernels._flipped_windows`): the same
    counts, so the same result, at the cost of the sparser lists."""
    starts_x = np.concatenate([[plan.observed], plan.starts_x]).astype(np.int64)
    starts_y = np.concatenate([[plan.observed], plan.starts_y]).astype(np.int64)
    y = _complement(a_y, theiler) if flip_y else np.ascontiguousarray(a_y, dtype=np.uint8)
    values = _flipped_windows(y, pairs_x, pairs_y, starts_x, starts_y, plan.length,
                              int(theiler), flip_x, flip_y)
    return _result(values, plan.surrogates)
