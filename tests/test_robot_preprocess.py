"""Preprocessing: velocity (Eq. 11-12), derived signals, trimming, resampling."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ChannelError, ParameterError, SignalError, WindowError
from funcnet.robot.io.read import read_trace
from funcnet.robot.preprocess import (
    add_derived_signals,
    resample,
    segment_velocity,
    staircase_signals,
    trim,
    velocity,
)
from funcnet.robot.recording import Recording, SignalInfo


@pytest.fixture(scope="module")
def real(real_trace) -> Recording:
    return read_trace(real_trace)


def velocity_by_hand(x: list[float], dt: float) -> list[float]:
    """Eq. 11 and Eq. 12 written out, with the documented ends."""
    n = len(x)
    v = []
    for i in range(n):
        if i == 0:
            v.append((x[1] - x[0]) / dt)
        elif i == n - 1:
            v.append((x[n - 1] - x[n - 2]) / dt)
        else:
            v.append((x[i + 1] - x[i - 1]) / (2 * dt))
    smooth = []
    for i in range(n):
        around = v[max(i - 1, 0) : i + 2]
        smooth.append(sum(around) / len(around))
    return smooth


def test_velocity_matches_eq_11_12_written_out():
    rng = np.random.default_rng(3)
    x = np.cumsum(rng.normal(size=50))
    np.testing.assert_allclose(velocity(x, 0.002), velocity_by_hand(list(x), 0.002), rtol=1e-12)


def test_velocity_ends_and_exactness():
    # A straight line: the exact slope everywhere, ends included.
    np.testing.assert_allclose(velocity(3.0 * np.arange(10.0) + 1, 0.5), 6.0)
    # A parabola x = t^2: the central difference is exact inside (2t), so Eq. 12 gives 2t too
    # where all three neighbours are central; the ends use the one-sided differences.
    t = np.arange(6) * 0.1
    v = velocity(t**2, 0.1)
    np.testing.assert_allclose(v[2:-2], 2 * t[2:-2])
    np.testing.assert_allclose(v[0], ((0.01 - 0.0) / 0.1 + 0.2) / 2)
    np.testing.assert_allclose(v[-1], (2 * 0.4 + (0.25 - 0.16) / 0.1) / 2)
    assert velocity([1.0, 4.0], 1.0).tolist() == [3.0, 3.0]


def test_velocity_of_an_ipo_staircase_spans_one_step():
    # 4 ms samples of a ramp held over the 2 ms ticks: Eq. 11 always spans exactly one step.
    ramp = np.repeat(np.arange(20.0), 2)
    raw_central = (ramp[2:] - ramp[:-2]) / (2 * 0.002)
    np.testing.assert_allclose(raw_central, 1 / 0.004)
    np.testing.assert_allclose(velocity(ramp, 0.002)[2:-2], 1 / 0.004)


def test_velocity_is_taken_within_each_segment_of_a_recording_with_gaps():
    rng = np.random.default_rng(4)
    x = np.cumsum(rng.normal(size=30))
    x[10:13] = np.nan  # a gap of three ticks; a segment of one tick (20) between two gaps
    x[19] = x[21] = np.nan
    t = np.arange(30) * 0.002
    data = pd.DataFrame({"AP": x}, index=pd.Index(t.round(9), name="time"))
    gaps = ((0.02, 0.026), (0.038, 0.04), (0.042, 0.044))
    rec = Recording(data, {}, {"AP": SignalInfo("AP", "posn", None, 0.002)},
                    sample_period=0.002, gaps=gaps)
    v = segment_velocity(rec, x)
    for first, stop in ((0, 10), (13, 19), (22, 30)):  # Eq. 11-12 on each segment alone
        np.testing.assert_allclose(v[first:stop], velocity_by_hand(list(x[first:stop]), 0.002),
                                   rtol=1e-12)
    assert np.isnan(v[[10, 11, 12, 19, 20, 21]]).all()  # the gaps, and one tick: no speed
    # V of add_derived_signals is the same; without gaps, velocity as before
    np.testing.assert_array_equal(add_derived_signals(rec, ["V"]).data["V"], v)
    whole = Recording(data.fillna(0.0), {}, rec.signals, sample_period=0.002)
    np.testing.assert_array_equal(segment_velocity(whole, whole.data["AP"].to_numpy()),
                                  velocity(whole.data["AP"].to_numpy(), 0.002))


def test_velocity_rejects_bad_input():
    with pytest.raises(SignalError, match="ap"):
        velocity([1.0], 0.002)
    with pytest.raises(ParameterError, match="sample_period"):
        velocity([1.0, 2.0], 0.0)


def test_derived_signals_on_the_real_trace(real):
    rec = add_derived_signals(real)
    d = rec.data
    np.testing.assert_array_equal(d["FE"], d["RP"] - d["AP"])
    np.testing.assert_array_equal(d["TORSION"], d["MP"] - d["AP"])
    np.testing.assert_array_equal(d["V"], velocity(real.data["AP"].to_numpy(), 0.002))
    assert list(d.columns[-3:]) == ["V", "FE", "TORSION"]
    assert rec.signals["V"].interval == 0.002 and rec.signals["V"].units_type == "velo"
    assert rec.signals["FE"].interval == 0.004  # AP is a 4 ms staircase
    assert rec.signals["TORSION"].name == "MP - AP"
    assert "V" not in rec.roles  # roles name controller signals only
    # The cruise of the first move runs at 108 deg/s (RP); AP follows it.
    assert abs(d["V"].loc[7.5] - 108.0) < 1.0
    # Recomputing replaces, it does not duplicate.
    assert list(add_derived_signals(rec, ["V"]).data.columns) == list(d.columns)


def test_derived_signals_need_their_inputs(real):
    only_ac = Recording(real.data[["AC"]], {}, {"AC": real.signals["AC"]}, source="x.xml")
    with pytest.raises(ChannelError, match="x.xml.*FE needs the column 'RP'"):
        add_derived_signals(only_ac, ["FE"])
    with pytest.raises(ParameterError, match="'SPEED'"):
        add_derived_signals(real, ["SPEED"])


def test_trim_to_motion_and_to_a_range(real):
    moving = trim(real, margin=0.2)
    speed = np.abs(velocity(real.data["RP"].to_numpy(), 0.002))
    ticks = np.flatnonzero(speed > 1e-4 * speed.max())
    assert moving.data.index[0] == pytest.approx(real.data.index[ticks[0]] - 0.2)
    assert moving.data.index[-1] == pytest.approx(real.data.index[ticks[-1]] + 0.2)
    # RP is constant before the motion starts: the first change is at 6.408 s.
    assert real.data["RP"].loc[:6.406].nunique() == 1 and real.data.at[6.408, "RP"] > 0
    assert 6.2 < moving.data.index[0] <= 6.208
    part = trim(real, start=10.0, stop=10.01)
    assert part.data.index.tolist() == [10.0, 10.002, 10.004, 10.006, 10.008]
    assert trim(real, start=45.0).data.index[-1] == 45.416
    with pytest.raises(WindowError, match="axis7-braking-trace.xml"):
        trim(real, start=40.0, stop=50.0)


def test_trim_needs_motion(real):
    still = real.window(0.0, 5.0)
    with pytest.raises(SignalError, match="RP never moves"):
        trim(still)


def test_staircase_signals(real):
    assert staircase_signals(real) == ["aaStat", "MP", "AP"]
    assert staircase_signals(real, ["RP", "AC"]) == []


def test_decimate_keeps_the_ipo_ticks(real):
    coarse = resample(real)
    assert coarse.sample_period == 0.004
    # The IPO signals are written at 2, 6, 10 ... ms; those ticks are kept, values untouched.
    assert coarse.data.index[:3].tolist() == [0.002, 0.006, 0.01]
    np.testing.assert_array_equal(coarse.data, real.data.iloc[1::2])
    assert not coarse.data[["AP", "MP"]].isna().any().any()
    assert staircase_signals(coarse) == []
    assert {info.interval for info in coarse.signals.values()} == {0.004}


def test_interpolate_draws_lines_between_native_samples(real):
    fine = resample(real, method="interpolate")
    assert fine.sample_period == 0.002 and staircase_signals(fine) == []
    ap, native = fine.data["AP"].to_numpy(), real.data["AP"].to_numpy()
    # Native samples (odd ticks) unchanged, the ticks between them are midpoints.
    np.testing.assert_array_equal(ap[1::2], native[1::2])
    np.testing.assert_allclose(ap[2:-1:2], (native[1:-2:2] + native[3::2]) / 2)
    assert np.isnan(ap[0])  # before the first sample
    np.testing.assert_array_equal(fine.data["RP"], real.data["RP"])  # servo signals untouched
    assert fine.signals["AP"].interval == 0.002


def test_resample_rejects_periods_off_the_grid(real):
    with pytest.raises(ParameterError, match="period"):
        resample(real, 0.003)
    with pytest.raises(ParameterError, match="method"):
        resample(real, method="spline")


def test_resample_to_a_coarser_period_small():
    index = pd.Index(np.round(np.arange(8) * 0.002, 9), name="time")
    data = pd.DataFrame({"A": np.arange(8.0)}, index=index)
    rec = Recording(data, {}, {"A": SignalInfo("A", None, None, 0.002)})
    out = resample(rec, 0.008)
    assert out.data["A"].tolist() == [0.0, 4.0] and out.signals["A"].interval == 0.008
