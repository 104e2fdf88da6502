"""read_recording: a trace with the derived signals a selection needs, resampled when asked."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from funcnet.errors import ChannelError, ParameterError
from funcnet.robot import read_recording
from funcnet.robot.io.read import read_trace
from funcnet.robot.prepare import derived_signals_needed, prepare_recording
from funcnet.robot.preprocess import add_derived_signals, resample, staircase_signals, velocity


@pytest.fixture(scope="module")
def raw(real_trace):
    return read_trace(real_trace)


def test_default_adds_v_from_ap(real_trace, raw):
    recording = read_recording(real_trace)
    assert list(recording.data.columns) == [*raw.data.columns, "V"]
    expected = add_derived_signals(raw, ["V"])
    pd.testing.assert_frame_equal(recording.data, expected.data)
    assert recording.signals["V"] == expected.signals["V"]
    assert recording.roles == raw.roles and recording.source == raw.source


def test_only_the_derived_signals_named(real_trace, raw):
    recording = read_recording(real_trace, signals=["RP", "TORSION", "FE"])
    assert list(recording.data.columns) == [*raw.data.columns, "FE", "TORSION"]
    np.testing.assert_array_equal(
        recording.data["FE"].to_numpy(), (raw.data["RP"] - raw.data["AP"]).to_numpy()
    )
    assert list(read_recording(real_trace, signals=["RP", "AP"]).data.columns) == list(
        raw.data.columns
    )


@pytest.mark.parametrize("method", ["decimate", "interpolate"])
def test_resampled_derived_signals_come_from_resampled_inputs(real_trace, raw, method):
    recording = read_recording(real_trace, signals=["RP", "AP", "V", "FE"], resample=method)
    # As the command line did it: derived signals on the native grid, resampled, recomputed.
    native = add_derived_signals(raw, ["V", "FE"])
    expected = add_derived_signals(resample(native, method=method), ["V", "FE"])
    pd.testing.assert_frame_equal(recording.data, expected.data)
    assert recording.signals == expected.signals
    assert recording.sample_period == expected.sample_period
    ap = recording.data["AP"].to_numpy()
    ok = ~np.isnan(ap)
    v = velocity(ap[ok], recording.sample_period)
    np.testing.assert_array_equal(recording.data["V"].to_numpy()[ok][5:-5], v[5:-5])
    if method == "decimate":
        assert recording.sample_period == 0.004
        assert staircase_signals(recording, ["RP", "AP", "V", "FE"]) == []


def test_prepare_recording_is_read_recording_after_the_read(real_trace, raw):
    # the interpolated positions first, then V and FE from them (as the inspection did it)
    prepared = prepare_recording(raw, signals=["V", "FE"], resample="interpolate")
    expected = add_derived_signals(resample(raw, method="interpolate"), ["V", "FE"])
    pd.testing.assert_frame_equal(prepared.data, expected.data)
    assert prepared.signals == expected.signals
    again = read_recording(real_trace, signals=["V", "FE"], resample="interpolate")
    pd.testing.assert_frame_equal(prepared.data, again.data)
    with pytest.raises(ParameterError, match="resample"):
        prepare_recording(raw, resample="nearest")


def test_a_derived_column_stored_in_the_file_is_recomputed_after_resampling(
    real_trace, raw, tmp_path
):
    stored = tmp_path / "with-v.parquet"
    add_derived_signals(raw, ["V"]).to_parquet(stored)
    recording = read_recording(stored, resample="decimate")
    expected = read_recording(real_trace, resample="decimate")
    pd.testing.assert_frame_equal(recording.data, expected.data)


def test_bad_resample_is_refused_before_reading(tmp_path):
    with pytest.raises(ParameterError, match="resample must be one of decimate, interpolate"):
        read_recording(tmp_path / "missing.xml", resample="linear")
    try:
        read_recording(tmp_path / "missing.xml", resample="linear")
    except ParameterError as error:
        assert error.parameter == "resample"
        assert error.spelled("--resample").startswith("--resample must be")


def test_missing_input_of_a_derived_signal(tmp_path):
    path = tmp_path / "rp.csv"
    path.write_text("time,RP\n0,0\n0.002,1\n0.004,2\n")
    assert list(read_recording(path).data.columns) == ["RP"]  # no AP: no V by default
    with pytest.raises(ChannelError, match="'AP'"):
        read_recording(path, signals=["RP", "V"])


def test_derived_signals_needed():
    assert derived_signals_needed(None, ["RP"]) == ()
    assert derived_signals_needed(("V", "TORSION"), ["AP", "MP"]) == ("V", "TORSION")
