"""Write an ``FEMesh`` for people: VTU for ParaView, PNG for reports."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from hubvib.foundation.output import atomic_path

from .fe_mesh import GMSH_TO_VTK_TETRA10, FEMesh

_MESHIO = {"triangle": "triangle", "triangle6": "triangle6", "tetra": "tetra",
           "tetra10": "tetra10"}
_FACETS = {(2, 1): "line", (2, 2): "line3", (3, 1): "triangle", (3, 2): "triangle6"}


def write_vtu(mesh: FEMesh, path: Path) -> Path:
    """VTU with the cells and every named boundary group as cells of its own.

    Cell data ``group`` holds the group number; field data maps names to numbers
    (0 is the body).  Written atomically.
    """
    import meshio

    names = sorted(mesh.boundaries)
    facet_type = _FACETS[(mesh.dim, mesh.order)]
    body = mesh.cells[:, GMSH_TO_VTK_TETRA10] if mesh.cell_type == "tetra10" else mesh.cells
    cells = [(_MESHIO[mesh.cell_type], body)]
    groups = [np.zeros(len(mesh.cells), dtype=np.int32)]
    for number, name in enumerate(names, start=1):
        elements = mesh.boundaries[name]
        if len(elements):
            if mesh.order == 2 and mesh.dim == 2:
                elements = elements[:, [0, 1, 2]]  # gmsh line3 is (v0, v1, mid) like VTK
            cells.append((facet_type, elements))
            groups.append(np.full(len(elements), number, dtype=np.int32))
    points = mesh.points if mesh.dim == 3 else np.column_stack(
        [mesh.points, np.zeros(len(mesh.points))])
    out = meshio.Mesh(points, cells, cell_data={"group": groups},
                      field_data={name: np.array([i, mesh.dim - 1]) for i, name in
                                  enumerate(names, start=1)})
    with atomic_path(path) as tmp:
        meshio.write(tmp, out, file_format="vtu")
    return Path(path)


def write_png(mesh: FEMesh, path: Path, centre=None, half_width: float | None = None,
              title: str = "") -> Path:
    """Picture of the mesh edges around ``centre`` [m] (default: the crack, else the whole part).

    Plane meshes: crack faces red, supports blue, load patches green.  Solid
    meshes with a crack: the crack face unfolded into (depth along the path, z),
    the front red; without a crack: the face z = 0.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    fig, ax = plt.subplots(figsize=(7, 7))
    if mesh.dim == 3 and "crack_a" in mesh.boundaries:
        _draw_crack_face(ax, mesh, LineCollection)
    else:
        plane = mesh if mesh.dim == 2 else FEMesh(mesh.points[:, :2], mesh.boundaries["face_0"],
                                                  "triangle", {}, {}, mesh.info)
        _draw_plane(ax, plane, centre, half_width, LineCollection)
    ax.set_aspect("equal")
    ax.set_title(title or f"{mesh.info.get('elements', len(mesh.cells))} {mesh.cell_type} elements")
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=130, bbox_inches="tight")
    finally:
        plt.close(fig)
    return Path(path)


def _draw_plane(ax, mesh, centre, half_width, LineCollection):
    xy = mesh.points[:, :2]
    path_points = np.asarray(mesh.info.get("crack_path") or [])
    if centre is None and len(path_points):
        centre = path_points.mean(axis=0)
        half_width = half_width or 1.5 * np.ptp(path_points, axis=0).max() + 2e-3
    edges = mesh.cells[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    if centre is not None:
        centre = np.asarray(centre, dtype=float)
        inside = np.all(np.abs(xy[edges].mean(axis=1) - centre) < 1.2 * half_width, axis=1)
        edges = edges[inside]
    ax.add_collection(LineCollection(xy[edges], colors="0.35", linewidths=0.3))

    def colour_of(name):
        if name.startswith("crack_"):
            return "red"
        if name.startswith("support_"):
            return "tab:blue"
        return "tab:green" if name.endswith("_load") else None

    for name, elements in mesh.boundaries.items():
        colour = colour_of(name)
        if colour and len(elements):
            ax.add_collection(LineCollection(xy[elements[:, :2]], colors=colour, linewidths=1.5))
    if centre is not None:
        ax.set_xlim(centre[0] - half_width, centre[0] + half_width)
        ax.set_ylim(centre[1] - half_width, centre[1] + half_width)
    else:
        ax.autoscale()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def _draw_crack_face(ax, mesh, LineCollection):
    path = np.asarray(mesh.info["crack_path"])
    lengths = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    faces = mesh.boundaries["crack_a"]
    nodes = np.unique(faces)
    xy = mesh.points[nodes, :2]
    # depth along the polyline: project on each segment, keep the nearest
    best = np.full(len(nodes), np.inf)
    depth = np.zeros(len(nodes))
    for a, b, s0 in zip(path[:-1], path[1:], lengths[:-1]):
        d = (b - a) / np.hypot(*(b - a))
        t = np.clip((xy - a) @ d, 0, np.hypot(*(b - a)))
        gap = np.hypot(*(xy - a - t[:, None] * d).T)
        better = gap < best
        best[better], depth[better] = gap[better], s0 + t[better]
    unfolded = np.zeros((len(mesh.points), 2))
    unfolded[nodes] = np.column_stack([depth, mesh.points[nodes, 2]])
    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    ax.add_collection(LineCollection(unfolded[edges], colors="0.35", linewidths=0.4))
    front = mesh.points_of.get("crack_front", np.zeros(0, int))
    ax.plot(unfolded[front, 0], unfolded[front, 1], "r.", ms=3, label="crack front")
    ax.autoscale()
    ax.legend(loc="upper right")
    ax.set_xlabel("depth along the crack path [m]")
    ax.set_ylabel("z across the face width [m]")
