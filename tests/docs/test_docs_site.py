"""The documentation site: every generated-figure marker names a table or a command that
exists, every committed data file names the command that regenerates it, and the site builds
in strict mode (broken links, a failing example or a failing table fail it)."""
import importlib.util
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from hubvib.cli import _parser
from hubvib.studies.scene import shipped_scenes

ROOT = Path(__file__).parents[2]
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


def _data_entries() -> list[str]:
    return sorted(e.name for e in (DOCS / "data").iterdir()
                  if e.name != "inputs" and not e.name.endswith(".meta.json")
                  and e.suffix != ".sh")


def test_every_data_file_names_the_command_that_regenerates_it():
    """Each docs/data entry has docs/data/<entry>.meta.json whose "command" list holds
    exact shell commands, run from the repository root, of an existing ``hubvib``
    subcommand (or a library module's entry point); every scene or design file a command
    names exists (a shipped scene by its name, else a file), every output it writes lies in
    the entry; the tables' provenance lines (``DATA_SOURCES``) name the same commands."""
    import shlex

    generate = _generate()
    commands = set(_parser()._subparsers._group_actions[0].choices)
    metas = sorted(p.name.removesuffix(".meta.json") for p in (DOCS / "data").glob("*.meta.json"))
    assert metas == _data_entries(), "one meta file per docs/data entry, none without its data"
    for name in _data_entries():
        meta_path = DOCS / "data" / f"{name}.meta.json"
        assert meta_path.exists(), f"docs/data/{name} has no {meta_path.name}"
        meta = json.loads(meta_path.read_text())
        assert meta.get("command"), f"{meta_path.name}: no regenerating command"
        key = name + ("/" if (DOCS / "data" / name).is_dir() else "")
        assert generate.DATA_SOURCES[key].startswith("; ".join(meta["command"])), key
        for command in meta["command"]:
            argv = shlex.split(command)
            if argv[0] == "python":  # a library module's own entry point
                assert argv[1] == "-m" and importlib.util.find_spec(argv[2]), command
            else:
                assert argv[0] == "hubvib" and argv[1] in commands, command
            if argv[:2] in (["hubvib", "run"], ["hubvib", "signal"]):
                scene = argv[2]
                assert scene in shipped_scenes() or (ROOT / scene).is_file(), (
                    f"{meta_path.name}: {command!r} names no shipped scene or file {scene!r}")
            for flag in ("--design", "--params"):
                if flag in argv:
                    path = argv[argv.index(flag) + 1]
                    assert (ROOT / path).is_file(), f"{meta_path.name}: no file {path}"
            outputs = [argv[i + 1] for i, a in enumerate(argv[:-1]) if a in (">", "--out")]
            assert outputs, f"{meta_path.name}: {command!r} writes into docs/data"
            for out in outputs:
                assert out == f"docs/data/{name}" or out.startswith(f"docs/data/{name}/"), (
                    f"{meta_path.name}: {command!r} writes {out}, outside docs/data/{name}")


def test_regenerate_script_covers_every_data_entry():
    """docs/data/regenerate.sh reruns every entry once (its ENTRIES list) and reads the
    commands from the meta files."""
    script = (DOCS / "data" / "regenerate.sh").read_text()
    listed = re.search(r"ENTRIES=\((.*?)\)", script, re.S).group(1).split()
    assert sorted(listed) == _data_entries(), "regenerate.sh ENTRIES against docs/data"
    assert len(set(listed)) == len(listed), "each entry once"


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


def _written(page: Path) -> str:
    """A page without its generated blocks (what its author wrote)."""
    return _generate().expand(page.read_text(encoding="utf-8"), lambda kind, body: "")


@pytest.mark.parametrize("page", sorted(p.name for p in DOCS.glob("*.md")
                                         if "```python" in _written(p)))
