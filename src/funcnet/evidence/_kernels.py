"""Compiled kernels of the evidence: joint recurrences in shifted windows (private).

Recurrence matrices arrive dense, as ``uint8`` arrays (a window holds at most a few thousand
states, and every surrogate or resample reads them at arbitrary offsets, which dense rows make
a plain index). Surrogates never copy or recompute a matrix: a time offset of Y against X is a
shift of the indices at which ``A_Y`` is read. A shift lattice packs each matrix's listed pairs
once per test into rows of bits and counts a window by popcounts of its rows
(:func:`_window_bits`): the integer counts of the scan of every listed pair, in ``length / 64``
words per state (docs/validation/evidence.md, section 9).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit, prange, types
from numba.extending import intrinsic

Array = np.ndarray
Int = int | np.integer[Any]


if TYPE_CHECKING:  # what the intrinsic computes, as mypy should see it

    def _popcount(word: Any) -> Any: ...

else:

    @intrinsic
    def _popcount(typingctx: Any, word: Any) -> Any:
        """Number of set bits of a uint64 (LLVM ``ctpop``; the core keeps its own, private)."""
        signature = types.uint64(types.uint64)

        def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
            return builder.ctpop(args[0])

        return signature, codegen


@njit(cache=True, inline="always")
def _statistics(n_x: Int, n_y: Int, n_xy: Int, row_x: Array, row_y: Array, row_xy: Array,
                length: Int, theiler: Int) -> tuple[float, float, float]:
    """``(phi, mcr(x|y), mcr(y|x))`` from the counts of one window (shared by both kernels)."""
    sum_x_given_y = 0.0
    sum_y_given_x = 0.0
    rows_x = 0
    rows_y = 0
    for u in range(length):
        if row_y[u] > 0:
            sum_x_given_y += row_xy[u] / row_y[u]
            rows_y += 1
        if row_x[u] > 0:
            sum_y_given_x += row_xy[u] / row_x[u]
            rows_x += 1
    gap = min(theiler + 1, length)
    n_pairs = (length - gap) * (length - gap + 1) // 2
    phi = 0.0
    if n_pairs > 0:
        px = n_x / n_pairs
        py = n_y / n_pairs
        var = px * (1.0 - px) * py * (1.0 - py)
        if var > 0.0:
            phi = (n_xy / n_pairs - px * py) / np.sqrt(var)
    x_given_y = sum_x_given_y / rows_y if rows_y else 0.0
    y_given_x = sum_y_given_x / rows_x if rows_x else 0.0
    return phi, x_given_y, y_given_x


@njit(cache=True)
def _scan(a_y: Array, pairs_x: Array, pairs_y: Array, start_x: Int, start_y: Int, length: Int,
          theiler: Int) -> tuple[int, int, int, Array, Array, Array]:
    """The window's counts ``(n_x, n_y, n_xy, row_x, row_y, row_xy)``: recurrent pairs of X, of
    Y, of both, and each state's share of them (:func:`_window_counts`)."""
    row_x = np.zeros(length, dtype=np.int64)
    row_y = np.zeros(length, dtype=np.int64)
    row_xy = np.zeros(length, dtype=np.int64)
    n_x = 0
    n_y = 0
    n_xy = 0
    stop_x = start_x + length
    for k in range(pairs_x.shape[0]):
        i = pairs_x[k, 0]
        j = pairs_x[k, 1]
        if i < start_x or j >= stop_x or j - i <= theiler:
            continue
        u = i - start_x
        v = j - start_x
        n_x += 1
        row_x[u] += 1
        row_x[v] += 1
        if a_y[start_y + u, start_y + v]:
            n_xy += 1
            row_xy[u] += 1
            row_xy[v] += 1
    stop_y = start_y + length
    for k in range(pairs_y.shape[0]):
        i = pairs_y[k, 0]
        j = pairs_y[k, 1]
        if i < start_y or j >= stop_y or j - i <= theiler:
            continue
        n_y += 1
        row_y[i - start_y] += 1
        row_y[j - start_y] += 1
    return n_x, n_y, n_xy, row_x, row_y, row_xy


@njit(cache=True)
def _window_counts(a_y: Array, pairs_x: Array, pairs_y: Array, start_x: Int, start_y: Int,
                   length: Int, theiler: Int) -> tuple[float, float, float]:
    """``(phi, mcr(x|y), mcr(y|x))`` of the window pairing ``x[start_x + i]``, ``y[start_y + i]``.

    ``phi`` is the correlation of the indicators ``A_X[i, j]`` and ``A_Y[i, j]`` over the
    window's pairs ``i < j``, ``j - i > theiler``; ``mcr(x|y)`` the mean over the window's states
    of ``sum_j JR_ij / sum_j A_Y[i, j]`` (states without a Y-neighbour left out). ``pairs_x``
    and ``pairs_y`` list the recurrent pairs ``(i, j)``, ``i < j``, of each whole matrix: a
    window visits them, not its ``L^2`` cells.
    """
    n_x, n_y, n_xy, row_x, row_y, row_xy = _scan(a_y, pairs_x, pairs_y, start_x, start_y,
                                                  length, theiler)
    return _statistics(n_x, n_y, n_xy, row_x, row_y, row_xy, length, theiler)


