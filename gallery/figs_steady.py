"""Steady (quasi-steady) results of the seed's Sec. 4.4 and the model comparison of Sec. 6.1:
Fig. 4.8 (characteristic and regimes), 4.9/4.10 (fields along y = 0), 4.11 (speed and load),
4.12 (parameter study), and FASTSIM / Polach / ECF dry / ECF wet at 5, 10, 20 m/s."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from . import run
from .core import Check, Figure, curve_cx, f3, f4, g, grid_name, grid_of, pct
from .plotstyle import MODEL_COLORS, figure, label_panel, save, shade_regimes

G_PA = 79.3e9  # shear modulus of wheel and rail (creep-core default `G_GPa`, seed Sec. 5.1)
TAB41 = ("Tab. 4.1 (preset `table4.1`: L_e_0 = 0.2522 um/GPa, L_e_p = inf, L_e_T = 0; "
         "L_p_0 = 0.25 mm, L_p_p = 1 /GPa, L_p_T = 0.0025 /degC; tau_c1_0 = 0.3 GPa, "
         "tau_c1_p = 1 /GPa, tau_c1_T = 0.0025 /degC; tau_c2_0 = 1.1 GPa, tau_c2_p = 1 /GPa, "
         "tau_c2_T = 0.0025 /degC)")


def regimes(cx: np.ndarray, d: dict) -> dict:
    """R1/R2 boundary: the creepage where the plastic + sliding area share first exceeds the
    elastic share; R2/R3 boundary: the maximum of f."""
    inel = d["frac_plastic"] + d["frac_sliding"] - d["frac_elastic"]
    k = int(np.argmax(inel > 0))
    c12 = float(cx[k - 1] + (cx[k] - cx[k - 1]) * (-inel[k - 1]) / (inel[k] - inel[k - 1]))
    i = int(np.argmax(d["f"]))
    return {"c12": c12, "f_c12": float(np.interp(c12, cx, d["f"])), "c_max": float(cx[i]),
            "f_max": float(d["f"][i])}


# =========================================================================== Fig. 4.8
def fig4_8_compute(S):
    cfg = run.config("table4.1", grid=grid_of(S))
    cx = curve_cx(S)
    d = run.curve(cfg, cx, v=20.0, fn_kN=110.0)
    r = regimes(cx, d)
    s1 = r["f_c12"] / r["c12"]
    s2 = (r["f_max"] - r["f_c12"]) / (r["c_max"] - r["c12"])
    beyond = cx >= r["c_max"]
    rises = np.diff(d["f"][beyond])
    n = dict(r, slope_R1=s1, slope_R2=s2, slope_ratio=s1 / s2, f_50=float(d["f"][-1]),
             drop_to_50=1.0 - float(d["f"][-1]) / r["f_max"], max_rise_in_R3=float(max(rises.max(), 0.0)),
             T_max_at_max=float(d["T_max_C"][int(np.argmax(d["f"]))]), grid=grid_name(S))
    return n, {"cx": cx, "d": d}


def fig4_8_checks(n, S):
    return [
        Check("4.8-three-regimes",
              "the steady characteristic has a steep rise at small creepage (R1), a moderate rise at medium creepage (R2) and a fall at large creepage (R3)",
              f"mean slope in R1 (0 to {pct(n['c12'], 3)}) {g(n['slope_R1'])}, in R2 (to the maximum at {pct(n['c_max'])}) {g(n['slope_R2'])}: "
              f"ratio {g(n['slope_ratio'], 3)} (assert > 10); f falls from {f4(n['f_max'])} to {f4(n['f_50'])} at 50 % "
              f"({100 * n['drop_to_50']:.0f} %, assert > 30 %) and never rises again by more than 1e-3 (largest rise {g(n['max_rise_in_R3'], 2)})",
              n["slope_ratio"] > 10 and n["drop_to_50"] > 0.3 and n["max_rise_in_R3"] < 1e-3),
        Check("4.8-max-near-5pct",
              "c_x = 5 % is a creepage close to the maximum of the characteristic (Tab. 4.1, 20 m/s)",
              f"maximum f = {f4(n['f_max'])} at c_x = {pct(n['c_max'])} (assert 2.5 % <= c_max <= 10 %)",
              0.025 <= n["c_max"] <= 0.10),
    ]


def fig4_8_text(n, S):
    return {
        "params": f"{TAB41}; F_N = 110 kN, v = 20 m/s, a = 7.63 mm, b = 7.88 mm, T_B = T0 = 20 degC; grid {n['grid']}; `ecf curve`.",
        "seed": "The seed presents the steady ECF characteristic for the Vectron operating point as its typical result and says it shows the three regimes of the vehicle tests: a steep rise of traction at low creepage (R1), a moderate rise at medium creepage (R2) and a loss of traction at high creepage (R3).",
        "shows": f"The same curve from `ecf curve`. Regimes are marked by a rule the seed does not give, so we state ours: R1 ends where the plastic plus sliding share of the contact area first exceeds the elastic share (c_x = {pct(n['c12'], 3)}), R3 starts at the maximum f = {f4(n['f_max'])} at c_x = {pct(n['c_max'])}. The mean slope in R1 is {g(n['slope_ratio'], 3)} times that in R2; from the maximum to 50 % the coefficient falls by {100 * n['drop_to_50']:.0f} %.",
    }


def fig4_8_plot(n, data, out, S):
    cx, d = 100 * data["cx"], data["d"]
    fig, ax = figure(1, 2, w=11, h=4.2)
    for a, xmax, lab in ((ax[0, 0], 2.0, "(a) small creepage"), (ax[0, 1], 50.0, "(b) whole range")):
        shade_regimes(a, 100 * n["c12"], 100 * n["c_max"], xmax)
        m = cx <= xmax + 1e-9
        a.plot(cx[m], d["f"][m], "k-", label="ECF, Tab. 4.1")
        a.set_xlim(0, xmax)
        a.set_ylim(0, 0.4)
        a.set_xlabel("longitudinal creepage $c_x$ [%]")
        a.set_ylabel("traction coefficient $f = F_x/F_N$ [-]")
        label_panel(a, lab)
    ax[0, 0].text(100 * n["c12"] / 2, 0.02, "R1", ha="center", fontweight="bold")
    ax[0, 0].text(1.2, 0.02, "R2", ha="center", fontweight="bold")
    ax[0, 1].text(100 * n["c_max"] / 2, 0.02, "R1+R2", ha="center", fontweight="bold", fontsize=8)
    ax[0, 1].text(27, 0.02, "R3", ha="center", fontweight="bold")
    ax[0, 1].plot([100 * n["c_max"]], [n["f_max"]], "ro")
    ax[0, 1].annotate(f"max f = {n['f_max']:.3f}\nat $c_x$ = {100 * n['c_max']:.2f} %", (100 * n["c_max"], n["f_max"]),
                      xytext=(12, 0.34), arrowprops={"arrowstyle": "->"})
    ax[0, 1].legend(loc="center right", title=f"$F_N$ = 110 kN, v = 20 m/s, grid {n['grid']}")
    return [save(fig, out, "fig4_08_characteristic.png", "Seed Fig. 4.8: steady ECF characteristic and the regimes R1, R2, R3")]


FIG4_8 = Figure("fig4_08", "Fig. 4.8", "Steady characteristic and its three regimes",
                fig4_8_compute, fig4_8_checks, fig4_8_text, fig4_8_plot, ["fig4_08_characteristic.png"])


# =========================================================================== Fig. 4.9/4.10
FIELD_CX = [0.001, 0.01, 0.05, 0.30]


def _transition_x(fl: dict) -> float:
    """Elastic-plastic transition along y = 0: between the last elastic node (from the
    leading edge) and the first node that is plastic or sliding."""
    r, x = fl["regime"], fl["x_mm"]
    inside = fl["p_Pa"] > 0
    idx = np.where((r >= 1) & inside)[0]
    if len(idx) == 0:
        return float("nan")
    k = int(idx[0])
    return float(0.5 * (x[k] + x[k - 1])) if k > 0 else float(x[k])


def kalker_c11(cfg, v=20.0, fn_kN=110.0, a=7.63e-3, b=7.88e-3):
    """Kalker's C11 as the code uses it, from the linear-theory slope F_x = G a b C11 c_x
    at c_x = 1e-6 (docs/model.md section 2)."""
    c = 1e-6
    f = float(run.curve(cfg, [c], v=v, fn_kN=fn_kN)["f"][0])
    return f * fn_kN * 1e3 / (G_PA * a * b * c)


def analytic_transition(c, c11, a=7.63e-3, b=7.88e-3, fn=110e3, tc1_0=0.3e9, tc1_p=1e-9, le=0.2522e-15):
    """x where the elastic stress of Eq. 4.21, c (a - x)/(L_x + L_e), reaches tau_c1(p(x)) of
    Eq. 4.3 at T = T0 along y = 0 (Hertz pressure Eq. 2.6)."""
    p0 = 3 * fn / (2 * math.pi * a * b)
    lx = 8 * a / (3 * c11 * G_PA)

    def tc1(x):
        return tc1_0 * (1 - math.exp(-p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2)) * tc1_p))

    x = brentq(lambda x: c * (a - x) / (lx + le) - tc1(x), -a * 0.999, a * 0.999)
    xs = -4e-3  # the seed's "x <= -4 mm"
    l_needed = c * (a - xs) / tc1(xs) - le
    return {"x_analytic_mm": x * 1e3, "L_x": lx, "L_factor_for_minus4mm": l_needed / lx}


def fig4_9_compute(S):
    cfg = run.config("table4.1", grid=grid_of(S))
    fields = {c: run.field(cfg, c, v=20.0, fn_kN=110.0) for c in FIELD_CX}
    n = {"grid": grid_name(S), "cases": {}}
    for c, fl in fields.items():
        inside = fl["p_Pa"] > 0
        x = fl["x_mm"]
        k2 = int(np.argmax(fl["tau_c2_Pa"]))
        n["cases"][f"{c:g}"] = {
            "T_max": float(fl["T_C"].max()),
            "x_transition_mm": _transition_x(fl),
            "plastic_share": float(np.mean(fl["regime"][inside] >= 1)),
            "sliding_share": float(np.mean(fl["regime"][inside] == 2)),
            "tau_max_MPa": float(fl["tau_Pa"].max() / 1e6),
            "tau_c2_max_MPa": float(fl["tau_c2_Pa"].max() / 1e6),
            "x_tau_c2_max_mm": float(x[k2]),
            "tau_integral_N_per_mm": float(-np.trapezoid(fl["tau_Pa"], x) / 1e6),  # MPa*mm = N/mm
        }
    c11 = kalker_c11(cfg)
    n["C11"] = c11
    n.update(analytic_transition(0.001, c11))
    return n, {"fields": fields}


def fig4_9_checks(n, S):
    c = n["cases"]
    a, b, cc, d = c["0.001"], c["0.01"], c["0.05"], c["0.3"]
    return [
        # The rise at 0.1 % sits at the trailing-edge node and is not converged on the
        # gallery's grid (table4.1, 20 m/s: 31.4 degC on 80 cells, 35.5 degC on 1280; with
        # equal strips at their midpoints, 25.8 and 34.3 degC). An absolute bound
        # of 10 K held only through that under-resolution; "very low" is judged against the
        # rise at 30 % creepage instead.
        Check("4.9-low-temperature-at-0.1pct",
              "at c_x = 0.1 % the temperature is very low and has no significant influence",
              f"T_max = {a['T_max']:.1f} degC (T_B = 20 degC); rise {a['T_max'] - 20.0:.1f} K, "
              f"{100 * (a['T_max'] - 20.0) / (d['T_max'] - 20.0):.1f} % of the rise at 30 % "
              f"({d['T_max'] - 20.0:.0f} K; assert < 5 %)",
              a["T_max"] - 20.0 < 0.05 * (d["T_max"] - 20.0)),
        Check("4.9-elastic-dominated-at-0.1pct",
              "at c_x = 0.1 % the stress is dominated by the elasticity of wheel, rail and layer; only near the trailing edge does the layer harden",
              f"elastic-plastic transition at x = {a['x_transition_mm']:.2f} mm (trailing half: assert x < 0); plastic share along y = 0 {100 * a['plastic_share']:.0f} % (assert < 50 %)",
              a["x_transition_mm"] < 0 and a["plastic_share"] < 0.5),
        Check("4.9-transition-at-minus-4mm",
              "at c_x = 0.1 % the layer hardens only for x <= -4 mm",
              f"transition at x = {a['x_transition_mm']:.2f} mm (assert <= -3.5 mm); Eq. 4.21 with Kalker's L_x = 8a/(3 C11 G) (C11 = {n['C11']:.3f}) against tau_c1 of Eq. 4.3 gives {n['x_analytic_mm']:.2f} mm by hand",
              a["x_transition_mm"] <= -3.5, expected=False,
              why=f"The code follows the equations: solving c_x (a - x)/(L_x + L_e) = tau_c1(p(x)) by hand (Python, Kalker's C11 taken from the code's own linear-theory slope, T = T0) puts the transition at {n['x_analytic_mm']:.2f} mm, next to the code's {a['x_transition_mm']:.2f} mm. A transition at -4 mm needs a wheel-rail flexibility {n['L_factor_for_minus4mm']:.2f} times Kalker's L_x; the seed does not print its C11, G or nu, so its flexibility cannot be checked, and '-4 mm' may also be read off a coarse figure."),
        Check("4.9-plastic-nearly-everywhere-at-1pct",
              "at c_x = 1 % the transition moves close to the leading edge and the layer is plastic in nearly the whole contact",
              f"transition at x = {b['x_transition_mm']:.2f} mm (0.1 %: {a['x_transition_mm']:.2f} mm); plastic share {100 * b['plastic_share']:.0f} % (assert > 90 % and transition nearer the leading edge)",
              b["plastic_share"] > 0.9 and b["x_transition_mm"] > a["x_transition_mm"]),
        Check("4.10-temperature-significant-at-5pct",
              "at c_x = 5 % the temperature rises significantly and lowers and distorts the critical shear stresses",
              f"T_max = {cc['T_max']:.0f} degC (assert > 150 degC); max tau_c2 {cc['tau_c2_max_MPa']:.0f} MPa against {a['tau_c2_max_MPa']:.0f} MPa at 0.1 % (assert 10 % lower); its peak moves to x = {cc['x_tau_c2_max_mm']:.2f} mm (0.1 %: {a['x_tau_c2_max_mm']:.2f} mm; assert towards the leading edge by > 0.5 mm)",
              cc["T_max"] > 150 and cc["tau_c2_max_MPa"] < 0.9 * a["tau_c2_max_MPa"] and cc["x_tau_c2_max_mm"] > a["x_tau_c2_max_mm"] + 0.5),
        Check("4.9-temperature-dominant-at-30pct",
              "at c_x = 30 % the temperature dominates: the lower critical shear stresses reduce the stress and with it the force",
              f"T_max {d['T_max']:.0f} degC (5 %: {cc['T_max']:.0f}); area under tau(x, 0) {d['tau_integral_N_per_mm']:.0f} N/mm against {cc['tau_integral_N_per_mm']:.0f} N/mm at 5 % (assert lower); max tau {d['tau_max_MPa']:.0f} MPa (5 %: {cc['tau_max_MPa']:.0f} MPa)",
              d["T_max"] > cc["T_max"] and d["tau_integral_N_per_mm"] < cc["tau_integral_N_per_mm"] and d["tau_max_MPa"] < cc["tau_max_MPa"]),
    ]


def fig4_9_text(n, S):
    c = n["cases"]
    rows = "\n".join(
        f"| {pct(float(k), 1)} | {v['T_max']:.1f} | {v['x_transition_mm']:.2f} | {100 * v['plastic_share']:.0f} | {100 * v['sliding_share']:.0f} | {v['tau_max_MPa']:.0f} | {v['tau_c2_max_MPa']:.0f} | {v['tau_integral_N_per_mm']:.0f} |"
        for k, v in c.items())
    table = ("| c_x | T_max [degC] | transition x [mm] | plastic + sliding share [%] | sliding share [%] | max tau [MPa] | max tau_c2 [MPa] | area under tau(x) [N/mm] |\n"
             "|---|---|---|---|---|---|---|---|\n" + rows)
    return {
        "params": f"{TAB41}; F_N = 110 kN, v = 20 m/s, a = 7.63 mm, b = 7.88 mm; grid {n['grid']}, the strip nearest y = 0; `ecf field`.",
        "seed": "The seed explains the regimes with the stress along y = 0: at 0.1 % the elastic bodies and layer dominate, the temperature hardly matters and the layer hardens only near the trailing edge (x <= -4 mm); at 1 % the layer is plastic almost everywhere; at 5 %, near the maximum, the temperature rises strongly and lowers and distorts the critical shear stresses; at 30 % the temperature dominates and the stress falls.",
        "shows": "The stress |tau|, tau_c1 and tau_c2 (Fig. 4.9) and the pressure and temperature (Fig. 4.10) from `ecf field` at the four creepages; the leading edge is on the right, as in the seed.\n\n" + table,
    }


def fig4_9_plot(n, data, out, S):
    F = data["fields"]
    fig, ax = figure(2, 2, w=11, h=7.5)
    for a, (c, fl), lab in zip(ax.flat, F.items(), "abcd"):
        x = fl["x_mm"]
        a.plot(x, fl["tau_Pa"] / 1e6, "k-", label=r"$|\tau|$")
        a.plot(x, fl["tau_c1_Pa"] / 1e6, "b--", label=r"$\tau_{c1}$")
        a.plot(x, fl["tau_c2_Pa"] / 1e6, "r-.", label=r"$\tau_{c2}$")
        xt = n["cases"][f"{c:g}"]["x_transition_mm"]
        if math.isfinite(xt):
            a.axvline(xt, color="g", lw=0.8, ls=":", label=f"elastic | plastic ({xt:.2f} mm)")
        a.set_xlabel("x [mm] (trailing edge left, leading edge right)")
        a.set_ylabel("shear stress at y = 0 [MPa]")
        a.set_xlim(-7.8, 7.8)
        a.set_ylim(bottom=0)
        label_panel(a, f"({lab}) $c_x$ = {100 * c:g} %")
        a.legend(loc="upper left")
    p1 = save(fig, out, "fig4_09_stress_fields.png", "Seed Fig. 4.9: stresses along y = 0 (Tab. 4.1, 110 kN, 20 m/s)")
    fig, ax = figure(1, 2, w=11, h=4.2)
    fl = F[FIELD_CX[0]]
    ax[0, 0].plot(fl["x_mm"], fl["p_Pa"] / 1e6, "k-")
    ax[0, 0].set_xlabel("x [mm]")
    ax[0, 0].set_ylabel("normal pressure p(x, 0) [MPa]")
    label_panel(ax[0, 0], "(a) Hertz pressure (Eq. 2.6), p0 = 874 MPa")
    for c, fl in F.items():
        ax[0, 1].plot(fl["x_mm"], fl["T_C"], label=f"$c_x$ = {100 * c:g} %")
    ax[0, 1].set_xlabel("x [mm]")
    ax[0, 1].set_ylabel("bristle temperature T(x, 0) [°C]")
    ax[0, 1].legend()
    label_panel(ax[0, 1], "(b) flash temperature (Eq. 4.35)")
    p2 = save(fig, out, "fig4_10_pressure_temperature.png", "Seed Fig. 4.10: pressure and temperature along y = 0")
    return [p1, p2]


FIG4_9 = Figure("fig4_09", "Fig. 4.9/4.10", "Stresses, pressure and temperature along y = 0",
                fig4_9_compute, fig4_9_checks, fig4_9_text, fig4_9_plot,
                ["fig4_09_stress_fields.png", "fig4_10_pressure_temperature.png"])


# =========================================================================== Fig. 4.11
SPEEDS = [5.0, 10.0, 20.0]
PROBE = [0.01, 0.05, 0.10, 0.30]


def fig4_11_compute(S):
    cfg = run.config("table4.1", grid=grid_of(S))
    cx = curve_cx(S)
    sp = {v: run.curve(cfg, cx, v=v, fn_kN=110.0) for v in SPEEDS}
    ld = {fn: run.curve(cfg, cx, v=20.0, fn_kN=fn) for fn in (50.0, 110.0)}
    n = {"grid": grid_name(S), "speed": {}, "load": {}}
    for v, d in sp.items():
        i = int(np.argmax(d["f"]))
        n["speed"][f"{v:g}"] = {"f_max": float(d["f"][i]), "c_max": float(cx[i]),
                                "f_at": {f"{c:g}": float(np.interp(c, cx, d["f"])) for c in PROBE},
                                "T_max_5pct": float(np.interp(0.05, cx, d["T_max_C"]))}
    for fn, d in ld.items():
        i = int(np.argmax(d["f"]))
        n["load"][f"{fn:g}"] = {"f_max": float(d["f"][i]), "c_max": float(cx[i]), "a_mm": float(d["a_mm"][0]),
                                "b_mm": float(d["b_mm"][0]), "p0_MPa": float(d["p0_MPa"][0]),
                                "f_at": {f"{c:g}": float(np.interp(c, cx, d["f"])) for c in PROBE},
                                "T_max_5pct": float(np.interp(0.05, cx, d["T_max_C"]))}
    diff = ld[110.0]["f"] - ld[50.0]["f"]
    k = int(np.argmax(diff))
    n["load"]["max_f110_minus_f50"] = float(diff[k])
    n["load"]["at_c"] = float(cx[k])
    return n, {"cx": cx, "speed": sp, "load": ld}


def fig4_11_checks(n, S):
    s, l = n["speed"], n["load"]
    fall_v = all(s["5"]["f_at"][c] > s["10"]["f_at"][c] > s["20"]["f_at"][c] for c in ("0.01", "0.05", "0.1", "0.3"))
    return [
        Check("4.11-speed-lowers-traction",
              "a higher speed heats the layer more and lowers the traction level",
              "f at 1 / 5 / 10 / 30 %: " + "; ".join(f"{v} m/s: " + "/".join(f3(s[v]['f_at'][c]) for c in ('0.01', '0.05', '0.1', '0.3')) for v in ("5", "10", "20"))
              + f"; T_max at 5 %: {s['5']['T_max_5pct']:.0f} / {s['10']['T_max_5pct']:.0f} / {s['20']['T_max_5pct']:.0f} degC (assert f falls and T rises with v at every probe)",
              fall_v and s["5"]["T_max_5pct"] < s["10"]["T_max_5pct"] < s["20"]["T_max_5pct"]),
        Check("4.11-max-moves-to-smaller-creepage",
              "the maximum of traction moves to smaller creepage at higher speed (Ch. 4 list of effects)",
              f"c_max = {pct(s['5']['c_max'])} / {pct(s['10']['c_max'])} / {pct(s['20']['c_max'])} at 5 / 10 / 20 m/s (assert strictly decreasing)",
              s["5"]["c_max"] > s["10"]["c_max"] > s["20"]["c_max"]),
        Check("4.11-load-lowers-traction",
              "a higher normal load heats the layer more and lowers the traction level",
              f"f_max {f4(l['50']['f_max'])} at 50 kN, {f4(l['110']['f_max'])} at 110 kN; f at 10 % {f3(l['50']['f_at']['0.1'])} / {f3(l['110']['f_at']['0.1'])}, at 30 % {f3(l['50']['f_at']['0.3'])} / {f3(l['110']['f_at']['0.3'])}; "
              f"T_max at 5 %: {l['50']['T_max_5pct']:.0f} / {l['110']['T_max_5pct']:.0f} degC (assert lower f and higher T at 110 kN)",
              l["50"]["f_max"] > l["110"]["f_max"] and l["50"]["f_at"]["0.1"] > l["110"]["f_at"]["0.1"]
              and l["50"]["f_at"]["0.3"] > l["110"]["f_at"]["0.3"] and l["110"]["T_max_5pct"] > l["50"]["T_max_5pct"]),
        Check("4.11-hertz-50kN",
              "for 50 kN the semi-axes shrink to a = 5.87 mm, b = 6.06 mm",
              f"a = {l['50']['a_mm']:.2f} mm, b = {l['50']['b_mm']:.2f} mm (cube-root scaling of 7.63/7.88 mm at 110 kN; assert within 0.01 mm)",
              abs(l["50"]["a_mm"] - 5.87) < 0.01 and abs(l["50"]["b_mm"] - 6.06) < 0.01),
    ]


def fig4_11_text(n, S):
    s, l = n["speed"], n["load"]
    return {
        "params": f"{TAB41}; (a) F_N = 110 kN, v = 5, 10, 20 m/s; (b) v = 20 m/s, F_N = 50 kN and 110 kN (semi-axes from the Hertz cube-root law, 5.87 x 6.06 mm at 50 kN); grid {n['grid']}. The seed does not list the speeds of Fig. 4.11: 5, 10, 20 m/s are those of its vehicle tests.",
        "seed": "The seed shows that a higher speed or a higher normal load both raise the temperature, which lowers the critical shear stresses and so the traction level; its list of model features adds that the maximum moves to smaller creepage at higher speed.",
        "shows": f"Maxima: {f4(s['5']['f_max'])} at {pct(s['5']['c_max'])} (5 m/s), {f4(s['10']['f_max'])} at {pct(s['10']['c_max'])} (10 m/s), {f4(s['20']['f_max'])} at {pct(s['20']['c_max'])} (20 m/s); {f4(l['50']['f_max'])} at 50 kN against {f4(l['110']['f_max'])} at 110 kN. "
                 f"One detail the seed's sentence does not cover: in R2 the two loads nearly coincide (at {pct(l['at_c'], 1)} the 110 kN curve lies {g(l['max_f110_minus_f50'], 2)} above the 50 kN one), because the pressure factor 1 - exp(-p tau_c_p) of Eq. 4.3 strengthens the layer at the higher pressure, which offsets the heating there; in R1 the lower load has the higher f (Kalker's slope scales with (a b)/F_N) and in R3 the heating wins.",
    }


def fig4_11_plot(n, data, out, S):
    cx = 100 * data["cx"]
    fig, ax = figure(1, 2, w=11, h=4.2)
    for v, d in data["speed"].items():
        ax[0, 0].plot(cx, d["f"], label=f"v = {v:g} m/s")
        i = int(np.argmax(d["f"]))
        ax[0, 0].plot(cx[i], d["f"][i], "k.", ms=8)
    for fn, d in data["load"].items():
        ax[0, 1].plot(cx, d["f"], label=f"$F_N$ = {fn:g} kN (a = {d['a_mm'][0]:.2f} mm, b = {d['b_mm'][0]:.2f} mm)")
        i = int(np.argmax(d["f"]))
        ax[0, 1].plot(cx[i], d["f"][i], "k.", ms=8)
    for a, lab in ((ax[0, 0], "(a) speed, $F_N$ = 110 kN"), (ax[0, 1], "(b) normal load, v = 20 m/s")):
        a.set_xlim(0, 50)
        a.set_ylim(0, 0.4)
        a.set_xlabel("longitudinal creepage $c_x$ [%]")
        a.set_ylabel("traction coefficient f [-]")
        a.legend(loc="lower right")
        label_panel(a, lab)
    return [save(fig, out, "fig4_11_speed_load.png", "Seed Fig. 4.11: speed and normal-load dependence (Tab. 4.1; dots: maxima)")]


FIG4_11 = Figure("fig4_11", "Fig. 4.11", "Speed and normal-load dependence",
                 fig4_11_compute, fig4_11_checks, fig4_11_text, fig4_11_plot, ["fig4_11_speed_load.png"])


# =========================================================================== Fig. 4.12
# (panel, parameter, varied value, unit, how the value was chosen)
STUDY = [
    ("a", "L_e_0_um_per_GPa", 252.2, "um/GPa", "x1000 (the seed: 'adjusted by three orders of magnitude')"),
    ("a", "L_e_p_per_GPa", 1.0, "1/GPa", "not shown by the seed ('no significant change'); 1/GPa as tau_c1_p"),
    ("a", "L_e_T_per_C", 0.0025, "1/degC", "not shown by the seed ('no significant change'); 0.0025 as the other T coefficients"),
    ("b", "L_p_0_mm", 1.0, "mm", "value of the seed's legend"),
    ("b", "L_p_p_per_GPa", 0.5, "1/GPa", "value of the seed's legend"),
    ("b", "L_p_T_per_C", 0.01, "1/degC", "value of the seed's legend"),
    ("c", "tau_c1_0_GPa", 0.6, "GPa", "x2 (not in the text; x4 would exceed tau_c2_0)"),
    ("c", "tau_c1_p_per_GPa", 0.5, "1/GPa", "x0.5 (not in the text; the pattern of panel b)"),
    ("c", "tau_c1_T_per_C", 0.01, "1/degC", "0.01 (not in the text; the pattern of panel b)"),
    ("d", "tau_c2_0_GPa", 2.2, "GPa", "x2 (not in the text)"),
    ("d", "tau_c2_p_per_GPa", 0.5, "1/GPa", "x0.5 (not in the text; the pattern of panel b)"),
    ("d", "tau_c2_T_per_C", 0.01, "1/degC", "0.01 (not in the text; the pattern of panel b)"),
]
PANEL_TITLE = {"a": "(a) elasticity of the 3BL: $L_e$", "b": "(b) plasticity: $L_p$",
               "c": r"(c) first critical shear stress $\tau_{c1}$", "d": r"(d) second critical shear stress $\tau_{c2}$"}
SYMBOL = {"L_e_0_um_per_GPa": "$L_e^0$", "L_e_p_per_GPa": "$L_e^p$", "L_e_T_per_C": "$L_e^T$",
          "L_p_0_mm": "$L_p^0$", "L_p_p_per_GPa": "$L_p^p$", "L_p_T_per_C": "$L_p^T$",
          "tau_c1_0_GPa": r"$\tau_{c1}^0$", "tau_c1_p_per_GPa": r"$\tau_{c1}^p$", "tau_c1_T_per_C": r"$\tau_{c1}^T$",
          "tau_c2_0_GPa": r"$\tau_{c2}^0$", "tau_c2_p_per_GPa": r"$\tau_{c2}^p$", "tau_c2_T_per_C": r"$\tau_{c2}^T$"}


def fig4_12_compute(S):
    cx = curve_cx(S, c_max=0.20)
    base = run.curve(run.config("table4.1", grid=grid_of(S)), cx, v=5.0)
    r = regimes(cx, base)
    fb = base["f"]
    R1, R2, R3 = cx <= r["c12"], (cx > r["c12"]) & (cx <= r["c_max"]), cx > r["c_max"]
    n = {"grid": grid_name(S), "base": r, "var": {}}
    curves = {}
    for panel, name, val, unit, why in STUDY:
        d = run.curve(run.config("table4.1", grid=grid_of(S), params={name: val}), cx, v=5.0)
        f = d["f"]
        df = f - fb
        i = int(np.argmax(f))
        j = int(np.argmax(np.abs(df)))
        k05 = int(np.argmin(np.abs(cx - 0.0005)))
        hi1, hi25 = cx >= 0.01, cx >= 0.025
        n["var"][name] = {
            "panel": panel, "value": val, "unit": unit, "f_max": float(f[i]), "c_max": float(cx[i]),
            "rel_change_f_max": float(f[i] / r["f_max"] - 1.0),
            "max_abs_df": float(np.abs(df).max()), "c_at_max_abs_df": float(cx[j]),
            "mean_abs_df_R1": float(np.abs(df[R1]).mean()), "mean_abs_df_R2": float(np.abs(df[R2]).mean()),
            "mean_abs_df_R3": float(np.abs(df[R3]).mean()),
            "rel_df_at_0.05pct": float(df[k05] / fb[k05]),
            "max_rel_df_above_1pct": float(np.max(np.abs(df[hi1] / fb[hi1]))),
            "max_rel_df_above_2.5pct": float(np.max(np.abs(df[hi25] / fb[hi25]))),
        }
        curves[name] = f
    return n, {"cx": cx, "base": fb, "curves": curves}


def fig4_12_checks(n, S):
    V, b = n["var"], n["base"]
    le0, lep, let = V["L_e_0_um_per_GPa"], V["L_e_p_per_GPa"], V["L_e_T_per_C"]
    inR2 = lambda v: b["c12"] < v["c_at_max_abs_df"] <= b["c_max"]  # noqa: E731
    tc1 = [V[k] for k in ("tau_c1_0_GPa", "tau_c1_p_per_GPa", "tau_c1_T_per_C")]
    tc2 = [V[k] for k in ("tau_c2_0_GPa", "tau_c2_p_per_GPa", "tau_c2_T_per_C")]
    lp = [V[k] for k in ("L_p_0_mm", "L_p_p_per_GPa", "L_p_T_per_C")]
    return [
        Check("4.12a-Le0-acts-in-R1",
              "L_e_0, raised by three orders of magnitude, changes the initial rise and hardly the rest of the characteristic",
              f"f at 0.05 % changes by {100 * le0['rel_df_at_0.05pct']:.0f} % (assert |.| > 30 %); the softer layer stretches the initial rise to about 2 %, so f still differs by up to {100 * le0['max_rel_df_above_1pct']:.1f} % above c_x = 1 %, but by at most {100 * le0['max_rel_df_above_2.5pct']:.1f} % above 2.5 % (assert < 3 %); f_max by {100 * le0['rel_change_f_max']:+.1f} %",
              abs(le0["rel_df_at_0.05pct"]) > 0.3 and le0["max_rel_df_above_2.5pct"] < 0.03),
        Check("4.12a-Lep-LeT-insignificant",
              "L_e_p and L_e_T do not change the characteristic significantly (so the seed does not show them)",
              f"largest |delta f| {g(lep['max_abs_df'], 2)} (L_e_p = 1/GPa) and {g(let['max_abs_df'], 2)} (L_e_T = 0.0025/degC) (assert < 0.005)",
              lep["max_abs_df"] < 0.005 and let["max_abs_df"] < 0.005),
        Check("4.12b-plasticity-moves-the-maximum",
              "the plasticity coefficients L_p_0, L_p_p, L_p_T change the maximum of the characteristic",
              "f_max changes by " + ", ".join(f"{100 * v['rel_change_f_max']:+.0f} %" for v in lp) + " (assert each |.| > 5 %)",
              all(abs(v["rel_change_f_max"]) > 0.05 for v in lp)),
        Check("4.12c-tau_c1-acts-in-R2",
              "the tau_c1 coefficients mainly change the moderate rise in R2",
              "largest |delta f| at c_x = " + ", ".join(pct(v["c_at_max_abs_df"]) for v in tc1)
              + f" (R2 = {pct(b['c12'], 3)} to {pct(b['c_max'])}); mean |delta f| in R2 " + ", ".join(g(v["mean_abs_df_R2"], 2) for v in tc1)
              + " against R1 " + ", ".join(g(v["mean_abs_df_R1"], 2) for v in tc1) + " (assert the largest change lies in R2 and R2 > R1 for each)",
              all(inR2(v) and v["mean_abs_df_R2"] > v["mean_abs_df_R1"] for v in tc1)),
        Check("4.12d-tau_c2-sets-the-level-in-R2-R3",
              "the tau_c2 coefficients set the overall level of traction at medium and high creepage (R2 and R3)",
              "mean |delta f| in R2 / R3: " + ", ".join(f"{g(v['mean_abs_df_R2'], 2)} / {g(v['mean_abs_df_R3'], 2)}" for v in tc2)
              + "; in R1: " + ", ".join(g(v["mean_abs_df_R1"], 2) for v in tc2) + " (assert R2 and R3 each > 0.02 and > 10 x R1)",
              all(v["mean_abs_df_R2"] > 0.02 and v["mean_abs_df_R3"] > 0.02 and min(v["mean_abs_df_R2"], v["mean_abs_df_R3"]) > 10 * v["mean_abs_df_R1"] for v in tc2)),
    ]


def fig4_12_text(n, S):
    rows = []
    for panel, name, val, unit, why in STUDY:
        v = n["var"][name]
        rows.append(f"| ({panel}) | `{name}` | {val:g} {unit} | {why} | {f4(v['f_max'])} at {pct(v['c_max'])} | {100 * v['rel_change_f_max']:+.1f} % | {g(v['max_abs_df'], 3)} at {pct(v['c_at_max_abs_df'])} |")
    b = n["base"]
    table = ("| panel | parameter | varied value | choice | f_max at c_max | change of f_max | largest abs(delta f) |\n"
             "|---|---|---|---|---|---|---|\n" + "\n".join(rows))
    return {
        "params": f"{TAB41} except v = 5 m/s (as the seed); F_N = 110 kN, a = 7.63 mm, b = 7.88 mm; one coefficient changed at a time, creepage 0-20 %; grid {n['grid']}. The seed's text gives the varied values only for panel (b) (from its legend: L_p_0 = 1 mm, L_p_p = 0.5/GPa, L_p_T = 0.01/degC) and says L_e_0 was changed by three orders of magnitude; the values of panels (c) and (d) are ours (table).",
        "seed": "The seed varies each group of coefficients of Eq. 4.3/4.4 at 5 m/s: L_e_0 changes only the steep initial rise (L_e_p and L_e_T change nothing significant and are not shown); the plasticity coefficients change the maximum; the tau_c1 coefficients change the moderate rise in R2; the tau_c2 coefficients change the overall level in R2 and R3.",
        "shows": f"Default: f_max = {f4(b['f_max'])} at {pct(b['c_max'])}, R1/R2 boundary at {pct(b['c12'], 3)}.\n\n" + table,
    }


def fig4_12_plot(n, data, out, S):
    cx = 100 * data["cx"]
    fig, ax = figure(2, 2, w=11, h=8)
    axes = {"a": ax[0, 0], "b": ax[0, 1], "c": ax[1, 0], "d": ax[1, 1]}
    for p, a in axes.items():
        a.plot(cx, data["base"], "k-", lw=2, label="default (Tab. 4.1, v = 5 m/s)")
    for panel, name, val, unit, why in STUDY:
        lab = f"{SYMBOL[name]} = {val:g} {unit.replace('um', 'µm').replace('degC', '°C')}"
        axes[panel].plot(cx, data["curves"][name], label=lab, ls="--" if name.endswith("_T_per_C") else "-")
    ins = axes["a"].inset_axes([0.45, 0.12, 0.5, 0.42])
    ins.plot(cx, data["base"], "k-", lw=2)
    for panel, name, val, unit, why in STUDY:
        if panel == "a":
            ins.plot(cx, data["curves"][name], ls="--" if name.endswith("_T_per_C") else "-")
    ins.set_xlim(0, 1)
    ins.set_ylim(0, 0.3)
    ins.set_xlabel("$c_x$ [%]", fontsize=7)
    ins.set_ylabel("f [-]", fontsize=7)
    ins.tick_params(labelsize=7)
    for p, a in axes.items():
        a.set_xlim(0, 20)
        a.set_ylim(0, 0.6)
        a.set_xlabel("longitudinal creepage $c_x$ [%]")
        a.set_ylabel("traction coefficient f [-]")
        a.legend(loc="upper right" if p != "a" else "upper left", fontsize=7.5)
        label_panel(a, PANEL_TITLE[p])
    return [save(fig, out, "fig4_12_parameter_study.png", "Seed Fig. 4.12: parameter study of Eq. 4.3/4.4 (Tab. 4.1, v = 5 m/s)")]


FIG4_12 = Figure("fig4_12", "Fig. 4.12", "Parameter study of the material coefficients",
                 fig4_12_compute, fig4_12_checks, fig4_12_text, fig4_12_plot, ["fig4_12_parameter_study.png"])


# =========================================================================== models
MODELS = [("fastsim", "FASTSIM, mu = 0.25"), ("polach", "Polach (Sec. 3.1.1)"), ("dry", "ECF dry (Tab. 5.4)"), ("wet", "ECF wet (Tab. 5.4)")]


def models_compute(S):
    cx = curve_cx(S)
    cfgs = {"fastsim": run.config("fastsim", grid=grid_of(S)), "polach": run.config("polach"),
            "dry": run.config("dry", grid=grid_of(S)), "wet": run.config("wet", grid=grid_of(S, wet=True))}
    curves, n = {}, {"grid": grid_name(S), "wet_grid": grid_name(S, wet=True), "m": {}}
    for m, cfg in cfgs.items():
        n["m"][m] = {}
        for v in SPEEDS:
            d = run.curve(cfg, cx, v=v)
            curves[(m, v)] = d["f"]
            i = int(np.argmax(d["f"]))
            n["m"][m][f"{v:g}"] = {"f_max": float(d["f"][i]), "c_max": float(cx[i]),
                                   "f_at": {f"{c:g}": float(np.interp(c, cx, d["f"])) for c in PROBE}}
    n["fastsim_speed_spread"] = float(max(np.abs(curves[("fastsim", 5.0)] - curves[("fastsim", v)]).max() for v in SPEEDS))
    return n, {"cx": cx, "curves": curves}


def models_checks(n, S):
    M = n["m"]

    def falls(m, c):
        return M[m]["5"]["f_at"][c] > M[m]["10"]["f_at"][c] > M[m]["20"]["f_at"][c]

    return [
        Check("6.1-fastsim-no-speed-dependence",
              "FASTSIM (constant friction coefficient) cannot reproduce the speed dependence of the vehicle tests",
              f"largest difference between the FASTSIM curves at 5, 10, 20 m/s: {g(n['fastsim_speed_spread'], 2)} (assert < 1e-6); f saturates at {f4(M['fastsim']['5']['f_at']['0.3'])} (mu = 0.25)",
              n["fastsim_speed_spread"] < 1e-6),
        Check("6.1-ecf-polach-speed-dependence",
              "the Polach model and ECF both lower the traction at higher speed (the vehicle tests' speed dependence)",
              "f at 10 % / 30 % for 5, 10, 20 m/s: " + "; ".join(f"{m}: " + ", ".join(f"{f3(M[m][v]['f_at']['0.1'])}/{f3(M[m][v]['f_at']['0.3'])}" for v in ("5", "10", "20")) for m in ("polach", "dry", "wet"))
              + " (assert both fall with v for each model)",
              all(falls(m, c) for m in ("polach", "dry", "wet") for c in ("0.1", "0.3"))),
        Check("6.1-ecf-max-shift",
              "ECF moves the maximum to smaller creepage at higher speed, dry and wet",
              "c_max at 5 / 10 / 20 m/s: " + "; ".join(f"{m}: " + " / ".join(pct(M[m][v]["c_max"]) for v in ("5", "10", "20")) for m in ("dry", "wet"))
              + " (assert non-increasing and lower at 20 than at 5 m/s)",
              all(M[m]["5"]["c_max"] >= M[m]["10"]["c_max"] >= M[m]["20"]["c_max"] and M[m]["5"]["c_max"] > M[m]["20"]["c_max"] for m in ("dry", "wet"))),
        Check("5.1-wet-below-dry",
              "wet conditions give lower maxima than dry ones (vehicle tests, Sec. 3.1/3.3; all wet coefficients of Tab. 5.2 are lower)",
              "f_max dry / wet: " + "; ".join(f"{v} m/s {f3(M['dry'][v]['f_max'])} / {f3(M['wet'][v]['f_max'])}" for v in ("5", "10", "20")) + " (assert wet < dry at every speed)",
              all(M["wet"][v]["f_max"] < M["dry"][v]["f_max"] for v in ("5", "10", "20"))),
    ]


def models_text(n, S):
    M = n["m"]
    rows = "\n".join(f"| {lab} | " + " | ".join(f"{f3(M[m][v]['f_max'])} at {pct(M[m][v]['c_max'], 1)}" for v in ("5", "10", "20")) + " |" for m, lab in MODELS)
    return {
        "params": f"F_N = 110 kN, a = 7.63 mm, b = 7.88 mm, T_B = 20 degC; FASTSIM preset `fastsim` (mu = 0.25, elliptic Hertz bound), Polach preset `polach` (mu0 = 0.35, A = 0.3, B = 0.7 s/m, k_A = 0.68, k_S = 0.14), ECF presets `dry` and `wet` (Tab. 5.4 with the unrounded Tab. 5.2/5.3 values); grid {n['grid']}, wet {n['wet_grid']} (docs/model.md section 9).",
        "seed": "The seed compares the models with the vehicle tests (Fig. 3.8, 6.1, 6.2, Tab. 6.1): FASTSIM has no speed dependence, the Polach model has one through the slip velocity, and ECF reproduces the speed dependence, the traction loss at high creepage and, with the calibrated sets, lower traction in wet than in dry conditions. The measured curves themselves are not part of the seed's text, so only the models are compared here.",
        "shows": "Maximum f and its creepage:\n\n| model | 5 m/s | 10 m/s | 20 m/s |\n|---|---|---|---|\n" + rows,
    }


def models_plot(n, data, out, S):
    cx = 100 * data["cx"]
    fig, ax = figure(1, 3, w=15, h=4.5)
    for a, v in zip(ax.flat, SPEEDS):
        for m, lab in MODELS:
            a.plot(cx, data["curves"][(m, v)], color=MODEL_COLORS[m], label=lab)
        a.set_xlim(0, 50)
        a.set_ylim(0, 0.42)
        a.set_xlabel("longitudinal creepage $c_x$ [%]")
        a.set_ylabel("traction coefficient f [-]")
        label_panel(a, f"v = {v:g} m/s")
        a.legend(loc="lower right")
    return [save(fig, out, "models_fastsim_polach_ecf.png", "FASTSIM, Polach and ECF (dry, wet) at 5, 10 and 20 m/s (cf. seed Fig. 3.8, 6.1, 6.2)")]


MODELS_FIG = Figure("models", "Fig. 3.8/6.1/6.2 (models only)", "FASTSIM, Polach, ECF dry and wet at 5, 10, 20 m/s",
                    models_compute, models_checks, models_text, models_plot, ["models_fastsim_polach_ecf.png"])

FIGURES = [FIG4_8, FIG4_9, FIG4_11, FIG4_12, MODELS_FIG]
