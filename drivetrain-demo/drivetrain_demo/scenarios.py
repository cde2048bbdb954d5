"""Scenarios step / ramp / sine: run, write CSV time series, JSON summary and PNG plots.

step: desired creepage 0 -> 15 % at t = 0, v = 5 m/s (seed Fig. 6.4)
ramp: desired creepage 0 -> 50 % -> 0 in 8 s (seed Fig. 3.1b, 6.5), v = 5, 10, 20 m/s
sine: prescribed c_x = c_m + c_A sin(2 pi f0 t), c_m = 12 %, c_A = 10 %, f0 = 53 Hz on one
      contact (seed Fig. 6.6): hysteresis of f over c_x against the steady curve
"""

from __future__ import annotations

import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import __version__, analysis, contact, cosim, io_util, stability
from .errors import ConfigError, DrivetrainError, FMUNotFoundError
from .params import Params

RAMP_PEAK = 0.50
RAMP_DURATION = 8.0
STEP_TARGET = 0.15
SINE = {"cm": 0.12, "ca": 0.10, "f0": 53.0}
OSC_THRESHOLD = 1e-3  # p-p creepage above which an oscillation counts as sustained
DEFAULT_T_END = {"step": 2.5, "ramp": RAMP_DURATION, "sine": 10 / 53.0}
SCENARIOS = ("step", "ramp", "sine")
MODELS = ("ecf", "fastsim", "polach")
# Contact conditions accepted by --preset (ECF parameter sets of the FMU; seed Tab. 4.1, Tab. 5.4).
# twin_disc is not among them: it is the 47 mm disc rig's line contact, not a wheel on a rail.
CONDITIONS = ("table4.1", "dry", "wet", "dry_sanded", "wet_sanded")
# FASTSIM under a condition: the seed fitted mu = 0.25 to the dry vehicle tests at 5 m/s (Sec. 3.1.1,
# Fig. 3.8); for another condition mu is scaled by the ratio of the adhesion maxima of the ECF
# steady curves of that condition and of dry (v = 5 m/s, F_N = 110 kN, T_bulk = 20 degC, FMU grid
# 80x21): mu_P = 0.25 * max f_ECF,P / max f_ECF,dry. Computed by `condition_mu()`, checked by a test,
# documented in docs/drivetrain.md.
FASTSIM_MU_DRY = 0.25
FASTSIM_MU = {"table4.1": 0.248, "dry": 0.25, "wet": 0.223, "dry_sanded": 0.25, "wet_sanded": 0.25}
# minimum run length (s) per scenario: the analysis windows must fit inside the run
MIN_T_END = {"step": 0.8, "ramp": 1.0}
MIN_SINE_PERIODS = 2


# The demo's bristle grid (nx, ny) of the FMU, under the FMU's default scheme (cells-ho for ECF,
# cells for FASTSIM). Step 0 -> 15 % at 5 m/s, ECF against 80x21: frequency within 0.01 %,
# limit-cycle amplitude +0.18 % (within 0.5 % on 12x7, 12x9, 14x7, 16x9, 20x7; up to 3.5 % off on
# 10x7, 14x5, 16x5). 12x7 would be cheaper, but there FASTSIM's decayed response leaves a 68 Hz
# ripple of the grid (p-p 3.6e-4) that hides its 54 Hz transient; on 14x7 it is 4e-5 and the
# transient reads 54.28 Hz (docs/drivetrain.md, Convergence).
DEFAULT_GRID = (14, 7)
DEFAULT_GRID_TEXT = f"{DEFAULT_GRID[0]}x{DEFAULT_GRID[1]}"


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
    overrides: dict = field(default_factory=dict)  # --set values applied to the parameters (provenance only)
    save_every: int = 1  # write every N-th row of the trace CSV (the analysis uses every row)

    @property
    def condition(self) -> str:
        """Label of the contact condition in file names: the preset, or `default` (the model's own)."""
        return self.preset or "default"

    @property
    def tag(self) -> str:
        """Base name of the output files: <scenario>_<model>_<condition>_v<v>."""
        return f"{self.scenario}_{self.model}_{self.condition}_v{self.v:g}"

    def resolved_t_end(self) -> float:
        """Simulated time, s: t_end, or the scenario's default (sine: 10 periods of f0)."""
        if self.t_end:
            return self.t_end
        return 10 / self.sine["f0"] if self.scenario == "sine" else DEFAULT_T_END[self.scenario]


