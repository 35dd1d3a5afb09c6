"""Subcommands of ``hubvib``: one module each, found by name.

A command is one file here that defines ``add_parser(sub)`` (which sets
``handler``) and nothing heavy at import time; ``hubvib/cli.py`` discovers it.
``torus_screw.py`` becomes ``hubvib torus-screw``.
"""
from __future__ import annotations

import importlib
import pkgutil


def command_modules() -> list:
    """Every command module, in name order."""
    return [importlib.import_module(f"{__name__}.{info.name}")
            for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name)
            if not info.name.startswith("_")]
