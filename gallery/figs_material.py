"""The 3BL sub-model alone: seed Fig. 5.1 (normal-stress dependence, rough / smooth parameters
of Tab. 5.1) and Fig. 5.3 (the parametrized dry and wet behaviour at several temperatures).
Evaluated with gallery/material.py: the formulas of creep-core/src/bristle.rs and engine.rs."""
from __future__ import annotations

import numpy as np

from . import material as M
from .core import Check, Figure, g
from .plotstyle import figure, label_panel, save

U_MAX_MM = 1.5

# Tab. 5.1 (HPT tests, dry, first day; no temperature dependence in these tests)
TAB51 = {
    "rough": {"L_e_0_um_per_GPa": 0.2522, "L_p_0_mm": 0.1640, "tau_c1_0_GPa": 0.2645, "tau_c2_0_GPa": 0.8113},
    "smooth": {"L_e_0_um_per_GPa": 0.2522, "L_p_0_mm": 0.1490, "tau_c1_0_GPa": 0.2727, "tau_c2_0_GPa": 0.8349},
}
TAB51_P = {"L_e_p_per_GPa": float("inf"), "L_p_p_per_GPa": 96.561, "tau_c1_p_per_GPa": 1.4474, "tau_c2_p_per_GPa": 1.3223,
           "L_e_T_per_C": 0.0, "L_p_T_per_C": 0.0, "tau_c1_T_per_C": 0.0, "tau_c2_T_per_C": 0.0}
PRESSURES = [0.5, 1.0]
TEMPS = [20.0, 50.0, 100.0, 200.0, 400.0]


# =========================================================================== Fig. 5.1
def fig5_1_compute(S):
    u = np.linspace(0.0, U_MAX_MM, S["material_n"])
    curves, n = {}, {"cases": {}}
    for rough in TAB51:
        P = dict(TAB51_P, **TAB51[rough])
        for p in PRESSURES:
            m = M.material(P, p, 20.0)
            curves[(rough, p)] = M.tau_of_u(m, u)
            n["cases"][f"{rough}@{p:g}"] = {"tau_c1_MPa": 1e3 * m["tau_c1"], "tau_c2_MPa": 1e3 * m["tau_c2"], "L_p_mm": m["L_p"],
                                          "tau_at_1mm_MPa": 1e3 * float(np.interp(1.0, u, curves[(rough, p)]))}
    mask = u >= 0.05
    n["max_rel_rough_smooth"] = float(max(np.max(np.abs(curves[("rough", p)][mask] / curves[("smooth", p)][mask] - 1)) for p in PRESSURES))
    n["ratio_1GPa_to_0.5GPa_at_1mm"] = n["cases"]["rough@1"]["tau_at_1mm_MPa"] / n["cases"]["rough@0.5"]["tau_at_1mm_MPa"]
    return n, {"u": u, "curves": curves}


def fig5_1_checks(n, S):
    return [
        Check("5.1-roughness-insignificant",
              "the rough and smooth parameter sets give nearly the same layer behaviour: the roughness is not significant",
              f"largest relative difference rough/smooth for u >= 0.05 mm: {100 * n['max_rel_rough_smooth']:.1f} % (assert < 10 %)",
              n["max_rel_rough_smooth"] < 0.10),
        Check("5.1-pressure-raises-stress",
              "the layer's shear stress rises with the normal stress (granular behaviour, Sec. 3.3)",
              f"tau at u = 1 mm is {n['ratio_1GPa_to_0.5GPa_at_1mm']:.2f} times higher at 1 GPa than at 0.5 GPa (rough; assert > 1.2)",
              n["ratio_1GPa_to_0.5GPa_at_1mm"] > 1.2),
    ]


