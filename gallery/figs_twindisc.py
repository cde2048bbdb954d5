"""Twin-disc rig (seed Sec. 6.3, Fig. 6.7/6.8): line contact of two 47 mm discs, 10 mm wide,
at p0 = 0.9 and 1.5 GPa; model curves only (the measured curves are not in the seed's text)."""
from __future__ import annotations

import math

import numpy as np

from . import run
from .core import Check, Figure, f3, grid_name, grid_of, pct
from .plotstyle import MODEL_COLORS, figure, label_panel, save

R_MM, W_MM = 11.75, 10.0  # equivalent radius of two 47 mm discs, width (preset twin_disc)
G_PA, NU = 79.3e9, 0.28
P0 = [0.9, 1.5]
V_TD = 1.0  # Tab. 3.2: 0.5 and 1 m/s
LINE = {"line_radius_mm": R_MM, "line_width_mm": W_MM}


def fn_for_p0(p0_gpa: float) -> float:
    """Total normal force (kN) of the line contact with peak pressure p0 (Eq. 2.7):
    p0 = sqrt(F' E* / (pi R)), E* = E / (2 (1 - nu^2)), E = 2 G (1 + nu)."""
    e_star = 2 * G_PA * (1 + NU) / (2 * (1 - NU ** 2))
    f_line = math.pi * R_MM * 1e-3 * (p0_gpa * 1e9) ** 2 / e_star
    return f_line * W_MM * 1e-3 / 1e3


def td_compute(S):
    cx = np.concatenate([[0.0], np.geomspace(1e-4, 0.01, S["curve_low_n"]), np.linspace(0.01, 0.10, 37)[1:]])
    sets = {
        "6.7": {"ECF dry (Sec. 6.1 set)": run.config("dry", grid=grid_of(S), geometry=LINE),
                "FASTSIM mu = 0.25": run.config("fastsim", grid=grid_of(S), geometry=LINE)},
        "6.8": {"ECF twin-disc set": run.config("twin_disc", grid=grid_of(S)),
                "FASTSIM mu = 0.6": run.config("fastsim", grid=grid_of(S), params={"mu": 0.6}, geometry=LINE)},
    }
    n = {"grid": grid_name(S), "fn_kN": {f"{p:g}": fn_for_p0(p) for p in P0}, "sets": {}}
    curves = {}
    for fig, models in sets.items():
        n["sets"][fig] = {}
        for name, cfg in models.items():
            n["sets"][fig][name] = {}
            for p in P0:
                d = run.curve(cfg, cx, v=V_TD, fn_kN=fn_for_p0(p))
                curves[(fig, name, p)] = d["f"]
                n["sets"][fig][name][f"{p:g}"] = {"p0_MPa_code": float(d["p0_MPa"][0]), "f_at_5pct": float(np.interp(0.05, cx, d["f"])),
                                                  "f_max": float(d["f"].max())}
    return n, {"cx": cx, "curves": curves}


def td_checks(n, S):
    s7, s8 = n["sets"]["6.7"], n["sets"]["6.8"]
    p0ok = all(abs(v[p]["p0_MPa_code"] - 1e3 * float(p)) < 1.0 for fig in n["sets"].values() for v in fig.values() for p in v)

    def spread(v):
        return abs(v["0.9"]["f_at_5pct"] - v["1.5"]["f_at_5pct"])

    ecf = [s7["ECF dry (Sec. 6.1 set)"], s8["ECF twin-disc set"]]
    fs = [s7["FASTSIM mu = 0.25"], s8["FASTSIM mu = 0.6"]]
    return [
        Check("6.3-line-contact-pressure",
              "the twin-disc tests run at p0 = 0.9 and 1.5 GPa (line contact, Eq. 2.7)",
              f"F_N = {n['fn_kN']['0.9']:.3f} kN and {n['fn_kN']['1.5']:.3f} kN over 10 mm give p0 = " + ", ".join(f"{v[p]['p0_MPa_code']:.0f}" for fig in n["sets"].values() for v in list(fig.values())[:1] for p in v) + " MPa in the code (assert within 1 MPa)",
              p0ok),
        Check("6.3-normal-load-dependence",
              "ECF's error on the twin-disc tests is smaller because its layer parameters depend on the normal stress; FASTSIM's friction coefficient does not",
              "f at 5 %, 0.9 vs 1.5 GPa: " + "; ".join(f"{k}: {f3(v['0.9']['f_at_5pct'])} / {f3(v['1.5']['f_at_5pct'])}" for fig in n["sets"].values() for k, v in fig.items()) + " (assert ECF differs by > 0.01 for both sets, FASTSIM by < 0.005)",
              all(spread(v) > 0.01 for v in ecf) and all(spread(v) < 0.005 for v in fs)),
    ]


