"""Coupling tested across repetitions of one motion: does Y follow X beyond the command?

In a closed loop every signal follows the set-point, and a smooth robot window holds too few
time-shift surrogates to decide anything (docs/validation/evidence.md, "Robot windows"). Repetitions
of the same motion, aligned on the set-point, give what one window cannot: an independent sample per
repetition. :func:`repetition_evidence` asks, for every pair, whether X and Y share more than
the command.

Statistic
    For repetitions ``i, j`` of ``R``, ``phi[i, j]`` is the joint-recurrence correlation of X
    from repetition ``i`` with Y from repetition ``j`` over the whole window (the statistic of
    :mod:`funcnet.evidence.dependence`, same kernel). The coupling statistic is the excess of
    the same-repetition pairings over the cross-repetition ones::

        D = mean_i phi[i, i] - mean_{i != j} phi[i, j]

    The shared command enters ``phi[i, i]`` and ``phi[i, j]`` alike; what only the same
    repetition shares -- X's own fluctuations reaching Y -- raises the diagonal.

Signals: residuals about the mean over the repetitions (the default, ``residuals=True``)
    Each signal of each repetition minus its mean over the repetitions, then normalized and
    embedded as the network's signals are. On raw signals the recurrences are those of the
    command's shape, the same in every repetition, and the fluctuations beyond it barely move
    ``phi``; the residuals keep only the fluctuations. Chosen by the validation
    (docs/validation/evidence.md, "Repetitions": power on the physical links, residuals against
    raw).

Surrogates: repetition shuffles
    A surrogate pairs X of repetition ``i`` with Y of repetition ``pi(i)`` for a permutation
    ``pi`` of the repetitions: its statistic is ``mean_i phi[i, pi(i)]`` minus the same
    off-diagonal mean (the sum of all ``phi`` does not depend on ``pi``). When the repetitions
    are independent draws of the same motion and X and Y share nothing beyond it, every
    permutation gives a draw of the same law (exchangeability): the test is exact. With ``R <=
    7`` every permutation is used (``K = R! - 1`` surrogates), else ``K`` random ones.

p-value
    ``(1 + #{surrogate D >= observed D}) / (K + 1)``; the smallest is ``1 / R!`` (``R <= 7``)
    or ``1 / (K + 1)``. With ``m`` pairs a lone discovery under Benjamini-Hochberg at ``alpha``
    needs ``1 / R! <= alpha / m`` (:func:`repetitions_needed`): ``R >= 4`` for one pair at
    0.05, 5 for up to 6 pairs, 6 for up to 36, 7 for up to 252. Fewer repetitions leave the pair
    *untestable*, whatever the data.

Direction
    The conditional-recurrence index ``MCR(X|Y) - MCR(Y|X)`` of the same pairings, its
    same-repetition mean minus its cross-repetition mean, with a two-sided permutation
    p-value, as the single-window test reads it (:mod:`funcnet.evidence.dependence`).

Asymmetry
    ``C_diff`` and ``T_diff`` of each repetition's own network (the raw signals, the network's
    numbers, :func:`funcnet.core.batch.batch_pairs`), their mean and a Student-t interval of the
    mean from their spread across the repetitions; ``kind_share`` is the share of repetitions
    whose network gives the pair its most common kind (``kind``).

What it assumes: the repetitions are aligned on the command, and nothing but the pair's own
coupling makes a repetition differ from the others in both X and Y at once. A drift shared by
X and Y across the repetitions (a warming axis, a mirrored move whose friction differs) is a
common cause the test reports as coupling.

References
----------
M. C. Romano, M. Thiel, J. Kurths, W. von Bloh, "Multivariate recurrence plots", Phys. Lett. A
330, 214-223 (2004) (joint recurrences).
M. C. Romano, M. Thiel, J. Kurths, C. Grebogi, "Estimation of the direction of the coupling by
conditional probabilities of recurrence", Phys. Rev. E 76, 036211 (2007).
E. J. G. Pitman, "Significance tests which may be applied to samples from any populations",
J. R. Stat. Soc. Suppl. 4, 119-130 (1937) (permutation tests).
Y. Benjamini, Y. Hochberg, "Controlling the false discovery rate", J. R. Stat. Soc. B 57,
289-300 (1995).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from typing import Any, Unpack

import numpy as np
import pandas as pd
from scipy import special  # stdtrit is scipy.stats.t.ppf, without its import

from funcnet.core.batch import batch_pairs
from funcnet.core.embedding import signal_states
from funcnet.core.kinds import measure_kinds
from funcnet.core.normalization import normalize
from funcnet.core.recurrence import auto_recurrence
from funcnet.core.thresholds import signal_thresholds
from funcnet.errors import ParameterError, SignalError
from funcnet.evidence._kernels import _repetition_counts
from funcnet.evidence.dependence import benjamini_hochberg, default_surrogates
from funcnet.evidence.pairs import _check_alpha, _check_surrogates
from funcnet.evidence.reading import evidence_readings
from funcnet.parameters import NetworkParameters, ParameterOverrides, resolve

__all__ = ["REPETITION_COLUMNS", "repetition_evidence", "repetition_tests", "repetitions_needed",
           "smallest_p_value", "EXHAUSTIVE_MAX"]

#: A residual whose range is at most this fraction of its signal's range is constant.
_ROUNDING = 1e-12

#: Up to this many repetitions every permutation is a surrogate (7! = 5040).
EXHAUSTIVE_MAX = 7

#: The columns of :func:`repetition_evidence`'s table, in order.
REPETITION_COLUMNS: tuple[str, ...] = (
    "x", "y", "repetitions", "surrogates", "coupling_statistic", "coupling_p", "coupled",
    "direction_index", "direction_p", "direction", "kind", "kind_share",
    "c_diff_mean", "c_diff_low", "c_diff_high", "t_diff_mean", "t_diff_low", "t_diff_high",
    "evidence", "evidence_reason",
)


def smallest_p_value(repetitions: int, surrogates: int | None = None) -> float:
    """The smallest p-value the repetition test can give with ``R`` repetitions.

    Parameters
    ----------
    repetitions : int
        ``R``.
    surrogates : int, optional
        ``K`` random permutations (``R > EXHAUSTIVE_MAX``); default: every permutation.

    Returns
    -------
    float
        ``1 / R!`` with every permutation, else ``max(1 / R!, 1 / (K + 1))``.

    Examples
    --------
    >>> smallest_p_value(3), smallest_p_value(4), smallest_p_value(20, 999)
    (0.16666666666666666, 0.041666666666666664, 0.001)
    """
    exact = 1.0 / math.factorial(int(repetitions))
    return exact if surrogates is None else max(exact, 1.0 / (int(surrogates) + 1))


def repetitions_needed(n_pairs: int, alpha: float = 0.05) -> int:
    """The fewest repetitions for which a lone discovery among ``n_pairs`` can pass BH at ``alpha``.

    The smallest p-value ``1 / R!`` must not exceed Benjamini-Hochberg's smallest threshold
    ``alpha / n_pairs``.

    Parameters
    ----------
    n_pairs : int
        ``m``, the pairs adjusted together.
    alpha : float

    Returns
    -------
    int

    Examples
    --------
    >>> [repetitions_needed(m) for m in (1, 6, 10, 36, 210)]
    [4, 5, 6, 6, 7]
    """
    alpha = _check_alpha(alpha)
    r = 2
    while 1.0 / math.factorial(r) > alpha / max(int(n_pairs), 1) * (1 + 1e-12):
        r += 1
    return r


def _stack(repetitions: Any, signals: Sequence[str] | None) -> tuple[np.ndarray, list[str]]:
    """``(R, N, n)`` float64 and the node names from DataFrames or arrays of one shape."""
    if isinstance(repetitions, (np.ndarray, pd.DataFrame)) or not isinstance(
            repetitions, Sequence):
        if not (isinstance(repetitions, np.ndarray) and repetitions.ndim == 3):
            raise ParameterError.of("repetitions", "must be a sequence of windows (DataFrames or "
                                    "2-D arrays) or an array (R, time, signals)")
    items = list(repetitions)
    if len(items) < 2:
        raise ParameterError.of("repetitions", f"must hold at least 2 windows, got {len(items)}")
    frames = [isinstance(item, pd.DataFrame) for item in items]
    if any(frames) and not all(frames):
        raise ParameterError.of("repetitions", "mixes DataFrames and arrays")
    if all(frames):
        columns = [str(c) for c in items[0].columns]
        names = columns if signals is None else [str(s) for s in signals]
        for r, frame in enumerate(items):
            missing = [s for s in names if s not in [str(c) for c in frame.columns]]
            if missing:
                raise SignalError(f"repetition {r} has no signal(s) {', '.join(missing)}")
        arrays = [np.asarray(frame.set_axis([str(c) for c in frame.columns], axis=1)[names],
                             dtype=np.float64) for frame in items]
    else:
        arrays = [np.asarray(item, dtype=np.float64) for item in items]
        if arrays[0].ndim != 2:
            raise ParameterError.of("repetitions", f"windows must be 2-D (time x signals), got "
                                    f"shape {arrays[0].shape}")
        width = arrays[0].shape[1]
        names = [str(k) for k in range(width)] if signals is None else [str(s) for s in signals]
        if len(names) != width:
            raise ParameterError.of("signals", f"names {len(names)} signals for windows of "
                                    f"{width} columns")
    shapes = {a.shape for a in arrays}
    if len(shapes) != 1:
        raise SignalError(f"repetitions must all have one shape, got {sorted(shapes)}")
    if len(set(names)) != len(names) or len(names) < 2:
        raise ParameterError.of("signals", f"must name at least two distinct signals, got {names}")
    stack = np.stack(arrays)
    bad = np.argwhere(~np.isfinite(stack))
    if bad.size:
        r, t, s = bad[0]
        raise SignalError(f"repetition {r}: signal {names[s]} is not finite at sample {t}")
    return stack, names


def _permutations(r: int, surrogates: int, seed: int) -> np.ndarray:
    """The surrogate permutations, shape (K, R): every one but the identity, or K random."""
    if r <= EXHAUSTIVE_MAX:
        return np.array(list(itertools.permutations(range(r)))[1:], dtype=np.int64)
    rng = np.random.default_rng([int(seed), r])
    return np.argsort(rng.random((surrogates, r)), axis=1)


def _recurrences(stack: np.ndarray, p: NetworkParameters, residuals: bool, names: list[str]
                 ) -> tuple[list[np.ndarray], list[np.ndarray], list[np.ndarray], int, set[int]]:
    """Per node: dense recurrence matrices (R, M, M), their recurrent pairs, the pairs' offsets;
    the states' number; the nodes constant in every repetition."""
    values = stack - stack.mean(axis=0) if residuals else stack
    r, _, n = values.shape
    thresholds, _ = signal_thresholds(p, n)
    dense, pairs, offsets = [], [], []
    constants: set[int] = set()
    length = 0
    for s in range(n):
        rate, eps = thresholds[s]
        # A residual within rounding of the signal's own range is nothing beyond the mean (a
        # set-point the same in every repetition leaves float noise of its mean).
        flat = _ROUNDING * float(np.ptp(stack[:, :, s]))
        mats, lists = [], []
        flat_repetitions = 0
        for i in range(r):
            signal = values[i, :, s]
            constant = float(np.ptp(signal)) <= flat
            states = signal_states(
                signal if constant or p.normalize is None
                else normalize(signal, p.normalize, names=names[s]),
                parameters=p, name=f"{names[s]} (repetition {i})")
            if constant:
                # Every state recurs: phi is 0 against any Y, so is D, and p is 1.
                matrix = np.ones((len(states), len(states)), dtype=np.uint8)
                np.fill_diagonal(matrix, 0)
                flat_repetitions += 1
            else:
                matrix = auto_recurrence(states, rr=rate, eps=eps, parameters=p,
                                         name=names[s]).to_dense().astype(np.uint8)
            mats.append(matrix)
            lists.append(np.argwhere(np.triu(matrix, 1)).astype(np.int64))
            length = len(states)
        if flat_repetitions == r:
            constants.add(s)
        dense.append(np.ascontiguousarray(np.stack(mats)))
        pairs.append(np.ascontiguousarray(np.concatenate(lists)))
        offsets.append(np.concatenate([[0], np.cumsum([len(x) for x in lists])]).astype(np.int64))
    return dense, pairs, offsets, length, constants


