"""The options the commands share, declared once, and how their values are read and checked.

The network options are built from :class:`~funcnet.parameters.NetworkParameters` (its names,
defaults and descriptions): a command takes them all with :func:`network_options`. Values are
checked before any trace is read, and a :class:`~funcnet.errors.ParameterError` of the library
is re-spelled with the option's name (``--rr must be ...``) by :func:`spelled_as_options`.
"""

from __future__ import annotations

import contextlib
import functools
import inspect
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer

from funcnet.errors import ParameterError
from funcnet.parameters import EvidenceSettings, NetworkParameters

__all__ = [
    "FLAGS", "NO_OPTION", "NetworkOptions", "network_options", "spelled_as_options",
    "evidence_settings", "parse_size", "signal_list", "window_request",
]

# --------------------------------------------------------------------------------------------
# how the command line spells the library's parameters

#: The command line's spelling of each parameter, for the messages of a bad value.
FLAGS = {
    **{name: "--" + name.replace("_", "-") for name in NetworkParameters.names()},
    "degenerate": "--keep-degenerate",
    "resample": "--resample",
    **{name: "--" + name.replace("_", "-")
       for name in ("surrogates", "alpha", "resamples", "surrogate_method", "intervals")},
}
#: Network parameters with no option: explicit thresholds replace the rates.
NO_OPTION = ("eps",)


@contextlib.contextmanager
def spelled_as_options() -> Iterator[None]:
    """Re-spell a :class:`ParameterError` with the option's name (``--rr must be ...``; a bad
    ``--vary`` grid as ``--vary ...``)."""
    try:
        yield
    except ParameterError as exc:
        text = str(exc)
        if text.startswith("grid"):
            raise ParameterError("--vary" + text.removeprefix("grid")) from None
        flag = FLAGS.get(exc.parameter or "")
        if flag is None:
            raise
        raise ParameterError(exc.spelled(flag), parameter=flag, detail=exc.detail) from None


# --------------------------------------------------------------------------------------------
# the network options: one per parameter of NetworkParameters

# The order of the help; every parameter with an option, once (checked below).
_NETWORK_OPTION_ORDER = ("dim", "delay", "rr", "cr", "mu", "mu_c", "mu_t", "metric",
                         "normalize", "measure", "rule", "theiler", "degenerate")
assert sorted(_NETWORK_OPTION_ORDER) == sorted(set(NetworkParameters.names()) - set(NO_OPTION))
# A threshold of its own defaults to mu's.
_DEFAULT_OF = {"mu_c": "mu", "mu_t": "mu"}


def _default_text(name: str) -> str:
    if name in _DEFAULT_OF:
        return f"[default: {FLAGS[_DEFAULT_OF[name]]}]"
    value = NetworkParameters.defaults()[name]
    return f"[default: {'none' if value is None else value}]"


def _network_option(name: str) -> inspect.Parameter:
    """The command parameter of one network parameter (a flag for ``degenerate``)."""
    description = NetworkParameters.descriptions()[name]
    if name == "degenerate":
        annotation: Any = Annotated[bool, typer.Option(FLAGS[name], metavar="", help=description)]
        return inspect.Parameter("keep_degenerate", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                 annotation=annotation, default=False)
    default = NetworkParameters.defaults()[name]
    kind = float if default is None else type(default)
    annotation = Annotated[
        kind | None, typer.Option(FLAGS[name], help=f"{description} {_default_text(name)}")
    ]
    return inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD,
                             annotation=annotation, default=None)


_NETWORK_OPTIONS = tuple(_network_option(name) for name in _NETWORK_OPTION_ORDER)


@dataclass(frozen=True)
class NetworkOptions:
    """The network options as given: ``values`` by parameter name (``None``: not given)."""

    values: dict[str, Any]

    def overrides(self) -> dict[str, Any]:
        """The options given, as :class:`NetworkParameters` overrides (``--normalize none``
        is ``normalize=None``, ``--keep-degenerate`` is ``degenerate="keep"``)."""
        overrides = {k: v for k, v in self.values.items()
                     if v is not None and k not in ("normalize", "keep_degenerate")}
        normalize = self.values["normalize"]
        if normalize is not None:
            overrides["normalize"] = None if normalize.lower() == "none" else normalize
        if self.values["keep_degenerate"]:
            overrides["degenerate"] = "keep"
        return overrides

    def parameters(self) -> NetworkParameters:
        """The parameters, checked; a bad value's message names its option."""
        with spelled_as_options():
            return NetworkParameters(**self.overrides())


