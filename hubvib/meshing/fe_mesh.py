"""A finite-element mesh with named groups, as handed to the FE stage (SI units)."""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hubvib.foundation.output import atomic_path

#: gmsh element type -> (name, dimension, number of vertices)
ELEMENT_TYPES = {
    1: ("line", 1, 2), 8: ("line3", 1, 2),
    2: ("triangle", 2, 3), 9: ("triangle6", 2, 3),
    4: ("tetra", 3, 4), 11: ("tetra10", 3, 4),
}
#: mid-edge nodes of a gmsh tetra10, in its node order 4..9
TETRA10_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (2, 3), (1, 3))
#: gmsh tetra10 -> VTK / meshio / scikit-fem order (mid-nodes 13 and 23 swap)
GMSH_TO_VTK_TETRA10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]


@dataclass(frozen=True, eq=False)
class FEMesh:
    """Nodes, cells and named groups.

    Attributes
    ----------
    points : ndarray (n, 2 or 3)
        Node coordinates [m].
    cells : ndarray (n_cells, nodes per cell)
        Connectivity in gmsh node order (triangle6: 3 vertices, then the
        mid-edge nodes of edges 01, 12, 20; tetra10 likewise, gmsh order).
    cell_type : str
        One of ``triangle``, ``triangle6``, ``tetra``, ``tetra10``.
    boundaries : dict str -> ndarray (n_facets, nodes per facet)
        Boundary facets (lines in 2D, triangles in 3D) of each named group,
        same node order convention.
    points_of : dict str -> ndarray
        Named node sets (crack tip, crack mouth).
    info : dict
        Parameters and measures (JSON-serialisable).
    cell_quality : ndarray (n_cells,) or None
        gmsh's minimum scaled Jacobian (min SICN) of each cell as meshed (curved cells
        with their curvature), 1 for a perfect cell, <= 0 for an inverted one.
    """

    points: np.ndarray
    cells: np.ndarray
    cell_type: str
    boundaries: dict = field(default_factory=dict)
    points_of: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    cell_quality: np.ndarray | None = None

    @property
    def dim(self) -> int:
        return 3 if self.cell_type.startswith("tetra") else 2

    @property
    def order(self) -> int:
        return 2 if self.cell_type in ("triangle6", "tetra10") else 1

    @property
    def vertex_count(self) -> int:
        return self.dim + 1

    def vertices(self) -> np.ndarray:
        """Indices of the nodes that are element vertices."""
        return np.unique(self.cells[:, :self.vertex_count])

    def save(self, path: Path) -> None:
        """Write to ``path`` (.npz), atomically."""
        path = Path(path)
        arrays = {"points": self.points, "cells": self.cells}
        arrays.update({f"boundary:{k}": v for k, v in self.boundaries.items()})
        arrays.update({f"points_of:{k}": v for k, v in self.points_of.items()})
        if self.cell_quality is not None:
            arrays["cell_quality"] = self.cell_quality
        meta = json.dumps({"cell_type": self.cell_type, "info": self.info})

        with atomic_path(path) as tmp, open(tmp, "wb") as handle:
            np.savez(handle, meta=np.array(meta), **arrays)

    @classmethod
    def load(cls, path: Path) -> "FEMesh":
        with np.load(path, allow_pickle=False) as data:
            meta = json.loads(str(data["meta"]))
            return cls(points=data["points"], cells=data["cells"], cell_type=meta["cell_type"],
                       boundaries={k.split(":", 1)[1]: data[k] for k in data.files
                                   if k.startswith("boundary:")},
                       points_of={k.split(":", 1)[1]: data[k] for k in data.files
                                  if k.startswith("points_of:")},
                       info=meta["info"],
                       cell_quality=data["cell_quality"] if "cell_quality" in data.files
                       else None)
