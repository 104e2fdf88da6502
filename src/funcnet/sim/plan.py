"""The design of experiments: the paper's plan (Table 1), user plans, writing traces.

(Over 600 lines: two plan builders, the TOML reader with its error messages, and the writer.)

A :class:`~funcnet.sim.trial.Trial` is one motion of the simulated axis
(:mod:`funcnet.sim.axis`): speed, TCP distance, step, forward or forward-then-reverse, and
optional fault knobs. :func:`paper_plan` gives the 36 trials of the paper's Table 1,
:func:`read_plan` reads a plan from a TOML file and :func:`write_plan` simulates a plan into a
directory of SINUMERIK traces with a manifest.

A plan file lists groups; each group is the Cartesian product of its lists::

    # my-plan.toml -- `funcnet simulate --plan my-plan.toml --out traces/`
    [[group]]
    name = "main"                  # group label, also the start of each trial's name
    speeds = [35, 175, 350]        # deg/min
    tcps = [1.2, 1.6, 2.0]         # m, TCP distance from the axis
    steps = [1, 3, 10]             # deg; a negative step moves the other way
    direction = "forward"          # or "forward+reverse" (back to the start, same file)

    [[group]]
    name = "worn-gear"
    speeds = [35]
    tcps = [1.6]
    steps = [1]
    direction = "forward+reverse"
    backlash = [0.02, 0.05, 0.1]   # fault knobs, a number or a list (one trial per value):
    friction_scale = 1.5           # backlash in deg (full width), friction and stiffness
    stiffness_scale = 0.7          # as factors of the healthy axis

    [[group]]
    name = "plant-like"
    speeds = [175]
    tcps = [2.0]
    steps = [1]
    direction = "forward+reverse"
    backlash = 0.0083333           # 0.5 arcmin
    noise_scale = [1, 2]           # multiplies every noise source (a knob too)
    seeds = [1, 2, 3]              # one trial per seed (its own noise), "-r<seed>" in the name
    sensors = "real"               # "paper" (default) or "real": the real trace's encoders,
                                   # current noise and 4 ms IPO logging of AP and MP
    arm_model = "elastic"          # "rigid" (default) or "elastic" (a third mass)
    position_feedback = "motor"    # "arm" (default) or "motor": the encoder the loop reads

Every key but ``name``, ``speeds``, ``tcps`` and ``steps`` is optional (``direction`` defaults
to ``"forward"``; knobs left out keep the axis's values). Trial names are
``<group>-v<speed>-p<tcp in dm>-s<step>`` plus ``-b<backlash>``, ``-f<friction_scale>``,
``-k<stiffness_scale>``, ``-n<noise_scale>`` for the knobs a group sets and ``-r<seed>`` for
its seeds, e.g. ``main-v35-p16-s3`` for the paper's baseline. ``backlash`` is the full
dead-zone width in degrees (1 arcmin = 1/60 deg: 0.25 arcmin is ``backlash = 0.0041667``).

Named plans (:data:`NAMED_PLANS`): ``"paper"`` and ``"backlash-sweep"``
(:func:`backlash_sweep_plan`); :func:`read_plan` takes those names too.
"""

from __future__ import annotations

import csv
import dataclasses
import hashlib
import io
import itertools
import json
import multiprocessing
import os
import tomllib
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

from funcnet._io import file_sha256, write_text_atomic
from funcnet.errors import ParameterError, StudyError
from funcnet.sim.axis import (
    AxisParameters,
    effective_parameters,
    simulate_trial,
    trial_duration,
)
from funcnet.sim.trial import FAULT_KNOBS, NAME_PATTERN, OPTIONS, Trial
from funcnet.sim.writer import write_trace

__all__ = [
    "Trial",
    "paper_plan",
    "backlash_sweep_plan",
    "continuous_sweep_plan",
    "named_plan",
    "NAMED_PLANS",
    "read_plan",
    "write_plan",
    "MANIFEST_COLUMNS",
    "OPTIONAL_MANIFEST_COLUMNS",
    "ARCMIN",
    "SWEEP_GRID",
]