@njit(cache=True)
def _upper_pairs(a: Array) -> Array:
    """The pairs ``(i, j)``, ``i < j``, of the non-zero cells of a matrix, in row order, then
    column order: ``np.argwhere(np.triu(a, 1))`` without the matrix's copy."""
    m, n = a.shape
    count = 0
    for i in range(m):
        for j in range(i + 1, n):
            if a[i, j]:
                count += 1
    out = np.empty((count, 2), dtype=np.int64)
    k = 0
    for i in range(m):
        for j in range(i + 1, n):
            if a[i, j]:
                out[k, 0] = i
                out[k, 1] = j
                k += 1
    return out


@njit(cache=True)
def _sorted_upper(pairs: Array, m: Int) -> bool:
    """Whether ``pairs`` lists distinct pairs ``0 <= i < j < m`` in row order, then column
    order (as :func:`~funcnet.evidence.dependence.recurrent_pairs` gives them)."""
    for k in range(pairs.shape[0]):
        i = pairs[k, 0]
        j = pairs[k, 1]
        if i < 0 or j <= i or j >= m:
            return False
        if k > 0:
            h = pairs[k - 1, 0]
            if i < h or (i == h and j <= pairs[k - 1, 1]):
                return False
    return True


@njit(cache=True)
def _packed_rows(pairs: Array, m: Int) -> Array:
    """The symmetric matrix of the pairs ``(i, j)`` as bits: row ``i``, bit ``j & 63`` of word
    ``j >> 6``; shape (m, words), one spare word per row so that a read of 64 bits at any
    offset inside the row has the word after it. ``m * (m / 8 + 8)`` bytes."""
    words = (m + 63) // 64 + 1
    bits = np.zeros((m, words), dtype=np.uint64)
    one = np.uint64(1)
    for k in range(pairs.shape[0]):
        i = pairs[k, 0]
        j = pairs[k, 1]
        bits[i, j >> 6] |= one << np.uint64(j & 63)
        bits[j, i >> 6] |= one << np.uint64(i & 63)
    return bits


@njit(cache=True, inline="always")
def _bit(bits: Array, row: Int, column: Int) -> int:
    return int((bits[row, column >> 6] >> np.uint64(column & 63)) & np.uint64(1))


