"""Scenarios step / ramp / sine: run, write CSV time series, JSON summary and PNG plots.

step: desired creepage 0 -> 15 % at t = 0, v = 5 m/s (seed Fig. 6.4)
ramp: desired creepage 0 -> 50 % -> 0 in 8 s (seed Fig. 3.1b, 6.5), v = 5, 10, 20 m/s
sine: prescribed c_x = c_m + c_A sin(2 pi f0 t), c_m = 12 %, c_A = 10 %, f0 = 53 Hz on one
      contact (seed Fig. 6.6): hysteresis of f over c_x against the steady curve
"""

from __future__ import annotations

import csv
import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import analysis, contact, simulate, stability
from .params import Params

RAMP_PEAK = 0.50
RAMP_DURATION = 8.0
STEP_TARGET = 0.15
SINE = {"cm": 0.12, "ca": 0.10, "f0": 53.0}
OSC_THRESHOLD = 1e-3  # p-p creepage above which an oscillation counts as sustained
DEFAULT_T_END = {"step": 2.5, "ramp": RAMP_DURATION, "sine": 10 / 53.0}


@dataclass
class RunConfig:
    """Options of one scenario run (units in the names; defaults in cli.py)."""

    scenario: str
    model: str = "ecf"  # contact model: ecf | fastsim | polach (FMU parameter `model`)
    v: float = 5.0  # vehicle speed, m/s
    out: Path = Path("out")  # output directory
    h: float = 2.5e-4  # communication step = integrator step, s
    t_end: float | None = None  # simulated time, s (None: scenario default)
    grid: tuple | None = None  # bristle grid (nx, ny) of the FMU, None: FMU default
    contact: str = "auto"  # fmu | curve (steady-curve stand-in) | auto (fmu if found)
    fmu: str | None = None  # path of the contact FMU
    transient: bool = True  # transient contact model (FMU parameter `transient`)
    parallel: bool = True  # step the two wheel contacts in two threads
    preset: str | None = None  # contact preset (FMU parameter `preset`)
    fmu_params: dict = field(default_factory=dict)  # further FMU parameters NAME=VALUE
    progress: bool = True
    c_target: float = STEP_TARGET  # step: desired creepage after the step, -
    sine: dict = field(default_factory=lambda: dict(SINE))


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def resolve_contact(cfg: RunConfig):
    """('fmu', path) or ('curve', None)."""
    if cfg.contact in ("fmu", "auto"):
        path = contact.find_fmu(cfg.fmu)
        if path:
            return "fmu", path
        if cfg.contact == "fmu":
            raise SystemExit("error: contact FMU not found (build it with scripts/build-fmu.sh or pass --fmu)")
        log("warning: contact FMU not found, using the steady-curve stand-in (no contact dynamics)")
    return "curve", None


def make_contacts(cfg: RunConfig, p: Params, kind, path, n=2):
    names = ("wheel_L", "wheel_S")
    out = []
    for i in range(n):
        kw = dict(model=cfg.model, v=cfg.v, F_N=p.contact.F_N, T_bulk=p.contact.T_bulk, preset=cfg.preset,
                  grid=cfg.grid)
        if kind == "fmu":
            kw.update(transient=cfg.transient, params=cfg.fmu_params, name=names[i])
        out.append(contact.make_contact(kind, fmu_path=path, **kw))
    return out


class SteadyCurve:
    """Steady characteristic f(c_x) of the contact at the run's operating point."""

    def __init__(self, cfg: RunConfig, p: Params, kind, path):
        self.cfg, self.p, self.kind, self.path = cfg, p, kind, path
        if kind == "curve":
            self._c = contact.CurveContact(model=cfg.model, v=cfg.v, F_N=p.contact.F_N, T_bulk=p.contact.T_bulk,
                                           preset=cfg.preset, grid=cfg.grid)

    def __call__(self, cx):
        cx = np.atleast_1d(np.asarray(cx, float))
        if self.kind == "curve":
            return self._c.steady_f(cx)
        return contact.steady_curve_fmu(self.path, cx, model=self.cfg.model, v=self.cfg.v, F_N=self.p.contact.F_N,
                                        T_bulk=self.p.contact.T_bulk, preset=self.cfg.preset, grid=self.cfg.grid,
                                        params=self.cfg.fmu_params)

    def slope(self, c, dc=0.005):
        fm, f0, fp = self([max(c - dc, 0.0), c, c + dc])
        return float(f0), float((fp - fm) / (c + dc - max(c - dc, 0.0)))


