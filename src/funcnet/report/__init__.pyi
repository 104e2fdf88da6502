"""Type stub of funcnet.report: the names its lazy table exports (:mod:`funcnet._lazy`)."""

from funcnet.report.backlash_page import write_backlash_page as write_backlash_page
from funcnet.report.html import save_figure as save_figure
from funcnet.report.inspect import (
    inspect_trace as inspect_trace,
    write_inspection as write_inspection,
    write_inspections as write_inspections,
)
from funcnet.report.study_report import write_report as write_report
from funcnet.report.track_page import write_trends as write_trends

__all__: list[str]
