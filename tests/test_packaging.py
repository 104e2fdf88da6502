"""The distribution's licence, citation and changelog agree with pyproject.toml."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]


def test_the_licence_file_is_the_declared_licence() -> None:
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert PROJECT["license"] == "MIT"
    assert text.startswith("MIT License\n")
    assert "Copyright (c) 2026 the funcnet authors" in text
    assert 'THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND' in text


def test_the_citation_names_this_version_and_the_paper() -> None:
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    top = dict(re.findall(r"^([a-z-]+): (.+)$", text, flags=re.MULTILINE))
    assert top["cff-version"] == "1.2.0"
    assert top["type"] == "software"
    assert top["version"] == PROJECT["version"]
    assert top["license"] == PROJECT["license"]
    assert top["title"].strip('"').startswith(PROJECT["name"] + ":")
    assert 'title: "Functional Network-Based Analysis of Industrial Robot Dynamics"' in text
    families = re.findall(r"family-names: \"?([^\"\n]+)\"?", text)
    assert families == ["El Dabett", "Hansen", "Geier"]


def test_the_changelog_has_an_unreleased_section_and_this_version() -> None:
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    headings = re.findall(r"^## \[([^\]]+)\]", text, flags=re.MULTILINE)
    assert headings[0] == "Unreleased"
    assert PROJECT["version"] in headings
