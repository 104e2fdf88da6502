"""Shared test settings: headless plotting, hypothesis profile, the recordings the tests read.

The licensed sample recordings ship in the repository's ``data/`` folder (``KUKA``, ``UR5``). The
SINUMERIK trace has no licence and lives beside the clone, in ``../shared/data/sinumerik/``: a test
that needs it skips with one line saying where to put it, unless ``FUNCNET_REQUIRE_SHARED=1`` (set
by ``.ci/run``, whose machine has ``../shared``) turns that skip into a failure.
"""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib
import pytest
from hypothesis import HealthCheck, settings

matplotlib.use("Agg")

# Numba compiles on first use; a deadline would count compilation against the first example.
settings.register_profile(
    "funcnet", deadline=None, max_examples=40, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "funcnet"))

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "data"
KUKA = DATA / "kuka-kr300"
UR5 = DATA / "ur5"
SHARED = REPO.parent / "shared"
REAL_TRACE = SHARED / "data" / "sinumerik" / "axis7-braking-trace.xml"
REQUIRE_SHARED = "FUNCNET_REQUIRE_SHARED"


def shipped(*parts: str) -> Path:
    """Path of a sample recording shipped in ``data/``; a missing one fails (it is committed)."""
    path = DATA.joinpath(*parts)
    if not path.exists():
        pytest.fail(f"the shipped recording is missing: {path}")
    return path


def need_real_trace() -> Path:
    """The SINUMERIK trace beside the clone; a skip, or a failure under ``REQUIRE_SHARED``."""
    if REAL_TRACE.is_file():
        return REAL_TRACE
    message = (f"the SINUMERIK trace is not beside the clone: put it at "
               f"../shared/data/sinumerik/axis7-braking-trace.xml ({REAL_TRACE})")
    if os.environ.get(REQUIRE_SHARED) == "1":
        pytest.fail(message)
    pytest.skip(message)


@pytest.fixture(scope="session")
def real_trace() -> Path:
    """Path of the real SINUMERIK trace kept in ``../shared`` (see :func:`need_real_trace`)."""
    return need_real_trace()


@pytest.fixture(scope="session")
def ur5_runs() -> Path:
    """The folder of the UR5's log folders shipped in ``data/ur5`` (one folder per run)."""
    return shipped("ur5")
