"""MkDocs hooks of the hubvib documentation (``hooks:`` in mkdocs.yml).

* ``on_config``: lays out the installed package the way it imports (``hubvib.lumped`` from
  ``lumped/``, ...: pyproject's ``package-dir``) as a tree of symbolic links in a scratch
  folder, so that mkdocstrings reads every docstring statically under its import path.
* ``on_page_markdown``: replaces each generated-figure marker by what the library computes
  now, so no figure in the docs is typed by hand:

  - ``<!-- gen: NAME -->``: the table ``NAME`` of ``docs/generate.py``;
  - ``<!-- cli: hubvib ARGS [; exit=N] -->``: the command run in-process (``hubvib.cli.main``)
    in a scratch folder holding ``docs/data/inputs``, shown as a console block with its
    output; a different exit code than ``N`` (default 0) fails the build;

  each with the block committed after it up to ``<!-- /gen -->`` (``<!-- /cli -->``), which
  the generated text replaces (``generate.expand``; a marker without a block is expanded
  the same way).

An unknown marker, a table that raises or a command that fails stops the build, and so does
a page whose committed block is not what its marker generates now (except the ``LIVE``
ones, measured while the docs are built: timings), and a ``docs/data`` entry written by other
code than the current (its meta file's "source_key", ``generate.stale_data``) or with no
source key at all (``generate.unkeyed_data``; only the entries of
``generate.UNKEYED_EXEMPT`` go without one, each with its reason): the pages in the
repository cannot go stale unnoticed, the slow blocks included (``mkdocs build --strict``
runs every generator anyway).  ``docs/data/regenerate.sh [ENTRY ... | --stale]`` reruns the
entries' commands, records their source key and refills the pages.
"""
from __future__ import annotations

import atexit
import shutil
import sys
import tempfile
import tomllib
from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.plugins import event_priority

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

import generate  # noqa: E402  (docs/generate.py, beside this file)


def source_tree(root: Path = ROOT) -> Path:
    """A folder whose ``hubvib/`` is the package as it installs: ``hubvib/*`` plus each
    ``package-dir`` entry of pyproject.toml linked under its dotted name."""
    folder = Path(tempfile.mkdtemp(prefix="hubvib-docs-src-"))
    atexit.register(shutil.rmtree, folder, True)
    package = folder / "hubvib"
    package.mkdir()
    for entry in (root / "hubvib").iterdir():
        if entry.name != "__pycache__":
            (package / entry.name).symlink_to(entry)
    tool = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    for name, where in tool.get("package-dir", {}).items():
        parts = name.split(".")
        if parts[0] == "hubvib" and len(parts) == 2 and not (package / parts[1]).exists():
            (package / parts[1]).symlink_to(root / where)
    return folder


@event_priority(100)  # before mkdocstrings reads its handler options
def on_config(config):
    problems = generate.data_problems()
    if problems:
        raise PluginError("; ".join(problems))
    handlers = config["plugins"]["mkdocstrings"].config.setdefault("handlers", {})
    python = handlers.setdefault("python", {})
    python["paths"] = [str(source_tree())] + list(python.get("paths", []))
    return config


def on_page_markdown(markdown, page, config, files):
    made = {}

    def render(kind, body):
        if (kind, body) not in made:
            try:
                made[kind, body] = generate.render(kind, body)
            except Exception as exc:  # any failure of a figure fails the build, naming the page
                raise PluginError(f"{page.file.src_path}: <!-- {kind}: {body} -->: {exc}"
                                  ) from exc
        return made[kind, body]

    stale = generate.stale(markdown, render, skip=generate.LIVE)
    if stale:
        raise PluginError(f"{page.file.src_path}: committed blocks not what their markers "
                          f"generate now: {'; '.join(stale)}; refill with python "
                          f"docs/generate.py --write docs/{page.file.src_path}")
    return generate.expand(markdown, render)
