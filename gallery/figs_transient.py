"""Transient results of the seed's Sec. 4.5: creepage steps (Fig. 4.13-4.21), periodic
creepage (Fig. 4.22-4.25), and a numerical note on the transient model at constant input."""
from __future__ import annotations

import numpy as np

from . import run
from .core import Check, Figure, f3, f4, g, grid_name, grid_of, loop_area, pct, self_crossings, settling
from .figs_steady import G_PA, _transition_x, kalker_c11
from .plotstyle import figure, label_panel, save

V_T = 5.0  # Tab. 4.2
A_MM = 7.63
T_CROSS_MS = 2 * A_MM / V_T  # 2a/v = 3.052 ms: every bristle in the contact entered after the step
STEPS = [(0.001, 0.01), (0.01, 0.001), (0.10, 0.30), (0.01, 0.30), (0.30, 0.01)]
STEP_FIG = {(0.001, 0.01): "4.14", (0.01, 0.001): "4.16", (0.10, 0.30): "4.18", (0.01, 0.30): "4.20", (0.30, 0.01): "4.21"}
FIELD_STEPS = {(0.001, 0.01): "4.15", (0.01, 0.001): "4.17", (0.10, 0.30): "4.19"}
FIELD_TIMES = [0.0, 0.1, 0.4, 0.8, 1.6, 3.1]
SETTLE_WINDOW_MS = 1.0
TAB42 = "Tab. 4.2 (preset `table4.1`, tau_c1_0 = +0.3 GPa), F_N = 110 kN, v = 5 m/s, a = 7.63 mm, b = 7.88 mm, T_B = 20 degC"


def key(a, b):
    return f"{100 * a:g}->{100 * b:g}"


def _zones(x):
    """Leading quarter of the contact length (x > a/2), middle half, trailing quarter."""
    return {"lead": x > A_MM / 2, "mid": np.abs(x) <= A_MM / 2, "trail": x < -A_MM / 2}


def _plastic_from(fl) -> float:
    """Start (towards the leading edge) of the plastic/sliding zone that reaches the trailing edge."""
    x, r = fl["x_mm"], fl["regime"]
    inside = fl["p_Pa"] > 0
    k = len(x) - 1
    while k >= 0 and (r[k] >= 1 or not inside[k]):
        k -= 1
    return float(0.5 * (x[k] + x[k + 1])) if 0 <= k < len(x) - 1 else float("nan")


# =========================================================================== Fig. 4.13-4.21
def steps_compute(S):
    cfg = run.config("table4.1", grid=grid_of(S))
    dt, dur = S["step_dt_ms"], S["step_duration_ms"]
    cx = np.concatenate([np.linspace(0, 0.01, 41), np.linspace(0.01, 0.35, 69)[1:]])
    qs = run.curve(cfg, cx, v=V_T)
    n = {"grid": grid_name(S), "dt_ms": dt, "duration_ms": dur, "t_cross_ms": T_CROSS_MS, "steps": {}, "fields": {}}
    c11 = kalker_c11(cfg)
    # stress gained by an elastic bristle in 0.1 ms at c_x = 1 % (Eq. 4.21, no spin)
    n["dtau_1pct_0.1ms_MPa"] = 0.01 * V_T * 1e-4 / (8 * A_MM * 1e-3 / (3 * c11 * G_PA) + 0.2522e-15) / 1e6
    data = {"qs_cx": cx, "qs_f": qs["f"], "steps": {}, "fields": {}}
    for a, b in STEPS:
        d = run.step(cfg, a, b, v=V_T, duration_ms=dur, dt_ms=dt)
        t, f = d["t_s"] * 1e3, d["f"]
        s = settling(t, f, SETTLE_WINDOW_MS)
        f_qs_a, f_qs_b = (float(np.interp(c, cx, qs["f"])) for c in (a, b))
        late = t >= 3.1
        early = (t > 0) & (t <= 1.0)
        ip, im = int(np.argmax(np.where(early, f, -np.inf))), int(np.argmin(np.where(early, f, np.inf)))
        e = dict(s, f_qs_from=f_qs_a, f_qs_to=f_qs_b,
                 late_max_rel_dev_from_qs=float(np.max(np.abs(f[late] / f_qs_b - 1))),
                 f_new_rel_dev_from_qs=s["f_new"] / f_qs_b - 1,
                 t_peak_ms=float(t[ip]), f_peak=float(f[ip]), t_dip_ms=float(t[im]), f_dip=float(f[im]),
                 f_at_0_1ms=float(np.interp(0.1, t, f)), f_at_0_31ms=float(np.interp(0.31, t, f)),
                 dip_0_to_0_1ms=float(f[0] - np.min(f[(t > 0) & (t <= 0.1 + 1e-9)])),
                 T_max_end=float(d["T_max_C"][-1]))
        n["steps"][key(a, b)] = e
        data["steps"][(a, b)] = d
    for (a, b), fig in FIELD_STEPS.items():
        F = run.step_fields(cfg, a, b, FIELD_TIMES, v=V_T, dt_ms=dt)
        data["fields"][(a, b)] = F
        fe = {}
        for t, fl in F.items():
            th = _zones(fl["x_mm"])
            inside = fl["p_Pa"] > 0
            fe[f"{t:g}"] = {
                "f": float(fl["f"][0]), "T_max": float(fl["T_C"].max()),
                **{f"plastic_{k}": float(np.mean(fl["regime"][m & inside] >= 1)) for k, m in th.items()},
                "at_tau_c2_share": float(np.mean(fl["tau_Pa"][inside] >= 0.95 * fl["tau_c2_Pa"][inside])),
                "x_transition_mm": _transition_x(fl),
                "x_plastic_from_mm": _plastic_from(fl),
                "lead_tau_over_tau_c1": float(np.mean(fl["tau_Pa"][th["lead"] & inside] / fl["tau_c1_Pa"][th["lead"] & inside])),
            }
        ref = F[3.1]
        for t in (0.1, 0.8):
            th = _zones(ref["x_mm"])
            diff = np.abs(F[t]["tau_Pa"] - ref["tau_Pa"]) / 1e6
            fe[f"{t:g}"].update({f"dtau_vs_3.1_{k}_MPa": float(diff[m].mean()) for k, m in th.items()})
        n["fields"][key(a, b)] = fe
    return n, data


