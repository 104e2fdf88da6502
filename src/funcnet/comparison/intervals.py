"""The intervals where RUN departs from its references beyond their spread.

A tick of RUN departs when some signal of some axis lies more than ``threshold`` spreads from
the references' band (:class:`~funcnet.comparison.band.Band`); departing stretches less than
``merge`` seconds apart are one interval, and an interval shorter than ``min_duration`` is
dropped. Each interval names its axes and signals (those beyond the threshold in it), its
size (the largest departure, in spreads) and, per signal and axis, the physical difference from
the band's centre where it departs most, with its unit.

Examples
--------
>>> import numpy as np
>>> size = np.zeros(100); size[40:50] = 9.0; size[53:56] = 7.0
>>> diff = size * 0.1
>>> found = find_intervals({("CR", 2): size}, {("CR", 2): diff}, {"CR": "A"},
...                        times=np.arange(100) * 0.01, threshold=6.0, merge=0.05)
>>> [(i.start, i.stop, i.axes, i.signals, i.size) for i in found]
[(0.4, 0.56, (2,), ('CR',), 9.0)]
>>> found[0].differences[0]
Difference(signal='CR', axis=2, value=0.9, unit='A', size=9.0)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from funcnet.comparison.align import _runs
from funcnet.errors import ParameterError

__all__ = ["Difference", "Interval", "find_intervals"]


@dataclass(frozen=True)
class Difference:
    """One signal of one axis in an interval: RUN minus the band's centre where it departs most.

    Attributes
    ----------
    signal : str
    axis : int
    value : float
        The difference, in ``unit``.
    unit : str or None
        None when the recording does not say.
    size : float
        The departure there, in multiples of the references' spread.
    """

    signal: str
    axis: int
    value: float
    unit: str | None
    size: float


@dataclass(frozen=True)
class Interval:
    """A stretch of RUN that departs from the references (module notes).

    Attributes
    ----------
    start, stop : float
        RUN's seconds, ``start <= t < stop``.
    axes : tuple of int
    signals : tuple of str
    size : float
        The largest departure in it, in multiples of the references' spread.
    differences : tuple of Difference
        One per signal and axis beyond the threshold, largest first.
    """

    start: float
    stop: float
    axes: tuple[int, ...]
    signals: tuple[str, ...]
    size: float
    differences: tuple[Difference, ...]

    def as_dict(self) -> dict[str, object]:
        """The interval as plain JSON-ready values."""
        return {"start": self.start, "stop": self.stop, "axes": list(self.axes),
                "signals": list(self.signals), "size": self.size,
                "differences": [{"signal": d.signal, "axis": d.axis, "value": d.value,
                                 "unit": d.unit, "size": d.size} for d in self.differences]}


def find_intervals(
    sizes: Mapping[tuple[str, int], np.ndarray],
    differences: Mapping[tuple[str, int], np.ndarray],
    units: Mapping[str, str | None],
    *,
    times: np.ndarray,
    threshold: float = 6.0,
    merge: float = 0.5,
    min_duration: float = 0.05,
) -> tuple[Interval, ...]:
    """The intervals where some signal departs beyond ``threshold`` spreads (module notes).

    Parameters
    ----------
    sizes : mapping of (signal, axis) to ndarray
        Departure per tick of RUN, in spreads (NaN: not compared).
    differences : mapping of (signal, axis) to ndarray
        RUN minus the band's centre per tick, in the signal's unit.
    units : mapping of signal to str or None
    times : ndarray
        RUN's seconds per tick.
    threshold : float
        Departure (spreads) beyond which a tick departs.
    merge : float
        Departing stretches closer than this (seconds) are one interval.
    min_duration : float
        Shorter intervals are dropped (seconds).

    Returns
    -------
    tuple of Interval
        In time order.

    Raises
    ------
    ParameterError
        A bad ``threshold``, ``merge`` or ``min_duration``.
    """
    if not threshold > 0 or not merge >= 0 or not min_duration >= 0:
        raise ParameterError("threshold must be > 0, merge and min_duration >= 0")
    times = np.asarray(times, dtype=np.float64)
    if not sizes:
        return ()
    period = float(times[1] - times[0]) if times.size > 1 else 1.0
    keys = list(sizes)
    stack = np.stack([np.nan_to_num(np.asarray(sizes[k]), nan=0.0) for k in keys])
    hot = (stack > threshold).any(axis=0)
    spans: list[list[int]] = []
    for a, b in _runs(np.asarray(hot)):
        if spans and (a - spans[-1][1]) * period < merge:
            spans[-1][1] = b
        else:
            spans.append([a, b])
    found = []
    for a, b in spans:
        if (b - a) * period < min_duration - 1e-9:
            continue
        parts = []
        for j, (signal, axis) in enumerate(keys):
            piece = stack[j, a:b]
            if piece.max() > threshold:
                at = a + int(np.argmax(piece))
                parts.append(Difference(signal, axis, round(float(differences[keys[j]][at]), 6),
                                        units.get(signal), round(float(piece.max()), 2)))
        parts.sort(key=lambda d: -d.size)
        found.append(Interval(
            start=round(float(times[a]), 6), stop=round(float(times[b - 1]) + period, 6),
            axes=tuple(sorted({d.axis for d in parts})),
            signals=tuple(dict.fromkeys(s for s, _ in keys if any(d.signal == s for d in parts))),
            size=max(d.size for d in parts), differences=tuple(parts)))
    return tuple(found)
