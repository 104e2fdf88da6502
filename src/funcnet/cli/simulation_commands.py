"""``funcnet demo`` and ``funcnet simulate``: the simulated axis, and the paper's analyses on it."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from funcnet.cli.messages import progress_bar, reported_errors
from funcnet.cli.options import Quiet

__all__ = ["demo", "simulate"]


def demo(
    out: Annotated[
        Path, typer.Option("--out", help="Folder of the report (and of the simulated plan).")
    ] = Path("out"),
    quiet: Quiet = False,
) -> None:
    """Simulate the paper's plan of experiments, analyse it and write the HTML report.

    The 36 trials of the paper's Table 1 are simulated into OUT/plan (trials already there with
    the same parameters are kept), the analyses of the paper's section 4 run on them, and the
    report is written to OUT. The path of the report is printed.
    """
    # The report counts the analyses' warnings per problem: not printed once per trial here.
    with reported_errors(summarized=True):
        from funcnet.paper.demo import build_demo_report
        from funcnet.sim import paper_plan, write_plan

        plan_dir = out / "plan"
        with progress_bar(quiet, "simulating") as progress:
            write_plan(paper_plan(), plan_dir, progress=progress)
        with progress_bar(quiet, "analysing") as progress:
            report = build_demo_report(plan_dir, out, progress=progress)
    typer.echo(f"report: {report}")


def simulate(
    out: Annotated[Path, typer.Option("--out", help="Folder of the traces (may exist).")],
    plan: Annotated[
        str,
        typer.Option(
            "--plan",
            help="'paper' (the 36 trials of the paper's Table 1), 'backlash-sweep' (reversal "
            "trials over backlash widths, speeds, TCPs and nuisances), 'continuous-sweep' "
            "(smooth set-points turning without a rest, with and without a gravity load) or a "
            "plan TOML file.",
        ),
    ] = "paper",
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seed of the noise.")] = 0,
    quiet: Quiet = False,
) -> None:
    """Simulate a plan of experiments on the model axis and write its traces.

    One SINUMERIK-format XML trace per trial and a manifest of every trial's parameters and
    ground truth are written to OUT. Trials already written with the same parameters are not
    simulated again. The same seed gives the same bytes.
    """
    with reported_errors():
        from funcnet.sim import NAMED_PLANS, named_plan, paper_plan, read_plan, write_plan

        if plan == "paper":
            trials = paper_plan()
        else:
            trials = named_plan(plan) if plan in NAMED_PLANS else read_plan(plan)
        traces = [out / f"{trial.name}.xml" for trial in trials]
        before = [_file_identity(path) for path in traces]
        with progress_bar(quiet, "simulating") as progress:
            manifest = write_plan(trials, out, seed=seed, progress=progress)
        # write_plan replaces a trace it simulates (atomic rename: a new file); one it skips
        # keeps its identity.
        skipped = sum(
            old is not None and old == _file_identity(path)
            for old, path in zip(before, traces, strict=True)
        )
    typer.echo(
        f"{len(trials)} traces and {manifest.name} in {manifest.parent}: "
        f"{len(trials) - skipped} simulated, {skipped} skipped (already there, same parameters)"
    )


def _file_identity(path: Path) -> tuple[int, int, int] | None:
    """(device, inode, modification time) of a file, ``None`` when there is none."""
    try:
        status = path.stat()
    except FileNotFoundError:
        return None
    return status.st_dev, status.st_ino, status.st_mtime_ns
