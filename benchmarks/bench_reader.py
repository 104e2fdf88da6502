"""Benchmark of the SINUMERIK trace reader: speed on the real trace, memory on a one-hour trace.

Run from the repository root::

    python -m benchmarks.bench_reader [--seconds 3600]

1. The real 45 s trace (``../shared/data/sinumerik/axis7-braking-trace.xml``): the first call in
   a fresh interpreter (imports included: nothing may be compiled on it), then the best of three
   calls in one process. Target: well under 2 s.
2. A generated trace of ``--seconds`` (default one hour: 1.8 million records at 2 ms) with six
   signals under the default SINUMERIK names (four servo signals every 2 ms, two IPO signals
   every 4 ms, as in the real trace), read in a fresh interpreter whose peak resident memory is
   taken from ``resource.getrusage``. Target: under 1 GB.

The competitor, run on both files in the same way: what one writes without funcnet,
``pandas.read_xml(path, xpath="//rec")`` (the whole document as one lxml tree) and a forward
fill. It is not equivalent -- it keeps only the ticks that have a record and knows nothing of
the grids, the metadata or hostile files -- so its figures are a floor for a naive reader.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REAL_TRACE = Path(__file__).resolve().parents[2] / "shared/data/sinumerik/axis7-braking-trace.xml"

# Run in a fresh interpreter: read one trace, report wall and CPU time (the machine may be
# shared) and peak RSS (KiB on Linux).
_CHILD = """
import json, resource, sys, time
start = time.perf_counter()
from funcnet.robot import read_trace
recording = read_trace(sys.argv[1])
seconds = time.perf_counter() - start
usage = resource.getrusage(resource.RUSAGE_SELF)
print(json.dumps({"seconds": seconds, "cpu": usage.ru_utime + usage.ru_stime,
                  "shape": list(recording.data.shape), "max_rss_kib": usage.ru_maxrss}))
"""

# The competitor: the whole document through pandas.read_xml, then a forward fill.
_NAIVE_CHILD = """
import json, resource, sys, time
start = time.perf_counter()
import pandas as pd
data = pd.read_xml(sys.argv[1], xpath="//rec", parser="lxml").set_index("time").ffill()
seconds = time.perf_counter() - start
usage = resource.getrusage(resource.RUSAGE_SELF)
print(json.dumps({"seconds": seconds, "cpu": usage.ru_utime + usage.ru_stime,
                  "shape": list(data.shape), "max_rss_kib": usage.ru_maxrss}))
"""

SERVO = [
    ("nckServoDataCmdPos2ndEnc64", "posn", "double"),
    ("nckServoDataActCurr32", "current", "float"),
    ("nckServoDataCmdCurr32", "current", "float"),
    ("nckServoDataFlwErr64", "posn", "double"),
]
IPO = [("measPos2", "posn", "double"), ("measPos1", "posn", "double")]


def write_long_trace(path: Path, seconds: float, *, seed: int = 0) -> int:
    """Write a SINUMERIK-like trace of ``seconds`` at 2 ms: one record per tick. Returns records."""
    n = int(round(seconds / 0.002)) + 1
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 0.002
    rp = 90.0 * (1 - np.cos(2 * np.pi * t / 60.0))  # back and forth once a minute
    servo = [rp, rng.normal(0, 5, n), rng.normal(0, 5, n), rng.normal(0, 1e-3, n)]
    ipo = [rp - 1e-3, rp + 2e-3]
    signals = [(f"f{i + 1}", name, 0.002, u, d) for i, (name, u, d) in enumerate(SERVO)] + [
        (f"f{i + 5}", name, 0.004, u, d) for i, (name, u, d) in enumerate(IPO)
    ]
    with open(path, "w", encoding="utf-8") as out:
        out.write('<?xml version="1.0" encoding="utf-8" ?>\n<traceSession version="01.00.03.02">\n')
        out.write('<traceCaptureSetup_V20><sampleRateSettings servoSampleRate="0.002"/>')
        out.write('</traceCaptureSetup_V20>\n<traceData dataFrames="1">\n <dataFrame>\n')
        out.write(
            '  <frameHeader startTime="2026-01-01T00:00:00.000Z" '
            f'stopInc="{(n - 1) * 0.002:.6f}"/>\n'
        )
        for key, name, interval, units, dtype in signals:
            out.write(
                f'  <dataSignal id="{key}" interval="{interval:.6f}" name="/Nck/!SD/{name} '
                f'[u1, 1]" unitsType="{units}" dataType="{dtype}"/>\n'
            )
        chunk = 50_000
        for first in range(0, n, chunk):
            lines = []
            for i in range(first, min(first + chunk, n)):
                line = (
                    f'  <rec time="{t[i]:.6f}" f1="{servo[0][i]:.6f}" f2="{servo[1][i]:.6f}" '
                    f'f3="{servo[2][i]:.6f}" f4="{servo[3][i]:.6f}"'
                )
                if i % 2 == 1:  # IPO signals on the odd ticks, as the real controller writes
                    line += f' f5="{ipo[0][i]:.6f}" f6="{ipo[1][i]:.6f}"'
                lines.append(line + "/>\n")
            out.write("".join(lines))
        out.write(" </dataFrame>\n</traceData>\n</traceSession>\n")
    return n


def read_in_child(path: Path, code: str = _CHILD) -> dict:
    result = subprocess.run(
        [sys.executable, "-c", code, str(path)], capture_output=True, text=True, check=True
    )
    return json.loads(result.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3600.0, help="long trace length")
    args = parser.parse_args(argv)

    from funcnet.robot import read_trace

    first = read_in_child(REAL_TRACE)
    timings = []
    for _ in range(3):
        start = time.perf_counter()
        read_trace(REAL_TRACE)
        timings.append(time.perf_counter() - start)
    print(f"real 45 s trace {REAL_TRACE.name}: shape {tuple(first['shape'])}")
    print(
        f"  first call in a fresh interpreter (imports included): {first['seconds']:.3f} s "
        f"(CPU {first['cpu']:.3f} s)"
    )
    print(f"  best of 3 in one process: {min(timings):.3f} s")
    naive = read_in_child(REAL_TRACE, _NAIVE_CHILD)
    print(
        f"  competitor pandas.read_xml + ffill, fresh interpreter: {naive['seconds']:.3f} s, "
        f"shape {tuple(naive['shape'])}; ratio competitor/funcnet "
        f"{naive['seconds'] / first['seconds']:.1f}x"
    )

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "long.xml"
        start = time.perf_counter()
        records = write_long_trace(path, args.seconds)
        written = time.perf_counter() - start
        size_mb = path.stat().st_size / 1e6
        print(
            f"generated {args.seconds:g} s trace: {records} records, 6 signals, "
            f"{size_mb:.0f} MB in {written:.1f} s"
        )
        long = read_in_child(path)
        print(
            f"  read in {long['seconds']:.1f} s (CPU {long['cpu']:.1f} s), "
            f"shape {tuple(long['shape'])}"
        )
        print(f"  peak RSS of the reading process: {long['max_rss_kib'] / 1024:.0f} MiB")
        naive = read_in_child(path, _NAIVE_CHILD)
        print(
            f"  competitor pandas.read_xml + ffill: {naive['seconds']:.1f} s, peak RSS "
            f"{naive['max_rss_kib'] / 1024:.0f} MiB; ratios competitor/funcnet: time "
            f"{naive['seconds'] / long['seconds']:.1f}x, memory "
            f"{naive['max_rss_kib'] / long['max_rss_kib']:.1f}x"
        )


if __name__ == "__main__":
    main()