def predict(p: Params, v, c, curve: SteadyCurve):
    f0, s = curve.slope(c)
    return stability.analyse(p, v, c, f0, s)


def write_csv(path: Path, cols: dict):
    names = list(cols)
    data = np.column_stack([cols[n] for n in names])
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for r in data:
            w.writerow([f"{x:.9g}" for x in r])


def _json_clean(o):
    if isinstance(o, dict):
        return {k: _json_clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_json_clean(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return None if not math.isfinite(float(o)) else float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.bool_,)):
        return bool(o)
    if isinstance(o, Path):
        return str(o)
    return o


def c_des_function(cfg: RunConfig):
    if cfg.scenario == "step":
        return lambda t: cfg.c_target
    if cfg.scenario == "ramp":
        half = RAMP_DURATION / 2

        def ramp(t):
            if t <= half:
                return RAMP_PEAK * t / half
            if t <= RAMP_DURATION:
                return RAMP_PEAK * (RAMP_DURATION - t) / half
            return 0.0

        return ramp
    raise ValueError(cfg.scenario)


def run(cfg: RunConfig, p: Params, write=True, plot=True):
    """Runs one scenario for one model. Returns (summary dict, results dict)."""
    if cfg.scenario == "sine":
        return run_sine(cfg, p, write, plot)
    t_end = cfg.t_end or DEFAULT_T_END[cfg.scenario]
    kind, path = resolve_contact(cfg)
    tag = f"{cfg.scenario}_{cfg.model}_v{cfg.v:g}"
    log(f"[{tag}] contact: {kind}{' ' + str(path) if path else ''}, grid {cfg.grid or 'FMU default'}, "
        f"transient {cfg.transient}, h = {cfg.h * 1e3:g} ms, t_end = {t_end:g} s")
    t0 = time.perf_counter()
    curve = SteadyCurve(cfg, p, kind, path)
    c_grid = np.linspace(0.0, 0.6 if cfg.scenario == "step" else 1.0, 121)
    f_grid = curve(c_grid)
    t_curve = time.perf_counter() - t0
    cL, cS = make_contacts(cfg, p, kind, path)
    try:
        res, stats = simulate.simulate(p, cL, cS, cfg.v, c_des_function(cfg), t_end, cfg.h,
                                       parallel=cfg.parallel and kind == "fmu", progress=cfg.progress, label=tag)
    finally:
        cL.close()
        cS.close()
    t = res["t_s"]
    # linear analysis at the operating point(s)
    if cfg.scenario == "step":
        lin = predict(p, cfg.v, cfg.c_target, curve)
        settled = (max(0.3, t_end - 1.0), t_end)
        ramp_info = {}
    else:
        scan_c = np.round(np.arange(0.01, RAMP_PEAK + 1e-9, 0.01), 4)
        fs = curve(np.concatenate([scan_c - 0.005, scan_c + 0.005, scan_c]))
        n = len(scan_c)
        scans = [stability.analyse(p, cfg.v, c, fs[2 * n + i], (fs[n + i] - fs[i]) / 0.01)
                 for i, c in enumerate(scan_c)]
        unst = [s for s in scans if s["predicted_unstable"]]
        lin = max(scans, key=lambda s: s["predicted_growth_rate"])
        settled = (0.5, t_end)
        ramp_info = {
            "predicted_unstable_cx_range": [min(s["cx"] for s in unst), max(s["cx"] for s in unst)] if unst else None,
            "stability_scan": [{"cx": s["cx"], "f": s["f"], "dfdc": s["dfdc"],
                                "frequency_hz": s["predicted_frequency_hz"],
                                "damping_ratio": s["predicted_damping_ratio"]} for s in scans],
        }
    # spectrum: for the ramp the slow trend is removed by a 0.1 s moving average first
    sig = res["cx_L"] if cfg.scenario == "step" else analysis.oscillation_part(t, res["cx_L"], 0.1)
    f_dom, (freqs, spec) = analysis.dominant_frequency(t, sig, *settled, fmin=10.0)
    amp = analysis.peak_to_peak(t, res["cx_L"], t_end - 0.5, t_end)
    # frequency of the transient right after the step / start (meaningful also when it decays)
    f_tr, spec_tr = analysis.dominant_frequency(t, sig, 0.2, min(t_end, 1.0), fmin=10.0)
    period = 1.0 / (f_dom if np.isfinite(f_dom) and f_dom > 0 else lin["predicted_frequency_hz"])
    env_t, env = analysis.envelope(t, res["cx_L"], period, win=0.1)
    keep = env_t >= 0.5  # the start-up (controller, stick-slip at ~0 creepage) is not an oscillation
    env_t, env = env_t[keep], env[keep]
    osc = analysis.oscillation_part(t, res["cx_L"], period)

    def osc_pp(a, b):
        m = (t >= a) & (t <= b) & np.isfinite(osc)
        return float(np.max(osc[m]) - np.min(osc[m])) if m.sum() > 3 else float("nan")

    osc_thr = 0.01
    osc_windows = env_t[env > osc_thr]
    summary = {
        "scenario": cfg.scenario,
        "model": cfg.model,
        "v_mps": cfg.v,
        "contact": kind,
        "fmu": str(path) if path else None,
        "grid": list(cfg.grid) if cfg.grid else "FMU default",
        "transient": cfg.transient if kind == "fmu" else False,
        "h_s": cfg.h,
        "t_end_s": t_end,
        "cx_target": cfg.c_target if cfg.scenario == "step" else RAMP_PEAK,
        "settled_window_s": list(settled),
        "dominant_frequency_hz": f_dom,
        "oscillation_amplitude": amp,
        "oscillation_amplitude_note": "peak-to-peak of c_x,L (dimensionless, linear trend removed) over the last 0.5 s",
        "sustained_oscillation": bool(amp > OSC_THRESHOLD) if cfg.scenario == "step"
        else bool(len(env) and env.max() > 10 * OSC_THRESHOLD),
        "sustained_oscillation_note": f"step: oscillation_amplitude > {OSC_THRESHOLD} (0.1 % creepage); ramp: "
                                      f"max_envelope_pp > {10 * OSC_THRESHOLD}; otherwise dominant_frequency_hz is "
                                      "that of numerical noise or of the ramp's trend",
        "transient_frequency_hz": f_tr,
        "transient_frequency_note": "dominant frequency of c_x,L over 0.2-1.0 s (the response to the step, also when it decays)",
        "pp_last_0.25s": analysis.peak_to_peak(t, res["cx_L"], t_end - 0.25, t_end),
        "pp_prev_0.25s": analysis.peak_to_peak(t, res["cx_L"], t_end - 0.5, t_end - 0.25),
        "osc_pp_early": osc_pp(0.5, min(1.0, t_end)),
        "osc_pp_late": osc_pp(t_end - 0.5, t_end),
        "osc_pp_note": "p-p of c_x,L minus its moving average over one period, 0.5-1.0 s and last 0.5 s",
        "mode_amplitude_early": analysis.tone_amplitude(t, sig, lin["predicted_frequency_hz"], 0.2, min(0.7, t_end)),
        "mode_amplitude_late": analysis.tone_amplitude(t, sig, lin["predicted_frequency_hz"], t_end - 0.5, t_end),
        "mode_amplitude_note": "amplitude of c_x,L at the predicted frequency (windowed DFT), 0.2-0.7 s and last 0.5 s",
        "max_envelope_pp": float(env.max()) if len(env) else float("nan"),
        "oscillating_time_s": [float(osc_windows.min()), float(osc_windows.max())] if len(osc_windows) else None,
        "mean_cx_L_last_0.5s": float(np.nanmean(res["cx_L"][t >= t_end - 0.5])),
        "predicted_frequency_hz": lin["predicted_frequency_hz"],
        "predicted_unstable": lin["predicted_unstable"],
        "predicted_damping_ratio": lin["predicted_damping_ratio"],
        "linear_analysis": lin,
        **ramp_info,
        "real_time_factor": stats["real_time_factor"],
        "real_time_factor_note": "wall-clock time of the co-simulation loop / simulated time (< 1: faster than real time)",
        "timing_s": {"loop": stats["wall_s"], "contact_calls": stats["contact_s"],
                     "python_and_drivetrain": stats["wall_s"] - stats["contact_s"], "steady_curve": t_curve},
        "parallel_contacts": stats["parallel_contacts"],
        "drivetrain_params": p.source,
    }
    results = {"res": res, "spectrum": (freqs, spec), "curve": (c_grid, f_grid), "env": (env_t, env),
               "spectrum_transient": spec_tr}
    if cfg.scenario == "ramp" and len(osc_windows):
        cd = c_des_function(cfg)
        summary["oscillating_cx_des_up"] = [cd(float(osc_windows.min())), cd(min(float(osc_windows.max()), 4.0))]
        summary["oscillating_cx_des_down"] = [cd(float(osc_windows.max())), cd(max(float(osc_windows.min()), 4.0))]
        summary["oscillating_note"] = ("desired creepage when the oscillation p-p first/last exceeds 1 % "
                                       "(compare predicted_unstable_cx_range; growth needs time, so the onset lags)")
    if cfg.scenario == "ramp" and len(env) and env.max() > OSC_THRESHOLD:
        tm = float(env_t[np.argmax(env)])
        summary["zoom_window_s"] = [max(0.0, tm - 0.05), min(t_end, tm + 0.05)]
    else:
        summary["zoom_window_s"] = [max(0.0, t_end - 0.1), t_end]
    if write:
        out = Path(cfg.out)
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / f"{tag}.csv", res)
        write_csv(out / f"{tag}_steady_curve.csv", {"cx": c_grid, "f": f_grid})
        files = [out / f"{tag}.csv", out / f"{tag}_steady_curve.csv"]
        if plot:
            from . import plots
            files.append(plots.plot_run(out / f"{tag}.png", summary, results))
        summary["files"] = [str(f) for f in files] + [str(out / f"{tag}.json")]
        (out / f"{tag}.json").write_text(json.dumps(_json_clean(summary), indent=2))
    if summary["sustained_oscillation"]:
        osc_txt = f"dominant frequency {f_dom:.2f} Hz"
    elif cfg.scenario == "ramp":
        osc_txt = f"no oscillation (p-p of c_x,L below {100 * 10 * OSC_THRESHOLD:g} % throughout)"
    else:
        osc_txt = f"no sustained oscillation (response {f_tr:.2f} Hz decays)"
    log(f"[{tag}] {osc_txt}, oscillation p-p {100 * amp:.3f} % (last 0.5 s), "
        f"predicted {lin['predicted_frequency_hz']:.2f} Hz {'UNSTABLE' if lin['predicted_unstable'] else 'stable'}, "
        f"real-time factor {stats['real_time_factor']:.3f}")
    return _json_clean(summary), results


