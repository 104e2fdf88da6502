"""The recordings of a study: trace files, and the traces of a simulated plan of experiments."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path

import pandas as pd

from funcnet._io import file_sha256
from funcnet.study.spec import Study
from funcnet.study.tasks import Source

__all__ = ["simulated_recordings", "sources", "manifest_trials"]


def simulated_recordings(
    study: Study, out: Path, progress: Callable[[int, int, str], None] | None = None
) -> list[Path]:
    """Simulate the study's plan (trials already written are kept) and list its traces.

    Parameters
    ----------
    study : Study
        With ``simulated`` set: ``"paper"`` or a plan TOML file.
    out : Path
        The results folder; the plan goes to ``study.plan_dir`` or ``out/plan``.
    progress : callable, optional
        Passed to :func:`funcnet.sim.write_plan`.

    Returns
    -------
    list of Path
        One trace per trial, in the plan's order.
    """
    from funcnet.sim import paper_plan, read_plan, write_plan

    if study.simulated is None:
        return []
    trials = paper_plan() if study.simulated == "paper" else read_plan(study.simulated)
    plan_dir = study.plan_dir if study.plan_dir is not None else out / "plan"
    write_plan(trials, plan_dir, seed=study.seed, progress=progress)
    return [plan_dir / f"{trial.name}.xml" for trial in trials]


def sources(paths: Iterable[Path], base_dir: Path) -> list[Source]:
    """The recordings as the tasks see them; each folder's ``manifest.csv`` is read once.

    Parameters
    ----------
    paths : iterable of Path
        Trace files.
    base_dir : Path
        The folder recording names are relative to.

    Returns
    -------
    list of Source
        A recording's name in the results is its path relative to ``base_dir`` (absolute when
        outside it); its trial is the name the folder's manifest gives it, else the file's stem;
        its content is hashed (SHA-256).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.csv").write_text("time,RP\\n0,1\\n")
    >>> [(s.name, s.trial) for s in sources([folder / "a.csv"], folder)]
    [('a.csv', 'a')]
    """
    base = base_dir.resolve()
    trial_names: dict[Path, dict[str, str]] = {}
    found = []
    for path in paths:
        path = Path(path).resolve()
        try:
            name = path.relative_to(base).as_posix()
        except ValueError:
            name = path.as_posix()
        if path.parent not in trial_names:
            trial_names[path.parent] = manifest_trials(path.parent / "manifest.csv")
        trial = trial_names[path.parent].get(path.name, path.stem)
        found.append(Source(str(path), name, trial, file_sha256(path)))
    return found


def manifest_trials(manifest: Path) -> dict[str, str]:
    """File name -> trial name from a plan's manifest (:func:`funcnet.sim.write_plan`).

    Parameters
    ----------
    manifest : Path
        A ``manifest.csv`` (columns ``file`` and ``name``); a missing file gives ``{}``.

    Returns
    -------
    dict
        Only files listed once.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> manifest = pathlib.Path(tempfile.mkdtemp()) / "manifest.csv"
    >>> _ = manifest.write_text("file,name\\nplan/a.xml,trial-a\\n")
    >>> manifest_trials(manifest)
    {'a.xml': 'trial-a'}
    """
    if not manifest.is_file():
        return {}
    table = pd.read_csv(manifest, dtype=str)
    if not {"file", "name"} <= set(table.columns):
        return {}
    files = table["file"].map(lambda v: Path(v).name)
    unique = ~files.duplicated(keep=False)  # a file listed twice names no trial
    return dict(zip(files[unique], table["name"][unique], strict=True))
