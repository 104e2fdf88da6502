"""Shared test settings: headless plotting, hypothesis profile, the real trace beside the repo."""

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
SHARED = REPO.parent / "shared"
REAL_TRACE = SHARED / "data" / "sinumerik" / "axis7-braking-trace.xml"


@pytest.fixture(scope="session")
def real_trace() -> Path:
    """Path of the real SINUMERIK trace kept in ``../shared`` (CI puts it beside the clone)."""
    if not REAL_TRACE.exists():  # pragma: no cover - CI always has it
        pytest.fail(f"the real trace is missing: {REAL_TRACE}")
    return REAL_TRACE


UR5 = SHARED / "data" / "ur5"


@pytest.fixture(scope="session")
def ur5_runs() -> Path:
    """The folder of the UR5's log folders kept in ``../shared`` (one folder per run)."""
    if not UR5.is_dir():  # pragma: no cover - CI always has it
        pytest.fail(f"the UR5 runs are missing: {UR5}")
    return UR5