#: Bump when the simulator or the writer changes what a trial's bytes are: older files are then
#: written again instead of being skipped.
FORMAT_VERSION = 1

#: Columns of ``manifest.csv``: the trial, the parameters in effect, the ground truth, and the
#: file's fingerprint (inputs) and SHA-256 (bytes).
MANIFEST_COLUMNS = (
    "name",
    "group",
    "file",
    "speed",
    "tcp",
    "step",
    "reverse",
    "backlash",
    "friction_scale",
    "stiffness_scale",
    "seed",
    "duration",
    "motion_start",
    "motion_end",
    "breakaway_time",
    "reversal_time",
    "restart_time",
    "lost_motion",
    "windup_forward",
    "windup_reverse",
    "noise_scale",
    "sensors",
    "arm_model",
    "position_feedback",
    "fingerprint",
    "sha256",
)

#: Columns ``manifest.csv`` gains, before ``fingerprint``, only when a trial of the plan sets
#: them (the continuous sweep's ``arm_load`` and ``profile``): the manifests of the existing
#: plans keep their bytes.
OPTIONAL_MANIFEST_COLUMNS = ("arm_load", "profile")

#: 1 arcmin in degrees: plans and manifests give ``backlash`` in degrees (full dead-zone width).
ARCMIN = 1.0 / 60.0

#: The backlash sweep's grid: backlash in arcmin, speeds in deg/min, TCP in m,
#: friction and stiffness scales, noise seeds and noise scales (1: the real trace's level).
SWEEP_GRID: dict[str, tuple[float, ...]] = {
    "backlash_arcmin": (0.0, 0.25, 0.5, 1.0, 2.0, 4.0),
    "speeds": (35.0, 175.0),
    "tcps": (1.2, 1.6, 2.0),
    "friction_scale": (0.7, 1.0, 1.4),
    "stiffness_scale": (0.7, 1.0, 1.4),
    "seeds": (1.0, 2.0, 3.0),
    "noise_scale": (1.0, 2.0),
}


_LETTERS = (("backlash", "b"), ("friction_scale", "f"), ("stiffness_scale", "k"),
            ("noise_scale", "n"), ("arm_load", "g"))  # fmt: skip


def _trial_name(group: str, speed: float, tcp: float, step: float, knobs: dict[str, float],
                seed: int | None = None) -> str:  # fmt: skip
    suffix = "".join(f"-{letter}{knobs[k]:g}" for k, letter in _LETTERS if k in knobs)
    if seed is not None:
        suffix += f"-r{seed}"
    return f"{group}-v{speed:g}-p{tcp * 10:g}-s{step:g}{suffix}"


def _expand(
    group: str,
    speeds: Iterable[float],
    tcps: Iterable[float],
    steps: Iterable[float],
    reverse: bool,
    knobs: dict[str, list[float]] | None = None,
    seeds: Sequence[int | None] = (None,),
    options: dict[str, str] | None = None,
) -> list[Trial]:
    knobs = knobs or {}
    trials = []
    combos = itertools.product(speeds, tcps, steps, *knobs.values(), seeds)
    chosen_options: dict[str, Any] = dict(options or {})
    for raw in combos:
        combo: tuple[Any, ...] = tuple(raw)  # numbers, the seed last (an int or None)
        speed, tcp, step = (float(v) for v in combo[:3])
        chosen = {k: float(v) for k, v in zip(knobs, combo[3:-1], strict=True)}
        seed = None if combo[-1] is None else int(combo[-1])
        trials.append(
            Trial(
                _trial_name(group, speed, tcp, step, chosen, seed),
                group,
                speed,
                tcp,
                step,
                reverse,
                **chosen,  # type: ignore[arg-type]  # the knobs are float fields
                **chosen_options,
                seed=seed,
            )
        )
    return trials


