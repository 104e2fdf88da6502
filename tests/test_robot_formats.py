"""Recordings engineers have: MATLAB (MAT 5, MAT 7.3), HDF5, CSV and Parquet, one or many axes.

The KUKA KR 300 runs shipped in ``data/kuka-kr300`` are compared with an independent reading
(``scipy.io.loadmat`` as their README says); the rules on gaps, duplicates, off-grid time,
constant channels, bad text and time that does not increase are checked on small files written
here, in every format they apply to.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
import scipy.io

from conftest import KUKA
from funcnet.errors import (
    ChannelError,
    ParameterError,
    RecordingWarning,
    TraceFormatError,
    WindowError,
)
from funcnet.robot import read_recording, read_trace
from funcnet.robot.preprocess import velocity
from funcnet.robot.recording import Recording

ROOT = Path(__file__).resolve().parents[1]
KUKA_MAP = ROOT / "examples" / "kuka-kr300-channels.toml"
RUNS = ["kr300-run-A.mat", "kr300-run-B.mat"]
FIELDS = {"RP": "ref_pos_deg", "AP": "act_pos_se_deg", "MP": "act_pos_mot_deg",
          "AC": "act_torque_abs_nm"}


def read_said(*args, **kwargs) -> tuple[Recording, list[RecordingWarning]]:
    """read_trace, and the RecordingWarnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        recording = read_trace(*args, **kwargs)
    return recording, [w.message for w in caught if isinstance(w.message, RecordingWarning)]


def kuka_struct(name: str):
    return scipy.io.loadmat(KUKA / name, squeeze_me=True, struct_as_record=False)["rec"]


# -- the KUKA runs ---------------------------------------------------------------------------


@pytest.mark.parametrize("run", RUNS)
def test_kuka_run_reads_as_one_recording_of_six_axes(run):
    rec, said = read_said(KUKA / run, channels=KUKA_MAP)
    struct = kuka_struct(run)
    assert rec.axes == (1, 2, 3, 4, 5, 6) and rec.axis is None
    assert rec.sample_period == 0.004 and len(rec.data) == 2501
    assert rec.data.index[-1] == pytest.approx(struct.time_cont[-1], abs=1e-6)
    roles = sorted(rec.roles)
    expected = sorted(f"A{n}.{r}" for n in range(1, 7) for r in ("RP", "MP", "AC"))
    assert roles == sorted(expected + ["A1.AP", "A2.AP", "A3.AP"])  # 21 nodes
    for column in roles:
        axis, role = int(column[1]), column[3:]
        np.testing.assert_array_equal(
            rec.data[column].to_numpy(), getattr(struct, FIELDS[role])[axis - 1]
        )
    assert rec.signals["A2.AC"].unit == "N m" and rec.signals["A2.RP"].unit == "deg"
    assert rec.gaps == () and rec.segments == [(0.0, 10.004)]
    # The arm-side encoder is not fitted on axes 4-6: all zeros, left out and said, in one line.
    constant = [w for w in said if w.problem == "constant"]
    assert len(constant) == 1 and "\n" not in str(constant[0])
    assert {"A4.AP", "A5.AP", "A6.AP"} <= set(constant[0].signals)
    assert "A4.AP = 0" in str(constant[0]) and run in str(constant[0])
    assert not any(s in rec.data for s in ("A4.AP", "A5.AP", "A6.AP"))
    assert [w.problem for w in said] == ["constant"]


@pytest.mark.parametrize("axis", [1, 5])
def test_kuka_one_axis_reads_like_a_one_axis_trace(axis):
    rec, said = read_said(KUKA / RUNS[1], channels=KUKA_MAP, axis=axis)
    struct = kuka_struct(RUNS[1])
    assert rec.axis == axis and rec.axes == ()
    for role in ("RP", "MP", "AC"):
        np.testing.assert_array_equal(rec.data[role], getattr(struct, FIELDS[role])[axis - 1])
    assert ("AP" in rec.data) == (axis <= 3)
    assert rec.roles["RP"] == f"rec.ref_pos_deg(axis {axis})"
    # The same as choosing the axis after reading them all.
    every = read_said(KUKA / RUNS[1], channels=KUKA_MAP)[0].for_axis(axis)
    pd.testing.assert_frame_equal(rec.data[every.data.columns], every.data)
    with pytest.raises(ChannelError, match="axis 7 is not in the file; it holds axes 1-6"):
        read_trace(KUKA / RUNS[1], channels=KUKA_MAP, axis=7)


