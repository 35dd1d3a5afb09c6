"""The one invalidation rule of the caches (hubvib.foundation.source_graph): a key hashes
the source of every hubvib module a computation imports, found from its entry modules.

The graph rules are checked on a small made-up package tree; the keys of the caches on
the installed source, edited through ``conftest.edit_source``.
"""
import functools
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from hubvib.foundation import source_graph
from hubvib.foundation.source_graph import SourceGraph, find_module, source_key


def _tree(tmp_path, files: dict[str, str]) -> SourceGraph:
    """A graph over made-up modules: ``files`` maps a dotted name to its source (a
    package's name maps to its ``__init__.py``)."""
    paths = {}
    for name, text in files.items():
        packages = {other.rpartition(".")[0] for other in files if "." in other}
        folder = tmp_path.joinpath(*name.split("."))
        path = folder / "__init__.py" if name in packages else folder.with_suffix(".py")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
        paths[name] = path
    return SourceGraph(paths.get)


TREE = {
    "hubvib": "",
    "hubvib.a": "",
    "hubvib.a.top": """
        import numpy
        from hubvib.a import near
        from . import sibling

        def compute():
            from hubvib.b.deep import value  # an import inside a function counts
            return value
        """,
    "hubvib.a.near": "",
    "hubvib.a.sibling": "from .near import *\n",
    "hubvib.a.unused": "",
    "hubvib.b": """
        from typing import TYPE_CHECKING

        if TYPE_CHECKING:
            from .face import shown
            from .other import hidden
        """,
    "hubvib.b.deep": "from hubvib.b import shown\n",
    "hubvib.b.face": "shown = 1\n",
    "hubvib.b.other": "hidden = 2\n",
    "hubvib.c": "",
    "hubvib.c.attr": "import hubvib.b\n\nvalue = hubvib.b.hidden\n",
}


def test_the_graph_follows_every_import_that_runs(tmp_path):
    graph = _tree(tmp_path, TREE)
    assert graph.modules("hubvib.a.top") == [
        "hubvib", "hubvib.a", "hubvib.a.near", "hubvib.a.sibling", "hubvib.a.top",
        "hubvib.b", "hubvib.b.deep", "hubvib.b.face"]


def test_a_face_name_reached_through_an_attribute_counts_its_module(tmp_path):
    graph = _tree(tmp_path, TREE)
    assert graph.modules("hubvib.c.attr") == ["hubvib", "hubvib.b", "hubvib.b.other",
                                             "hubvib.c", "hubvib.c.attr"]


def test_the_key_changes_with_a_module_of_the_graph_only(tmp_path):
    before = _tree(tmp_path / "one", TREE).key("hubvib.a.top")
    assert _tree(tmp_path / "two", TREE).key("hubvib.a.top") == before, \
        "the same bytes elsewhere (other paths, other times): the same key"
    for name, changed in [("hubvib.b.face", True), ("hubvib.a.sibling", True),
                          ("hubvib.b.other", False), ("hubvib.a.unused", False)]:
        edited = dict(TREE, **{name: TREE[name] + "# an edit\n"})
        key = _tree(tmp_path / name, edited).key("hubvib.a.top")
        assert (key != before) == changed, name


def test_an_import_added_by_an_edit_joins_the_graph(tmp_path):
    edited = dict(TREE, **{"hubvib.a.near": "import hubvib.a.unused\n"})
    assert "hubvib.a.unused" in _tree(tmp_path, edited).modules("hubvib.a.top")


def test_an_entry_without_a_source_file_is_refused(tmp_path):
    with pytest.raises(ValueError, match="no source file for hubvib.a.missing"):
        _tree(tmp_path, TREE).key("hubvib.a.missing")


def test_the_key_does_not_depend_on_file_times(tmp_path, edit_source):
    before = source_key("hubvib.cases.runner")
    copy = edit_source("hubvib.reducer.stages", line="")
    os.utime(copy, (0, 0))
    assert source_key("hubvib.cases.runner") == before


