"""Type stub of funcnet.track: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.track.add import (
    Added as Added,
    add_runs as add_runs,
    read_run as read_run,
)
from funcnet.track.detect import (
    DRIFT as DRIFT,
    LEARN as LEARN,
    LEVEL as LEVEL,
    Detection as Detection,
    detect_changes as detect_changes,
)
from funcnet.track.figures import (
    FIGURES as FIGURES,
    axis_figures as axis_figures,
)
from funcnet.track.program import (
    program_signature as program_signature,
    same_program as same_program,
)
from funcnet.track.store import (
    open_store as open_store,
    read_figures as read_figures,
    read_runs as read_runs,
)
from funcnet.track.trend import (
    Trends as Trends,
    robot_trends as robot_trends,
)

__all__: list[str]
