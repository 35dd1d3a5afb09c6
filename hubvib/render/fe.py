"""Off-screen renders of the FE ring: deformed under the planet mesh forces (von Mises),
a zoom on the crack tip, and the ring's lowest elastic modes on its mounting (SI inside).

The modes are those of the ring on the mounting asked (``MOUNTINGS``; the crack study
passes its elastic ring's: by default a Winkler foundation on the support arcs sized to the
design's lumped c_r and c_ru), the ring's rigid motions on that mounting left out: the
pictures show the ring's own modes, as the report's elastic ring section counts them.

The load is the operating one: each of the three planets pushes on its ring
tooth with the mesh force of the design's sun torque (``hubvib.design``); planet 1
sits on the cracked tooth.  Drawn on the corner nodes (linear triangles); the
deformation is magnified, by the factor printed on the image.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubvib.reducer.stages import lumped_parameters, material, mesh_force, ring_gear
from hubvib.fem.elasticity import solve
from hubvib.fem.ring_body import MOUNTINGS, Foundation, ring_body
from hubvib.fem.ring_stiffness import mesh_force_load, planet_teeth
from hubvib.fem.stress import von_mises
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh
from hubvib.render.modes import clear_picture, plotter_for, save_picture, write_atomically

MODES = 4
MAGNIFIED = 0.03  # largest drawn displacement as a fraction of the ring's outer radius
TIP_VIEW = 2.5e-3  # [m] half height of the crack-tip zoom


@dataclass(frozen=True)
class RingFields:
    """The ring's corner nodes and triangles with its loaded state and modes (SI)."""

    points: np.ndarray        # (n, 2) [m]
    triangles: np.ndarray     # (m, 3) into points
    displacement: np.ndarray  # (n, 2) [m] under the mesh forces
    von_mises: np.ndarray     # (n,) [Pa]
    mode_shapes: np.ndarray   # (k, n, 2) mass-normalised
    mode_hz: np.ndarray       # (k,)
    crack_tip: np.ndarray | None  # (2,) [m]
    ring_torque: float        # [N m]
    label: str
    mounting: str = "clamped"  # what the modes are computed on: one of ``MOUNTINGS``
    mounting_words: str = "clamped on its supports"
    mode_diameters: tuple = ()  # each mode's dominant nodal diameters on the mid-rim circle


def mounting_words(mounting: str, foundation: Foundation | None) -> str:
    """The mounting in words, for pictures and captions."""
    if mounting == "foundation":
        return (f"on a Winkler foundation over its support arcs (k_n {foundation.k_n:.3g}, "
                f"k_t {foundation.k_t:.3g} N/m^2)")
    return {"clamped": "clamped on its supports", "free": "free"}[mounting]


def elastic_modes(body, count: int) -> tuple[np.ndarray, np.ndarray, tuple]:
    """The ``count`` lowest elastic modes of a mounted ring (``fem.ring_body.RingBody``):
    frequencies [Hz], shapes on the body's free DOFs (M-normalised, largest entry positive)
    and dominant nodal diameters; the ring's rigid motions on its mounting (a rigid
    rotation or translation on the mid-rim circle) are left out."""
    import scipy.sparse.linalg as spla

    from hubvib.elastic.content import diameter_content, is_elastic_ring_shape
    from hubvib.fem.ring_basis import FREE_SHIFT
    from hubvib.fem.solvers import factorise, pick
    from hubvib.foundation.blas import blas_threads

    sigma = FREE_SHIFT if body.mounting == "free" else 0.0
    A = (body.K - sigma * body.M).tocsr() if sigma else body.K
    method = pick("auto", body.ndofs, 2)
    factor = factorise(A, "superlu" if method == "amg" else method)
    try:
        inverse = spla.LinearOperator(A.shape, matvec=factor.solve, dtype=float)
        k = min(count + 6, body.ndofs - 2)
        v0 = np.ones(body.ndofs) / np.sqrt(body.ndofs)
        with blas_threads(1):
            values, vectors = spla.eigsh(body.K, k=k, M=body.M, sigma=sigma, which="LM",
                                         v0=v0, OPinv=inverse)
    finally:
        factor.free()
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    probe = np.asarray(body.probe @ vectors)
    keep = [j for j in range(values.size) if is_elastic_ring_shape(probe[:, j])][:count]
    shapes = vectors[:, keep]
    shapes = shapes / np.sqrt(np.einsum("ij,ij->j", shapes, body.M @ shapes))
    signs = np.sign(shapes[np.abs(shapes).argmax(axis=0), np.arange(shapes.shape[1])])
    shapes = shapes * np.where(signs == 0, 1.0, signs)
    diameters = tuple(int(np.argmax(diameter_content(probe[:, j]))) for j in keep)
    hz = np.sqrt(np.clip(values[keep], 0.0, None)) / (2 * math.pi)
    return hz, shapes, diameters


