"""Every file a docstring or a comment names exists: the package source, the tests, the
docs pages and the README name files of the repository only as they are now."""
from pathlib import Path

import pytest

from tests.helpers.named_paths import exists, missing_paths, named_modules, named_paths, prose

ROOT = Path(__file__).parents[2]
#: the source folders (``pyproject.toml``'s package folders) and the tests
SOURCE = ("hubvib", "fem", "meshing", "lumped", "validation", "scenes", "tests")


def _sources() -> list[Path]:
    return sorted(p for folder in SOURCE for p in (ROOT / folder).rglob("*.py")
                  if "__pycache__" not in p.parts)


@pytest.mark.slow
def test_every_path_a_docstring_or_comment_names_exists():
    files = _sources()
    assert len(files) > 200, "the scan reads the whole package source and the tests"
    missing = missing_paths(files, ROOT)
    assert not missing, "named but not in the repository:\n" + "\n".join(map(str, missing))


def test_every_path_the_docs_and_the_readme_name_exists():
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    missing = missing_paths(pages, ROOT)
    assert not missing, "named but not in the repository:\n" + "\n".join(map(str, missing))


ROOTS = ("hubvib", "fem", "docs", "tests", "runtime")


@pytest.mark.parametrize("text, paths", [
    ("see ``hubvib/runtime/fe_cache.py`` and fem/solvers.py:239.",
     ["hubvib/runtime/fe_cache.py", "fem/solvers.py"]),
    ("(docs/fe_accuracy.md#speed-and-memory), `tests/signal/test_*.py`",
     ["docs/fe_accuracy.md", "tests/signal/test_*.py"]),
    ("runtime/fe_cache.py, the tests/ folder", ["runtime/fe_cache.py", "tests/"]),
    ("N/m, c_ru/c_r, 1/s, ~/.cache/hubvib/x.json, $HUBVIB_CACHE/fem/x.json, hubvib-out/a.md", []),
    ("fem/solvers (a module named without its suffix)", []),
])
def test_the_scanner_finds_the_paths_of_a_text(text, paths):
    assert [path for _, path in named_paths(text, ROOTS)] == paths


def test_the_scanner_finds_modules_named_without_their_folder():
    text = "solvers.py (``fem/solvers.py``), test_fem.py:12, setup.py.\ntest_*.py, a.pyc"
    assert named_modules(text) == [(0, "solvers.py"), (0, "test_fem.py"), (0, "setup.py")]


def test_the_scanner_reads_docstrings_and_comments_not_code_strings():
    source = ('"""Module: docs/a.md."""\nPATH = "docs/b.md"\n\n\ndef f():\n'
              '    """Function: docs/c.md."""\n    return 1  # comment: docs/d.md\n')
    texts = " ".join(text for _, text in prose(source))
    assert [p for _, p in named_paths(texts, ROOTS)] == ["docs/a.md", "docs/c.md", "docs/d.md"]


def test_a_planted_missing_path_is_reported_with_its_file_and_line(tmp_path):
    """A small repository whose module names a file that exists, one in the app packages'
    folder, one that does not, a glob that matches nothing and a module of no folder: the
    scan reports the last three, by file and line."""
    (tmp_path / "hubvib" / "runtime").mkdir(parents=True)
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "page.md").write_text("# page\n")
    (tmp_path / "hubvib" / "runtime" / "fe_cache.py").write_text("")
    module = tmp_path / "hubvib" / "module.py"
    module.write_text('"""One page: docs/page.md; the cache: runtime/fe_cache.py.\n\n'
                      'A file that was removed: docs/removed.md."""\n'
                      "X = 1  # the tests of it: tests/test_gone_*.py\n"
                      "# its twin: gone.py, itself: module.py\n")
    (tmp_path / "tests").mkdir()
    missing = missing_paths([module], tmp_path)
    assert [(str(m.file), m.line, m.path) for m in missing] == [
        ("hubvib/module.py", 3, "docs/removed.md"), ("hubvib/module.py", 4, "tests/test_gone_*.py"),
        ("hubvib/module.py", 5, "gone.py")]
    assert exists("docs/page.md", tmp_path) and exists("runtime/fe_cache.py", tmp_path)
    assert not exists("docs/removed.md", tmp_path)