def steps_checks(n, S):
    st, fd = n["steps"], n["fields"]
    up, down, hi, r13, r31 = st["0.1->1"], st["1->0.1"], st["10->30"], st["1->30"], st["30->1"]
    f01 = fd["0.1->1"]
    f10 = fd["1->0.1"]
    f30 = fd["10->30"]
    worst_late = max(v["late_max_rel_dev_from_qs"] for v in st.values())
    overshoot = r13["f_peak"] - r13["f_old"]
    return [
        Check("4.14-steady-after-2a/v",
              f"after t = 2a/v = 3.1 ms every bristle in the contact has entered after the step, so the force equals the quasi-steady value of the new creepage",
              "largest deviation from `ecf curve` for t >= 3.1 ms: " + ", ".join(f"{k} %: {100 * v['late_max_rel_dev_from_qs']:.2f} %" for k, v in st.items()) + " (assert < 1 % for every step)",
              worst_late < 0.01),
        Check("4.16-down-slower-than-up",
              "the step 1 % -> 0.1 % takes longer to approach the quasi-steady value than 0.1 % -> 1 %",
              f"settling time {down['t_settle']:.2f} ms against {up['t_settle']:.2f} ms (assert longer)",
              down["t_settle"] > up["t_settle"]),
        Check("4.18-10-30-faster-than-1-0.1",
              "the step 10 % -> 30 % reaches a traction close to the quasi-steady value sooner than 1 % -> 0.1 %",
              f"settling time {hi['t_settle']:.2f} ms against {down['t_settle']:.2f} ms (assert shorter)",
              hi["t_settle"] < down["t_settle"]),
        Check("4.20-rise-then-fall",
              "after the step 1 % -> 30 % the traction first rises (the displacements grow faster than the temperature) and then falls to the lower quasi-steady value",
              f"f rises from {f4(r13['f_old'])} to {f4(r13['f_peak'])} at t = {r13['t_peak_ms']:.2f} ms, then falls to {f4(r13['f_new'])} (assert rise > 0.01 and end below start)",
              overshoot > 0.01 and r13["f_new"] < r13["f_old"]),
        Check("4.20-peak-within-0.1ms",
              "the rise after 1 % -> 30 % lasts for 0 < t <= 0.1 ms",
              f"peak at t = {r13['t_peak_ms']:.2f} ms (assert <= 0.15 ms); f(0.1 ms) = {f4(r13['f_at_0_1ms'])}",
              r13["t_peak_ms"] <= 0.15, expected=False,
              why="The rise ends when the flash temperature of the bristles has grown enough to soften the layer. How fast it grows depends on the thermal constants of wheel and rail (lambda, kappa in Eq. 4.31-4.35), which the seed does not give; the project uses steel's 50 W/(m K) and 14 mm^2/s (model-spec section 5). The shape (rise, then fall) is reproduced; the time scale is not pinned by the seed's data."),
        Check("4.20-steady-at-0.31ms-literal",
              "after 1 % -> 30 % the quasi-steady solution is reached for t >= 0.31 ms (as printed)",
              f"settling time {r13['t_settle']:.2f} ms; at 0.31 ms f = {f4(r13['f_at_0_31ms'])} against the new level {f4(r13['f_new'])} (assert settled by 0.31 ms)",
              r13["t_settle"] <= 0.31, expected=False,
              why="Read literally, 0.31 ms is a tenth of the crossing time 2a/v = 3.1 ms that the seed quotes everywhere else in Sec. 4.5.1; bristles that entered before the step are still in the contact at 0.31 ms and still carry their old history, so no reading of Eq. 4.14-4.35 lets the force be quasi-steady then. We read it as a typo for 3.1 ms (next check)."),
        Check("4.20-steady-by-3.1ms",
              "(reading 0.31 ms as 3.1 ms) after 1 % -> 30 % the quasi-steady solution is reached by t = 3.1 ms",
              f"settling time {r13['t_settle']:.2f} ms (assert <= 3.1 ms)",
              r13["t_settle"] <= 3.1),
        Check("4.21-small-dip",
              "after 30 % -> 1 % the traction first dips slightly (0 < t <= 0.1 ms), less pronounced than the rise after 1 % -> 30 %",
              f"dip of {g(r31['dip_0_to_0_1ms'], 2)} below the start within 0.1 ms (deepest at {r31['t_dip_ms']:.3f} ms) against a rise of {g(overshoot, 3)} after 1 % -> 30 % (assert dip > 0 and < rise / 10)",
              r31["dip_0_to_0_1ms"] > 0 and r31["dip_0_to_0_1ms"] < overshoot / 10, expected=False,
              why="The converged model has no dip: on a 160x42 grid f only falls towards the new level (largest rise above the start within 0.1 ms: 2.6e-5 with the code before the tau_c1 ride rule, 2.3e-4 with it; docs/model.md section 4). The dip of 1.6e-4 that the 80x21 grid showed before that rule was discretisation noise of the size of the roughness near the peak (docs/model.md section 9). The seed's dip may come from its global temperature iteration; its figure is not in the text."),
        Check("4.15-leading-edge-plastic-at-0.1ms",
              "0.1 % -> 1 %, t = 0.1 ms: the bristles at the leading edge now deform plastically while those around the middle are elastic",
              f"plastic share at t = 0.1 ms: leading quarter (x > a/2) {100 * f01['0.1']['plastic_lead']:.0f} %, middle half {100 * f01['0.1']['plastic_mid']:.0f} %, trailing quarter {100 * f01['0.1']['plastic_trail']:.0f} %; the zone that is plastic up to the trailing edge starts at x = {f01['0.1']['x_plastic_from_mm']:.2f} mm (assert leading > middle)",
              f01["0.1"]["plastic_lead"] > f01["0.1"]["plastic_mid"], expected=False,
              why=f"In the code the pattern is the other way round. With Eq. 4.16/4.21 an elastic bristle gains c_x v dt / (L_x + L_e) = {n['dtau_1pct_0.1ms_MPa']:.0f} MPa in 0.1 ms at c_x = 1 %, wherever it is. Bristles that entered after the step, or were near the leading edge, start from little stress: at 0.1 ms the leading quarter carries on average {100 * f01['0.1']['lead_tau_over_tau_c1']:.0f} % of its tau_c1 and is still elastic. Bristles in the middle already carry the stress they built up at 0.1 % and go past tau_c1 first. We found no reading of Eq. 4.14-4.21 that makes fresh bristles at the leading edge yield before the pre-loaded ones in the middle. The seed's figure is missing from the text, so we cannot tell what it plotted."),
        Check("4.15-close-to-final-at-0.8ms",
              "0.1 % -> 1 %, t = 0.8 ms: the stress is already very close to the final one, with a small difference near the trailing edge (bristles that entered before the step)",
              f"mean abs(tau(0.8 ms) - tau(3.1 ms)): leading quarter {f01['0.8']['dtau_vs_3.1_lead_MPa']:.1f}, middle half {f01['0.8']['dtau_vs_3.1_mid_MPa']:.1f}, trailing quarter {f01['0.8']['dtau_vs_3.1_trail_MPa']:.1f} MPa (assert trailing > 2 x leading and middle)",
              f01["0.8"]["dtau_vs_3.1_trail_MPa"] > 2 * max(f01["0.8"]["dtau_vs_3.1_lead_MPa"], f01["0.8"]["dtau_vs_3.1_mid_MPa"])),
        Check("4.17-leading-edge-elastic",
              "1 % -> 0.1 %: the leading edge becomes elastic because of the lower creepage",
              f"the elastic zone at the leading edge reaches down to x = {f10['0']['x_transition_mm']:.2f} mm at t = 0 and to x = {f10['0.1']['x_transition_mm']:.2f} mm at 0.1 ms; plastic share of the leading quarter {100 * f10['0']['plastic_lead']:.0f} % -> {100 * f10['0.1']['plastic_lead']:.0f} % (assert the elastic zone grows by > 1 mm)",
              f10["0"]["x_transition_mm"] - f10["0.1"]["x_transition_mm"] > 1.0),
        Check("4.19-temperature-controls-the-delay",
              "10 % -> 30 %: the delay is set by the temperature dependence of tau_c1 and tau_c2 rather than by the elasto-plastic interplay",
              f"share of bristles at |tau| >= 0.95 tau_c2 (stress capped by the temperature-dependent strength): {100 * f30['0.1']['at_tau_c2_share']:.0f} % at 0.1 ms, {100 * f30['0.8']['at_tau_c2_share']:.0f} % at 0.8 ms; T_max {f30['0']['T_max']:.0f} -> {f30['0.1']['T_max']:.0f} -> {f30['0.8']['T_max']:.0f} -> {f30['3.1']['T_max']:.0f} degC (assert > 50 % and T rising)",
              f30["0.1"]["at_tau_c2_share"] > 0.5 and f30["0.8"]["at_tau_c2_share"] > 0.5
              and f30["0"]["T_max"] < f30["0.1"]["T_max"] < f30["0.8"]["T_max"] < f30["3.1"]["T_max"]),
    ]


