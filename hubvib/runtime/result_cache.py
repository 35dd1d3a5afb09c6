"""A slow, deterministic library result cached on disk by what it was computed from.

The default scene's detection study (POD, detectability map, carrier study) takes
10-15 s and depends only on its inputs (the crack model, the options, the mesh
timing) and on the source that computes it; the FE cases it starts from are cached
already (:mod:`.fe_cache`).  An entry is one file named by a SHA-256 of the pickled
inputs, of the source of the packages named by the caller and of the numpy and
scipy versions: any change to any of them is another entry.  The file holds the
SHA-256 of its payload, then the payload (the pickled result); it is used only when
the checksum matches and the result is of the expected type; otherwise the result
is computed again, with a one-line notice, and the entry replaced.  Entries are
written atomically; a cache folder that cannot be written costs nothing but the
time (the result is computed and returned as usual).

The entries live below ``$HUBVIB_CACHE`` (``~/.cache/hubvib``) beside the FE cases
and renders, and are read only from there: the same trust as the FE cache.
"""
from __future__ import annotations

import hashlib
import pickle
import sys
import tempfile
from functools import lru_cache
from importlib import metadata
from pathlib import Path

from hubvib.foundation.output import atomic_path
from hubvib.meshing.cache import root_folder

FORMAT = b"hubvib-result-cache 1\n"
_DIGEST = 64  # hex characters of a SHA-256


@lru_cache(maxsize=None)
def source_version(*folders: str) -> str:
    """Hash of every ``*.py`` below ``folders`` (sorted by path) and of the numpy and
    scipy versions."""
    digest = hashlib.sha256()
    for folder in folders:
        root = Path(folder)
        for path in sorted(root.rglob("*.py")):
            digest.update(path.relative_to(root).as_posix().encode())
            digest.update(path.read_bytes())
    for package in ("numpy", "scipy"):
        digest.update(f"{package} {metadata.version(package)}".encode())
    return digest.hexdigest()


def cache_folder() -> Path:
    return root_folder() / "results"


def entry_path(kind: str, inputs, folders: tuple[str, ...]) -> Path:
    """The entry of ``inputs`` (any picklable value) for the source in ``folders``."""
    digest = hashlib.sha256(FORMAT + kind.encode() + source_version(*folders).encode())
    digest.update(pickle.dumps(inputs, protocol=pickle.HIGHEST_PROTOCOL))
    return cache_folder() / f"{kind}-{digest.hexdigest()[:24]}.pickle"


def cached_result(kind: str, inputs, folders: tuple[str, ...], compute, expected: type):
    """``compute()`` once per ``inputs`` and source in ``folders``; later calls load the
    entry (checked: checksum, then type ``expected``)."""
    try:
        path = entry_path(kind, inputs, folders)
    except (pickle.PicklingError, TypeError, AttributeError, OSError):
        return compute()  # inputs that cannot be keyed: nothing is cached
    result = _load(path, expected)
    if result is not None:
        return result
    payload = pickle.dumps(compute(), protocol=pickle.HIGHEST_PROTOCOL)
    try:
        with atomic_path(path) as tmp:
            tmp.write_bytes(FORMAT + hashlib.sha256(payload).hexdigest().encode() + payload)
    except OSError:
        pass  # a cache folder that cannot be written: the result is returned all the same
    # the result as a later run loads it: a first run and a rerun hand on the same objects
    # (and key what they feed, such as the figures, alike)
    return pickle.loads(payload)


def _load(path: Path, expected: type):
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        return _notice(path, exc.strerror or str(exc))
    head = len(FORMAT)
    if not data.startswith(FORMAT):
        return _notice(path, "not a hubvib result cache entry")
    payload = data[head + _DIGEST:]
    if hashlib.sha256(payload).hexdigest().encode() != data[head:head + _DIGEST]:
        return _notice(path, "checksum differs")
    try:
        result = pickle.loads(payload)
    except Exception as exc:  # noqa: BLE001 - any unreadable entry is recomputed
        return _notice(path, f"cannot be read ({type(exc).__name__})")
    if not isinstance(result, expected):
        return _notice(path, f"holds a {type(result).__name__}, not a {expected.__name__}")
    return result


def _notice(path: Path, why: str) -> None:
    print(f"hubvib: result cache entry {path.name}: {why}; computing again", file=sys.stderr)
    return None


def cached_figure(path: Path, build, args: tuple, folders: tuple[str, ...]) -> Path:
    """``save_figure(build(*args), path)`` (PNG), the PNG kept by ``build``'s name, its
    ``args``, the source in ``folders`` and the matplotlib version: a rerun with the same
    data copies the picture instead of drawing it."""
    from hubvib.foundation.output import save_figure

    def png() -> bytes:
        with tempfile.TemporaryDirectory(prefix="hubvib-figure-") as scratch:
            return save_figure(build(*args), Path(scratch) / "figure.png").read_bytes()

    inputs = (build.__module__, build.__qualname__, metadata.version("matplotlib"), args)
    data = cached_result(f"figure-{build.__name__}", inputs, folders, png, bytes)
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)
