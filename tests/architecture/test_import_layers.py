"""The layers hold (import-linter contracts in pyproject.toml) and no module
imports itself back through others (grimp's graph, imports inside functions included).

The stage folders (fem/, meshing/, lumped/, validation/) sit at the repository root and
install as subpackages of hubvib (pyproject ``package-dir``).  import-linter and grimp walk
one package folder, so the checks run on the house assembled as it installs: every package
folder copied to its dotted place under a temporary ``hubvib/``, imported from there in a
fresh interpreter.
"""
import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]


@pytest.fixture(scope="module")
def house(tmp_path_factory) -> Path:
    """A folder holding ``hubvib/`` laid out as the wheel installs it (Python files only)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    folders = config["package-dir"]
    out = tmp_path_factory.mktemp("house")
    for package in config["packages"]:
        parent = next((p for p in sorted(folders, key=len, reverse=True)
                       if package == p or package.startswith(p + ".")), None)
        rest = package[len(parent):].lstrip(".").replace(".", "/") if parent else package
        source = ROOT / folders[parent] / rest if parent else ROOT / rest
        target = out / package.replace(".", "/")
        target.mkdir(parents=True, exist_ok=True)
        for file in source.glob("*.py"):
            shutil.copy2(file, target / file.name)
    return out


def _in_house(house: Path, code: str, *args: str) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter started in ``house``, so that hubvib is imported
    from there (path entries come before the editable install's finder)."""
    return subprocess.run([sys.executable, "-c", code, *args], cwd=house, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(house)}, timeout=300)


def test_house_is_the_installed_layout(house):
    run = _in_house(house, "import hubvib.fem, hubvib.lumped; print(hubvib.fem.__file__)")
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith(str(house)), run.stdout


def test_import_linter_contracts_are_kept(house):
    code = ("import sys\nfrom importlinter.cli import lint_imports\n"
            "sys.exit(lint_imports(config_filename=sys.argv[1], no_cache=True))")
    run = _in_house(house, code, str(ROOT / "pyproject.toml"))
    assert run.returncode == 0, f"import-linter (pyproject.toml [tool.importlinter]):\n{run.stdout}{run.stderr}"
    assert "3 kept, 0 broken" in run.stdout, run.stdout


def test_validation_contract_refuses_a_build_import(house, tmp_path):
    """The validation contract is not vacuous: a validation module importing the build layer
    (as ``validation/convergence.py`` did) breaks it."""
    probe = tmp_path / "house"
    shutil.copytree(house, probe)
    (probe / "hubvib" / "validation" / "probe.py").write_text("import hubvib.reducer\n")
    code = ("import sys\nfrom importlinter.cli import lint_imports\n"
            "sys.exit(lint_imports(config_filename=sys.argv[1], no_cache=True))")
    run = _in_house(probe, code, str(ROOT / "pyproject.toml"))
    assert run.returncode != 0 and "validation imports the stages only" in run.stdout
    assert "hubvib.validation.probe -> hubvib.reducer" in run.stdout, run.stdout


def test_app_layers_are_directed(house, tmp_path):
    """The studies sit above detection and signal, which are independent, and the crack
    cases below them all: an import back up (detection -> studies, cases -> detection) or
    across (signal -> detection) breaks the layers contract."""
    probe = tmp_path / "house"
    shutil.copytree(house, probe)
    (probe / "hubvib" / "detection" / "probe.py").write_text("import hubvib.studies.scene\n")
    (probe / "hubvib" / "signal" / "probe.py").write_text("import hubvib.detection.model\n")
    (probe / "hubvib" / "cases" / "probe.py").write_text("import hubvib.detection.model\n")
    code = ("import sys\nfrom importlinter.cli import lint_imports\n"
            "sys.exit(lint_imports(config_filename=sys.argv[1], no_cache=True))")
    run = _in_house(probe, code, str(ROOT / "pyproject.toml"))
    assert run.returncode != 0, run.stdout
    for line in ("hubvib.detection.probe -> hubvib.studies.scene",
                 "hubvib.signal.probe -> hubvib.detection.model",
                 "hubvib.cases.probe -> hubvib.detection.model"):
        assert line in run.stdout, f"{line} not reported:\n{run.stdout}"


def _cycles(graph) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10_000))
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.find_modules_directly_imported_by(v):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for module in sorted(graph.modules):
        if module not in index:
            visit(module)
    return found


def test_no_module_cycle(house):
    pytest.importorskip("grimp")
    code = ("import json, grimp\ngraph = grimp.build_graph('hubvib', cache_dir=None)\n"
            "print(json.dumps({m: sorted(graph.find_modules_directly_imported_by(m))"
            " for m in graph.modules}))")
    run = _in_house(house, code)
    assert run.returncode == 0, run.stderr
    edges = json.loads(run.stdout)

    class Graph:
        modules = set(edges)

        def find_modules_directly_imported_by(self, m):
            return edges[m]

    assert len(edges) > 100, "grimp must see every subpackage of hubvib, the root folders too"
    assert any(m.startswith("hubvib.fem.") for m in edges), "grimp does not see hubvib.fem"
    assert _cycles(Graph()) == [], "module import cycles (grimp, every import counted)"


def test_cycle_finder_finds_a_cycle():
    """The check above can fail: a graph with a -> b -> a gives that cycle."""
    class Graph:
        modules = {"a", "b", "c"}
        edges = {"a": {"b"}, "b": {"a"}, "c": {"a"}}

        def find_modules_directly_imported_by(self, m):
            return self.edges[m]

    assert _cycles(Graph()) == [["a", "b"]]


def test_validation_takes_the_built_gears_as_an_argument():
    """No silent Raba default below the build layer: a reducer quantity without its gears is
    refused, naming what is missing (the command passes hubvib.reducer's Raba gears)."""
    from hubvib.validation.convergence import Gears, compute_level

    with pytest.raises(ValueError, match=r"quantity 'c_ru' needs the built gears \(Gears\)"):
        compute_level("c_ru", 4.0)
    with pytest.raises(ValueError, match="c_sp needs the sun and planet bodies"):
        compute_level("c_sp", 4.0, Gears(ring=object()))
