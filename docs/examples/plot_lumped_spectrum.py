"""
Lumped spectrum of the Raba 118/76 reducer and a frequency shift
=================================================================

The 9 + 3N DOF planetary model of the paper's reducer: its natural frequencies, and how
each one moves when the ring's torsional support stiffness ``c_ru`` drops tenfold
(1e6 → 1e5 N/m), the paper's crack hypothesis.
"""
import matplotlib.pyplot as plt
import numpy as np

from hubvib import lumped
from hubvib.reducer import lumped_preset

params = lumped_preset("raba118")                # the paper's table, SI units
spectrum = lumped.natural_modes(params)          # energy-consistent model
for i in range(spectrum.omega.size):
    print(f"mode {i + 1:2d}  {spectrum.omega[i]:9.2f} rad/s  {spectrum.kind[i]}")

# %%
# Lower ``c_ru`` tenfold and follow every mode.
shift = lumped.frequency_shift(params, "c_ru", 1e5)
print(np.round(shift.percent[:4], 2))

fig, ax = plt.subplots(figsize=(7, 3.5))
modes = np.arange(1, spectrum.omega.size + 1)
ax.bar(modes, shift.percent, color=["C0" if k == "rotational" else "C1" for k in spectrum.kind])
ax.set_xlabel("mode")
ax.set_ylabel("shift [%]")
ax.set_title("Raba 118/76: c_ru 1e6 → 1e5 N/m (blue: rotational modes)")
ax.set_xticks(modes)
fig.tight_layout()
