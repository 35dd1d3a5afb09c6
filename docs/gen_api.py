"""API pages from docstrings (run by mkdocs-gen-files while the site builds).

One page per stable package path.  A package that declares ``__all__`` is shown by that
face; one that does not yet is shown module by module.  Where each package's source lives
comes from pyproject.toml's ``package-dir``, so a package moved on disk needs no edit here.
"""
from __future__ import annotations

import ast
import tomllib
from pathlib import Path

import mkdocs_gen_files

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = {
    "lumped": "The 9 + 3N DOF lumped planetary model: parameters, spectra, shifts, sweeps.",
    "fem": "scikit-fem stiffnesses of the ring, the tooth pairs and the bearings.",
    "meshing": "Gmsh meshes of the ring gear (plane and solid, intact and cracked) and gears.",
    "validation": "Checks against published spectra, exact solutions, references and CalculiX.",
    "design": "The reducer design file: one source for geometry, FE and the lumped model.",
    "detection": "Crack detectability: mounting in series, POD, detectability map, diagnosis.",
    "signal": "The vibration signal at a sensor on the housing and its indicators.",
}


def package_folder(name: str) -> Path:
    tool = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    where = tool.get("package-dir", {}).get(f"hubvib.{name}")
    return ROOT / where if where else ROOT / "hubvib" / name


def exported(init: Path) -> list[str] | None:
    """The names in ``__all__`` of a package's ``__init__.py`` (None without one)."""
    for node in ast.parse(init.read_text()).body:
        targets = node.targets if isinstance(node, ast.Assign) else []
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
            return list(ast.literal_eval(node.value))
    return None


def page(name: str, summary: str) -> str:
    folder = package_folder(name)
    lines = [f"# `hubvib.{name}`", "", summary, ""]
    names = exported(folder / "__init__.py")
    if names:
        lines += [f"The package's public face (`__all__`).", "",
                  f"::: hubvib.{name}", "    options:", "      show_root_heading: false",
                  "      members:"]
        lines += [f"        - {n}" for n in names]
    else:
        lines += [f"::: hubvib.{name}", "    options:", "      show_root_heading: false",
                  "      members: false", ""]
        modules = sorted(p.stem for p in folder.glob("*.py") if not p.stem.startswith("_"))
        subpackages = sorted(p.name for p in folder.iterdir()
                             if (p / "__init__.py").exists() and not p.name.startswith("_"))
        for module in modules + subpackages:
            lines += [f"::: hubvib.{name}.{module}", "    options:", "      heading_level: 2", ""]
    return "\n".join(lines) + "\n"


with mkdocs_gen_files.open("api/index.md", "w") as handle:
    handle.write("# API reference\n\nGenerated from the docstrings (numpydoc, SI units in "
                 "brackets) of each package under its import path.\n\n")
    for name, summary in PACKAGES.items():
        handle.write(f"- [`hubvib.{name}`]({name}.md): {summary}\n")

for name, summary in PACKAGES.items():
    with mkdocs_gen_files.open(f"api/{name}.md", "w") as handle:
        handle.write(page(name, summary))
