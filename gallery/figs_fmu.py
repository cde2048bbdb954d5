"""The contact's fields as the FMI 3.0 FMU gives them: the field arrays (field_x, field_p,
field_tau_x, field_tau_c2, field_T, field_regime) during the creepage step 0.1 -> 1 % of
Tab. 4.2, read from dist/ecf_contact_fmi3.fmu through fmpy, beside the steady field of
`ecf field` at the new creepage."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from . import run
from .core import Check, Figure, f3, g
from .plotstyle import figure, label_panel, save

V = 5.0  # Tab. 4.2
A_MM = 7.63
CX_FROM, CX_TO = 0.001, 0.01
DT_MS = 0.05
TIMES_MS = [0.0, 0.4, 0.8, 1.6, 3.1, 6.0]
FMU3 = Path(os.environ.get("ECF_FMU3_PATH", run.ROOT / "dist" / "ecf_contact_fmi3.fmu"))
FIELDS = ["field_x", "field_p", "field_tau_x", "field_tau_c2", "field_T"]


def fmu_compute(S):
    from fmpy import extract, read_model_description
    from fmpy.fmi3 import FMU3Slave

    md = read_model_description(str(FMU3))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    n = int(next(v.start for v in md.modelVariables if v.name == "n_field"))
    s = FMU3Slave(guid=md.instantiationToken, unzipDirectory=extract(str(FMU3)),
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="gallery")
    s.instantiate()
    s.setString([vr["preset"]], ["table4.1"])
    # the presets' grid (80 x 21, cells-ho), as `ecf field` runs it
    s.setFloat64([vr["rel_tol"]], [0.0])
    s.setFloat64([vr["cx"], vr["v"], vr["FN"], vr["T_bulk"]], [CX_FROM, V, 110e3, 20.0])
    s.enterInitializationMode()
    s.exitInitializationMode()

    def read():
        d = {k: np.array(s.getFloat64([vr[k]], nValues=n)) for k in FIELDS}
        d["field_regime"] = np.array(s.getInt32([vr["field_regime"]], nValues=n))
        d["Fx"] = s.getFloat64([vr["Fx"]])[0]
        return d

    snaps = {0.0: read()}
    s.setFloat64([vr["cx"]], [CX_TO])
    steps = int(round(max(TIMES_MS) / DT_MS))
    for k in range(steps):
        s.doStep(currentCommunicationPoint=k * DT_MS * 1e-3, communicationStepSize=DT_MS * 1e-3)
        t = round((k + 1) * DT_MS, 6)
        if t in TIMES_MS:
            snaps[t] = read()
    s.terminate()
    s.freeInstance()
    cli = run.field(run.config("table4.1"), CX_TO, v=V)
    last = snaps[max(TIMES_MS)]
    # the CLI's steady field at the FMU's points (x in mm there)
    order = np.argsort(cli["x_mm"])
    tau_cli = np.interp(last["field_x"] * 1e3, cli["x_mm"][order], cli["tau_x_Pa"][order])
    tmax = float(np.abs(tau_cli).max())
    # the edges aside: there the two lattices' nodes sit at other places (the FMU's strip has
    # its phase after the run, `ecf field`'s steady march none) and the traction drops steeply
    inner = np.abs(last["field_x"] * 1e3) < 0.9 * A_MM
    dev = np.abs(last["field_tau_x"] - tau_cli) / tmax
    nums = {
        "n_field": n, "dt_ms": DT_MS, "times_ms": TIMES_MS,
        "x_first_mm": float(last["field_x"][0] * 1e3), "x_last_mm": float(last["field_x"][-1] * 1e3),
        "p_min_inside_MPa": float(last["field_p"][1:-1].min() / 1e6),
        "tau_x_max_MPa": {f"{t:g}": float(np.abs(d["field_tau_x"]).max() / 1e6) for t, d in snaps.items()},
        "T_max_C": {f"{t:g}": float(d["field_T"].max()) for t, d in snaps.items()},
        "n_yielded": {f"{t:g}": int((d["field_regime"] > 0).sum()) for t, d in snaps.items()},
        "Fx_kN": {f"{t:g}": float(d["Fx"] / 1e3) for t, d in snaps.items()},
        "dev_inner_max": float(dev[inner].max()),
        "dev_mean": float(dev.mean()),
    }
    return nums, {"snaps": snaps, "cli": cli}


def fmu_checks(n, S):
    t0, t1 = "0", f"{max(TIMES_MS):g}"
    return [
        Check("fmu3-arrays-along-the-strip",
              "the FMU's field arrays run along the strip at y = 0 from the leading edge to the trailing edge, the pressure positive inside",
              f"{n['n_field']} points from x = {f3(n['x_first_mm'])} mm to {f3(n['x_last_mm'])} mm, smallest inner pressure {g(n['p_min_inside_MPa'])} MPa (assert x from + to -, p > 0)",
              n["x_first_mm"] > 0 > n["x_last_mm"] and n["p_min_inside_MPa"] > 0),
        Check("fmu3-step-raises-traction-temperature-yield",
              "after the creepage step the traction grows along the strip, the surface heats up and more bristles yield",
              f"max |tau_x| {g(n['tau_x_max_MPa'][t0])} -> {g(n['tau_x_max_MPa'][t1])} MPa, T_max {g(n['T_max_C'][t0])} -> {g(n['T_max_C'][t1])} degC, points yielded {n['n_yielded'][t0]} -> {n['n_yielded'][t1]} (assert all grow)",
              n["tau_x_max_MPa"][t1] > n["tau_x_max_MPa"][t0] and n["T_max_C"][t1] > n["T_max_C"][t0] and n["n_yielded"][t1] > n["n_yielded"][t0]),
        Check("fmu3-field-settles-to-ecf-field",
              "about 2a/v after the step the field is the steady field of the new creepage (the FMU and `ecf field` run one engine)",
              f"at {t1} ms tau_x differs from `ecf field` at 1 % by at most {100 * n['dev_inner_max']:.2f} % of its largest |tau_x| inside |x| < 0.9 a, by {100 * n['dev_mean']:.2f} % on average over the strip (assert < 1 % and < 0.5 %)",
              n["dev_inner_max"] < 0.01 and n["dev_mean"] < 0.005),
    ]


def fmu_text(n, S):
    return {
        "params": f"Tab. 4.2 (preset `table4.1`), F_N = 110 kN, v = {V:g} m/s, T_B = 20 degC, the presets' grid 80 x 21 (`rel_tol = 0`), communication step {DT_MS:g} ms; c_x = {100 * CX_FROM:g} % until t = 0 (the steady state at initialization), then {100 * CX_TO:g} %. Read from `dist/ecf_contact_fmi3.fmu` through fmpy (`FMU3Slave`, `getFloat64(..., nValues=n_field)`), n_field = {n['n_field']} (its start value); see gallery/figs_fmu.py and docs/fmu.md (Field arrays).",
        "seed": "The seed's Fig. 4.15 shows the fields of this step from the model itself; here the same fields come out of the co-simulation component, as a host sees them beside the forces.",
        "shows": "F_x = " + ", ".join(f"{g(v)} kN ({t} ms)" for t, v in n["Fx_kN"].items()) + ". The traction rises from the leading edge as new bristles enter, and the trailing part yields and heats up; the last frame lies on the steady field of `ecf field` (dashed).",
    }


def fmu_plot(n, data, out, S):
    fig, ax = figure(2, 2, w=11, h=7)
    snaps = data["snaps"]
    cmap = [f"C{i}" for i in range(len(snaps))]
    for (t, d), c in zip(sorted(snaps.items()), cmap):
        x = d["field_x"] * 1e3
        ax[0, 0].plot(x, d["field_tau_x"] / 1e6, color=c, label=f"t = {t:g} ms")
        ax[0, 1].plot(x, d["field_T"], color=c, label=f"t = {t:g} ms")
        ax[1, 1].step(x, d["field_regime"] + 0.04 * TIMES_MS.index(t), color=c, where="mid", label=f"t = {t:g} ms")
    last = snaps[max(TIMES_MS)]
    x = last["field_x"] * 1e3
    ax[0, 0].plot(data["cli"]["x_mm"], data["cli"]["tau_x_Pa"] / 1e6, "k--", lw=1, label="`ecf field`, 1 % (steady)")
    ax[1, 0].plot(x, last["field_p"] / 1e6, "k-", label="pressure p")
    tc2 = np.where(last["field_tau_c2"] < 0, np.nan, last["field_tau_c2"])
    ax[1, 0].plot(x, tc2 / 1e6, "C3-", label="strength tau_c2")
    ax[1, 0].plot(x, np.abs(last["field_tau_x"]) / 1e6, "C0-", label="|tau_x|")
    for a in ax.flat:
        a.set_xlabel("x [mm] (leading edge right)")
        a.legend(fontsize=7)
    ax[0, 0].set_ylabel("tau_x [MPa]")
    ax[0, 1].set_ylabel("surface temperature T [degC]")
    ax[1, 0].set_ylabel("stress [MPa]")
    ax[1, 1].set_ylabel("regime (0 elastic, 1 plastic, 2 sliding)")
    label_panel(ax[0, 0], "(a) field_tau_x after the step")
    label_panel(ax[0, 1], "(b) field_T")
    label_panel(ax[1, 0], f"(c) field_p, field_tau_c2, |field_tau_x| at {max(TIMES_MS):g} ms")
    label_panel(ax[1, 1], "(d) field_regime (offset per frame)")
    return [save(fig, out, "fmu3_field_step.png",
                 f"The FMI 3.0 FMU's field arrays during the creepage step {100 * CX_FROM:g} -> {100 * CX_TO:g} % (Tab. 4.2, v = {V:g} m/s)")]


FMU_FIELD_FIG = Figure("fmu3_field_step", "(FMU, cf. Fig. 4.15)", "Field arrays of the FMI 3.0 FMU during a creepage step",
                       fmu_compute, fmu_checks, fmu_text, fmu_plot, ["fmu3_field_step.png"], section="transient")

FIGURES = [FMU_FIELD_FIG]