def fig5_1_text(n, S):
    rows = "\n".join(f"| {k.split('@')[0]} | {k.split('@')[1]} | {v['tau_c1_MPa']:.0f} | {v['tau_c2_MPa']:.0f} | {v['L_p_mm']:.4f} | {v['tau_at_1mm_MPa']:.0f} |" for k, v in n["cases"].items())
    return {
        "params": "Tab. 5.1 rough and smooth sets (L_e_0 = 0.2522 um/GPa, L_e_p = inf, L_p_p = 96.561/GPa, tau_c1_p = 1.4474/GPa, tau_c2_p = 1.3223/GPa; L_p_0, tau_c1_0, tau_c2_0 per roughness), no temperature dependence (the HPT discs turn slowly); normal stress 0.5 and 1 GPa (the seed's HPT stresses; it does not say which two Fig. 5.1 uses); Eq. 4.1-4.4 evaluated in Python (gallery/material.py, the formula of creep-core/src/bristle.rs).",
        "seed": "The seed fits the 3BL sub-model to high-pressure-torsion tests at two normal stresses and two roughnesses and concludes that the roughness has no significant influence, so it uses the mean pressure coefficients from then on. The measured curves are not in the text; only the model side is reproduced.",
        "shows": "The layer law of Eq. 4.1/4.2 at the two stresses (figure) and its coefficients:\n\n| set | p [GPa] | tau_c1 [MPa] | tau_c2 [MPa] | L_p [mm] | tau at u = 1 mm [MPa] |\n|---|---|---|---|---|---|\n" + rows,
    }


def fig5_1_plot(n, data, out, S):
    u = data["u"]
    fig, ax = figure(1, 1, w=6.8, h=4.4)
    a = ax[0, 0]
    for (rough, p), tau in data["curves"].items():
        a.plot(u, 1e3 * tau, ls="-" if rough == "rough" else "--", color="C0" if p == 1.0 else "C1",
               label=f"{rough}, p = {p:g} GPa")
    a.set_xlabel("layer displacement u [mm]")
    a.set_ylabel(r"shear stress $|\tau|$ [MPa]")
    a.set_xlim(0, U_MAX_MM)
    a.set_ylim(bottom=0)
    a.legend(loc="lower right")
    return [save(fig, out, "fig5_01_hpt_model.png", "Seed Fig. 5.1 (model side): 3BL law, Tab. 5.1, two normal stresses")]


FIG5_1 = Figure("fig5_01", "Fig. 5.1 (model only)", "3BL sub-model at two normal stresses, rough and smooth",
                fig5_1_compute, fig5_1_checks, fig5_1_text, fig5_1_plot, ["fig5_01_hpt_model.png"], section="material")


# =========================================================================== Fig. 5.3
def fig5_3_compute(S):
    u = np.linspace(0.0, U_MAX_MM, S["material_n"])
    curves, n = {}, {"cond": {}}
    for cond in ("dry", "wet"):
        P = M.preset_params(cond)
        n["cond"][cond] = {}
        for T in TEMPS:
            m = M.material(P, 1.0, T)
            curves[(cond, T)] = M.tau_of_u(m, u)
            n["cond"][cond][f"{T:g}"] = {"tau_c1_MPa": 1e3 * m["tau_c1"], "tau_c2_MPa": 1e3 * m["tau_c2"], "L_p_mm": m["L_p"],
                                        "u63_mm": M.u_fraction(m, 1 - np.exp(-1)),
                                        "tau_at_0.5mm_MPa": 1e3 * float(np.interp(0.5, u, curves[(cond, T)])),
                                        "tau_at_1mm_MPa": 1e3 * float(np.interp(1.0, u, curves[(cond, T)]))}
    return n, {"u": u, "curves": curves}