def ring_fields(design, crack=None, options=None, modes: int = MODES,
                mounting: str = "clamped", foundation: tuple | None = None) -> RingFields:
    """Solve the design's ring under its planet mesh forces (at the design's sun torque, on
    its held supports) and for its lowest ``modes`` elastic modes on ``mounting`` (one of
    ``MOUNTINGS``); ``foundation``: (k_n, k_t) [N/m^2] of a ``"foundation"`` mounting, None:
    sized so that its rigid-ring totals are the design's lumped c_r and c_ru."""
    if mounting not in MOUNTINGS:
        raise ValueError(f"mounting = {mounting!r}; allowed: {', '.join(MOUNTINGS)}")
    ring = ring_gear(design)
    mesh = ring_mesh(ring, crack, options or MeshOptions())
    sized_to = None
    if mounting == "foundation" and foundation is None:
        params = lumped_parameters(design)
        sized_to = (params.c_r, params.c_ru)
    body = ring_body(ring, mesh, material(design), mounting,
                     None if foundation is None else Foundation(*foundation),
                     sized_to=sized_to)
    model = body.model
    force = mesh_force(design)
    tooth = 0 if crack is None else crack.tooth
    teeth = planet_teeth(ring, tooth, design.n_planets)
    u = solve(model, mesh_force_load(model, ring, teeth, force), ["supports"]).u
    stress = von_mises(model, u)
    fe = model.basis.mesh
    corners = np.unique(fe.t)
    index = np.full(fe.p.shape[1], -1)
    index[corners] = np.arange(len(corners))
    dofs = model.basis.nodal_dofs[:, corners]

    def at_corners(vector):
        return np.column_stack([vector[dofs[0]], vector[dofs[1]]])

    hz, shapes, diameters = elastic_modes(body, modes)
    full = body.expand @ shapes
    tip = None
    if crack is not None and len(mesh.points_of.get("crack_tip", [])):
        tip = mesh.points[mesh.points_of["crack_tip"]].reshape(-1, 2).mean(axis=0)
    torque = design.n_planets * force * ring.gear.base_diameter / 2
    what = "intact" if crack is None else (f"{crack.start} crack {1e3 * crack.depth:.3g} mm "
                                           f"at tooth {crack.tooth}")
    return RingFields(fe.p[:, corners].T, index[fe.t.T], at_corners(u), stress[corners],
                      np.array([at_corners(s) for s in full.T]), hz, tip, torque,
                      f"{design.name} ring, {what}", mounting,
                      mounting_words(mounting, body.foundation), diameters)


def _grid(fields: RingFields, displacement: np.ndarray, scale: float, scalars: dict):
    import pyvista as pv

    points = np.column_stack([fields.points + scale * displacement,
                              np.zeros(len(fields.points))])
    grid = pv.UnstructuredGrid({pv.CellType.TRIANGLE: fields.triangles}, points)
    for name, values in scalars.items():
        grid.point_data[name] = values
    return grid


def _scale(fields: RingFields, displacement: np.ndarray) -> float:
    largest = np.abs(displacement).max()
    outer = np.hypot(*fields.points.T).max()
    return MAGNIFIED * outer / largest if largest > 0 else 0.0


def _outline(fields: RingFields):
    return _grid(fields, fields.displacement, 0.0, {}).extract_feature_edges()


#: a vertical colour bar at the right with its title above the ticks (a horizontal bar's
#: title overlapped its tick labels)
_BAR = {"color": "black", "vertical": True, "position_x": 0.86, "position_y": 0.1,
        "height": 0.7, "width": 0.06, "title_font_size": 14, "label_font_size": 12,
        "n_labels": 5, "fmt": "%.3g"}
#: pixels between a colour bar's title and the top of the bar: the top tick label is
#: centred on that top and reaches half its height above it
_TITLE_SEPARATION = 8


def _readable_bars(plotter) -> None:
    """Each colour bar's title and tick labels black on opaque white boxes (readable over
    any colour of the map: the crack-tip close-up puts the bar over the mesh), the title
    clear of the top tick label."""
    for bar in plotter.scalar_bars.values():
        bar.SetVerticalTitleSeparation(_TITLE_SEPARATION)
        for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
            text.SetBackgroundColor(1.0, 1.0, 1.0)
            text.SetBackgroundOpacity(1.0)


#: the pictures' title size (pyvista font size at the 900 px window)
LABEL_FONT = 12


def _label(plotter, text: str, font_size: int = LABEL_FONT) -> None:
    """Black text on a white, mostly opaque box in the upper left: readable on any colour
    of the mesh under it (the crack-tip close-up's title was black on dark navy)."""
    actor = plotter.add_text(text, position="upper_left", font_size=font_size,
                             color="black")
    prop = actor.GetTextProperty()
    prop.SetBackgroundColor(1.0, 1.0, 1.0)
    prop.SetBackgroundOpacity(0.85)


