"""One look for every gallery figure: seed figure number in the title, units on every axis."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({
    "figure.dpi": 100,
    "savefig.dpi": 110,
    "font.size": 9.5,
    "axes.titlesize": 10,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "legend.fontsize": 8,
    "legend.framealpha": 0.85,
    "lines.linewidth": 1.4,
})

# regime colours (R1 steep rise, R2 moderate rise, R3 falling branch)
REGIME_COLORS = {"R1": "#d9ecff", "R2": "#e4f5dc", "R3": "#fde2d6"}
MODEL_COLORS = {"fastsim": "#7f7f7f", "polach": "#9467bd", "dry": "#d62728", "wet": "#1f77b4"}


def figure(nrows=1, ncols=1, w=6.4, h=4.2, **kw):
    fig, axes = plt.subplots(nrows, ncols, figsize=(w, h), squeeze=False, **kw)
    return fig, axes


def save(fig, outdir: Path, name: str, suptitle: str) -> str:
    fig.suptitle(suptitle, fontsize=11, fontweight="bold")
    fig.tight_layout()
    outdir.mkdir(parents=True, exist_ok=True)
    fig.savefig(outdir / name)
    plt.close(fig)
    return name


def label_panel(ax, text: str):
    ax.set_title(text, loc="left")


def shade_regimes(ax, c12_pct: float, cmax_pct: float, xmax_pct: float, ytext=None):
    """Shades R1 [0, c12], R2 [c12, c_max], R3 [c_max, xmax] (creepage axis in %)."""
    ax.axvspan(0, c12_pct, color=REGIME_COLORS["R1"], zorder=0, lw=0)
    ax.axvspan(c12_pct, cmax_pct, color=REGIME_COLORS["R2"], zorder=0, lw=0)
    ax.axvspan(cmax_pct, xmax_pct, color=REGIME_COLORS["R3"], zorder=0, lw=0)
