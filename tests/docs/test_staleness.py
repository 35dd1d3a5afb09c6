"""Generated docs that cannot go stale: the docs build refuses a committed block that is not
what its marker generates now, and a docs/data entry written by other code than the
current (its meta file's source key, recorded when docs/data/regenerate.sh reran it)."""
import json
from pathlib import Path

import pytest

from tests.helpers.docs_modules import docs_module

ROOT = Path(__file__).parents[2]
DOCS = ROOT / "docs"


def test_data_entries_were_written_by_the_current_source():
    """Each docs/data entry's meta file holds the source key of the hubvib modules its
    commands import, as they are now (``docs/data/regenerate.sh ENTRY`` records it)."""
    stale = docs_module("generate").stale_data()
    assert not stale, (f"docs/data entries written by other code than the current: {stale}; "
                       f"regenerate with docs/data/regenerate.sh {' '.join(stale)}")


def test_a_recorded_source_key_is_current_until_the_code_changes(tmp_path, monkeypatch):
    generate = docs_module("generate")
    monkeypatch.setattr(generate, "DATA", tmp_path)
    (tmp_path / "x.json").write_text("{}")
    meta = tmp_path / "x.json.meta.json"
    meta.write_text(json.dumps({"command": ["hubvib design check demo.toml > docs/data/x.json"]}))
    assert generate.stale_data() == [] and generate.unkeyed_data() == ["x.json"], \
        "no key recorded: unkeyed, not stale"
    generate.record_source(["x.json"])
    assert generate.stale_data() == []
    assert json.loads(meta.read_text())["command"], "the other fields are kept"
    recorded = json.loads(meta.read_text())
    recorded["source_key"] = "0" * len(recorded["source_key"])  # written by other code
    meta.write_text(json.dumps(recorded))
    assert generate.stale_data() == ["x.json"]


def test_the_modules_of_a_command_are_its_command_module_or_entry_point():
    generate = docs_module("generate")
    assert generate.command_modules("hubvib crack-path --out docs/data/p") == [
        "hubvib.cli", "hubvib.commands.crack_path"]
    assert generate.command_modules("python -m hubvib.studies.diagnosis_check --out x") == [
        "hubvib.studies.diagnosis_check"]
    with pytest.raises(ValueError, match="runs hubvib or python -m"):
        generate.command_modules("bash make.sh")


class _Page:
    class file:
        src_path = "page.md"


def test_the_docs_build_refuses_a_stale_committed_block():
    """A cli block whose committed output differs from what the command prints now stops
    the build, naming the page and the marker; the current block passes and is expanded."""
    pytest.importorskip("mkdocs")
    from mkdocs.exceptions import PluginError

    hooks = docs_module("hooks")
    generate = hooks.generate
    marker = "<!-- cli: hubvib design check demo4.toml ; exit=2 -->"
    now = generate.render("cli", "hubvib design check demo4.toml ; exit=2")
    page = f"# p\n\n{marker}\n{now}\n<!-- /cli -->\n"
    assert hooks.on_page_markdown(page, _Page, {}, None) == f"# p\n\n{now}\n"
    old = page.replace("n_planets = 4", "n_planets = 5")
    with pytest.raises(PluginError, match="page.md: committed blocks not what"):
        hooks.on_page_markdown(old, _Page, {}, None)


def test_only_measured_blocks_escape_the_build_comparison():
    """Every marker of the pages is compared with its generator by the docs build except the
    LIVE ones (timings measured while it runs), and those are few."""
    generate = docs_module("generate")
    bodies = {body for page in DOCS.glob("*.md")
              for _, body, _ in generate.blocks(page.read_text(encoding="utf-8"))}
    assert generate.LIVE <= bodies, f"LIVE names no marker: {sorted(generate.LIVE - bodies)}"
    assert generate.SLOW <= bodies, f"SLOW names no marker: {sorted(generate.SLOW - bodies)}"
    assert len(generate.LIVE) <= 5, "measured blocks only"


def test_an_edited_input_file_makes_its_entry_stale(tmp_path, monkeypatch):
    """The key covers the files a command reads besides the code: a scene or design file it
    names and every shipped scene; the file it writes (after ``--out`` or ``>``) is not an
    input."""
    generate = docs_module("generate")
    monkeypatch.setattr(generate, "ROOT", tmp_path)
    monkeypatch.setattr(generate, "DATA", tmp_path / "docs" / "data")
    data = tmp_path / "docs" / "data"
    data.mkdir(parents=True)
    (tmp_path / "scenes").mkdir()
    shipped, named = tmp_path / "scenes" / "a.toml", tmp_path / "own.toml"
    shipped.write_text("[study]\n")
    named.write_text("[design]\n")
    (data / "x.json").write_text("{}")
    (data / "x.json.meta.json").write_text(json.dumps(
        {"command": ["hubvib design check own.toml > docs/data/x.json"]}))
    generate.record_source(["x.json"])
    assert generate.stale_data() == []
    (data / "x.json").write_text('{"new": 1}')
    assert generate.stale_data() == [], "the output is not an input"
    for path in (named, shipped):
        before = path.read_text()
        path.write_text(before + "# edited\n")
        assert generate.stale_data() == ["x.json"], f"{path.name} edited"
        path.write_text(before)
        assert generate.stale_data() == []


def test_an_entry_reading_another_reruns_with_it(tmp_path, monkeypatch):
    """An entry whose command reads another entry's committed files (as fe_substructure
    reads raba118_crack's results.json) is rerun whenever that one is: rerunning the first
    rewrites the second's input."""
    generate = docs_module("generate")
    monkeypatch.setattr(generate, "ROOT", tmp_path)
    monkeypatch.setattr(generate, "DATA", tmp_path / "docs" / "data")
    data = tmp_path / "docs" / "data"
    (data / "run").mkdir(parents=True)
    (tmp_path / "scenes").mkdir()
    (data / "run" / "results.json").write_text("{}")
    (data / "agree.json").write_text("{}")
    (data / "other.json").write_text("{}")
    for name, command in (("run", "hubvib run x --out docs/data/run"),
                          ("agree.json", "python -m hubvib.studies.fe_agreement "
                           "docs/data/run/results.json --out docs/data/agree.json"),
                          ("other.json", "hubvib design check y > docs/data/other.json")):
        (data / f"{name}.meta.json").write_text(json.dumps({"command": [command]}))
    assert generate.readers_of({"run"}) == {"run", "agree.json"}
    assert generate.readers_of({"agree.json"}) == {"agree.json"}
    assert generate.stale_or_unkeyed() == ["agree.json", "other.json", "run"], "unkeyed: all"
