"""funcnet compare: runs of one simulated program, aligned, compared, a push found."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.comparison import align_on_setpoints, compare_runs, find_intervals, reference_band
from funcnet.comparison.align import Alignment
from funcnet.errors import SignalError
from funcnet.robot.recording import Recording, SignalInfo

PERIOD = 0.01
CYCLE = 2.0  # seconds of one cycle of the simulated program


def _program(t: np.ndarray, axis: int, other: bool = False) -> np.ndarray:
    """Set-point of one axis: a smooth closed path repeated every CYCLE seconds."""
    phase = 2 * np.pi * t / CYCLE
    if other:  # another program: other poses
        return 0.8 + 0.3 * np.sin(phase + axis)
    return 0.5 * np.sin(phase + axis) + 0.2 * np.sin(2 * phase) * axis


def _run(seed: int, *, start: float = 0.0, cycles: float = 4.0, push: tuple | None = None,
         other: bool = False, stretch: tuple | None = None) -> Recording:
    """A run: ``cycles`` of the program from program time ``start``; optional push
    ``(t0, t1, axis, amps)`` on the measured current; optional slow-down
    ``(t0, t1, factor)`` of the program clock."""
    rng = np.random.default_rng(seed)
    n = int(round(cycles * CYCLE / PERIOD))
    t = np.arange(n) * PERIOD
    clock = start + t
    if stretch is not None:  # the program's clock runs slower from t0 to t1
        t0, t1, factor = stretch
        clock = start + np.where(t < t0, t, t0 + (np.minimum(t, t1) - t0) * factor
                                 + np.maximum(t - t1, 0))
    columns: dict[str, np.ndarray] = {}
    for axis in (1, 2):
        rp = _program(clock, axis, other)
        speed = np.gradient(rp, PERIOD)
        rc = 2.0 * np.gradient(speed, PERIOD) * 0.05 + 0.5 * np.sign(speed)
        ac = rc + rng.normal(0, 0.05, n)
        if push is not None and push[2] == axis:
            inside = (t >= push[0]) & (t < push[1])
            ac[inside] += push[3]
        ap = rp - 0.002 * speed + rng.normal(0, 1e-4, n)
        columns.update({f"A{axis}.RP": rp, f"A{axis}.AP": ap, f"A{axis}.RC": rc,
                        f"A{axis}.AC": ac})
    data = pd.DataFrame(columns, index=pd.Index(np.round(t, 9), name="time"))
    units = {"RP": "rad", "AP": "rad", "RC": "A", "AC": "A"}
    signals = {c: SignalInfo(c, None, None, PERIOD, units[c.split(".")[1]]) for c in data}
    return Recording(data, {c: c for c in data}, signals, source=f"run{seed}",
                     sample_period=PERIOD)


def _setpoints(rec: Recording) -> np.ndarray:
    return rec.data[["A1.RP", "A2.RP"]].to_numpy()


# ------------------------------------------------------------------------------------ align

def test_alignment_matches_brute_force_offsets() -> None:
    ref, run = _run(1, cycles=3.0), _run(2, start=0.37, cycles=2.0)
    a = align_on_setpoints(_setpoints(run), _setpoints(ref), period=PERIOD, window=1.0,
                           step=0.2)
    assert a.covered.all()
    # brute force for one piece: RMS over every offset, a plain loop
    r, f = _setpoints(run), _setpoints(ref)
    width, first = 100, 60  # the piece [60, 80) is matched with its context [20, 120)
    a0 = 70 - width // 2
    best = []
    for k in range(len(f) - width + 1):
        rms = np.sqrt(np.mean((r[a0:a0 + width] - f[k:k + width]) ** 2))
        best.append(rms)
    best = np.array(best)
    # offsets within tolerance, the smallest of each stretch of them
    ok = best <= a.tolerance
    minima = [k for k in range(len(best)) if ok[k]
              and best[k] == best[max(k - 30, 0):k + 30][ok[max(k - 30, 0):k + 30]].min()]
    expected = sorted(first + k - a0 for k in minima)
    assert a.matches[first][a.matches[first] >= 0].tolist() == expected
    # each match is a cycle of the reference: 37 ticks of start, 200 ticks per cycle
    assert all((m - first - 37) % 200 == 0 for m in expected)


def test_alignment_follows_a_local_slow_down() -> None:
    ref = _run(1, cycles=3.0)
    run = _run(2, cycles=2.5, stretch=(1.5, 2.5, 0.85))  # 15 % slower for 1 s
    a = align_on_setpoints(_setpoints(run), _setpoints(ref), period=PERIOD)
    assert a.covered.mean() > 0.97
    matched = a.matches[:, 0]
    ok = matched >= 0
    diff = np.abs(_setpoints(run)[ok] - _setpoints(ref)[matched[ok]]).max()
    assert diff < 0.05  # the set-points at matched ticks agree, slow-down or not


def test_reference_with_a_gap_is_never_matched_across_it() -> None:
    ref = _run(1, cycles=4.0)
    ref.data.iloc[300:340] = np.nan
    run = _run(2, start=0.5, cycles=2.0)
    a = align_on_setpoints(_setpoints(run), ref.data[["A1.RP", "A2.RP"]].to_numpy(),
                           period=PERIOD)
    used = a.matches[a.matches >= 0]
    assert not ((used >= 300) & (used < 340)).any()
    assert a.covered.all()  # other cycles cover what the gap hides


# ------------------------------------------------------------------------------------ band

def test_band_spread_is_the_references_standard_deviation() -> None:
    rng = np.random.default_rng(5)
    refs = [rng.normal(size=50) for _ in range(4)]
    run = rng.normal(size=50)
    same = Alignment(np.arange(50)[:, None], np.zeros(50), 0.02)
    band = reference_band(run, refs, [same] * 4, period=1.0, smooth=1.0, detail=1.0)
    stacked = np.stack(refs, axis=1)
    for i in range(50):  # a plain loop: mean and sample standard deviation per tick
        values = list(stacked[i])
        mean = sum(values) / 4
        sd = (sum((v - mean) ** 2 for v in values) / 3) ** 0.5
        assert band.centre[i] == pytest.approx(mean)
        floor = 0.25 * np.median(np.std(stacked, axis=1, ddof=1))
        assert band.spread[i] == pytest.approx(max(sd, floor))
        assert band.size[i] == pytest.approx(abs(run[i] - mean)
                                             / (band.spread[i] * (1 + 1 / 4) ** 0.5))
    assert not band.within_run


def test_intervals_merge_and_drop() -> None:
    times = np.arange(300) * 0.01
    size = np.zeros(300)
    size[10:20] = 8.0          # 0.1 s: kept
    size[60:63] = 9.0          # 0.03 s, alone: dropped
    size[100:120] = 7.0        # two stretches 0.2 s apart: one interval
    size[140:150] = 7.5
    found = find_intervals({("CR", 1): size}, {("CR", 1): size / 10}, {"CR": "A"},
                           times=times, threshold=6.0, merge=0.3, min_duration=0.05)
    assert [(i.start, i.stop) for i in found] == [(0.1, 0.2), (1.0, 1.5)]
    assert found[1].size == 7.5 and found[1].differences[0].unit == "A"


# ------------------------------------------------------------------------------------ compare

def test_push_is_found_and_placed() -> None:
    refs = [_run(1, start=0.0, cycles=3.0), _run(2, start=0.8, cycles=3.5)]
    run = _run(3, start=1.3, cycles=5.0, push=(5.0, 5.6, 1, 1.5))
    c = compare_runs(run, refs, networks=False)
    assert c.compared > 0.95
    hits = [i for i in c.intervals if i.start <= 5.6 and i.stop >= 5.0]
    assert len(hits) == 1 and 1 in hits[0].axes and "CR" in hits[0].signals
    assert hits[0].start == pytest.approx(5.0, abs=0.15)
    assert hits[0].stop == pytest.approx(5.6, abs=0.15)
    top = hits[0].differences[0]
    assert (top.signal, top.axis, top.unit) == ("CR", 1, "A")
    assert top.value == pytest.approx(1.5, abs=0.3)
    assert len(c.intervals) == 1  # nothing else
    assert not c.within_run


def test_clean_repeats_show_nothing() -> None:
    refs = [_run(1, cycles=3.0), _run(2, start=0.5, cycles=3.0)]
    for seed in (3, 4, 5):
        c = compare_runs(_run(seed, start=0.9, cycles=4.5), refs, networks=False)
        assert c.intervals == (), (seed, c.intervals)
        assert c.compared > 0.95


def test_one_reference_says_the_band_is_within_one_run() -> None:
    c = compare_runs(_run(3, start=0.3, cycles=3.0, push=(2.0, 2.5, 2, 2.0)),
                     [_run(1, cycles=4.0)], networks=False)
    assert c.within_run
    assert any("one reference" in note for note in c.notes)
    assert any(2 in i.axes and i.start < 2.5 and i.stop > 2.0 for i in c.intervals)


def test_another_program_is_refused() -> None:
    with pytest.raises(SignalError, match="set-points do not match"):
        compare_runs(_run(3, cycles=2.0), [_run(1, cycles=2.0, other=True)], networks=False)


def test_networks_reading_has_windows_per_pair() -> None:
    refs = [_run(1, cycles=3.0), _run(2, start=0.5, cycles=3.0)]
    c = compare_runs(_run(3, start=0.9, cycles=3.0), refs, networks=True)
    net = c.networks
    assert net is not None and net.windows == len(net.starts) > 0
    assert set(net.run) == {(a, p, m) for a in (1, 2) for p in ("RC-AC", "RC-FE", "AC-FE")
                            for m in ("c_diff", "t_diff", "coupling")}
    assert c.readings == ("residuals",)


# ------------------------------------------------------------------------------------ CLI

def _write(tmp_path, name: str, rec: Recording):
    path = tmp_path / f"{name}.parquet"
    rec.to_parquet(path)
    return path


def test_cli_writes_page_and_json(tmp_path) -> None:
    run = _write(tmp_path, "run", _run(3, start=1.3, cycles=5.0, push=(5.0, 5.6, 1, 1.5)))
    a = _write(tmp_path, "a", _run(1, cycles=3.0))
    b = _write(tmp_path, "b", _run(2, start=0.8, cycles=3.5))
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["compare", str(run), "--against", str(a), "--against",
                                      str(b), "-o", str(out), "--no-networks"])
    assert result.exit_code == 0, result.output
    doc = json.loads((out / "changes.json").read_text())
    assert len(doc["intervals"]) == 1
    assert {"start", "stop", "axes", "signals", "size", "differences"} <= set(doc["intervals"][0])
    html = (out / "index.html").read_text()
    assert "carry" not in html or "The intervals come from the residuals" in html
    assert "The intervals come from the residuals" in html
    assert (out / "figures" / "axis1.png").exists()
    assert not list(out.glob(".*.tmp"))


def test_cli_one_reference_page_says_estimated(tmp_path) -> None:
    run = _write(tmp_path, "run", _run(3, start=0.3, cycles=3.0))
    a = _write(tmp_path, "a", _run(1, cycles=4.0))
    result = CliRunner().invoke(app, ["compare", str(run), "--against", str(a), "-o",
                                      str(tmp_path / "o"), "--no-networks"])
    assert result.exit_code == 0, result.output
    assert "The band is estimated with one reference" in (tmp_path / "o" / "index.html"
                                                           ).read_text()


def test_cli_refuses_another_program_in_one_line(tmp_path) -> None:
    run = _write(tmp_path, "run", _run(3, cycles=2.0))
    other = _write(tmp_path, "other", _run(1, cycles=2.0, other=True))
    result = CliRunner().invoke(app, ["compare", str(run), "--against", str(other), "-o",
                                      str(tmp_path / "o")])
    assert result.exit_code == 2
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("funcnet: error: ")
    assert "set-points do not match" in lines[0] and "other.parquet" in lines[0]
    assert not (tmp_path / "o" / "index.html").exists()


def test_reference_with_a_gap_and_another_length_still_finds_the_push() -> None:
    gapped = _run(1, cycles=3.0)
    gapped.data.iloc[250:300] = np.nan  # values missing: a gap, as a reader leaves it
    refs = [gapped, _run(2, start=0.8, cycles=4.5)]
    c = compare_runs(_run(3, start=1.3, cycles=5.0, push=(5.0, 5.6, 1, 1.5)), refs,
                     networks=False)
    assert c.compared > 0.95
    assert [(i.start < 5.6 and i.stop > 5.0) for i in c.intervals] == [True]


def test_gaps_in_run_are_not_compared_and_said() -> None:
    run = _run(3, start=1.3, cycles=3.0)
    run.data.iloc[100:150] = np.nan
    c = compare_runs(run, [_run(1, cycles=3.0), _run(2, start=0.5, cycles=3.0)],
                     networks=False)
    assert not c.covered[100:150].any() and c.covered[:100].all()
    assert any("0.5 s of RUN have no set-point (gaps)" in note for note in c.notes)
    assert all(i.stop <= 1.0 or i.start >= 1.5 for i in c.intervals)
