"""The 3BL material law alone (seed Eq. 4.1-4.4), evaluated in Python for seed Fig. 5.1 and 5.3.

This is the formula of creep-core, not a second model: `voce()` and `Material` in
creep-core/src/bristle.rs and `Contact::material()` in creep-core/src/engine.rs, i.e.
  tau_c1(p, T) = tau_c1_0 [1 - exp(-p tau_c1_p)] exp(-(T - T0) tau_c1_T)          (Eq. 4.3)
  tau_c2(p, T) = tau_c2_0 [1 - exp(-p tau_c2_p)] exp(-(T - T0) tau_c2_T)          (Eq. 4.3)
  L_e(p, T) = L_e_0 / ([1 - exp(-p L_e_p)] exp(-(T - T0) L_e_T))                  (Eq. 4.4)
  L_p(p, T) = L_p_0 / ([1 - exp(-p L_p_p)] exp(-(T - T0) L_p_T))                  (Eq. 4.4)
  tau_c1 is capped at tau_c2 (docs/model.md section 5)
and for a layer sheared by u at constant (p, T) (a high-pressure-torsion test, no wheel or
rail: the flexibility is the layer's own L_e):
  |tau| = u / L_e                                           for u <= tau_c1 L_e   (Eq. 4.1)
  |tau| = tau_c1 + (tau_c2 - tau_c1)(1 - exp(-(u - Delta u)/L_p)),  Delta u = tau_c1 L_e  (Eq. 4.2)
The parameter values are read from the presets creep-core/presets/*.json, so this module
follows any change of the shipped parameter sets.
"""
from __future__ import annotations

import json
import math

import numpy as np

from .run import ROOT


def preset_params(name: str) -> dict:
    p = json.loads((ROOT / "creep-core" / "presets" / f"{name}.json").read_text())["params"]
    return {k: (math.inf if v in ("inf", "Infinity") else float(v)) for k, v in p.items()}


def _pf(p_gpa: float, c: float) -> float:
    """Pressure factor 1 - exp(-p c) (1 for c = inf)."""
    return 1.0 if math.isinf(c) else -math.expm1(-p_gpa * c)


def material(P: dict, p_gpa: float, T: float, T0: float = 20.0) -> dict:
    """tau_c1, tau_c2 (GPa), L_e (mm/GPa), L_p (mm) at pressure p (GPa) and temperature T (degC)."""
    tf = lambda c: math.exp(-(T - T0) * c)  # noqa: E731
    tc2 = P["tau_c2_0_GPa"] * _pf(p_gpa, P["tau_c2_p_per_GPa"]) * tf(P["tau_c2_T_per_C"])
    tc1 = min(P["tau_c1_0_GPa"] * _pf(p_gpa, P["tau_c1_p_per_GPa"]) * tf(P["tau_c1_T_per_C"]), tc2)
    le = P["L_e_0_um_per_GPa"] * 1e-3 / (_pf(p_gpa, P["L_e_p_per_GPa"]) * tf(P["L_e_T_per_C"]))
    lp = P["L_p_0_mm"] / (_pf(p_gpa, P["L_p_p_per_GPa"]) * tf(P["L_p_T_per_C"]))
    return {"tau_c1": tc1, "tau_c2": tc2, "L_e": le, "L_p": lp}


def tau_of_u(m: dict, u_mm: np.ndarray) -> np.ndarray:
    """|tau| (GPa) over the layer displacement u (mm), monotonic loading (Eq. 4.1, 4.2)."""
    du = m["tau_c1"] * m["L_e"]
    el = np.minimum(u_mm, du) / m["L_e"] if m["L_e"] > 0 else np.full_like(u_mm, m["tau_c1"])
    s = np.maximum(u_mm - du, 0.0)
    pl = m["tau_c1"] + (m["tau_c2"] - m["tau_c1"]) * (-np.expm1(-s / m["L_p"]))
    return np.where(u_mm <= du, el, pl)


def u_fraction(m: dict, frac: float) -> float:
    """Displacement (mm) at which the hardening has covered `frac` of tau_c2 - tau_c1."""
    return m["tau_c1"] * m["L_e"] - m["L_p"] * math.log1p(-frac)
