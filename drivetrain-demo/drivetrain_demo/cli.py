"""Command line: python -m drivetrain_demo SCENARIO --model M [--v-mps V] --out DIR [--json].

SCENARIO: step | ramp | sine | modal.  --model: ecf | fastsim | polach | both (= ecf and fastsim,
plus a side-by-side comparison plot).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import params as params_mod
from . import scenarios, stability

MODELS = ("ecf", "fastsim", "polach")


def _grid(s):
    try:
        nx, ny = (int(x) for x in s.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"grid '{s}': expected NXxNY, e.g. 20x11") from None
    if not (2 <= nx <= 2000 and 1 <= ny <= 1000):
        raise argparse.ArgumentTypeError(f"grid '{s}': need 2 <= NX <= 2000, 1 <= NY <= 1000")
    return nx, ny


def _positive(name):
    def f(s):
        try:
            x = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} '{s}' is not a number") from None
        if not x > 0:
            raise argparse.ArgumentTypeError(f"{name} must be > 0 (got {s})")
        return x
    return f


def _kv(s):
    if "=" not in s:
        raise argparse.ArgumentTypeError(f"'{s}': expected NAME=VALUE")
    k, v = s.split("=", 1)
    return k.strip(), v.strip()


def build_parser():
    ap = argparse.ArgumentParser(
        prog="python -m drivetrain_demo",
        description="Drive-train oscillations of a locomotive wheelset with the ECF contact FMU (seed Sec. 3.1.2, 6.2).",
        epilog="Units: creepages dimensionless (0.15 = 15 %), speeds m/s, times s unless the option says ms.")
    ap.add_argument("scenario", choices=("step", "ramp", "sine", "modal", "bench"),
                    help="step: c_des 0 -> 15 %% (Fig. 6.4); ramp: 0 -> 50 %% -> 0 in 8 s (Fig. 6.5); "
                         "sine: prescribed c_x on one contact (Fig. 6.6); modal: modal and linear stability analysis; "
                         "bench: where the time goes (Python loop, FMU calls, physics)")
    ap.add_argument("--model", default="ecf", choices=MODELS + ("both",),
                    help="contact model (FMU parameter `model`); both = ecf and fastsim side by side [default: ecf]")
    ap.add_argument("--v-mps", type=_positive("--v-mps"), default=5.0, help="vehicle speed, m/s [default: 5]")
    ap.add_argument("--out", type=Path, default=Path("out"), help="output directory [default: out]")
    ap.add_argument("--json", action="store_true", help="print the JSON summary to stdout")
    ap.add_argument("--h-ms", type=_positive("--h-ms"), default=0.25,
                    help="communication step = integrator step, ms (converged range 0.125-0.5) [default: 0.25]")
    ap.add_argument("--t-end", type=_positive("--t-end"), default=None,
                    help="simulated time, s [default: step 2.5, ramp 8, sine 10 periods]")
    ap.add_argument("--grid", type=_grid, default=None,
                    help="bristle grid NXxNY of the contact FMU (e.g. 16x9) [default: 16x9]")
    ap.add_argument("--fmu-default-grid", action="store_true", help="use the FMU's own default grid instead of 16x9")
    ap.add_argument("--contact", choices=("auto", "fmu", "curve"), default="auto",
                    help="fmu: contact FMU; curve: steady-curve stand-in from `ecf curve` (no contact dynamics); "
                         "auto: FMU if found [default: auto]")
    ap.add_argument("--fmu", default=None, help="path of the contact FMU [default: $ECF_FMU_PATH, $ECF_CONTACT_FMU or dist/ecf_contact.fmu]")
    ap.add_argument("--no-transient", action="store_true", help="quasi-steady contact (FMU parameter transient = false)")
    ap.add_argument("--serial", action="store_true", help="step the two contacts one after the other (no threads)")
    ap.add_argument("--preset", default=None, help="contact preset (FMU parameter `preset`)")
    ap.add_argument("--fmu-param", type=_kv, action="append", default=[], metavar="NAME=VALUE",
                    help="further FMU parameter, e.g. mu=0.3 (repeatable)")
    ap.add_argument("--params", type=Path, default=None,
                    help="drive-train parameter file (TOML) [default: drivetrain_demo/data/locomotive.toml]")
    ap.add_argument("--set", type=_kv, action="append", default=[], metavar="NAME=VALUE",
                    help="override a drive-train/controller value, e.g. C_L=1.0e7 (SI units as in the file)")
    ap.add_argument("--cx", type=float, default=None,
                    help="step: desired creepage after the step; modal: creepage of the operating point [default: 0.15]")
    ap.add_argument("--sine", type=float, nargs=3, metavar=("CM", "CA", "F0_HZ"), default=None,
                    help="sine: mean, amplitude (dimensionless) and frequency (Hz) [default: 0.12 0.10 53]")
    ap.add_argument("--quiet", action="store_true", help="no progress output")
    return ap


def apply_overrides(p, sets):
    dt_fields = set(p.drivetrain.__dataclass_fields__)
    ct_fields = set(p.controller.__dataclass_fields__)
    for k, v in sets:
        try:
            x = float(v)
        except ValueError:
            raise SystemExit(f"error: --set {k}={v}: value is not a number") from None
        if k in dt_fields:
            p = p.with_drivetrain(**{k: x})
        elif k in ct_fields:
            p = p.with_controller(**{k: x})
        else:
            raise SystemExit(f"error: --set {k}: unknown (drive-train: {', '.join(sorted(dt_fields))}; "
                             f"controller: {', '.join(sorted(ct_fields))})")
    return p


def main(argv=None):
    a = build_parser().parse_args(argv)
    p = apply_overrides(params_mod.load(a.params), a.set)
    grid = None if a.fmu_default_grid else (a.grid or (16, 9))
    if a.cx is not None and not (0.0 <= a.cx <= 1.0):
        raise SystemExit(f"error: --cx {a.cx}: creepage must be in [0, 1] (dimensionless, 0.15 = 15 %)")
    models = ("ecf", "fastsim") if a.model == "both" else (a.model,)
    if a.scenario == "modal":
        return modal(a, p, models, grid)
    if a.scenario == "bench":
        from . import bench, contact
        path = contact.find_fmu(a.fmu)
        if path is None:
            raise SystemExit("error: bench needs the contact FMU (scripts/build-fmu.sh or --fmu)")
        b = bench.run_bench(p, path, grid=grid or (80, 21), h=a.h_ms * 1e-3, v=a.v_mps,
                            model=models[0])
        print(json.dumps(b, indent=2) if a.json else bench.format_bench(b))
        return 0
    summaries, runs = {}, []
    for m in models:
        cfg = scenarios.RunConfig(
            scenario=a.scenario, model=m, v=a.v_mps, out=a.out, h=a.h_ms * 1e-3, t_end=a.t_end, grid=grid,
            contact=a.contact, fmu=a.fmu, transient=not a.no_transient, parallel=not a.serial, preset=a.preset,
            fmu_params=dict(a.fmu_param), progress=not a.quiet)
        if a.cx is not None:
            cfg.c_target = a.cx
        if a.sine:
            cfg.sine = {"cm": a.sine[0], "ca": a.sine[1], "f0": a.sine[2]}
        s, r = scenarios.run(cfg, p)
        summaries[m] = s
        runs.append((s, r))
    if len(runs) > 1:
        from . import plots
        path = plots.plot_compare(Path(a.out) / f"{a.scenario}_compare_v{a.v_mps:g}.png", runs)
        print(f"comparison plot: {path}", file=sys.stderr)
    if a.json:
        print(json.dumps(summaries if len(models) > 1 else summaries[models[0]], indent=2))
    return 0


def modal(a, p, models, grid):
    print("free drive-train (no contact, no damping, no controller): natural frequencies and mode shapes")
    print("  shapes on the axle side (motor angle / j_G), |amplitude| max = 1, phase relative to wheel L")
    for m in stability.undamped_modes(p):
        print(f"  {m.frequency_hz:8.2f} Hz  {m.description}")
    c = 0.15 if a.cx is None else a.cx
    out = {}
    for model in models:
        cfg = scenarios.RunConfig(scenario="step", model=model, v=a.v_mps, grid=grid, contact=a.contact, fmu=a.fmu,
                                  preset=a.preset, fmu_params=dict(a.fmu_param))
        kind, path = scenarios.resolve_contact(cfg)
        curve = scenarios.SteadyCurve(cfg, p, kind, path)
        res = scenarios.predict(p, a.v_mps, c, curve)
        print(f"\n{model.upper()} ({kind}):")
        print(stability.format_report(res))
        out[model] = res
    if a.json:
        print(json.dumps(scenarios._json_clean(out), indent=2))
    return 0