def _scale_bar(plotter, centre) -> None:
    """A white bar of a round length [mm] in the lower left of the ``TIP_VIEW`` window,
    labelled: the close-up's length scale."""
    import pyvista as pv

    length = 10 ** math.floor(math.log10(0.5 * TIP_VIEW))  # [m]
    if 2 * length <= 0.5 * TIP_VIEW:
        length *= 2
    x0, y0 = centre[0] - 0.85 * TIP_VIEW, centre[1] - 0.85 * TIP_VIEW
    bar = pv.Line((x0, y0, 0.01), (x0 + length, y0, 0.01))
    plotter.add_mesh(bar, color="white", line_width=6)
    plotter.add_mesh(bar, color="black", line_width=2)
    plotter.add_point_labels([(x0 + length / 2, y0 + 0.06 * TIP_VIEW, 0.01)],
                             [f"{1e3 * length:g} mm"], font_size=14, text_color="black",
                             shape_color="white", shape_opacity=0.85, show_points=False,
                             always_visible=True)


def _picture(plotter, path: Path, draw, centre=None) -> Path:
    """Draw on ``plotter``, look along -z (at ``centre`` with a ``TIP_VIEW`` window if
    given), save."""
    def write(tmp):
        clear_picture(plotter)
        draw(plotter)
        _readable_bars(plotter)
        plotter.view_xy()
        plotter.enable_parallel_projection()
        if centre is not None:
            plotter.camera.focal_point = (*centre, 0.0)
            plotter.camera.position = (*centre, 1.0)
            plotter.camera.parallel_scale = TIP_VIEW
        save_picture(plotter, tmp)

    return write_atomically(path, write)


def mode_file(k: int, mounting: str) -> str:
    """The file name of FE ring mode ``k`` (0-based) computed on ``mounting``."""
    return f"fe_ring_mode_{k + 1:02d}_{mounting}.png"


def render_fe(fields: RingFields, folder: Path, vtu: bool = False) -> list[Path]:
    """PNG: the loaded ring, the crack tip (if any), each mode; VTU of all fields on request."""
    folder = Path(folder)
    scale = _scale(fields, fields.displacement)
    mpa = fields.von_mises / 1e6
    loaded = _grid(fields, fields.displacement, scale, {"von Mises [MPa]": mpa})
    title = (f"{fields.label}\nring torque {fields.ring_torque:.0f} N m (from the design's "
             f"sun torque), deformation x{scale:.0f}")
    colour = dict(scalars="von Mises [MPa]", cmap="turbo",
                  clim=(0.0, float(np.percentile(mpa, 99.5))),
                  scalar_bar_args=_BAR | {"title": "von Mises [MPa]"})
    outline = _outline(fields)

    def whole(plotter):
        plotter.add_mesh(outline, color="#bbbbbb", line_width=1)
        plotter.add_mesh(loaded, **colour)
        _label(plotter, title + "\ngrey: undeformed outline")

    with plotter_for() as plotter:  # one plotter for every picture
        files = [_picture(plotter, folder / "fe_ring_loaded.png", whole)]
        if fields.crack_tip is not None:
            distance = np.hypot(*(fields.points - fields.crack_tip).T)
            centre = fields.crack_tip + scale * fields.displacement[np.argmin(distance)]
            near = mpa[distance < TIP_VIEW]

            def tip(plotter):
                plotter.add_mesh(loaded, show_edges=True, edge_color="#333333",
                                 **dict(colour, clim=(0.0, float(np.percentile(near, 99)))))
                _label(plotter, f"{fields.label}: crack tip, deformation x{scale:.0f}")
                _scale_bar(plotter, centre)

            files.append(_picture(plotter, folder / "fe_crack_tip.png", tip, centre))
        for k, (shape, hz) in enumerate(zip(fields.mode_shapes, fields.mode_hz)):
            size = np.hypot(*shape.T)
            grid = _grid(fields, shape, _scale(fields, shape),
                         {"displacement (normalised)": size / size.max()})

            def mode(plotter, grid=grid, k=k, hz=hz):
                plotter.add_mesh(outline, color="#bbbbbb", line_width=1)
                plotter.add_mesh(grid, scalars="displacement (normalised)", cmap="viridis",
                                 scalar_bar_args=_BAR | {"title": "displacement / largest"})
                n = (f" (n = {fields.mode_diameters[k]})"
                     if k < len(fields.mode_diameters) else "")
                _label(plotter, f"{fields.label}\nFE ring mode {k + 1}{n}: {hz:.1f} Hz,\n"
                       f"{fields.mounting_words}\ncolour: displacement / largest; grey: "
                       f"undeformed outline;\nlargest displacement drawn as "
                       f"{100 * MAGNIFIED:g} % of the outer radius")

            files.append(_picture(plotter, folder / mode_file(k, fields.mounting), mode))
    if vtu:
        data = {"displacement [m]": np.column_stack([fields.displacement,
                                                      np.zeros(len(fields.points))]),
                "von Mises [Pa]": fields.von_mises}
        for k, shape in enumerate(fields.mode_shapes):
            data[f"mode {k + 1} ({fields.mode_hz[k]:.1f} Hz)"] = np.column_stack(
                [shape, np.zeros(len(shape))])
        grid = _grid(fields, fields.displacement, 0.0, data)
        files.append(write_atomically(folder / "fe_ring.vtu", lambda tmp: grid.save(str(tmp))))
    return files
