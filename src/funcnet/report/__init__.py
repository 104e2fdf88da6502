"""Static HTML reports: the paper's analyses on the simulated plan, and a study's results.

Both reports are one ``index.html`` with PNG figures beside it in ``figures/`` and nothing
loaded from elsewhere (no CDN, no script, no web font), so the folder can be archived, mailed or
opened offline; every file is written atomically.

============  ================================================================================
module        what it holds
============  ================================================================================
``html``      page building: escaping, tables (pairs columns from
              :mod:`funcnet.network.schema`), figures, :func:`save_figure`
``demo``      :func:`build_demo_report`: :func:`funcnet.paper.run_paper_analyses` and the
              paper's figures on a simulated plan
``study``     :func:`write_report`: a study's results folder
============  ================================================================================

References
----------
.. [1] El Dabett, Hansen & Geier, "Functional network analysis of robot dynamics", sections 2-4.
"""

from __future__ import annotations

from funcnet.report.demo import build_demo_report
from funcnet.report.html import save_figure
from funcnet.report.study import write_report

__all__ = ["build_demo_report", "write_report", "save_figure"]
