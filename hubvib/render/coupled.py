"""Off-screen renders of the elastic-ring model's coupled modes: the FE ring's deformation
field with the lumped sun, carrier and planets moved by the same mode, PNG per mode, and
one VTU of the ring with every mode's displacement for ParaView (SI inside).

The ring is drawn on its corner nodes (linear triangles), coloured by its displacement
magnitude; the lumped bodies as in ``render.modes``.  One scale for the whole picture: the
largest displacement, ring or body, is drawn as ``modes.AMPLITUDE`` of the ring's outer
radius.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .modes import (AMPLITUDE, COLOURS, _bodies, _carrier, _motion, clear_picture,
                    plotter_for, save_picture, write_atomically)

LEGEND = ("ring: FE body coloured by its displacement; sun orange, planets green, carrier "
          f"grey;\ngrey outline: at rest; largest displacement drawn as {100 * AMPLITUDE:g} % "
          "of the ring radius")



def _ring_geometry(er):
    fe = er.body.model.basis.mesh
    corners = np.unique(fe.t)
    index = np.full(fe.p.shape[1], -1)
    index[corners] = np.arange(corners.size)
    return fe.p[:, corners].T, index[fe.t.T], er.body.model.basis.nodal_dofs[:, corners]


def ring_displacements(er, spectrum) -> np.ndarray:
    """(modes, corner nodes, 2): each coupled mode's ring displacement [m/sqrt(kg)]."""
    _, _, dofs = _ring_geometry(er)
    full = er.body.expand @ (er.basis.V @ spectrum.modes.ring)  # (model dofs, modes)
    return np.stack([full[dofs[0]].T, full[dofs[1]].T], axis=-1)


def _lumped_shape(spectrum, n_planets: int) -> np.ndarray:
    """The coupled modes' lumped part in the 9 + 3N order, the ring's rigid DOFs zero."""
    from hubvib.lumped.network import dof_names

    names = dof_names(n_planets)
    out = np.zeros((len(names), spectrum.modes.omega.size))
    for row, name in enumerate(spectrum.modes.lumped_names):
        out[names.index(name)] = spectrum.modes.lumped[row]
    return out


def _grid(points, triangles, displacement=None):
    import pyvista as pv

    xyz = np.column_stack([points, np.zeros(len(points))])
    if displacement is not None:
        xyz[:, :2] += displacement
    return pv.UnstructuredGrid({pv.CellType.TRIANGLE: triangles}, xyz)


#: the colour bar of the ring's displacement (fe's bar, with its own title)
BAR_TITLE = "ring displacement / largest"


def mounting_of(er) -> str:
    """The elastic ring's mounting in words (``render.fe.mounting_words``)."""
    from .fe import mounting_words

    return mounting_words(er.body.mounting, er.foundation)


def mode_title(spectrum, j: int, mounting: str) -> str:
    """What a coupled mode's picture says about it: number, frequency, class, nodal
    diameters, ring share and the mounting."""
    from hubvib.elastic.content import elastic_label

    content = spectrum.content[j]
    return (f"{elastic_label(content, spectrum.frequency_hz[j])}: the elastic ring's coupled "
            f"mode {j + 1}, ring nodal diameters n = {content.nodal_diameter},\nring share "
            f"{content.ring_share:.2f}; ring {mounting}")


def elastic_mode_file(rank: int, spectrum, j: int, mounting: str) -> str:
    """The file name of a watched coupled mode's picture: its rank among the watched modes,
    class, nodal diameters, frequency [Hz] and the ring's mounting (the caption reads them
    back, ``render.captions``)."""
    content = spectrum.content[j]
    return (f"elastic_mode_{rank + 1:02d}_{content.kind}_n{content.nodal_diameter}_"
            f"{spectrum.frequency_hz[j]:.0f}Hz_{mounting}.png")


