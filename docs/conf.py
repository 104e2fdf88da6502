"""Sphinx configuration: the user guide (Markdown, MyST) and the API reference (numpydoc).

Built by ``make docs`` (``sphinx-build -W``: a warning fails the build, so ``make test`` checks
it). Autodoc imports the package from ``src/``; nothing here reaches the network.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))
# Autodoc imports the plotting modules, and with them matplotlib: keep it headless.
os.environ.setdefault("MPLBACKEND", "Agg")

import funcnet  # noqa: E402

project = "funcnet"
author = "the funcnet authors"
release = funcnet.__version__
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build"]
root_doc = "index"

# Markdown: `#` headings become link targets, so guide pages can link to a section.
myst_heading_anchors = 3

# The API reference: members in the order of the source, every package's public names.
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # numpydoc's Parameters sections state the types
autodoc_default_options = {"members": True}

# numpydoc: class members are documented by autodoc, not listed again in a summary table.
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "alabaster"
html_title = f"funcnet {release}"
html_static_path: list[str] = []
# Wide enough for the pairs tables and command lines of the guide.
html_theme_options = {"page_width": "1240px", "sidebar_width": "240px"}
