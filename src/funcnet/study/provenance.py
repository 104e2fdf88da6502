"""Provenance of a study run: package versions, input hashes, the command; ``study.json``."""

from __future__ import annotations

import functools
import platform
import sys
from collections.abc import Iterable, Sequence
from typing import Any

from funcnet import __version__
from funcnet._io import file_sha256
from funcnet.study.spec import Study
from funcnet.study.tasks import Source

__all__ = ["package_versions", "provenance"]

#: The distributions whose versions a study records.
RECORDED_PACKAGES = ("numpy", "numba", "scipy", "pandas", "pyarrow", "dask", "distributed")


def package_versions(packages: Iterable[str]) -> dict[str, str | None]:
    """Versions of Python, funcnet and the given packages, for provenance.

    Parameters
    ----------
    packages : iterable of str
        Distribution names.

    Returns
    -------
    dict
        ``python``, ``funcnet``, then each package's installed version (``None`` if absent).

    Examples
    --------
    >>> versions = package_versions(["numpy", "no-such-distribution"])
    >>> list(versions), versions["no-such-distribution"]
    (['python', 'funcnet', 'numpy', 'no-such-distribution'], None)
    """
    versions: dict[str, str | None] = {
        "python": platform.python_version(),
        "funcnet": __version__,
    }
    versions.update({package: _installed_version(package) for package in packages})
    return versions


@functools.cache
def _installed_version(package: str) -> str | None:
    """A distribution's version, read once per process (its metadata is parsed each read)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(package)
    except PackageNotFoundError:
        return None


def provenance(study: Study, sources: Sequence[Source]) -> dict[str, Any]:
    """Versions, the SHA-256 of every input (recordings, channel map, study file), the command.

    Parameters
    ----------
    study : Study
    sources : sequence of Source
        The study's recordings, hashed already.

    Returns
    -------
    dict
        ``versions``, ``inputs`` (name -> SHA-256) and ``command`` (``sys.argv``).
    """
    inputs = {s.name: s.sha256 for s in sources}
    if study.channels is not None:
        inputs[str(study.channels)] = file_sha256(study.channels)
    if study.source is not None:
        inputs[str(study.source)] = file_sha256(study.source)
    return {
        "versions": package_versions(RECORDED_PACKAGES),
        "inputs": inputs,
        "command": list(sys.argv),
    }
