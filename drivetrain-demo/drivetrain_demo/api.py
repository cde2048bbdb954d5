"""Public Python API: studies as scripts.

    from drivetrain_demo import simulate, modal
    r = simulate("step", contact="ecf", preset="wet", v_mps=10, overrides={"C_L": 1.0e7})
    print(r.dominant_frequency_hz, r.oscillation_amplitude, r.predicted_unstable)
    m = modal(contact="ecf", v_mps=5, cx=0.15)
    print(m.predicted_frequency_hz, m.predicted_damping_ratio)

Units: speeds m/s, times s (h in ms where the name says so), creepages dimensionless
(0.15 = 15 %), normal load N, frequencies Hz. Bad input raises ConfigError (a ValueError), a
missing FMU FMUNotFoundError, an FMU failure FMUError; all derive from DrivetrainError.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import contact as contact_mod
from . import params as params_mod
from . import scenarios, stability
from .errors import ConfigError
from .params import Params


@dataclass
class Result:
    """Outcome of one simulated scenario.

    summary: the JSON summary (every key documented in docs/drivetrain.md, with `provenance`);
    traces: time series, column name -> numpy array (names carry units: t_s, Fx_L_N, ...);
    files: written files (empty when `out` was None)."""

    summary: dict
    traces: dict = field(repr=False)
    files: list = field(default_factory=list)

    @property
    def dominant_frequency_hz(self) -> float:
        """Dominant frequency of c_x,L over the settled window, Hz (meaningful when sustained_oscillation)."""
        return self.summary["dominant_frequency_hz"]

    @property
    def predicted_frequency_hz(self) -> float:
        """Frequency of the least damped torsional mode of the linear analysis, Hz."""
        return self.summary["predicted_frequency_hz"]

    @property
    def predicted_damping_ratio(self) -> float:
        """Damping ratio of that mode (< 0: unstable), dimensionless."""
        return self.summary["predicted_damping_ratio"]

    @property
    def predicted_unstable(self) -> bool:
        return self.summary["predicted_unstable"]

    @property
    def oscillation_amplitude(self) -> float:
        """Peak-to-peak of c_x,L over the last 0.5 s, dimensionless (0.28 = 28 % creepage)."""
        return self.summary["oscillation_amplitude"]

    @property
    def sustained_oscillation(self) -> bool:
        return self.summary.get("sustained_oscillation")

    @property
    def real_time_factor(self) -> float:
        """Wall-clock time of the co-simulation loop / simulated time (< 1: faster than real time)."""
        return self.summary["real_time_factor"]


@dataclass
class ModalResult:
    """Free drive-train modes and the linear stability analysis (seed Eq. 6.4) at one operating point.

    undamped_modes: list of stability.Mode (no contact, no damping, no controller);
    linear_analysis: dict of stability.analyse (modes with contact damping and controller,
    predicted_frequency_hz, predicted_damping_ratio, predicted_unstable, ...)."""

    undamped_modes: list
    linear_analysis: dict
    contact_kind: str
    provenance: dict

    @property
    def predicted_frequency_hz(self) -> float:
        return self.linear_analysis["predicted_frequency_hz"]

    @property
    def predicted_damping_ratio(self) -> float:
        return self.linear_analysis["predicted_damping_ratio"]

    @property
    def predicted_unstable(self) -> bool:
        return self.linear_analysis["predicted_unstable"]


def load_params(params=None, overrides=None) -> Params:
    """Params from a Params object, a parameter-file path or None (the shipped locomotive.toml),
    with `overrides` ({name: value} of [drivetrain], [controller] or [contact], SI units) applied."""
    if isinstance(params, Params):
        p = params
    else:
        p = params_mod.load(params)
    return params_mod.with_overrides(p, overrides or {})


def _grid(grid):
    if grid is None or grid == "fmu-default":
        return None
    if isinstance(grid, str):
        try:
            nx, ny = (int(x) for x in grid.lower().split("x"))
        except ValueError:
            raise ConfigError(f"grid {grid!r}: expected NXxNY, e.g. 14x7") from None
        return nx, ny
    return tuple(int(x) for x in grid)


def run_config(scenario="step", contact="ecf", *, preset=None, v_mps=5.0, t_end_s=None, h_ms=0.25, grid=scenarios.DEFAULT_GRID,
               fmu=None, fmu_params=None, transient=True, cx=None, sine=None, out=None, save_every=1,
               progress=False, contact_threads=True, contact_kind="fmu", overrides=None) -> scenarios.RunConfig:
    """The scenarios.RunConfig for the arguments of `simulate` (validated)."""
    cfg = scenarios.RunConfig(
        scenario=scenario, model=contact, v=float(v_mps), out=Path(out) if out else Path("out"), h=float(h_ms) * 1e-3,
        t_end=t_end_s, grid=_grid(grid), contact=contact_kind, fmu=str(fmu) if fmu else None, transient=transient,
        parallel=contact_threads, preset=preset, fmu_params=dict(fmu_params or {}), progress=progress,
        overrides=dict(overrides or {}), save_every=int(save_every))
    if cx is not None:
        cfg.c_target = float(cx)
    if sine is not None:
        cfg.sine = {"cm": float(sine[0]), "ca": float(sine[1]), "f0": float(sine[2])} if not isinstance(sine, dict) \
            else {k: float(sine[k]) for k in ("cm", "ca", "f0")}
    scenarios.validate(cfg)
    return cfg


def simulate(scenario: str = "step", contact: str = "ecf", *, params=None, overrides=None, preset=None,
             v_mps: float = 5.0, t_end_s: float | None = None, h_ms: float = 0.25, grid=scenarios.DEFAULT_GRID, fmu=None,
             fmu_params=None, transient: bool = True, cx: float | None = None, sine=None, out=None,
             save_every: int = 1, plot: bool = False, progress: bool = False, contact_threads: bool = True,
             contact_kind: str = "fmu") -> Result:
    """Runs one drive-train scenario with one contact model and analyses it.

    scenario: "step" (desired creepage 0 -> cx, default 15 %), "ramp" (0 -> 50 % -> 0 in 8 s) or
      "sine" (prescribed c_x = cm + ca sin(2 pi f0 t) on one contact, `sine=(cm, ca, f0_Hz)`);
    contact: contact model, "ecf", "fastsim" or "polach" (FMU parameter `model`);
    params: Params, a parameter-file path, or None (drivetrain_demo/data/locomotive.toml);
    overrides: {name: value} replacing drive-train/controller/contact values (SI), like --set;
    preset: contact condition (scenarios.CONDITIONS); FASTSIM gets a condition-matched mu;
    v_mps: vehicle speed, m/s; t_end_s: simulated time, s (None: scenario default; too short raises);
    h_ms: communication step, ms; grid: bristle grid (nx, ny) or "14x7" (default scenarios.DEFAULT_GRID), None for the FMU's own;
    fmu: FMU path (None: $ECF_FMU_PATH, $ECF_CONTACT_FMU, dist/ecf_contact.fmu);
    fmu_params: further FMU parameters {name: value}; transient: transient contact model;
    out: directory for CSV/JSON (and PNG when plot) files, None writes nothing;
    save_every: write every N-th trace row; contact_threads: step the two contacts in two threads;
    contact_kind: "fmu", "curve" (steady-curve stand-in, needs the ecf CLI) or "auto".

    Returns a Result; raises ConfigError / FMUNotFoundError / FMUError (all DrivetrainError)."""
    p = load_params(params, overrides)
    cfg = run_config(scenario, contact, preset=preset, v_mps=v_mps, t_end_s=t_end_s, h_ms=h_ms, grid=grid, fmu=fmu,
                     fmu_params=fmu_params, transient=transient, cx=cx, sine=sine, out=out, save_every=save_every,
                     progress=progress, contact_threads=contact_threads, contact_kind=contact_kind,
                     overrides=overrides)
    summary, results = scenarios.run(cfg, p, write=out is not None, plot=plot and out is not None)
    traces = {k: np.asarray(v) for k, v in results["res"].items()}
    return Result(summary, traces, [Path(f) for f in summary.get("files", [])])


def modal(contact: str = "ecf", *, params=None, overrides=None, preset=None, v_mps: float = 5.0, cx: float = 0.15,
          grid=scenarios.DEFAULT_GRID, fmu=None, fmu_params=None, contact_kind: str = "fmu") -> ModalResult:
    """Modal analysis of the free drive-train and linear stability (seed Eq. 6.4) at speed v_mps
    (m/s) and creepage cx (dimensionless) on both wheels, the contact linearized along the steady
    curve of `contact` (model) under `preset`. Arguments as for `simulate`."""
    p = load_params(params, overrides)
    cfg = run_config("step", contact, preset=preset, v_mps=v_mps, grid=grid, fmu=fmu, fmu_params=fmu_params, cx=cx,
                     contact_kind=contact_kind, overrides=overrides)
    kind, path = scenarios.resolve_contact(cfg)
    curve = scenarios.SteadyCurve(cfg, p, kind, path)
    lin = scenarios._json_clean(scenarios.predict(p, cfg.v, cfg.c_target, curve))
    prov = scenarios.provenance(cfg, p, kind, path)
    return ModalResult(stability.undamped_modes(p), lin, kind, prov)


def find_fmu(path=None):
    """The contact FMU path: `path`, $ECF_FMU_PATH, $ECF_CONTACT_FMU or dist/ecf_contact.fmu (None if absent)."""
    return contact_mod.find_fmu(path)
