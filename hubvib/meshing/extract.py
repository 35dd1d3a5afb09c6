"""Read a gmsh mesh straight from the gmsh API (keeps second-order boundary tags)."""
from __future__ import annotations

import numpy as np

from .fe_mesh import FEMesh
from .session import MeshingError

#: dimension -> {gmsh type: (cell name, nodes per cell)} for cells and their facets
_CELLS = {2: {2: ("triangle", 3), 9: ("triangle6", 6)}, 3: {4: ("tetra", 4), 11: ("tetra10", 10)}}
_FACETS = {2: {1: 2, 8: 3}, 3: {2: 3, 9: 6}}


def extract_plane(gmsh, groups: dict[str, list[int]]) -> tuple[FEMesh, np.ndarray]:
    """Triangles of the current model and the line elements of each named curve list."""
    return extract(gmsh, groups, 2)


def extract(gmsh, groups: dict[str, list[int]], dim: int) -> tuple[FEMesh, np.ndarray]:
    """Cells of dimension ``dim`` and the facets of each named list of (dim-1) entities.

    Only nodes used by cells are kept (spline control points are gmsh nodes
    too), in gmsh tag order.  Returns the mesh and the map gmsh node tag -> index.
    """
    model = gmsh.model
    tags, coords, _ = model.mesh.getNodes()
    types, element_tags, nodes = model.mesh.getElements(dim)
    if len(types) != 1 or int(types[0]) not in _CELLS[dim]:
        raise MeshingError(f"expected one cell type of dimension {dim}, gmsh gave {list(types)}")
    name, per = _CELLS[dim][int(types[0])]
    used = np.unique(nodes[0])
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[used] = np.arange(len(used))
    lookup = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    lookup[tags] = np.arange(len(tags))
    points = coords.reshape(-1, 3)[lookup[used], :dim]
    cells = index[nodes[0].reshape(-1, per)]
    quality = model.mesh.getElementQualities(element_tags[0], "minSICN")
    facet_nodes = _FACETS[dim][min(_FACETS[dim])] if per in (3, 4) else max(_FACETS[dim].values())

    def facet_elements(entities):
        blocks = []
        for entity in entities:
            etypes, _, enodes = model.mesh.getElements(dim - 1, entity)
            for t, n in zip(etypes, enodes):
                blocks.append(index[n.reshape(-1, _FACETS[dim][int(t)])])
        return np.vstack(blocks) if blocks else np.zeros((0, facet_nodes), int)

    boundaries = {group: facet_elements(entities) for group, entities in groups.items()}
    info = dict(nodes=int(len(points)), elements=int(len(cells)),
                min_quality=float(quality.min()), mean_quality=float(quality.mean()))
    return FEMesh(points, cells, name, boundaries, {}, info, quality), index
