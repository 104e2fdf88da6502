"""Every public package has its page in the API reference (docs/api), listed in its index.

A public package is a folder of ``src/funcnet`` with an ``__init__.py`` whose name does not start
with an underscore; the command line (``funcnet.cli``) is documented by its ``--help`` and the
guides instead. ``make docs`` builds the pages (and fails on a warning); this checks that none is
missing, which the build cannot see.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
API = ROOT / "docs" / "api"
NOT_REFERENCED = {"cli"}


def _packages() -> list[str]:
    return sorted(p.parent.name for p in (ROOT / "src" / "funcnet").glob("*/__init__.py")
                  if not p.parent.name.startswith("_") and p.parent.name not in NOT_REFERENCED)


def test_every_public_package_has_an_api_page_in_the_index() -> None:
    listed = set(re.findall(r"^   (\w+)$", (API / "index.rst").read_text(encoding="utf-8"),
                            flags=re.MULTILINE))
    assert len(_packages()) >= 10
    for name in _packages():
        page = API / f"{name}.rst"
        assert page.is_file(), f"funcnet.{name} has no page docs/api/{name}.rst"
        assert f".. automodule:: funcnet.{name}" in page.read_text(encoding="utf-8")
        assert name in listed, f"docs/api/{name}.rst is not in docs/api/index.rst"
    assert "funcnet" in listed  # the top-level names