def steps_text(n, S):
    rows = "\n".join(
        f"| Fig. {STEP_FIG[(a, b)]} | {100 * a:g} % -> {100 * b:g} % | {f4(v['f_old'])} | {f4(v['f_new'])} | {f4(v['f_qs_to'])} ({100 * v['f_new_rel_dev_from_qs']:+.2f} %) | {g(v['band'], 2)} | **{v['t_settle']:.2f}** | {f4(v['f_peak'])} at {v['t_peak_ms']:.2f} | {f4(v['f_dip'])} at {v['t_dip_ms']:.2f} |"
        for (a, b) in STEPS for v in [n["steps"][key(a, b)]])
    return {
        "params": f"{TAB42}; Eq. 4.36 step at t = 0 from the steady state of c_a; time step {n['dt_ms']} ms, {n['duration_ms']} ms simulated; grid {n['grid']}; `ecf step` for f(t), `ecf step --field-at-ms` for the stresses along y = 0 at chosen instants. 2a/v = {n['t_cross_ms']:.3f} ms.",
        "seed": "After a step of creepage the stresses approach the new steady distribution and reach it once every bristle in the contact has entered after the step (t = 2a/v = 3.1 ms). Going down (1 -> 0.1 %) takes longer than going up (0.1 -> 1 %). 10 -> 30 % comes close to the quasi-steady value sooner, and its delay comes from the temperature dependence of the critical shear stresses. 1 -> 30 % first rises, because the displacements grow faster than the temperature, then falls. 30 -> 1 % shows a small dip.",
        "shows": ("**Settling time** (the definition is ours; the seed gives none): f_new is the mean of f over the last "
                  f"{SETTLE_WINDOW_MS:g} ms of the run, when every bristle has entered after the step. The band is the larger of 2 % of abs(f_new - f_old) and the peak-to-peak ripple of f in that window, which is the transient model's own noise floor at constant input. The settling time is the first instant after which abs(f - f_new) stays inside the band.\n\n"
                  "| seed | step | f before | f_new (transient) | `ecf curve` at c_b | band | settling time [ms] | max f in 0-1 ms [ms] | min f in 0-1 ms [ms] |\n|---|---|---|---|---|---|---|---|---|\n" + rows),
    }


