"""Subcommands of ``hubvib``: one module each, found by name.

A command is one file here that defines ``add_parser(sub)`` (which sets
``handler``) and nothing heavy at import time; ``hubvib/cli.py`` discovers it.
``torus_screw.py`` becomes ``hubvib torus-screw``.  A command line that names a
command imports that module only (:func:`command_modules` with ``name``): each module
pulls in its own library stack (gmsh, scipy.integrate, scipy.stats, ...), and all of
them together cost a second or more before any command runs.
"""
from __future__ import annotations

import importlib
import pkgutil

__all__ = ["command_names", "command_modules"]


def command_names() -> list[str]:
    """Every command module's name (``torus_screw``), in name order, none imported."""
    return sorted(info.name for info in pkgutil.iter_modules(__path__)
                  if not info.name.startswith("_"))


def command_modules(name: str | None = None) -> list:
    """Every command module, in name order; with ``name`` (a command as typed,
    ``torus-screw``) only its module, or every module when no module has that name."""
    names = command_names()
    module = None if name is None else name.replace("-", "_")
    if module in names and module.replace("_", "-") == name:
        names = [module]
    return [importlib.import_module(f"{__name__}.{n}") for n in names]
