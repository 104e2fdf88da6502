"""Long windows: the blocked triangle kernel, heavy ties, the cost forecast.

The blocked kernel must count exactly what the row-wise kernel counts (integers, any order);
a signal that rests for a third of the window (tens of millions of pairs at distance 0 in a
real trace) must get its exact threshold without collecting the tied band; the forecast of
:func:`funcnet.core.recurrence.estimate_cost` is checked for its closed form, its monotonicity and,
in a fresh interpreter, against the memory one network really takes. No timing here: speed
belongs in ``benchmarks/bench_long.py``.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import funcnet.core.measures as measures
import funcnet.core.thresholds as order_statistic
from funcnet.core._isrn_kernels import (
    _cross_triangles,
    _cross_triangles_both,
    _pack_rows,
    _transpose_packed,
)
from funcnet.core.measures import cross_measures, isrn_measures
from funcnet.core.recurrence import (
    CostEstimate,
    PackedRecurrence,
    auto_recurrence,
    cross_recurrence,
    estimate_cost,
)
from funcnet.errors import ParameterError
from funcnet.parameters import NetworkParameters
from test_recurrence import make_signal, reference_auto, reference_cross, reference_embed

ROOT = Path(__file__).resolve().parents[1]


def packed(dense: np.ndarray) -> np.ndarray:
    """Bit-pack a dense boolean matrix as the kernels do (bit j of row i: word j // 64)."""
    n_rows, n_cols = dense.shape
    words = np.zeros((n_rows, (n_cols + 63) // 64), dtype=np.uint64)
    for j in range(n_cols):
        words[:, j >> 6] |= dense[:, j].astype(np.uint64) << np.uint64(j & 63)
    return words


def reference_triangles(cross: np.ndarray, auto: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(k_v, tri_v)`` by integer matrix products (Eq. 6-7 literally)."""
    c = cross.astype(np.int64)
    return c.sum(axis=1), ((c @ auto.astype(np.int64)) * c).sum(axis=1)


def random_isrn(rng: np.random.Generator, m_x: int, m_y: int, density: float):
    """Random symmetric A_X, A_Y (no self-loops) and CR_XY, dense; some rows left empty."""
    blocks = []
    for m in (m_x, m_y):
        upper = np.triu(rng.random((m, m)) < density, 1)
        blocks.append(upper | upper.T)
    cross = rng.random((m_x, m_y)) < density
    cross[rng.integers(0, m_x, size=max(1, m_x // 10))] = False
    return blocks[0], blocks[1], cross


# ----------------------------------------------------------------------------------------------
# the blocked kernel counts what the row-wise kernel counts


@settings(max_examples=40, deadline=None)
@given(
    m_x=st.integers(1, 300),
    m_y=st.integers(1, 300),
    density=st.sampled_from([0.02, 0.1, 0.5, 1.0]),
    block_words=st.sampled_from([1, 2, 3, 4, 8]),
    threads=st.integers(1, 3),
    seed=st.integers(0, 2**32 - 1),
)
def test_blocked_kernel_equals_row_wise_and_brute_force(
    m_x, m_y, density, block_words, threads, seed
):
    a_x, a_y, cross = random_isrn(np.random.default_rng(seed), m_x, m_y, density)
    cr_xy, cr_yx = packed(cross), packed(cross.T.copy())
    k_xy, tri_xy, k_yx, tri_yx = _cross_triangles_both(
        cr_xy, cr_yx, packed(a_x), packed(a_y), block_words, threads
    )
    row_xy, row_yx = _cross_triangles(cr_xy, packed(a_y)), _cross_triangles(cr_yx, packed(a_x))
    for got, want in zip((k_xy, tri_xy, k_yx, tri_yx), (*row_xy, *row_yx), strict=True):
        np.testing.assert_array_equal(got, want)
    np.testing.assert_array_equal(tri_xy, reference_triangles(cross, a_y)[1])
    np.testing.assert_array_equal(tri_yx, reference_triangles(cross.T, a_x)[1])


@pytest.mark.parametrize("n", [63, 64, 65, 127, 128, 129])
def test_blocked_kernel_at_word_edges(n):
    # Neighbours at bit 63 of a word, rows ending exactly at a word boundary.
    a_x, a_y, cross = random_isrn(np.random.default_rng(n), n, n + 1, 0.3)
    cross[:, 63 % (n + 1)] = True
    cr_xy, cr_yx = packed(cross), packed(cross.T.copy())
    counts = _cross_triangles_both(cr_xy, cr_yx, packed(a_x), packed(a_y), 1, 2)
    expected = (*_cross_triangles(cr_xy, packed(a_y)), *_cross_triangles(cr_yx, packed(a_x)))
    for got, want in zip(counts, expected, strict=True):
        np.testing.assert_array_equal(got, want)


def reference_values(xs, ys, rate):
    """C and T of both directions from dense brute-force structures (test_measures' rule)."""
    a_x, _ = reference_auto(xs, rr=rate)
    a_y, _ = reference_auto(ys, rr=rate)
    cross, _ = reference_cross(xs, ys, cr=rate)
    values = []
    for c, a in ((cross, a_y), (cross.T, a_x)):
        degree, triangles = reference_triangles(c, a)
        pairs = degree * (degree - 1)
        local = np.zeros(degree.size)
        np.divide(triangles, pairs, out=local, where=pairs > 0)
        values += [float(local.mean()), int(triangles.sum()) / pairs.sum() if pairs.sum() else 0.0]
    return values


@pytest.mark.parametrize("blocked", [True, False])
@pytest.mark.parametrize("kinds", [("sine", "walk"), ("quantized", "noise")])
def test_measures_through_the_blocked_kernel_equal_brute_force(monkeypatch, kinds, blocked):
    # The blocked kernel serves long windows only: force it here, on a size brute force affords.
    if blocked:
        monkeypatch.setattr(measures, "_BLOCKED_BYTES", 0)
    x, y = make_signal(kinds[0], 700, 1), make_signal(kinds[1], 700, 2)
    xs, ys = reference_embed(x, 3, 4), reference_embed(y, 3, 4)
    result = cross_measures(x, y, dim=3, delay=4, warn=False)
    c_xy, t_xy, c_yx, t_yx = reference_values(xs, ys, 0.05)
    assert (result.c_xy, result.t_xy, result.c_yx, result.t_yx) == (c_xy, t_xy, c_yx, t_yx)


# ----------------------------------------------------------------------------------------------
# heavy ties: the order statistic by counting, never by collecting the tied band


def resting(n, seed, share=0.4):
    """A ramp that rests (exactly constant) over ``share`` of the samples, then moves."""
    rng = np.random.default_rng(seed)
    rest = int(share * n)
    return np.concatenate([np.zeros(rest), np.cumsum(rng.random(n - rest))])


def no_collect(*args):
    raise AssertionError("the tied band must not be collected")


@pytest.mark.parametrize("metric", ["euclidean", "supremum"])
@pytest.mark.parametrize("rule", ["funcnet", "pyunicorn"])
def test_a_resting_signal_gets_its_exact_threshold_without_the_band(monkeypatch, metric, rule):
    monkeypatch.setattr(order_statistic, "_collect_band", no_collect)
    xs = reference_embed(resting(900, 1), 3, 2)
    assert xs.shape[0] ** 2 // 2 > order_statistic._DIRECT_PAIRS
    expected, eps = reference_auto(xs, rr=0.05, metric=metric, rule=rule)
    result = auto_recurrence(xs, rr=0.05, metric=metric, rule=rule)
    assert result.eps == eps == 0.0
    np.testing.assert_array_equal(result.to_dense(), expected)


@pytest.mark.parametrize("limit", [1000, 20_000])
@pytest.mark.parametrize("kind", ["levels", "quantized", "resting"])
def test_counting_passes_find_ties_inside_a_large_band(monkeypatch, kind, limit):
    # A tiny band limit and no room in the buffers: the band is narrowed by counting passes,
    # wherever the tied value lies (at an end of the sampled bracket or inside it).
    monkeypatch.setattr(order_statistic, "_BAND_LIMIT", limit)
    monkeypatch.setattr(order_statistic, "_BAND_SLACK", 0.0)
    x = resting(820, 3) if kind == "resting" else make_signal(kind, 820, 3)
    y = make_signal("walk", 820, 4)
    xs, ys = reference_embed(x, 2, 3), reference_embed(y, 2, 3)
    for rate in (0.05, 0.3):
        expected, eps = reference_auto(xs, rr=rate, theiler=1)
        result = auto_recurrence(xs, rr=rate, theiler=1)
        assert result.eps == eps
        np.testing.assert_array_equal(result.to_dense(), expected)
        expected, eps = reference_cross(xs, ys, cr=rate)
        result = cross_recurrence(xs, ys, cr=rate)
        assert result.eps == eps
        np.testing.assert_array_equal(result.to_dense(), expected)


@pytest.mark.parametrize("probes", [(), (0.0,), (0.5, 0.0)])
def test_narrow_meets_a_tied_order_statistic(monkeypatch, probes):
    monkeypatch.setattr(order_statistic, "_BAND_LIMIT", 100)
    xs = reference_embed(resting(400, 5), 2, 1)
    bt = np.ascontiguousarray(xs.T)
    keys = np.sort(((xs[:, None, :] - xs[None, :, :]) ** 2).sum(axis=2).ravel())
    rank = int(0.1 * keys.size)
    assert keys[rank - 1] == 0.0  # tied: the diagonal and the resting states
    bits = order_statistic._key_bits
    lo, hi, exact = order_statistic._narrow(
        xs, bt, False, 0, 0, rank, -1, 0, bits(1.0), int((keys <= 1.0).sum()), probes
    )
    assert exact and lo == hi == 0.0
    rank = int(0.7 * keys.size)  # untied: a band of at most 100 keys, or the value itself
    lo, hi, exact = order_statistic._narrow(
        xs, bt, False, 0, 0, rank, -1, 0, bits(keys[-1]), keys.size, probes
    )
    if exact:
        assert lo == hi == keys[rank - 1]
    else:
        assert lo <= keys[rank - 1] <= hi
        assert ((keys >= lo) & (keys <= hi)).sum() <= 100


def test_packing_is_unchanged_by_the_blocked_path(monkeypatch):
    # isrn_measures on precomputed blocks, blocked kernel forced, equals the row-wise counts.
    monkeypatch.setattr(measures, "_BLOCKED_BYTES", 0)
    x, y = make_signal("sine", 900, 7), make_signal("quantized", 900, 8)
    xs, ys = reference_embed(x, 3, 5), reference_embed(y, 3, 5)
    a_x, a_y = auto_recurrence(xs, rr=0.05), auto_recurrence(ys, rr=0.05)
    cr_xy = cross_recurrence(xs, ys, cr=0.05)
    result = isrn_measures(a_x, a_y, cr_xy)
    degree, triangles = _cross_triangles(cr_xy.rows, a_y.rows)
    pairs = degree * (degree - 1)
    assert result.t_xy == int(triangles.sum()) / int(pairs.sum())
    bound = order_statistic._key_bound(cr_xy.eps, False, 0)
    rows, count = _pack_rows(xs, np.ascontiguousarray(ys.T), False, 0, 0, bound)
    np.testing.assert_array_equal(rows, cr_xy.rows)
    assert count == cr_xy.n_recurrent
    np.testing.assert_array_equal(
        _transpose_packed(cr_xy.rows, cr_xy.n_cols), cr_xy.transposed().rows
    )
    assert isinstance(cr_xy, PackedRecurrence)


# ----------------------------------------------------------------------------------------------
# the forecast


def test_estimate_closed_form():
    cost = estimate_cost(22_706, 5, threads=2)
    m = 22_706 - 2 * 10
    packed_bytes = m * math.ceil(m / 64) * 8
    assert isinstance(cost, CostEstimate)
    assert (cost.n_states, cost.n_pairs, cost.threads) == (m, 10, 2)
    assert cost.held_bytes == 5 * packed_bytes
    assert cost.pair_bytes >= 2 * packed_bytes
    assert cost.bytes > cost.held_bytes + cost.pair_bytes
    assert cost.seconds == pytest.approx(cost.cpu_seconds / 2)
    assert "M = 22,686 states" in str(cost)
    # Parameters shape M, and the triangle term follows cr.
    p = NetworkParameters(dim=4, delay=5, cr=0.1)
    assert estimate_cost(1000, 2, p).n_states == 985
    assert estimate_cost(1000, 2, dim=4, delay=5, cr=0.1) == estimate_cost(1000, 2, p)


def test_estimate_is_monotone():
    sizes = [200, 1000, 5000, 20_000, 50_000]
    for field in ("seconds", "cpu_seconds", "bytes", "held_bytes"):
        by_size = [getattr(estimate_cost(n, 3, threads=2), field) for n in sizes]
        assert by_size == sorted(by_size) and by_size[0] < by_size[-1], field
        by_count = [getattr(estimate_cost(10_000, k, threads=2), field) for k in range(2, 8)]
        assert by_count == sorted(by_count) and by_count[0] < by_count[-1], field
    by_rate = [estimate_cost(10_000, 3, cr=cr).cpu_seconds for cr in (0.01, 0.05, 0.2)]
    assert by_rate == sorted(by_rate)
    assert estimate_cost(10_000, 3, threads=1).seconds > estimate_cost(10_000, 3, threads=2).seconds


@pytest.mark.parametrize(
    "args, kwargs, word",
    [
        ((10, 5), {}, "n_samples"),  # shorter than the embedding
        ((0, 5), {}, "n_samples"),
        ((1000, 1), {}, "n_signals"),
        ((1000.5, 2), {}, "n_samples"),
        ((1000, 2), {"threads": 0}, "threads"),
        ((1000, 2), {"mu": 0.1}, "mu"),
    ],
)
def test_estimate_rejects_bad_input(args, kwargs, word):
    with pytest.raises(ParameterError, match=word):
        estimate_cost(*args, **kwargs)


CHILD = textwrap.dedent(
    """
    import json, warnings
    import numpy as np
    from funcnet.core.measures import pairwise_cross_measures
    from funcnet.core.recurrence import estimate_cost

    def status(key):
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(key):
                    return int(line.split()[1]) * 1024

    warnings.simplefilter("ignore")
    rng = np.random.default_rng(0)
    n = 12_000
    t = np.arange(n)
    signals = [np.sin(0.01 * t) + 0.1 * rng.normal(size=n), np.cumsum(rng.normal(size=n)),
               np.round(np.cumsum(rng.normal(size=n)))]
    pairwise_cross_measures([s[:900] for s in signals])  # load the kernels
    before = status("VmRSS:")
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")  # reset the high-water mark to the current size
    pairwise_cross_measures(signals)
    cost = estimate_cost(n, len(signals))
    print(json.dumps({"used": status("VmHWM:") - before,
                      "model": cost.held_bytes + cost.pair_bytes}))
    """
)


@pytest.mark.skipif(not os.path.exists("/proc/self/clear_refs"), reason="Linux /proc only")
def test_estimated_memory_is_within_a_factor_of_what_one_network_takes():
    # 3 signals of 12,000 samples: 17 MiB per packed matrix; peak resident memory of a fresh
    # interpreter above its size after warm-up, against held + one pair's transient.
    output = subprocess.run(
        [sys.executable, "-c", CHILD], check=True, capture_output=True, text=True, cwd=ROOT,
        env={**os.environ, "OMP_WAIT_POLICY": "PASSIVE"},
    ).stdout
    report = json.loads(output.strip().splitlines()[-1])
    assert report["model"] / 3 <= report["used"] <= 3 * report["model"], report
