"""Benchmark: `funcnet inspect` on a simulated one-hour recording of six axes (bounded memory).

Run from the repository root::

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks.bench_hour [--minutes M] [--keep FILE.mat] \
        [--profile OUT]

The recording: each of six simulated axes (:func:`funcnet.sim.axis.simulate_trial`, the model
axis of ``funcnet simulate``) runs a work cycle every ``CYCLE`` s for an hour: one move out
and back (its own speed, step and TCP distance per axis, each cycle its own noise seed),
then rests until the next cycle (``--minutes`` makes it shorter, a whole number of
cycles, to see what grows with the length). The rest after a trial's own settling is filled by the
axis at rest: the set-point held, every measured signal its trial's last value plus Gaussian
noise of the spread of its trial's last second. The 2 ms log is kept every other sample
(4 ms, 250 Hz, the KUKA KR 300 runs' rate: 900,000 samples per signal) and written as a
MATLAB file in the KUKA layout (struct ``rec``, every signal six axes x samples), read with
``examples/kuka-kr300-channels.toml`` (RP, AP, MP; the current AC where the map reads the
torque). The page is timed as a child process: wall, CPU seconds (user + system) and peak
RSS (``ru_maxrss`` of the child).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: Seconds of one work cycle, and of the recording.
CYCLE = 300.0
HOUR = 3600.0
#: Per axis: speed (deg/min), step (deg), TCP distance (m) of its move out and back.
AXES = ((175, 10, 1.2), (175, -10, 1.6), (350, 10, 2.0), (350, -3, 1.2), (175, 3, 1.6),
        (350, 10, 2.0))
#: Simulated signal -> field of the KUKA layout (the map in examples/).
FIELDS = {"RP": "ref_pos_deg", "AP": "act_pos_se_deg", "MP": "act_pos_mot_deg",
          "AC": "act_torque_abs_nm"}
KEEP_EVERY = 2


def _cycle(axis: int, cycle: int) -> dict[str, np.ndarray]:
    """One work cycle of one axis at the 2 ms log: its trial, then the axis at rest."""
    from funcnet.sim.axis import simulate_trial
    from funcnet.sim.trial import Trial

    speed, step, tcp = AXES[axis]
    trial = Trial(name=f"a{axis + 1}-c{cycle}", group="hour", speed=speed, tcp=tcp, step=step,
                  reverse=True)
    data = simulate_trial(trial, seed=1000 * (axis + 1) + cycle).data
    period = float(data.index[1] - data.index[0])
    total = int(round(CYCLE / period))
    rng = np.random.default_rng(7000 * (axis + 1) + cycle)
    tail = int(round(1.0 / period))
    out = {}
    for name in FIELDS:
        values = data[name].to_numpy()
        rest = np.full(total - values.size, values[-1])
        if name != "RP":
            rest = rest + rng.normal(0.0, values[-tail:].std(), rest.size)
        out[name] = np.concatenate([values, rest])
    return out


def write_hour(path: Path, seconds: float = HOUR) -> Path:
    """Write the six-axis recording (one hour unless told) as a MATLAB file in the KUKA layout."""
    import scipy.io

    cycles = max(1, int(round(seconds / CYCLE)))
    signals: dict[str, list[np.ndarray]] = {name: [] for name in FIELDS}
    for axis in range(len(AXES)):
        parts = [_cycle(axis, c) for c in range(cycles)]
        for name in FIELDS:
            signals[name].append(np.concatenate([p[name] for p in parts])[::KEEP_EVERY])
    n = signals["RP"][0].size
    rec = {FIELDS[name]: np.vstack(rows) for name, rows in signals.items()}
    rec["time_cont"] = np.arange(n) * 0.002 * KEEP_EVERY
    scipy.io.savemat(path, {"rec": rec})
    return path


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--minutes", type=float, default=HOUR / 60,
                        help="length of the recording (whole cycles of 5 min); default 60")
    parser.add_argument("--keep", type=Path, default=None,
                        help="write the recording here (or read it, when it exists)")
    parser.add_argument("--profile", type=Path, default=None, help="cProfile output file")
    parser.add_argument("--no-evidence", action="store_true")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as scratch:
        path = args.keep or Path(scratch) / "hour.mat"
        if not path.exists():
            write_hour(path, 60 * args.minutes)
        environment = dict(os.environ, PYTHONPATH=str(ROOT / "src"),
                           OMP_WAIT_POLICY="PASSIVE")
        prefix = [sys.executable]
        if args.profile is not None:
            prefix += ["-m", "cProfile", "-o", str(args.profile)]
        command = [*prefix, "-m", "funcnet", "inspect", str(path), "--channels",
                   str(ROOT / "examples" / "kuka-kr300-channels.toml"), "--quiet", "-o",
                   str(Path(scratch) / "page"), *(["--no-evidence"] if args.no_evidence else [])]
        start = time.perf_counter()
        subprocess.run(command, check=True, cwd=ROOT, env=environment)
        wall = time.perf_counter() - start
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = usage.ru_utime + usage.ru_stime
    print(f"{args.minutes:g} min, six axes: wall {wall:.1f} s, CPU {cpu:.1f} s, "
          f"peak RSS {usage.ru_maxrss / 1024:.0f} MiB (load {os.getloadavg()[0]:.1f})")


if __name__ == "__main__":
    main()
