"""Building blocks of the gallery: settings, checks, figure records and the analysis helpers
(settling time, hysteresis loops, self-crossings, regime boundaries).

A figure is a `Figure` record with four pure parts:
  compute(S)          -> (numbers, data)   runs the project's programs (numbers: JSON-able)
  checks(numbers, S)  -> [Check]           every qualitative seed statement as an assertion
  text(numbers, S)    -> markdown          parameters, the seed's statement, what the figure shows
  plot(numbers, data, outdir, S) -> [png names]
`checks` and `text` depend on the numbers only, so docs/validation/README.md is a function of
docs/validation/numbers.json (tests-py/test_gallery.py re-renders and compares).
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np


# --------------------------------------------------------------------------- settings
FULL = {
    "mode": "full",
    "grid": None,  # None: creep-core's default grid 80x21 (ECF: cells-ho, FASTSIM: cells; docs/model.md section 9)
    "wet_grid": [320, 21],  # docs/model.md section 9: the wet preset needs a finer strip
    "curve_low_n": 41,  # geometric points from 0.01 % to 1 %
    "curve_high_n": 197,  # linear points from 1 % to 50 %
    "step_dt_ms": 0.01,
    "step_duration_ms": 6.0,
    "sine_steps_per_cycle": 200,
    "sine_cycles": 4,
    "health_dt_ms": [0.01, 0.001],
    "drivetrain": {"preset": "dry", "t_end_step": None, "t_end_ramp": None, "h_ms": None, "grid": None},
    "material_n": 801,
}
QUICK = {
    "mode": "quick",
    "grid": None,  # the ECF runs are cheap: the quick run keeps the default grid (the transient
    "wet_grid": [160, 21],  # checks need it) and saves on points, periods and the drive-train
    "curve_low_n": 15,
    "curve_high_n": 50,
    "step_dt_ms": 0.01,
    "step_duration_ms": 5.0,
    "sine_steps_per_cycle": 200,
    "sine_cycles": 3,
    "health_dt_ms": [0.01, 0.002],
    "drivetrain": {"preset": "dry", "t_end_step": 2.0, "t_end_ramp": 8.0, "h_ms": 0.5, "grid": [16, 9]},
    "material_n": 201,
}


def grid_of(S: dict, wet: bool = False):
    g = S["wet_grid"] if wet else S["grid"]
    return tuple(g) if g else None


def grid_name(S: dict, wet: bool = False) -> str:
    g = grid_of(S, wet)
    return f"{g[0]}x{g[1]}" if g else "80x21 (default; ECF cells-ho)"


def curve_cx(S: dict, c_max: float = 0.5) -> np.ndarray:
    lo = np.geomspace(1e-4, 1e-2, S["curve_low_n"])
    hi = np.linspace(0.01, c_max, S["curve_high_n"])[1:]
    return np.concatenate([[0.0], lo, hi])


# --------------------------------------------------------------------------- checks
@dataclass
class Check:
    """One qualitative statement of the seed turned into an assertion.

    `expected` is True when the project reproduces the statement; False marks a known,
    explained deviation (`why`). The gallery fails when `passed != expected`: a statement
    that stops holding, or a deviation that disappears, both need the README regenerated
    and the explanation revisited."""

    id: str
    seed: str  # the seed's statement, in our words
    measured: str  # what the code gives, with numbers
    passed: bool
    expected: bool = True
    why: str = ""  # for expected == False: the likely reason

    def as_dict(self):
        return {"id": self.id, "passed": bool(self.passed), "expected": bool(self.expected)}


@dataclass
class Figure:
    key: str  # file stem and numbers.json key, e.g. "fig4_08"
    seed_ref: str  # "Fig. 4.8"
    title: str
    compute: Callable
    checks: Callable
    text: Callable
    plot: Callable
    pngs: list = field(default_factory=list)  # file names the plot writes (for the tests)
    section: str = "steady"


# --------------------------------------------------------------------------- formatting
def pct(x: float, nd: int = 2) -> str:
    """A creepage (dimensionless) as a percentage string."""
    return f"{100.0 * x:.{nd}f} %"


def g(x: float, nd: int = 4) -> str:
    """A number with nd significant digits."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "n/a"
    return f"{x:.{nd}g}"