def test_python_blocks_of_the_pages_run(page, capsys):
    """Every ``python`` code block a page's author wrote runs as shown (house style: docs
    code is run); the generated blocks are checked against their generators."""
    for number, block in enumerate(re.findall(r"```python\n(.*?)```", _written(DOCS / page), re.S)):
        exec(compile(block, page, "exec"), {})
        printed = capsys.readouterr().out.splitlines()
        prints = [line for line in block.splitlines() if line.startswith("print(")]
        assert len(printed) == len(prints), (
            f"{page}, python block {number + 1}: {len(prints)} print lines, each commented with "
            f"what it shows, but the block printed {len(printed)} lines: {printed}")
        for line, statement in zip(printed, prints):
            assert re.search(r"\d", line) and not re.search(r"\bnan\b|\binf\b", line), (
                f"{page}: {statement.strip()!r} printed {line!r}, not the finite figures "
                "its comment describes")


@pytest.mark.slow
def test_site_builds_in_strict_mode(tmp_path):
    pytest.importorskip("mkdocs")
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


def _pages() -> list[Path]:
    return sorted(DOCS.glob("*.md"))


def test_committed_blocks_are_what_the_generators_give_now():
    """Each page reads in full in the repository: the generated text sits between its
    marker and the end marker, and it is what the generator gives now (a stale block fails;
    ``python docs/generate.py --write PAGE`` refills it).  Tables measured while the docs
    are built (``LIVE``: times) are never compared, the ``SLOW`` ones in the slow run."""
    generate = _generate()
    stale = [f"{page.name}: {name}" for page in _pages()
             for name in generate.stale(page.read_text(encoding="utf-8"),
                                        skip=generate.LIVE | generate.SLOW)]
    assert not stale, f"stale generated blocks (python docs/generate.py --write): {stale}"


@pytest.mark.slow
def test_slow_committed_blocks_are_current():
    generate = _generate()
    everything = {body for page in _pages()
                  for _, body, _ in generate.blocks(page.read_text(encoding="utf-8"))}
    stale = [f"{page.name}: {name}" for page in _pages()
             for name in generate.stale(page.read_text(encoding="utf-8"),
                                        skip=generate.LIVE | (everything - generate.SLOW))]
    assert not stale, f"stale generated blocks (python docs/generate.py --write): {stale}"


def test_every_marker_has_its_block_unless_its_data_is_not_committed():
    """A marker without a block is generated at build time only; that is allowed while its
    data file is not committed (the generator raises FileNotFoundError), not otherwise."""
    generate = _generate()
    missing = []
    for page in _pages():
        for kind, body, block in generate.blocks(page.read_text(encoding="utf-8")):
            if block is not None:
                continue
            try:
                generate.render(kind, body)
            except FileNotFoundError:
                continue
            missing.append(f"{page.name}: {kind}: {body}")
    assert not missing, f"markers without a committed block: {missing}"


def test_blocks_are_filled_expanded_and_found_stale():
    generate = _generate()
    fresh = {"a": "| x |\n|---|\n| 1 |", "b": "text b"}

    def render(kind, body):
        if body == "c":
            raise FileNotFoundError("docs/data/c.json")
        return fresh[body]

    page = ("# t\n\n<!-- gen: a -->\n| x |\n|---|\n| 0 |\n<!-- /gen -->\n\n"
            "<!-- gen: c -->\n\n<!-- gen: b -->\n\nend\n")
    assert generate.stale(page, render) == ["gen: a"], "a's committed block is old"
    filled = generate.fill(page, render)
    assert "<!-- gen: a -->\n| x |\n|---|\n| 1 |\n<!-- /gen -->" in filled
    assert "<!-- gen: b -->\ntext b\n<!-- /gen -->" in filled
    assert "<!-- gen: c -->\n\n" in filled, "no data yet: the marker stays without a block"
    assert generate.stale(filled, render) == []
    shown = generate.expand(filled, lambda kind, body: f"[{body}]")
    assert shown == "# t\n\n[a]\n\n[c]\n\n[b]\n\nend\n"


def test_the_command_page_names_every_command():
    """docs/commands.md: a row of its table per command (the README's list), and the
    generated reference of every argument."""
    page = (DOCS / "commands.md").read_text(encoding="utf-8")
    commands = set(_parser()._subparsers._group_actions[0].choices)
    rows = set(re.findall(r"^\| `hubvib ([\w-]+)", page, re.M))
    assert commands <= rows, f"commands without a row: {sorted(commands - rows)}"
    assert "--baseline-record" in page and "<!-- gen: command_flags -->" in page
