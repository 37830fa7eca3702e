"""A package's public names, each imported from its module on first use (PEP 562).

A room's ``__init__.py`` re-exports the names of its private modules.  Imported eagerly,
that would make ``from kinelab.io import ModelFile`` import every module of the room, and
every room those import: a command would load most of kinelab, and the libraries behind it,
before it starts.  Instead the room declares where each name lives::

    __getattr__, __dir__ = exports(__name__, {
        "kinelab.io._modelfile": ("ModelFile", "load", "save"),
        "kinelab.io._results": ("write_results",),
    })

and ``kinelab.io.ModelFile`` (or ``from kinelab.io import ModelFile``) imports
``kinelab.io._modelfile`` the first time it is asked for; the name is then an ordinary
attribute of the package.
"""
from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping

__all__ = ["exports"]


def exports(package: str, where: Mapping[str, Iterable[str]]) -> tuple[Callable, Callable]:
    """The module ``__getattr__`` and ``__dir__`` of ``package``, whose public names are
    those of ``where`` (module: the names it provides)."""
    modules = {name: module for module, names in where.items() for name in names}

    def __getattr__(name: str):
        module = modules.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(modules))

    return __getattr__, __dir__