def render_coupled_modes(er, spectrum, folder: Path, vtu: bool = True, modes=None,
                         names=None) -> list[Path]:
    """PNG of the coupled modes ``modes`` (0-based; None: all) of ``spectrum`` (an
    ``elastic.ElasticSpectrum`` of ``er``), named ``names(rank, j)`` (default
    ``coupled_mode_NN.png``): the ring's deformed mesh coloured by its displacement
    magnitude with a colour bar, the lumped bodies moved by the same mode, the mode's
    class, nodal diameters, frequency and the ring's mounting in the title; with ``vtu``,
    ``coupled_modes.vtu``: the ring with point data ``mode_NN`` (displacement, 3
    components) and field data ``frequency_hz``."""
    from .fe import _BAR, _label, _readable_bars

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    points, triangles, _ = _ring_geometry(er)
    ring_u = ring_displacements(er, spectrum)
    params = er.params.replace(theta=spectrum.modes.engagement.theta)
    lumped = _lumped_shape(spectrum, params.n_planets)
    bodies, r_c = _bodies(params)
    bodies.pop("ring")
    centres = [c for name, (_, c, _) in bodies.items() if name.startswith("planet")]
    bodies["carrier"] = (_carrier(centres, 0.06 * r_c), np.zeros(2), r_c)
    outer = float(np.hypot(*points.T).max())
    rest = _grid(points, triangles).extract_feature_edges()
    mounting = mounting_of(er)
    chosen = range(spectrum.frequency_hz.size) if modes is None else [int(j) for j in modes]
    names = names or (lambda rank, j: f"coupled_mode_{j + 1:02d}.png")
    files = []
    with plotter_for() as plotter:
        for rank, j in enumerate(chosen):
            motions = {name: _motion(params, lumped[:, j], name, r_c) for name in bodies}
            size = np.hypot(*ring_u[j].T)
            largest = max([float(np.abs(ring_u[j]).max())] + [
                max(abs(dx), abs(dy), abs(a) * r)
                for (dx, dy, a), (_, _, r) in zip(motions.values(), bodies.values())])
            scale = AMPLITUDE * outer / largest if largest > 0 else 0.0
            ring = _grid(points, triangles, scale * ring_u[j])
            ring.point_data[BAR_TITLE] = size / size.max() if size.max() > 0 else size
            label = f"{mode_title(spectrum, j, mounting)}\n{LEGEND}"

            def png(tmp, ring=ring, motions=motions, scale=scale, label=label):
                clear_picture(plotter)
                plotter.add_mesh(rest, color="#bbbbbb", line_width=1)
                plotter.add_mesh(ring, scalars=BAR_TITLE, cmap="viridis", clim=(0.0, 1.0),
                                 scalar_bar_args=_BAR | {"title": BAR_TITLE})
                for name, (mesh, centre, _) in bodies.items():
                    dx, dy, angle = (scale * v for v in motions[name])
                    moved = mesh.translate((-centre[0], -centre[1], 0.0), inplace=False)
                    moved = moved.rotate_z(math.degrees(angle), inplace=False)
                    moved = moved.translate((centre[0] + dx, centre[1] + dy, 0.0),
                                            inplace=False)
                    plotter.add_mesh(moved, color=COLOURS.get(name, "#1b9e77"))
                _label(plotter, label)
                _readable_bars(plotter)
                plotter.view_xy()
                plotter.enable_parallel_projection()
                save_picture(plotter, tmp)

            files.append(write_atomically(folder / names(rank, j), png))
    if vtu:
        grid = _grid(points, triangles)
        for j in range(ring_u.shape[0]):
            grid.point_data[f"mode_{j + 1:02d}"] = np.column_stack(
                [ring_u[j], np.zeros(len(points))])
        grid.field_data["frequency_hz"] = np.asarray(spectrum.frequency_hz)
        files.append(write_atomically(folder / "coupled_modes.vtu",
                                      lambda tmp: grid.save(str(tmp), binary=True)))
    return files


def render_watched_modes(er, spectrum, watched, folder: Path) -> list[Path]:
    """The pictures of the watched coupled modes ``watched`` (0-based, best first) of
    ``spectrum``, named by ``elastic_mode_file`` (no VTU)."""
    kind = er.body.mounting
    return render_coupled_modes(
        er, spectrum, folder, vtu=False, modes=watched,
        names=lambda rank, j: elastic_mode_file(rank, spectrum, j, kind))
