"""A time column in any unit: s, ms, us, ns, ISO 8601; absolute clocks read from the start.

Every reference is the grid the file was written from (``k * period``), or the date-times'
own arithmetic (:mod:`datetime`), independent of :mod:`funcnet.robot.io.clock`.
"""

from __future__ import annotations

import warnings
from datetime import UTC, datetime, timedelta
from pathlib import Path

import numpy as np
import pytest
import scipy.io
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.errors import ChannelError, RecordingWarning, TraceFormatError
from funcnet.robot import read_trace
from funcnet.robot.io.channels import ChannelMap
from funcnet.robot.io.layout import signal_files
from funcnet.robot.recording import Recording

ROOT = Path(__file__).resolve().parents[1]
MCS500 = ROOT / "data" / "mecademic-mcs500" / "mcs500-two-cycles.csv"
MCS500_MAP = ROOT / "examples" / "mecademic-channels.toml"
runner = CliRunner()


def _quiet_read(*args, **kwargs) -> Recording:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RecordingWarning)
        return read_trace(*args, **kwargs)


def _log(path: Path, stamps: list[str], header: str = "timestamp") -> Path:
    """A one-file log: the given time stamps, and a position that moves, in two columns."""
    rows = [f"{stamp}, {np.sin(k / 7):.6f}, {np.cos(k / 5):.6f}" for k, stamp in enumerate(stamps)]
    path.write_text(f"{header}, q0, q1\n" + "\n".join(rows) + "\n")
    return path


def _map(unit: str | None, time: str = "timestamp") -> ChannelMap:
    files = signal_files({"q": {"columns": ["q0", "q1"]}},
                         {"header": True, "separator": ",", "time": time}, "m.toml")
    return ChannelMap({"q": "RP"}, units={} if unit is None else {time: unit}, files=files)


# -- the MCS500's microsecond real-time clock ------------------------------------------------


def test_the_mcs500_clock_reads_from_zero_every_millisecond():
    rec = _quiet_read(MCS500, channels=MCS500_MAP)
    stamps = np.loadtxt(MCS500, delimiter=",", skiprows=1, usecols=0)
    assert rec.sample_period == 0.001 and len(rec.data) == len(stamps) == 1698
    # the reference: the file's own stamps, in microseconds from its first
    np.testing.assert_allclose(rec.data.index, (stamps - stamps[0]) * 1e-6, rtol=0, atol=1e-12)
    assert rec.data.index[0] == 0.0 and rec.data.index[-1] == 1.697
    assert rec.time_origin == stamps[0] * 1e-6 and rec.time_unit == "us"