def _excess(values: np.ndarray, perms: np.ndarray) -> tuple[float, np.ndarray]:
    """Same-repetition mean minus cross-repetition mean, observed and per permutation."""
    r = values.shape[0]
    total = values.sum()
    rows = np.arange(r)
    diagonal = values[rows, rows].sum()
    null_diagonal = values[rows[None, :], perms].sum(axis=1)

    def excess(d: Any) -> Any:
        return d / r - (total - d) / (r * (r - 1))

    return float(excess(diagonal)), excess(null_diagonal)


def _interval(values: np.ndarray, level: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean and Student-t interval of the mean over the repetitions (axis 0), per pair."""
    r = values.shape[0]
    mean = values.mean(axis=0)
    half = special.stdtrit(r - 1, (1 + level) / 2) * values.std(axis=0, ddof=1) / math.sqrt(r)
    return mean, mean - half, mean + half


def _most_common(kinds: np.ndarray) -> tuple[list[str], list[float]]:
    """Per column: the most common kind (first in order of appearance on ties) and its share."""
    most, share = [], []
    for column in kinds.T:
        labels, counts = np.unique(column.astype(str), return_counts=True)
        order = [list(column).index(label) for label in labels]
        best = max(range(len(labels)), key=lambda k: (counts[k], -order[k]))
        most.append(str(labels[best]))
        share.append(float(counts[best] / column.size))
    return most, share


def repetition_tests(
    repetitions: Sequence[Any],
    *,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    seed: int = 0,
    surrogates: int | None = None,
    residuals: bool = True,
    **overrides: Unpack[ParameterOverrides],
) -> pd.DataFrame:
    """The repetition coupling test of every pair alone, unadjusted (module notes).

    :func:`repetition_evidence` adjusts these p-values across the pairs and adds the networks'
    numbers; this is the test by itself, for callers that choose their own pairs to count (a
    validation).

    Parameters
    ----------
    repetitions, signals, parameters, seed, residuals, **overrides
        As :func:`repetition_evidence` (only the normalization, embedding and threshold
        parameters are used).
    surrogates : int, optional
        ``K`` random permutations for ``R > 7``; default 999. Ignored for ``R <= 7``.

    Returns
    -------
    pandas.DataFrame
        One row per pair: ``x``, ``y``, ``surrogates`` (``K``), ``coupling_statistic``
        (``D``), ``p_value`` (unadjusted), ``direction_index``, ``direction_p`` (unadjusted,
        two-sided).

    Raises
    ------
    ParameterError, SignalError
        As :func:`repetition_evidence`.

    Examples
    --------
    >>> from funcnet.validation.systems import henon_pair
    >>> runs = [henon_pair(200, 0.6, seed=s) for s in range(5)]
    >>> tests = repetition_tests(runs, signals=["x", "y"], delay=1)
    >>> int(tests.surrogates.item()), round(float(tests.p_value.item()), 4)
    (119, 0.0083)
    """
    p = resolve(parameters, overrides)
    _check_surrogates(surrogates)
    stack, names = _stack(repetitions, signals)
    return _tests(stack, names, p, seed, 999 if surrogates is None else surrogates, residuals)


def _tests(stack: np.ndarray, names: list[str], p: NetworkParameters, seed: int,
           surrogates: int, residuals: bool) -> pd.DataFrame:
    """:func:`repetition_tests` on a validated stack."""
    r, _, n = stack.shape
    perms = _permutations(r, surrogates, seed)
    k = int(perms.shape[0])
    dense, pairs, offsets, length, constants = _recurrences(stack, p, residuals, names)
    rows = []
    for a in range(n):
        for b in range(a + 1, n):
            if a in constants or b in constants:
                # phi is 0 in every pairing (the kernel's value); no direction to read either.
                counts = np.zeros((r, r, 3))
            else:
                counts = _repetition_counts(dense[b], pairs[a], offsets[a], pairs[b],
                                            offsets[b], length, p.theiler)
            observed, null = _excess(counts[:, :, 0], perms)
            p_value = (1 + int(np.count_nonzero(null >= observed))) / (k + 1)
            d_observed, d_null = _excess(counts[:, :, 1] - counts[:, :, 2], perms)
            centre = float(d_null.mean())
            spread = np.abs(d_null - centre)
            direction_p = (1 + int(np.count_nonzero(spread >= abs(d_observed - centre)))) / (k + 1)
            rows.append((names[a], names[b], k, observed, p_value, d_observed - centre,
                         direction_p))
    return pd.DataFrame(rows, columns=["x", "y", "surrogates", "coupling_statistic", "p_value",
                                       "direction_index", "direction_p"])


def repetition_evidence(
    repetitions: Sequence[Any],
    *,
    signals: Sequence[str] | None = None,
    parameters: NetworkParameters | None = None,
    alpha: float = 0.05,
    seed: int = 0,
    surrogates: int | None = None,
    residuals: bool = True,
    level: float = 0.95,
    **overrides: Unpack[ParameterOverrides],
) -> pd.DataFrame:
    """Evidence for every pair from ``R`` aligned repetitions of one motion (module notes).

    Parameters
    ----------
    repetitions : sequence of pandas.DataFrame or of array_like (N, n), or ndarray (R, N, n)
        ``R >= 2`` windows of one shape, one per repetition, aligned on the command: columns
        are the nodes (DataFrames) or signals (arrays, time on axis 0).
    signals : sequence of str, optional
        DataFrames: the columns to use (default all); arrays: the names of the columns
        (default ``"0"``, ``"1"``, ...).
    parameters : NetworkParameters, optional
        Normalization, embedding and thresholds (``normalize``, ``dim``, ``delay``, ``rr``,
        ``cr``, ``metric``, ``rule``, ``theiler``) and the edge rule (``mu``, ``mu_c``,
        ``mu_t``, ``measure``), as for a functional network of one repetition.
    alpha : float
        Level of the coupling and direction decisions (after Benjamini-Hochberg across the
        pairs).
    seed : int
        Seeds the random permutations (``R > 7``).
    surrogates : int, optional
        ``K`` random permutations for ``R > 7``; default
        ``max(999, default_surrogates(m, alpha))``. Ignored for ``R <= 7`` (all ``R! - 1``).
    residuals : bool
        Test the residuals about the mean over the repetitions (default) or the raw signals.
    level : float
        Coverage of the ``c_diff``/``t_diff`` intervals.
    **overrides
        Fields of ``parameters``.

    Returns
    -------
    pandas.DataFrame
        One row per pair (X before Y in signal order), columns :data:`REPETITION_COLUMNS`:
        ``repetitions`` ``R``; ``surrogates`` ``K``; ``coupling_statistic`` ``D``;
        ``coupling_p`` its permutation p-value, BH-adjusted across the pairs; ``coupled``
        (``coupling_p <= alpha``); ``direction_index``, ``direction_p`` (BH-adjusted) and
        ``direction``; ``kind`` and ``kind_share``; ``c_diff_mean``, ``c_diff_low``,
        ``c_diff_high``, ``t_diff_*`` likewise; ``evidence`` and ``evidence_reason``, read
        as a single window's (:func:`funcnet.evidence.reading.evidence_readings`: with ``K``
        shuffles a pair is ``untestable`` when ``1 / (K + 1) > alpha``), the reason ending
        with the repetitions a decision needs.

    Raises
    ------
    ParameterError
        Fewer than two repetitions or signals, a bad ``alpha``, ``level``, ``surrogates`` or
        parameter.
    SignalError
        Windows of different shapes, a missing column, NaN or infinite values (the message
        names the repetition and the signal), or windows too short for the embedding.

    References
    ----------
    Romano et al. (2004, 2007) for ``phi`` and the direction index; Pitman (1937) for the
    permutation test; Benjamini and Hochberg (1995); Eq. 10 and section 2.4 of the paper for
    ``C_diff``, ``T_diff`` and the kinds.

    Examples
    --------
    >>> from funcnet.validation.systems import henon_pair
    >>> runs = [henon_pair(300, 0.6, seed=s) for s in range(6)]
    >>> table = repetition_evidence(runs, signals=["x", "y"], delay=1)
    >>> row = table.iloc[0]
    >>> int(row.repetitions), int(row.surrogates), round(float(row.coupling_p), 4), row.evidence
    (6, 719, 0.0014, 'coupled')
    >>> repetition_evidence(runs[:3], signals=["x", "y"], delay=1).evidence.item()
    'untestable'
    """
    alpha = _check_alpha(alpha)
    if isinstance(level, bool) or not isinstance(level, (int, float)) or not 0 < level < 1:
        raise ParameterError.of("level", f"must be in (0, 1), got {level!r}")
    _check_surrogates(surrogates)
    p = resolve(parameters, overrides)
    stack, names = _stack(repetitions, signals)
    r, _, n = stack.shape
    n_pairs = n * (n - 1) // 2
    k_random = max(999, default_surrogates(n_pairs, alpha)) if surrogates is None else surrogates

    try:
        numbers = batch_pairs(stack, names=names, parameters=p)
    except SignalError as error:
        raise SignalError(str(error).replace("window", "repetition", 1)) from None
    kinds = np.stack([measure_kinds(c, t, p)[2]
                      for c, t in zip(numbers["c_diff"], numbers["t_diff"], strict=True)])
    kind, kind_share = _most_common(kinds)
    c_mean, c_low, c_high = _interval(numbers["c_diff"], level)
    t_mean, t_low, t_high = _interval(numbers["t_diff"], level)

    tests = _tests(stack, names, p, seed, k_random, residuals)
    k = int(tests.surrogates.iloc[0])
    keys = list(zip(tests.x, tests.y, strict=True))
    index = tests.direction_index.tolist()
    statistic = tests.coupling_statistic.tolist()
    raw_p, raw_dp = tests.p_value, tests.direction_p
    coupling_p = benjamini_hochberg(raw_p)
    direction_p = benjamini_hochberg(raw_dp)
    coupled = [bool(value <= alpha) for value in coupling_p]
    directions = []
    for q in range(len(keys)):
        direction = ""
        if coupled[q] and direction_p[q] <= alpha and index[q] != 0:
            direction = "x->y" if index[q] > 0 else "y->x"
        directions.append(direction)
    # The single-window labels and rule (untestable included), with K = R! - 1 or K shuffles.
    labels, reasons = evidence_readings(coupled, list(coupling_p), [k] * len(keys), directions,
                                        kind, alpha)
    needed = (f"R={r} repetitions ({'every permutation' if r <= EXHAUSTIVE_MAX else 'shuffles'}"
              f"); a decision needs R >= {repetitions_needed(1, alpha)} for one pair, "
              f"R >= {repetitions_needed(n_pairs, alpha)} for a lone discovery among "
              f"{n_pairs}")
    rows = []
    for q, (x, y) in enumerate(keys):
        rows.append((x, y, r, k, statistic[q], float(coupling_p[q]), coupled[q], index[q],
                     float(direction_p[q]), directions[q], kind[q], kind_share[q],
                     float(c_mean[q]), float(c_low[q]), float(c_high[q]),
                     float(t_mean[q]), float(t_low[q]), float(t_high[q]), labels[q],
                     f"{reasons[q]}; {needed}"))
    return pd.DataFrame(rows, columns=list(REPETITION_COLUMNS))
