"""The study description: a TOML file read into a frozen :class:`Study`.

Everything a run needs is checked here, when the file is read, before anything is simulated or
hashed: the keys, the recordings, the window kinds and their options, and every network
parameter value of the grid (through :meth:`funcnet.parameters.NetworkParameters.from_mapping`,
so a bad value gives the same message as anywhere else, naming the file and the TOML key).

Length: over 600 lines because every table of the TOML file ([recordings], [[windows]],
[network], [evidence], [stability]) and its checks belong together.
"""

from __future__ import annotations

import dataclasses
import glob
import inspect
import itertools
import os
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from funcnet.errors import ParameterError, StudyError
from funcnet.parameters import NetworkParameters

__all__ = [
    "WINDOW_KINDS",
    "EVIDENCE_KEYS",
    "WindowSpec",
    "Study",
    "load_study",
    "parameter_grid",
    "evidence_settings",
]

#: Window kinds of a study: one per builder of :mod:`funcnet.robot.windows`, and ``range``.
WINDOW_KINDS = ("phases", "fixed", "reversal", "sliding", "range")
BUILDERS = {
    "phases": "phase_windows",
    "fixed": "fixed_windows",
    "reversal": "reversal_windows",
    "sliding": "sliding_windows",
}
#: Default width (s) of ``reversal`` windows, the demo's (:func:`funcnet.paper.run_paper_analyses`
#: ``reversal_width``): the paper's Fig. 11b shows its five shifted windows inside a ~300 ms
#: reversal, so each is at most ~220 ms; the whole detected reversal (~850 ms on the paper plan)
#: would make the +-20/40 ms shifts say little. ``width = ...`` in the TOML overrides it.
REVERSAL_WIDTH = 0.2
#: Parameters whose single value is itself a list in TOML: a list of such lists spans a grid.
_PAIR_VALUED = ("eps",)

_Fail = Callable[[str, str], StudyError]

#: The keys of a study's ``[evidence]`` table besides ``enabled``: the evidence keywords of
#: :func:`funcnet.functional_network`, with its defaults.
EVIDENCE_KEYS: dict[str, Any] = {"surrogates": None, "alpha": 0.05, "seed": 0, "resamples": 200,
                                 "edge_rule": "paper", "surrogate_method": "shift"}


