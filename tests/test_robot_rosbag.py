"""ROS bags (ROS 2 MCAP and sqlite3, ROS 1) read through a channel map's [bag] table.

The bags are written here with rosbags' own writers from arrays the tests hold; the references
are those arrays, picked by joint name with plain loops, and a UR5 log folder read by the folder
reader.
"""

from __future__ import annotations

import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from funcnet.cli import app
from funcnet.errors import ChannelError, TraceError, TraceFormatError
from funcnet.robot import read_trace
from funcnet.robot.io.channels import channel_map

ROOT = Path(__file__).resolve().parents[1]
ROS2_MAP = ROOT / "examples" / "ros2-channels.toml"
UR5_MAP = ROOT / "examples" / "ur5-channels.toml"
JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
          "wrist_2_joint", "wrist_3_joint"]
STATE = "/scaled_joint_trajectory_controller/controller_state"
STATE_TYPE = "control_msgs/msg/JointTrajectoryControllerState"
START = 1_764_000_000_000_000_000  # ns since the epoch: 2025-11-24T16:00:00 UTC
runner = CliRunner()

# control_msgs/msg/JointTrajectoryControllerState: not among rosbags' built-in types; the
# writer stores these definitions in the bag, and the reader must take them from there.
NEW_STATE = """std_msgs/Header header
string[] joint_names
trajectory_msgs/JointTrajectoryPoint reference
trajectory_msgs/JointTrajectoryPoint feedback
trajectory_msgs/JointTrajectoryPoint error
trajectory_msgs/JointTrajectoryPoint output
"""
OLD_STATE = """Header header
string[] joint_names
trajectory_msgs/JointTrajectoryPoint desired
trajectory_msgs/JointTrajectoryPoint actual
trajectory_msgs/JointTrajectoryPoint error
"""


def ur5_data() -> Path:
    """The UR5 log folders: the repository's data/ur5, else ../shared/data/ur5."""
    for place in (ROOT / "data" / "ur5", ROOT.parent / "shared" / "data" / "ur5"):
        if place.is_dir():
            return place
    pytest.fail("the UR5 recordings are missing (data/ur5, ../shared/data/ur5)")


