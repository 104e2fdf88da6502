"""The parameters of a functional network: every default and every check, once.

:class:`NetworkParameters` is the one contract between the numerical core, the pipeline, the
study files, the paper analyses and the command line. Each of them takes a
``NetworkParameters`` (or builds one from its own spelling: keyword arguments, a TOML table, CLI
options), so a bad value is rejected with the same message wherever it enters; the message
names the parameter, and :meth:`funcnet.errors.ParameterError.spelled` re-spells it for an
entry point (``--rr``, a TOML key).

Targets are named as the arguments (``rr``, ``cr``); what a computation achieved is named
``achieved_rr_x``, ``achieved_rr_y``, ``achieved_cr`` in its results, never ``rr``/``cr``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, TypedDict, Unpack

from funcnet.errors import ParameterError

__all__ = [
    "NetworkParameters",
    "ParameterOverrides",
    "BlockOverrides",
    "EvidenceSettings",
    "METRICS",
    "METRIC_ALIASES",
    "RULES",
    "NORMALIZATIONS",
    "MEASURES",
    "DEGENERATE_POLICIES",
    "PAIR_FIELDS",
    "check_int",
    "check_rate",
    "check_eps_value",
    "canonical_metric",
    "resolve",
]

METRICS = ("euclidean", "supremum", "manhattan")
#: The names SciPy and most of the field use for the same distances.
METRIC_ALIASES = {"chebyshev": "supremum", "maximum": "supremum", "cityblock": "manhattan"}
RULES = ("funcnet", "pyunicorn")
NORMALIZATIONS = ("minmax", "zscore", None)
MEASURES = ("both", "clustering", "transitivity")
#: What happens to a pair whose recurrence structure is degenerate (too few distinct states):
#: ``"drop"`` (default) keeps it in the pairs table only, ``"keep"`` also keeps its edge,
#: flagged ``degenerate``.
DEGENERATE_POLICIES = ("drop", "keep")

#: The parameters a single pair's measures depend on (the others act on the network).
PAIR_FIELDS = ("dim", "delay", "rr", "cr", "eps", "metric", "rule", "theiler")


# --------------------------------------------------------------------------------------------
# checks of single values, shared by every function that takes them


def check_int(value: Any, name: str, minimum: int) -> int:
    """``value`` as an ``int >= minimum``; a :class:`ParameterError` naming ``name`` otherwise.

    Examples
    --------
    >>> check_int(3, "dim", 1)
    3
    >>> check_int(0, "dim", 1)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: dim must be >= 1, got 0
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ParameterError.of(name, f"must be an integer, got {value!r}")
    if value < minimum:
        raise ParameterError.of(name, f"must be >= {minimum}, got {value}")
    return int(value)


def check_rate(rate: Any, name: str) -> float:
    """``rate`` as a float in the open interval (0, 1); names ``name`` otherwise.

    Examples
    --------
    >>> check_rate(2.0, "rr")
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: rr must be in (0, 1), got 2.0
    """
    if isinstance(rate, bool) or not isinstance(rate, numbers.Real):
        raise ParameterError.of(name, f"must be a number in (0, 1), got {rate!r}")
    rate = float(rate)
    if not 0.0 < rate < 1.0:
        raise ParameterError.of(name, f"must be in (0, 1), got {rate}")
    return rate


def check_eps_value(eps: Any, name: str) -> float:
    """A threshold: a positive finite float; names ``name`` otherwise."""
    if isinstance(eps, bool) or not isinstance(eps, numbers.Real):
        raise ParameterError.of(name, f"must be a positive number, got {eps!r}")
    eps = float(eps)
    if not (eps > 0.0 and math.isfinite(eps)):
        raise ParameterError.of(name, f"must be positive and finite, got {eps}")
    return eps