def steps_plot(n, data, out, S):
    files = []
    qs_cx, qs_f = 100 * data["qs_cx"], data["qs_f"]
    for (a, b), d in data["steps"].items():
        e = n["steps"][key(a, b)]
        t = d["t_s"] * 1e3
        fig, ax = figure(1, 2, w=11, h=4.2)
        A = ax[0, 0]
        A.plot(np.concatenate([[-0.5], t]), np.concatenate([[d["f"][0]], d["f"]]), "k-", label="transient (`ecf step`)")
        A.axhline(e["f_qs_from"], color="C0", ls="--", label=f"quasi-steady, $c_x$ = {100 * a:g} %")
        A.axhline(e["f_qs_to"], color="C3", ls="--", label=f"quasi-steady, $c_x$ = {100 * b:g} %")
        A.axvline(T_CROSS_MS, color="gray", ls=":", label="2a/v = 3.05 ms")
        A.axvline(e["t_settle"], color="g", ls="-.", label=f"settled (2 % band): {e['t_settle']:.2f} ms")
        A.set_xlabel("time after the step t [ms]")
        A.set_ylabel("traction coefficient f [-]")
        A.set_xlim(-0.5, t[-1])
        A.legend(loc="best")
        label_panel(A, "(a) f over time")
        B = ax[0, 1]
        m = qs_cx <= max(35, 100 * max(a, b) + 5)
        B.plot(qs_cx[m], qs_f[m], "C7-", label="quasi-steady characteristic")
        B.plot(100 * np.concatenate([[a], d["cx"][1:]]), d["f"], "k.-", ms=3, label="transient path")
        B.plot([100 * a], [d["f"][0]], "o", color="C0", label="before the step")
        B.plot([100 * b], [e["f_new"]], "s", color="C3", label="end of the run")
        if max(a, b) <= 0.011:
            B.set_xlim(0, 1.5)
        B.set_xlabel("longitudinal creepage $c_x$ [%]")
        B.set_ylabel("traction coefficient f [-]")
        B.legend(loc="lower right")
        label_panel(B, "(b) against the quasi-steady characteristic")
        name = f"fig{STEP_FIG[(a, b)].replace('.', '_')}_step_{100 * a:g}_to_{100 * b:g}.png"
        files.append(save(fig, out, name, f"Seed Fig. {STEP_FIG[(a, b)]}: creepage step {100 * a:g} % -> {100 * b:g} % (Tab. 4.2, v = 5 m/s)"))
    # Fig. 4.13: frames
    F = data["fields"][(0.001, 0.01)]
    fig, ax = figure(1, 2, w=11, h=4.2, sharey=True)
    for i, (t, fl) in enumerate(F.items()):
        ax[0, 0].plot(fl["x_rail_mm"], fl["tau_Pa"] / 1e6, color=f"C{i}", label=f"t = {t:g} ms")
        ax[0, 1].plot(fl["x_mm"], fl["tau_Pa"] / 1e6, color=f"C{i}", label=f"t = {t:g} ms")
    ax[0, 0].set_xlabel("x in a frame fixed on the rail [mm] (contact moves right at v)")
    ax[0, 1].set_xlabel("x in the frame moving with the wheel (contact frame) [mm]")
    for A in ax.flat:
        A.set_ylabel(r"shear stress $|\tau|$ at y = 0 [MPa]")
        A.legend(loc="upper left")
    label_panel(ax[0, 0], "(a) fixed on the rail")
    label_panel(ax[0, 1], "(b) moving with the wheel")
    files.append(save(fig, out, "fig4_13_frames.png", "Seed Fig. 4.13: step 0.1 % -> 1 %, stress along y = 0 in two frames"))
    # Fig. 4.15, 4.17, 4.19: stresses at 0.1 and 0.8 ms next to f(t)
    for (a, b), fig_no in FIELD_STEPS.items():
        F = data["fields"][(a, b)]
        d = data["steps"][(a, b)]
        fig, ax = figure(2, 2, w=11, h=7.5)
        for row, t in enumerate((0.1, 0.8)):
            A = ax[row, 0]
            fl, f0, fe = F[t], F[0.0], F[3.1]
            A.plot(f0["x_mm"], f0["tau_Pa"] / 1e6, color="0.6", lw=1, label=r"$|\tau|$ at t = 0")
            A.plot(fe["x_mm"], fe["tau_Pa"] / 1e6, color="0.6", lw=1, ls=":", label=r"$|\tau|$ at t = 3.1 ms")
            A.plot(fl["x_mm"], fl["tau_Pa"] / 1e6, "k-", label=rf"$|\tau|$ at t = {t:g} ms")
            A.plot(fl["x_mm"], fl["tau_c1_Pa"] / 1e6, "b--", label=r"$\tau_{c1}$")
            A.plot(fl["x_mm"], fl["tau_c2_Pa"] / 1e6, "r-.", label=r"$\tau_{c2}$")
            pl = (fl["regime"] >= 1) & (fl["p_Pa"] > 0)
            A.plot(fl["x_mm"][pl], np.zeros(pl.sum()) + 5, "g|", ms=8, label="plastic / sliding bristle")
            A.set_xlabel("x [mm] (leading edge right)")
            A.set_ylabel("shear stress at y = 0 [MPa]")
            A.set_xlim(-7.8, 7.8)
            A.set_ylim(bottom=0)
            A.legend(loc="upper left", fontsize=7)
            label_panel(A, f"({'ac'[row]}) stresses at t = {t:g} ms")
            B = ax[row, 1]
            tt = d["t_s"] * 1e3
            B.plot(tt, d["f"], "k-")
            B.axvline(t, color="g", ls="--", label=f"t = {t:g} ms")
            B.set_xlabel("time after the step t [ms]")
            B.set_ylabel("traction coefficient f [-]")
            B.legend()
            label_panel(B, f"({'bd'[row]}) traction over time")
        files.append(save(fig, out, f"fig{fig_no.replace('.', '_')}_fields_{100 * a:g}_to_{100 * b:g}.png",
                          f"Seed Fig. {fig_no}: stresses during the step {100 * a:g} % -> {100 * b:g} % (Tab. 4.2, v = 5 m/s)"))
    # settling overview
    fig, ax = figure(1, 1, w=7.5, h=4)
    A = ax[0, 0]
    labs = [f"{100 * a:g} → {100 * b:g} %\n(Fig. {STEP_FIG[(a, b)]})" for a, b in STEPS]
    vals = [n["steps"][key(a, b)]["t_settle"] for a, b in STEPS]
    A.bar(labs, vals, color="C0")
    A.axhline(T_CROSS_MS, color="gray", ls=":", label="2a/v = 3.05 ms")
    for i, v in enumerate(vals):
        A.text(i, v + 0.05, f"{v:.2f}", ha="center")
    A.set_ylabel("settling time (2 % band) [ms]")
    A.legend()
    files.append(save(fig, out, "fig4_steps_settling_times.png", "Seed Fig. 4.14-4.21: settling times of the creepage steps"))
    return files