@dataclass(frozen=True)
class WindowSpec:
    """One ``[[windows]]`` entry: a window kind and the options passed to its builder.

    Parameters
    ----------
    kind : str
        One of :data:`WINDOW_KINDS`.
    options : tuple of (str, value)
        Keyword arguments of the builder (``width``, ``step`` for ``"sliding"``; ``start``,
        ``stop`` for ``"range"``; the builder's own options otherwise), sorted by name.

    Examples
    --------
    >>> WindowSpec("range", (("start", 0.5), ("stop", 1.5))).as_dict()
    {'kind': 'range', 'start': 0.5, 'stop': 1.5}
    """

    kind: str
    options: tuple[tuple[str, Any], ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """The specification as a plain dict (``kind`` plus options)."""
        return {"kind": self.kind, **dict(self.options)}


@dataclass(frozen=True)
class Study:
    """A batch of functional networks: recordings x windows x parameter grid.

    Parameters
    ----------
    recordings : tuple of Path
        Trace files (SINUMERIK XML, CSV or Parquet), absolute.
    windows : tuple of WindowSpec
        Window specifications; each expands, per recording, to one or more windows.
    parameters : tuple of (str, tuple)
        Network parameters and their values; several values span a grid (see
        :func:`parameter_grid`). Parameters not named keep the defaults of
        :class:`~funcnet.parameters.NetworkParameters`. Checked by :func:`parameter_grid`
        (and so by :func:`load_study`).
    signals : tuple of str, optional
        Node columns; ``None`` takes every role of each trace plus V, in the paper's order
        (:data:`funcnet.robot.PAPER_NODES`).
    simulated : str, optional
        ``"paper"`` (the paper's plan of experiments) or the path of a plan TOML file: the plan
        is simulated into ``plan_dir`` before the run and its traces are added to ``recordings``.
    plan_dir : Path, optional
        Where the simulated plan is written; ``None`` means ``<out_dir>/plan``.
    seed : int
        Seed of the simulated plan.
    channels : Path, optional
        Channel map (TOML) for reading the traces.
    axis : int, optional
        Axis to read from traces of several axes.
    resample : {"decimate", "interpolate"}, optional
        Bring every trace onto one grid without staircases before anything else
        (:func:`funcnet.robot.read_recording`); None keeps the native grid.
    constant : str
        ``"error"`` (a signal constant in a window fails the task) or ``"drop"`` (it is left out
        of that window's network); see :func:`funcnet.window_networks`.
    base_dir : Path
        Folder that recording names in the results are relative to (the study file's folder).
    source : Path, optional
        The study file, for error messages and provenance.
    evidence : tuple of (str, value)
        The ``[evidence]`` settings (every key of :data:`EVIDENCE_KEYS`, sorted) when it is
        enabled, else empty: each network gets the evidence columns
        (:func:`evidence_settings`).
    stability : tuple of (str, value)
        ``(("grid", ...),)`` when ``[stability]`` is enabled (the grid as written, checked by
        :func:`funcnet.network.stability.check_grid`; ``None`` for the default grid), else
        empty: each window's rows get the stability columns of
        :func:`funcnet.network.stability.edge_stability`.

    Examples
    --------
    >>> Study(parameters=(("delay", (5, 10)),)).to_dict()["parameters"]
    {'delay': [5, 10]}
    """

    recordings: tuple[Path, ...] = ()
    windows: tuple[WindowSpec, ...] = (WindowSpec("phases"),)
    parameters: tuple[tuple[str, tuple[Any, ...]], ...] = ()
    signals: tuple[str, ...] | None = None
    simulated: str | None = None
    plan_dir: Path | None = None
    seed: int = 0
    channels: Path | None = None
    axis: int | None = None
    resample: str | None = None
    constant: str = "drop"
    base_dir: Path = dataclasses.field(default_factory=Path.cwd)
    source: Path | None = None
    evidence: tuple[tuple[str, Any], ...] = ()
    stability: tuple[tuple[str, Any], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The study as JSON-compatible data (paths as strings)."""
        return {
            "source": _str_or_none(self.source),
            "base_dir": str(self.base_dir),
            "recordings": [str(p) for p in self.recordings],
            "simulated": self.simulated,
            "plan_dir": _str_or_none(self.plan_dir),
            "seed": self.seed,
            "channels": _str_or_none(self.channels),
            "axis": self.axis,
            "resample": self.resample,
            "signals": None if self.signals is None else list(self.signals),
            "constant": self.constant,
            "windows": [w.as_dict() for w in self.windows],
            "parameters": {name: list(values) for name, values in self.parameters},
            "evidence": dict(self.evidence) if self.evidence else None,
            "stability": _stability_record(self.stability),
        }


def _stability_record(stability: tuple[tuple[str, Any], ...]) -> dict[str, Any] | None:
    """``[stability]`` as JSON-compatible data (grid values as lists), None when off."""
    if not stability:
        return None
    grid = dict(stability)["grid"]
    return {"grid": None if grid is None else {key: [list(v) if isinstance(v, tuple) else v
                                                     for v in values]
                                               for key, values in grid}}


def evidence_settings(study: Study) -> dict[str, Any] | None:
    """The evidence keywords of :func:`funcnet.functional_network` for a study, or None.

    Parameters
    ----------
    study : Study

    Returns
    -------
    dict or None
        ``surrogates``, ``alpha``, ``seed``, ``resamples``, ``edge_rule``,
        ``surrogate_method`` when the study's ``[evidence]`` is enabled.

    Examples
    --------
    >>> evidence_settings(Study()) is None
    True
    >>> evidence_settings(Study(evidence=(("alpha", 0.1),)))
    {'alpha': 0.1}
    """
    return dict(study.evidence) if study.evidence else None


def _str_or_none(value: object) -> str | None:
    return None if value is None else str(value)


def parameter_grid(study: Study) -> list[NetworkParameters]:
    """Every parameter set of the study's grid, in a fixed order.

    The product is taken over the parameters in the order the study names them, the last one
    varying fastest; parameters the study does not name keep their defaults.

    Parameters
    ----------
    study : Study

    Returns
    -------
    list of NetworkParameters
        One validated parameter set per grid point.

    Raises
    ------
    StudyError
        A value is not a valid network parameter (or not one a study can vary); the message
        names the study file and the parameter as ``[network] <name>``.

    Examples
    --------
    >>> grid = parameter_grid(Study(parameters=(("delay", (5, 10)), ("rr", (0.1,)))))
    >>> [(p.delay, p.rr, p.dim) for p in grid]
    [(5, 0.1, 3), (10, 0.1, 3)]
    >>> parameter_grid(Study(parameters=(("rr", (2.0,)),)))
    Traceback (most recent call last):
        ...
    funcnet.errors.StudyError: study: [network] rr must be in (0, 1), got 2.0
    """
    where = f"{study.source}: " if study.source is not None else "study: "
    names = [name for name, _ in study.parameters]
    grid = []
    for combo in itertools.product(*(values for _, values in study.parameters)):
        mapping = dict(zip(names, combo, strict=True))
        try:
            parameters = NetworkParameters.from_mapping(mapping)
        except ParameterError as exc:
            name = exc.parameter if exc.parameter is not None else "network"
            raise StudyError(exc.spelled(f"[network] {name}", where)) from None
        if isinstance(parameters.rr, tuple) or isinstance(_auto_eps(parameters), tuple):
            # A study's nodes differ between recordings and windows (default roles, constant
            # signals dropped), so a per-signal value has no fixed meaning there.
            name = "rr" if isinstance(parameters.rr, tuple) else "eps"
            raise StudyError(
                f"{where}[network] {name}: one value per signal is not supported in a study "
                "(its signals vary between recordings and windows); give one value"
            )
        grid.append(parameters)
    return grid


def _auto_eps(parameters: NetworkParameters) -> Any:
    return None if parameters.eps is None else parameters.eps[0]


def load_study(path: str | os.PathLike[str]) -> Study:
    """Read a study description from a TOML file.

    Relative paths and glob patterns are taken relative to the file's folder. See
    ``examples/study.toml`` for a documented example. Layout::

        signals = ["RP", "AP", "MP", "V", "RC", "AC"]   # optional
        constant = "error"           # optional: "drop" (default) or "error"
        [recordings]
        paths = ["traces/*.xml"]     # files, run folders (read through channels) or globs
        simulated = "paper"          # optional: "paper" or a plan TOML file
        plan_dir = "plan"            # optional, default <out_dir>/plan
        seed = 0                     # optional, seed of the simulated plan
        channels = "channels.toml"   # optional channel map
        axis = 7                     # optional
        resample = "decimate"        # optional: "decimate" or "interpolate"
        [[windows]]                  # default: one table with kind = "phases"
        kind = "sliding"             # phases | fixed | reversal | sliding | range
        width = 0.6
        step = 0.3
        [network]
        delay = [5, 10]              # a list spans a grid
        eps = [0.2, 0.3]             # eps is a pair (auto, cross): a list of pairs spans a grid
        [evidence]                   # optional: the evidence columns on every row
        enabled = true
        surrogates = 99              # optional, default chosen from the number of pairs
        alpha = 0.05                 # optional, also seed, resamples, edge_rule,
                                     # surrogate_method (funcnet.functional_network's)
        [stability]                  # optional: each pair's stability over a settings grid
        enabled = true
        grid = {mu = [0.03, 0.1]}    # optional, default funcnet.network.stability's grid

    TOML has no null: ``"none"`` stands for None (``normalize = "none"``, ``eps = ["none",
    0.2]``).

    Parameters
    ----------
    path : path-like
        The TOML file.

    Returns
    -------
    Study

    Raises
    ------
    StudyError
        On malformed TOML, an unknown key, a value of the wrong type, an invalid network
        parameter or evidence setting or stability grid, a window kind or option that does not
        exist, or a pattern that matches no file; the one-line message names the file and the
        key.
    OSError
        If the file cannot be read.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.xml").write_text("<traceSession/>")
    >>> _ = (folder / "s.toml").write_text('''
    ... [recordings]
    ... paths = ["*.xml"]
    ... [[windows]]
    ... kind = "range"
    ... start = 0.5
    ... stop = 1.5
    ... [network]
    ... delay = [5, 10]
    ... ''')
    >>> study = load_study(folder / "s.toml")
    >>> [p.name for p in study.recordings], study.windows[0].as_dict()
    (['a.xml'], {'kind': 'range', 'start': 0.5, 'stop': 1.5})
    >>> [p.delay for p in parameter_grid(study)]
    [5, 10]
    >>> _ = (folder / "bad.toml").write_text('[recordings]\\npaths = ["*.xml"]\\n'
    ...                                      '[network]\\nrr = 2.0\\n')
    >>> load_study(folder / "bad.toml")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    funcnet.errors.StudyError: .../bad.toml: [network] rr must be in (0, 1), got 2.0
    """
    source = Path(path).resolve()
    with open(source, "rb") as fh:
        raw = fh.read()
    try:
        doc = tomllib.loads(raw.decode("utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise StudyError(f"{source}: not valid TOML: {exc}") from None
    study = _study_from_document(doc, source)
    parameter_grid(study)  # every value checked now, not at the first task
    return study


def _study_from_document(doc: Mapping[str, Any], source: Path) -> Study:
    base = source.parent

    def fail(key: str, message: str) -> StudyError:
        return StudyError(f"{source}: {key}: {message}")

    _reject_unknown(doc, {"signals", "constant", "recordings", "windows", "network", "evidence",
                          "stability"}, "", fail)
    table = doc.get("recordings", {})
    if not isinstance(table, dict):
        raise fail("recordings", "must be a table ([recordings])")
    _reject_unknown(
        table, {"paths", "simulated", "plan_dir", "seed", "channels", "axis", "resample"},
        "recordings.", fail,
    )
    files = _recording_files(table.get("paths", []), base, fail)
    simulated = _simulated(table.get("simulated"), base, fail)
    if not files and simulated is None:
        raise fail("recordings", "names no recording (give paths or simulated)")
    plan_dir = table.get("plan_dir")
    if plan_dir is not None and not isinstance(plan_dir, str):
        raise fail("recordings.plan_dir", "must be a folder name")
    seed = table.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise fail("recordings.seed", "must be a non-negative integer")
    channels = table.get("channels")
    if channels is not None:
        if not isinstance(channels, str):
            raise fail("recordings.channels", "must be the name of a channel map TOML file")
        channels = (base / channels).resolve()
        if not channels.is_file():
            raise fail("recordings.channels", f"channel map {channels} does not exist")
    axis = table.get("axis")
    if axis is not None and (isinstance(axis, bool) or not isinstance(axis, int) or axis < 0):
        raise fail("recordings.axis", "must be a non-negative integer")
    from funcnet.robot.prepare import RESAMPLE_METHODS

    resample = table.get("resample")
    if resample is not None and resample not in RESAMPLE_METHODS:
        raise fail("recordings.resample", f"must be {' or '.join(map(repr, RESAMPLE_METHODS))}")

    from funcnet.pipeline import CONSTANT_POLICIES

    constant = doc.get("constant", "drop")
    if constant not in CONSTANT_POLICIES:
        raise fail("constant", f"must be {' or '.join(map(repr, CONSTANT_POLICIES))}")

    windows_list = doc.get("windows", [{"kind": "phases"}])
    if not isinstance(windows_list, list) or not windows_list:
        raise fail("windows", "must be one or more [[windows]] tables")
    windows = tuple(
        _window_spec(entry, f"windows[{i}]", fail) for i, entry in enumerate(windows_list)
    )

    return Study(
        recordings=tuple(files),
        windows=windows,
        parameters=_network_table(doc.get("network", {}), fail),
        signals=_signals(doc.get("signals"), fail),
        simulated=simulated,
        plan_dir=None if plan_dir is None else (base / plan_dir).resolve(),
        seed=seed,
        channels=channels,
        axis=axis,
        resample=resample,
        constant=constant,
        base_dir=base,
        source=source,
        evidence=_evidence_table(doc.get("evidence", {}), fail),
        stability=_stability_table(doc.get("stability", {}), fail),
    )


def _enabled(table: Any, name: str, known: set[str], fail: _Fail) -> bool:
    """Whether an optional ``[name]`` table is enabled; its keys checked."""
    if not isinstance(table, dict):
        raise fail(f"[{name}]", "must be a table")
    _reject_unknown(table, {"enabled", *known}, f"[{name}] ", fail)
    enabled = table.get("enabled", bool(table))
    if not isinstance(enabled, bool):
        raise fail(f"[{name}] enabled", "must be true or false")
    return enabled


def _evidence_table(table: Any, fail: _Fail) -> tuple[tuple[str, Any], ...]:
    """``[evidence]`` as sorted (key, value) pairs, every value checked; empty when off."""
    from funcnet.evidence import EDGE_RULES, check_evidence_arguments

    if not _enabled(table, "evidence", set(EVIDENCE_KEYS), fail):
        return ()
    settings = {**EVIDENCE_KEYS, **{k: _from_toml(v) for k, v in table.items()
                                    if k != "enabled"}}
    seed = settings["seed"]
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise fail("[evidence] seed", "must be a non-negative integer")
    if settings["edge_rule"] not in EDGE_RULES:
        raise fail("[evidence] edge_rule", f"must be one of {', '.join(EDGE_RULES)}, got "
                   f"{settings['edge_rule']!r}")
    if settings["edge_rule"] == "interval" and settings["resamples"] == 0:
        raise fail("[evidence] edge_rule", "'interval' needs intervals: resamples >= 1")
    try:
        check_evidence_arguments(settings["surrogates"], settings["alpha"],
                                 settings["resamples"], settings["surrogate_method"])
    except ParameterError as exc:
        name = exc.parameter if exc.parameter is not None else "evidence"
        raise fail(f"[evidence] {name}", str(exc.detail or exc)) from None
    return tuple(sorted(settings.items()))


def _stability_table(table: Any, fail: _Fail) -> tuple[tuple[str, Any], ...]:
    """``[stability]`` as ``(("grid", grid),)``, the grid checked; empty when off."""
    if not _enabled(table, "stability", {"grid"}, fail):
        return ()
    grid = table.get("grid")
    if grid is None:
        return (("grid", None),)
    if not isinstance(grid, dict) or not grid:
        raise fail("[stability] grid", "must be a table of parameter -> list of values")
    from funcnet.network.stability import check_grid

    values = {key: [_from_toml(v) for v in (value if isinstance(value, list) else [value])]
              for key, value in grid.items()}
    try:
        check_grid(values)
    except ParameterError as exc:
        raise fail("[stability] grid", str(exc)) from None
    # kept as written (checked only): edge_stability reads it again on each window
    return (("grid", tuple(sorted((key, tuple(v)) for key, v in values.items()))),)


def _recording_files(patterns: Any, base: Path, fail: _Fail) -> list[Path]:
    if isinstance(patterns, str):
        patterns = [patterns]
    if not isinstance(patterns, list) or not all(isinstance(p, str) for p in patterns):
        raise fail("recordings.paths", "must be a list of file names or glob patterns")
    files: list[Path] = []
    for pattern in patterns:
        matches = sorted(glob.glob(str(base / pattern), recursive=True))
        # A folder is a run of one file per signal, read through the channel map's [signals].
        matches = [m for m in matches if Path(m).is_file() or Path(m).is_dir()]
        if not matches:
            raise fail("recordings.paths", f"{pattern!r} matches no file")
        files.extend(Path(m).resolve() for m in matches)
    return files


def _simulated(simulated: Any, base: Path, fail: _Fail) -> str | None:
    if simulated is None or simulated == "paper":
        return simulated
    if not isinstance(simulated, str):
        raise fail("recordings.simulated", 'must be "paper" or a plan TOML file')
    plan_file = (base / simulated).resolve()
    if not plan_file.is_file():
        raise fail("recordings.simulated", f"plan file {plan_file} does not exist")
    return str(plan_file)


def _signals(signals: Any, fail: _Fail) -> tuple[str, ...] | None:
    if signals is None:
        return None
    if isinstance(signals, str):
        signals = [s.strip() for s in signals.split(",")]
    if not isinstance(signals, list) or not all(isinstance(s, str) and s for s in signals):
        raise fail("signals", "must be a list of signal names")
    if len(set(signals)) != len(signals) or len(signals) < 2:
        raise fail("signals", "must name at least two distinct signals")
    return tuple(signals)


def _network_table(network: Any, fail: _Fail) -> tuple[tuple[str, tuple[Any, ...]], ...]:
    """``[network]`` as (name, values) pairs; the values are checked by :func:`parameter_grid`."""
    if not isinstance(network, dict):
        raise fail("[network]", "must be a table")
    parameters = []
    for name, value in network.items():
        if name in _PAIR_VALUED:
            grid = isinstance(value, list) and bool(value) and isinstance(value[0], list)
        else:
            grid = isinstance(value, list)
        values = [_from_toml(v) for v in (value if grid else [value])]
        if not values:
            raise fail(f"[network] {name}", "an empty list spans no grid")
        if len(set(map(repr, values))) != len(values):
            raise fail(f"[network] {name}", "repeats a value")
        parameters.append((name, tuple(values)))
    return tuple(parameters)


def _from_toml(value: Any) -> Any:
    # TOML has no null and no tuple: "none" stands for None, lists become tuples.
    if isinstance(value, str) and value.lower() == "none":
        return None
    if isinstance(value, list):
        return tuple(_from_toml(v) for v in value)
    return value


def _reject_unknown(table: Mapping[str, Any], known: set[str], prefix: str, fail: _Fail) -> None:
    for key in table:
        if key not in known:
            raise fail(f"{prefix}{key}", f"unknown key (known: {', '.join(sorted(known))})")


def _window_spec(entry: Any, key: str, fail: _Fail) -> WindowSpec:
    if not isinstance(entry, dict):
        raise fail(key, "must be a table")
    kind = entry.get("kind")
    if kind not in WINDOW_KINDS:
        raise fail(f"{key}.kind", f"{kind!r} is not one of {', '.join(WINDOW_KINDS)}")
    options = {k: v for k, v in entry.items() if k != "kind"}
    allowed, required = window_options(kind)
    _reject_unknown(options, allowed, f"{key}.", fail)
    for name in sorted(required):
        if name not in options:
            raise fail(f"{key}.{name}", f"is required for {kind} windows")
    if kind == "range":
        for bound in ("start", "stop"):
            value = options[bound]
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise fail(f"{key}.{bound}", "must be a time in seconds")
        if not options["start"] < options["stop"]:
            raise fail(f"{key}.stop", "must be greater than start")
        options = {k: float(v) for k, v in options.items()}
    if kind == "reversal":
        options.setdefault("width", REVERSAL_WIDTH)
    return WindowSpec(kind, tuple(sorted(options.items())))


def window_options(kind: str) -> tuple[set[str], set[str]]:
    """Options of a window kind and those required: its builder's parameters after the first.

    The kinds built from detected phases also take :func:`~funcnet.robot.detect_phases`'s
    thresholds (``standstill``, ``cruise``, ...). Read from the builders' signatures, so that
    the study follows them.

    Parameters
    ----------
    kind : str
        One of :data:`WINDOW_KINDS`.

    Returns
    -------
    allowed, required : set of str

    Examples
    --------
    >>> [sorted(names) for names in window_options("range")]
    [['start', 'stop'], ['start', 'stop']]
    >>> sorted(window_options("sliding")[1])
    ['step', 'width']
    """
    if kind == "range":
        return {"start", "stop"}, {"start", "stop"}
    import funcnet.robot as robot

    parameters = list(inspect.signature(getattr(robot, BUILDERS[kind])).parameters.values())[1:]
    allowed = {p.name for p in parameters}
    required = {p.name for p in parameters if p.default is inspect.Parameter.empty}
    if kind != "sliding":
        allowed |= phase_options()
    return allowed, required


def phase_options() -> set[str]:
    """The options of :func:`funcnet.robot.detect_phases` (its thresholds).

    Returns
    -------
    set of str

    Examples
    --------
    >>> "standstill" in phase_options()
    True
    """
    from funcnet.robot import detect_phases

    return set(list(inspect.signature(detect_phases).parameters)[1:])