def backlash_sweep_plan(
    *,
    noise_scales: Sequence[float] = SWEEP_GRID["noise_scale"],
    seeds: Sequence[int] = (1, 2, 3),
    sensors: str = "real",
    arm_model: str = "rigid",
    position_feedback: str = "arm",
    backlash_arcmin: Sequence[float] = SWEEP_GRID["backlash_arcmin"],
    speeds: Sequence[float] = SWEEP_GRID["speeds"],
    tcps: Sequence[float] = SWEEP_GRID["tcps"],
    friction_scales: Sequence[float] = SWEEP_GRID["friction_scale"],
    stiffness_scales: Sequence[float] = SWEEP_GRID["stiffness_scale"],
    group: str = "sweep",
) -> list[Trial]:
    """The systematic backlash sweep: reversal trials over backlash and the plant's nuisances.

    Every trial moves +1 deg and back at once (as the paper's backlash trials), over backlash
    {0, 0.25, 0.5, 1, 2, 4} arcmin x speed {35, 175} deg/min x TCP {1.2, 1.6, 2.0} m x friction
    scale {0.7, 1, 1.4} x stiffness scale {0.7, 1, 1.4} x noise seeds {1, 2, 3} x noise scale
    {1, 2} (the real trace's noise level and twice it): 1944 trials by default, with the
    sensors and logging of the real trace (``sensors="real"``).

    Parameters
    ----------
    noise_scales, seeds, backlash_arcmin, speeds, tcps, friction_scales, stiffness_scales
        The grid (backlash in arcmin here; trials and manifests hold it in degrees).
    sensors, arm_model, position_feedback : str
        Trial options (:data:`~funcnet.sim.trial.OPTIONS`), the same for every trial.
    group : str
        The trials' group and the start of their names.

    Returns
    -------
    list of Trial
        Named ``<group>-v<speed>-p<tcp dm>-s1-b<backlash deg>-f..-k..-n..-r<seed>``.

    Examples
    --------
    >>> plan = backlash_sweep_plan()
    >>> len(plan), plan[0].name
    (1944, 'sweep-v35-p12-s1-b0-f0.7-k0.7-n1-r1')
    >>> round(plan[-1].backlash * 60, 6), plan[-1].sensors
    (4.0, 'real')
    """
    knobs = {
        "backlash": [b * ARCMIN for b in backlash_arcmin],
        "friction_scale": [float(v) for v in friction_scales],
        "stiffness_scale": [float(v) for v in stiffness_scales],
        "noise_scale": [float(v) for v in noise_scales],
    }
    options = {"sensors": sensors, "arm_model": arm_model, "position_feedback": position_feedback}
    return _expand(group, speeds, tcps, (1.0,), True, knobs, [int(s) for s in seeds], options)


def continuous_sweep_plan(
    *,
    backlash_arcmin: Sequence[float] = SWEEP_GRID["backlash_arcmin"],
    arm_loads: Sequence[float] = (0.0, 1000.0),
    speeds: Sequence[float] = SWEEP_GRID["speeds"],
    tcps: Sequence[float] = SWEEP_GRID["tcps"],
    friction_scales: Sequence[float] = SWEEP_GRID["friction_scale"],
    seeds: Sequence[int] = (1,),
    group: str = "smooth",
) -> list[Trial]:
    """Trials in continuous motion: smooth multi-reversal set-points, with and without a load.

    Every trial goes out by 1 deg and back twice along smooth curves (``profile="smooth"``:
    three direction changes without a rest, as a real robot's trajectories), over backlash x
    gravity load on the arm (``arm_load`` N m: 0, and 1000 -- more than the arm's inertia and
    friction torques at these speeds, so the gear torque keeps its sign through every turn, as
    on a robot's axes 2 and 3) x speed x TCP x friction, the real trace's sensors, stiffness and
    noise at their nominal values: 216 trials by default. The truth is the reversal error at
    each turn (:func:`funcnet.sim.axis.reversal_error_truth`), its mean the manifest's
    ``lost_motion``.

    Examples
    --------
    >>> plan = continuous_sweep_plan()
    >>> len(plan), plan[0].profile, plan[-1].name
    (216, 'smooth', 'smooth-v175-p20-s1-b0.0666667-f1.4-g1000-r1')
    """
    knobs = {
        "backlash": [b * ARCMIN for b in backlash_arcmin],
        "friction_scale": [float(v) for v in friction_scales],
        "arm_load": [float(v) for v in arm_loads],
    }
    options = {"sensors": "real", "profile": "smooth"}
    return _expand(group, speeds, tcps, (1.0,), False, knobs, [int(s) for s in seeds], options)


