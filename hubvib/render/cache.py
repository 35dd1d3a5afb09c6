"""Rendered files cached by what they show: a rerun copies them instead of rendering.

An entry is a folder named by a hash of the render's inputs, of the source key of the
render's entry modules (``modules``: every hubvib module they import counts,
:func:`hubvib.foundation.source_graph.source_key`) and of the pyvista and VTK versions,
holding the files as written and a ``manifest.json`` with the SHA-256 of each and the
files the render returned.  It is used only when every listed file is there with its
checksum; otherwise the files are rendered again (with a one-line notice) and the
entry replaced.  Entries are written whole (``output.atomic_folder``): the folder
appears under its name only when complete.  Whatever goes wrong with the cache (a
folder that cannot be written, an entry replaced while it is copied), the files are
rendered in place instead.
"""
from __future__ import annotations

import hashlib
import json
import shutil
import sys
from functools import lru_cache
from importlib import metadata
from pathlib import Path, PurePosixPath

import numpy as np

from hubvib.foundation.files import MAX_TABLE_BYTES, read_bytes, read_text
from hubvib.foundation.output import atomic_folder
from hubvib.foundation.source_graph import source_key
from hubvib.meshing.cache import root_folder
from hubvib.runtime.fe_cache import canonical

MANIFEST = "manifest.json"


@lru_cache(maxsize=1)
def _libraries() -> str:
    """The pyvista and VTK versions (part of every key)."""
    versions = []
    for package in ("pyvista", "vtk"):
        try:
            versions.append(f"{package} {metadata.version(package)}")
        except metadata.PackageNotFoundError:
            versions.append(f"{package} absent")
    return ", ".join(versions)


def array_digest(array) -> str:
    """SHA-256 of an array's shape and values, rounded to 10 digits relative to its largest
    entry (the last digits of an eigensolver do not change a picture)."""
    values = np.asarray(array, dtype=float)
    if not np.isfinite(values).all():
        raise ValueError("array_digest: the array holds NaN or infinity")
    scale = float(np.abs(values).max(initial=0.0)) or 1.0
    digest = hashlib.sha256(repr(values.shape).encode())
    digest.update(np.round(values / scale, 10).tobytes())
    return digest.hexdigest()


def cache_folder() -> Path:
    return root_folder() / "renders"


def cached_render(kind: str, inputs: dict, folder: Path, render,
                  modules: tuple[str, ...]) -> list[Path]:
    """``render(target)`` (returns the files it wrote below ``target``) once per ``inputs``
    and source of ``modules`` (the entry modules of the render, dotted names: every hubvib
    module they import counts); the files land in ``folder`` either way and their paths
    there are returned."""
    folder = Path(folder)
    entry = _entry(kind, inputs, modules)
    listed = _verified(entry, notice=True) or _render_into(entry, render)
    if listed is not None:
        try:
            for name in listed["files"]:
                target = folder / name
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(entry / name, target)
            return [folder / name for name in listed["returned"]]
        except OSError:  # the entry went away meanwhile (another run replacing it)
            pass
    return render(folder)


def is_cached(kind: str, inputs: dict, modules: tuple[str, ...]) -> bool:
    """Whether ``cached_render(kind, inputs, ..., modules)`` would copy a complete, checked
    entry (no notice printed here: ``cached_render`` says it when it renders again)."""
    return _verified(_entry(kind, inputs, modules)) is not None


def _entry(kind: str, inputs: dict, modules: tuple[str, ...]) -> Path:
    key = hashlib.sha256(canonical([kind, source_key(*modules), _libraries(), inputs])
                         .encode()).hexdigest()[:24]
    return cache_folder() / f"{kind}-{key}"


def _safe(name) -> bool:
    path = PurePosixPath(name) if isinstance(name, str) else None
    return (path is not None and not path.is_absolute() and ".." not in path.parts
            and name != MANIFEST and name != "")


def _verified(entry: Path, notice: bool = False) -> dict | None:
    """The entry's manifest (``files``: name -> SHA-256; ``returned``: the names the
    render returned, at least one) if every file matches its checksum, else None."""
    manifest = entry / MANIFEST
    if not manifest.exists():
        return None
    try:
        listed = json.loads(read_text(manifest, "manifest", ValueError, "JSON"))
        files, returned = listed["files"], listed["returned"]
        if not (isinstance(files, dict) and files and isinstance(returned, list) and returned
                and all(map(_safe, files)) and set(returned) <= set(files)):
            raise ValueError("the manifest does not list the rendered files")
        for name, digest in files.items():
            data = read_bytes(entry / name, name, ValueError, "rendered",
                              max_bytes=MAX_TABLE_BYTES)
            if hashlib.sha256(data).hexdigest() != digest:
                raise ValueError(f"{name}: checksum differs")
        return listed
    except (OSError, ValueError, KeyError, TypeError) as exc:
        if notice:
            print(f"hubvib: render cache entry {entry.name}: {exc}; rendering again",
                  file=sys.stderr)
        return None


def _render_into(entry: Path, render) -> dict | None:
    """Render into a scratch folder that takes ``entry``'s place whole; None when the cache
    folder cannot take it (the caller renders in place)."""
    try:
        with atomic_folder(entry) as scratch:
            returned = [Path(p).relative_to(scratch).as_posix() for p in render(scratch)]
            files = sorted(p for p in scratch.rglob("*") if p.is_file())
            listed = {"files": {p.relative_to(scratch).as_posix():
                                hashlib.sha256(p.read_bytes()).hexdigest() for p in files},
                      "returned": returned}
            (scratch / MANIFEST).write_text(json.dumps(listed), encoding="utf-8")
    except OSError:
        return None
    return _verified(entry)
