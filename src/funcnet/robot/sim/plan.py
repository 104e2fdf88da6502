"""The design of experiments: the paper's plan (Table 1), user plans, writing traces.

A :class:`~funcnet.robot.sim.trial.Trial` is one motion of the simulated axis
(:mod:`funcnet.robot.sim.axis`): speed, TCP distance, step, forward or forward-then-reverse, and
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

Every key but ``name``, ``speeds``, ``tcps`` and ``steps`` is optional (``direction`` defaults
to ``"forward"``; knobs left out keep the axis's values). Trial names are
``<group>-v<speed>-p<tcp in dm>-s<step>`` plus ``-b<backlash>``, ``-f<friction_scale>``,
``-k<stiffness_scale>`` for the knobs a group sets, e.g. ``main-v35-p16-s3`` for the paper's
baseline.
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
from funcnet.robot.sim.axis import (
    AxisParameters,
    effective_parameters,
    simulate_trial,
    trial_duration,
)
from funcnet.robot.sim.trial import FAULT_KNOBS, NAME_PATTERN, Trial
from funcnet.robot.sim.writer import write_trace

__all__ = ["Trial", "paper_plan", "read_plan", "write_plan", "MANIFEST_COLUMNS"]

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
    "fingerprint",
    "sha256",
)


def _trial_name(group: str, speed: float, tcp: float, step: float, knobs: dict[str, float]) -> str:
    suffix = "".join(
        f"-{letter}{knobs[k]:g}"
        for k, letter in (("backlash", "b"), ("friction_scale", "f"), ("stiffness_scale", "k"))
        if k in knobs
    )
    return f"{group}-v{speed:g}-p{tcp * 10:g}-s{step:g}{suffix}"


def _expand(
    group: str,
    speeds: Iterable[float],
    tcps: Iterable[float],
    steps: Iterable[float],
    reverse: bool,
    knobs: dict[str, list[float]] | None = None,
) -> list[Trial]:
    knobs = knobs or {}
    trials = []
    for speed, tcp, step, *values in itertools.product(speeds, tcps, steps, *knobs.values()):
        chosen = dict(zip(knobs, values, strict=True))
        trials.append(
            Trial(
                _trial_name(group, speed, tcp, step, chosen),
                group,
                speed,
                tcp,
                step,
                reverse,
                **chosen,
            )
        )
    return trials


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


_GROUP_KEYS = {"name", "speeds", "tcps", "steps", "direction", *FAULT_KNOBS}
_DIRECTIONS = {"forward": False, "forward+reverse": True}


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
        :data:`~funcnet.robot.sim.axis.MAX_TRIAL_DURATION` with the default axis parameters.
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
        where = f"{path}: group {number}"
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
        try:
            expanded = _expand(
                name, lists["speeds"], lists["tcps"], lists["steps"], _DIRECTIONS[direction], knobs
            )
            for trial in expanded:
                trial_duration(trial)
        except ParameterError as exc:
            raise ParameterError(f"{where} ({name}): {exc}") from None
        trials += expanded
    names = [t.name for t in trials]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise StudyError(f"{path}: trial names occur twice: {duplicates}")
    return trials


def _fingerprint(trial: Trial, params: AxisParameters, seed: int) -> str:
    """SHA-256 of everything a trial's bytes depend on."""
    payload = {
        "format": FORMAT_VERSION,
        "trial": dataclasses.asdict(trial),
        "params": dataclasses.asdict(params),
        "seed": int(seed),
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def _simulate_and_write(
    trial: Trial, out_dir: Path, seed: int, params: AxisParameters | None
) -> dict[str, Any]:
    """Simulate one trial, write its trace, return its manifest row (runs in a worker)."""
    sim = simulate_trial(trial, params, seed=seed)
    p = sim.params
    target = out_dir / f"{trial.name}.xml"
    write_trace(
        target, sim.data, axis=1, session_name=trial.name, drive_period=1.0 / p.speed_loop_rate
    )
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
        Noise seed (see :func:`~funcnet.robot.sim.axis.simulate_trial`).
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
        lost motion at the reversal, breakaway time, ...; NaN where a trial has none).

    Raises
    ------
    ParameterError
        Two trials share a name, ``workers`` < 1, or a trial would span more than
        :data:`~funcnet.robot.sim.axis.MAX_TRIAL_DURATION` (checked for every trial before
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
        fingerprint = _fingerprint(trial, effective_parameters(trial, params), seed)
        target = out / f"{trial.name}.xml"
        if (
            old
            and old.get("fingerprint") == fingerprint
            and target.is_file()
            and old.get("sha256") == file_sha256(target)
        ):
            rows[trial.name] = old
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
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(MANIFEST_COLUMNS)
    for name in names:
        writer.writerow([_cell(rows[name][column]) for column in MANIFEST_COLUMNS])
    return write_text_atomic(manifest, buffer.getvalue())