def validate(cfg: RunConfig):
    """Checks the options of a run; raises ConfigError naming the option and the accepted values."""
    if cfg.scenario not in SCENARIOS:
        raise ConfigError(f"scenario {cfg.scenario!r}: unknown (accepted: {', '.join(SCENARIOS)})")
    if cfg.model not in MODELS:
        raise ConfigError(f"--model {cfg.model}: unknown (accepted: {', '.join(MODELS)}, both)")
    if cfg.preset is not None and cfg.preset not in CONDITIONS:
        raise ConfigError(f"--preset {cfg.preset}: unknown (accepted: {', '.join(CONDITIONS)})")
    if cfg.preset is not None and cfg.model == "polach":
        raise ConfigError(f"--preset {cfg.preset} with --model polach: Polach's parameters exist only for the "
                          "seed's vehicle tests (no preset); use --model ecf or fastsim for a condition")
    if not (cfg.v > 0 and math.isfinite(cfg.v)):
        raise ConfigError(f"--v-mps {cfg.v}: must be > 0 (m/s)")
    if not (cfg.h > 0 and math.isfinite(cfg.h)):
        raise ConfigError(f"--h-ms {cfg.h * 1e3:g}: must be > 0 (ms)")
    if cfg.save_every < 1:
        raise ConfigError(f"--save-every {cfg.save_every}: must be an integer >= 1")
    if cfg.grid is not None:
        nx, ny = cfg.grid
        if not (2 <= nx <= 2000 and 1 <= ny <= 1000):
            raise ConfigError(f"--grid {nx}x{ny}: need 2 <= NX <= 2000, 1 <= NY <= 1000")
    if not (0.0 <= cfg.c_target <= 1.0):
        raise ConfigError(f"--cx {cfg.c_target}: creepage must be in [0, 1] (dimensionless, 0.15 = 15 %)")
    t_end = cfg.resolved_t_end()
    if cfg.scenario == "sine":
        need = MIN_SINE_PERIODS / cfg.sine["f0"]
        if t_end < need - 1e-12:
            raise ConfigError(f"--t-end {t_end:g}: too short for the sine analysis (last period of "
                              f"{MIN_SINE_PERIODS} or more): need >= {need:.4g} s at f0 = {cfg.sine['f0']:g} Hz")
    elif t_end < MIN_T_END[cfg.scenario]:
        raise ConfigError(f"--t-end {t_end:g}: too short to analyse a {cfg.scenario} (the spectrum needs a settled "
                          f"window of >= 0.5 s after 0.3 s): need >= {MIN_T_END[cfg.scenario]:g} s")
    if t_end / cfg.h < 100:
        raise ConfigError(f"--t-end {t_end:g} with --h-ms {cfg.h * 1e3:g}: fewer than 100 steps")


def contact_settings(cfg: RunConfig):
    """(FMU preset, FMU parameters, note) the contact of this run gets.

    ECF: the preset as given. FASTSIM under a condition: no FMU preset (the `fastsim` model's own),
    mu matched to the condition (FASTSIM_MU), unless --fmu-param mu=... is given."""
    params = dict(cfg.fmu_params)
    if cfg.model == "fastsim" and cfg.preset is not None:
        note = None
        if "mu" not in params:
            params["mu"] = condition_mu(cfg.preset)
            note = (f"FASTSIM under condition {cfg.preset!r}: mu = {params['mu']:.3f} = 0.25 x max f_ECF,{cfg.preset} / "
                    "max f_ECF,dry (seed Sec. 3.1.1: mu = 0.25 fitted to the dry vehicle tests; docs/drivetrain.md)")
        return None, params, note
    return cfg.preset, params, None


def condition_mu(preset: str, fmu_path=None) -> float:
    """FASTSIM friction coefficient matched to a contact condition (see FASTSIM_MU). Values not in the
    table are computed from the FMU's ECF steady curves (needs the FMU)."""
    if preset not in CONDITIONS:
        raise ConfigError(f"--preset {preset}: unknown (accepted: {', '.join(CONDITIONS)})")
    if FASTSIM_MU.get(preset) is not None and fmu_path is None:
        return FASTSIM_MU[preset]
    return round(FASTSIM_MU_DRY * ecf_adhesion_max(preset, fmu_path) / ecf_adhesion_max("dry", fmu_path), 3)