def test_the_mcs500_clock_without_its_unit_is_refused_in_one_line(tmp_path):
    bare = tmp_path / "bare.toml"
    bare.write_text(MCS500_MAP.read_text().replace('timestamp = "us"', ""))
    with pytest.raises(ChannelError) as caught:
        _quiet_read(MCS500, channels=bare)
    message = str(caught.value)
    assert "\n" not in message and "'timestamp' steps by 1000 per sample" in message
    assert "as us every 1 ms" in message and '[units] timestamp = "us"' in message
    result = runner.invoke(app, ["inspect", str(MCS500), "--channels", str(bare),
                                 "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and result.output.strip().count("\n") == 0
    assert "state its unit" in result.output


# -- every unit, one grid --------------------------------------------------------------------


@pytest.mark.parametrize(("unit", "factor"), [("s", 1.0), ("ms", 1e3), ("us", 1e6),
                                              ("ns", 1e9)])
@pytest.mark.parametrize("start", [0.0, 5000.0])
def test_each_time_unit_gives_the_same_grid(tmp_path, unit, factor, start):
    period = 0.002
    ticks = np.arange(40)
    stamps = [f"{(start + k * period) * factor:.0f}" if unit != "s"
              else f"{start + k * period:.3f}" for k in ticks]
    rec = _quiet_read(_log(tmp_path / "log.csv", stamps), channels=_map(unit), axis=1)
    assert rec.sample_period == period
    # a clock at 5000 s counts from before the log: read from its start, its reading kept
    np.testing.assert_allclose(rec.data.index, ticks * period, rtol=0, atol=1e-9)
    assert rec.time_origin == pytest.approx(start, abs=1e-9)
    assert rec.time_unit == (None if unit == "s" else unit)


def test_a_clock_that_starts_late_but_not_absolute_keeps_its_values(tmp_path):
    stamps = [f"{(3 + k * 0.004) * 1e3:.0f}" for k in range(30)]
    rec = _quiet_read(_log(tmp_path / "log.csv", stamps), channels=_map("ms"), axis=2)
    assert rec.data.index[0] == 3.0 and rec.time_origin == 0.0


@pytest.mark.parametrize("stamps", [[str(k) for k in range(30)],          # a ms counter, 1 kHz
                                    [str(k * 10**6) for k in range(30)],  # ns, 1 kHz
                                    [f"{k * 1e-8:.8f}" for k in range(30)]])
def test_an_implausible_step_without_a_unit_is_never_taken_as_seconds(tmp_path, stamps):
    with pytest.raises(ChannelError, match=r"no unit stated.*\[units\] timestamp = "):
        read_trace(_log(tmp_path / "log.csv", stamps), channels=_map(None), axis=1)


def test_a_slow_log_is_read_once_its_unit_is_stated(tmp_path):
    stamps = [str(k) for k in range(30)]  # one sample a second
    with pytest.raises(ChannelError):
        read_trace(_log(tmp_path / "log.csv", stamps), channels=_map(None), axis=1)
    rec = _quiet_read(tmp_path / "log.csv", channels=_map("s"), axis=1)
    assert rec.sample_period == 1.0


def test_an_unknown_time_unit_is_an_error_naming_the_column(tmp_path):
    path = _log(tmp_path / "log.csv", [str(k) for k in range(30)])
    with pytest.raises(ChannelError, match=r"unit of time column 'timestamp' is 'fortnight'"):
        read_trace(path, channels=_map("fortnight"), axis=1)


def test_the_time_unit_under_time_names_any_time_column(tmp_path):
    path = _log(tmp_path / "log.csv", [str(2 * k) for k in range(30)])
    rec = _quiet_read(path, channels=_map(None).updated({}, units={"time": "ms"}), axis=1)
    assert rec.sample_period == 0.002


# -- ISO 8601 date-times ---------------------------------------------------------------------


def test_iso_date_times_read_from_the_start_with_the_date_kept(tmp_path):
    start = datetime(2024, 3, 7, 14, 23, 2, 500_000, tzinfo=UTC)
    times = [start + timedelta(milliseconds=4 * k) for k in range(50)]
    stamps = [t.strftime("%Y-%m-%dT%H:%M:%S.%f") for t in times]
    rec = _quiet_read(_log(tmp_path / "log.csv", stamps), channels=_map(None), axis=1)
    assert rec.sample_period == 0.004
    np.testing.assert_allclose(rec.data.index, [(t - start).total_seconds() for t in times],
                               rtol=0, atol=1e-9)
    assert rec.start_time == stamps[0] and rec.time_unit == "ISO 8601"
    assert rec.time_origin == pytest.approx(start.timestamp(), abs=1e-6)


def test_iso_date_times_in_a_plain_csv_time_column(tmp_path):
    path = tmp_path / "t.csv"
    start = datetime(2025, 1, 2, 3, 4, 5)
    rows = [f"{(start + timedelta(milliseconds=2 * k)).isoformat(timespec='milliseconds')},"
            f"{np.sin(k / 9):.5f}" for k in range(40)]
    path.write_text("time,RP\n" + "\n".join(rows) + "\n")
    rec = _quiet_read(path)
    assert rec.sample_period == 0.002 and rec.data.index[-1] == pytest.approx(0.078)
    assert rec.start_time == "2025-01-02T03:04:05.000"


def test_text_that_is_neither_number_nor_date_names_its_line(tmp_path):
    stamps = [str(0.002 * k) for k in range(10)]
    stamps[4] = "soon"
    with pytest.raises(TraceFormatError, match=r"line 6: time column 'timestamp' holds 'soon'"):
        read_trace(_log(tmp_path / "log.csv", stamps), channels=_map(None), axis=1)


# -- arrays and the stored recording ---------------------------------------------------------


def test_a_mat_file_in_milliseconds(tmp_path):
    path = tmp_path / "run.mat"
    time_ms = 2.0 * np.arange(60) + 7_200_000.0  # two hours of uptime, 2 ms steps
    scipy.io.savemat(path, {"rec": {"t": time_ms, "pos": np.sin(np.arange(60) / 8)}})
    cmap = ChannelMap({"rec.t": "time", "pos": "RP"}, units={"rec.t": "ms"})
    rec = _quiet_read(path, channels=cmap)
    np.testing.assert_allclose(rec.data.index, 0.002 * np.arange(60), rtol=0, atol=1e-9)
    assert rec.time_origin == 7200.0


def test_the_clock_survives_the_parquet_round_trip(tmp_path):
    rec = _quiet_read(MCS500, channels=MCS500_MAP, axis=3)
    again = Recording.from_parquet(rec.to_parquet(tmp_path / "r.parquet"))
    assert (again.time_origin, again.time_unit) == (rec.time_origin, "us")
    assert again.signals["RP"].unit == "mm"


# -- a unit per axis -------------------------------------------------------------------------


def test_a_list_of_units_must_give_one_per_column(tmp_path):
    path = _log(tmp_path / "log.csv", [f"{0.002 * k:.3f}" for k in range(30)])
    cmap = _map(None).updated({}, units={"q": ["deg", "mm", "deg"]})
    with pytest.raises(ChannelError, match=r"lists 3 units for its 2 columns"):
        read_trace(path, channels=cmap, axis=1)
    with pytest.raises(ChannelError, match="one unit, not a list"):
        read_trace(path, channels=_map(None).updated({}, units={"timestamp": ["s"]}), axis=1)


def test_a_unit_list_in_toml_is_kept_per_axis(tmp_path):
    toml = tmp_path / "m.toml"
    toml.write_text('defaults = false\n[layout]\nheader = true\ntime = "timestamp"\n'
                    '[signals]\nq = { columns = ["q0", "q1"] }\n[channels]\nq = "RP"\n'
                    '[units]\nq = ["rad", "m"]\n')
    path = _log(tmp_path / "log.csv", [f"{0.002 * k:.3f}" for k in range(30)])
    rec = _quiet_read(path, channels=toml)
    assert rec.signals["A1.RP"].unit == "rad" and rec.signals["A2.RP"].unit == "m"
    bad = tmp_path / "bad.toml"
    bad.write_text(toml.read_text().replace('["rad", "m"]', '["rad", 3]'))
    with pytest.raises(ChannelError, match="a list of one per axis"):
        read_trace(path, channels=bad)