def f3(x: float) -> str:
    return f"{x:.3f}"


def f4(x: float) -> str:
    return f"{x:.4f}"


def clean(o):
    """numpy -> plain Python for JSON (floats rounded to 10 significant digits)."""
    if isinstance(o, dict):
        return {str(k): clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [clean(v) for v in o]
    if isinstance(o, np.ndarray):
        return [clean(v) for v in o.tolist()]
    if isinstance(o, (np.bool_, bool)):
        return bool(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.floating, float)):
        x = float(o)
        if not math.isfinite(x):
            return None
        return float(f"{x:.10g}")
    return o


# --------------------------------------------------------------------------- analysis
def settling(t: np.ndarray, f: np.ndarray, window: float, tol: float = 0.02) -> dict:
    """Settling of a step response f(t) (t from 0, f[0] the level before the step).

    f_new is the mean of f over the last `window` of the run (every bristle entered after
    the step: the transient model's own new steady level). The band is the larger of
    tol * |f_new - f_old| and the peak-to-peak ripple of f in that window (the transient
    model's own noise floor at constant input). The settling time is the first instant
    after which |f - f_new| stays inside the band."""
    f_old = float(f[0])
    last = t >= t[-1] - window - 1e-12
    f_new = float(np.mean(f[last]))
    ripple = float(np.ptp(f[last]))
    band = max(tol * abs(f_new - f_old), ripple)
    out = np.abs(f - f_new) > band
    out[0] = True
    k = int(np.where(out)[0][-1])
    ts = float(t[k + 1]) if k + 1 < len(t) else float("nan")
    return {"f_old": f_old, "f_new": f_new, "ripple": ripple, "band": band, "t_settle": ts}


# the drive-train demo's analysis module is the one home of loop_area (the gallery runs the
# demo from its source folder too)
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "drivetrain-demo"))
from drivetrain_demo.analysis import loop_area  # noqa: E402  (signed area, closes the loop)
from drivetrain_demo.scenarios import DEFAULT_GRID_TEXT as DEMO_GRID  # noqa: E402,F401  (the demo's grid)


def self_crossings(x: np.ndarray, y: np.ndarray) -> list[tuple[float, float]]:
    """Points where the polyline (x, y) crosses itself (closing segment excluded)."""
    pts = []
    n = len(x)
    for i in range(n - 1):
        p = np.array([x[i], y[i]])
        r = np.array([x[i + 1] - x[i], y[i + 1] - y[i]])
        for j in range(i + 2, n - 1):
            if i == 0 and j == n - 2:
                continue
            q = np.array([x[j], y[j]])
            s = np.array([x[j + 1] - x[j], y[j + 1] - y[j]])
            den = r[0] * s[1] - r[1] * s[0]
            if den == 0.0:
                continue
            qp = q - p
            tt = (qp[0] * s[1] - qp[1] * s[0]) / den
            uu = (qp[0] * r[1] - qp[1] * r[0]) / den
            if 0.0 <= tt < 1.0 and 0.0 <= uu < 1.0:
                pt = p + tt * r
                pts.append((float(pt[0]), float(pt[1])))
    return pts


def crossing_x(x: np.ndarray, y: np.ndarray, level: float) -> float:
    """First x (in array order) where y crosses `level` (linear interpolation)."""
    s = y - level
    for i in range(len(s) - 1):
        if s[i] == 0.0:
            return float(x[i])
        if s[i] * s[i + 1] < 0.0:
            return float(x[i] + (x[i + 1] - x[i]) * s[i] / (s[i] - s[i + 1]))
    return float("nan")
