"""The repetition coupling test (funcnet.evidence.repetitions): brute-force references, exactness,
false positives and power on synthetic and simulated repetitions with known truth, bad input."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import t as student_t

import funcnet
from funcnet.core.embedding import embed
from funcnet.core.normalization import normalize
from funcnet.core.recurrence import auto_recurrence
from funcnet.errors import ParameterError, SignalError
from funcnet.evidence.repetitions import (
    REPETITION_COLUMNS,
    repetition_evidence,
    repetition_tests,
    repetitions_needed,
    smallest_p_value,
)
from funcnet.network import functional_network


def _ar(rng: np.random.Generator, n: int, a: float = 0.9) -> np.ndarray:
    out = np.zeros(n)
    noise = rng.standard_normal(n)
    for k in range(1, n):
        out[k] = a * out[k - 1] + noise[k]
    return out


def _runs(r: int, seed: int, coupling: float, n: int = 200) -> np.ndarray:
    """R runs of (X, Y): a shared command plus own AR(1) noise; Y follows X's noise by
    ``coupling``."""
    rng = np.random.default_rng(seed)
    command = np.sin(np.linspace(0, 3 * np.pi, n)) * 5
    out = []
    for _ in range(r):
        x_noise = _ar(rng, n)
        y = command + coupling * x_noise + _ar(rng, n)
        out.append(np.column_stack([command + x_noise, y]))
    return np.stack(out)


def _brute_phi(a: np.ndarray, b: np.ndarray, theiler: int) -> float:
    """Correlation of two recurrence indicator matrices over i < j, j - i > theiler."""
    i, j = np.triu_indices(a.shape[0], theiler + 1)
    x, y = a[i, j].astype(float), b[i, j].astype(float)
    px, py = x.mean(), y.mean()
    return float(((x * y).mean() - px * py) / math.sqrt(px * (1 - px) * py * (1 - py)))


def _brute_matrices(values: np.ndarray, residuals: bool) -> list[list[np.ndarray]]:
    p = funcnet.NetworkParameters()
    data = values - values.mean(axis=0) if residuals else values
    return [[auto_recurrence(embed(normalize(data[i, :, s]), p.dim, p.delay), rr=p.rr)
             .to_dense() for i in range(data.shape[0])] for s in range(data.shape[2])]


@pytest.mark.parametrize("residuals", [True, False])
def test_statistic_and_p_value_match_brute_force(residuals: bool) -> None:
    values = _runs(5, seed=3, coupling=0.7, n=120)
    found = repetition_tests(values, signals=["x", "y"], residuals=residuals).iloc[0]
    mats = _brute_matrices(values, residuals)
    phi = np.array([[_brute_phi(mats[0][i], mats[1][j], 0) for j in range(5)]
                    for i in range(5)])

    def excess(perm: tuple[int, ...]) -> float:
        same = np.mean([phi[i, perm[i]] for i in range(5)])
        cross = (phi.sum() - 5 * same) / 20
        return float(same - cross)

    observed = excess(tuple(range(5)))
    null = [excess(perm) for perm in itertools.permutations(range(5))][1:]
    assert found.coupling_statistic == pytest.approx(observed, abs=1e-12)
    assert found.surrogates == 119
    assert found.p_value == pytest.approx((1 + sum(v >= observed - 1e-12 for v in null)) / 120)


def test_smallest_p_value_and_repetitions_needed_closed_form() -> None:
    assert [smallest_p_value(r) for r in (2, 3, 4, 5)] == [0.5, 1 / 6, 1 / 24, 1 / 120]
    assert smallest_p_value(12, 999) == 0.001
    # 1/R! <= alpha/m, the first R that does it.
    for m in (1, 3, 6, 7, 10, 36, 37, 210, 253):
        r = repetitions_needed(m)
        assert 1 / math.factorial(r) <= 0.05 / m < 1 / math.factorial(r - 1)


def test_coupled_pair_found_with_random_permutations() -> None:
    coupled = repetition_evidence(_runs(8, seed=1, coupling=0.8), signals=["x", "y"])
    assert coupled.coupled.item() and coupled.evidence.item() in ("coupled", "coupled-directed")
    assert int(coupled.surrogates.item()) == 999  # R > 7: random permutations
    assert coupled.coupling_p.item() == 0.001
    again = repetition_evidence(_runs(8, seed=1, coupling=0.8), signals=["x", "y"], seed=1)
    assert again.coupling_statistic.item() == coupled.coupling_statistic.item()


def test_false_positive_rate_and_power_on_synthetic_repetitions() -> None:
    # Exchangeable under the null: the rate at alpha is at most alpha up to binomial noise
    # (150 independent tests: mean 7.5, sd 2.7; bound at 4 sd).
    rejected = [repetition_tests(_runs(6, seed=s, coupling=0.0, n=100)).p_value.item() <= 0.05
                for s in range(150)]
    assert sum(rejected) <= 18
    power = [repetition_tests(_runs(6, seed=s, coupling=0.6, n=100)).p_value.item() <= 0.05
             for s in range(1000, 1030)]
    assert sum(power) >= 27


def test_untestable_with_too_few_repetitions_says_how_many_are_needed() -> None:
    three = repetition_evidence(_runs(3, seed=0, coupling=1.0), signals=["x", "y"])
    assert three.evidence.item() == "untestable"
    assert three.surrogates.item() == 5
    assert "K=5 surrogates: smallest p 0.167 > alpha 0.05" in three.evidence_reason.item()
    assert "R >= 4 for one pair" in three.evidence_reason.item()
    four = repetition_evidence(_runs(4, seed=0, coupling=1.0), signals=["x", "y"])
    assert four.evidence.item() != "untestable"
    assert four.coupling_p.item() >= 1 / 24


def test_a_command_the_same_in_every_repetition_carries_nothing() -> None:
    values = _runs(6, seed=2, coupling=0.5)
    command = np.sin(np.linspace(0, 3 * np.pi, 200)) * 5 + 0.1
    stack = np.concatenate([np.broadcast_to(command[None, :, None], (6, 200, 1)), values],
                           axis=2)
    table = repetition_tests(stack, signals=["RP", "x", "y"])
    assert table.coupling_statistic.tolist()[:2] == [0.0, 0.0]
    assert table.p_value.tolist()[:2] == [1.0, 1.0]
    # On the raw signals too: the same recurrences in every repetition pair alike with Y.
    raw = repetition_tests(stack, signals=["RP", "x", "y"], residuals=False)
    assert abs(raw.coupling_statistic.iloc[0]) < 1e-12
    assert table.coupling_statistic.iloc[2] > 0 and table.p_value.iloc[2] <= 0.05


def test_two_repetitions_residuals_carry_nothing() -> None:
    # With R = 2 each residual is the other's negative: the same recurrences, D = 0.
    two = repetition_tests(_runs(2, seed=0, coupling=1.0), signals=["x", "y"])
    assert two.coupling_statistic.item() == pytest.approx(0.0, abs=1e-12)
    assert two.p_value.item() == 1.0


def test_network_columns_against_each_repetition_s_own_network() -> None:
    rng = np.random.default_rng(5)
    frames = [pd.DataFrame(rng.standard_normal((150, 3)).cumsum(axis=0), columns=["a", "b", "c"])
              for _ in range(6)]
    table = repetition_evidence(frames, mu=0.01)
    assert list(table.columns) == list(REPETITION_COLUMNS)
    assert list(zip(table.x, table.y, strict=True)) == [("a", "b"), ("a", "c"), ("b", "c")]
    nets = [functional_network(frame, mu=0.01).pairs for frame in frames]
    for q, row in table.iterrows():
        c = np.array([net.c_diff.iloc[q] for net in nets])
        half = student_t.ppf(0.975, 5) * c.std(ddof=1) / math.sqrt(6)
        assert row.c_diff_mean == pytest.approx(c.mean(), rel=1e-12)
        assert row.c_diff_low == pytest.approx(c.mean() - half, rel=1e-9)
        assert row.c_diff_high == pytest.approx(c.mean() + half, rel=1e-9)
        t = np.array([net.t_diff.iloc[q] for net in nets])
        assert row.t_diff_mean == pytest.approx(t.mean(), rel=1e-12)
        kinds = pd.Series([net.kind.iloc[q] for net in nets]).value_counts()
        assert row.kind_share == kinds.max() / 6
        assert row.kind in set(kinds[kinds == kinds.max()].index)
    assert (table.repetitions == 6).all() and (table.surrogates == 719).all()
    # The same numbers from arrays and from a selection of columns.
    arrays = repetition_evidence([f.to_numpy() for f in frames], signals=["a", "b", "c"], mu=0.01)
    pd.testing.assert_frame_equal(arrays, table)
    two = repetition_evidence(frames, signals=["c", "a"], mu=0.01)
    assert list(zip(two.x, two.y, strict=True)) == [("c", "a")]


def test_pairs_adjusted_with_benjamini_hochberg() -> None:
    rng = np.random.default_rng(2)
    values = _runs(6, seed=4, coupling=0.8)
    stack = np.concatenate([values, rng.standard_normal((6, 200, 1))], axis=2)
    raw = repetition_tests(stack, signals=["x", "y", "z"])
    table = repetition_evidence(stack, signals=["x", "y", "z"])
    p = raw.p_value.to_numpy()
    order = np.argsort(p)
    adjusted = np.minimum.accumulate((p[order] * 3 / np.arange(1, 4))[::-1])[::-1]
    expected = np.empty(3)
    expected[order] = np.minimum(adjusted, 1)
    np.testing.assert_allclose(table.coupling_p, expected)


def test_bad_input_is_named() -> None:
    values = _runs(4, seed=0, coupling=0.0)
    with pytest.raises(ParameterError, match="at least 2"):
        repetition_evidence(values[:1])
    with pytest.raises(SignalError, match="one shape"):
        repetition_evidence([values[0], values[1][:-1]])
    bad = values.copy()
    bad[2, 7, 1] = np.nan
    with pytest.raises(SignalError, match="repetition 2: signal y is not finite"):
        repetition_evidence(bad, signals=["x", "y"])
    frames = [pd.DataFrame(v, columns=["x", "y"]) for v in values]
    with pytest.raises(SignalError, match="no signal.*z"):
        repetition_evidence(frames, signals=["x", "z"])
    with pytest.raises(ParameterError, match="mixes"):
        repetition_evidence([frames[0], values[1]])
    with pytest.raises(ParameterError, match="alpha"):
        repetition_evidence(values, alpha=1.5)
    with pytest.raises(ParameterError, match="surrogates"):
        repetition_evidence(values, surrogates=0)
    with pytest.raises(ParameterError, match="mu"):
        repetition_evidence(values, mu=-1.0)


def test_exported_at_the_top_level() -> None:
    assert funcnet.repetition_evidence is repetition_evidence


def test_false_positives_and_power_on_simulated_repetitions() -> None:
    # docs/validation/evidence.md, "Repetitions", on a fixed small seed set: 40 runs of one move
    # (175 deg/min, the real trace's sensors), a 300-sample cruise window logged every 4 ms; 8 draws
    # of R = 10 runs for set A and 10 others for set B. Null: X from A_i, Y from B_i (16 pairs
    # a draw); coupled: RC-AC, AC-MP, MP-AP within A and within B. The validation's cells
    # (1280 tests each) spread 0.03-0.07 around 0.05; tests of one draw share their runs, so
    # the bound allows three standard errors of 8 draws (0.04): at most 21 of 128.
    from funcnet.sim import Trial, simulate_trial

    trial = Trial("validate", "repetitions", speed=175, tcp=1.6, step=10.0, sensors="real")
    columns = ["AP", "MP", "RC", "AC"]
    runs = [simulate_trial(trial, seed=s).data[columns].to_numpy()[::2][445:745]
            for s in range(1, 41)]
    rng = np.random.default_rng(0)
    names = [f"A.{c}" for c in columns] + [f"B.{c}" for c in columns]
    null, links = [], {("RC", "AC"): 0, ("AC", "MP"): 0, ("MP", "AP"): 0}
    for _ in range(8):
        chosen = rng.choice(40, size=20, replace=False)
        stack = np.stack([np.hstack([runs[chosen[i]], runs[chosen[10 + i]]]) for i in range(10)])
        tests = repetition_tests(stack, signals=names, seed=int(rng.integers(1000)))
        rejected = {(x, y): p <= 0.05 for x, y, p in zip(tests.x, tests.y, tests.p_value,
                                                         strict=True)}
        null += [v for (x, y), v in rejected.items() if x[0] != y[0]]
        for u, v in links:
            for side in "AB":
                key = tuple(sorted((f"{side}.{u}", f"{side}.{v}"), key=names.index))
                links[(u, v)] += rejected[key]
    assert len(null) == 128 and sum(null) <= 21
    assert links[("RC", "AC")] >= 15  # of 16 (the validation: 160 of 160)
    assert links[("AC", "MP")] >= 14 and links[("MP", "AP")] >= 14
