"""Curated package faces: each package's ``__all__`` is what a user of that
layer imports, resolved on first use (PEP 562, ``hubvib.foundation.lazy``), so importing
a package stays light and its face stays true."""
import importlib
import json
import pkgutil
import subprocess
import sys
import textwrap

import pytest

from hubvib.foundation.lazy import face_imports, lazy_face

#: the packages whose ``__init__.py`` declares a face (lumped and signal have eager ones);
#: foundation first: every other face imports its ``lazy``
FACES = ["hubvib.foundation", "hubvib.commands", "hubvib.companion", "hubvib.detection",
         "hubvib.identification", "hubvib.render", "hubvib.reports", "hubvib.runtime",
         "hubvib.studies",
         "hubvib.meshing", "hubvib.fem", "hubvib.validation"]
#: what no package import and no face may load (the lazy heavy dependencies)
HEAVY = ["gmsh", "skfem", "pyvista", "matplotlib", "dask", "distributed"]

PROBE = textwrap.dedent("""
    import importlib, json, sys
    packages, heavy, resolve = json.loads(sys.argv[1])
    seen = {}
    for name in packages:  # each package as imported alone: what it adds to sys.modules
        before = set(sys.modules)
        importlib.import_module(name)
        seen[name] = sorted(m for m in set(sys.modules) - before
                            if m.split(".")[0] in heavy or m.startswith(name + "."))
    if resolve:  # then every name of every face
        for name in packages:
            module = sys.modules[name]
            for attribute in module.__all__:
                getattr(module, attribute)
    seen["faces"] = sorted(m for m in sys.modules if m.split(".")[0] in heavy)
    print(json.dumps(seen))
""")


def _probe(resolve: bool) -> dict:
    """What importing each package (and, with ``resolve``, every face name) loads, measured
    in one fresh process."""
    run = subprocess.run([sys.executable, "-c", PROBE, json.dumps([FACES, HEAVY, resolve])],
                         capture_output=True, text=True, check=True)
    return json.loads(run.stdout)


@pytest.fixture(scope="module")
def imported():
    """What importing each package loads: one fresh process (the faces not resolved)."""
    return _probe(resolve=False)


@pytest.mark.parametrize("package", FACES)
def test_import_package_loads_no_submodule_and_nothing_heavy(package, imported):
    """``import hubvib.fem`` (etc.) in a fresh process adds none of its submodules and no
    gmsh, scikit-fem, pyvista, matplotlib or dask to ``sys.modules`` (measured there)."""
    allowed = ["hubvib.foundation.lazy"] if package == "hubvib.foundation" else []
    assert imported[package] == allowed, f"import {package} loaded {imported[package]}"


@pytest.mark.parametrize("package", FACES)
def test_every_face_name_resolves(package):
    """Every name of the face imports (no stale name) and is its module's object."""
    module = importlib.import_module(package)
    for name in module.__all__:
        value = getattr(module, name)
        assert getattr(value, "__name__", name) == name or not callable(value), \
            f"{package}.{name} resolves to {value!r}"


@pytest.mark.slow  # imports every module of hubvib in a fresh process (~2 s); the default
# run resolves every name in test_every_face_name_resolves and checks the package imports
def test_every_face_resolves_without_heavy_imports():
    """All names of all faces together load none of the heavy dependencies: those stay
    inside the functions that use them (measured in a fresh process)."""
    seen = _probe(resolve=True)
    assert seen["faces"] == [], f"resolving the faces loaded {seen['faces']}"


@pytest.mark.parametrize("package", FACES)
def test_face_is_declared_once_and_shadows_no_submodule(package):
    """``__all__`` names what the TYPE_CHECKING block imports (docs and type checkers read
    that block), and no face name is also a submodule's name: an imported submodule would
    replace the lazily imported function on the package."""
    module = importlib.import_module(package)
    assert len(set(module.__all__)) == len(module.__all__), f"{package}: a name twice"
    submodules = {info.name for info in pkgutil.iter_modules(module.__path__)}
    assert not set(module.__all__) & submodules, \
        f"{package}: face names that are also submodules: {set(module.__all__) & submodules}"
    if package != "hubvib.commands":  # the one eager face: its own two functions
        assert sorted(face_imports(module.__file__)) == sorted(module.__all__)
        assert set(module.__all__) <= set(dir(module))


def test_lazy_face_refuses_a_face_that_disagrees_with_its_imports(tmp_path):
    """A name in ``__all__`` that the TYPE_CHECKING block does not import (or the other
    way round) is an ImportError naming it; an unknown attribute is an AttributeError
    naming the package and the attribute."""
    init = tmp_path / "__init__.py"
    init.write_text("if TYPE_CHECKING:\n    from .elasticity import solve\n")
    with pytest.raises(ImportError, match=r"pkg: __all__ and the TYPE_CHECKING .*'extra'"):
        lazy_face("pkg", str(init), ["solve", "extra"])
    getattr_, _ = lazy_face("pkg", str(init), ["solve"])
    with pytest.raises(AttributeError, match="module 'pkg' has no attribute 'nothing'"):
        getattr_("nothing")
    init.write_text("if TYPE_CHECKING:\n    import os\n")
    with pytest.raises(ValueError, match="only 'from .module import name' lines"):
        face_imports(init)


def test_a_face_name_is_the_object_its_module_defines():
    """``hubvib.fem.solve`` is ``hubvib.fem.elasticity.solve`` (the same object, not a
    copy), and it is kept on the package after the first use."""
    import hubvib.fem
    from hubvib.fem.elasticity import solve

    assert hubvib.fem.solve is solve
    assert hubvib.fem.__dict__["solve"] is solve


def test_the_run_command_leaves_out_the_signal_and_statistics_stacks():
    """``hubvib run`` imports its command, the study kinds and the scene reader before it
    knows the scene: none of them loads scipy.signal or scipy.stats (~0.5 CPU s of a cached
    rerun's ~2); the signal study and the POD import them where they run (fresh process)."""
    probe = ("import sys, hubvib.commands.run, hubvib.studies.kinds, hubvib.studies.scene; "
             "print(sorted(m for m in ('scipy.signal', 'scipy.stats') if m in sys.modules))")
    run = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True)
    assert run.stdout.strip() == "[]", f"loaded before any scene runs: {run.stdout.strip()}"
