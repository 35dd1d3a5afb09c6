"""scikit-fem's triangle and tetrahedron meshes with a faster edge and facet numbering.

scikit-fem numbers a mesh's edges and facets (``Mesh.build_entities``) with
``np.unique(..., axis=1)``, which sorts the columns as structured records: on the
solid ring the mesh and basis build and the tooth loads take several times longer that
way (the figures: ``docs/fe_accuracy.md#measured-behind-the-codes-choices``).  Here each sorted vertex tuple is one
int64 key (its vertices as digits in base ``vertices``), and ``np.unique`` of the keys gives the same entities, in the same
(lexicographic) order, with the same first-occurrence indices and element map:
``tests/fem/test_solid.py`` compares both bit for bit.  Imported lazily (it imports
scikit-fem), by ``to_skfem``.
"""
from __future__ import annotations

import numpy as np
import skfem


def build_entities(t, indices, sort=True):
    """``skfem.Mesh.build_entities`` by int64 keys: the entities (sorted vertex tuples, or
    as the first element gives them when ``sort`` is false) and each element's entity."""
    if indices is None:
        return None, None
    indexing = np.hstack(tuple([t[ix] for ix in indices]))
    ordered = np.sort(indexing, axis=0)
    base = int(ordered.max()) + 1 if ordered.size else 1
    if base ** len(ordered) >= 2 ** 63:  # keys would overflow: scikit-fem's own way
        return skfem.Mesh.build_entities(t, indices, sort)
    key = ordered[0].astype(np.int64)
    for row in ordered[1:]:
        key = key * base + row
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    mapping = inverse.reshape((len(indices), t.shape[1]))
    return np.ascontiguousarray((ordered if sort else indexing)[:, first]), mapping


class MeshTri1(skfem.MeshTri1):
    build_entities = staticmethod(build_entities)


class MeshTri2(skfem.MeshTri2):
    build_entities = staticmethod(build_entities)


class MeshTet1(skfem.MeshTet1):
    build_entities = staticmethod(build_entities)


class MeshTet2(skfem.MeshTet2):
    build_entities = staticmethod(build_entities)
