"""A slow, deterministic library result cached on disk by what it was computed from.

The default scene's detection study (POD, detectability map, carrier study) depends
only on its inputs (the crack model, the options, the mesh timing) and on the source
that computes it; the FE cases it starts from are cached already (:mod:`.fe_cache`).
An entry is one file named by a SHA-256 of the pickled inputs, of the source key of the
computation's entry modules and of the modules of the inputs' classes (the caller names
the entry modules; the key hashes every hubvib module they import,
:func:`hubvib.foundation.source_graph.source_key`) and of the numpy and scipy versions:
any change to any of them is another entry.  The file holds the SHA-256 of its
payload, then the payload (the pickled result); it is used only when the checksum
matches and the result is of the expected type; otherwise the result is computed
again, with a one-line notice, and the entry replaced.  Entries are written atomically;
a cache folder that cannot be written costs nothing but the time (the result is
computed and returned as usual).

The entries live below ``$HUBVIB_CACHE`` (``~/.cache/hubvib``) beside the FE cases
and renders, and are read only from there: the same trust as the FE cache.
"""
from __future__ import annotations

import hashlib
import io
import pickle
import sys
import tempfile
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from types import FunctionType

from hubvib.foundation.output import atomic_path
from hubvib.foundation.source_graph import source_key
from hubvib.meshing.cache import root_folder

FORMAT = b"hubvib-result-cache 1\n"
_ROOT = __name__.partition(".")[0]
_DIGEST = 64  # hex characters of a SHA-256


@lru_cache(maxsize=None)
def _libraries() -> bytes:
    """The numpy and scipy versions (part of every key)."""
    return "".join(f"{package} {metadata.version(package)}\n"
                   for package in ("numpy", "scipy")).encode()


def cache_folder() -> Path:
    return root_folder() / "results"


class _Pickler(pickle.Pickler):
    """A pickler that notes the hubvib modules of the classes and functions it meets: the
    inputs' methods run in the computation, so their source is part of its key."""

    def __init__(self, file):
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self.modules: set[str] = set()

    def reducer_override(self, obj):
        owner = obj if isinstance(obj, (type, FunctionType)) else type(obj)
        module = getattr(owner, "__module__", None)
        if isinstance(module, str) and (module == _ROOT or module.startswith(_ROOT + ".")):
            self.modules.add(module)
        return NotImplemented


def entry_path(kind: str, inputs, modules: tuple[str, ...]) -> Path:
    """The entry of ``inputs`` (any picklable value) computed by ``modules`` (the entry
    modules of the computation, dotted names; the modules of the inputs' own classes
    count too)."""
    buffer = io.BytesIO()
    pickler = _Pickler(buffer)
    pickler.dump(inputs)
    digest = hashlib.sha256(FORMAT + kind.encode() + _libraries())
    digest.update(source_key(*modules, *sorted(pickler.modules)).encode())
    digest.update(buffer.getvalue())
    return cache_folder() / f"{kind}-{digest.hexdigest()[:24]}.pickle"


def cached_result(kind: str, inputs, modules: tuple[str, ...], compute, expected: type):
    """``compute()`` once per ``inputs`` and source of ``modules`` (the entry modules of the
    computation: every hubvib module they import counts); later calls load the entry
    (checked: checksum, then type ``expected``)."""
    try:
        path = entry_path(kind, inputs, modules)
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


def cached_entry(kind: str, inputs, modules: tuple[str, ...], expected: type):
    """The entry :func:`cached_result` would load for these arguments (checked), or None
    when there is none (nothing is computed)."""
    try:
        path = entry_path(kind, inputs, modules)
    except (pickle.PicklingError, TypeError, AttributeError, OSError):
        return None
    return _load(path, expected)


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


def cached_figure(path: Path, build, args: tuple) -> Path:
    """``save_figure(build(*args), path)`` (PNG), the PNG kept by ``build``'s name, its
    ``args``, the source of ``build``'s module and of the module of ``save_figure`` (and
    of every hubvib module they import) and the matplotlib version: a rerun with the same
    data copies the picture instead of drawing it."""
    from hubvib.foundation.output import save_figure

    def png() -> bytes:
        with tempfile.TemporaryDirectory(prefix="hubvib-figure-") as scratch:
            return save_figure(build(*args), Path(scratch) / "figure.png").read_bytes()

    inputs = (build.__module__, build.__qualname__, metadata.version("matplotlib"), args)
    data = cached_result(f"figure-{build.__name__}", inputs,
                         (build.__module__, save_figure.__module__), png, bytes)
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)
