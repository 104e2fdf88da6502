"""Names of a package that load on first use (PEP 562), so that importing it stays cheap.

``import funcnet`` or ``import funcnet.robot`` must not compile Numba kernels or import
matplotlib: the trace reader and the command line start fast. Each package ``__init__`` keeps a
literal table ``_EXPORTS`` (name -> module) and hands it to :func:`attach`. A name that was
renamed stays reachable under its old name, with a :class:`DeprecationWarning` that points at
the user's line (:func:`deprecated_names`).
"""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import Callable, Mapping, Sequence
from importlib import import_module
from typing import Any

from funcnet.errors import caller_stacklevel

__all__ = ["attach", "deprecated_names"]

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def deprecated_names(module: str, renamed: Mapping[str, str]) -> Callable[[str], Any]:
    """A module's ``__getattr__`` that gives each old name's new value, with a warning.

    Parameters
    ----------
    module : str
        The module's ``__name__``.
    renamed : mapping of str to str
        Old name -> the new name, an attribute of the same module.

    Returns
    -------
    callable
        ``__getattr__(name)``: the new name's value with a :class:`DeprecationWarning` naming
        both (at the user's line), AttributeError for any other name.

    Examples
    --------
    >>> import warnings
    >>> getattr_ = deprecated_names("funcnet._lazy", {"attach_names": "attach"})
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     found = getattr_("attach_names")
    >>> found is attach, str(caught[0].message)
    (True, 'funcnet._lazy.attach_names is deprecated: use funcnet._lazy.attach')
    """

    def __getattr__(name: str) -> Any:
        if name not in renamed:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        value = getattr(sys.modules[module], renamed[name])
        # `from package import old` asks twice, first through importlib's hasattr: warn once,
        # at the import line itself.
        frame: Any = sys._getframe(1)
        while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE_DIR):
            frame = frame.f_back
        if frame is None or not frame.f_code.co_filename.startswith("<frozen importlib"):
            warnings.warn(f"{module}.{name} is deprecated: use {module}.{renamed[name]}",
                          DeprecationWarning, stacklevel=caller_stacklevel())
        return value

    return __getattr__


def attach(
    package: str,
    exports: Mapping[str, str],
    defined: Sequence[str] = (),
    deprecated: Mapping[str, str] | None = None,
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
    deprecated : mapping of str to str, optional
        Old name -> its new name in ``exports``: still given, with a warning
        (:func:`deprecated_names`), and not listed in ``__all__``.

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

    old = deprecated_names(package, deprecated or {})

    def __getattr__(name: str) -> Any:
        if deprecated and name in deprecated:
            return old(name)
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
