"""Before any FE work: can the cache (``$HUBVIB_CACHE``) keep what the work computes?

A cache that is a file, read-only or on a read-only mount would otherwise be
found only when the first finished case is stored, and that case's minutes of
work lost.

``sweep_cache`` removes, once per process, the hidden scratch a killed run left in the
cache (``.fe-ring-*``, ``.modes-*``, ``.<entry>.json.*``: render folders and entries
being written): those whose owner process has exited, and any older than a day
(``hubvib.foundation.output.remove_stale_scratch``).  ``check_writable`` (``hubvib run``
before its FE work) sweeps, and so do the other commands that add to the cache
(``stiffness``, ``signal``).
"""
from __future__ import annotations

import os
import tempfile
from functools import lru_cache
from pathlib import Path

from hubvib.foundation.errors import InputError
from hubvib.foundation.output import remove_stale_scratch
from hubvib.meshing.cache import root_folder

#: folder levels below the cache root that are swept (``stiffness/tooth-curves`` is two)
SWEPT_LEVELS = 2


class CacheError(InputError):
    """The cache folder cannot be written; the message names it and how to fix it."""


def check_writable(*subfolders: str) -> Path:
    """The cache root, after checking that it and ``subfolders`` are writable folders.

    Creates them if needed (as the cache does).  Raises :class:`CacheError`
    naming ``$HUBVIB_CACHE`` (or the default ``~/.cache/hubvib``) otherwise.
    """
    root = root_folder()
    sweep_cache(root)
    source = "HUBVIB_CACHE" if os.environ.get("HUBVIB_CACHE") else "the default cache"
    for folder in [root, *(root / name for name in subfolders)]:
        try:
            if folder.exists() and not folder.is_dir():
                raise NotADirectoryError(20, "it exists and is not a folder")
            folder.mkdir(parents=True, exist_ok=True)
            tempfile.TemporaryFile(dir=folder).close()
        except OSError as exc:
            raise CacheError(f"{source} = {str(root)!r}: cannot write {str(folder)!r}: "
                             f"{exc.strerror}; set HUBVIB_CACHE to a writable folder") from None
    return Path(root)


def sweep_cache(root: Path | None = None) -> list[Path]:
    """Remove the stale scratch of the cache at ``root`` (default ``$HUBVIB_CACHE``), in it
    and ``SWEPT_LEVELS`` levels of folders below (see the module docstring); the first
    call per process and root does the work, later ones return what it removed."""
    return list(_sweep(Path(root if root is not None else root_folder()).resolve()))


@lru_cache(maxsize=None)
def _sweep(root: Path) -> tuple[Path, ...]:
    removed, level = [], [root]
    for _ in range(SWEPT_LEVELS + 1):
        below = []
        for folder in level:
            removed += remove_stale_scratch(folder)
            try:
                below += [p for p in folder.iterdir()
                          if p.is_dir() and not p.is_symlink() and not p.name.startswith(".")]
            except OSError:
                continue
        level = below
    return tuple(removed)
