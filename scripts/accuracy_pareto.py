"""Pareto PNGs of the accuracy table: largest F_x error against cost, one PNG per case.

Reads creep-core/data/accuracy.csv (written by `bash scripts/bench.sh --only accuracy`) and
writes docs/img/accuracy/pareto_<preset>_<kind>_<v>mps_<dt>ms.png: per case the largest F_x
error over the response (% of the extrapolated limit's largest value) against wall time /
simulated time on one thread, log-log, both schemes, each point labelled with its grid, the
Pareto front over both schemes (no other point is both cheaper and more accurate) drawn as a
line, a line at 1 % and one at real time.

    .venv/bin/python scripts/accuracy_pareto.py [CSV] [OUTDIR]
"""
from __future__ import annotations

import csv
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from gallery.plotstyle import figure, plt  # noqa: E402  (sets the Agg backend and the look)

SCHEMES = {"cells": ("#d62728", "o"), "continuous": ("#1f77b4", "s"), "cells-ho": ("#9467bd", "^")}
# label offsets (points) per scheme, so that the grid names of the three do not overlap
OFFSET = {"cells": (5, 3), "continuous": (5, -9), "cells-ho": (-30, 3)}


def read(path: Path) -> tuple[list[str], list[dict]]:
    """The comment lines and the rows of the table."""
    notes, body = [], []
    for line in path.read_text().splitlines():
        (notes if line.startswith("#") else body).append(line.lstrip("# ") if line.startswith("#") else line)
    rows = list(csv.DictReader(body))
    for r in rows:
        for k in ("v_m_s", "dt_ms", "fx_max_pct", "wall_per_sim", "fx_limit_unc_pct"):
            r[k] = float(r[k])
        r["nx"], r["ny"] = int(r["nx"]), int(r["ny"])
    return notes, rows


def front(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The non-dominated points (cost, error), by increasing cost."""
    out, best = [], float("inf")
    for c, e in sorted(points):
        if e < best:
            out.append((c, e))
            best = e
    return out


def num(x: float) -> str:
    return f"{x:g}".replace(".", "p")


def plot_case(key, rows: list[dict], measured: str, outdir: Path) -> str:
    preset, kind, v, dt = key
    fig, ax = figure(w=6.4, h=4.6)
    ax = ax[0][0]
    pts = []
    for scheme, (color, marker) in SCHEMES.items():
        rs = [r for r in rows if r["scheme"] == scheme]
        xs = [r["wall_per_sim"] for r in rs]
        ys = [max(r["fx_max_pct"], 1e-3) for r in rs]
        ax.plot(xs, ys, marker, color=color, label=scheme, ms=6, ls="none", zorder=3)
        for r, x, y in zip(rs, xs, ys):
            ax.annotate(f"{r['nx']}x{r['ny']}", (x, y), textcoords="offset points", xytext=OFFSET[scheme],
                        fontsize=7.5, color=color)
        pts += list(zip(xs, ys))
    fr = front(pts)
    ax.plot([p[0] for p in fr], [p[1] for p in fr], "-", color="#2ca02c", lw=5, alpha=0.35, zorder=2,
            label="Pareto front (all schemes)")
    ax.axhline(1.0, color="k", ls="--", lw=1, label="1 % F_x")
    ax.axvline(1.0, color="0.5", ls=":", lw=1, label="real time")
    ax.set_xscale("log")
    ax.set_yscale("log")
    from matplotlib.ticker import FuncFormatter
    plain = FuncFormatter(lambda y, _: f"{y:g}")
    ax.yaxis.set_major_formatter(plain)
    ax.yaxis.set_minor_formatter(FuncFormatter(lambda y, _: f"{y:g}" if f"{y:g}"[0] in "235" else ""))
    ax.xaxis.set_major_formatter(plain)
    lo = min(p[1] for p in pts)
    ax.set_ylim(min(0.5, 0.7 * lo), 1.6 * max(p[1] for p in pts))
    ax.set_xlabel("cost: wall time / simulated time, one thread (-)")
    ax.set_ylabel("largest F_x error over the response (%)")
    unc = max(r["fx_limit_unc_pct"] for r in rows)
    what = "creepage step" if kind == "step" else "creepage sine 50 Hz"
    ax.set_title(f"limit uncertain by {unc:.2f} % (F_x); {measured}", fontsize=7.5, loc="left")
    ax.legend(loc="lower left", fontsize=7)
    name = f"pareto_{preset}_{kind}_{num(v)}mps_{num(dt)}ms.png"
    fig.suptitle(f"Accuracy per cost: {preset}, {what} at {v:g} m/s, {dt:g} ms steps", fontsize=11, fontweight="bold")
    fig.tight_layout()
    outdir.mkdir(parents=True, exist_ok=True)
    fig.savefig(outdir / name)
    plt.close(fig)
    return name


def main(argv: list[str]) -> int:
    src = Path(argv[0]) if argv else ROOT / "creep-core/data/accuracy.csv"
    outdir = Path(argv[1]) if len(argv) > 1 else ROOT / "docs/img/accuracy"
    notes, rows = read(src)
    measured = next((n.split(" (start")[0].split(";")[0] for n in notes if n.startswith("measured on")), "")
    cases: dict = {}
    for r in rows:
        cases.setdefault((r["preset"], r["kind"], r["v_m_s"], r["dt_ms"]), []).append(r)
    # a full regeneration: no stale PNG of a case the table no longer has survives
    for old in outdir.glob("pareto_*.png"):
        old.unlink()
    for key, rs in cases.items():
        print(outdir / plot_case(key, rs, measured, outdir))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