STEPS_FIG = Figure("fig4_13_21", "Fig. 4.13-4.21", "Creepage steps",
                   steps_compute, steps_checks, steps_text, steps_plot,
                   ["fig4_14_step_0.1_to_1.png", "fig4_16_step_1_to_0.1.png", "fig4_18_step_10_to_30.png",
                    "fig4_20_step_1_to_30.png", "fig4_21_step_30_to_1.png", "fig4_13_frames.png",
                    "fig4_15_fields_0.1_to_1.png", "fig4_17_fields_1_to_0.1.png", "fig4_19_fields_10_to_30.png",
                    "fig4_steps_settling_times.png"], section="transient")


# =========================================================================== Fig. 4.22-4.25
# (name, cm, ca, f0 [Hz], v [m/s], effects)
SINES = [
    ("4.22", 0.20, 0.10, 100.0, 5.0, None),
    ("4.22-noT", 0.20, 0.10, 100.0, 5.0, ["-temperature"]),
    ("4.23", 0.25, 0.25, 100.0, 5.0, None),
    ("50Hz", 0.25, 0.25, 50.0, 5.0, None),
    ("10Hz", 0.25, 0.25, 10.0, 5.0, None),
    ("20mps", 0.25, 0.25, 100.0, 20.0, None),
]


