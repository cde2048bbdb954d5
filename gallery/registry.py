"""All gallery figures, in README order."""
from __future__ import annotations

from . import figs_drivetrain, figs_fmu, figs_material, figs_steady, figs_transient, figs_twindisc

SECTIONS = [
    ("steady", "Quasi-steady results (seed Sec. 4.4, 6.1)"),
    ("transient", "Transient results (seed Sec. 4.5)"),
    ("material", "The 3BL material law (seed Sec. 5.1, 5.2)"),
    ("drivetrain", "Validation set-ups (seed Sec. 6.2, 6.3)"),
    ("notes", "Numerical notes"),
]

FIGURES = (figs_steady.FIGURES + figs_transient.FIGURES + figs_fmu.FIGURES + figs_material.FIGURES
           + figs_drivetrain.FIGURES + figs_twindisc.FIGURES + figs_transient.NOTES)

# figures whose producer belongs to another part of the project and may not be ready:
# when they fail, the gallery marks them pending with the reason instead of failing.
MAY_BE_PENDING = {"fig6_04_06"}


def by_key(key: str):
    for f in FIGURES:
        if f.key == key:
            return f
    raise KeyError(key)
