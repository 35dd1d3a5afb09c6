"""The intact pieces of the substructured plane ring, shared on disk by the processes and
runs of an FE stage (``meshing.ring_pieces``, ``fem.substructure``).

Every crack case of a design and mesh level glues the same intact pieces (the plain
pitch, the pitches with a support end) around its crack's block and condenses them the
same way.  With ``pieces_on_disk`` they are meshed and condensed once per design and
level: each is a result-cache entry (``runtime.result_cache.cached_result``: keyed by its
inputs, the piece's geometry and options, or its mesh, nodes and material, and by the
source of the modules that compute it; checked before it is trusted).
"""
from __future__ import annotations

from contextlib import contextmanager

from hubvib.fem.substructure import Condensed, set_condensation_store
from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.ring_pieces import set_mesh_store
from hubvib.runtime.result_cache import cached_result


def stored_mesh(compute, inputs) -> FEMesh:
    """An intact piece's mesh from the result cache (computed and stored when missing)."""
    return cached_result("ring-piece-mesh", inputs, ("hubvib.meshing.ring_pieces",),
                         compute, FEMesh)


def stored_condensation(compute, inputs) -> Condensed:
    """An intact piece's condensation from the result cache (computed and stored when
    missing; its factorisation is made again on reading)."""
    return cached_result("ring-piece-condensation", inputs, ("hubvib.fem.substructure",),
                         compute, Condensed)


@contextmanager
def pieces_on_disk():
    """Within: the intact pieces' meshes and condensations come from the result cache."""
    set_mesh_store(stored_mesh)
    set_condensation_store(stored_condensation)
    try:
        yield
    finally:
        set_mesh_store(None)
        set_condensation_store(None)
