"""Names of a package that load on first use (PEP 562), so that importing it stays cheap.

``import funcnet`` or ``import funcnet.robot`` must not compile Numba kernels or import
matplotlib: the trace reader and the command line start fast. Each package ``__init__`` keeps a
literal table ``_EXPORTS`` (name -> module) and hands it to :func:`attach`.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping, Sequence
from importlib import import_module
from typing import Any

__all__ = ["attach"]


def attach(
    package: str,
    exports: Mapping[str, str],
    defined: Sequence[str] = (),
) -> tuple[Callable[[str], Any], Callable[[], list[str]], list[str]]:
    """``__getattr__``, ``__dir__`` and ``__all__`` for ``package``'s lazy ``exports``.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : mapping of str to str
        Public name -> the module that defines it.
    defined : sequence of str, optional
        Public names the package defines itself (``__version__``), listed in ``__all__`` too.

    Returns
    -------
    tuple
        ``(__getattr__, __dir__, __all__)``, to assign at the package's top level.

    Examples
    --------
    >>> getattr_, dir_, all_ = attach("funcnet", {"NetworkParameters": "funcnet.parameters"})
    >>> getattr_("NetworkParameters").__name__, all_
    ('NetworkParameters', ['NetworkParameters'])
    """

    def __getattr__(name: str) -> Any:
        try:
            module = exports[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        value = getattr(import_module(module), name)
        setattr(sys.modules[package], name, value)  # later look-ups skip this function
        return value

    names = [*defined, *exports]

    def __dir__() -> list[str]:
        return sorted(names)

    return __getattr__, __dir__, names