def td_text(n, S):
    rows = "\n".join(f"| Fig. {fig} | {k} | " + " | ".join(f"{f3(v[p]['f_at_5pct'])} (max {f3(v[p]['f_max'])})" for p in ("0.9", "1.5")) + " |"
                     for fig, models in n["sets"].items() for k, v in models.items())
    return {
        "params": f"Line contact of two discs of 47 mm diameter (equivalent radius {R_MM} mm), {W_MM:g} mm wide (preset `twin_disc` geometry); p0 = 0.9 and 1.5 GPa (F_N = {n['fn_kN']['0.9']:.3f} and {n['fn_kN']['1.5']:.3f} kN, from p0 = sqrt(F' E*/(pi R))); v = {V_TD:g} m/s (Tab. 3.2 lists 0.5 and 1 m/s); grid {n['grid']}. Fig. 6.7: ECF with the Sec. 6.1 (dry) set and FASTSIM mu = 0.25; Fig. 6.8: ECF with tau_c1_0 = 824.64 MPa, tau_c2_0 = 7937.81 MPa (preset `twin_disc`) and FASTSIM mu = 0.6.",
        "seed": "With the vehicle-test parameters all models give too little traction for the twin-disc rig (Fig. 6.7). With a harder layer (raised critical shear stresses) or mu = 0.6 they reach the measured level, and ECF has the smallest error because its layer parameters depend on the normal stress (Fig. 6.8, Tab. 6.4). The measurements are not in the text: only the model curves are shown.",
        "shows": "With the twin-disc set the ECF curve keeps rising up to 10 % (tau_c2_0 = 7.9 GPa is never approached), and the 1.5 GPa curve is not smooth between about 2 and 6 %; a 4x finer strip does not remove the ripples (checked by hand, not part of the gallery's assertions). f at c_x = 5 % (and the maximum up to 10 %):\n\n| seed | model | p0 = 0.9 GPa | p0 = 1.5 GPa |\n|---|---|---|---|\n" + rows,
    }


def td_plot(n, data, out, S):
    cx = 100 * data["cx"]
    fig, ax = figure(1, 2, w=11, h=4.3)
    for a, fig_no in zip(ax.flat, ("6.7", "6.8")):
        for name in n["sets"][fig_no]:
            col = MODEL_COLORS["fastsim"] if name.startswith("FASTSIM") else MODEL_COLORS["dry"]
            for p, ls in zip(P0, ("-", "--")):
                a.plot(cx, data["curves"][(fig_no, name, p)], color=col, ls=ls, label=f"{name}, p0 = {p:g} GPa")
        a.set_xlim(0, 10)
        a.set_ylim(bottom=0)
        a.set_xlabel("longitudinal creepage $c_x$ [%]")
        a.set_ylabel("traction coefficient f [-]")
        a.legend(loc="lower right", fontsize=7.5)
        label_panel(a, f"({'ab'[fig_no == '6.8']}) Fig. {fig_no}: {'vehicle-test parameters' if fig_no == '6.7' else 'adjusted parameters'}")
    return [save(fig, out, "fig6_7_6_8_twin_disc.png", f"Seed Fig. 6.7/6.8 (models only): twin-disc line contact, v = {V_TD:g} m/s")]


TD_FIG = Figure("fig6_07_08", "Fig. 6.7/6.8 (models only)", "Twin-disc rig: line contact at 0.9 and 1.5 GPa",
                td_compute, td_checks, td_text, td_plot, ["fig6_7_6_8_twin_disc.png"], section="drivetrain")

FIGURES = [TD_FIG]
