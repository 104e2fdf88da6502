"""A renamed public name still works under its old name, with one warning at the user's line."""

from __future__ import annotations

import subprocess
import sys
import warnings

import pytest

RENAMED = [
    ("funcnet.robot", "Turn", "SetpointTurn"),
    ("funcnet.robot.phases", "Turn", "SetpointTurn"),
    ("funcnet.robot.units", "POSITION_ROLES", "POSITION_UNIT_ROLES"),
    ("funcnet.robot.units", "SPEED_ROLES", "SPEED_UNIT_ROLES"),
    ("funcnet.robot.repeats", "POSITION_ROLES", "ABSOLUTE_POSITION_ROLES"),
]


@pytest.mark.parametrize(("module", "old", "new"), RENAMED)
def test_an_old_name_gives_the_new_value_and_says_so(module: str, old: str, new: str) -> None:
    imported = __import__(module, fromlist=[new])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = getattr(imported, old)
    assert value is getattr(imported, new)
    (warning,) = caught
    assert warning.category is DeprecationWarning
    assert str(warning.message) == f"{module}.{old} is deprecated: use {module}.{new}"
    assert warning.filename == __file__  # the user's line, not funcnet's
    assert old not in getattr(imported, "__all__", ())


def test_an_import_of_an_old_name_warns_once_at_its_line() -> None:
    # `from package import old` asks for the name twice (importlib's hasattr, then the import)
    code = ("import warnings\nwarnings.simplefilter('always')\n"
            "from funcnet.robot import Turn\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True)
    lines = [line for line in result.stderr.splitlines() if "DeprecationWarning" in line]
    assert lines == ["<string>:3: DeprecationWarning: funcnet.robot.Turn is deprecated: use "
                     "funcnet.robot.SetpointTurn"]


def test_an_unknown_name_is_still_an_attribute_error() -> None:
    import funcnet.robot.units

    with pytest.raises(AttributeError, match="POSITION_RULES"):
        funcnet.robot.units.POSITION_RULES  # noqa: B018
