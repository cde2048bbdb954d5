"""Draws fmu-crate/assets/model.png, the FMU's icon (a wheel on a rail with the contact patch and its bristle grid): .venv/bin/python fmu-crate/assets/make_icon.py"""
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import Circle, Ellipse, Rectangle

fig = plt.figure(figsize=(1.28, 1.28), dpi=100)
ax = fig.add_axes([0, 0, 1, 1])
ax.set_xlim(0, 1)
ax.set_ylim(0, 1)
ax.axis("off")
ax.add_patch(Rectangle((0.02, 0.08), 0.96, 0.16, color="#6b6b6b"))            # rail
ax.add_patch(Circle((0.5, 0.62), 0.36, color="#2f4f8f"))                        # wheel
ax.add_patch(Circle((0.5, 0.62), 0.08, color="#d9d9d9"))                        # hub
ax.add_patch(Ellipse((0.5, 0.255), 0.34, 0.07, color="#e8a317", zorder=3))      # contact patch
for k in range(7):                                                              # bristles
    x = 0.36 + 0.28 * k / 6
    ax.plot([x, x + 0.02 + 0.01 * k], [0.23, 0.28], color="#7a3d00", lw=1.0, zorder=4)
fig.savefig(pathlib.Path(__file__).with_name("model.png"), dpi=100)
