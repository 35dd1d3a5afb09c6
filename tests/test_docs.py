"""The documentation site: every generated-figure marker names a table or a command that
exists, every committed data file names the command that regenerates it, and the site builds
in strict mode (broken links, a failing example or a failing table fail it)."""
import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from hubvib.cli import _parser

ROOT = Path(__file__).parents[1]
DOCS = ROOT / "docs"
MARKER = re.compile(r"<!--\s*(gen|cli):\s*(.*?)\s*-->")


def _generate():
    spec = importlib.util.spec_from_file_location("docs_generate", DOCS / "generate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _markers():
    return [(page.name, kind, body) for page in sorted(DOCS.glob("*.md"))
            for kind, body in MARKER.findall(page.read_text())]


def test_every_marker_names_a_table_or_a_hubvib_command():
    generate = _generate()
    commands = set(_parser()._subparsers._group_actions[0].choices)
    markers = _markers()
    assert len(markers) >= 20, "the pages quote generated figures"
    for page, kind, body in markers:
        if kind == "gen":
            assert body in generate.TABLES, f"{page}: no generated table {body!r}"
        else:
            argv = body.split(";")[0].split()
            assert argv[0] == "hubvib" and argv[1] in commands, f"{page}: {body!r}"


def test_every_data_file_names_the_command_that_regenerates_it():
    generate = _generate()
    commands = set(_parser()._subparsers._group_actions[0].choices)
    for entry in sorted((DOCS / "data").iterdir()):
        if entry.name == "inputs" or entry.name.endswith(".meta.json"):
            continue
        key = entry.name + ("/" if entry.is_dir() else "")
        assert key in generate.DATA_SOURCES, f"docs/data/{key} has no regenerating command"
        for command in (c.split() for c in generate.DATA_SOURCES[key].split(";")):
            if command[0] == "python":  # a library module's own entry point
                assert command[1] == "-m" and importlib.util.find_spec(command[2]), command
            else:
                assert command[0] == "hubvib" and command[1] in commands, command


def test_generated_tables_are_the_library_figures():
    """Two tables against independent sources: the lumped spectrum's first two modes
    against the published Raba 118/76 values (tolerance 0.2 %, the paper's print
    precision, as in hubvib.validation.raba118) and a console block against the command."""
    generate = _generate()
    rows = [line.split("|")[1:-1] for line in generate.table("lumped_spectrum").splitlines()[2:]]
    omega = [float(row[3]) for row in rows[:2]]
    assert omega == pytest.approx([337, 537], rel=0.002), "Raba 118/76 published ω1, ω2"
    block = generate.console(["hubvib", "design", "check", "demo4.toml"], expected=2)
    assert "hubvib: error: design.n_planets = 4" in block
    with pytest.raises(RuntimeError, match="exit 2, expected 0"):
        generate.console(["hubvib", "design", "check", "demo4.toml"])


@pytest.mark.parametrize("page", sorted(p.name for p in DOCS.glob("*.md")
                                         if "```python" in p.read_text()))
def test_python_blocks_of_the_pages_run(page, capsys):
    """Every ``python`` code block of a page runs as shown (house style: docs code is run)."""
    for block in re.findall(r"```python\n(.*?)```", (DOCS / page).read_text(), re.S):
        exec(compile(block, page, "exec"), {})
    assert capsys.readouterr().out, f"{page}: the blocks print what their comments describe"


@pytest.mark.slow
def test_site_builds_in_strict_mode(tmp_path):
    mkdocs = pytest.importorskip("mkdocs")
    assert mkdocs
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1", DISABLE_MKDOCS_2_WARNING="true")
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict",
                             "--site-dir", str(tmp_path / "site")], cwd=ROOT, env=env,
                            capture_output=True, text=True, timeout=1200)
    assert result.returncode == 0, result.stderr[-3000:]
    site = tmp_path / "site"
    api = (site / "api" / "lumped" / "index.html").read_text()
    assert "natural_modes" in api, "the API page is generated from the docstrings"
    gallery = (site / "gallery" / "plot_lumped_spectrum" / "index.html").read_text()
    assert "rotational" in gallery, "the gallery example ran and its output is on the page"
    for page in site.rglob("*.html"):
        assert not MARKER.search(page.read_text()), f"{page}: a marker was not expanded"
