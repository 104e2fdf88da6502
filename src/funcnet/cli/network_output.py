"""What ``funcnet network`` writes: the printed pairs table and the network files.

On a terminal the pairs table is a rich table of its main columns; piped, every column as plain
text but ``direction_reason`` (a sentence; ``-o pairs.csv`` keeps it). The set-point check
comes first. ``-o`` writes JSON, GraphML, the pairs table as CSV, or a drawing; for several
windows one file per window, named after it.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import typer

from funcnet.cli.messages import is_terminal

__all__ = ["network_files", "print_pairs", "print_setpoint_check", "write_network"]


# The pairs-table columns shown on a terminal; piped output and -o .json hold them all.
_MAIN_COLUMNS = ("x", "y", "kind", "direction", "weight", "c_diff", "t_diff")
_WIDE_COLUMNS = ("c_xy", "c_yx", "t_xy", "t_yx", "eps_ordered", "rate_exceeded")
_FLAG_COLUMN = "degenerate"
# With --evidence, the terminal also shows the coupling test's p-value and each pair's reading.
_EVIDENCE_SHOWN = ("coupling_p", "evidence")
_PAIRS_CAPTION = (
    "negative diff reads as x->y (an asymmetry, not proof of a driver); degenerate pairs are "
    "{degenerate}; -o net.json keeps every column"
)
_DEGENERATE_CAPTION = {"drop": "no edges", "keep": "flagged edges"}
_EVIDENCE_CAPTION = (
    "coupling_p: the coupling test's adjusted p-value (it cannot be below 1/(surrogates+1)); "
    "untestable = the test could not have rejected whatever the data (few surrogates: not "
    "uncoupled, evidence_reason says why); asymmetry-only = a tested arrow without coupling "
    "evidence"
)


def _shown_columns(narrow: bool, evidence: bool = False) -> list[str]:
    """The columns of a terminal's table (all names of funcnet.network.schema's pairs, and
    with ``evidence`` two of its evidence columns); a narrow terminal leaves out the weight."""
    main = [c for c in _MAIN_COLUMNS if not (narrow and c == "weight")]
    groups = (main, () if narrow else _WIDE_COLUMNS, (_FLAG_COLUMN,),
              _EVIDENCE_SHOWN if evidence else ())
    return [name for group in groups for name in group]


def _pairs_table(net: Any, columns: Sequence[str], number_format: str) -> Any:
    from rich.table import Table

    pairs = net.pairs
    caption = _PAIRS_CAPTION.format(degenerate=_DEGENERATE_CAPTION[net.parameters.degenerate])
    if "evidence" in pairs.columns:
        caption += "; " + _EVIDENCE_CAPTION
    table = Table(title=net.label, caption=caption)
    for column in columns:
        numeric = pairs[column].dtype.kind == "f"
        table.add_column(column, justify="right" if numeric else "left", no_wrap=True)
    for row in pairs[list(columns)].itertuples(index=False):
        table.add_row(*(format(v, number_format) if isinstance(v, float) else str(v) for v in row))
    return table


def print_pairs(net: Any) -> None:
    """The pairs table: a rich table on a terminal, every column as plain text otherwise.

    A terminal too narrow for the main columns gets fewer of them, at 3 significant digits,
    rather than every number cut short. The ``degenerate`` flag is always shown.
    """
    from funcnet.network.schema import EVIDENCE_COLUMNS, PAIR_COLUMNS

    evidence = "evidence" in net.pairs.columns
    if not is_terminal(sys.stdout):
        # direction_reason is a sentence: whitespace-separated text cannot hold it (-o .csv)
        columns = [*(c for c in PAIR_COLUMNS if c != "direction_reason"),
                   *(EVIDENCE_COLUMNS if evidence else ())]
        typer.echo(net.pairs.loc[:, columns].to_string(index=False))
        return
    from rich.console import Console

    console = Console()
    table = _pairs_table(net, _shown_columns(narrow=False, evidence=evidence), ".4f")
    # Measured without the terminal's limit: the width the table needs to show every number.
    if console.measure(table, options=console.options.update_width(10_000)).maximum > console.width:
        table = _pairs_table(net, _shown_columns(narrow=True, evidence=evidence), ".3g")
    console.print(table)


def setpoint_lines(nets: Sequence[Any]) -> list[str]:
    """The set-point check of the networks (:func:`funcnet.network.setpoint_check`), for the
    rule's arrows and for ``direction``, one sentence each; nothing without a set-point."""
    from funcnet.network.setpoint import setpoint_check

    checks = [setpoint_check(nets, column=column) for column in ("kind", "direction")]
    if not checks[0].pairs:
        return [checks[0].sentence()]
    where = f" (over {len(nets)} networks)" if len(nets) > 1 else ""
    return [f"Set-point check{where}: {checks[0].sentence()}", checks[1].sentence()]


def print_setpoint_check(nets: Sequence[Any], *, tables: bool) -> None:
    """The set-point check before anything else, on stdout (above a terminal's tables, wrapped
    to its width; before the files written); on stderr when the table is piped, which then
    stays plain columns."""
    if tables and not is_terminal(sys.stdout):
        for line in setpoint_lines(nets):
            typer.echo(line, err=True)
        return
    if tables:
        from rich.console import Console

        console = Console()
        for line in setpoint_lines(nets):
            console.print(line, markup=False, highlight=False)
        return
    for line in setpoint_lines(nets):
        typer.echo(line)


def write_network(net: Any, output: Path, inches: tuple[float, float], trace: Path, *,
                  arrows: str = "direction") -> None:
    suffix = output.suffix.lower()
    if suffix in (".json", ".graphml"):
        net.write(output)
        return
    if suffix == ".csv":  # the pairs table, every column (the evidence's too)
        from funcnet._io import write_text_atomic

        write_text_atomic(output, net.pairs.to_csv(index=False))
        return
    from funcnet.plot import network_title, save_network

    save_network(net, output, size=inches, title=network_title(net, source=str(trace)),
                 arrows=arrows)


def network_files(output: Path, labels: Sequence[str]) -> list[Path]:
    """-o for one network is the file; for several, one file per window named after it."""
    if len(labels) == 1:
        return [output]
    slugs = ["-".join("".join(c if c.isalnum() else " " for c in str(label)).split())
             for label in labels]
    return [output.with_name(f"{output.stem}-{slug}{output.suffix}") for slug in slugs]
