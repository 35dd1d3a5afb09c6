"""
Off-screen render of a mode shape
=================================

The lowest translational mode of the Raba 118/76 lumped model drawn by PyVista off-screen
(no display needed): the sun, the ring and the planets as discs, moved by the mode's
translations (grey: at rest). ``hubvib run`` renders every mode shape of a study this way.
"""
import math
import os
import tempfile
from pathlib import Path

import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import numpy as np

from hubvib import lumped
from hubvib.reducer import lumped_preset

params = lumped_preset("raba118")
spectrum = lumped.natural_modes(params)
index = spectrum.kind.index("translational")
shape = dict(zip(lumped.dof_names(len(params.theta)), spectrum.shapes[:, index]))
print(f"mode {index + 1}: {spectrum.kind[index]}, {spectrum.omega[index]:.2f} rad/s")

# %%
# Centres of the bodies at rest [m] and their translations in the mode (planets: ``eta``
# radial and ``tau`` tangential in the carrier frame).
r_c = params.d_c / 2
centres = {"sun": np.zeros(2), "ring": np.zeros(2)}
moves = {"sun": np.array([shape["x_s"], shape["y_s"]]),
         "ring": np.array([shape["x_r"], shape["y_r"]])}
for i, angle in enumerate(params.theta):
    radial = np.array([math.cos(angle), math.sin(angle)])
    tangential = np.array([-radial[1], radial[0]])
    centres[f"planet {i + 1}"] = r_c * radial
    moves[f"planet {i + 1}"] = (np.array([shape["x_c"], shape["y_c"]])
                                + shape[f"eta_{i + 1}"] * radial
                                + shape[f"tau_{i + 1}"] * tangential)
scale = 0.15 * params.d_r / max(np.linalg.norm(m) for m in moves.values())

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
import pyvista as pv  # noqa: E402  (heavy and optional: imported where it is used)

plotter = pv.Plotter(off_screen=True, window_size=(600, 600))
plotter.set_background("white")
radii = {"sun": (0.0, params.d_s / 2), "ring": (params.d_r / 2, 0.6 * params.d_r)}
for name, (x, y) in centres.items():
    inner, outer = radii.get(name, (0.0, params.d_p / 2))
    for offset, colour, opacity in ((np.zeros(2), "lightgrey", 0.4),
                                    (scale * moves[name], "tab:blue", 0.9)):
        disc = pv.Disc(center=(x + offset[0], y + offset[1], 0.0), inner=inner, outer=outer,
                       c_res=72)
        plotter.add_mesh(disc, color=colour, opacity=opacity)
plotter.view_xy()
png = Path(tempfile.mkdtemp()) / "mode.png"
plotter.screenshot(str(png))
plotter.close()

# %%
# The picture PyVista wrote off-screen, shown with matplotlib so that the gallery keeps it.
fig, ax = plt.subplots(figsize=(5, 5))
ax.imshow(mpimg.imread(png))
ax.set_title(f"mode {index + 1}, {spectrum.omega[index] / (2 * math.pi):.1f} Hz, "
             f"translations x{scale:.3g}")
ax.set_axis_off()
