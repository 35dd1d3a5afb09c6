"""The repository paths that docstrings and comments name, and which of them do not exist.

A named path is a word such as ``hubvib/runtime/fe_cache.py``, ``fem/solvers.py:239``,
``docs/fe_accuracy.md#speed``, ``tests/fem/test_solid.py`` or ``tests/signal/test_*.py``: it
starts with a folder of the repository (or of ``hubvib/``, where the app packages live:
``runtime/fe_cache.py`` is ``hubvib/runtime/fe_cache.py``) and ends in a file name with a
suffix or in ``/``.  A line number (``:239``) or an anchor (``#speed``) after it is dropped, a
``*`` is a glob that must match at least one file.  A module named alone (``solvers.py``,
``conftest.py``) must be the name of some file of the repository.  Only docstrings (module,
class, function) and comments are read: strings in code are data, not prose.
"""
from __future__ import annotations

import ast
import io
import re
import tokenize
from dataclasses import dataclass
from pathlib import Path

#: the suffixes a named file may end in (a word like ``1/s.`` or ``N/m`` is not a path)
SUFFIXES = ("py", "md", "toml", "json", "csv", "txt", "yml", "yaml", "cfg", "ini", "png",
            "svg", "html", "npz", "npy", "inp", "msh", "vtu", "wav", "uff", "unv")

_WORD = re.compile(r"(?<![\w./~$-])((?:\.?[A-Za-z_][\w.-]*/)+(?:[\w*.-]*\.(?:%s)|)(?=[\s`'\"),:;#\]]|$|\.(?:\s|$)))"
                   % "|".join(SUFFIXES))

#: a Python file named without its folder
_MODULE = re.compile(r"(?<![\w./~$*-])([A-Za-z_]\w*\.py)(?![\w/*-])")


@dataclass(frozen=True)
class NamedPath:
    """``path`` named in ``file`` at ``line`` (1-based)."""
    file: Path
    line: int
    path: str

    def __str__(self) -> str:
        return f"{self.file}:{self.line}: {self.path}"


def prose(source: str) -> list[tuple[int, str]]:
    """(first line, text) of every docstring and comment of the Python ``source``."""
    found = []
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                found.append((body[0].lineno, body[0].value.value))
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type == tokenize.COMMENT:
            found.append((token.start[0], token.string))
    return found


def named_paths(text: str, roots: tuple[str, ...]) -> list[tuple[int, str]]:
    """(line offset, path) of each word of ``text`` that names a path under one of the
    folders ``roots`` (first component)."""
    found = []
    for offset, line in enumerate(text.splitlines()):
        for match in _WORD.finditer(line):
            word = match.group(1).rstrip(".")
            if word.split("/", 1)[0] in roots:
                found.append((offset, word))
    return found


def named_modules(text: str) -> list[tuple[int, str]]:
    """(line offset, file name) of each Python file ``text`` names without its folder."""
    return [(offset, match.group(1)) for offset, line in enumerate(text.splitlines())
            for match in _MODULE.finditer(line)]


def exists(path: str, root: Path) -> bool:
    """Whether ``path`` (a file, a folder with a trailing ``/`` or a glob) is in the
    repository at ``root`` or, for the app packages, under ``root / "hubvib"``."""
    for base in (root, root / "hubvib"):
        if "*" in path:
            if any(base.glob(path)):
                return True
        elif (base / path).exists():
            return True
    return False


def missing_paths(files, root: Path) -> list[NamedPath]:
    """Every path named in the docstrings and comments of the Python ``files`` (or the whole
    text of a Markdown file) that is not in the repository at ``root``."""
    folders = [p for p in root.iterdir() if p.is_dir() and not p.name.startswith(".")]
    roots = tuple(sorted({p.name for p in folders} | {".ci"}
                         | {p.name for p in (root / "hubvib").iterdir() if p.is_dir()}))
    modules = {p.name for folder in folders if not (folder / "pyvenv.cfg").exists()
               for p in folder.rglob("*.py")} | {p.name for p in root.glob("*.py")}
    missing = []
    for file in files:
        source = file.read_text(encoding="utf-8")
        texts = prose(source) if file.suffix == ".py" else [(1, source)]
        for start, text in texts:
            named = named_paths(text, roots)
            gone = [(offset, path) for offset, path in named if not exists(path, root)]
            gone += [(offset, name) for offset, name in named_modules(text) if name not in modules]
            missing += [NamedPath(file.relative_to(root), start + offset, path)
                        for offset, path in sorted(gone)]
    return missing
