"""
Crack-depth sweep of the FE ring stiffness (fast accuracy)
==========================================================

The plane FE model of the Raba 118/76 ring gear with a root crack in tooth 0, at the
"fast" mesh level of a crack scene (element sizes doubled, ``scale = 2``): the ring body's
torsional stiffness ``c_ru`` (mean over the carrier positions of one planet pitch) and its
radial stiffness ``c_r``, each with its error estimate (the difference to a mesh twice as
coarse).
"""
import matplotlib.pyplot as plt
import numpy as np

from hubvib.reducer import raba118
from hubvib.fem.estimate import estimate_ring
from hubvib.meshing.crack import Crack

ring = raba118.ring_gear()
depths = [0.0, 0.004, 0.008]                     # [m]
# the rim parts of the work-conjugate split, the ring body the lumped model uses [N/m]
results = [estimate_ring(ring, Crack(0, d) if d > 0 else None, scale=2.0, definition="rim")
           for d in depths]
intact = results[0]
for depth, r in zip(depths, results):
    print(f"depth {1e3 * depth:4.1f} mm: c_ru {r.c_ru:.5g} ± {r.c_ru_error:.2g} N/m "
          f"({r.c_ru / intact.c_ru - 1:+.2%}), c_r {r.c_r:.5g} N/m ({r.c_r / intact.c_r - 1:+.2%}), "
          f"{r.dofs} DOFs")

# %%
# Relative change against the intact ring; the error bars are the change's own estimate,
# ``(fine - fine intact) - (coarse - coarse intact)``.
change = np.array([r.c_ru / intact.c_ru - 1 for r in results])
error = np.array([abs((r.c_ru - intact.c_ru) - (r.c_ru_coarse - intact.c_ru_coarse))
                  / intact.c_ru for r in results])
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.errorbar(1e3 * np.array(depths), 100 * change, yerr=100 * error, marker="o", capsize=3)
ax.set_xlabel("crack depth [mm]")
ax.set_ylabel("change of c_ru [%]")
ax.set_title("Raba 118/76 ring body, plane FE, fast level")
fig.tight_layout()
