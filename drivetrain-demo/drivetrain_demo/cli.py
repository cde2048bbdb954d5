"""Command line: python -m drivetrain_demo SCENARIO --model M [--v-mps V] --out DIR [--json].

SCENARIO: step | ramp | sine | modal | bench.  --model: ecf | fastsim | polach | both (= ecf and
fastsim, plus a side-by-side comparison plot).
    python -m drivetrain_demo sweep SWEEP.toml --out DIR [--scheduler local|serial|tcp://HOST:8786]
    python -m drivetrain_demo regress BASELINE.json [--tolerance-hz 0.5]
Errors of the library (DrivetrainError) become one line `error: ...` on stderr and exit code 2.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import params as params_mod
from . import regress, scenarios, stability
from .errors import DrivetrainError

MODELS = scenarios.MODELS


def _grid(s):
    try:
        nx, ny = (int(x) for x in s.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"grid '{s}': expected NXxNY, e.g. 20x11") from None
    if not (2 <= nx <= 2000 and 1 <= ny <= 1000):
        raise argparse.ArgumentTypeError(f"grid '{s}': need 2 <= NX <= 2000, 1 <= NY <= 1000")
    return nx, ny


def _positive(name, integer=False):
    def f(s):
        try:
            x = int(s) if integer else float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} '{s}' is not {'an integer' if integer else 'a number'}") from None
        if not x > 0 or x != x or x == float("inf"):
            raise argparse.ArgumentTypeError(f"{name} must be > 0 (got {s})")
        return x
    return f


def _kv(s):
    if "=" not in s:
        raise argparse.ArgumentTypeError(f"'{s}': expected NAME=VALUE")
    k, v = s.split("=", 1)
    return k.strip(), v.strip()


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage block): `PROG: error: MESSAGE (see --help)`."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def build_parser():
    ap = _Parser(
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
                    help=f"bristle grid NXxNY of the contact FMU [default: {scenarios.DEFAULT_GRID_TEXT}]")
    ap.add_argument("--fmu-default-grid", action="store_true", help=f"use the FMU's own default grid instead of {scenarios.DEFAULT_GRID_TEXT}")
    ap.add_argument("--contact", choices=("auto", "fmu", "curve"), default="auto",
                    help="fmu: contact FMU; curve: steady-curve stand-in from `ecf curve` (no contact dynamics); "
                         "auto: FMU if found [default: auto]")
    ap.add_argument("--fmu", default=None, help="path of the contact FMU [default: $ECF_FMU_PATH, $ECF_CONTACT_FMU or dist/ecf_contact.fmu]")
    ap.add_argument("--no-transient", action="store_true", help="quasi-steady contact (FMU parameter transient = false)")
    ap.add_argument("--serial", action="store_true", help="step the two contacts one after the other (no threads)")
    ap.add_argument("--preset", default=None, choices=scenarios.CONDITIONS,
                    help="contact condition (FMU parameter `preset` of ECF); FASTSIM gets a friction coefficient "
                         "matched to it (docs/drivetrain.md) [default: the model's own]")
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
    ap.add_argument("--save-every", type=_positive("--save-every", integer=True), default=1, metavar="N",
                    help="write every N-th row of the time-series CSV (and the last) [default: 1, all]")
    ap.add_argument("--save-baseline", type=Path, default=None, metavar="FILE",
                    help="write a regression baseline of the run(s) to FILE (python -m drivetrain_demo regress FILE)")
    ap.add_argument("--quiet", action="store_true", help="no progress output")
    return ap


def build_sweep_parser():
    ap = _Parser(
        prog="python -m drivetrain_demo sweep",
        description="Run every case of a sweep file as a Dask task; write a tidy table (sweep.csv, sweep.parquet), "
                    "traces and a stability map into --out. Re-running skips the cases already done.")
    ap.add_argument("sweep_file", type=Path, metavar="SWEEP.toml", help="sweep file (docs/drivetrain.md, "
                    "example drivetrain-demo/examples/sweep.toml)")
    ap.add_argument("--out", type=Path, required=True, help="output directory (created; reused for resume)")
    ap.add_argument("--scheduler", default="local",
                    help="local: in-process LocalCluster (one worker process per core); serial: no Dask, one case "
                         "after the other; tcp://HOST:8786: an existing dask.distributed scheduler [default: local]")
    ap.add_argument("--workers", type=_positive("--workers", integer=True), default=None,
                    help="worker processes of the LocalCluster [default: all cores]")
    ap.add_argument("--save-every", type=_positive("--save-every", integer=True), default=None, metavar="N",
                    help="write every N-th trace row [default: the sweep file's save_every, else 1]")
    ap.add_argument("--fmu", default=None, help="contact FMU [default: $ECF_FMU_PATH, $ECF_CONTACT_FMU, dist/ecf_contact.fmu]")
    ap.add_argument("--no-plot", action="store_true", help="do not draw stability_map.png")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    return ap


def build_regress_parser():
    ap = _Parser(
        prog="python -m drivetrain_demo regress",
        description="Re-run the scenarios of a baseline (written by --save-baseline) and exit 1 with a readable "
                    "diff when a frequency, the amplitude or a stability verdict moved.")
    ap.add_argument("baseline", type=Path, metavar="BASELINE.json")
    ap.add_argument("--tolerance-hz", type=float, default=0.5, help="allowed change of a frequency, Hz [default: 0.5]")
    ap.add_argument("--tolerance-amplitude", type=float, default=0.1,
                    help="allowed relative change of the oscillation amplitude (0.1 = 10 %%) [default: 0.1]")
    ap.add_argument("--fmu", default=None, help="contact FMU [default: $ECF_FMU_PATH, $ECF_CONTACT_FMU, dist/ecf_contact.fmu]")
    ap.add_argument("--quiet", action="store_true", help="no progress output")
    return ap


def apply_overrides(p, sets):
    """--set NAME=VALUE pairs applied to the parameters (params.with_overrides)."""
    return params_mod.with_overrides(p, sets)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        if argv and argv[0] == "sweep":
            return sweep_main(argv[1:])
        if argv and argv[0] == "regress":
            return regress_main(argv[1:])
        return _main(argv)
    except DrivetrainError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130


def sweep_main(argv):
    a = build_sweep_parser().parse_args(argv)
    from . import sweep
    r = sweep.run_sweep(a.sweep_file, a.out, scheduler=a.scheduler, workers=a.workers, save_every=a.save_every,
                        fmu=a.fmu, progress=not a.quiet, plot=not a.no_plot)
    for f in r["files"]:
        print(f)
    return 0


def regress_main(argv):
    a = build_regress_parser().parse_args(argv)
    ok, report = regress.regress(a.baseline, a.tolerance_hz, a.tolerance_amplitude, fmu=a.fmu,
                                 progress=not a.quiet)
    print(report)
    return 0 if ok else 1


def _main(argv):
    a = build_parser().parse_args(argv)
    p = apply_overrides(params_mod.load(a.params), a.set)
    grid = None if a.fmu_default_grid else (a.grid or scenarios.DEFAULT_GRID)
    if a.cx is not None and not (0.0 <= a.cx <= 1.0):
        raise scenarios.ConfigError(f"--cx {a.cx}: creepage must be in [0, 1] (dimensionless, 0.15 = 15 %)")
    models = ("ecf", "fastsim") if a.model == "both" else (a.model,)
    if a.scenario == "modal":
        return modal(a, p, models, grid)
    if a.scenario == "bench":
        from . import bench, contact
        path = contact.find_fmu(a.fmu)
        if path is None:
            raise scenarios.FMUNotFoundError("bench needs the contact FMU (scripts/build-fmu.sh or --fmu)")
        b = bench.run_bench(p, path, grid=grid or (80, 21), h=a.h_ms * 1e-3, v=a.v_mps,
                            model=models[0])
        print(json.dumps(b, indent=2) if a.json else bench.format_bench(b))
        return 0
    summaries, runs, cfgs = {}, [], []
    for m in models:
        cfg = scenarios.RunConfig(
            scenario=a.scenario, model=m, v=a.v_mps, out=a.out, h=a.h_ms * 1e-3, t_end=a.t_end, grid=grid,
            contact=a.contact, fmu=a.fmu, transient=not a.no_transient, parallel=not a.serial, preset=a.preset,
            fmu_params=dict(a.fmu_param), progress=not a.quiet, overrides=dict(a.set), save_every=a.save_every)
        if a.cx is not None:
            cfg.c_target = a.cx
        if a.sine:
            cfg.sine = {"cm": a.sine[0], "ca": a.sine[1], "f0": a.sine[2]}
        scenarios.validate(cfg)
        cfgs.append(cfg)
    for cfg in cfgs:  # every option checked before the first run starts
        s, r = scenarios.run(cfg, p)
        summaries[cfg.model] = s
        runs.append((s, r))
    if len(runs) > 1:
        from . import io_util, plots
        path = Path(a.out) / f"{a.scenario}_compare_{cfgs[0].condition}_v{a.v_mps:g}.png"
        with io_util.atomic_path(path) as tmp:
            plots.plot_compare(tmp, runs)
        print(f"comparison plot: {path}", file=sys.stderr)
    if a.save_baseline:
        regress.save(a.save_baseline, [regress.entry(c, p, s) for c, (s, _) in zip(cfgs, runs)])
        print(f"baseline: {a.save_baseline}", file=sys.stderr)
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
        cfg.c_target = c
        scenarios.validate(cfg)
        kind, path = scenarios.resolve_contact(cfg)
        curve = scenarios.SteadyCurve(cfg, p, kind, path)
        res = scenarios.predict(p, a.v_mps, c, curve)
        print(f"\n{model.upper()} ({kind}):")
        print(stability.format_report(res))
        out[model] = res
    if a.json:
        print(json.dumps(scenarios._json_clean(out), indent=2))
    return 0
