"""Lazy package faces (PEP 562): a package's ``__all__`` names, imported on first use.

A package lists its face once, as imports in an ``if TYPE_CHECKING:`` block of its
``__init__.py`` (what documentation tools and type checkers read), and hands its module
``__getattr__`` and ``__dir__`` to :func:`lazy_face`, which reads that block from the
source.  ``import hubvib.fem`` then costs no submodule; ``hubvib.fem.solve`` imports
``hubvib.fem.elasticity`` when it is first used and keeps it on the package.  A face
name must not be a submodule's name (``tests/architecture/test_package_faces.py``
checks): an imported submodule would take its place on the package.  Standard library only.
"""
from __future__ import annotations

import ast
import importlib
import sys
from pathlib import Path
from typing import Callable


def face_imports(init: Path) -> dict[str, str]:
    """Each name the ``if TYPE_CHECKING:`` block of ``init`` imports, with its relative
    module (``{"solve": ".elasticity"}``); only ``from .module import name`` forms count."""
    names: dict[str, str] = {}
    for node in ast.parse(Path(init).read_text(encoding="utf-8")).body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for statement in node.body:
                if not (isinstance(statement, ast.ImportFrom) and statement.level == 1
                        and statement.module):
                    raise ValueError(f"{init}: the TYPE_CHECKING block holds only "
                                     f"'from .module import name' lines, got "
                                     f"{ast.unparse(statement)!r}")
                for alias in statement.names:
                    names[alias.asname or alias.name] = f".{statement.module}"
    return names


def lazy_face(package: str, init: str, public: list[str]) -> tuple[Callable, Callable]:
    """The module ``__getattr__`` and ``__dir__`` of ``package`` (its ``__name__``), whose
    ``__init__.py`` is ``init`` (its ``__file__``) and whose face is ``public`` (its
    ``__all__``, which must name exactly what the TYPE_CHECKING block imports)."""
    where = face_imports(Path(init))
    if sorted(where) != sorted(public):
        raise ImportError(f"{package}: __all__ and the TYPE_CHECKING imports differ: "
                          f"{sorted(set(where) ^ set(public))}")

    def __getattr__(name: str):
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where[name], package), name)
        setattr(sys.modules[package], name, value)  # kept: the next use is a plain lookup
        return value

    def __dir__() -> list[str]:
        return sorted(set(public) | set(importlib.import_module(package).__dict__))

    return __getattr__, __dir__
