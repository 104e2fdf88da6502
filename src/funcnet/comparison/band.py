"""How far RUN departs from its references, signal by signal: the references' band.

Given RUN aligned on each reference (:func:`~funcnet.comparison.align.align_on_setpoints`),
every tick of RUN has a set of reference values: one per reference and cycle through that
point of the program. Their mean is the band's centre; their spread (standard deviation),
averaged along the program over ``smooth`` seconds, is how much runs of the program differ
there. With one reference the values come from its cycles only: the spread is that *within one
run*, which leaves out what differs between runs (warm-up, payload, another day) and is
therefore smaller -- more of RUN reads as changed (:attr:`Band.within_run`).

RUN's departure at a tick is ``|run - centre| / (spread * sqrt(1 + 1/k))`` for ``k`` reference
values (the difference of a new run from a mean of ``k`` has that spread), averaged over
``detail`` seconds; it is in multiples of the references' spread.

Examples
--------
>>> import numpy as np
>>> from funcnet.comparison.align import Alignment
>>> rng = np.random.default_rng(1)
>>> refs = [rng.normal(0, 0.1, 400) for _ in range(3)]
>>> run = rng.normal(0, 0.1, 400); run[200:220] += 2.0             # one departure
>>> same = np.arange(400)[:, None]
>>> align = [Alignment(same, np.zeros(400), 0.02)] * 3
>>> b = reference_band(run, refs, align, period=0.01, smooth=0.5, detail=0.05)
>>> bool(b.size[210] > 6), bool(np.median(b.size) < 2), b.within_run
(True, True, False)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from funcnet.comparison.align import Alignment
from funcnet.errors import ParameterError

__all__ = ["Band", "reference_band", "SPREAD_FLOOR", "reference_values"]

#: A spread is never taken below this fraction of its median along the program: where the few
#: reference values happen to agree, a small difference would otherwise read as a huge one.
SPREAD_FLOOR = 0.25


@dataclass(frozen=True)
class Band:
    """One signal of RUN against the references' band, tick by tick of RUN.

    Attributes
    ----------
    run, centre, spread : ndarray
        RUN's values, the references' mean and their spread (standard deviation along the
        program), in the signal's unit; NaN where no reference covers RUN.
    count : ndarray of int
        Reference values per tick (references times cycles).
    size : ndarray
        RUN's departure in multiples of the spread (module notes); NaN where not compared.
    within_run : bool
        The spread comes from the cycles of one run (one reference).
    filled : float
        Fraction of the compared ticks where fewer than two reference values lay within
        ``smooth`` seconds: their spread is the signal's median spread along the program.
    """

    run: np.ndarray = field(repr=False)
    centre: np.ndarray = field(repr=False)
    spread: np.ndarray = field(repr=False)
    count: np.ndarray = field(repr=False)
    size: np.ndarray = field(repr=False)
    within_run: bool
    filled: float


def reference_values(reference: np.ndarray, alignment: Alignment) -> np.ndarray:
    """The values of one reference signal at every match of each tick of RUN.

    Returns
    -------
    ndarray, shape (n_run, k)
        NaN where a tick has fewer than ``k`` matches.
    """
    idx = alignment.matches
    values = np.asarray(reference, dtype=np.float64)[np.clip(idx, 0, None)]
    return np.where(idx >= 0, values, np.nan)


def _rolling_mean(x: np.ndarray, width: int) -> np.ndarray:
    """Centred moving mean over ``width`` ticks, ignoring NaN (NaN where all are)."""
    ok = np.isfinite(x)
    kernel = np.ones(max(width, 1))
    total = np.convolve(np.where(ok, x, 0.0), kernel, mode="same")
    n = np.convolve(ok.astype(np.float64), kernel, mode="same")
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, total / n, np.nan)


def reference_band(
    run: np.ndarray,
    references: Sequence[np.ndarray],
    alignments: Sequence[Alignment],
    *,
    period: float,
    smooth: float = 0.5,
    detail: float = 0.1,
) -> Band:
    """RUN's signal against the band of the same signal in the references (module notes).

    Parameters
    ----------
    run : ndarray, shape (n,)
        The signal of RUN.
    references : sequence of ndarray
        The same signal of each reference.
    alignments : sequence of Alignment
        RUN aligned on each reference, in the same order.
    period : float
        Sample period in seconds.
    smooth : float
        Seconds along the program over which the references' spread is averaged.
    detail : float
        Seconds over which RUN's departure is averaged (a single noisy tick is no change).

    Returns
    -------
    Band

    Raises
    ------
    ParameterError
        No reference, or references and alignments of different numbers.
    """
    if not references or len(references) != len(alignments):
        raise ParameterError.of("references", "one alignment per reference, at least one")
    run = np.asarray(run, dtype=np.float64)
    values = np.concatenate([reference_values(r, a) for r, a in
                             zip(references, alignments, strict=True)], axis=1)
    count = np.isfinite(values).sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        centre = np.where(count > 0, np.nansum(values, axis=1) / count, np.nan)
        deviation = np.where(np.isfinite(values), values - centre[:, None], 0.0)
        variance = np.where(count >= 2, (deviation ** 2).sum(axis=1) / (count - 1), np.nan)
    smoothed = _rolling_mean(variance, int(round(smooth / period)))
    compared = count > 0
    spread = np.sqrt(smoothed)
    typical = float(np.nanmedian(spread[compared])) if np.isfinite(spread[compared]).any() \
        else np.nan
    missing = compared & ~np.isfinite(spread)
    filled = float(missing.sum() / max(compared.sum(), 1))
    spread = np.where(missing, typical, spread)
    if np.isfinite(typical) and typical > 0:
        spread = np.maximum(spread, SPREAD_FLOOR * typical)
    spread = np.where(compared, spread, np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        raw = np.abs(run - centre) / (spread * np.sqrt(1.0 + 1.0 / np.maximum(count, 1)))
    raw = np.where(compared & (spread > 0), raw, np.nan)
    size = np.where(compared, _rolling_mean(raw, int(round(detail / period))), np.nan)
    within = len(references) == 1
    return Band(run=run, centre=centre, spread=spread, count=count, size=size,
                within_run=within, filled=filled)