def test_every_process_computes_the_same_key(tmp_path):
    """Another interpreter started elsewhere (another working folder, another hash seed)
    computes the same key: a worker and its client agree."""
    code = ("from hubvib.foundation.source_graph import source_key; "
            "print(source_key('hubvib.cases.runner', 'hubvib.detection.crack_detection'))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=tmp_path, env=dict(os.environ, PYTHONHASHSEED="123"), check=True)
    assert run.stdout.strip() == source_key("hubvib.detection.crack_detection",
                                            "hubvib.cases.runner")


def test_modules_are_found_without_being_imported():
    code = ("import sys; from hubvib.foundation.source_graph import PROCESS_GRAPH as g; "
            "g.key('hubvib.studies.crack_study'); "
            "print(sorted(m for m in sys.modules if m.startswith('hubvib.')))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert run.stdout.strip() == "['hubvib.foundation', 'hubvib.foundation.lazy', " \
                                 "'hubvib.foundation.source_graph']", run.stdout


def test_find_module_gives_the_installed_source():
    import hubvib.fem.solvers
    import hubvib.meshing.cache

    assert find_module("hubvib.fem.solvers") == \
        Path(hubvib.fem.solvers.__file__)
    assert find_module("hubvib.meshing.cache").read_bytes() == \
        Path(hubvib.meshing.cache.__file__).read_bytes()
    assert find_module("hubvib.no_such_module") is None


#: each cache's entry modules, and whether the computation imports the build layer's
#: stage builders (``hubvib.reducer.stages``) and the mode pictures (``hubvib.render.modes``)
CACHES = {
    "FE crack case": ("hubvib.cases.runner", True, False),
    "intact tooth curve": ("hubvib.runtime.tooth_curves", False, False),
    "signal tooth curve": ("hubvib.signal.mesh_curves", True, False),
    "predicted crack path": ("hubvib.cases.predicted_path", True, False),
    "detection study": ("hubvib.detection.crack_detection", True, False),
    "FE ring render": ("hubvib.render.fe", True, True),
    "mode render": ("hubvib.render.modes", False, True),
}


@pytest.mark.parametrize("cache", sorted(CACHES))
def test_each_cache_is_keyed_on_its_import_graph(cache, edit_source):
    entry, builds, renders = CACHES[cache]
    before = source_key(entry)
    edit_source("hubvib.reducer.stages")
    after_build = source_key(entry)
    edit_source("hubvib.render.modes")
    after_render = source_key(entry)
    assert (after_build != before) == builds
    assert (after_render != after_build) == renders


def test_the_caches_name_those_entry_modules():
    import hubvib.detection.crack_detection as study
    from hubvib.runtime import tooth_curves
    from hubvib.signal import mesh_curves
    from hubvib.cases import predicted_path
    from hubvib.cases import runner as crack_sweep
    from hubvib.render import schedule

    named = {crack_sweep.SOURCE, tooth_curves.SOURCE, mesh_curves.SOURCE,
             predicted_path.SOURCE, study.SOURCE, schedule.FE_SOURCE,
             schedule.MODES_SOURCE}
    assert named == {(entry,) for entry, _, _ in CACHES.values()}


def test_the_mesh_cache_is_keyed_on_the_meshers_source(tmp_path, edit_source):
    from hubvib.meshing.cache import cached
    from hubvib.meshing.fe_mesh import FEMesh

    calls = []

    def mesher(size):
        calls.append(size)
        return FEMesh(np.zeros((3, 2)), np.array([[0, 1, 2]]), "triangle")

    mesher.__module__ = "hubvib.meshing.ring_mesh"
    build = functools.partial(mesher, 1.0)
    for _ in range(2):
        cached(build, "ring", 1.0, folder=tmp_path)
    edit_source("hubvib.meshing.ring_outline")  # imported by ring_mesh
    cached(build, "ring", 1.0, folder=tmp_path)
    edit_source("hubvib.render.modes")
    cached(build, "ring", 1.0, folder=tmp_path)
    assert len(calls) == 2


def test_the_source_key_of_the_installed_house(installed_copy):
    """The package copied as the wheel lays it out keys as the editable install does: only
    module names and bytes count."""
    code = ("from hubvib.foundation.source_graph import source_key, find_module; "
            "print(find_module('hubvib.fem.solvers')); "
            "print(source_key('hubvib.cases.runner'))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=installed_copy,
                         env=dict(os.environ, PYTHONPATH=str(installed_copy)), check=True)
    where, key = run.stdout.split()
    assert where.startswith(str(installed_copy))
    assert key == source_key("hubvib.cases.runner")
