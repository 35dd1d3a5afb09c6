"""The still picture of a lumped mode (matplotlib, off-screen): each body at rest as a
dashed outline, moved by the mode as a filled shape, and its motion as arrows, a straight
one from its centre for its translation and a curved one around its centre for its turn.

Geometry and motion are those of ``render.modes`` (toothed plates of the base diameters,
the carrier as arms to the planet centres, planet coordinates in the carrier frame).  Two
scales, both stated in the picture: the bodies are moved so the largest displacement is
``AMPLITUDE`` of the ring radius, the arrows so the largest motion is ``ARROW`` of it (arc
length for a turn, at the arrow's own radius: the arrow's length is the motion's size).
Motions below ``SMALLEST`` of the largest get no arrow; each body's arrows are a dark
shade of its colour (the sun's and the carrier's both start at the centre).
"""
from __future__ import annotations

import math

import numpy as np

from .lumped_geometry import AMPLITUDE, COLOURS, PLANET_COLOUR, motion, toothed_outline

#: the largest motion's arrow, as a fraction of the ring radius
ARROW = 0.32
#: motions smaller than this fraction of the largest get no arrow
SMALLEST = 0.03
#: size of the saved picture [in] and its resolution [dpi]: 900 x 900 px
SIZE_IN = 9.0
DPI = 100
#: text sizes [pt] at the saved size
TITLE_PT = 14
TEXT_PT = 12
#: each body's arrows: a dark shade of its colour, so the sun's and the carrier's arrows,
#: both from the centre, are told apart; a white rim keeps them visible over any fill
ARROW_COLOURS = {"sun": "#8c3500", "ring": "#2f2a75", "carrier": "#111111"}
PLANET_ARROW = "#0a5a42"
#: the arrowhead's size [pt], at most and at least: a short arrow gets a smaller head, so
#: its length still shows the motion's size
HEAD_PT = (14.0, 22.0)
#: the ring's outer radius as drawn, as a fraction of its pitch radius
RING_OUTER = 1.18


def arrow_colour(name: str) -> str:
    return ARROW_COLOURS.get(name, PLANET_ARROW)


def _arrow_style(name: str, length: float, scale: float) -> dict:
    """Colour, rim and head of the arrow of body ``name`` that is ``length`` [m] long in a
    picture of ``scale`` points per metre."""
    from matplotlib import patheffects

    head = min(max(0.5 * length * scale, HEAD_PT[0]), HEAD_PT[1])
    return {"color": arrow_colour(name), "mutation_scale": head, "lw": 2.6, "zorder": 6,
            "path_effects": [patheffects.withStroke(linewidth=4.6, foreground="white")]}


def _geometry(params) -> dict:
    """Each member's outlines at rest (closed polygons, (n, 2) [m]), centre and radius."""
    r_s, r_p, r_r = params.d_s / 2, params.d_p / 2, params.d_r / 2
    r_c = r_s + r_p
    teeth = {name: max(8, round(2 * math.pi * r / 10.2e-3))
             for name, r in (("sun", r_s), ("planet", r_p), ("ring", r_r))}

    def circle(radius, n=180):
        phi = np.linspace(0, 2 * math.pi, n, endpoint=False)
        return np.column_stack([radius * np.cos(phi), radius * np.sin(phi)])

    bodies = {"ring": ([circle(RING_OUTER * r_r), toothed_outline(r_r, teeth["ring"], -2.5e-3)],
                       np.zeros(2), r_r),
              "sun": ([toothed_outline(r_s, teeth["sun"], 2.5e-3), circle(0.35 * r_s)],
                      np.zeros(2), r_s)}
    centres = []
    for i, theta in enumerate(params.theta):
        centre = r_c * np.array([math.cos(theta), math.sin(theta)])
        centres.append(centre)
        bodies[f"planet {i + 1}"] = (
            [toothed_outline(r_p, teeth["planet"], 2.5e-3) + centre,
             circle(0.3 * r_p) + centre], centre, r_p)
    half = 0.06 * r_c
    arms = []
    for c in centres:
        along = c / np.hypot(*c)
        side = half * np.array([-along[1], along[0]])
        arms.append(np.array([side, c + side, c - side, -side]))
    bodies["carrier"] = (arms, np.zeros(2), r_c)
    return bodies


def _moved(outlines, centre, dx, dy, angle):
    c, s = math.cos(angle), math.sin(angle)
    turn = np.array([[c, -s], [s, c]])
    return [(o - centre) @ turn.T + centre + (dx, dy) for o in outlines]


def _path(outlines, holes: bool = True):
    """A compound path of closed polygons: the first counter-clockwise, the others (its
    holes) clockwise, so the non-zero fill leaves the holes open; all counter-clockwise
    without ``holes`` (the carrier's arms)."""
    from matplotlib.path import Path as MplPath

    vertices, codes = [], []
    for k, o in enumerate(outlines):
        area = 0.5 * np.sum(o[:, 0] * np.roll(o[:, 1], -1) - np.roll(o[:, 0], -1) * o[:, 1])
        if (area > 0) != (k == 0 or not holes):
            o = o[::-1]
        vertices += [*o, o[0]]
        codes += [MplPath.MOVETO] + [MplPath.LINETO] * (len(o) - 1) + [MplPath.CLOSEPOLY]
    return MplPath(np.array(vertices), codes)