def sines_compute(S):
    spc, cyc = S["sine_steps_per_cycle"], S["sine_cycles"]
    cx = np.linspace(0.0, 0.55, 221)
    qs = {v: run.curve(run.config("table4.1", grid=grid_of(S)), cx, v=v)["f"] for v in (5.0, 20.0)}
    n = {"grid": grid_name(S), "steps_per_cycle": spc, "cycles": cyc, "runs": {}}
    data = {"qs_cx": cx, "qs": qs, "runs": {}}
    for name, cm, ca, f0, v, eff in SINES:
        cfg = run.config("table4.1", grid=grid_of(S), effects=eff)
        d = run.sine(cfg, cm, ca, f0, v=v, cycles=cyc, steps_per_cycle=spc)
        c, f = d["cx"], d["f"]
        N = len(c)
        last, prev, first = slice(N - spc - 1, N), slice(N - 2 * spc - 1, N - spc), slice(0, spc + 1)
        frange = float(np.ptp(f[last]))
        qs_v = qs[v] if eff is None else run.curve(cfg, cx, v=v)["f"]
        dev = f[last] - np.interp(c[last], cx, qs_v)
        cr = self_crossings(c[last], f[last])
        n["runs"][name] = {
            "cm": cm, "ca": ca, "f0": f0, "v": v, "temperature": eff is None,
            "f_min": float(f[last].min()), "f_max": float(f[last].max()),
            "periodicity_rms_rel": float(np.sqrt(np.mean((f[last] - f[prev]) ** 2)) / frange),
            "first_cycle_rms_rel": float(np.sqrt(np.mean((f[first] - f[last]) ** 2)) / frange),
            "loop_area": loop_area(c[last], f[last]),
            "rms_dev_from_qs": float(np.sqrt(np.mean(dev ** 2))),
            "crossings_cx": [p[0] for p in cr], "crossings_f": [p[1] for p in cr],
        }
        data["runs"][name] = (d, qs_v)
    return n, data


def sines_checks(n, S):
    R = n["runs"]
    a, nt, b, h50, h10, v20 = R["4.22"], R["4.22-noT"], R["4.23"], R["50Hz"], R["10Hz"], R["20mps"]

    def one_cross(r):
        return len(r["crossings_cx"]) == 1 and 0.025 <= r["crossings_cx"][0] <= 0.10

    def cr(r):
        return ", ".join(pct(c) for c in r["crossings_cx"]) or "none"

    return [
        Check("4.22-limit-cycle",
              "under periodic creepage the traction becomes periodic and quickly approaches a limit cycle (the seed: within about 1 ms)",
              "RMS difference between the last two periods, relative to the f range: " + ", ".join(f"{k} {100 * r['periodicity_rms_rel']:.2f} %" for k, r in R.items())
              + "; between the first and the last period: at most " + f"{100 * max(r['first_cycle_rms_rel'] for r in R.values()):.1f} % (assert < 2 % and < 5 %: the first period is already close to the limit cycle; the output does not resolve the seed's 1 ms further)",
              all(r["periodicity_rms_rel"] < 0.02 and r["first_cycle_rms_rel"] < 0.05 for r in R.values())),
        Check("4.22-hysteresis-from-temperature",
              "with c_m = 20 %, c_A = 10 % (both extremes in R3) the hysteresis comes mainly from the time dependence of the temperature model",
              f"loop area {g(a['loop_area'], 3)} (negative: clockwise in the c_x-f plane); with the temperature switched off the same creepage gives {g(nt['loop_area'], 3)} (assert the loop runs the other way without temperature, i.e. the thermal lag sets its sense)",
              a["loop_area"] < 0 < nt["loop_area"]),
        Check("4.23-self-crossing-near-5pct",
              "with c_m = c_A = 25 % the hysteresis crosses itself at c_x of about 5 %",
              f"self-crossings of the last period at c_x = {cr(b)} (assert exactly one, between 2.5 % and 10 %)",
              one_cross(b)),
        Check("4.24-frequency",
              "at 50 Hz the loop has the same shape (crossing itself near 5 %) but deviates less from the quasi-steady curve than at 100 Hz; the quasi-steady curve is the limit f0 -> 0",
              f"RMS deviation from the quasi-steady curve: {f4(b['rms_dev_from_qs'])} (100 Hz), {f4(h50['rms_dev_from_qs'])} (50 Hz), {f4(h10['rms_dev_from_qs'])} (10 Hz); crossing at 50 Hz: {cr(h50)} (assert falling with frequency and one crossing in 2.5-10 % at 50 Hz)",
              b["rms_dev_from_qs"] > h50["rms_dev_from_qs"] > h10["rms_dev_from_qs"] and one_cross(h50)),
        Check("4.25-speed",
              "at a higher speed the limit cycle deviates less from the quasi-steady curve (bristles cross the contact faster)",
              f"RMS deviation {f4(b['rms_dev_from_qs'])} at 5 m/s, {f4(v20['rms_dev_from_qs'])} at 20 m/s (assert smaller at 20 m/s)",
              v20["rms_dev_from_qs"] < b["rms_dev_from_qs"]),
    ]


