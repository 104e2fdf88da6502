"""The shift lattice's window kernel: counts by popcounts of packed rows against brute force and
against the scan of every listed pair it replaced (the same numbers, bit for bit), and the
recurrent pairs of a matrix against NumPy."""

from __future__ import annotations

import numpy as np
import pytest

from funcnet.core.embedding import embed
from funcnet.core.recurrence import auto_recurrence
from funcnet.errors import ParameterError
from funcnet.evidence import dependence_test, shift_plan
from funcnet.evidence._kernels import _window_counts, _windows
from funcnet.evidence.dependence import recurrent_pairs, shift_bits, shift_test
from funcnet.validation import systems


def dense(states):
    return auto_recurrence(states, rr=0.05).to_dense().astype(np.uint8)


def brute(a_x, a_y, start_x, start_y, length, theiler):
    """``(phi, mcr(x|y), mcr(y|x))`` of one window from the dense matrices, written out."""
    x = np.triu(a_x[start_x:start_x + length, start_x:start_x + length], theiler + 1) > 0
    y = np.triu(a_y[start_y:start_y + length, start_y:start_y + length], theiler + 1) > 0
    xy = x & y
    row_x, row_y, row_xy = (m.sum(0) + m.sum(1) for m in (x, y, xy))
    gap = min(theiler + 1, length)
    n_pairs = (length - gap) * (length - gap + 1) // 2
    px, py = x.sum() / n_pairs, y.sum() / n_pairs
    phi = (xy.sum() / n_pairs - px * py) / np.sqrt(px * (1 - px) * py * (1 - py))
    x_given_y = np.mean(row_xy[row_y > 0] / row_y[row_y > 0])
    y_given_x = np.mean(row_xy[row_x > 0] / row_x[row_x > 0])
    return phi, x_given_y, y_given_x


def scanned(a_y, pairs_x, pairs_y, starts_x, starts_y, length, theiler):
    """The previous kernel: every window visits every listed pair."""
    return np.array([_window_counts(a_y, pairs_x, pairs_y, sx, sy, length, theiler)
                     for sx, sy in zip(starts_x, starts_y, strict=True)])


def pair_matrices(n, seed):
    data = systems.henon_pair(n, 0.4, seed=seed)
    return dense(embed(data[:, 0], 3, 1)), dense(embed(data[:, 1], 3, 1))


@pytest.mark.parametrize("theiler", [0, 1, 5])
def test_packed_windows_equal_the_scan_bit_for_bit_and_brute_force(theiler):
    a_x, a_y = pair_matrices(700, seed=1)
    pairs_x, pairs_y = recurrent_pairs(a_x), recurrent_pairs(a_y)
    m = a_x.shape[0]
    # bit offsets 0, 63, 64, 65 and others; lengths below, at and above a multiple of 64
    starts_x = np.array([0, 63, 64, 65, 130, 7, 200, 311], dtype=np.int64)
    starts_y = np.array([64, 0, 129, 3, 1, 250, 200, 5], dtype=np.int64)
    for length in (127, 128, 129, 380):
        keep = np.maximum(starts_x, starts_y) + length <= m
        sx, sy = starts_x[keep], starts_y[keep]
        got = _windows(a_y, pairs_x, pairs_y, sx, sy, length, theiler)
        old = scanned(a_y, pairs_x, pairs_y, sx, sy, length, theiler)
        assert np.array_equal(got.view(np.int64), old.view(np.int64))
        for k in range(sx.size):
            np.testing.assert_allclose(got[k], brute(a_x, a_y, sx[k], sy[k], length, theiler),
                                       rtol=1e-12, atol=1e-15)


def test_unsorted_or_repeated_pairs_are_scanned():
    a_x, a_y = pair_matrices(400, seed=2)
    pairs_x, pairs_y = recurrent_pairs(a_x), recurrent_pairs(a_y)
    plan = shift_plan(a_x.shape[0], 19, min_shift=5)
    starts = plan.starts_x, plan.starts_y, plan.length, 0
    shuffled = pairs_x[np.random.default_rng(0).permutation(pairs_x.shape[0])]
    want = _windows(a_y, pairs_x, pairs_y, *starts)
    assert np.array_equal(_windows(a_y, shuffled, pairs_y, *starts), want)
    # a repeated pair is counted twice by the scan: the kernel must not pack it away
    doubled = np.vstack([pairs_x[:1], pairs_x])
    assert np.array_equal(_windows(a_y, doubled, pairs_y, *starts),
                          scanned(a_y, doubled, pairs_y, *starts))
    assert not np.array_equal(_windows(a_y, doubled, pairs_y, *starts), want)


def test_a_long_window_test_is_the_scans():
    # a robot-sized window (3,000 states, a lattice of 21 windows of about half of it)
    data = systems.henon_pair(3002, 0.4, seed=3)
    a_x, a_y = (dense(embed(data[:, k], 3, 1)) for k in (0, 1))
    plan = shift_plan(a_x.shape[0], 20, min_shift=70)
    result = dependence_test(a_x, a_y, plan)
    starts_x = np.concatenate([[plan.observed], plan.starts_x])
    starts_y = np.concatenate([[plan.observed], plan.starts_y])
    old = scanned(a_y, recurrent_pairs(a_x), recurrent_pairs(a_y), starts_x, starts_y,
                  plan.length, 0)
    assert result.statistic == old[0, 0]
    assert np.array_equal(result.null_statistics, old[1:, 0])
    assert result.p_value == pytest.approx(1 / 21)  # coupled: the observed window first


@pytest.mark.parametrize("theiler", [0, 2])
def test_the_packed_rows_test_is_the_dense_matrices_test(theiler):
    # a signal's packed rows made into bits once: the bits the kernel makes of its pairs list,
    # and the test's every number (the scan of every listed pair, written out, for the windows)
    data = systems.henon_pair(900, 0.4, seed=5)
    packed = [auto_recurrence(embed(data[:, k], 3, 1), rr=0.05, theiler=theiler)
              for k in (0, 1)]
    a_x, a_y = (a.to_dense().astype(np.uint8) for a in packed)
    bits_x, bits_y = (shift_bits(a.rows) for a in packed)
    plan = shift_plan(a_x.shape[0], 30, min_shift=9)
    got = shift_test(bits_x, bits_y, plan, theiler=theiler)
    want = dependence_test(a_x, a_y, plan, theiler=theiler)
    old = scanned(a_y, recurrent_pairs(a_x), recurrent_pairs(a_y),
                  np.concatenate([[plan.observed], plan.starts_x]),
                  np.concatenate([[plan.observed], plan.starts_y]), plan.length, theiler)
    assert got.statistic == want.statistic == old[0, 0]
    assert np.array_equal(got.null_statistics, old[1:, 0])
    assert (got.p_value, got.direction_index, got.direction_p) == (
        want.p_value, want.direction_index, want.direction_p)
    with pytest.raises(ParameterError, match="bits_y"):
        shift_test(bits_x, bits_y[:, :-1], plan)


@pytest.mark.parametrize("dtype", [np.uint8, bool, np.int64, np.float64])
def test_recurrent_pairs_are_numpys(dtype):
    rng = np.random.default_rng(4)
    for shape in ((0, 0), (1, 1), (37, 37), (20, 45), (45, 20)):
        a = (rng.random(shape) < 0.2).astype(dtype) * (3 if dtype is np.int64 else 1)
        got = recurrent_pairs(a)
        want = np.argwhere(np.triu(a, 1)).astype(np.int64)
        assert got.dtype == np.int64 and got.shape == want.shape
        assert np.array_equal(got, want)
