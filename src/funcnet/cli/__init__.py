"""The ``funcnet`` command line: a thin layer over the library.

Commands: ``demo`` (simulate the paper's plan, analyse it, write the report), ``simulate``,
``network`` (the functional networks of one trace: one per phase, or of one window),
``inspect`` (the engineer's HTML report of traces), ``compare`` (a run against earlier
runs of its program), ``backlash`` (diagnose backlash in traces),
``study`` (a batch from a TOML file), ``report`` (HTML report of a study's results) and
``track add``/``track show`` (a robot's runs kept and trended).
``funcnet COMMAND --help`` is each command's reference.

Conventions:

* An error in the input (every :class:`~funcnet.errors.FuncnetError`, an operating-system error
  on a file, and a usage error: unknown option or command, missing argument, bad value) prints
  exactly one plain-text line, ``funcnet: error: MESSAGE``, on stderr and exits with status 2.
  Nothing is left half-written: outputs are written to a temporary file and renamed.
* Warnings of the library print as one line counting them per problem after the command
  succeeded (``--verbose``: one line each, ``funcnet: warning: MESSAGE``, once per distinct
  message); an error prints its one line only; ``demo`` and ``study`` count them per problem
  (in the report, in the summary lines).
* Progress bars go to stderr, only when stderr is a terminal and ``--quiet`` is not given.
* ``funcnet study`` exits with status 1 when it finished but some tasks could not be analysed
  (listed in ``study.json``), so that scripts notice.

Modules: :mod:`~funcnet.cli.messages` (errors, warnings, progress), :mod:`~funcnet.cli.options`
(the shared options, the network options built from ``NetworkParameters``),
:mod:`~funcnet.cli.selection` (windows and signals of a recording), one module per group of
commands; every command is registered here, in :data:`COMMANDS`, and nowhere else.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Callable, Sequence
from typing import Annotated, Any

import typer
from typer.core import TyperCommand, TyperGroup

from funcnet import __version__
from funcnet.cli.backlash_commands import backlash, backlash_report
from funcnet.cli.compare_command import compare
from funcnet.cli.inspect_command import inspect
from funcnet.cli.messages import one_line
from funcnet.cli.network_commands import network, stability
from funcnet.cli.simulation_commands import demo, simulate
from funcnet.cli.study_commands import report, study
from funcnet.cli.track_commands import track_app

__all__ = ["COMMANDS", "app", "main"]


class _PlainErrorsGroup(TyperGroup):
    """The ``funcnet`` group, printing a usage error as one plain line (exit status 2).

    Typer's own handling prints the usage, a hint and the message in a rich box.
    """

    def main(
        self,
        args: Sequence[str] | None = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        windows_expand_args: bool = True,
        **extra: object,
    ) -> Any:
        forwarded: dict[str, Any] = dict(extra, windows_expand_args=windows_expand_args)
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **forwarded)
        try:
            # Not standalone, click raises its errors here and returns typer.Exit's status, or
            # the command's value (None) when it ends normally.
            status = super().main(args, prog_name, complete_var, False, **forwarded)
        except typer.Abort:
            sys.stderr.write("funcnet: error: aborted\n")
            sys.exit(1)
        except typer.TyperException as exc:
            # typer vendors click; its public base class is all we name. A usage error carries
            # the context; bare `funcnet` raises one whose message is the help itself.
            message = exc.format_message()  # type: ignore[attr-defined]
            ctx = getattr(exc, "ctx", None)
            if ctx is not None and message == ctx.get_help():
                sys.stdout.write(message + "\n")
            else:
                sys.stderr.write(f"funcnet: error: {one_line(message)}\n")
            sys.exit(exc.exit_code)  # type: ignore[attr-defined]
        sys.exit(status if isinstance(status, int) else 0)


class _PlainUsageCommand(TyperCommand):
    """A command whose usage line names its arguments in capitals (``TRACE...``), not in
    braces (typer writes a required argument as ``{trace}``)."""

    def collect_usage_pieces(self, ctx: Any) -> list[str]:
        return [piece.replace("{", "").replace("}", "").upper() if "{" in piece else piece
                for piece in super().collect_usage_pieces(ctx)]

    def get_help(self, ctx: Any) -> str:
        # typer shows a list argument's type as Python's "<list[Path]>"; say "<path>..."
        return _LIST_TYPE.sub(lambda m: f"<{m.group(1).lower()}>...", super().get_help(ctx))


_LIST_TYPE = re.compile(r"<list\[(\w+)\]>")


app = typer.Typer(
    cls=_PlainErrorsGroup,
    name="funcnet",
    help=(
        "Functional networks of robot-axis controller traces, from inter-system recurrence "
        "networks (El Dabett, Hansen & Geier). Start with `funcnet demo`."
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain click help: wrapped cleanly, no "<bool>" on flags
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"funcnet {__version__}")
        raise typer.Exit()


@app.callback()
def _main_options(
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, metavar="", help="Print the version."
        ),
    ] = False,
) -> None:
    """Functional networks of robot-axis controller traces."""


#: Every command, in the order ``funcnet --help`` lists them (its name: the function's, with
#: dashes).
COMMANDS: tuple[Callable[..., None], ...] = (
    demo, simulate, network, backlash, inspect, compare, study, report, stability,
    backlash_report,
)
for _command in COMMANDS:
    app.command(cls=_PlainUsageCommand)(_command)
for _info in track_app.registered_commands:  # track add, track show: the same usage lines
    _info.cls = _PlainUsageCommand
app.add_typer(track_app)


def main() -> None:
    """Entry point of the ``funcnet`` command."""
    # An application's choice, not the library's: idle OpenMP threads that spin instead of
    # sleeping made the kernels ~3x slower on a loaded 2-core machine.
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    # The one choice of matplotlib's backend: a command only writes files, never opens a window.
    os.environ.setdefault("MPLBACKEND", "Agg")
    app(prog_name="funcnet")