def sines_text(n, S):
    rows = "\n".join(
        f"| {k} | {100 * r['cm']:g} ± {100 * r['ca']:g} % | {r['f0']:g} | {r['v']:g} | {'on' if r['temperature'] else 'off'} | {f3(r['f_min'])}-{f3(r['f_max'])} | {g(r['loop_area'], 3)} | {f4(r['rms_dev_from_qs'])} | {', '.join(pct(c) for c in r['crossings_cx']) or '-'} | {100 * r['periodicity_rms_rel']:.2f} % |"
        for k, r in n["runs"].items())
    return {
        "params": f"{TAB42}; c_x = c_m + c_A sin(2 pi f0 t) (Eq. 4.37) from the steady state of c_m; {n['steps_per_cycle']} time steps per period, {n['cycles']} periods, the last one analysed; grid {n['grid']}; `ecf sine`. The seed does not list the two speeds of Fig. 4.25: 5 and 20 m/s are used. The 10 Hz run and the run without temperature are ours (the f0 -> 0 limit and the mechanism of Fig. 4.22).",
        "seed": "Periodic creepage gives a periodic traction that settles on a limit cycle. With both extremes in R3 (20 ± 10 %) the hysteresis comes from the thermal time dependence. With 25 ± 25 % the loop is more complex and crosses itself near 5 %. At 50 Hz it deviates less from the quasi-steady curve than at 100 Hz (the quasi-steady curve is the f0 -> 0 limit). At a higher speed it deviates less as well.",
        "shows": "Loop area: signed area of the last period in the (c_x, f) plane, negative = clockwise. Deviation: RMS of f(t) - f_quasi-steady(c_x(t)) over the last period.\n\n| run | c_x | f0 [Hz] | v [m/s] | temperature | f range | loop area | RMS deviation | self-crossings | period-to-period RMS |\n|---|---|---|---|---|---|---|---|---|---|\n" + rows,
    }


def sines_plot(n, data, out, S):
    files = []
    cx = 100 * data["qs_cx"]

    def hyst(A, name, label, color="k", qs=True):
        d, qs_v = data["runs"][name]
        spc = n["steps_per_cycle"]
        c, f = 100 * d["cx"], d["f"]
        if qs:
            A.plot(cx, qs_v, color="C7", lw=2, label=f"quasi-steady, v = {n['runs'][name]['v']:g} m/s")
        A.plot(c[:-spc], f[:-spc], color=color, lw=0.6, alpha=0.35)
        A.plot(c[-spc - 1:], f[-spc - 1:], color=color, label=label)
        k = len(c) - spc // 2
        A.annotate("", xy=(c[k + 1], f[k + 1]), xytext=(c[k - 2], f[k - 2]), arrowprops={"arrowstyle": "->", "color": color, "lw": 1.5})
        for x, y in zip(n["runs"][name]["crossings_cx"], n["runs"][name]["crossings_f"]):
            A.plot(100 * x, y, "x", color=color, ms=9, mew=2)
        A.set_xlabel("longitudinal creepage $c_x$ [%]")
        A.set_ylabel("traction coefficient f [-]")

    for fig_no, name, title in (("4.22", "4.22", "c_m = 20 %, c_A = 10 %, f0 = 100 Hz"), ("4.23", "4.23", "c_m = 25 %, c_A = 25 %, f0 = 100 Hz")):
        d, _ = data["runs"][name]
        fig, ax = figure(1, 2, w=11, h=4.3)
        A = ax[0, 0]
        t = d["t_s"] * 1e3
        A.plot(t, d["f"], "k-", label="f (transient)")
        A.set_xlabel("time t [ms]")
        A.set_ylabel("traction coefficient f [-]")
        A2 = A.twinx()
        A2.plot(t, 100 * d["cx"], "C0--", lw=0.8)
        A2.set_ylabel("creepage $c_x$ [%] (dashed)", color="C0")
        A2.grid(False)
        label_panel(A, "(a) traction and creepage over time")
        hyst(ax[0, 1], name, "transient (last period bold)")
        ax[0, 1].set_xlim(0, 55)
        ax[0, 1].legend(loc="lower left" if name == "4.23" else "upper right")
        label_panel(ax[0, 1], "(b) hysteresis (x: self-crossing)")
        files.append(save(fig, out, f"fig{fig_no.replace('.', '_')}_sine.png", f"Seed Fig. {fig_no}: periodic creepage, {title} (Tab. 4.2, v = 5 m/s)"))
    fig, ax = figure(1, 2, w=11, h=4.3)
    hyst(ax[0, 0], "4.23", "100 Hz", color="k")
    hyst(ax[0, 0], "50Hz", "50 Hz", color="C3", qs=False)
    hyst(ax[0, 0], "10Hz", "10 Hz (ours: toward f0 -> 0)", color="C2", qs=False)
    ax[0, 0].legend(loc="upper right")
    ax[0, 0].set_ylim(0, 0.45)
    label_panel(ax[0, 0], "(a) v = 5 m/s, three frequencies")
    hyst(ax[0, 1], "4.22", "20 ± 10 %, with temperature", color="k")
    hyst(ax[0, 1], "4.22-noT", "20 ± 10 %, temperature off", color="C1", qs=False)
    ax[0, 1].set_xlim(5, 35)
    ax[0, 1].set_ylim(0.2, 0.75)
    ax[0, 1].legend(loc="upper right")
    label_panel(ax[0, 1], "(b) mechanism of Fig. 4.22: loop sense with and without heat")
    for A in (ax[0, 0],):
        A.set_xlim(0, 55)
    files.append(save(fig, out, "fig4_24_frequency.png", "Seed Fig. 4.24: limit cycles at 100 and 50 Hz (c_m = c_A = 25 %) against the quasi-steady curve"))
    fig, ax = figure(1, 1, w=7, h=4.5)
    hyst(ax[0, 0], "4.23", "v = 5 m/s", color="k")
    hyst(ax[0, 0], "20mps", "v = 20 m/s", color="C3")
    ax[0, 0].set_xlim(0, 55)
    ax[0, 0].legend(loc="lower left")
    files.append(save(fig, out, "fig4_25_speed.png", "Seed Fig. 4.25: limit cycles at 5 and 20 m/s (100 Hz, 25 ± 25 %)"))
    return files


