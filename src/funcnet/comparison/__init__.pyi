"""Type stub of funcnet.comparison: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.comparison.align import (
    Alignment as Alignment,
    align_on_setpoints as align_on_setpoints,
)
from funcnet.comparison.band import Band as Band, reference_band as reference_band
from funcnet.comparison.compare import Comparison as Comparison, compare_runs as compare_runs
from funcnet.comparison.intervals import (
    Difference as Difference,
    Interval as Interval,
    find_intervals as find_intervals,
)
from funcnet.comparison.networks import (
    NetworkComparison as NetworkComparison,
    compare_networks as compare_networks,
)

__all__: list[str]
