"""The one invalidation rule of every cache: a result is keyed on its inputs and on the
source of every hubvib module its computation imports.

:func:`source_key` names a computation by its entry module(s) (the module holding the
cached function, ``__name__`` of the caller) and hashes the bytes of every module of the
``hubvib`` package those modules import, transitively: the import graph read from the
source with :mod:`ast`, without importing anything.  Every import counts, those inside
functions included; an import of ``a.b.c`` also counts the packages ``a`` and ``a.b``
(their ``__init__`` runs), and a name taken from a lazy package face
(:mod:`hubvib.foundation.lazy`) counts the module the face takes it from.  The imports of
an ``if TYPE_CHECKING:`` block do not run and do not count.  A module outside the
graph (a render module, for an FE case) leaves the key as it is.  An import by a name
computed at run time (``importlib.import_module``) is not seen: a cached computation
imports what it runs with ``import`` statements.

The key depends on the file bytes and the module names only (sorted), not on times or
paths, so it is the same in every process that imports the same source; a process
computes each key once (:class:`SourceGraph` keeps the files it read).  Standard library
only.
"""
from __future__ import annotations

import ast
import hashlib
import sys
import threading
from importlib.machinery import ModuleSpec
from pathlib import Path
from typing import Callable

from .lazy import face_imports

#: the package whose modules a key covers (imports of anything else are the inputs' or
#: the environment's business)
ROOT = __name__.partition(".")[0]


def find_module(name: str) -> Path | None:
    """The source file of module ``name`` as the import system would load it, found
    without importing it or its packages (``None``: no such module or no source file)."""
    spec = _spec(name)
    if spec is None or not spec.has_location or not spec.origin:
        return None
    path = Path(spec.origin)
    return path if path.suffix == ".py" else None


def _spec(name: str) -> ModuleSpec | None:
    parent = name.rpartition(".")[0]
    module = sys.modules.get(name)
    if module is not None and getattr(module, "__spec__", None) is not None:
        return module.__spec__
    path = None
    if parent:
        parent_spec = _spec(parent)
        if parent_spec is None or parent_spec.submodule_search_locations is None:
            return None
        path = list(parent_spec.submodule_search_locations)
    for finder in sys.meta_path:
        find = getattr(finder, "find_spec", None)
        if find is None:
            continue
        try:
            spec = find(name, path, None)
        except (ImportError, ValueError):
            continue
        if spec is not None:
            return spec
    return None


