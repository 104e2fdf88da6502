"""Type stub of funcnet.study: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.study.provenance import package_versions as package_versions
from funcnet.study.run import (
    StudyResult as StudyResult,
    TaskFailure as TaskFailure,
    run_study as run_study,
)
from funcnet.study.spec import (
    WINDOW_KINDS as WINDOW_KINDS,
    Study as Study,
    WindowSpec as WindowSpec,
    load_study as load_study,
    parameter_grid as parameter_grid,
)
from funcnet.study.store import (
    PARAMETER_COLUMNS as PARAMETER_COLUMNS,
    load_results as load_results,
    network_from_rows as network_from_rows,
)

__all__: list[str]