@njit(cache=True)
def _window_bits(bits_x: Array, bits_y: Array, start_x: Int, start_y: Int, length: Int,
                 theiler: Int) -> tuple[float, float, float]:
    """:func:`_window_counts` from the matrices as bits (:func:`_packed_rows`).

    State ``u`` of the window counts its X-, Y- and joint neighbours in the window as
    popcounts of its two rows read from ``start_x`` and ``start_y`` (64 states a word), less
    the ``theiler`` band (the diagonal is empty). Each pair is counted at both its states, so
    ``n_x`` is half the sum of ``row_x``: the integer counts of :func:`_window_counts`, and the
    statistics the same numbers, bit for bit.
    """
    row_x = np.zeros(length, dtype=np.int64)
    row_y = np.zeros(length, dtype=np.int64)
    row_xy = np.zeros(length, dtype=np.int64)
    words = (length + 63) >> 6
    rest = length & 63
    last = ~np.uint64(0) if rest == 0 else (np.uint64(1) << np.uint64(rest)) - np.uint64(1)
    word_x, shift_x = start_x >> 6, np.uint64(start_x & 63)
    word_y, shift_y = start_y >> 6, np.uint64(start_y & 63)
    back_x, back_y = np.uint64(63) - shift_x, np.uint64(63) - shift_y
    for u in range(length):
        r_x = start_x + u
        r_y = start_y + u
        # the row's words as views: one load per word, no index arithmetic in the loop
        xs = bits_x[r_x, word_x : word_x + words + 1]
        ys = bits_y[r_y, word_y : word_y + words + 1]
        cx = np.uint64(0)
        cy = np.uint64(0)
        cxy = np.uint64(0)
        for w in range(words):
            xw = (xs[w] >> shift_x) | ((xs[w + 1] << np.uint64(1)) << back_x)
            yw = (ys[w] >> shift_y) | ((ys[w + 1] << np.uint64(1)) << back_y)
            if w == words - 1:
                xw &= last
                yw &= last
            cx += _popcount(xw)
            cy += _popcount(yw)
            cxy += _popcount(xw & yw)
        nx, ny, nxy = np.int64(cx), np.int64(cy), np.int64(cxy)
        for v in range(max(0, u - theiler), min(length, u + theiler + 1)):
            if v != u:
                bx = _bit(bits_x, r_x, start_x + v)
                by = _bit(bits_y, r_y, start_y + v)
                nx -= bx
                ny -= by
                nxy -= bx & by
        row_x[u] = nx
        row_y[u] = ny
        row_xy[u] = nxy
    n_x = np.int64(row_x.sum() // 2)
    n_y = np.int64(row_y.sum() // 2)
    n_xy = np.int64(row_xy.sum() // 2)
    return _statistics(n_x, n_y, n_xy, row_x, row_y, row_xy, length, theiler)


@njit(cache=True, parallel=True)
def _bit_windows(bits_x: Array, bits_y: Array, starts_x: Array, starts_y: Array, length: Int,
                 theiler: Int) -> Array:
    """:func:`_window_bits` of every window ``(starts_x[k], starts_y[k])``: shape (K, 3), from
    matrices already as bits (:func:`_packed_rows`; a signal in many pairs is packed once)."""
    out = np.empty((starts_x.size, 3), dtype=np.float64)
    for k in prange(starts_x.size):
        phi, xy, yx = _window_bits(bits_x, bits_y, starts_x[k], starts_y[k], length, theiler)
        out[k, 0] = phi
        out[k, 1] = xy
        out[k, 2] = yx
    return out


@njit(cache=True, parallel=True)
def _windows(a_y: Array, pairs_x: Array, pairs_y: Array, starts_x: Array, starts_y: Array,
             length: Int, theiler: Int) -> Array:
    """:func:`_window_counts` of every window ``(starts_x[k], starts_y[k])``: shape (K, 3).

    Pairs lists as :func:`~funcnet.evidence.dependence.recurrent_pairs` gives them (distinct,
    ``i < j``, sorted) are turned into bits once (:func:`_packed_rows`, two matrices of
    ``M**2 / 8`` bytes) and every window counts by popcounts (:func:`_window_bits`, about
    ``length**2 / 20`` word operations instead of a visit of every listed pair): the same
    numbers. Other lists are scanned whole for each window, reading Y's pairs in ``a_y``.
    """
    n = starts_x.size
    m = a_y.shape[0]
    if _sorted_upper(pairs_x, m) and _sorted_upper(pairs_y, m):
        return _bit_windows(_packed_rows(pairs_x, m), _packed_rows(pairs_y, m), starts_x,
                            starts_y, length, theiler)
    out = np.empty((n, 3), dtype=np.float64)
    for k in prange(n):
        phi, xy, yx = _window_counts(a_y, pairs_x, pairs_y, starts_x[k], starts_y[k], length,
                                     theiler)
        out[k, 0] = phi
        out[k, 1] = xy
        out[k, 2] = yx
    return out


@njit(cache=True)
def _twin_walks(labels: Array, counts: Array, order: Array, first: Array, starts: Array,
                choices: Array, restarts: Array) -> Array:
    """Twin-surrogate index sequences, shape (K, M), from pre-drawn random numbers.

    Surrogate ``s`` starts at ``starts[s]``; at step ``t`` from state ``k`` it moves on from a
    member of ``k``'s twin class drawn by ``choices[s, t]`` (uniform in [0, 1): the class's
    ``counts`` members listed at ``order[first[label]:]``, ``k`` itself among them) to that
    member's successor, restarting at ``restarts[s, t]`` past the end (Thiel et al. 2006).
    """
    n_sur = starts.size
    m = labels.size
    out = np.empty((n_sur, m), dtype=np.int64)
    for s in range(n_sur):
        k = starts[s]
        for t in range(m):
            out[s, t] = k
            label = labels[k]
            size = counts[label]
            if size > 1:
                k = order[first[label] + min(int(choices[s, t] * size), size - 1)]
            k += 1
            if k >= m:
                k = restarts[s, t]
    return out


@njit(cache=True)
def _index_counts(a_x: Array, a_y: Array, index: Array, theiler: Int) -> tuple[float, float, float]:
    """``(phi, mcr(x|y), mcr(y|x))`` of X's whole matrix against Y read at ``index``.

    As :func:`_window_counts`, over every pair ``u < v``, ``v - u > theiler``: X's states
    ``u, v`` and Y's states ``index[u], index[v]``; a Y-state paired with itself
    (``index[u] == index[v]``, a surrogate revisiting a state) is recurrent. Dense: a twin
    surrogate's recurrences are not a shift of Y's, so there is no sparse list to visit.
    """
    length = index.size
    row_x = np.zeros(length, dtype=np.int64)
    row_y = np.zeros(length, dtype=np.int64)
    row_xy = np.zeros(length, dtype=np.int64)
    n_x = 0
    n_y = 0
    n_xy = 0
    for u in range(length):
        iu = index[u]
        for v in range(u + theiler + 1, length):
            iv = index[v]
            rx = a_x[u, v] != 0
            ry = iu == iv or a_y[iu, iv] != 0
            if rx:
                n_x += 1
                row_x[u] += 1
                row_x[v] += 1
            if ry:
                n_y += 1
                row_y[u] += 1
                row_y[v] += 1
                if rx:
                    n_xy += 1
                    row_xy[u] += 1
                    row_xy[v] += 1
    return _statistics(n_x, n_y, n_xy, row_x, row_y, row_xy, length, theiler)


@njit(cache=True, parallel=True)
def _index_windows(a_x: Array, a_y: Array, indices: Array, theiler: Int) -> Array:
    """:func:`_index_counts` of every row of ``indices``: shape (K, 3)."""
    n = indices.shape[0]
    out = np.empty((n, 3), dtype=np.float64)
    for k in prange(n):
        phi, xy, yx = _index_counts(a_x, a_y, indices[k], theiler)
        out[k, 0] = phi
        out[k, 1] = xy
        out[k, 2] = yx
    return out


@njit(cache=True, parallel=True)
def _repetition_counts(a_y: Array, pairs_x: Array, offsets_x: Array, pairs_y: Array,
                       offsets_y: Array, length: Int, theiler: Int) -> Array:
    """:func:`_window_counts` of X of every repetition against Y of every repetition.

    ``a_y`` stacks Y's dense matrices, shape (R, L, L); ``pairs_x[offsets_x[i]:offsets_x[i +
    1]]`` are the recurrent pairs of X in repetition ``i`` (``pairs_y`` likewise). Returns shape
    (R, R, 3): row ``i``, column ``j`` pairs X of repetition ``i`` with Y of repetition ``j``
    over the whole window.
    """
    r = a_y.shape[0]
    out = np.empty((r, r, 3), dtype=np.float64)
    for k in prange(r * r):
        i = k // r
        j = k % r
        phi, xy, yx = _window_counts(
            a_y[j], pairs_x[offsets_x[i]:offsets_x[i + 1]],
            pairs_y[offsets_y[j]:offsets_y[j + 1]], 0, 0, length, theiler,
        )
        out[i, j, 0] = phi
        out[i, j, 1] = xy
        out[i, j, 2] = yx
    return out


@njit(cache=True, parallel=True)
def _flipped_windows(a_y: Array, pairs_x: Array, pairs_y: Array, starts_x: Array,
                     starts_y: Array, length: Int, theiler: Int, flip_x: bool,
                     flip_y: bool) -> Array:
    """:func:`_windows` of X and Y given by their complements where ``flip_x`` (``flip_y``).

    A flipped signal's ``pairs`` list its candidate pairs that are *not* recurrent (and
    ``a_y`` is Y's complement when ``flip_y``): a signal recurrent almost everywhere (a
    set-point at rest, tied at distance 0) is visited through its few non-recurrent pairs.
    Its counts are the window's candidates less its complement's; the joint counts follow by
    inclusion-exclusion. The same integer counts as :func:`_windows` of the matrices
    themselves, so the same statistics.
    """
    n = starts_x.size
    out = np.empty((n, 3), dtype=np.float64)
    cand = np.empty(length, dtype=np.int64)
    for u in range(length):
        cand[u] = max(0, u - theiler) + max(0, length - 1 - u - theiler)
    total = cand.sum() // 2
    for k in prange(n):
        n_a, n_b, n_ab, row_a, row_b, row_ab = _scan(a_y, pairs_x, pairs_y, starts_x[k],
                                                     starts_y[k], length, theiler)
        row_x = cand - row_a if flip_x else row_a
        row_y = cand - row_b if flip_y else row_b
        n_x = total - n_a if flip_x else n_a
        n_y = total - n_b if flip_y else n_b
        if flip_x and flip_y:
            row_xy = cand - row_a - row_b + row_ab
            n_xy = total - n_a - n_b + n_ab
        elif flip_x:
            row_xy = row_b - row_ab
            n_xy = n_b - n_ab
        elif flip_y:
            row_xy = row_a - row_ab
            n_xy = n_a - n_ab
        else:
            row_xy = row_ab
            n_xy = n_ab
        phi, xy, yx = _statistics(n_x, n_y, n_xy, row_x, row_y, row_xy, length, theiler)
        out[k, 0] = phi
        out[k, 1] = xy
        out[k, 2] = yx
    return out
