"""Speed of ``compare_runs``: a 30 s six-joint run against two references (target <= 60 s).

A simulated program of six joints repeating every 6.4 s, logged at 125 Hz as a UR5 logs it
(RP, AP, RC, AC per joint): RUN 30 s, references 16 s and 22 s starting elsewhere in the
program. Timed (median of 3 after a warm-up that compiles the kernels): :func:`compare_runs`
with the networks' reading (what ``funcnet compare`` computes) and without it. In the same
process the competitor: what an engineer writes in pandas without funcnet -- one global lag
per reference from the cross-correlation of the set-points, then ``|AC - RC|`` of RUN minus
the references' mean at that lag -- which finds no local slow-down, no extra cycle, and no
band. When the UR5 folders are there (``FUNCNET_UR5``, default data/ur5), the
force-sensor run against No8 and No9 NoDist is timed too, reading included.

    PYTHONPATH=src python -m benchmarks.bench_compare
"""

from __future__ import annotations

import os
import platform
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from benchmarks.bench_core import timed
from funcnet.comparison import compare_runs
from funcnet.robot.recording import Recording, SignalInfo

PERIOD = 0.008
CYCLE = 6.4


def simulated(seed: int, start: float, seconds: float) -> Recording:
    rng = np.random.default_rng(seed)
    t = np.arange(int(round(seconds / PERIOD))) * PERIOD
    phase = 2 * np.pi * (start + t) / CYCLE
    columns = {}
    for axis in range(1, 7):
        rp = 0.8 * np.sin(phase + axis) + 0.3 * np.sin(2 * phase + 0.5 * axis)
        speed = np.gradient(rp, PERIOD)
        rc = 0.5 * np.gradient(speed, PERIOD) + 0.8 * np.tanh(speed / 0.05) + 0.3 * axis
        columns.update({f"A{axis}.RP": rp, f"A{axis}.AP": rp - 0.002 * speed
                        + rng.normal(0, 1e-4, t.size), f"A{axis}.RC": rc,
                        f"A{axis}.AC": rc + rng.normal(0, 0.1, t.size)})
    data = pd.DataFrame(columns, index=pd.Index(np.round(t, 9), name="time"))
    units = {"RP": "rad", "AP": "rad", "RC": "A", "AC": "A"}
    return Recording(data, {c: c for c in data},
                     {c: SignalInfo(c, None, None, PERIOD, units[c[3:]]) for c in data},
                     source=f"sim{seed}", sample_period=PERIOD)


def competitor(run: Recording, refs: list[Recording]) -> np.ndarray:
    """One global lag per reference (set-point cross-correlation), then |AC - RC| differences."""
    def cols(r: Recording, role: str) -> np.ndarray:
        return r.data[[f"A{a}.{role}" for a in range(1, 7)]].to_numpy()

    x = cols(run, "RP") - cols(run, "RP").mean(axis=0)
    residual = np.abs(cols(run, "AC") - cols(run, "RC"))
    others = []
    for ref in refs:
        y = cols(ref, "RP") - cols(ref, "RP").mean(axis=0)
        corr = sum(np.correlate(x[:, j], y[:, j], mode="full") for j in range(6))
        lag = int(np.argmax(corr)) - (len(y) - 1)
        shifted = np.full_like(residual, np.nan)
        ref_res = np.abs(cols(ref, "AC") - cols(ref, "RC"))
        lo, hi = max(lag, 0), min(len(x), len(y) + lag)
        shifted[lo:hi] = ref_res[lo - lag:hi - lag]
        others.append(shifted)
    with warnings.catch_warnings():  # ticks no reference covers: NaN, as the engineer's would
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nansum(np.abs(residual - np.nanmean(others, axis=0))[:, :3], axis=1)



def main() -> None:
    run = simulated(3, 1.1, 30.0)
    refs = [simulated(1, 0.0, 16.0), simulated(2, 2.5, 22.0)]
    compare_runs(run, refs)  # warm-up: compiles the kernels
    full, full_best, _, _ = timed(lambda: compare_runs(run, refs), 3)
    plain, _, _, _ = timed(lambda: compare_runs(run, refs, networks=False), 3)
    rival, _, _, _ = timed(lambda: competitor(run, refs), 3)
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load {os.getloadavg()[0]:.1f}")
    print(f"compare_runs, 30 s x 6 joints vs 2 references, with networks: median {full:.2f} s "
          f"(best {full_best:.2f} s); target <= 60 s: {'met' if full <= 60 else 'NOT met'}")
    print(f"  residuals only: {plain:.2f} s; competitor (global lag + |AC - RC|, pandas): "
          f"{rival:.3f} s; ratio with networks {full / rival:.0f}x, residuals only "
          f"{plain / rival:.0f}x")
    folder = Path(os.environ.get("FUNCNET_UR5", Path(__file__).parents[1] / "data/ur5"))
    channels = Path(__file__).parents[1] / "examples/ur5-channels.toml"
    if (folder / "Movement_No9_Singularity_Free_ForceSensor").is_dir():
        from funcnet.robot.io.read import read_trace

        def real() -> None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                names = ["Movement_No9_Singularity_Free_ForceSensor",
                         "Movement_No8_Singularity_Free_1", "Movement_No9_Singularity_Free_NoDist"]
                recs = [read_trace(folder / n, channels=channels) for n in names]
            compare_runs(recs[0], recs[1:])

        median, best, _, _ = timed(real, 3)
        print(f"UR5 No9 ForceSensor (34.4 s) vs No8 and No9 NoDist, reading included: median "
              f"{median:.2f} s (best {best:.2f} s)")


if __name__ == "__main__":
    main()