#: Plans known by name (``funcnet simulate --plan NAME``; :func:`named_plan`).
NAMED_PLANS: dict[str, Callable[[], list[Trial]]] = {
    "paper": lambda: paper_plan(),
    "backlash-sweep": lambda: backlash_sweep_plan(),
    "continuous-sweep": lambda: continuous_sweep_plan(),
}


def named_plan(name: str) -> list[Trial]:
    """A plan by name: ``"paper"`` (:func:`paper_plan`) or ``"backlash-sweep"``.

    Raises
    ------
    ParameterError
        Not a name of :data:`NAMED_PLANS`.

    Examples
    --------
    >>> len(named_plan("paper"))
    36
    """
    try:
        return NAMED_PLANS[name]()
    except KeyError:
        raise ParameterError.of(
            "plan", f"must be one of {', '.join(NAMED_PLANS)} or a TOML file; got {name!r}"
        ) from None


def paper_plan() -> list[Trial]:
    """The 36 trials of the paper's design of experiments (Table 1).

    27 main trials (35 / 175 / 350 deg/min x TCP 1.2 / 1.6 / 2.0 m x steps 1 / 3 / 10 deg,
    forward), 3 static-friction trials (1 deg/min, 1 deg, each TCP) and 6 backlash trials
    (+-1 deg forward then reverse in one trace, 35 and 175 deg/min, each TCP).

    Returns
    -------
    list of Trial
        In Table 1's order; the baseline (35 deg/min, 3 deg, 1.6 m) is ``main-v35-p16-s3``.

    References
    ----------
    .. [1] El Dabett, Hansen & Geier, section 3.1 and Table 1.

    Examples
    --------
    >>> plan = paper_plan()
    >>> len(plan), sum(t.reverse for t in plan), plan[4].name
    (36, 6, 'main-v35-p16-s3')
    """
    tcps = (1.2, 1.6, 2.0)
    return (
        _expand("main", (35, 175, 350), tcps, (1, 3, 10), reverse=False)
        + _expand("static-friction", (1,), tcps, (1,), reverse=False)
        + _expand("backlash", (35, 175), tcps, (1,), reverse=True)
    )


_GROUP_KEYS = {"name", "speeds", "tcps", "steps", "direction", "seeds", *FAULT_KNOBS, *OPTIONS}
_DIRECTIONS = {"forward": False, "forward+reverse": True}