def fig5_3_checks(n, S):
    d, w = n["cond"]["dry"], n["cond"]["wet"]
    ts = [f"{T:g}" for T in TEMPS]
    falls = all(all(c[a]["tau_at_1mm_MPa"] > c[b]["tau_at_1mm_MPa"] for a, b in zip(ts, ts[1:])) for c in (d, w))
    du = [d[t]["u63_mm"] for t in ts]
    wu = [w[t]["u63_mm"] for t in ts]
    return [
        Check("5.3-heat-lowers-friction",
              "the friction level falls with temperature, dry and wet",
              "tau at u = 1 mm, dry: " + " / ".join(f"{d[t]['tau_at_1mm_MPa']:.0f}" for t in ts) + " MPa; wet: " + " / ".join(f"{w[t]['tau_at_1mm_MPa']:.0f}" for t in ts)
              + f" MPa at {' / '.join(ts)} degC (assert strictly falling)",
              falls),
        Check("5.3-dry-shape-kept",
              "dry curves look qualitatively the same at every temperature",
              f"displacement to 63 % of the hardening, dry: {g(min(du), 4)} to {g(max(du), 4)} mm over 20-400 degC (L_p_T = 0; assert spread < 5 %)",
              max(du) / min(du) - 1 < 0.05),
        Check("5.3-wet-plasticity-dominates-when-hot",
              "for wet conditions the shape changes: with L_p_T the behaviour becomes dominated by plasticity at higher temperature",
              "displacement to 63 % of the hardening, wet: " + " / ".join(f"{x:.3f}" for x in wu) + f" mm at {' / '.join(ts)} degC; tau_c1 falls from {w['20']['tau_c1_MPa']:.0f} MPa to {g(w['50']['tau_c1_MPa'], 2)} MPa at 50 degC (assert the 63 % displacement at 200 degC > 3 x that at 20 degC)",
              w["200"]["u63_mm"] > 3 * w["20"]["u63_mm"]),
    ]


def fig5_3_text(n, S):
    rows = []
    for cond, c in n["cond"].items():
        for T, v in c.items():
            rows.append(f"| {cond} | {T} | {g(v['tau_c1_MPa'], 3)} | {v['tau_c2_MPa']:.0f} | {v['L_p_mm']:.3f} | {v['u63_mm']:.3f} | {v['tau_at_1mm_MPa']:.0f} |")
    return {
        "params": "Presets `dry` and `wet` (Tab. 5.4 with the unrounded Tab. 5.2/5.3 values; wet tau_c1_T = 0.54879/degC of Tab. 5.3, Tab. 5.4 prints 0.559; temperature coefficients in 1/degC although Tab. 5.4 prints 1/GPa), read from creep-core/presets/*.json; p = 1 GPa as in the seed; T = 20, 50, 100, 200, 400 degC with T0 = 20 degC (the seed does not list its temperatures). The curve is Eq. 4.1 up to tau_c1, then Voce's law Eq. 4.2 (with Eq. 4.3/4.4 for the coefficients), evaluated in Python by gallery/material.py: the formula of `voce()` in creep-core/src/bristle.rs and `Contact::material()` in creep-core/src/engine.rs, for a layer alone (no wheel or rail flexibility), loaded monotonically.",
        "seed": "The seed shows the calibrated layer law at 1 GPa for several temperatures: the friction level falls as the temperature rises; dry curves keep their shape, while wet curves change shape because L_p grows with temperature, so the hot wet layer is dominated by plasticity.",
        "shows": "'u63' is the displacement at which 63 % of the hardening from tau_c1 to tau_c2 is done (Delta u + L_p).\n\n| condition | T [degC] | tau_c1 [MPa] | tau_c2 [MPa] | L_p [mm] | u63 [mm] | tau at 1 mm [MPa] |\n|---|---|---|---|---|---|---|\n" + "\n".join(rows),
    }


def fig5_3_plot(n, data, out, S):
    u = data["u"]
    fig, ax = figure(1, 2, w=11, h=4.4, sharey=True)
    for a, cond in zip(ax.flat, ("dry", "wet")):
        for i, T in enumerate(TEMPS):
            a.plot(u, 1e3 * data["curves"][(cond, T)], color=f"C{i}", label=f"T = {T:g} °C")
        a.set_xlabel("layer displacement u [mm]")
        a.set_ylabel(r"shear stress $|\tau|$ [MPa]")
        a.set_xlim(0, U_MAX_MM)
        a.set_ylim(0, 520)
        a.legend(loc="lower right")
        label_panel(a, f"({'a' if cond == 'dry' else 'b'}) {cond}, p = 1 GPa")
    return [save(fig, out, "fig5_03_material_law.png", "Seed Fig. 5.3: parametrized 3BL behaviour (Tab. 5.4) at several temperatures")]


FIG5_3 = Figure("fig5_03", "Fig. 5.3", "Parametrized material behaviour, dry and wet, at several temperatures",
                fig5_3_compute, fig5_3_checks, fig5_3_text, fig5_3_plot, ["fig5_03_material_law.png"], section="material")

FIGURES = [FIG5_1, FIG5_3]