SINES_FIG = Figure("fig4_22_25", "Fig. 4.22-4.25", "Periodic creepage, limit cycles, frequency and speed",
                   sines_compute, sines_checks, sines_text, sines_plot,
                   ["fig4_22_sine.png", "fig4_23_sine.png", "fig4_24_frequency.png", "fig4_25_speed.png"], section="transient")


# =========================================================================== numerical note
def health_compute(S):
    cfg = run.config("table4.1", grid=grid_of(S))
    f_qs = float(run.curve(cfg, [0.30], v=V_T)["f"][0])
    n = {"grid": grid_name(S), "f_qs": f_qs, "runs": {}}
    data = {}
    for dt in S["health_dt_ms"]:
        d = run.step(cfg, 0.30, 0.30, v=V_T, duration_ms=6.0, dt_ms=dt)
        f = d["f"][1:]
        n["runs"][f"{dt:g}"] = {"mean_rel": float(f.mean() / f_qs - 1), "min_rel": float(f.min() / f_qs - 1), "max_rel": float(f.max() / f_qs - 1),
                                "max_jump": float(np.max(np.abs(np.diff(d["f"]))))}
        data[dt] = d
    return n, data


def health_checks(n, S):
    R = n["runs"]
    worst = max(max(abs(r["min_rel"]), abs(r["max_rel"])) for r in R.values())
    r0 = R[f"{S['health_dt_ms'][0]:g}"]
    first = max(abs(r0["min_rel"]), abs(r0["max_rel"]))
    return [
        Check("N1-constant-input-stays-steady",
              "(not a seed statement; a property any transient model must have) with constant creepage the transient model stays at its steady state, whatever the time step",
              "f relative to `ecf curve` at c_x = 30 %, v = 5 m/s, over 6 ms: " + "; ".join(f"dt = {k} ms: mean {100 * r['mean_rel']:+.2f} %, range {100 * r['min_rel']:+.2f} % to {100 * r['max_rel']:+.2f} %, largest jump in one step {g(r['max_jump'], 2)}" for k, r in R.items()) + " (assert within 1 %)",
              worst < 0.01,
              why="Found by this gallery and fixed in creep-core: with temperature on, the elastic energy released when the layer softens within one sub-step fed back on the flash temperature with a gain growing like 1/sqrt(sub-step), so steps of 1 us let f drop by up to 10 %. The self-heating part of that release is now damped when its gain approaches 1 (docs/model.md, section 6; test tiny_time_steps_at_high_creepage_stay_on_the_steady_state)."),
    ]


def health_text(n, S):
    rows = "\n".join(f"| {k} | {100 * r['mean_rel']:+.2f} % | {100 * r['min_rel']:+.2f} % | {100 * r['max_rel']:+.2f} % | {g(r['max_jump'], 2)} |" for k, r in n["runs"].items())
    return {
        "params": f"{TAB42}; c_x = 30 % held constant (`ecf step --cx-from 0.3 --cx-to 0.3`), 6 ms; grid {n['grid']}; quasi-steady f = {f4(n['f_qs'])}.",
        "seed": "Not a seed figure. The seed's transient results assume that the time-discrete model converges as the time step shrinks (Eq. 4.15, 4.35). This note shows that the project's code stays on its steady state with constant input at the time step used above and at a ten times smaller one (it did not before the fix described in the check).",
        "shows": "| dt [ms] | mean f vs steady | min | max | largest jump in one step |\n|---|---|---|---|---|\n" + rows,
    }


def health_plot(n, data, out, S):
    fig, ax = figure(1, 1, w=7.5, h=4)
    A = ax[0, 0]
    for i, (dt, d) in enumerate(data.items()):
        A.plot(d["t_s"] * 1e3, d["f"], color=f"C{i}", lw=0.8, label=f"dt = {dt:g} ms")
    A.axhline(n["f_qs"], color="k", ls="--", label="steady state (`ecf curve`)")
    A.set_xlabel("time t [ms]")
    A.set_ylabel("traction coefficient f [-]")
    A.legend()
    return [save(fig, out, "note_constant_input_time_step.png", "Numerical note: transient ECF at constant c_x = 30 % (v = 5 m/s), two time steps")]


HEALTH_FIG = Figure("note_time_step", "(numerical note)", "Transient model at constant input and the time step",
                    health_compute, health_checks, health_text, health_plot, ["note_constant_input_time_step.png"], section="notes")

FIGURES = [STEPS_FIG, SINES_FIG]
NOTES = [HEALTH_FIG]