def _group_trials(group: Any, where: str) -> list[Trial]:
    """The trials of one ``[[group]]`` of a plan, each checked; ``where`` names the group."""
    if not isinstance(group, dict):
        raise StudyError(f"{where}: must be a table")
    unknown = set(group) - _GROUP_KEYS
    if unknown:
        raise StudyError(f"{where}: unknown key(s) {sorted(unknown)}")
    name = group.get("name")
    if not isinstance(name, str) or not NAME_PATTERN.fullmatch(name):
        raise StudyError(f"{where}: 'name' must be a file-name-safe string")
    lists = {}
    for key in ("speeds", "tcps", "steps", *FAULT_KNOBS):
        if key not in group:
            if key in ("speeds", "tcps", "steps"):
                raise StudyError(f"{where} ({name}): missing key '{key}'")
            continue
        value = group[key]
        values = value if isinstance(value, list) else [value]
        if not values or not all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in values
        ):
            raise StudyError(
                f"{where} ({name}): '{key}' must be a number or a list of "
                f"numbers, got {value!r}"
            )
        lists[key] = [float(v) for v in values]
    direction = group.get("direction", "forward")
    if direction not in _DIRECTIONS:
        raise StudyError(
            f"{where} ({name}): 'direction' must be one of "
            f"{sorted(_DIRECTIONS)}, got {direction!r}"
        )
    knobs: dict[str, list[float]] = {k: lists[k] for k in FAULT_KNOBS if k in lists}
    seeds: list[int | None] = [None]
    if "seeds" in group:
        raw = group["seeds"]
        raw = raw if isinstance(raw, list) else [raw]
        if not raw or not all(
            isinstance(v, int) and not isinstance(v, bool) and v >= 0 for v in raw
        ):
            raise StudyError(
                f"{where} ({name}): 'seeds' must be a non-negative integer or a list of "
                f"them, got {group['seeds']!r}"
            )
        seeds = list(raw)
    options = {}
    for option, words in OPTIONS.items():
        if option in group:
            if group[option] not in words:
                raise StudyError(
                    f"{where} ({name}): '{option}' must be one of {list(words)}, "
                    f"got {group[option]!r}"
                )
            options[option] = group[option]
    try:
        expanded = _expand(
            name, lists["speeds"], lists["tcps"], lists["steps"], _DIRECTIONS[direction],
            knobs, seeds, options,
        )  # fmt: skip
        for trial in expanded:
            trial_duration(trial)
    except ParameterError as exc:
        raise ParameterError(f"{where} ({name}): {exc}") from None
    return expanded


def read_plan(path: str | os.PathLike[str]) -> list[Trial]:
    """Read a plan of experiments from a TOML file (format in the module's docstring).

    Parameters
    ----------
    path : path-like
        The TOML file: one ``[[group]]`` table per group of trials.

    Returns
    -------
    list of Trial
        Group by group, each the product speeds x tcps x steps x knob values.

    Raises
    ------
    StudyError
        The file cannot be read or is not TOML, a key is unknown or missing, a value has the
        wrong type, or two trials get the same name. The message names the file, the group and
        the key.
    ParameterError
        A trial's value is out of range (from :class:`Trial`), or a trial would span more than
        :data:`~funcnet.sim.axis.MAX_TRIAL_DURATION` with the default axis parameters.
        The message names the file, the group and the trial.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> toml = 'group = [{name = "slow", speeds = [1, 35], tcps = [1.6], steps = [1]}]'
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "plan.toml"
    >>> _ = path.write_text(toml)
    >>> [t.name for t in read_plan(path)]
    ['slow-v1-p16-s1', 'slow-v35-p16-s1']
    """
    if isinstance(path, str) and path in NAMED_PLANS and not Path(path).exists():
        return named_plan(path)
    path = Path(path)
    try:
        document = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise StudyError(f"{path}: not a valid TOML plan: {exc}") from None
    except OSError as exc:
        raise StudyError(f"{path}: cannot read the plan: {exc.strerror or exc}") from None
    extra = set(document) - {"group"}
    groups = document.get("group")
    if extra or not isinstance(groups, list) or not groups:
        raise StudyError(
            f"{path}: a plan is a list of [[group]] tables (unknown keys: {sorted(extra)})"
        )
    trials: list[Trial] = []
    for number, group in enumerate(groups, start=1):
        trials += _group_trials(group, f"{path}: group {number}")
    names = [t.name for t in trials]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise StudyError(f"{path}: trial names occur twice: {duplicates}")
    return trials


_LATER_TRIAL_FIELDS = ("noise_scale", "sensors", "arm_model", "position_feedback", "seed",
                       "arm_load", "profile")  # fmt: skip