class _Bag:
    """Messages written with rosbags' writers: ROS 2 (mcap, sqlite3) or ROS 1."""

    def __init__(self, path: Path, storage: str, *, old: bool = False) -> None:
        from rosbags.typesys import Stores, get_types_from_msg, get_typestore

        self.ros1 = storage == "ros1"
        self.store = get_typestore(Stores.ROS1_NOETIC if self.ros1 else Stores.ROS2_HUMBLE)
        self.state_type = STATE_TYPE
        self.store.register(get_types_from_msg(OLD_STATE if old or self.ros1 else NEW_STATE,
                                               self.state_type))
        self.old = old or self.ros1
        if self.ros1:
            from rosbags.rosbag1 import Writer as Writer1

            self.writer = Writer1(path)
        else:
            from rosbags.rosbag2 import StoragePlugin, Writer

            plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
            self.writer = Writer(path, version=9, storage_plugin=plugin)
        self.writer.open()
        self.connections: dict[str, object] = {}
        self.delay = 0  # ns from a message's stamp to when the bag logs it

    def _type(self, name: str):
        return self.store.types[name]

    def _header(self, ns: int):
        time = self._type("builtin_interfaces/msg/Time")(sec=ns // 10**9, nanosec=ns % 10**9)
        extra = {"seq": 0} if self.ros1 else {}
        return self._type("std_msgs/msg/Header")(stamp=time, frame_id="", **extra)

    def _write(self, topic: str, msgtype: str, message, ns: int) -> None:
        if topic not in self.connections:
            self.connections[topic] = self.writer.add_connection(topic, msgtype,
                                                                 typestore=self.store)
        data = (self.store.serialize_ros1(message, msgtype) if self.ros1
                else self.store.serialize_cdr(message, msgtype))
        self.writer.write(self.connections[topic], ns + self.delay, data)

    def joint_states(self, ns: int, names, position, velocity, effort) -> None:
        msgtype = "sensor_msgs/msg/JointState"
        self._write("/joint_states", msgtype, self._type(msgtype)(
            header=self._header(ns), name=list(names), position=np.asarray(position, float),
            velocity=np.asarray(velocity, float), effort=np.asarray(effort, float)), ns)

    def _point(self, positions):
        empty = np.array([], dtype=float)
        return self._type("trajectory_msgs/msg/JointTrajectoryPoint")(
            positions=np.asarray(positions, float), velocities=empty, accelerations=empty,
            effort=empty,
            time_from_start=self._type("builtin_interfaces/msg/Duration")(sec=0, nanosec=0))

    def state(self, ns: int, names, reference, feedback) -> None:
        parts = {"desired" if self.old else "reference": self._point(reference),
                 "actual" if self.old else "feedback": self._point(feedback),
                 "error": self._point(np.subtract(reference, feedback))}
        if not self.old:
            parts["output"] = self._point([])
        self._write(STATE, self.state_type, self._type(self.state_type)(
            header=self._header(ns), joint_names=list(names), **parts), ns)

    def close(self) -> None:
        self.writer.close()


def _signals(n: int) -> dict[str, np.ndarray]:
    """Per tick and joint: a set-point that goes out and back, its follower, speed, current."""
    k = np.arange(n)[:, None]
    j = np.arange(6)[None, :]
    rp = 0.1 * j + 0.004 * (n / 2 - np.abs(k - n / 2))
    return {"RP": rp, "AP": rp - 0.001 * (j + 1), "V": np.cos(k / 7.0 + j), "AC": 0.5 * j + k / n}


def _write(path: Path, storage: str, n: int = 120, *, period_ns: int = 8_000_000,
           controller: bool = True, order=None, state_every: int = 1, state_stop: int | None = None,
           old: bool = False, delay_ns: int = 0) -> dict[str, np.ndarray]:
    """A UR-like bag of ``n`` /joint_states and the controller's state every ``state_every``-th
    tick up to ``state_stop``; /joint_states' joints in ``order`` (indices into JOINTS)."""
    values = _signals(n)
    order = list(range(6)) if order is None else list(order)
    bag = _Bag(path, storage, old=old)
    bag.delay = delay_ns
    for k in range(n):
        ns = START + k * period_ns
        bag.joint_states(ns, [JOINTS[i] for i in order], values["AP"][k, order],
                         values["V"][k, order], values["AC"][k, order])
        if controller and k % state_every == 0 and (state_stop is None or k < state_stop):
            bag.state(ns, JOINTS, values["RP"][k], values["AP"][k])
    bag.close()
    return values


def _read(path: Path, channels=ROS2_MAP, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        recording = read_trace(path, channels=channels, **options)
    return recording, [str(w.message) for w in caught]


def _map(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "map.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("storage", ["mcap", "sqlite3"])
def test_a_bag_folder_and_its_file_read_as_written(tmp_path, storage):
    from rosbags.typesys import Stores, get_typestore

    # control_msgs is not built in: the controller's state is read from the bag's definition
    assert STATE_TYPE not in get_typestore(Stores.ROS2_HUMBLE).fielddefs
    bag = tmp_path / "bag"
    values = _write(bag, storage)
    storage_file = next(p for p in bag.iterdir() if p.suffix in (".mcap", ".db3"))
    for path in (bag, storage_file):
        recording, said = _read(path)
        assert recording.sample_period == 0.008 and len(recording.data) == 120
        assert recording.data.index[0] == 0.0 and recording.start_time.startswith("2025-11-24T16")
        for role in ("RP", "AP", "V", "AC"):
            for axis in range(1, 7):
                column = recording.data[f"A{axis}.{role}"].to_numpy()
                np.testing.assert_array_equal(column, values[role][:, axis - 1])
        assert recording.roles["A3.RP"] == f"{STATE} reference.positions (elbow_joint)"
        units = {c: recording.signals[c].unit for c in ("A1.RP", "A1.AP", "A1.V", "A1.AC")}
        assert units == {"A1.RP": "rad", "A1.AP": "rad", "A1.V": "rad/s", "A1.AC": "A"}
        assert not said


def test_joints_are_matched_by_name_not_by_position(tmp_path):
    _write(tmp_path / "ordered", "mcap")
    _write(tmp_path / "shuffled", "mcap", order=[2, 1, 0, 5, 3, 4])
    ordered, _ = _read(tmp_path / "ordered")
    shuffled, _ = _read(tmp_path / "shuffled")
    assert list(shuffled.data.columns) == list(ordered.data.columns)
    np.testing.assert_array_equal(shuffled.data.to_numpy(), ordered.data.to_numpy())


def test_one_axis_is_the_joint_listed_at_its_place(tmp_path):
    values = _write(tmp_path / "bag", "sqlite3", order=[5, 4, 3, 2, 1, 0])
    recording, _ = _read(tmp_path / "bag", axis=2)
    assert recording.axis == 2 and set(recording.data.columns) == {"RP", "AP", "V", "AC"}
    np.testing.assert_array_equal(recording.data["V"].to_numpy(), values["V"][:, 1])


def test_a_bag_without_the_controller_topic(tmp_path):
    values = _write(tmp_path / "bag", "mcap", controller=False)
    spec = ROS2_MAP.read_text()
    with pytest.raises(ChannelError, match=f"topic {STATE} .*reference.*is not in the bag; its "
                       r"topics are \['/joint_states'\]"):
        read_trace(tmp_path / "bag", channels=ROS2_MAP)
    # Its comment's recipe: AP from /joint_states.
    text = "\n".join(line for line in spec.splitlines()
                     if not line.startswith(("reference", "feedback")))
    text = text.replace("\n[channels]\n", "\n[channels]\njoint_position = \"AP\"\n").replace(
        "\n[bag.signals]\n",
        '\n[bag.signals]\njoint_position = { topic = "/joint_states", field = "position" }\n')
    recording, _ = _read(tmp_path / "bag", channels=_map(tmp_path, text))
    assert "A1.RP" not in recording.data
    np.testing.assert_array_equal(recording.data["A4.AP"].to_numpy(), values["AP"][:, 3])
    assert recording.signals["A4.AP"].unit == "rad"  # REP 103's


def test_two_rates_on_the_finest_grid_the_slower_held(tmp_path):
    # /joint_states every 8 ms, the controller every 40 ms: the grid is 8 ms, RP a staircase.
    values = _write(tmp_path / "bag", "mcap", state_every=5)
    recording, said = _read(tmp_path / "bag")
    assert recording.sample_period == 0.008
    held = [values["RP"][k - k % 5, 0] for k in range(len(recording.data))]
    np.testing.assert_array_equal(recording.data["A1.RP"].to_numpy(), held)
    assert recording.signals["A1.RP"].interval == 0.04
    assert recording.signals["A1.V"].interval == 0.008
    np.testing.assert_array_equal(recording.data["A1.V"].to_numpy(),
                                  values["V"][: len(recording.data), 0])
    assert any("one grid of 0.008 s" in s and f"{STATE} every 0.04 s, each value held" in s
               for s in said), said


def test_stamps_that_jitter_are_interpolated_onto_the_grid(tmp_path):
    # Positions linear in time: interpolated onto the grid, the line itself at every tick.
    n = 200
    jitter = np.random.default_rng(3).uniform(-300_000, 300_000, n)  # +-0.3 ms on 2 ms
    jitter[0] = jitter[-1] = 0
    bag = _Bag(tmp_path / "bag", "mcap")
    stamps = START + np.arange(n) * 2_000_000 + jitter.astype(np.int64)
    for ns in stamps:
        t = (ns - START) / 1e9
        bag.joint_states(int(ns), JOINTS, [t * (j + 1) for j in range(6)], [1.0] * 6,
                         [2.0 + t] * 6)
    bag.close()
    text = ROS2_MAP.read_text().replace('feedback = "AP"', 'joint_position = "AP"')
    text = "\n".join(line for line in text.splitlines()
                     if not line.startswith(("reference", "feedback")))
    text = text.replace(
        "\n[bag.signals]\n",
        '\n[bag.signals]\njoint_position = { topic = "/joint_states", field = "position" }\n')
    recording, said = _read(tmp_path / "bag", channels=_map(tmp_path, text))
    steps = np.diff(stamps) / 1e6
    assert recording.sample_period == float(np.round(np.median(steps) / 1e3, 6))
    time = recording.data.index.to_numpy()
    np.testing.assert_allclose(recording.data["A3.AP"].to_numpy(), 3 * time, rtol=0, atol=1e-8)
    assert any(f"/joint_states (steps {steps.min():.4g}-{steps.max():.4g} ms, off the grid) "
               "interpolated linearly" in s for s in said), said


def test_a_topic_cut_short_trims_the_recording_and_says_so(tmp_path):
    values = _write(tmp_path / "bag", "sqlite3", state_stop=90)
    recording, said = _read(tmp_path / "bag")
    assert len(recording.data) == 90
    np.testing.assert_array_equal(recording.data["A2.RP"].to_numpy(), values["RP"][:90, 1])
    assert any("read over the span they share, 0-0.712 s: /joint_states (last at 0.952 s)" in s
               for s in said), said


@pytest.mark.parametrize("old", [False, True])
def test_the_older_controller_state_reads_desired_and_actual(tmp_path, old):
    values = _write(tmp_path / "bag", "mcap", old=old)
    recording, _ = _read(tmp_path / "bag")
    field = "desired" if old else "reference"
    assert recording.roles["A1.RP"] == f"{STATE} {field}.positions (shoulder_pan_joint)"
    np.testing.assert_array_equal(recording.data["A6.AP"].to_numpy(), values["AP"][:, 5])


def test_a_ros1_bag(tmp_path):
    values = _write(tmp_path / "run.bag", "ros1", order=[1, 0, 2, 3, 4, 5])
    recording, _ = _read(tmp_path / "run.bag")
    for role in ("RP", "AP", "V", "AC"):
        np.testing.assert_array_equal(recording.data[f"A2.{role}"].to_numpy(), values[role][:, 1])


def test_log_time_instead_of_the_header_stamp(tmp_path):
    # Logged 1 ms after each stamp: the same values, the same relative time.
    _write(tmp_path / "bag", "mcap", delay_ns=1_000_000)
    text = ROS2_MAP.read_text().replace('time = "header"', 'time = "log"')
    recording, _ = _read(tmp_path / "bag", channels=_map(tmp_path, text))
    stamped, _ = _read(tmp_path / "bag")
    np.testing.assert_array_equal(recording.data.to_numpy(), stamped.data.to_numpy())
    assert recording.start_time == "2025-11-24T16:00:00.001000+00:00"
    assert stamped.start_time == "2025-11-24T16:00:00+00:00"


def _corrupt(tmp_path: Path) -> Path:
    whole = next((tmp_path / "bag").glob("*.mcap")).read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(whole[: len(whole) // 2])  # the recorder stopped mid-file
    return cut


@pytest.mark.parametrize("case, error, message", [
    ("topic", ChannelError, r"topic /joint_state \(of joint_velocity, joint_effort\) is not in "
     r"the bag; its topics are \['/joint_states', '/scaled"),
    ("joint", ChannelError, r"joint 'elbow' of \[bag\] joints is not among the names "
     f"{STATE} carries \\(message 1\\): \\['shoulder_pan_joint'"),
    ("field", ChannelError, r"'joint_velocity': /joint_states \(sensor_msgs/msg/JointState\) "
     r"has no field 'velocities'; its fields are \['header', 'name', 'position', 'velocity', "
     r"'effort'\]"),
    ("corrupt", TraceFormatError, r"cut.mcap: not a readable ROS bag: File end magic is "
     "invalid"),
    ("missing", TraceError, "nothing.mcap: no such file"),
    ("folder", TraceFormatError, "a folder without metadata.yaml: not a ROS 2 bag's folder"),
])
def test_bad_input_raises_an_error_naming_it_and_the_cli_says_it_in_one_line(
        tmp_path, case, error, message):
    _write(tmp_path / "bag", "mcap")
    path, text = tmp_path / "bag", ROS2_MAP.read_text()
    if case == "topic":
        text = text.replace('topic = "/joint_states"', 'topic = "/joint_state"')
    elif case == "joint":
        text = text.replace('"elbow_joint",', '"elbow",')
    elif case == "field":
        text = text.replace('field = "velocity"', 'field = "velocities"')
    elif case == "corrupt":
        path = _corrupt(tmp_path)
    elif case == "missing":
        path = tmp_path / "nothing.mcap"
    else:
        (tmp_path / "bag" / "metadata.yaml").unlink()  # the .mcap alone, in a folder
    channels = _map(tmp_path, text)
    with pytest.raises(error, match=message):
        read_trace(path, channels=channels)
    result = runner.invoke(app, ["inspect", str(path), "--channels", str(channels),
                                 "--no-evidence", "-q", "-o", str(tmp_path / "page")])
    assert result.exit_code == 2, result.output
    assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output
    assert str(path.name) in result.output


def test_a_map_for_a_bag_is_checked(tmp_path):
    with pytest.raises(ChannelError, match=r"\[bag\]: joints must list"):
        channel_map(_map(tmp_path, '[bag]\njoints = []\n[bag.signals]\n'
                                   'q = { topic = "/j", field = "position" }\n'))
    # a name repeated but for blanks is the same joint twice
    with pytest.raises(ChannelError, match=r"\[bag\]: joints must list"):
        channel_map(_map(tmp_path, '[bag]\njoints = ["a", " a"]\n[bag.signals]\n'
                                   'q = { topic = "/j", field = "position" }\n'))
    with pytest.raises(ChannelError, match=r"time must be \"header\"|time must be"):
        channel_map(_map(tmp_path, '[bag]\ntime = "stamp"\njoints = ["a"]\n[bag.signals]\n'
                                   'q = { topic = "/j", field = "position" }\n'))
    _write(tmp_path / "bag", "mcap")
    with pytest.raises(ChannelError, match="entry 'q_target' = 'RP' names no signal of"):
        read_trace(tmp_path / "bag", channels=_map(
            tmp_path, ROS2_MAP.read_text().replace('reference = "RP"', 'q_target = "RP"')))
    # a map that keeps the SINUMERIK defaults (no "defaults = false") reads the same
    kept, _ = _read(tmp_path / "bag", channels=_map(
        tmp_path, ROS2_MAP.read_text().replace("defaults = false", "defaults = true")))
    assert kept.data.shape == (120, 24)
    with pytest.raises(ChannelError, match=r"a ROS bag is read through a channel map with a "
                       r"\[bag\] table"):
        read_trace(tmp_path / "bag", channels=UR5_MAP)


def _ur5_bag(path: Path, storage: str, run: Path, seconds: float | None = None):
    """A bag of a UR5 log folder (its first ``seconds``): /joint_states (q_actual, qd_actual,
    i_actual) and the controller's state (q_target, q_actual), stamped with the folder's time."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the folder's cut lines and trimmed ends
        folder = read_trace(run, channels=UR5_MAP)
    data = folder.data if seconds is None else folder.data.loc[: seconds]
    bag = _Bag(path, storage)

    def joints(name: str, k: int) -> np.ndarray:
        return np.array([data[f"A{a}.{name}"].iloc[k] for a in range(1, 7)])

    for k, t in enumerate(data.index):
        ns = START + int(round(t * 1e9))
        bag.joint_states(ns, JOINTS, joints("AP", k), joints("V", k), joints("AC", k))
        bag.state(ns, JOINTS, joints("RP", k), joints("AP", k))
    bag.close()
    return folder


@pytest.mark.parametrize("storage", ["mcap", "sqlite3"])
def test_a_bag_of_a_ur5_run_gives_the_run_folders_values(tmp_path, storage):
    run = ur5_data() / "Movement_No8_Singularity_Free_1"
    folder = _ur5_bag(tmp_path / "bag", storage, run)
    recording, _ = _read(tmp_path / "bag")
    assert recording.sample_period == folder.sample_period == 0.008
    np.testing.assert_array_equal(recording.data.index, folder.data.index - folder.data.index[0])
    for column in [f"A{a}.{role}" for a in range(1, 7) for role in ("RP", "AP", "V", "AC")]:
        np.testing.assert_array_equal(recording.data[column].to_numpy(),
                                      folder.data[column].to_numpy(), err_msg=column)
        assert recording.signals[column].unit == folder.signals[column].unit, column


def test_inspect_writes_the_robots_page_and_the_shoulders(tmp_path):
    run = ur5_data() / "Movement_No8_Singularity_Free_1"
    _ur5_bag(tmp_path / "bag", "mcap", run, seconds=4.0)  # the first move of every joint
    out = tmp_path / "robot"
    result = runner.invoke(app, ["inspect", str(tmp_path / "bag"), "--channels", str(ROS2_MAP),
                                 "--no-evidence", "-q", "-o", str(out)])
    assert result.exit_code == 0, result.output
    robot = (out / "index.html").read_text()
    names = tomllib.loads(ROS2_MAP.read_text())["axis_names"]
    assert all(name in robot for name in names)
    assert "Converted to degrees" in robot
    shoulder = tmp_path / "shoulder"
    result = runner.invoke(app, ["inspect", str(tmp_path / "bag"), "--channels", str(ROS2_MAP),
                                 "--axis", "2", "--no-evidence", "-q", "-o", str(shoulder)])
    assert result.exit_code == 0, result.output
    assert "What axis 2 (shoulder) does" in (shoulder / "index.html").read_text()
