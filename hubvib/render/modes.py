"""Off-screen renders of lumped mode shapes: gear-like bodies moved by the mode (the PNG
drawn by ``mode_figure`` with arrows for the motion; the GIF animation and the VTM by
pyvista).

Sun, planets and ring are drawn as toothed plates of their base diameters, the
carrier as arms to the planet centres.  Each body is translated by its (x, y)
and turned by ``u / r_b`` (the rotation coordinate is an arc length on the
base circle).  Planet coordinates (tau, eta) are in the carrier frame at the
planet's angle and are added to the carrier's own motion there.  The mode is
scaled so its largest displacement is ``AMPLITUDE`` of the ring radius; shapes
are sign-fixed by the eigensolver, so the same mode renders identically.
"""
from __future__ import annotations

import math
import os
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from hubvib.foundation.output import atomic_path

from .lumped_geometry import AMPLITUDE, COLOURS, motion as _motion
from .lumped_geometry import toothed_outline as _toothed_outline

TOOTH_PITCH = 10.2e-3   # [m] arc between drawn teeth (module 3.25 mm: pi m)
THICKNESS = 0.02        # [m] plate thickness, for shading only
SIZE = (900, 900)       # [px]
#: zlib level of the PNG files (Pillow's default: 6), the same pixels: encoding is
#: faster than at 6 and the files hardly larger (level 1 gains no more time)
PNG_COMPRESSION = 3
#: what the colours, the grey outline and the scale of a mode render mean (in the picture)
LEGEND = (f"sun orange, planets green, ring purple, carrier grey; grey outline: at rest; "
          f"largest displacement drawn as {100 * AMPLITUDE:g} % of the ring radius")


def _plate(outline: np.ndarray, hole: float):
    """Plate between a toothed outline and a round hole of radius ``hole``, extruded."""
    phi = np.arctan2(outline[:, 1], outline[:, 0])
    return _between(np.column_stack([hole * np.cos(phi), hole * np.sin(phi)]), outline)


def _annulus(toothed: np.ndarray, outer: float):
    """Ring with internal teeth ``toothed`` and a round rim of radius ``outer``, extruded."""
    phi = np.arctan2(toothed[:, 1], toothed[:, 0])
    return _between(toothed, np.column_stack([outer * np.cos(phi), outer * np.sin(phi)]))


def _between(inner: np.ndarray, outer: np.ndarray):
    """Extruded quad strip between two closed polygons with matching points."""
    import pyvista as pv

    n = len(inner)
    i = np.arange(n)
    j = (i + 1) % n
    faces = np.column_stack([np.full(n, 4), i, j, n + j, n + i]).ravel()
    points = np.vstack([inner, outer])
    surface = pv.PolyData(np.column_stack([points, np.zeros(len(points))]), faces=faces)
    return surface.extrude((0, 0, THICKNESS), capping=True)


def _bodies(params):
    """Reference geometry of each member and where its centre is [m]."""
    r_s, r_p, r_r = params.d_s / 2, params.d_p / 2, params.d_r / 2
    r_c = r_s + r_p  # planet centres on the carrier
    teeth = {name: max(8, round(2 * math.pi * r / TOOTH_PITCH))
             for name, r in (("sun", r_s), ("planet", r_p), ("ring", r_r))}
    bodies = {"sun": (_plate(_toothed_outline(r_s, teeth["sun"], 2.5e-3), 0.35 * r_s),
                      np.zeros(2), r_s),
              "ring": (_annulus(_toothed_outline(r_r, teeth["ring"], -2.5e-3), 1.18 * r_r),
                       np.zeros(2), r_r)}
    for i, theta in enumerate(params.theta):
        centre = r_c * np.array([math.cos(theta), math.sin(theta)])
        plate = _plate(_toothed_outline(r_p, teeth["planet"], 2.5e-3), 0.3 * r_p)
        bodies[f"planet {i + 1}"] = (plate.translate((*centre, 0.0)), centre, r_p)
    return bodies, r_c


def _carrier(centres: list[np.ndarray], width: float):
    import pyvista as pv

    arms = [pv.Tube(pointa=(0, 0, -THICKNESS), pointb=(*c, -THICKNESS), radius=width)
            for c in centres]
    return arms[0].merge(arms[1:]) if len(arms) > 1 else arms[0]


def deformed_bodies(params, shape: np.ndarray, phase: float = 1.0) -> dict:
    """Each member's mesh moved by ``phase`` times the scaled mode ``shape``."""
    bodies, r_c = _bodies(params)
    centres = [c for name, (_, c, _) in bodies.items() if name.startswith("planet")]
    bodies["carrier"] = (_carrier(centres, 0.06 * r_c), np.zeros(2), r_c)
    ring_radius = params.d_r / 2
    motions = {name: _motion(params, shape, name, r_c) for name in bodies}
    largest = max(max(abs(dx), abs(dy), abs(a) * r) for (dx, dy, a), (_, _, r) in
                  zip(motions.values(), bodies.values()))
    scale = phase * AMPLITUDE * ring_radius / largest if largest > 0 else 0.0
    moved = {}
    for name, (mesh, centre, _) in bodies.items():
        dx, dy, angle = (scale * v for v in motions[name])
        out = mesh.translate((-centre[0], -centre[1], 0.0), inplace=False)
        out = out.rotate_z(math.degrees(angle), inplace=False)
        moved[name] = out.translate((centre[0] + dx, centre[1] + dy, 0.0), inplace=False)
    return moved