class SourceGraph:
    """The import graph of the ``hubvib`` modules, read from ``locate(name)`` (the source
    file of a module, or None), and the source keys of computations over it.

    One instance per process serves every cache (:func:`source_key`); a test builds its
    own over edited copies of some modules."""

    def __init__(self, locate: Callable[[str], Path | None] = find_module):
        self._locate = locate
        self._files: dict[str, Path | None] = {}
        self._imports: dict[str, frozenset[str]] = {}
        self._keys: dict[tuple[str, ...], str] = {}
        self._faces: dict[str, dict[str, str]] = {}
        self._lock = threading.Lock()

    def file(self, name: str) -> Path | None:
        if name not in self._files:
            self._files[name] = self._locate(name)
        return self._files[name]

    def is_module(self, name: str) -> bool:
        return self.file(name) is not None

    def modules(self, *entries: str) -> list[str]:
        """Every module (sorted) whose source decides what ``entries`` compute: the entries
        themselves and the ``hubvib`` modules they import, transitively."""
        seen: set[str] = set()
        todo = list(entries)
        while todo:
            name = todo.pop()
            if name in seen or self.file(name) is None:
                continue
            seen.add(name)
            todo.extend(self._parents(name))
            todo.extend(self.imports(name) - seen)
        return sorted(seen)

    def key(self, *entries: str) -> str:
        """SHA-256 (hex) of the name and bytes of every module of :meth:`modules`.

        ``ValueError`` when an entry module is not found (a misspelt name would key on
        nothing)."""
        entries = tuple(sorted(set(entries)))
        with self._lock:
            if entries not in self._keys:
                missing = [name for name in entries if self.file(name) is None]
                if missing:
                    raise ValueError(f"source_key: no source file for {', '.join(missing)}")
                digest = hashlib.sha256()
                for name in self.modules(*entries):
                    digest.update(name.encode() + b"\0")
                    digest.update(hashlib.sha256(self.file(name).read_bytes()).digest())
                self._keys[entries] = digest.hexdigest()
            return self._keys[entries]

    def imports(self, name: str) -> frozenset[str]:
        """The ``hubvib`` modules that module ``name`` imports directly (any scope)."""
        if name not in self._imports:
            path = self.file(name)
            self._imports[name] = frozenset() if path is None else frozenset(
                self._read_imports(name, path))
        return self._imports[name]

    def _parents(self, name: str) -> list[str]:
        parts = name.split(".")
        return [".".join(parts[:i]) for i in range(1, len(parts))]

    def _is_package(self, name: str) -> bool:
        path = self.file(name)
        return path is not None and path.name == "__init__.py"

    def _face(self, package: str) -> dict[str, str]:
        """Name -> module of a lazy package face (empty for any other package)."""
        if package not in self._faces:
            face = {}
            if self._is_package(package):
                try:
                    face = face_imports(self.file(package))
                except (ValueError, SyntaxError, OSError):
                    face = {}
            self._faces[package] = {attr: package + module for attr, module in face.items()}
        return self._faces[package]

    def _member(self, package: str, attr: str) -> str | None:
        """The module that ``package.attr`` loads: a submodule, or the face's module."""
        if self.is_module(f"{package}.{attr}"):
            return f"{package}.{attr}"
        return self._face(package).get(attr)

    def _read_imports(self, name: str, path: Path) -> set[str]:
        tree = ast.parse(path.read_bytes(), filename=str(path))
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found: set[str] = set()
        bound: dict[str, str] = {}  # local name -> hubvib module it is bound to

        def add(module: str) -> None:
            if module == ROOT or module.startswith(ROOT + "."):
                found.add(module)

        for node in _statements(tree.body):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    add(alias.name)
                    if alias.asname:
                        bound[alias.asname] = alias.name
                    else:
                        top = alias.name.partition(".")[0]
                        bound[top] = top
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                    source = f"{base}.{node.module}" if node.module else base
                else:
                    source = node.module or ""
                if not (source == ROOT or source.startswith(ROOT + ".")):
                    continue
                add(source)
                for alias in node.names:
                    if alias.name == "*":
                        found.update(self._face(source).values())
                        continue
                    member = self._member(source, alias.name)
                    if member is not None:
                        add(member)
                        if self.is_module(f"{source}.{alias.name}"):
                            bound[alias.asname or alias.name] = member
        # ``package.name`` reaches a submodule or a face's module: only where a package
        # itself is bound to a name (``import hubvib.fem``) is every expression read
        packages = {local: module for local, module in bound.items()
                    if (module == ROOT or module.startswith(ROOT + "."))
                    and self._is_package(module)}
        if packages:
            for node in ast.walk(tree):
                chain = _dotted(node) if isinstance(node, ast.Attribute) else None
                if not chain or chain[0] not in packages:
                    continue
                module = packages[chain[0]]
                for attr in chain[1:]:
                    member = self._member(module, attr)
                    if member is None:
                        break
                    add(member)
                    if member != f"{module}.{attr}" or not self._is_package(member):
                        break  # a face's name or a plain module: no deeper package
                    module = member
        return found


#: the fields of a statement that hold statements (a function's body, a branch, ...)
_BLOCKS = ("body", "orelse", "finalbody", "handlers", "cases")


def _statements(body: list):
    """Every statement in ``body`` and in the blocks nested in it (function and class
    bodies, branches, handlers), except the body of an ``if TYPE_CHECKING:`` block."""
    todo = list(body)
    while todo:
        node = todo.pop()
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            todo.extend(node.orelse)
            continue
        yield node
        for field in _BLOCKS:
            todo.extend(getattr(node, field, ()))


def _is_type_checking(test: ast.expr) -> bool:
    """``TYPE_CHECKING`` or ``typing.TYPE_CHECKING``."""
    return ((isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
            or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


def _dotted(node: ast.Attribute) -> list[str] | None:
    """``a.b.c`` as ``["a", "b", "c"]``; None when the chain does not start at a name."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    return [node.id, *reversed(parts)]


#: the graph of this process (replaced by tests that point it at edited sources)
PROCESS_GRAPH = SourceGraph()


def source_key(*entries: str) -> str:
    """The source key of the computation in module(s) ``entries`` (dotted names): a hash of
    every ``hubvib`` module they import (:class:`SourceGraph`); computed once per process."""
    return PROCESS_GRAPH.key(*entries)