def ecf_adhesion_max(preset: str, fmu_path=None, v=5.0, F_N=110e3, T_bulk=20.0) -> float:
    """Maximum of the steady ECF curve f(c_x), c_x in 0-60 %, for a condition (on the presets' grid
    80x21, given explicitly: the FMU's own default is the grid its rel_tol chooses)."""
    path = contact.find_fmu(fmu_path)
    if path is None:
        raise FMUNotFoundError("the condition-matched FASTSIM mu needs the contact FMU (scripts/build-fmu.sh)")
    cx = np.concatenate([np.linspace(0.005, 0.1, 39), np.linspace(0.11, 0.6, 50)])
    f = contact.steady_curve_fmu(path, cx, model="ecf", v=v, F_N=F_N, T_bulk=T_bulk, preset=preset,
                                 grid=(80, 21))
    return float(np.max(f))


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def _say(cfg: RunConfig, msg):
    if cfg.progress:
        log(msg)


def resolve_contact(cfg: RunConfig):
    """('fmu', path) or ('curve', None)."""
    if cfg.contact in ("fmu", "auto"):
        path = contact.find_fmu(cfg.fmu)
        if path:
            return "fmu", path
        if cfg.contact == "fmu":
            raise FMUNotFoundError("contact FMU not found (build it with scripts/build-fmu.sh, pass --fmu "
                                   "or set $ECF_FMU_PATH)")
        log("warning: contact FMU not found, using the steady-curve stand-in (no contact dynamics)")
    return "curve", None


def make_contacts(cfg: RunConfig, p: Params, kind, path, n=2):
    names = ("wheel_L", "wheel_S")
    preset, fmu_params, _ = contact_settings(cfg)
    out = []
    for i in range(n):
        kw = dict(model=cfg.model, v=cfg.v, F_N=p.contact.F_N, T_bulk=p.contact.T_bulk, preset=preset,
                  grid=cfg.grid)
        if kind == "fmu":
            kw.update(transient=cfg.transient, params=fmu_params, name=names[i])
        out.append(contact.make_contact(kind, fmu_path=path, **kw))
    return out


class SteadyCurve:
    """Steady characteristic f(c_x) of the contact at the run's operating point."""

    def __init__(self, cfg: RunConfig, p: Params, kind, path):
        self.cfg, self.p, self.kind, self.path = cfg, p, kind, path
        self.preset, self.fmu_params, _ = contact_settings(cfg)
        if kind == "curve":
            if self.fmu_params:
                raise ConfigError("--fmu-param (or a condition-matched FASTSIM mu) needs --contact fmu; "
                                  "the steady-curve stand-in takes no FMU parameters")
            self._c = contact.CurveContact(model=cfg.model, v=cfg.v, F_N=p.contact.F_N, T_bulk=p.contact.T_bulk,
                                           preset=self.preset, grid=cfg.grid)

    def __call__(self, cx):
        cx = np.atleast_1d(np.asarray(cx, float))
        if self.kind == "curve":
            return self._c.steady_f(cx)
        return contact.steady_curve_fmu(self.path, cx, model=self.cfg.model, v=self.cfg.v, F_N=self.p.contact.F_N,
                                        T_bulk=self.p.contact.T_bulk, preset=self.preset, grid=self.cfg.grid,
                                        params=self.fmu_params)

    def slope(self, c, dc=0.005):
        fm, f0, fp = self([max(c - dc, 0.0), c, c + dc])
        return float(f0), float((fp - fm) / (c + dc - max(c - dc, 0.0)))


def predict(p: Params, v, c, curve: SteadyCurve):
    f0, s = curve.slope(c)
    return stability.analyse(p, v, c, f0, s)


def write_csv(path: Path, cols: dict, every: int = 1):
    """Atomic CSV writer (io_util.write_csv): every N-th row and the last."""
    return io_util.write_csv(path, cols, every)


def provenance(cfg: RunConfig, p: Params, kind, path) -> dict:
    """What made a result: options, preset, every --set and --fmu-param, grid, FMU identity, versions."""
    preset, fmu_params, note = contact_settings(cfg)
    prov = {
        "project_version": __version__,
        "preset": cfg.preset,
        "condition": cfg.condition,
        "fmu_preset": preset,
        "fmu_params": {k: (v if isinstance(v, (int, float, bool)) else str(v)) for k, v in fmu_params.items()},
        "fmu_params_given": {k: str(v) for k, v in cfg.fmu_params.items()},
        "overrides": {k: float(v) for k, v in cfg.overrides.items()},
        "grid": list(cfg.grid) if cfg.grid else "FMU default",
        "h_s": cfg.h,
        "save_every": cfg.save_every,
        "fmu_identity": contact.fmu_identity(path) if path else None,
        "drivetrain_params": p.source,
        "F_N_N": p.contact.F_N,
        "T_bulk_C": p.contact.T_bulk,
    }
    if note:
        prov["fastsim_mu_note"] = note
    return prov