Command = TypeVar("Command", bound=Callable[..., Any])


def network_options(command: Command) -> Command:
    """Give a command every network option: its parameter ``network`` (a
    :class:`NetworkOptions`) becomes one option per network parameter, in its place."""
    signature = inspect.signature(command, eval_str=True)
    parameters = list(signature.parameters.values())
    at = [p.name for p in parameters].index("network")
    names = [option.name for option in _NETWORK_OPTIONS]

    @functools.wraps(command)
    def with_options(**given: object) -> Any:
        values = {name: given.pop(name) for name in names}
        return command(**given, network=NetworkOptions(values))

    kind = parameters[at].kind  # keyword-only, so that it may come after options with defaults
    replaced = [*parameters[:at], *(option.replace(kind=kind) for option in _NETWORK_OPTIONS),
                *parameters[at + 1:]]
    with_options.__signature__ = signature.replace(parameters=replaced)  # type: ignore[attr-defined]
    with_options.__annotations__ = {p.name: p.annotation for p in replaced}
    return with_options  # type: ignore[return-value]


# --------------------------------------------------------------------------------------------
# options shared by the commands (one definition, one help text)

Trace = Annotated[Path, typer.Argument(
    help="Trace file: SINUMERIK XML, CSV, Parquet, MATLAB (.mat), HDF5 (.h5), a ROS bag.")]
Channels = Annotated[
    Path | None,
    typer.Option("--channels", help="Channel map TOML: a [channels] table of 'signal name = "
                 "\"ROLE\"' pairs (a MATLAB field bare or with its struct path, quoted; the "
                 "role time names a MATLAB or HDF5 file's time), optional [units]. E.g. "
                 "examples/kuka-kr300-channels.toml."),
]
Axis = Annotated[
    int | None,
    typer.Option("--axis", help="Axis to read (1-based) from a trace of several axes. Without "
                 "it a MATLAB or HDF5 file with one row per axis is read whole, its nodes "
                 "named A1.RP, A2.MP, ..."),
]
Verbose = Annotated[
    bool,
    typer.Option("--verbose", "-v", metavar="",
                 help="Print every warning in full (by default: one line counting them)."),
]
# metavar="": a flag takes no value, so the help shows none (typer's default is "<bool>").
Quiet = Annotated[
    bool,
    typer.Option(
        "--quiet", "-q", metavar="", help="No progress bar (also off when not on a terminal)."
    ),
]
Evidence = Annotated[
    bool,
    typer.Option(
        "--evidence", metavar="",
        help="Add each pair's evidence (funcnet.evidence): a coupling test on joint "
        "recurrences against time-shift surrogates (coupling_p, Benjamini-Hochberg adjusted; "
        "coupled), intervals of C_diff and T_diff, a direction index, and the reading "
        "'evidence' (coupled-directed, coupled, not-coupled, asymmetry-only = an arrow "
        "without coupling evidence, untestable = too few surrogates to reject at alpha "
        "whatever the data) with its evidence_reason. Off: the paper's network only.",
    ),
]
Surrogates = Annotated[
    int | None,
    typer.Option(
        "--surrogates", min=1, metavar="K",
        help="Surrogates of the coupling test (with --evidence). [default: 99, or more so "
        "that one discovery among the pairs can pass: m/alpha - 1 for m pairs]",
    ),
]
Alpha = Annotated[
    float,
    typer.Option("--alpha", help="Level of the coupling test (FDR over a network's pairs, "
                 "with --evidence)."),
]
EvidenceSeed = Annotated[
    int, typer.Option("--seed", min=0, help="Seed of the surrogates and resamples.")
]
Resamples = Annotated[
    int,
    typer.Option("--resamples", min=0, help="Resamples of the C_diff/T_diff intervals (with "
                 "--evidence; 0: no intervals, faster)."),
]
EdgeRule = Annotated[
    str,
    typer.Option(
        "--edge-rule", metavar="RULE",
        help="paper (the mu rule, as published) or interval (directed only when the "
        "difference's interval excludes 0 and |diff| >= mu; needs --evidence).",
    ),
]
SurrogateMethod = Annotated[
    str,
    typer.Option("--surrogate-method", metavar="METHOD",
                 help="Surrogates of the coupling test: shift (circular time shifts) or twin "
                 "(twin surrogates); with --evidence."),
]
Intervals = Annotated[
    str,
    typer.Option("--intervals", metavar="PAIRS",
                 help="Whose C_diff/T_diff intervals are drawn (with --evidence): coupled "
                 "(the pairs whose coupling test rejects at --alpha), testable (those whose "
                 "test can reach --alpha, known before anything is computed) or all (every "
                 "pair's: slowest)."),
]