_LATER_AXIS_FIELDS = ("position_log_period", "noise_scale", "current_drift",
                      "current_drift_frequency", "cogging_torque", "cogging_periods",
                      "arm_model", "link_stiffness", "link_damping",
                      "position_feedback", "arm_load")  # fmt: skip


def _fingerprint(trial: Trial, params: AxisParameters, seed: int) -> str:
    """SHA-256 of everything a trial's bytes depend on."""
    # Fields added after FORMAT_VERSION 1 enter only when they differ from their defaults, so
    # that the files of earlier plans keep their fingerprints (and are not simulated again).
    trial_fields = {k: v for k, v in dataclasses.asdict(trial).items()
                    if not (k in _LATER_TRIAL_FIELDS and v is None)}  # fmt: skip
    defaults = dataclasses.asdict(AxisParameters())
    param_fields = {k: v for k, v in dataclasses.asdict(params).items()
                    if not (k in _LATER_AXIS_FIELDS and v == defaults[k])}  # fmt: skip
    payload = {
        "format": FORMAT_VERSION,
        "trial": trial_fields,
        "params": param_fields,
        "seed": int(seed),
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def _simulate_and_write(
    trial: Trial, out_dir: Path, seed: int, params: AxisParameters | None
) -> dict[str, Any]:
    """Simulate one trial, write its trace, return its manifest row (runs in a worker)."""
    seed = seed if trial.seed is None else trial.seed
    sim = simulate_trial(trial, params, seed=seed)
    p = sim.params
    target = out_dir / f"{trial.name}.xml"
    ipo = {"AP": p.position_log_period, "MP": p.position_log_period}
    write_trace(
        target, sim.data, axis=1, session_name=trial.name, drive_period=1.0 / p.speed_loop_rate,
        intervals=ipo if p.position_log_period != p.log_period else None,
    )  # fmt: skip
    row: dict[str, Any] = {
        "name": trial.name,
        "group": trial.group,
        "file": target.name,
        "speed": trial.speed,
        "tcp": trial.tcp,
        "step": trial.step,
        "reverse": trial.reverse,
        "backlash": p.backlash,
        "friction_scale": p.friction_scale,
        "stiffness_scale": p.stiffness_scale,
        "seed": seed,
        "duration": float(sim.data.index[-1]),
        "noise_scale": p.noise_scale,
        "sensors": trial.sensors or "paper",
        "arm_model": p.arm_model,
        "position_feedback": p.position_feedback,
        "arm_load": p.arm_load,
        "profile": trial.profile or "step",
    }
    row.update({k: sim.truth[k] for k in MANIFEST_COLUMNS if k in sim.truth and k not in row})
    row["fingerprint"] = _fingerprint(trial, p, seed)
    row["sha256"] = file_sha256(target)
    return row


def _read_manifest(path: Path) -> dict[str, dict[str, str]]:
    if not path.is_file():
        return {}
    with open(path, newline="", encoding="utf-8") as fh:
        return {row["name"]: row for row in csv.DictReader(fh) if "name" in row}


def _cell(value: Any) -> str:
    return repr(float(value)) if isinstance(value, float) else str(value)


def write_plan(
    trials: Sequence[Trial],
    out_dir: str | os.PathLike[str],
    *,
    seed: int = 0,
    params: AxisParameters | None = None,
    progress: Callable[[int, int, str], None] | None = None,
    workers: int = 1,
) -> Path:
    """Simulate ``trials`` into ``out_dir``: one SINUMERIK trace per trial and ``manifest.csv``.

    Parameters
    ----------
    trials : sequence of Trial
        E.g. :func:`paper_plan` or :func:`read_plan`; names must be unique.
    out_dir : path-like
        Created if missing; may already hold an earlier run.
    seed : int
        Noise seed (see :func:`~funcnet.sim.axis.simulate_trial`).
    params : AxisParameters, optional
        The axis; the defaults when omitted.
    progress : callable, optional
        Called as ``progress(done, total, name)`` after each trial is written or skipped.
    workers : int
        Processes to simulate in (1: in this process). The paper's plan costs about 3 s of CPU
        in one process; a spawned worker first spends about a second importing, so more than
        one pays off only for long user plans on idle cores.

    Returns
    -------
    Path
        The manifest, ``out_dir / "manifest.csv"``: one row per trial in the given order with
        the columns :data:`MANIFEST_COLUMNS` (parameters in effect and ground truth: backlash,
        lost motion at the reversal, breakaway time, ...; NaN where a trial has none), and
        :data:`OPTIONAL_MANIFEST_COLUMNS` when a trial sets them.

    Raises
    ------
    ParameterError
        Two trials share a name, ``workers`` < 1, or a trial would span more than
        :data:`~funcnet.sim.axis.MAX_TRIAL_DURATION` (checked for every trial before
        anything is simulated or written).

    Notes
    -----
    Every file is written atomically. A trial is skipped -- not simulated again -- when the
    existing manifest lists it with the same fingerprint (trial, axis parameters, seed, format
    version) and its file still has the SHA-256 recorded there; so re-running a demo is fast,
    and a changed or damaged file is rewritten. The same inputs give the same bytes.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> out = tempfile.mkdtemp()
    >>> manifest = write_plan([Trial("quick", "main", speed=350, tcp=1.2, step=1)], out)
    >>> table = pd.read_csv(manifest)
    >>> table.loc[0, "file"], float(table.loc[0, "backlash"])
    ('quick.xml', 0.02)
    """
    trials = list(trials)
    names = [t.name for t in trials]
    if len(set(names)) != len(names):
        raise ParameterError("write_plan: trial names must be unique")
    if not isinstance(workers, int) or workers < 1:
        raise ParameterError(f"write_plan: workers must be a positive integer, got {workers!r}")
    for trial in trials:
        trial_duration(trial, params)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    manifest = out / "manifest.csv"
    previous = _read_manifest(manifest)
    rows: dict[str, dict[str, Any]] = {}
    todo = []
    for trial in trials:
        old = previous.get(trial.name)
        trial_seed = seed if trial.seed is None else trial.seed
        effective = effective_parameters(trial, params)
        fingerprint = _fingerprint(trial, effective, trial_seed)
        target = out / f"{trial.name}.xml"
        if (
            old
            and all(column in old for column in MANIFEST_COLUMNS)  # else an older manifest
            and old.get("fingerprint") == fingerprint
            and target.is_file()
            and old.get("sha256") == file_sha256(target)
        ):
            # a manifest written before the optional columns existed
            rows[trial.name] = {"arm_load": effective.arm_load,
                                "profile": trial.profile or "step", **old}  # fmt: skip
        else:
            todo.append(trial)
    total, done = len(trials), 0
    for name in names:
        if name in rows:
            done += 1
            if progress:
                progress(done, total, name)
    if workers > 1 and len(todo) > 1:
        # spawn, not fork: the caller may run threads (progress bars, a dask client)
        spawn = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=workers, mp_context=spawn) as pool:
            futures = [pool.submit(_simulate_and_write, t, out, seed, params) for t in todo]
            for trial, future in zip(todo, futures, strict=True):
                rows[trial.name] = future.result()
                done += 1
                if progress:
                    progress(done, total, trial.name)
    else:
        for trial in todo:
            rows[trial.name] = _simulate_and_write(trial, out, seed, params)
            done += 1
            if progress:
                progress(done, total, trial.name)
    columns = list(MANIFEST_COLUMNS)
    if any(float(r.get("arm_load") or 0) != 0 or r.get("profile", "step") not in ("step", "")
           for r in rows.values()):  # fmt: skip
        at = columns.index("fingerprint")
        columns[at:at] = OPTIONAL_MANIFEST_COLUMNS
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for name in names:
        writer.writerow([_cell(rows[name][column]) for column in columns])
    return write_text_atomic(manifest, buffer.getvalue())