def test_kuka_map_with_bare_and_struct_path_keys_agree():
    # A bare name that two structs hold is not chosen between: it is an error naming both.
    with pytest.raises(ChannelError, match=r"several variables have the role time: "
                       r"time_data.time_cont, rec.time_cont; name one by its path"):
        read_trace(KUKA / RUNS[0], channels={"time_cont": "time"})
    bare = {"rec.time_cont": "time", "ref_pos_deg": "RP", "act_torque_abs_nm": "AC"}
    dotted = {"rec.time_cont": "time", "rec.ref_pos_deg": "RP", "rec.act_torque_abs_nm": "ac"}
    a, _ = read_said(KUKA / RUNS[0], channels=bare, axis=2)
    b, _ = read_said(KUKA / RUNS[0], channels=dotted, axis=2)
    pd.testing.assert_frame_equal(a.data, b.data)
    assert a.roles == b.roles == {"RP": "rec.ref_pos_deg(axis 2)",
                                  "AC": "rec.act_torque_abs_nm(axis 2)"}


def test_kuka_qualified_nodes_are_accepted_and_derived_per_axis():
    rec = read_recording(KUKA / RUNS[0], channels=KUKA_MAP, signals=["A1.RP", "A2.V", "A3.FE"])
    struct = kuka_struct(RUNS[0])
    ap2 = struct.act_pos_se_deg[1]
    np.testing.assert_allclose(rec.data["A2.V"], velocity(ap2, 0.004), rtol=0, atol=0)
    np.testing.assert_array_equal(
        rec.data["A3.FE"], struct.ref_pos_deg[2] - struct.act_pos_se_deg[2]
    )
    assert "A1.V" not in rec.data  # derived only when named


def test_missing_time_is_asked_for_by_name():
    with pytest.raises(ChannelError, match=r"no variable is called time.*candidates: "
                       r".*rec\.time_cont"):
        read_trace(KUKA / RUNS[0], channels={"ref_pos_deg": "RP"})
    with pytest.raises(ChannelError, match="entry 'ref_pos' = 'RP' matches no signal"):
        read_trace(KUKA / RUNS[0], channels={"rec.time_cont": "time", "ref_pos": "RP"})


# -- small generated files -------------------------------------------------------------------


def signals(n: int = 50, period: float = 0.004):
    """Time, a two-axis RP, a one-axis torque: independent values to compare with."""
    rng = np.random.default_rng(7)
    time = np.arange(n) * period
    rp = np.cumsum(rng.normal(size=(2, n)), axis=1)
    torque = rng.normal(size=n)
    return time, rp, torque


def write_mat5(path: Path, time, rp, torque) -> Path:
    scipy.io.savemat(path, {"run": {"t": time, "pos": rp, "tau": torque}, "gain": 3.0})
    return path