def offscreen_plotter():
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    pv.OFF_SCREEN = True
    plotter = pv.Plotter(off_screen=True, window_size=SIZE)
    plotter.set_background("white")
    return plotter


@contextmanager
def plotter_for(plotter=None):
    """``plotter``, or a new ``offscreen_plotter`` closed after the block.

    One plotter serves many pictures (``clear_picture``, ``save_picture``), pixel for pixel
    as a new one per picture drew them, which cost a window, an OpenGL context and its
    shaders each time (the figures: ``docs/fe_accuracy.md``, Speed and memory).  Most of
    what is left is the render itself (multisampled on Mesa's llvmpipe; cheaper without
    anti-aliasing, dearer with FXAA)."""
    if plotter is not None:
        yield plotter
        return
    plotter = offscreen_plotter()
    try:
        yield plotter
    finally:
        plotter.close()


def clear_picture(plotter) -> None:
    """Remove every actor and scalar bar from ``plotter`` (its lights, background and
    window stay) and hold its renders until ``save_picture``: on a plotter that has
    rendered, every ``add_mesh`` would render again."""
    plotter.suppress_rendering = True
    for title in list(plotter.scalar_bars.keys()):
        plotter.remove_scalar_bar(title, render=False)
    plotter.clear_actors()


def save_picture(plotter, path: Path) -> None:
    """Render ``plotter`` once and write its picture to ``path`` (PNG)."""
    from PIL import Image

    plotter.suppress_rendering = False
    plotter.render()  # nothing on a new plotter: ``screenshot`` renders it the first time
    image = plotter.screenshot(None, return_img=True)
    Image.fromarray(image).save(path, format="PNG", compress_level=PNG_COMPRESSION)


def _draw(plotter, meshes: dict, reference: dict, label: str):
    for mesh in reference.values():
        plotter.add_mesh(mesh.extract_feature_edges(), color="#bbbbbb", line_width=1)
    for name, mesh in meshes.items():
        plotter.add_mesh(mesh, color=COLOURS.get(name, "#1b9e77"), smooth_shading=False)
    plotter.add_text(label, position="upper_left", font_size=12, color="black")
    plotter.view_xy()
    plotter.enable_parallel_projection()
    plotter.camera.zoom(1.25)


def write_atomically(path: Path, write) -> Path:
    """``write(tmp)`` into a temporary file that replaces ``path`` when it succeeds."""
    with atomic_path(path) as tmp:
        write(tmp)
    return path


def render_mode(params, spectrum, index: int, folder: Path, gif: bool = False,
                vtm: bool = False) -> list[Path]:
    """PNG (and GIF, VTM) of mode ``index`` (0-based) of ``spectrum``; returns the files.
    The PNG is ``mode_figure``'s (bodies at rest and moved, motion as arrows); the GIF
    animates the pyvista bodies; the VTM holds them moved by the mode."""
    from .mode_figure import save_mode_figure

    folder = Path(folder)
    shape = spectrum.shapes[:, index]
    omega = spectrum.omega[index]
    title = (f"rigid mode {index + 1}: {omega / (2 * math.pi):.2f} Hz ({omega:.1f} rad/s), "
             f"{spectrum.kind[index]}")
    stem = f"mode_{index + 1:02d}"
    files = [write_atomically(folder / f"{stem}.png",
                              lambda tmp: save_mode_figure(params, shape, title, tmp))]
    if gif:
        reference = deformed_bodies(params, shape, 0.0)
        label = f"{title}\n{LEGEND}"

        def animation(tmp):
            with plotter_for() as animated:
                animated.open_gif(str(tmp), fps=12)
                for phase in np.sin(np.linspace(0, 2 * math.pi, 24, endpoint=False)):
                    animated.clear()
                    _draw(animated, deformed_bodies(params, shape, float(phase)), reference,
                          label)
                    animated.write_frame()

        files.append(write_atomically(folder / f"{stem}.gif", animation))
    if vtm:
        import pyvista as pv

        blocks = pv.MultiBlock(deformed_bodies(params, shape))
        stem_path = folder / f"{stem}.vtm"
        blocks.save(str(stem_path))  # a .vtm plus a folder of pieces; written last, then listed
        files.append(stem_path)
    return files


def render_modes(params, spectrum, folder: Path, gif: bool = False, vtm: bool = False
                 ) -> list[Path]:
    """Every elastic mode of ``spectrum``: see ``render_mode``."""
    files = []
    for index in range(spectrum.omega.size):
        if spectrum.kind[index] != "rigid-body":
            files += render_mode(params, spectrum, index, folder, gif, vtm)
    return files
