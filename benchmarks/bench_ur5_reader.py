"""Benchmark of the readers of a robot's own logs (a UR5 folder, a ROS bag) against one CSV.

Run from the repository root::

    python -m benchmarks.bench_ur5_reader [--repeat 5]

For each run of the UR5 recordings (``data/ur5`` of the repository; README there):

1. ``read_trace(FOLDER, channels="examples/ur5-channels.toml")`` -- seven files of one signal and
   six joints each, cut lines dropped, ends trimmed, joined on their time stamps, every joint's
   columns named -- against the competitor, the same data (the recording's 42 columns over the
   same ticks, written once by pandas into one CSV with a time column) read by
   ``pandas.read_csv``. Target: within 2x.
2. ``read_trace(BAG, channels="examples/ros2-channels.toml")`` of a ROS 2 bag written once from
   the folder's recording with rosbags' writer, in MCAP and in sqlite3: ``/joint_states``
   (position, velocity, effort of six named joints) and the trajectory controller's state
   (``control_msgs``' type, read from the bag's own definition) at every tick -- two messages a
   tick, each deserialized, its joints matched by name -- against ``pandas.read_csv`` of the
   recording's 24 columns the bag gives (RP, AP, V, AC per joint) in one CSV. No target: what a
   bag costs against a table of the same numbers.

Both sides run in this process, alternately, best of ``--repeat`` calls each after one warm-up
call; the ratio is funcnet's time over pandas'. Wall and CPU time are both given: the machine is
shared, and CPU time (the readers run on one thread) is the less disturbed by other processes.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "ur5"
CHANNELS = ROOT / "examples" / "ur5-channels.toml"
ROS2_CHANNELS = ROOT / "examples" / "ros2-channels.toml"
JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
          "wrist_2_joint", "wrist_3_joint"]
STATE = "/scaled_joint_trajectory_controller/controller_state"
# control_msgs/msg/JointTrajectoryControllerState as control_msgs 4.x defines it
STATE_MSG = """std_msgs/Header header
string[] joint_names
trajectory_msgs/JointTrajectoryPoint reference
trajectory_msgs/JointTrajectoryPoint feedback
trajectory_msgs/JointTrajectoryPoint error
trajectory_msgs/JointTrajectoryPoint output
"""


def _timed(function) -> tuple[float, float]:
    """Wall and CPU seconds of one call (both readers run on one thread)."""
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def _best(repeat: int, mine, theirs) -> tuple[list[float], list[float]]:
    """Best wall and CPU seconds of each of two calls, run alternately after one warm-up each
    (so that load hits both alike)."""
    mine(), theirs()
    best_mine, best_theirs = [float("inf")] * 2, [float("inf")] * 2
    for _ in range(repeat):
        best_mine = [min(a, b) for a, b in zip(best_mine, _timed(mine), strict=True)]
        best_theirs = [min(a, b) for a, b in zip(best_theirs, _timed(theirs), strict=True)]
    return best_mine, best_theirs


def _quiet_read(path: Path, channels: Path):
    from funcnet.robot import read_trace

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the cut lines and trimmed ends, said per run
        return read_trace(path, channels=channels)


def _write_bag(recording, path: Path, storage: str) -> None:
    """The recording as a ROS 2 bag of ur_robot_driver's two topics, stamped with its time."""
    import numpy as np
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    store = get_typestore(Stores.ROS2_HUMBLE)
    state = "control_msgs/msg/JointTrajectoryControllerState"
    store.register(get_types_from_msg(STATE_MSG, state))
    kinds = store.types
    empty = np.array([], dtype=float)
    duration = kinds["builtin_interfaces/msg/Duration"](sec=0, nanosec=0)

    def point(values):
        return kinds["trajectory_msgs/msg/JointTrajectoryPoint"](
            positions=values, velocities=empty, accelerations=empty, effort=empty,
            time_from_start=duration)

    table = {role: np.ascontiguousarray(recording.data[[f"A{a}.{role}" for a in range(1, 7)]])
             for role in ("RP", "AP", "V", "AC")}
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    with Writer(path, version=9, storage_plugin=plugin) as writer:
        joints = writer.add_connection("/joint_states", "sensor_msgs/msg/JointState",
                                       typestore=store)
        controller = writer.add_connection(STATE, state, typestore=store)
        for k, t in enumerate(recording.data.index):
            ns = 1_764_000_000_000_000_000 + int(round(t * 1e9))
            header = kinds["std_msgs/msg/Header"](stamp=kinds["builtin_interfaces/msg/Time"](
                sec=ns // 10**9, nanosec=ns % 10**9), frame_id="")
            message = kinds["sensor_msgs/msg/JointState"](
                header=header, name=JOINTS, position=table["AP"][k], velocity=table["V"][k],
                effort=table["AC"][k])
            writer.write(joints, ns, store.serialize_cdr(message, message.__msgtype__))
            message = kinds[state](header=header, joint_names=JOINTS, reference=point(
                table["RP"][k]), feedback=point(table["AP"][k]),
                error=point(table["RP"][k] - table["AP"][k]), output=point(empty))
            writer.write(controller, ns, store.serialize_cdr(message, state))


def _row(name: str, shape: tuple[int, int], mine, theirs) -> tuple[float, float]:
    ratio = (mine[0] / theirs[0], mine[1] / theirs[1])
    print(f"| {name} | {shape[0]} x {shape[1]} | {mine[0] * 1e3:.1f} / {mine[1] * 1e3:.1f} "
          f"| {theirs[0] * 1e3:.1f} / {theirs[1] * 1e3:.1f} | {ratio[0]:.2f}x / "
          f"{ratio[1]:.2f}x |")
    return ratio


def _folders(repeat: int, runs: list[Path], tmp: Path) -> None:
    print("| run | rows x columns | funcnet folder wall / CPU [ms] | pandas one CSV wall / CPU "
          "[ms] | ratio wall / CPU |")
    print("|---|---|---|---|---|")
    ratios = []
    for folder in runs:
        recording = _quiet_read(folder, CHANNELS)
        one = tmp / f"{folder.name}.csv"
        recording.data.to_csv(one, float_format="%.6f")
        mine, theirs = _best(repeat, lambda f=folder: _quiet_read(f, CHANNELS),
                             lambda o=one: pd.read_csv(o))
        ratios.append(_row(folder.name, recording.data.shape, mine, theirs))
    print(f"worst ratio: wall {max(r[0] for r in ratios):.2f}x, CPU "
          f"{max(r[1] for r in ratios):.2f}x (target: within 2x)")


def _bags(repeat: int, runs: list[Path], tmp: Path) -> None:
    print("\n| run, bag storage | rows x columns | funcnet bag wall / CPU [ms] | pandas one CSV "
          "wall / CPU [ms] | ratio wall / CPU |")
    print("|---|---|---|---|---|")
    for folder in runs:
        recording = _quiet_read(folder, CHANNELS)
        for storage in ("mcap", "sqlite3"):
            bag = tmp / f"{folder.name}-{storage}"
            _write_bag(recording, bag, storage)
            read = _quiet_read(bag, ROS2_CHANNELS)
            one = tmp / f"{folder.name}-bag.csv"
            read.data.to_csv(one, float_format="%.6f")
            mine, theirs = _best(repeat, lambda b=bag: _quiet_read(b, ROS2_CHANNELS),
                                 lambda o=one: pd.read_csv(o))
            _row(f"{folder.name}, {storage}", read.data.shape, mine, theirs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; best of {args.repeat} calls each, "
          "alternating")
    runs = sorted(p for p in DATA.iterdir() if p.is_dir())
    with tempfile.TemporaryDirectory() as tmp:
        _folders(args.repeat, runs, Path(tmp))
        _bags(args.repeat, runs, Path(tmp))


if __name__ == "__main__":
    main()
