"""Every docs/data entry is held to the code that wrote it: the docs build fails on an entry
whose source key is not the current code's and on one with no key at all, except the few
entries ``docs/generate.py`` exempts with a reason; ``docs/data/regenerate.sh --stale``
reruns exactly the entries the build fails on."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from tests.helpers.docs_modules import docs_module

ROOT = Path(__file__).parents[2]
DOCS = ROOT / "docs"
COMMAND = "hubvib design check demo.toml > docs/data/{}"


def _plant(data: Path, entry: str, key: str | None = None) -> None:
    """A data entry written by ``COMMAND`` with meta file, and source key ``key`` if any."""
    (data / entry).write_text("{}")
    meta = {"command": [COMMAND.format(entry)]}
    if key is not None:
        meta["source_key"] = key
    (data / f"{entry}.meta.json").write_text(json.dumps(meta))


def _mkdocs_config():
    """The part of the MkDocs configuration ``on_config`` reads and extends."""
    return {"plugins": {"mkdocstrings": SimpleNamespace(config={})}}


def test_every_data_entry_carries_a_source_key_or_an_exemption():
    generate = docs_module("generate")
    unkeyed = generate.unkeyed_data()
    assert not unkeyed, (f"docs/data entries with no source key: {unkeyed}; regenerate with "
                         f"docs/data/regenerate.sh {' '.join(unkeyed)}")


def test_an_unkeyed_entry_fails_the_build_and_an_exempt_one_does_not(tmp_path, monkeypatch):
    pytest.importorskip("mkdocs")
    from mkdocs.exceptions import PluginError

    hooks = docs_module("hooks")
    generate = hooks.generate
    monkeypatch.setattr(generate, "DATA", tmp_path)
    _plant(tmp_path, "x.json")
    assert generate.unkeyed_data() == ["x.json"] and generate.stale_data() == []
    with pytest.raises(PluginError, match=r"no source key .*: x\.json"):
        hooks.on_config(_mkdocs_config())

    (tmp_path / "x.json.meta.json").unlink()
    exempt = sorted(generate.UNKEYED_EXEMPT)[0]
    _plant(tmp_path, exempt)
    assert generate.unkeyed_data() == [] and generate.data_problems() == [], \
        f"{exempt} is exempt: {generate.UNKEYED_EXEMPT[exempt]}"
    config = hooks.on_config(_mkdocs_config())
    assert config["plugins"]["mkdocstrings"].config["handlers"]["python"]["paths"], \
        "the build goes on past the data check"

    _plant(tmp_path, "x.json")
    generate.record_source(["x.json"])
    assert generate.data_problems() == [], "a keyed current entry beside an exempt one"


def test_exemptions_name_entries_and_their_pages_say_why():
    """Each exemption names an entry of docs/data and gives its reason; the benchmark's
    reason stands under every generated block read from it."""
    generate = docs_module("generate")
    entries = set(generate.data_entries())
    for entry, reason in generate.UNKEYED_EXEMPT.items():
        assert entry in entries, f"UNKEYED_EXEMPT names {entry}, not a docs/data entry"
        assert len(reason.split()) >= 5, f"{entry}: the exemption gives its reason"
    reason = generate.UNKEYED_EXEMPT["benchmark.json"]
    benchmark_blocks = [(page.name, body, block) for page in sorted(DOCS.glob("*.md"))
                        for kind, body, block in generate.blocks(page.read_text())
                        if kind == "gen" and body.startswith("benchmark_")]
    assert benchmark_blocks, "the pages quote the benchmark"
    for page, body, block in benchmark_blocks:
        assert block is not None and reason in block, f"{page}: {body} does not say {reason!r}"


def test_regenerate_stale_lists_the_stale_and_unkeyed_entries(tmp_path):
    """``regenerate.sh --list --stale`` on a planted docs/data: the entries stale_data() and
    unkeyed_data() name, those of its ENTRIES list in that order first, the rest after;
    not the current or the exempt ones."""
    data = tmp_path / "docs" / "data"
    data.mkdir(parents=True)
    shutil.copy(DOCS / "generate.py", tmp_path / "docs")
    shutil.copy(DOCS / "data" / "regenerate.sh", data)
    generate = docs_module("generate", tmp_path / "docs")
    assert generate.DATA == data
    _plant(data, "stiffness_10mm.json")  # unkeyed, listed in ENTRIES
    _plant(data, "crack_path")  # unkeyed, listed in ENTRIES
    _plant(data, "zz_stale.json", key="0" * 64)
    _plant(data, "aa_unkeyed.json")
    _plant(data, "current.json")
    generate.record_source(["current.json"])
    for exempt in generate.UNKEYED_EXEMPT:
        _plant(data, exempt)
    assert generate.stale_data() == ["zz_stale.json"]
    assert generate.unkeyed_data() == ["aa_unkeyed.json", "crack_path", "stiffness_10mm.json"]

    listed = subprocess.run(
        ["bash", str(data / "regenerate.sh"), "--list", "--stale"], capture_output=True,
        text=True, check=True, env={**os.environ, "PYTHON": sys.executable}).stdout.split()
    script = (data / "regenerate.sh").read_text()
    order = script.split("ENTRIES=(", 1)[1].split(")", 1)[0].split()
    in_order = sorted(["stiffness_10mm.json", "crack_path"], key=order.index)
    assert listed == in_order + ["aa_unkeyed.json", "zz_stale.json"], listed
    assert sorted(listed) == sorted(generate.stale_data() + generate.unkeyed_data())

    named = subprocess.run(
        ["bash", str(data / "regenerate.sh"), "--list", "crack_path"], capture_output=True,
        text=True, check=True, env={**os.environ, "PYTHON": sys.executable}).stdout.split()
    assert named == ["crack_path"], "named entries, as given"
