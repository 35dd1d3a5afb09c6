"""FE results cached on disk, checked before they are trusted.

Each entry is one JSON file named by a hash of its inputs and of its source key.  The
source key (:func:`hubvib.foundation.source_graph.source_key`, the rule of every hubvib
cache) hashes the source of every hubvib module the computation imports, named by its
entry modules (``modules``, the caller's ``__name__``): an edit to any of them, in
``fem/``, ``meshing/`` or ``hubvib/reducer/`` alike, invalidates the entries, and an edit
elsewhere leaves them.  An entry stores the inputs themselves, the result, the source key
and a SHA-256 checksum of all of it.  It is used only when it parses, its checksum
matches, its source key and inputs equal the case's and every value passes the caller's
check; otherwise it is recomputed, with a one-line notice.

Concurrent runs share entries: a case being computed is locked (``fcntl``), so a
second run waits for it instead of computing it again.
"""
from __future__ import annotations

import fcntl
import hashlib
import json
import math
from contextlib import contextmanager
from pathlib import Path

from hubvib.fem.estimate import SCHEMA_VERSION
from hubvib.foundation.files import MAX_TABLE_BYTES, read_text
from hubvib.foundation.output import write_json
from hubvib.foundation.source_graph import source_key

FORMAT = "hubvib-fe-cache"
FORMAT_VERSION = 3


class CacheEntryError(ValueError):
    """A cache entry that cannot be trusted; the message says why."""


class CacheFolderError(ValueError):
    """The cache folder cannot be used (not a folder, not writable, an entry that is a
    folder); raised before any case is computed where possible."""


def canonical(data) -> str:
    return json.dumps(data, sort_keys=True, allow_nan=False, separators=(",", ":"))


def entry_key(inputs: dict, *, modules: tuple[str, ...]) -> str:
    """File name stem of the entry for these inputs, computed by ``modules`` (the entry
    modules of the computation, whose import graph is its source)."""
    return hashlib.sha256(canonical([source_key(*modules), inputs]).encode()).hexdigest()[:24]


def _checksum(inputs: dict, result: dict, source: str) -> str:
    return hashlib.sha256(canonical([FORMAT, FORMAT_VERSION, source, inputs, result])
                          .encode()).hexdigest()


def write_entry(path: Path, inputs: dict, result: dict, *, modules: tuple[str, ...]) -> None:
    """Store ``result`` for ``inputs``, computed by ``modules``, atomically, with its
    checksum.

    A result holding NaN or infinity is refused (``ValueError`` naming the keys), and
    a folder that cannot be written raises ``CacheFolderError``: one line, no traceback.
    """
    source = source_key(*modules)
    try:
        checksum = _checksum(inputs, result, source)
    except ValueError:
        bad = sorted(k for k, v in result.items() if isinstance(v, float) and not math.isfinite(v))
        raise ValueError(f"FE result not stored in the cache: non-finite {', '.join(bad) or 'value'} "
                         f"for {inputs.get('crack', inputs)}") from None
    try:
        write_json(path, {"format": FORMAT, "version": FORMAT_VERSION, "source": source,
                          "schema": SCHEMA_VERSION, "inputs": inputs, "result": result,
                          "checksum": checksum})
    except OSError as exc:
        raise CacheFolderError(f"cannot write the FE cache entry {path}: {exc.strerror or exc}") \
            from None


def read_entry(path: Path, inputs: dict, check=None, *, modules: tuple[str, ...]) -> dict:
    """The stored result for ``inputs``, computed by ``modules`` (as in
    :func:`write_entry`); ``CacheEntryError`` says why it cannot be used.

    ``check(result)`` raises ``CacheEntryError`` for values that are not plausible.
    A folder where the entry should be raises ``CacheFolderError`` (it cannot be
    replaced, so computing the case would be lost work).
    """
    try:
        text = read_text(path, "entry", CacheEntryError, kind="JSON",
                         max_bytes=MAX_TABLE_BYTES)
    except CacheEntryError as exc:
        if not path.exists():  # a missing folder: case_lock reports it
            raise CacheEntryError("missing") from None
        if path.is_dir():
            raise CacheFolderError(f"the FE cache entry {path} is a folder; remove it") from None
        raise CacheEntryError(f"unreadable ({exc})") from None
    try:
        data = json.loads(text)
    except (ValueError, RecursionError):
        raise CacheEntryError("not valid JSON") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise CacheEntryError("not a hubvib FE cache entry")
    source = source_key(*modules)
    if data.get("version") != FORMAT_VERSION or data.get("schema") != SCHEMA_VERSION:
        raise CacheEntryError("written by another version of the FE cache")
    if data.get("source") != source:
        raise CacheEntryError("written by another version of the source that computes it")
    # stored inputs went through JSON (tuples read back as lists): compare like with like
    if data.get("inputs") != json.loads(canonical(inputs)):
        raise CacheEntryError("its inputs are not those of this case")
    result = data.get("result")
    if not isinstance(result, dict):
        raise CacheEntryError(f"its result is {type(result).__name__}, not a table")
    try:
        expected = _checksum(inputs, result, source)
    except ValueError:  # NaN or infinity in the result: canonical() refuses them
        raise CacheEntryError("non-finite value in its result") from None
    if data.get("checksum") != expected:
        raise CacheEntryError("checksum mismatch (edited or damaged)")
    if check is not None:
        check(result)
    return result


def finite_positive(result: dict, keys) -> None:
    """``CacheEntryError`` unless every key holds a finite number > 0."""
    for key in keys:
        value = result.get(key)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                math.isfinite(value) and value > 0):
            raise CacheEntryError(f"{key} = {value!r} is not a finite value > 0")


@contextmanager
def case_lock(path: Path, wait: bool):
    """Hold the lock of the entry at ``path``; yields False if ``wait`` is False and
    another process holds it."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        handle = open(path.with_suffix(".lock"), "a")
    except OSError as exc:
        raise CacheFolderError(f"cannot use the FE cache folder {path.parent} (set HUBVIB_CACHE "
                               f"to a writable folder): {exc.strerror or exc}") from None
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            yield False
            return
        try:
            yield True
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