def _check_nonnegative(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError.of(name, f"must be a number >= 0, got {value!r}")
    value = float(value)
    if not math.isfinite(value) or value < 0:
        raise ParameterError.of(name, f"must be finite and >= 0, got {value}")
    return value


def _check_choice(value: Any, name: str, choices: tuple[Any, ...]) -> Any:
    if value not in choices:
        shown = ", ".join("none" if c is None else str(c) for c in choices)
        raise ParameterError.of(name, f"must be one of {shown}; got {value!r}")
    return value


def canonical_metric(metric: Any) -> str:
    """The canonical name of a metric (``chebyshev`` -> ``supremum``, ``cityblock`` ->
    ``manhattan``).

    Examples
    --------
    >>> canonical_metric("chebyshev"), canonical_metric("euclidean")
    ('supremum', 'euclidean')
    """
    if isinstance(metric, str) and metric in METRIC_ALIASES:
        return METRIC_ALIASES[metric]
    if metric not in METRICS:
        names = ", ".join([*METRICS, *METRIC_ALIASES])
        raise ParameterError.of("metric", f"must be one of {names}; got {metric!r}")
    return str(metric)


def _rates(value: Any, name: str) -> float | tuple[float, ...]:
    """One rate, or one per signal (a tuple, in signal order)."""
    if isinstance(value, (list, tuple)):
        if len(value) < 1:
            raise ParameterError.of(name, "must be a rate or one rate per signal, got ()")
        return tuple(check_rate(v, name) for v in value)
    return check_rate(value, name)


def _eps(value: Any) -> tuple[float | tuple[float | None, ...] | None, float | None] | None:
    """``None`` or ``(auto, cross)``; ``auto`` one threshold or one per signal (None: rate)."""
    if value is None:
        return None
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise ParameterError.of(
            "eps",
            "must be (auto, cross): auto one threshold or one per signal, cross one threshold "
            f"(None keeps the rate); got {value!r}",
        )
    auto, cross = value
    if isinstance(auto, (list, tuple)):
        auto = tuple(None if a is None else check_eps_value(a, "eps") for a in auto)
        if all(a is None for a in auto):
            auto = None
    elif auto is not None:
        auto = check_eps_value(auto, "eps")
    cross = None if cross is None else check_eps_value(cross, "eps")
    if auto is None and cross is None:
        return None
    return (auto, cross)


# --------------------------------------------------------------------------------------------
# the contract


@dataclass(frozen=True)
class NetworkParameters:
    """Every parameter of a functional network, validated when it is made.

    Parameters
    ----------
    dim, delay : int
        Embedding dimension and delay in samples (Eq. 1); the paper's illustration uses 3, 10.
    rr : float in (0, 1), or a tuple of them
        Target recurrence rate inside each signal (section 3.4: 0.05), or one per signal in
        signal order (``(rr_x, rr_y)`` for a pair).
    cr : float in (0, 1)
        Target cross-recurrence rate between two signals (section 3.4: 0.05).
    eps : (auto, cross), optional
        Explicit thresholds instead of rates: ``auto`` one threshold for every signal's
        recurrence or one per signal (``(eps_x, eps_y)`` for a pair), ``cross`` one for every
        cross-recurrence; a ``None`` entry keeps its rate.
    metric : {"euclidean", "supremum", "manhattan"}
        Phase-space distance (Eq. 2-3 use Euclidean); ``chebyshev`` and ``cityblock`` are
        accepted and stored as ``supremum`` and ``manhattan``.
    rule : {"funcnet", "pyunicorn"}
        Threshold rule: funcnet's exact order statistic, or pyunicorn 1.0.0's.
    theiler : int >= 0
        Theiler window ``w``: recurrences of a signal with itself need ``|i - j| > w``. ``w = 0``
        excludes only the diagonal, as pyrqa's and RecurrenceAnalysis.jl's ``theiler = 1`` do
        (their window counts the diagonal: theirs is ours + 1). Must be 0 with
        ``rule="pyunicorn"``.
    mu : float >= 0
        Bidirectionality threshold on ``C_diff`` and ``T_diff`` (section 2.4, 3.4: 0.05).
    mu_c, mu_t : float >= 0, optional
        Separate thresholds for ``C_diff`` and ``T_diff``; each defaults to ``mu``.
    normalize : {"minmax", "zscore", None}
        Per-signal scaling inside each window (section 3.3: min-max).
    measure : {"both", "clustering", "transitivity"}
        Which asymmetry decides the edges (both: the intersection, as the code the paper ran).
    degenerate : {"drop", "keep"}
        A pair with a degenerate recurrence structure stays in the pairs table; ``"keep"`` also
        keeps it among the edges, flagged.

    Raises
    ------
    ParameterError
        The first bad value; the message names the parameter (``rr must be in (0, 1), got
        2.0``), and ``.parameter`` holds its name.

    References
    ----------
    Sections 2.2-2.4 (Eq. 1-10) and 3.4 of the paper.

    Examples
    --------
    >>> p = NetworkParameters(rr=0.1, metric="chebyshev")
    >>> p.rr, p.metric, p.mu_clustering
    (0.1, 'supremum', 0.05)
    >>> p.replace(mu=0.1).mu_transitivity
    0.1
    >>> NetworkParameters(rr=2.0)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: rr must be in (0, 1), got 2.0
    """

    dim: int = 3
    delay: int = 10
    rr: float | tuple[float, ...] = 0.05
    cr: float = 0.05
    eps: tuple[Any, Any] | None = None
    metric: str = "euclidean"
    rule: str = "funcnet"
    theiler: int = 0
    mu: float = 0.05
    mu_c: float | None = None
    mu_t: float | None = None
    normalize: str | None = "minmax"
    measure: str = "both"
    degenerate: str = "drop"

    def __post_init__(self) -> None:
        checked: dict[str, Any] = {
            "dim": check_int(self.dim, "dim", 1),
            "delay": check_int(self.delay, "delay", 1),
            "rr": _rates(self.rr, "rr"),
            "cr": check_rate(self.cr, "cr"),
            "eps": _eps(self.eps),
            "metric": canonical_metric(self.metric),
            "rule": _check_choice(self.rule, "rule", RULES),
            "theiler": check_int(self.theiler, "theiler", 0),
            "mu": _check_nonnegative(self.mu, "mu"),
            "mu_c": None if self.mu_c is None else _check_nonnegative(self.mu_c, "mu_c"),
            "mu_t": None if self.mu_t is None else _check_nonnegative(self.mu_t, "mu_t"),
            "normalize": _check_choice(self.normalize, "normalize", NORMALIZATIONS),
            "measure": _check_choice(self.measure, "measure", MEASURES),
            "degenerate": _check_choice(self.degenerate, "degenerate", DEGENERATE_POLICIES),
        }
        if checked["rule"] == "pyunicorn" and checked["theiler"] != 0:
            raise ParameterError.of(
                "theiler",
                f"must be 0 with rule='pyunicorn' (pyunicorn has no Theiler window); "
                f"got {checked['theiler']}",
            )
        for name, value in checked.items():
            object.__setattr__(self, name, value)

    # ----------------------------------------------------------------------------------------
    @property
    def mu_clustering(self) -> float:
        """The threshold on ``C_diff``: ``mu_c`` if given, else ``mu``."""
        return self.mu if self.mu_c is None else self.mu_c

    @property
    def mu_transitivity(self) -> float:
        """The threshold on ``T_diff``: ``mu_t`` if given, else ``mu``."""
        return self.mu if self.mu_t is None else self.mu_t

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(f.name for f in dataclasses.fields(cls) if f.init)

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """Every parameter's default (for help texts and documentation)."""
        return {f.name: f.default for f in dataclasses.fields(cls) if f.init}

    @classmethod
    def descriptions(cls) -> dict[str, str]:
        """Every parameter's one-line description (the command line's help texts).

        Examples
        --------
        >>> NetworkParameters.descriptions()["dim"]
        'Embedding dimension m (Eq. 1).'
        """
        return dict(_DESCRIPTIONS)

    def replace(self, **changes: Unpack[ParameterOverrides]) -> NetworkParameters:
        """A copy with ``changes`` (validated); unknown names raise :class:`ParameterError`."""
        _check_names(changes)
        return dataclasses.replace(self, **changes)

    def for_pair(self, i: int, j: int) -> NetworkParameters:
        """The parameters as the measures of the pair of signals ``i`` and ``j`` hold them:
        per-signal rates (``rr``) and thresholds (``eps``) become that pair's two.

        Examples
        --------
        >>> NetworkParameters(rr=(0.05, 0.1, 0.2)).for_pair(0, 2).rr
        (0.05, 0.2)
        >>> p = NetworkParameters(rr=0.1)
        >>> p.for_pair(0, 1) is p
        True
        """
        changes: dict[str, Any] = {}
        if isinstance(self.rr, tuple):
            changes["rr"] = (self.rr[i], self.rr[j])
        if self.eps is not None and isinstance(self.eps[0], tuple):
            changes["eps"] = ((self.eps[0][i], self.eps[0][j]), self.eps[1])
        return self.replace(**changes) if changes else self

    def to_dict(self) -> dict[str, Any]:
        """The parameters as a plain dict (tuples for ``rr``/``eps``), e.g. for JSON."""
        return {name: getattr(self, name) for name in self.names()}

    @classmethod
    def from_mapping(cls, mapping: Mapping[str, Any],
                     base: NetworkParameters | None = None) -> NetworkParameters:
        """Parameters from a mapping (a TOML table, JSON): unknown keys raise, names them.

        Lists become tuples (TOML and JSON have no tuples).

        Examples
        --------
        >>> NetworkParameters.from_mapping({"rr": 0.1, "eps": [None, 0.2]}).eps
        (None, 0.2)
        >>> NetworkParameters.from_mapping({"radius": 0.1})
        Traceback (most recent call last):
            ...
        funcnet.errors.ParameterError: radius is not a network parameter (dim, delay, rr, cr, \
eps, metric, rule, theiler, mu, mu_c, mu_t, normalize, measure, degenerate)
        """
        _check_names(mapping)
        values = {key: _tuples(value) for key, value in mapping.items()}
        return dataclasses.replace(base or cls(), **values)


# One line per parameter, for the entry points' help texts (the class docstring is the reference).
_DESCRIPTIONS = {
    "dim": "Embedding dimension m (Eq. 1).",
    "delay": "Embedding delay tau in samples (Eq. 1).",
    "rr": "Recurrence rate in each signal, fixes eps_X (Eq. 5).",
    "cr": "Cross-recurrence rate, fixes eps_XY (Eq. 3).",
    "eps": "Explicit thresholds (auto, cross) instead of the rates.",
    "metric": "Distance: euclidean, supremum (alias chebyshev) or manhattan (alias cityblock).",
    "rule": "Threshold rule: funcnet or pyunicorn.",
    "theiler": "Theiler window: exclude pairs with |i-j| <= THEILER (0 excludes only the "
               "diagonal, as pyrqa's theiler=1).",
    "mu": "Edge threshold on C_diff and T_diff (section 2.4).",
    "mu_c": "Edge threshold on C_diff alone.",
    "mu_t": "Edge threshold on T_diff alone.",
    "normalize": "Per-window normalization: minmax, zscore or none (signals as recorded).",
    "measure": "Edges from both, clustering or transitivity.",
    "degenerate": "Keep pairs with a degenerate recurrence structure (too few distinct states) "
                  "as edges, flagged degenerate; by default they are in the pairs table only.",
}


def _tuples(value: Any) -> Any:
    if isinstance(value, list):
        return tuple(_tuples(v) for v in value)
    return value


def _check_names(mapping: Mapping[str, Any]) -> None:
    known = NetworkParameters.names()
    for key in mapping:
        if key not in known:
            raise ParameterError.of(
                str(key), f"is not a network parameter ({', '.join(known)})"
            )


class BlockOverrides(TypedDict, total=False):
    """The :class:`NetworkParameters` keywords of one recurrence block: every field but the
    block's rates and thresholds (``rr``, ``cr``, ``eps``), which such a function names itself."""

    dim: int
    delay: int
    metric: str
    rule: str
    theiler: int
    mu: float
    mu_c: float | None
    mu_t: float | None
    normalize: str | None
    measure: str
    degenerate: str


class ParameterOverrides(BlockOverrides, total=False):
    """The keywords that override a :class:`NetworkParameters` field: one per field, by name.

    Functions that take network parameters as keywords (``functional_network(df, rr=0.1)``)
    type them with ``**overrides: Unpack[ParameterOverrides]`` (PEP 692), so that an editor and
    mypy see every keyword; each is checked when :class:`NetworkParameters` is made.

    Examples
    --------
    >>> sorted(ParameterOverrides.__annotations__) == sorted(NetworkParameters.names())
    True
    """

    rr: float | tuple[float, ...]
    cr: float
    eps: tuple[Any, Any] | None


class EvidenceSettings(TypedDict, total=False):
    """The evidence keywords of :func:`funcnet.network.add_evidence`, for functions that pass
    them on (``**settings: Unpack[EvidenceSettings]``); those not given take its defaults.

    Examples
    --------
    >>> sorted(EvidenceSettings.__annotations__)
    ['alpha', 'edge_rule', 'intervals', 'resamples', 'seed', 'surrogate_method', 'surrogates']
    """

    surrogates: int | None
    alpha: float
    seed: int
    resamples: int
    surrogate_method: str
    edge_rule: str
    intervals: str


def resolve(parameters: NetworkParameters | None, overrides: Mapping[str, Any], *,
            allowed: tuple[str, ...] | None = None) -> NetworkParameters:
    """``parameters`` (default: the defaults) with keyword ``overrides`` applied and validated.

    The entry points take ``parameters=None, **overrides``; ``allowed`` restricts the override
    names to those the function uses (a pair's measures do not take ``mu``).

    Examples
    --------
    >>> resolve(None, {"dim": 2}).dim
    2
    >>> resolve(None, {"mu": 0.1}, allowed=PAIR_FIELDS)
    Traceback (most recent call last):
        ...
    funcnet.errors.ParameterError: mu is not a parameter here (dim, delay, rr, cr, eps, metric, \
rule, theiler)
    """
    if parameters is not None and not isinstance(parameters, NetworkParameters):
        raise ParameterError.of(
            "parameters", f"must be a NetworkParameters, got {type(parameters).__name__}"
        )
    if allowed is not None:
        for key in overrides:
            if key not in allowed:
                raise ParameterError.of(
                    str(key), f"is not a parameter here ({', '.join(allowed)})"
                )
    if all(type(value) in _PLAIN for value in overrides.values()):
        # Plain values: the checked result is remembered (types in the key, so that 3.0 or True
        # is never taken for 3), which saves the checks in a loop of short pairs.
        spelled = tuple(
            (name, type(value), value.hex() if type(value) is float else value)
            for name, value in overrides.items()
        )
        return _resolved(parameters, spelled)
    base = parameters if parameters is not None else NetworkParameters()
    if not overrides:
        return base
    return base.replace(**overrides)


_PLAIN = (int, float, str, type(None))


@functools.lru_cache(maxsize=256)
def _resolved(parameters: NetworkParameters | None,
              spelled: tuple[tuple[str, type, Any], ...]) -> NetworkParameters:
    """:func:`resolve` of plain overrides, spelled as ``(name, type, value)`` (a float by its
    hex digits, so that -0.0 stays itself)."""
    base = parameters if parameters is not None else NetworkParameters()
    if not spelled:
        return base
    changes: dict[str, Any] = {name: float.fromhex(value) if kind is float else value
                               for name, kind, value in spelled}
    _check_names(changes)
    return dataclasses.replace(base, **changes)