def write_mat73(path: Path, time, rp, torque) -> Path:
    """A MATLAB 7.3 file as MATLAB writes one: HDF5 with a 512-byte header, columns stored
    transposed, every variable tagged with its MATLAB class."""
    with h5py.File(path, "w", userblock_size=512) as file:
        run = file.create_group("run")
        run.attrs["MATLAB_class"] = np.bytes_("struct")
        variables = {"t": time[np.newaxis, :], "pos": rp, "tau": torque[np.newaxis, :]}
        for name, value in variables.items():
            data = run.create_dataset(name, data=np.ascontiguousarray(value.T))
            data.attrs["MATLAB_class"] = np.bytes_("double")
        label = run.create_dataset("label", data=np.frombuffer(b"axis", dtype=np.uint16))
        label.attrs["MATLAB_class"] = np.bytes_("char")
    with path.open("r+b") as stream:
        stream.write(b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Thu Nov 26 2026 HDF5")
    return path


def write_hdf5(path: Path, time, rp, torque) -> Path:
    with h5py.File(path, "w") as file:
        group = file.create_group("run")
        group.create_dataset("time", data=time)
        group.create_dataset("pos", data=rp).attrs["units"] = "deg"
        group.create_dataset("tau", data=torque).attrs["units"] = "N m"
        file.create_dataset("other/pos", data=np.arange(7.0))
    return path


WRITERS = {"mat5": (write_mat5, ".mat"), "mat73": (write_mat73, ".mat"),
           "hdf5": (write_hdf5, ".h5")}
MAPS = {"mat5": {"run.t": "time", "pos": "RP", "tau": "AC"},
        "mat73": {"run.t": "time", "pos": "RP", "tau": "AC"},
        "hdf5": {"/run/pos": "RP", "tau": "AC"}}


def write(kind: str, tmp_path: Path, time, rp, torque) -> Path:
    writer, suffix = WRITERS[kind]
    return writer(tmp_path / f"{kind}{suffix}", time, rp, torque)


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_files_read_every_axis_or_one(kind, tmp_path):
    time, rp, torque = signals()
    path = write(kind, tmp_path, time, rp, torque)
    rec, said = read_said(path, channels=MAPS[kind])
    assert said == []
    assert list(rec.data.columns) == ["AC", "A1.RP", "A2.RP"]  # common first, then per axis
    np.testing.assert_array_equal(rec.data["A2.RP"], rp[1])
    np.testing.assert_array_equal(rec.data["AC"], torque)
    assert rec.sample_period == 0.004 and rec.data.index[0] == 0.0
    one = read_trace(path, channels=MAPS[kind], axis=1)
    assert list(one.data.columns) == ["RP", "AC"] and one.axis == 1  # the file's order
    np.testing.assert_array_equal(one.data["RP"], rp[0])
    if kind == "hdf5":
        assert one.signals["AC"].unit == "N m"
        assert one.roles == {"RP": "/run/pos(axis 1)", "AC": "/run/tau"}


def test_mat73_and_mat5_of_the_same_content_read_the_same(tmp_path):
    time, rp, torque = signals(period=0.001)
    a = read_trace(write("mat5", tmp_path, time, rp, torque), channels=MAPS["mat5"])
    b = read_trace(write("mat73", tmp_path, time, rp, torque), channels=MAPS["mat73"])
    pd.testing.assert_frame_equal(a.data, b.data)
    assert a.sample_period == b.sample_period == 0.001


@pytest.mark.parametrize("period", [0.001, 0.002, 0.008, 0.0125])
def test_any_sample_period(period, tmp_path):
    time, rp, torque = signals(period=period)
    rec = read_trace(write("hdf5", tmp_path, time + 3.0, rp, torque), channels=MAPS["hdf5"])
    assert rec.sample_period == period
    np.testing.assert_allclose(rec.data.index, time + 3.0, rtol=0, atol=1e-9)


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_file_gaps_split_the_recording(kind, tmp_path):
    time, rp, torque = signals()
    rp[1, 10:13] = np.nan
    torque[30] = np.nan
    path = write(kind, tmp_path, time, rp, torque)
    rec, said = read_said(path, channels=MAPS[kind])
    assert rec.gaps == ((0.04, 0.052), (0.12, 0.124))
    assert rec.segments == [(0.0, 0.04), (0.052, 0.12), (0.124, 0.2)]
    (gap,) = said
    assert gap.problem == "gap" and set(gap.signals) == {"A2.RP", "AC"}
    assert "0.04-0.052 s (A2.RP)" in str(gap) and "3 segments" in str(gap)
    rec.window(0.052, 0.12)  # within a segment
    with pytest.raises(WindowError, match=r"spans the gap \[0.04, 0.052\)"):
        rec.window(0.0, 0.1)
    # One axis: only its own gaps.
    assert read_said(path, channels=MAPS[kind], axis=1)[0].gaps == ((0.12, 0.124),)


def test_time_stamps_left_out_of_an_array_file_are_a_gap(tmp_path):
    time, rp, torque = signals()
    keep = np.r_[0:20, 25:50]
    path = write("mat5", tmp_path, time[keep], rp[:, keep], torque[keep])
    rec, said = read_said(path, channels=MAPS["mat5"])
    assert len(rec.data) == 50 and rec.gaps == ((0.08, 0.1),)
    assert np.isnan(rec.data["AC"].iloc[20:25]).all() and [w.problem for w in said] == ["gap"]


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_file_constant_channel_left_out(kind, tmp_path):
    time, rp, torque = signals()
    rp[1] = 0.0
    rec, said = read_said(write(kind, tmp_path, time, rp, torque), channels=MAPS[kind])
    assert "A2.RP" not in rec.data and "A1.RP" in rec.data and rec.axes == (1,)
    (constant,) = said
    assert constant.problem == "constant" and constant.signals == ("A2.RP",)


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_file_time_that_does_not_increase(kind, tmp_path):
    time, rp, torque = signals()
    time[17] = time[16]
    path = write(kind, tmp_path, time, rp, torque)
    with pytest.raises(TraceFormatError, match=r"sample 18: time 0.064 does not increase") as err:
        read_trace(path, channels=MAPS[kind])
    assert str(path) in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_file_infinite_value_is_an_error(kind, tmp_path):
    time, rp, torque = signals()
    rp[0, 5] = np.inf
    with pytest.raises(TraceFormatError, match=r"pos\(axis 1\) sample 6: inf is not a finite"):
        read_trace(write(kind, tmp_path, time, rp, torque), channels=MAPS[kind])


@pytest.mark.parametrize("kind", list(WRITERS))
def test_array_file_off_grid_time_offers_the_interpolation(kind, tmp_path):
    time, rp, torque = signals()
    jittered = time + np.random.default_rng(3).uniform(-4e-4, 4e-4, size=time.size)
    jittered[0] = 0.0
    path = write(kind, tmp_path, jittered, rp, torque)
    median = round(float(np.median(np.diff(jittered))), 6)
    with pytest.raises(TraceFormatError, match=r"sample 2: time .* is not on the .* grid.*"
                       r"resample='interpolate' \(--resample interpolate\) interpolates every "
                       rf"signal onto a {median:g} s grid"):
        read_trace(path, channels=MAPS[kind])
    rec = read_recording(path, channels=MAPS[kind], resample="interpolate")
    assert rec.sample_period == median
    grid = np.arange(len(rec.data)) * median
    np.testing.assert_allclose(rec.data.index, grid, atol=1e-9)
    np.testing.assert_allclose(rec.data["A1.RP"], np.interp(grid, jittered, rp[0]), atol=1e-12)
    assert grid[-1] <= jittered[-1] < grid[-1] + median


def test_hdf5_named_by_path_and_mat_struct_paths(tmp_path):
    time, rp, torque = signals()
    path = write("hdf5", tmp_path, time, rp, torque)
    # A variable the map names must be a signal of the time's length.
    with pytest.raises(ChannelError, match=r"'/other/pos' \(role MP\) has shape \(7,\)"):
        read_trace(path, channels={"/other/pos": "MP"})
    # Bare 'pos' names both /run/pos and /other/pos; only the one of the time's length is read.
    rec = read_trace(path, channels={"pos": "RP"})
    assert "A1.RP" in rec.data


# -- tables ----------------------------------------------------------------------------------


def test_csv_missing_values_are_gaps_but_leading_ones_are_not(tmp_path):
    path = tmp_path / "t.csv"
    rows = ["time,RP,AP"] + [f"{k * 0.002:.3f},{k},{'' if k == 0 else k % 3}" for k in range(10)]
    rows[6] = "0.010,,1"  # RP missing at tick 5
    rows[7] = "0.012,NaN,2"
    path.write_text("\n".join(rows) + "\n")
    rec, said = read_said(path)
    assert rec.gaps == ((0.01, 0.014),)  # AP's empty first cell (not written yet) is no gap
    assert np.isnan(rec.data["AP"].iloc[0]) and [w.problem for w in said] == ["gap"]
    # The gaps survive a round trip through the recording's Parquet file.
    again = Recording.from_parquet(rec.to_parquet(tmp_path / "r.parquet"))
    assert again.gaps == rec.gaps and again.segments == [(0.0, 0.01), (0.014, 0.02)]


def test_csv_duplicated_column_names(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("time,RP,temp,temp\n0,1,2,3\n0.002,2,3,4\n0.004,3,4,5\n")
    rec, said = read_said(path)
    assert list(rec.data.columns) == ["RP"]
    assert said[0].problem == "duplicate" and "'temp' (columns 3, 4)" in str(said[0])
    path.write_text("time,RP,RP\n0,1,2\n0.002,2,3\n")
    with pytest.raises(ChannelError, match=r"channel 'RP' is given 2 times \(columns 2, 3\)"):
        read_trace(path)
    path.write_text("time,time,RP\n0,0,1\n0.002,0.002,2\n")
    with pytest.raises(ChannelError, match="the time column is given 2 times"):
        read_trace(path)


def test_parquet_duplicated_column_names_and_gaps(tmp_path):
    table = pa.table([pa.array([0.0, 0.002, 0.004, 0.006]), pa.array([1.0, None, 3.0, 4.0]),
                      pa.array([1.0, 2.0, 3.0, 5.0]), pa.array([1.0, 2.0, 2.0, 2.0])],
                     names=["time", "RP", "x", "x"])
    pq.write_table(table, tmp_path / "p.parquet")
    rec, said = read_said(tmp_path / "p.parquet")
    assert list(rec.data.columns) == ["RP"] and rec.gaps == ((0.002, 0.004),)
    assert sorted(w.problem for w in said) == ["duplicate", "gap"]


def test_csv_constant_channel_and_off_grid_time(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("time,RP,MP\n0,0,5\n0.004,1,5\n0.0081,2,5\n0.012,3,5\n")
    with pytest.raises(TraceFormatError, match=r"line 3: time 0.004 is not on the 0.0039 s "
                       r"grid.*onto a 0.004 s grid"):
        read_trace(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rec = read_recording(path, resample="interpolate")
    # the constant MP left out, and the positions of no stated unit (computed as degrees)
    assert [w.message.problem for w in caught if isinstance(w.message, RecordingWarning)] == [
        "constant", "unit"]
    assert list(rec.data.columns) == ["RP"] == [*rec.signals]
    np.testing.assert_allclose(rec.data["RP"], np.interp([0, 0.004, 0.008, 0.012],
                                                         [0, 0.004, 0.0081, 0.012], [0, 1, 2, 3]))


def test_off_grid_is_a_checked_parameter(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("time,RP\n0,0\n0.004,1\n")
    with pytest.raises(ParameterError, match="off_grid must be one of error, interpolate"):
        read_trace(path, off_grid="nearest")


def test_units_table_of_the_channel_map(tmp_path):
    toml = tmp_path / "m.toml"
    toml.write_text('defaults = false\n[channels]\n"run.t" = "time"\ntau = "AC"\n'
                    '[units]\ntau = "N m"\n')
    time, rp, torque = signals()
    path = write("mat5", tmp_path, time, rp, torque)
    rec = read_trace(path, channels=toml, axis=2)
    assert rec.signals["AC"].unit == "N m" and rec.signals["pos"].unit is None
    toml.write_text('[channels]\n"run.t" = "time"\n[units]\ntorque = "N m"\n')
    with pytest.raises(ChannelError, match="unit of 'torque' given, but no signal is called so"):
        read_trace(path, channels=toml, axis=2)
