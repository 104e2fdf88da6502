"""Write ``ur5-rtde-sample.csv``: a small log of the shape of UR's RTDE recorder.

The first line names the columns (``timestamp target_q_0 ... actual_current_5``), blanks
separate them, 125 Hz. The motion is made up: every joint goes out and back once (a cosine
profile, one direction change at the middle), the measured position lags the set-point by two
samples with a little noise, the currents follow the acceleration and the friction's sign.
Run ``python tests/data/make_ur5_rtde_sample.py`` to write it again (seeded: the same file).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

FIELDS = ("target_q", "target_qd", "target_qdd", "target_current", "target_moment",
          "actual_q", "actual_qd", "actual_current")


def sample(n: int = 150, period: float = 0.008, start: float = 1234.5) -> str:
    rng = np.random.default_rng(7)
    t = np.arange(n) * period
    span = t[-1]
    columns: dict[str, list[np.ndarray]] = {name: [] for name in FIELDS}
    for joint in range(6):
        amplitude = 0.3 + 0.1 * joint
        q = 0.5 * joint + amplitude * (1 - np.cos(2 * np.pi * t / span)) / 2
        qd = amplitude * np.pi / span * np.sin(2 * np.pi * t / span)
        qdd = amplitude * 2 * np.pi**2 / span**2 * np.cos(2 * np.pi * t / span)
        current = 0.8 * qdd + 0.3 * np.tanh(qd / 0.02)
        actual = np.concatenate([q[:1], q[:1], q[:-2]]) + rng.normal(0, 2e-5, n)
        columns["target_q"].append(q)
        columns["target_qd"].append(qd)
        columns["target_qdd"].append(qdd)
        columns["target_current"].append(current)
        columns["target_moment"].append(5.0 * current)
        columns["actual_q"].append(actual)
        columns["actual_qd"].append(np.gradient(actual, period))
        columns["actual_current"].append(current + rng.normal(0, 0.01, n))
    names = ["timestamp"] + [f"{name}_{j}" for name in FIELDS for j in range(6)]
    table = np.column_stack([start + t] + [c for name in FIELDS for c in columns[name]])
    rows = [" ".join(f"{v:.6f}" for v in row) for row in table]
    return " ".join(names) + "\n" + "\n".join(rows) + "\n"


if __name__ == "__main__":
    Path(__file__).with_name("ur5-rtde-sample.csv").write_text(sample(), encoding="utf-8")
