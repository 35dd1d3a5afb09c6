"""Read a plane gmsh mesh straight from the gmsh API (keeps second-order boundary tags)."""
from __future__ import annotations

import numpy as np

from .fe_mesh import ELEMENT_TYPES, FEMesh
from .session import MeshingError


def extract_plane(gmsh, groups: dict[str, list[int]]) -> tuple[FEMesh, np.ndarray]:
    """Triangles of the current model and the line elements of each named curve list.

    Only nodes used by triangles are kept (spline control points are gmsh nodes
    too), in gmsh tag order.  Returns the mesh and the map gmsh node tag -> index.
    """
    model = gmsh.model
    tags, coords, _ = model.mesh.getNodes()
    types, element_tags, nodes = model.mesh.getElements(2)
    if len(types) != 1:
        raise MeshingError(f"expected one triangle type, gmsh gave types {list(types)}")
    name, _, _ = ELEMENT_TYPES[int(types[0])]
    per = 6 if name == "triangle6" else 3
    used = np.unique(nodes[0])
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[used] = np.arange(len(used))
    lookup = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    lookup[tags] = np.arange(len(tags))
    points = coords.reshape(-1, 3)[lookup[used], :2]
    cells = index[nodes[0].reshape(-1, per)]
    quality = model.mesh.getElementQualities(element_tags[0], "minSICN")

    def curve_elements(curves):
        blocks = []
        for curve in curves:
            etypes, _, enodes = model.mesh.getElements(1, curve)
            for t, n in zip(etypes, enodes):
                blocks.append(index[n.reshape(-1, 3 if int(t) == 8 else 2)])
        return np.vstack(blocks) if blocks else np.zeros((0, 3 if per == 6 else 2), int)

    boundaries = {group: curve_elements(curves) for group, curves in groups.items()}
    info = dict(nodes=int(len(points)), elements=int(len(cells)),
                min_quality=float(quality.min()), mean_quality=float(quality.mean()))
    return FEMesh(points, cells, name, boundaries, {}, info), index