def _arc_arrow(ax, centre, radius, sweep, gid: str, start: float = 35.0, **style):
    """A curved arrow around ``centre`` at ``radius`` [m] over ``sweep`` [rad] (sign:
    counter-clockwise positive), starting at ``start`` [deg] (the body's upper right)."""
    from matplotlib.patches import FancyArrowPatch
    from matplotlib.path import Path as MplPath

    phi = math.radians(start) + np.linspace(0.0, sweep, max(8, int(abs(sweep) / 0.05)))
    points = centre + radius * np.column_stack([np.cos(phi), np.sin(phi)])
    ax.add_patch(FancyArrowPatch(path=MplPath(points), arrowstyle="-|>", gid=gid, **style))


def mode_figure(params, shape: np.ndarray, title: str):
    """The matplotlib figure of the mode ``shape`` (network coordinate order) of ``params``
    (a ``PlanetaryParameters``) under ``title``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyArrowPatch, Patch, PathPatch

    bodies = _geometry(params)
    r_c = params.d_s / 2 + params.d_p / 2
    ring_radius = params.d_r / 2
    motions = {name: motion(params, shape, name, r_c) for name in bodies}
    sizes = {name: (math.hypot(dx, dy), abs(a) * bodies[name][2])
             for name, (dx, dy, a) in motions.items()}
    largest = max(max(v) for v in sizes.values())
    move = AMPLITUDE * ring_radius / largest if largest > 0 else 0.0
    arrow = ARROW * ring_radius / largest if largest > 0 else 0.0
    fig, ax = plt.subplots(figsize=(SIZE_IN, SIZE_IN), dpi=DPI, layout="constrained")
    order = ("carrier", "ring", "sun", *[n for n in bodies if n.startswith("planet")])
    for name in order:
        outlines, centre, _ = bodies[name]
        dx, dy, angle = motions[name]
        colour = COLOURS.get(name, PLANET_COLOUR)
        moved = _moved(outlines, centre, move * dx, move * dy, move * angle)
        ax.add_patch(PathPatch(_path(moved, name != "carrier"), facecolor=colour, edgecolor="none", alpha=0.8,
                               zorder=2 if name != "carrier" else 3))
        ax.add_patch(PathPatch(_path(outlines, name != "carrier"), facecolor="none", edgecolor="0.15", lw=1.0,
                               ls=(0, (4, 3)), zorder=4))
    # the moved ring whole (a translation of AMPLITUDE cut its outer edge off)
    limit = (RING_OUTER + AMPLITUDE + 0.03) * ring_radius
    scale = 0.8 * SIZE_IN * 72 / (2 * limit)  # points per metre (the axes: ~80 % wide)
    for name in order:
        _, centre, radius = bodies[name]
        dx, dy, angle = motions[name]
        translation, turn = sizes[name]
        if translation >= SMALLEST * largest:
            tip = centre + arrow * np.array([dx, dy])
            ax.add_patch(FancyArrowPatch(centre, tip, arrowstyle="-|>", shrinkA=0, shrinkB=0,
                                         gid=f"translation {name}",
                                         **_arrow_style(name, arrow * translation, scale)))
        if turn >= SMALLEST * largest:
            at = {"ring": 1.09 * ring_radius, "carrier": 0.5 * r_c}.get(name, 0.65 * radius)
            sweep = math.copysign(min(arrow * turn / at, math.radians(300)), angle)
            # the carrier's turn lies over the sun: it starts on the side opposite the
            # sun's, so the two arcs do not run into each other
            _arc_arrow(ax, centre, at, sweep, f"turn {name}",
                       215.0 if name == "carrier" else 35.0,
                       **_arrow_style(name, abs(sweep) * at, scale))
    ax.set_xlim(-limit, limit)
    ax.set_ylim(-limit, limit)
    ax.set_aspect("equal")
    ax.axis("off")
    fig.suptitle(title, fontsize=TITLE_PT)
    ax.set_title(f"filled: moved by the mode (largest displacement {100 * AMPLITUDE:g} % of "
                 f"the ring radius)\narrows: the motion (largest {100 * ARROW:g} % of the "
                 f"ring radius; none below {100 * SMALLEST:g} % of the largest)",
                 fontsize=TEXT_PT)
    handles = [Patch(facecolor=COLOURS["sun"], alpha=0.8, label="sun"),
               Patch(facecolor=PLANET_COLOUR, alpha=0.8, label="planets"),
               Patch(facecolor=COLOURS["ring"], alpha=0.8, label="ring"),
               Patch(facecolor=COLOURS["carrier"], alpha=0.8, label="carrier"),
               Line2D([], [], color="0.15", lw=1.0, ls=(0, (4, 3)), label="at rest"),
               Line2D([], [], color=ARROW_COLOURS["carrier"], lw=2.6, marker=">", ms=9,
                      label="arrows: translation, turn (curved),\nin a dark shade of the "
                            "body's colour")]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=TEXT_PT,
               frameon=False)
    return fig


def save_mode_figure(params, shape: np.ndarray, title: str, path) -> None:
    """``mode_figure`` written as a PNG of ``SIZE_IN`` inches at ``DPI`` to ``path``."""
    import matplotlib.pyplot as plt

    fig = mode_figure(params, shape, title)
    try:
        fig.savefig(path, format="png", dpi=DPI)
    finally:
        plt.close(fig)
