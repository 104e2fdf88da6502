"""The direction reading's p-values do not hinge on the BLAS kernel (funcnet.network.direction).

The same readings run in child processes under two or three of OpenBLAS's kernels
(``OPENBLAS_CORETYPE``); a kernel the CPU lacks is skipped (the child reports the architecture
OpenBLAS took, through threadpoolctl). The p-values agree to a relative 1e-6 (measured: 2e-11 on
these windows; up to 4e-7 on windows whose set-point and follower share a level 1e8 times their
noise, where rounding the inputs alone moves a p-value that much), the NaN and within-step flags
and the readings are equal. Against exact rational arithmetic (integer determinants, no
rounding) the p-values of two such pairs agree to a relative 1e-7.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from funcnet.network.direction import prediction_p

TOLERANCE = 1e-6
KERNELS = ("Haswell", "SkylakeX", "Sandybridge")

CHILD = r"""
import json, sys
import numpy as np
from threadpoolctl import threadpool_info
sys.path.insert(0, sys.argv[1])
from test_direction_kernels import readings
found = [info.get("architecture") for info in threadpool_info() if info["user_api"] == "blas"]
print(json.dumps({"architecture": found, "readings": readings()}))
"""


def _trajectory(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    acceleration = np.convolve(rng.standard_normal(n + 60), np.hanning(60), "valid")[:n]
    return np.cumsum(np.cumsum(acceleration))


def _windows() -> list[np.ndarray]:
    """Robot-like windows: a set-point logged to 4 decimals on a level 1e4 times its motion, a
    measured position two samples behind it, a current; and a long follower of a coarse
    set-point (lags of a ramp spanning 3.5e6 with innovations of 0.006)."""
    found = []
    for seed in range(3):
        rng = np.random.default_rng(seed)
        setpoint = _trajectory(160, seed) / 50 + 1e4
        measured = np.concatenate([setpoint[:2], setpoint[:-2]]) + 1e-3 * rng.standard_normal(160)
        current = np.gradient(np.gradient(setpoint)) * 1e3 + 0.3 * rng.standard_normal(160)
        found.append(np.column_stack([np.round(setpoint, 4), measured, current]))
    setpoint = _trajectory(2000, 7)
    follower = setpoint + 0.017 * np.random.default_rng(15).standard_normal(2000)
    found.append(np.column_stack([follower, np.round(setpoint / 1.7) * 1.7]))
    return found


def readings() -> list[dict[str, list[list[float]] | list[list[bool]]]]:
    """p-values and within-step flags of every ordered pair of each window (21 lags, 5 for
    the long pair), as the child prints them."""
    from funcnet.network.direction import DIRECTION_GAP, _p_matrix

    out = []
    for window in _windows():
        lags = 21 if window.shape[0] < 1000 else 5
        found, within = _p_matrix(window, lags, DIRECTION_GAP)
        out.append({"p": np.where(np.isnan(found), -1.0, found).tolist(),
                     "within": within.tolist()})
    return out


def _child(kernel: str) -> dict[str, object] | None:
    env = {**os.environ, "OPENBLAS_CORETYPE": kernel, "OPENBLAS_NUM_THREADS": "1"}
    env["PYTHONPATH"] = os.pathsep.join([str(Path(__file__).parents[1] / "src"),
                                         env.get("PYTHONPATH", "")])
    done = subprocess.run([sys.executable, "-c", CHILD, str(Path(__file__).parent)], env=env,
                          capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        return None
    found = json.loads(done.stdout.strip().splitlines()[-1])
    if {a.lower() for a in found["architecture"]} != {kernel.lower()}:
        return None  # OpenBLAS did not take the kernel (the CPU lacks it)
    return found


def test_p_values_agree_across_blas_kernels():
    found = {kernel: _child(kernel) for kernel in KERNELS}
    ran = {kernel: result for kernel, result in found.items() if result is not None}
    if len(ran) < 2:
        pytest.skip(f"fewer than two OpenBLAS kernels run on this CPU: took {sorted(ran)}")
    (first, reference), *others = ran.items()
    for kernel, result in others:
        for a, b in zip(reference["readings"], result["readings"], strict=True):  # type: ignore
            pa, pb = np.array(a["p"]), np.array(b["p"])
            assert ((pa < 0) == (pb < 0)).all(), (first, kernel)
            assert a["within"] == b["within"], (first, kernel)
            assert pb == pytest.approx(pa, rel=TOLERANCE, abs=1e-300), (first, kernel)
            # the decisions at the pair's level (each way at 0.025) are equal
            assert ((pa <= 0.025) == (pb <= 0.025)).all(), (first, kernel)


def _exact_rss(design: np.ndarray, target: np.ndarray) -> Fraction:
    """The residual sum of squares of least squares on the float values as given, exactly: the
    ratio of the Gram determinants with and without the target (integer Bareiss elimination)."""
    columns = []
    for column in np.column_stack([design, target]).T:
        values = [Fraction(float(v)) for v in column]
        scale = math.lcm(*(v.denominator for v in values))
        columns.append(([int(v * scale) for v in values], scale))
    gram = [[sum(a * b for a, b in zip(x, y, strict=True)) for y, _ in columns]
            for x, _ in columns]
    return Fraction(_determinant(gram), _determinant([row[:-1] for row in gram[:-1]])) / (
        columns[-1][1] ** 2)


def _determinant(matrix: list[list[int]]) -> int:
    """Bareiss fraction-free elimination (a nonsingular Gram matrix: positive pivots)."""
    m = [row[:] for row in matrix]
    previous = 1
    for k in range(len(m) - 1):
        for i in range(k + 1, len(m)):
            for j in range(k + 1, len(m)):
                m[i][j] = (m[i][j] * m[k][k] - m[i][k] * m[k][j]) // previous
        previous = m[k][k]
    return m[-1][-1]


def _exact_p(x: np.ndarray, y: np.ndarray, p: int, gap: int) -> float:
    t = np.arange(p + gap, x.size)
    own = np.column_stack([np.ones(t.size)] + [y[t - k] for k in range(1, p + 1)])
    full = np.column_stack([own] + [x[t - gap - k] for k in range(1, p + 1)])
    restricted, unrestricted = _exact_rss(own, y[t]), _exact_rss(full, y[t])
    dfd = t.size - 2 * p - 1
    return float(stats.f.sf(float((restricted - unrestricted) / p / (unrestricted / dfd)), p,
                            dfd))


def test_p_values_match_exact_arithmetic_on_nearly_collinear_lags():
    """The follower of a coarse set-point (its lags nearly one column) from the set-point, and
    a set-point on a level 1e4 times its motion from its measured position and its current."""
    windows = _windows()
    follower, logged = windows[-1].T
    for x, y, p in ((logged, follower, 5), (logged[:400], follower[:400], 5),
                    (windows[0][:, 1], windows[0][:, 0], 8),
                    (windows[1][:, 2], windows[1][:, 0], 8)):
        exact = _exact_p(x, y, p, 1)
        assert 1e-12 < exact  # 0.87, 0.93, 4.4e-6, 0.027
        assert prediction_p(x, y, p) == pytest.approx(exact, rel=1e-7)