def _write_outputs(cfg, summary, results, res_cols, c_grid, f_grid, plot, plot_fn):
    out = Path(cfg.out)
    out.mkdir(parents=True, exist_ok=True)
    tag = cfg.tag
    files = [write_csv(out / f"{tag}.csv", res_cols, cfg.save_every),
             write_csv(out / f"{tag}_steady_curve.csv", {"cx": c_grid, "f": f_grid})]
    if plot:
        from . import plots
        with io_util.atomic_path(out / f"{tag}.png") as tmp:
            getattr(plots, plot_fn)(tmp, summary, results)
        files.append(out / f"{tag}.png")
    summary["files"] = [str(f) for f in files] + [str(out / f"{tag}.json")]
    io_util.write_json(out / f"{tag}.json", _json_clean(summary))


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
    validate(cfg)
    if cfg.scenario == "sine":
        return run_sine(cfg, p, write, plot)
    t_end = cfg.resolved_t_end()
    kind, path = resolve_contact(cfg)
    tag = cfg.tag
    _say(cfg, f"[{tag}] contact: {kind}{' ' + str(path) if path else ''}, grid {cfg.grid or 'FMU default'}, "
        f"transient {cfg.transient}, h = {cfg.h * 1e3:g} ms, t_end = {t_end:g} s")
    t0 = time.perf_counter()
    curve = SteadyCurve(cfg, p, kind, path)
    c_grid = np.linspace(0.0, 0.6 if cfg.scenario == "step" else 1.0, 121)
    f_grid = curve(c_grid)
    t_curve = time.perf_counter() - t0
    cL, cS = make_contacts(cfg, p, kind, path)
    try:
        res, stats = cosim.simulate(p, cL, cS, cfg.v, c_des_function(cfg), t_end, cfg.h,
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
        "provenance": provenance(cfg, p, kind, path),
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
        _write_outputs(cfg, summary, results, res, c_grid, f_grid, plot, "plot_run")
    if summary["sustained_oscillation"]:
        osc_txt = f"dominant frequency {f_dom:.2f} Hz"
    elif cfg.scenario == "ramp":
        osc_txt = f"no oscillation (p-p of c_x,L below {100 * 10 * OSC_THRESHOLD:g} % throughout)"
    else:
        osc_txt = f"no sustained oscillation (response {f_tr:.2f} Hz decays)"
    _say(cfg, f"[{tag}] {osc_txt}, oscillation p-p {100 * amp:.3f} % (last 0.5 s), "
        f"predicted {lin['predicted_frequency_hz']:.2f} Hz {'UNSTABLE' if lin['predicted_unstable'] else 'stable'}, "
        f"real-time factor {stats['real_time_factor']:.3f}")
    return _json_clean(summary), results


def run_sine(cfg: RunConfig, p: Params, write=True, plot=True):
    """Prescribed sinusoidal creepage on one contact (no drive-train), hysteresis against the steady curve."""
    cm, ca, f0 = cfg.sine["cm"], cfg.sine["ca"], cfg.sine["f0"]
    t_end = cfg.resolved_t_end()
    kind, path = resolve_contact(cfg)
    tag = cfg.tag
    _say(cfg, f"[{tag}] contact: {kind}, c_m = {cm}, c_A = {ca}, f0 = {f0} Hz, h = {cfg.h * 1e3:g} ms, t_end = {t_end:.4g} s")
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
        "provenance": provenance(cfg, p, kind, path),
    }
    results = {"res": {"t_s": t, "cx": cx, "f": f, "Fx_N": Fx, "T_max_C": Tmax}, "curve": (c_grid, f_grid),
               "spectrum": (freqs, spec)}
    if write:
        _write_outputs(cfg, summary, results, results["res"], c_grid, f_grid, plot, "plot_sine")
    _say(cfg, f"[{tag}] f over last cycle {summary['f_range_last_cycle']}, loop area {summary['hysteresis_loop_area']:.4g}, "
        f"CV(RMSE) vs steady {summary['cv_rmse_vs_steady_percent']:.2f} %")
    return _json_clean(summary), results
