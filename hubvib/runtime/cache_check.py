"""Before any FE work: can the cache (``$HUBVIB_CACHE``) keep what the work computes?

A cache that is a file, read-only or on a read-only mount would otherwise be
found only when the first finished case is stored, and that case's minutes of
work lost.
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

from hubvib.foundation.errors import InputError
from hubvib.meshing.cache import root_folder


class CacheError(InputError):
    """The cache folder cannot be written; the message names it and how to fix it."""


def check_writable(*subfolders: str) -> Path:
    """The cache root, after checking that it and ``subfolders`` are writable folders.

    Creates them if needed (as the cache does).  Raises :class:`CacheError`
    naming ``$HUBVIB_CACHE`` (or the default ``~/.cache/hubvib``) otherwise.
    """
    root = root_folder()
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
