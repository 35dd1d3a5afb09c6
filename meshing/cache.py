"""Meshes cached on disk by a hash of everything that defines them: the parameters and
the source of the mesher (the module of ``build`` and every hubvib module it imports,
:func:`hubvib.foundation.source_graph.source_key`)."""
from __future__ import annotations

import functools
import hashlib
import json
import os
from dataclasses import asdict, is_dataclass
from pathlib import Path

from hubvib.foundation.source_graph import source_key

from .fe_mesh import FEMesh


def root_folder() -> Path:
    """``$HUBVIB_CACHE`` or ``~/.cache/hubvib``: every stage keeps its results below it."""
    root = os.environ.get("HUBVIB_CACHE")
    return Path(root) if root else Path.home() / ".cache" / "hubvib"


def default_folder() -> Path:
    return root_folder() / "meshes"


def key(*parts) -> str:
    """Stable hash of dataclasses and plain values."""
    def plain(value):
        return asdict(value) if is_dataclass(value) else value
    text = json.dumps([plain(p) for p in parts], sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cached(build, *parts, folder: Path | None = None) -> tuple[FEMesh, bool]:
    """``build()`` once per parameter set and source of ``build``'s module (and of every
    hubvib module it imports); returns the mesh and whether it came from the cache."""
    folder = Path(folder) if folder is not None else default_folder()
    mesher = build.func if isinstance(build, functools.partial) else build
    path = folder / f"{key(source_key(mesher.__module__, __name__), *parts)}.npz"
    if path.exists():
        try:
            return FEMesh.load(path), True
        except (OSError, ValueError, KeyError):
            path.unlink(missing_ok=True)  # a damaged entry is rebuilt
    mesh = build()
    folder.mkdir(parents=True, exist_ok=True)
    mesh.save(path)
    return mesh, False