def run_sine(cfg: RunConfig, p: Params, write=True, plot=True):
    """Prescribed sinusoidal creepage on one contact (no drive-train), hysteresis against the steady curve."""
    cm, ca, f0 = cfg.sine["cm"], cfg.sine["ca"], cfg.sine["f0"]
    t_end = cfg.t_end or DEFAULT_T_END["sine"]
    kind, path = resolve_contact(cfg)
    tag = f"sine_{cfg.model}_v{cfg.v:g}"
    log(f"[{tag}] contact: {kind}, c_m = {cm}, c_A = {ca}, f0 = {f0} Hz, h = {cfg.h * 1e3:g} ms, t_end = {t_end:.4g} s")
    curve = SteadyCurve(cfg, p, kind, path)
    c_grid = np.linspace(0.0, 0.6, 121)
    f_grid = curve(c_grid)
    (c1,) = make_contacts(cfg, p, kind, path, n=1)
    n = int(round(t_end / cfg.h))
    t = np.arange(n + 1) * cfg.h
    cx = cm + ca * np.sin(2 * np.pi * f0 * t)
    f = np.full(n + 1, np.nan)
    Fx = np.full(n + 1, np.nan)
    Tmax = np.full(n + 1, np.nan)
    wall0 = time.perf_counter()
    try:
        # creepage held over [t_k, t_k+1] at its mid-step value; the output at t_k+1 is
        # recorded with the creepage that produced it
        for k in range(n):
            cmid = cm + ca * np.sin(2 * np.pi * f0 * (k + 0.5) * cfg.h)
            cx[k + 1] = cmid
            Fx[k + 1], f[k + 1] = c1.step(k * cfg.h, cfg.h, cmid)
            Tmax[k + 1] = c1.extra().get("T_max", np.nan)
    finally:
        c1.close()
    wall = time.perf_counter() - wall0
    period = 1.0 / f0
    last = t >= t_end - period - 1e-12
    c_last, f_last = cx[last], f[last]
    f_steady_last = np.interp(c_last, c_grid, f_grid)
    lin = predict(p, cfg.v, cm, curve)
    f_dom, (freqs, spec) = analysis.dominant_frequency(t, cx, period, t_end)
    summary = {
        "scenario": "sine",
        "model": cfg.model,
        "v_mps": cfg.v,
        "contact": kind,
        "fmu": str(path) if path else None,
        "grid": list(cfg.grid) if cfg.grid else "FMU default",
        "transient": cfg.transient if kind == "fmu" else False,
        "h_s": cfg.h,
        "t_end_s": t_end,
        "cx_mean": cm, "cx_amplitude": ca, "frequency_prescribed_hz": f0,
        "dominant_frequency_hz": f_dom,
        "oscillation_amplitude": analysis.peak_to_peak(t, cx, t_end - 0.5, t_end, detrend=False),
        "f_range_last_cycle": [float(np.nanmin(f_last)), float(np.nanmax(f_last))],
        "hysteresis_loop_area": analysis.loop_area(c_last, f_last),
        "hysteresis_loop_area_note": "signed area of f over c_x for the last period; > 0: counter-clockwise",
        "cv_rmse_vs_steady_percent": analysis.cv_rmse(f_last, f_steady_last),
        "predicted_frequency_hz": lin["predicted_frequency_hz"],
        "predicted_unstable": lin["predicted_unstable"],
        "predicted_damping_ratio": lin["predicted_damping_ratio"],
        "linear_analysis": lin,
        "real_time_factor": wall / t_end,
        "real_time_factor_note": "wall-clock time of the stepping loop / simulated time (one contact)",
    }
    results = {"res": {"t_s": t, "cx": cx, "f": f, "Fx_N": Fx, "T_max_C": Tmax}, "curve": (c_grid, f_grid),
               "spectrum": (freqs, spec)}
    if write:
        out = Path(cfg.out)
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / f"{tag}.csv", results["res"])
        write_csv(out / f"{tag}_steady_curve.csv", {"cx": c_grid, "f": f_grid})
        files = [out / f"{tag}.csv", out / f"{tag}_steady_curve.csv"]
        if plot:
            from . import plots
            files.append(plots.plot_sine(out / f"{tag}.png", summary, results))
        summary["files"] = [str(x) for x in files] + [str(out / f"{tag}.json")]
        (out / f"{tag}.json").write_text(json.dumps(_json_clean(summary), indent=2))
    log(f"[{tag}] f over last cycle {summary['f_range_last_cycle']}, loop area {summary['hysteresis_loop_area']:.4g}, "
        f"CV(RMSE) vs steady {summary['cv_rmse_vs_steady_percent']:.2f} %")
    return _json_clean(summary), results