# --------------------------------------------------------------------------------------------
# values read and checked before a trace is read


def _parse_window(text: str) -> tuple[float, float]:
    start_text, sep, stop_text = text.partition(":")
    try:
        if not sep:
            raise ValueError
        start, stop = float(start_text), float(stop_text)
    except ValueError:
        raise ParameterError(
            f"--window must be START:STOP in seconds (e.g. 1.0:5.0), got {text!r}"
        ) from None
    if not start < stop:
        raise ParameterError(f"--window: START must be less than STOP, got {text!r}")
    return start, stop


def window_request(phase: str | None, window: str | None
                   ) -> tuple[bool, tuple[float, float] | None]:
    """``--phase``/``--window`` checked before the trace is read: ``(whole, bounds)``."""
    if phase is not None and window is not None:
        raise ParameterError("give --phase or --window, not both")
    whole = window is not None and window.strip().lower() == "all"
    return whole, None if window is None or whole else _parse_window(window)


def parse_size(text: str) -> tuple[float, float]:
    """``--size WxH`` in pixels -> inches at 100 dpi."""
    width, sep, height = text.lower().partition("x")
    try:
        if not sep:
            raise ValueError
        w, h = int(width), int(height)
    except ValueError:
        raise ParameterError(f"--size must be WIDTHxHEIGHT in pixels (e.g. 900x900), got "
                             f"{text!r}") from None
    if not (100 <= w <= 10_000 and 100 <= h <= 10_000):
        raise ParameterError(f"--size: each side must be 100 to 10000 pixels, got {text!r}")
    return w / 100, h / 100


def signal_list(text: str | None) -> list[str] | None:
    """``--signals A,B,C`` as a list; a name given twice is an error naming the flag."""
    if text is None:
        return None
    names = [s.strip() for s in text.split(",") if s.strip()]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ParameterError(f"--signals names {', '.join(twice)} more than once")
    if not names:
        raise ParameterError("--signals is empty")
    return names


def evidence_settings(evidence: bool, surrogates: int | None, alpha: float, seed: int,
                      resamples: int, edge_rule: str, surrogate_method: str,
                      intervals: str = "coupled") -> EvidenceSettings | None:
    """The evidence keywords of :func:`funcnet.functional_network`, checked and spelled as the
    command's flags; ``None`` without ``--evidence``."""
    from funcnet.evidence import EDGE_RULES, check_evidence_arguments

    if edge_rule not in EDGE_RULES:
        raise ParameterError(f"--edge-rule must be one of {', '.join(EDGE_RULES)}, got "
                             f"{edge_rule!r}")
    if not evidence:
        if edge_rule == "interval":
            raise ParameterError("--edge-rule interval needs --evidence (it reads the "
                                 "intervals of the evidence)")
        return None
    if edge_rule == "interval" and resamples == 0:
        raise ParameterError("--edge-rule interval needs intervals: --resamples must be >= 1")
    with spelled_as_options():
        check_evidence_arguments(surrogates, alpha, resamples, surrogate_method, intervals)
    return EvidenceSettings(surrogates=surrogates, alpha=alpha, seed=seed, resamples=resamples,
                            edge_rule=edge_rule, surrogate_method=surrogate_method,
                            intervals=intervals)
