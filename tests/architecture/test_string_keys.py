"""FE quantities cross the code typed: a key of an FE case's dict form (``c_ru_N_m``,
``c_rp_engaged_ratio``, ...) is read by ``["..."]`` or ``.get("...")`` only in the functions
at the JSON / CSV / cache edges listed in ``EDGES``.  Everywhere else a case is a
``hubvib.cases.results.PlaneCase`` / ``SolidCase`` and its estimate is read by attribute."""
from __future__ import annotations

import ast
import tomllib
from dataclasses import fields
from pathlib import Path

import pytest

from hubvib.fem.estimate import RING_KEYS, CrackCaseEstimate, MeshEstimate, RingEstimate

ROOT = Path(__file__).parents[2]

#: the dict keys of the FE quantities of a crack case (the unit-suffixed names of
#: ``fem.estimate.RING_KEYS`` and the c_rp ratios, which have no unit)
FE_KEYS = frozenset(RING_KEYS.get(f.name, f.name)
                    for kind in (CrackCaseEstimate, RingEstimate) for f in fields(kind)
                    if f.name.startswith(("c_", "tooth_")))

#: the dict keys of the FE rows of ``hubvib stiffness`` (``MeshEstimate.to_dict`` and the
#: ring rows, ``studies.stiffness._ring_rows``): read typed in the modules that print them
STIFFNESS_KEYS = frozenset(
    {f"{f.name}_N_m" for f in fields(MeshEstimate)} | {"value_N_m", "error_N_m", "min_N_m",
                                                       "max_N_m", "root_land_N_m",
                                                       "root_land_error_N_m"})
#: the modules of the stiffness study, its command and the crack report's stiffness tables
STIFFNESS_MODULES = ("hubvib/studies/stiffness.py", "hubvib/commands/stiffness.py",
                     "hubvib/reports/crack_tables.py",
                     "hubvib/reports/mesh_stiffness_section.py")

#: (file, function) where the dict form may be read by literal key: a JSON / CSV / cache
#: edge that cannot read a typed case (the dict forms' ``from_dict`` read through the field
#: names); empty while every reader reads the typed cases
EDGES: set[tuple[str, str]] = set()


def _unit_suffixes(keys=FE_KEYS) -> frozenset[str]:
    """Literal ends of f-string keys that can only name an FE quantity (``f"{q}_N_m"``;
    a bare ``_m`` names any length and is left out)."""
    return frozenset(end for end in ("_" + key.split("_", 2)[-1] for key in keys)
                     if end != "_m")


def string_key_reads(source: str, keys=FE_KEYS) -> list[tuple[str, int, str]]:
    """Each read of one of ``keys`` in ``source``: (enclosing function's qualified name,
    line, key).  Counted: ``x["key"]`` and ``x[f"..._N_m"]`` when not assigned to, and
    ``x.get("key")`` / ``x.pop("key")``."""
    found: list[tuple[str, int, str]] = []
    suffixes = _unit_suffixes(keys)

    def key_of(node) -> str | None:
        if isinstance(node, ast.Constant) and node.value in keys:
            return node.value
        if isinstance(node, ast.JoinedStr) and node.values:
            last = node.values[-1]
            if isinstance(last, ast.Constant) and isinstance(last.value, str) and any(
                    last.value.endswith(s) for s in suffixes):
                return ast.unparse(node)
        return None

    def visit(node, scope: list[str]) -> None:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            scope = scope + [node.name]
        if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load):
            key = key_of(node.slice)
            if key:
                found.append((".".join(scope) or "<module>", node.lineno, key))
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("get", "pop") and node.args):
            key = key_of(node.args[0])
            if key:
                found.append((".".join(scope) or "<module>", node.lineno, key))
        for child in ast.iter_child_nodes(node):
            visit(child, scope)

    visit(ast.parse(source), [])
    return found


def _source_files() -> list[tuple[str, Path]]:
    """Every Python file of the installed packages, named by its path in the repository."""
    tool = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    folders = {ROOT / tool["package-dir"].get(p, p.replace(".", "/")) for p in tool["packages"]}
    return sorted((str(f.relative_to(ROOT)), f) for folder in folders
                  for f in folder.glob("*.py"))


@pytest.mark.slow
def test_no_fe_key_is_read_outside_the_edges():
    reads = [(name, *read) for name, path in _source_files()
             for read in string_key_reads(path.read_text(encoding="utf-8"))
             if (name, read[0]) not in EDGES]
    assert reads == [], ("FE quantities read by string key outside the JSON / CSV / cache "
                         "edges (read the typed case instead, or list a true edge in EDGES):\n"
                         + "\n".join(f"{n}:{line} in {where}: {key}"
                                     for n, where, line, key in reads))


def test_the_stiffness_rows_are_read_typed():
    """The stiffness study, its command and the crack report's stiffness tables read the
    typed estimates (``StiffnessCase``), never a row's ``"value_N_m"`` and the like."""
    reads = [(name, *read) for name in STIFFNESS_MODULES
             for read in string_key_reads((ROOT / name).read_text(encoding="utf-8"),
                                          STIFFNESS_KEYS | FE_KEYS)]
    assert reads == [], ("FE stiffness rows read by string key (read the typed "
                         "StiffnessCase / MeshEstimate / RingEstimate instead):\n"
                         + "\n".join(f"{n}:{line} in {where}: {key}"
                                      for n, where, line, key in reads))
    planted = 'def f(r):\n    return r["value_N_m"], r["iso_c_gamma_N_m"]\n'
    assert [read[2] for read in string_key_reads(planted, STIFFNESS_KEYS)] == [
        "value_N_m", "iso_c_gamma_N_m"], "the scan finds a planted stiffness-row read"


def test_every_edge_still_reads_a_key():
    """An edge that no longer reads the dict form leaves the list (no stale exceptions)."""
    files = dict(_source_files())
    used = {(name, read[0]) for name in {n for n, _ in EDGES}
            for read in string_key_reads(files[name].read_text(encoding="utf-8"))}
    assert EDGES <= used, f"edges without a string-key read: {sorted(EDGES - used)}"


def test_the_scanner_finds_a_planted_read():
    """The check can fail: reads planted in a function, a method and at module level, by
    subscript, ``.get`` and a unit-suffixed f-string, are each found with where they are."""
    planted = '''
row = {}
top = row["c_ru_N_m"]

def report(case):
    return case.get("c_rp_engaged_ratio"), case["label"], case.estimate.c_ru

class Table:
    def rows(self, r, name):
        r["c_r_N_m"] = 1.0          # a write, not a read
        return r[f"{name}_poor_half_N_m"]
'''
    assert string_key_reads(planted) == [
        ("<module>", 3, "c_ru_N_m"),
        ("report", 6, "c_rp_engaged_ratio"),
        ("Table.rows", 11, "f'{name}_poor_half_N_m'"),
    ]
    assert {"c_ru_N_m", "c_r_N_m", "c_rp_engaged_ratio", "c_rp_engaged_intact_window_N_m",
            "tooth_compliance_m_N"} <= FE_KEYS
    assert string_key_reads('x = r[f"{name}_m"]') == [], "a bare length key is not an FE one"
