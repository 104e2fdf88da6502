"""Reading a file: every format a recording comes in, and the channel map that names its signals.

Each module reads one kind of file onto a uniform time grid (:mod:`funcnet.robot.grid`) with its
signals' metadata (:class:`funcnet.robot.SignalInfo`); :mod:`~funcnet.robot.io.read` dispatches
on the file and makes the :class:`~funcnet.robot.Recording`.

=================  ===============================================================================
module             what it reads
=================  ===============================================================================
``read``           :func:`~funcnet.robot.read_trace` (a file as it is, any format) and
                   :func:`~funcnet.robot.read_recording` (the same, ready for analysis)
``channels``       the channel map: roles, units, where each signal is (TOML)
``layout``         its ``[signals]`` and ``[layout]`` tables: a signal's text file and columns
``topics``         its ``[bag]`` table: a signal's topic and message field
``clock``          a time column in s, ms, us, ns or ISO 8601 date-times, as seconds from 0
``sinumerik``      SINUMERIK trace XML (streaming, hardened)
``tables``         CSV and plain Parquet tables
``arrays``         MATLAB (MAT 5, MAT 7.3) and HDF5 files: named arrays, one row per axis
``signal_files``   a folder of one text file per signal (or one log), joined on time stamps
``rosbag``         ROS bags (MCAP, sqlite3, ROS 1): joints by name, topics on one grid
=================  ===============================================================================

Nothing here is exported: the entry points are :func:`funcnet.robot.read_trace` and
:func:`funcnet.robot.read_recording`.
"""
