//! The model commands of `ecf`: `curve`, `step`, `sine`, `field` and `info`, each writing its CSV (or text) into the output buffer.

use clap::{Args, ValueEnum};
use creep_core::engine::Scheme;
use creep_core::tolerance::{self, Filter};
use creep_core::{Config, CreepError, FieldPoint, Geometry, Grid, Inputs, Model, Outputs};
use std::io::Write;
use std::path::PathBuf;

/// How a time step advances the bristles (`creep_core::engine::Scheme`, docs/model.md
/// section 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SchemeArg {
    /// Cell by cell: the first-order reference, independent of the time step within 0.5 %
    Cells,
    /// Continuous sub-steps of up to 8 cells: 2-4x faster on 80x21 at 0.1-1 ms steps, its
    /// dependence on the time step up to about 1 %
    Continuous,
    /// Cell by cell with higher-order rules along each move (docs/model.md section 3.3):
    /// about twice the cost of cells on the same grid, more accurate at equal cost; ECF's
    /// default
    CellsHo,
}

impl SchemeArg {
    /// The engine's scheme of a name (`cells` is [`Scheme::CellsMarch`]).
    fn scheme(self) -> Scheme {
        match self {
            SchemeArg::Cells => Scheme::CellsMarch,
            SchemeArg::Continuous => Scheme::Continuous,
            SchemeArg::CellsHo => Scheme::CellsHigher,
        }
    }
}

#[derive(Args, Clone)]
pub(crate) struct TransientArgs {
    /// How a time step advances the bristles: cells (reference), continuous (faster) or
    /// cells-ho (higher-order rules along each move; see docs/model.md sections 3 and 9).
    /// Default: the scheme --tol chooses, else the configuration's (cells-ho for ECF, cells
    /// for FASTSIM, unless --config names another)
    #[arg(long, value_enum)]
    scheme: Option<SchemeArg>,
}

impl TransientArgs {
    /// The scheme given explicitly, if any.
    fn explicit(&self) -> Option<Scheme> {
        self.scheme.map(SchemeArg::scheme)
    }

    /// Sets the scheme: the explicit one, else the one --tol chose; else the configuration's
    /// stays.
    fn apply(&self, model: &mut Model, chosen: Option<Scheme>) {
        if let Some(s) = self.explicit().or(chosen) {
            model.set_scheme(s);
        }
    }
}

/// The schemes of a steady computation: the steady state is the cells' march, which the
/// higher-order rules change (the continuous scheme's steady state is the cells march).
#[derive(Clone, Copy, Debug, ValueEnum)]
enum SteadySchemeArg {
    /// Cell by cell (the first-order reference; FASTSIM's default)
    Cells,
    /// Cell by cell with the higher-order rules along each move (docs/model.md section 3.3;
    /// ECF's default)
    CellsHo,
}

#[derive(Args, Clone)]
pub(crate) struct SteadyArgs {
    /// How the steady march integrates a move: cells or cells-ho (higher-order rules along
    /// each move; docs/model.md section 3.3). Default: the scheme --tol chooses among
    /// these two, else the configuration's (cells-ho for ECF, cells for FASTSIM, unless
    /// --config names another)
    #[arg(long, value_enum)]
    scheme: Option<SteadySchemeArg>,
}

impl SteadyArgs {
    /// The scheme given explicitly, if any.
    fn explicit(&self) -> Option<Scheme> {
        self.scheme.map(|s| {
            match s {
                SteadySchemeArg::Cells => SchemeArg::Cells,
                SteadySchemeArg::CellsHo => SchemeArg::CellsHo,
            }
            .scheme()
        })
    }

    /// Sets the scheme: the explicit one, else the one --tol chose; else the configuration's
    /// stays.
    fn apply(&self, model: &mut Model, chosen: Option<Scheme>) {
        if let Some(s) = self.explicit().or(chosen) {
            model.set_scheme(s);
        }
    }
}

#[derive(Args, Clone)]
pub(crate) struct ModelArgs {
    /// Model: ecf, fastsim or polach
    #[arg(long, default_value = "ecf")]
    model: String,
    /// Preset: table4.1, dry, wet, dry_sanded, wet_sanded, twin_disc, fastsim, polach
    #[arg(long)]
    preset: Option<String>,
    /// Configuration JSON file ({"model":..., "preset":..., "effects":[...], "params":{...}})
    #[arg(long)]
    config: Option<PathBuf>,
    /// Coulomb friction coefficient (FASTSIM), dimensionless
    #[arg(long)]
    mu: Option<f64>,
    /// Rolling (vehicle) speed, m/s; negative: rolling backwards (creepages over |v|)
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    v_mps: f64,
    /// Normal force, kN (> 0)
    #[arg(
        long = "fn-kN",
        visible_alias = "fn-kn",
        default_value_t = 110.0,
        allow_negative_numbers = true
    )]
    fn_kn: f64,
    /// Semi-axis in rolling direction at this load, mm (with --b-mm)
    #[arg(long)]
    a_mm: Option<f64>,
    /// Lateral semi-axis at this load, mm (with --a-mm)
    #[arg(long)]
    b_mm: Option<f64>,
    /// Bristle grid NXxNY (cells per strip x strips), e.g. 40x21
    #[arg(long)]
    grid: Option<String>,
    /// Relative tolerance on F_x, a fraction (0.01 = 1 %), ECF model only: the grid and
    /// scheme (for curve and field: cells or cells-ho, whose steady marches differ) are the
    /// cheapest in the accuracy benchmark's table whose
    /// largest F_x error over its cases at the nearest tabulated speed not below |--v-mps|
    /// (those of the preset when it is a tabulated one unchanged, else the worst over dry,
    /// table4.1 and wet) meets it (else the cheapest that cannot be ranked below the most
    /// accurate, with a warning); --grid and --scheme override it. The choice is printed on
    /// stderr (docs/fmu.md, "Grid and scheme for a tolerance"). Default: off (the preset's
    /// grid)
    #[arg(long, value_parser = parse_tol)]
    tol: Option<f64>,
    /// How the local temperature of each bristle move is solved: exact (the implicit solve
    /// to its tolerance, the reference) or predictor (a predictor-corrector in two
    /// evaluations of the material law, within 0.02 % of exact on the accuracy benchmark;
    /// docs/model.md section 9). Default: the configuration's
    #[arg(long, value_enum)]
    temperature_solve: Option<crate::TemperatureSolveArg>,
    /// Lateral creepage, dimensionless
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    cy: f64,
    /// Spin creepage, 1/m
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    spin: f64,
    /// Bulk temperature, degC
    #[arg(long, default_value_t = 20.0, allow_hyphen_values = true)]
    t_bulk_c: f64,
    /// Parameter override NAME=VALUE (repeatable; units as in the name, see `ecf info`)
    #[arg(long = "param", value_name = "NAME=VALUE")]
    params: Vec<String>,
    /// Value of a data column read by formula or Rust effects, NAME=VALUE (repeatable)
    #[arg(long = "extra", value_name = "NAME=VALUE")]
    extra: Vec<String>,
}

/// An error writing the output.
pub(crate) fn io(e: std::io::Error) -> CreepError {
    CreepError::Config {
        source_name: "stdout".into(),
        message: e.to_string(),
    }
}

/// The model's warnings on stderr.
fn warn(m: &mut Model) {
    for msg in m.take_warnings() {
        eprintln!("warning: {msg}");
    }
}

/// `ecf curve`: the steady creep curve f(cx).
#[derive(Args, Clone)]
pub(crate) struct CurveArgs {
    #[command(flatten)]
    m: ModelArgs,
    #[command(flatten)]
    st: SteadyArgs,
    /// Creepages: comma separated (0.001,0.01) or start:stop:n (0.001:0.5:50), dimensionless
    #[arg(long, allow_hyphen_values = true)]
    cx: String,
}

impl CurveArgs {
    pub(crate) fn run(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        let m = &self.m;
        let mut cfg = m.config()?;
        let chosen = m.apply_tol(&mut cfg, None, true, self.st.explicit())?;
        let list = parse_list(&self.cx)?;
        let mut model = m.model(&cfg)?;
        // the higher-order rules change the steady march too
        self.st.apply(&mut model, chosen);
        writeln!(w, "cx,{}", out_header()).map_err(io)?;
        for c in list {
            let o = model
                .steady(&m.inputs(c))
                .map_err(|e| rename(e, "cx", "--cx"))?;
            writeln!(w, "{c},{}", out_row(&o)?).map_err(io)?;
        }
        warn(&mut model);
        Ok(())
    }
}

/// `ecf step`: the response to a creepage step, as a time series or as fields at instants.
#[derive(Args, Clone)]
pub(crate) struct StepArgs {
    #[command(flatten)]
    m: ModelArgs,
    #[command(flatten)]
    tr: TransientArgs,
    /// Creepage before the step (steady state at t <= 0), dimensionless
    #[arg(long, allow_hyphen_values = true)]
    cx_from: f64,
    /// Creepage after the step, dimensionless
    #[arg(long, allow_hyphen_values = true)]
    cx_to: f64,
    /// Simulated time after the step, ms
    #[arg(long, default_value_t = 5.0)]
    duration_ms: f64,
    /// Time step, ms
    #[arg(long, default_value_t = 0.01)]
    dt_ms: f64,
    /// Instead of the time series: the fields along y = 0 at these instants after the
    /// step (ms, comma separated, e.g. 0,0.1,0.8; each rounded to a whole time step; the
    /// run ends at the last one, --duration-ms is not used). CSV
    /// t_ms,f,x_mm,x_rail_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime, where
    /// x_rail = x + v t is the position in a frame fixed on the rail (seed Fig. 4.13-4.19)
    #[arg(long, value_name = "T1,T2,...")]
    field_at_ms: Option<String>,
}

impl StepArgs {
    pub(crate) fn run(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        match &self.field_at_ms {
            Some(at) => self.fields(at, w),
            None => self.series(w),
        }
    }

    /// The fields along y = 0 at the instants of `--field-at-ms`.
    fn fields(&self, at: &str, w: &mut Vec<u8>) -> Result<(), CreepError> {
        let (m, dt_ms) = (&self.m, self.dt_ms);
        let mut cfg = m.config()?;
        let at = parse_instants(at)?;
        if !(dt_ms.is_finite() && dt_ms > 0.0) {
            return Err(bad("--dt-ms", dt_ms, "must be finite and > 0 ms"));
        }
        let latest = at.iter().copied().fold(0.0, f64::max);
        check_step_count("--dt-ms", dt_ms, latest / dt_ms)?;
        let chosen = m.apply_tol(&mut cfg, Some(dt_ms * 1e-3), false, self.tr.explicit())?;
        let mut model = m.model(&cfg)?;
        self.tr.apply(&mut model, chosen);
        let mut o = model
            .steady(&m.inputs(self.cx_from))
            .map_err(|e| rename(e, "cx", "--cx-from"))?;
        let inp = m.inputs(self.cx_to);
        inp.validate().map_err(|e| rename(e, "cx", "--cx-to"))?;
        // each instant at the whole time step nearest to it
        let mut want: Vec<(usize, f64)> = at
            .iter()
            .map(|&t| ((t / dt_ms).round() as usize, t))
            .collect();
        want.sort_by_key(|p| p.0);
        let last = want.last().map_or(0, |w| w.0);
        let dt = dt_ms * 1e-3;
        writeln!(
            w,
            "t_ms,f,x_mm,x_rail_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime"
        )
        .map_err(io)?;
        for k in 0..=last {
            if k > 0 {
                o = model.step(dt, &inp)?;
            }
            for &(_, t_req) in want.iter().filter(|p| p.0 == k) {
                let t = k as f64 * dt;
                for p in field_of(&model)? {
                    writeln!(
                        w,
                        "{},{:.8},{:.5},{:.5},{}",
                        t_req,
                        o.f,
                        p.x * 1e3,
                        (p.x + m.v_mps * t) * 1e3,
                        field_values(&p)
                    )
                    .map_err(io)?;
                }
            }
        }
        warn(&mut model);
        Ok(())
    }

    /// The time series t_s,cx,outputs over `--duration-ms`.
    fn series(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        let (m, duration_ms, dt_ms) = (&self.m, self.duration_ms, self.dt_ms);
        let (cx_from, cx_to) = (self.cx_from, self.cx_to);
        let mut cfg = m.config()?;
        if !(duration_ms.is_finite() && duration_ms > 0.0 && duration_ms <= 1e6) {
            return Err(bad(
                "--duration-ms",
                duration_ms,
                "must be within (0, 1e6] ms",
            ));
        }
        if !(dt_ms.is_finite() && dt_ms > 0.0 && dt_ms <= duration_ms) {
            return Err(bad("--dt-ms", dt_ms, "must be > 0 and <= --duration-ms"));
        }
        check_step_count("--dt-ms", dt_ms, duration_ms / dt_ms)?;
        let chosen = m.apply_tol(&mut cfg, Some(dt_ms * 1e-3), false, self.tr.explicit())?;
        let mut model = m.model(&cfg)?;
        self.tr.apply(&mut model, chosen);
        let o = model
            .steady(&m.inputs(cx_from))
            .map_err(|e| rename(e, "cx", "--cx-from"))?;
        writeln!(w, "t_s,cx,{}", out_header()).map_err(io)?;
        writeln!(w, "0,{cx_from},{}", out_row(&o)?).map_err(io)?;
        let n = (duration_ms / dt_ms).round() as usize;
        let dt = dt_ms * 1e-3;
        let inp = m.inputs(cx_to);
        inp.validate().map_err(|e| rename(e, "cx", "--cx-to"))?;
        for k in 1..=n {
            let o = model.step(dt, &inp)?;
            writeln!(w, "{:.8},{cx_to},{}", k as f64 * dt, out_row(&o)?).map_err(io)?;
        }
        warn(&mut model);
        Ok(())
    }
}

/// `ecf sine`: periodic creepage cx = cm + ca sin(2 pi f t).
#[derive(Args, Clone)]
pub(crate) struct SineArgs {
    #[command(flatten)]
    m: ModelArgs,
    #[command(flatten)]
    tr: TransientArgs,
    /// Mean creepage c_m, dimensionless
    #[arg(long, allow_hyphen_values = true)]
    cm: f64,
    /// Amplitude c_A, dimensionless
    #[arg(long)]
    ca: f64,
    /// Frequency f_0, Hz
    #[arg(long)]
    freq_hz: f64,
    /// Number of periods
    #[arg(long, default_value_t = 3)]
    cycles: u32,
    /// Time steps per period
    #[arg(long, default_value_t = 200)]
    steps_per_cycle: u32,
}

impl SineArgs {
    pub(crate) fn run(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        let (m, cm, ca, freq_hz) = (&self.m, self.cm, self.ca, self.freq_hz);
        let (cycles, steps_per_cycle) = (self.cycles, self.steps_per_cycle);
        let mut cfg = m.config()?;
        if !(freq_hz.is_finite() && freq_hz > 0.0) {
            return Err(bad("--freq-hz", freq_hz, "must be finite and > 0 Hz"));
        }
        if !(ca.is_finite() && ca >= 0.0) {
            return Err(bad("--ca", ca, "must be finite and >= 0"));
        }
        if cycles == 0 || steps_per_cycle < 4 {
            return Err(bad(
                "--cycles/--steps-per-cycle",
                cycles as f64,
                "need >= 1 cycle and >= 4 steps per cycle",
            ));
        }
        check_step_count(
            "--cycles/--steps-per-cycle",
            cycles as f64,
            cycles as f64 * steps_per_cycle as f64,
        )?;
        let dt = 1.0 / (freq_hz * steps_per_cycle as f64);
        let chosen = m.apply_tol(&mut cfg, Some(dt), false, self.tr.explicit())?;
        let mut model = m.model(&cfg)?;
        self.tr.apply(&mut model, chosen);
        let o = model
            .steady(&m.inputs(cm))
            .map_err(|e| rename(e, "cx", "--cm"))?;
        writeln!(w, "t_s,cx,{}", out_header()).map_err(io)?;
        writeln!(w, "0,{cm},{}", out_row(&o)?).map_err(io)?;
        for k in 1..=(cycles * steps_per_cycle) {
            let t = k as f64 * dt;
            // creepage held constant over the step at its end value (Eq. 4.15)
            let c = cm + ca * (2.0 * std::f64::consts::PI * freq_hz * t).sin();
            let o = model
                .step(dt, &m.inputs(c))
                .map_err(|e| rename(e, "cx", "--cm/--ca"))?;
            writeln!(w, "{t:.8},{c:.8},{}", out_row(&o)?).map_err(io)?;
        }
        warn(&mut model);
        Ok(())
    }
}

/// `ecf field`: the fields along y = 0 at steady state.
#[derive(Args, Clone)]
pub(crate) struct FieldArgs {
    #[command(flatten)]
    m: ModelArgs,
    #[command(flatten)]
    st: SteadyArgs,
    /// Creepage, dimensionless
    #[arg(long, allow_hyphen_values = true)]
    cx: f64,
}

impl FieldArgs {
    pub(crate) fn run(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        let m = &self.m;
        let mut cfg = m.config()?;
        let chosen = m.apply_tol(&mut cfg, None, true, self.st.explicit())?;
        let mut model = m.model(&cfg)?;
        self.st.apply(&mut model, chosen);
        model
            .steady(&m.inputs(self.cx))
            .map_err(|e| rename(e, "cx", "--cx"))?;
        let f = field_of(&model)?;
        writeln!(
            w,
            "x_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime"
        )
        .map_err(io)?;
        for p in f {
            writeln!(w, "{:.5},{}", p.x * 1e3, field_values(&p)).map_err(io)?;
        }
        warn(&mut model);
        Ok(())
    }
}

/// The fields along y = 0 of a bristle model (an error for Polach).
fn field_of(model: &Model) -> Result<Vec<FieldPoint>, CreepError> {
    model.field_y0().ok_or_else(|| CreepError::Config {
        source_name: "--model".into(),
        message: "fields exist for the bristle models (ecf, fastsim), not for polach".into(),
    })
}

/// The columns tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime of a field point (the
/// same in `ecf field` and `ecf step --field-at-ms`); a strength without limit is -1.
fn field_values(p: &FieldPoint) -> String {
    let finite_or_minus_one = |x: f64| if x.is_finite() { x } else { -1.0 };
    format!(
        "{:.1},{:.1},{:.1},{:.1},{:.1},{:.3},{}",
        p.tau,
        p.tau_x,
        finite_or_minus_one(p.tau_c1),
        finite_or_minus_one(p.tau_c2),
        p.p,
        p.t,
        p.regime
    )
}

/// The instants of `--field-at-ms`: a comma-separated list of finite times >= 0 ms.
fn parse_instants(s: &str) -> Result<Vec<f64>, CreepError> {
    let at = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite() && *t >= 0.0 && *t <= 1e6)
                .ok_or_else(|| CreepError::Config {
                    source_name: "--field-at-ms".into(),
                    message: format!("'{}': expected a time in ms within [0, 1e6]", x.trim()),
                })
        })
        .collect::<Result<Vec<f64>, CreepError>>()?;
    if at.is_empty() {
        return Err(CreepError::Config {
            source_name: "--field-at-ms".into(),
            message: "give one or more instants in ms".into(),
        });
    }
    Ok(at)
}

/// The value of --tol: a finite relative tolerance > 0 (a fraction).
fn parse_tol(s: &str) -> Result<f64, String> {
    let x: f64 = s.trim().parse().map_err(|_| {
        format!("'{s}' is not a number; give a relative tolerance, e.g. 0.01 for 1 %")
    })?;
    tolerance::check_tol(x, "--tol").map_err(|e| e.to_string())?;
    Ok(x)
}

fn bad(field: &str, value: f64, expected: &str) -> CreepError {
    CreepError::OutOfRange {
        field: field.into(),
        value,
        expected: expected.into(),
    }
}

impl ModelArgs {
    /// The configuration of the model flags (a preset, a file or a model's defaults, with
    /// the flags' overrides), checked.
    fn config(&self) -> Result<Config, CreepError> {
        let mut cfg = match (&self.config, &self.preset) {
            (Some(_), Some(_)) => {
                return Err(CreepError::Config {
                    source_name: "--config/--preset".into(),
                    message: "give either --preset or --config, not both".into(),
                })
            }
            (Some(path), None) => Config::from_file(path)?,
            (None, Some(p)) => Config::preset(p)?,
            (None, None) => Config::for_model(&self.model)?,
        };
        if self.config.is_none()
            && self.preset.is_some()
            && cfg.model.name() != self.model
            && self.model != "ecf"
        {
            return Err(CreepError::Config {
                source_name: "--model".into(),
                message: format!(
                    "preset '{}' is a {} configuration, not {}",
                    cfg.preset,
                    cfg.model.name(),
                    self.model
                ),
            });
        }
        if let Some(mu) = self.mu {
            cfg.params
                .set(creep_core::params::P::Mu, mu)
                .map_err(|e| rename(e, "mu", "--mu"))?;
        }
        for p in &self.params {
            let (n, v) = p.split_once('=').ok_or_else(|| CreepError::Config {
                source_name: "--param".into(),
                message: format!("'{p}': expected NAME=VALUE"),
            })?;
            let x: f64 = if v == "inf" {
                f64::INFINITY
            } else {
                v.parse().map_err(|_| CreepError::Config {
                    source_name: "--param".into(),
                    message: format!("'{p}': value is not a number"),
                })?
            };
            cfg.params.set_by_name(n, x)?;
        }
        if let Some(g) = &self.grid {
            cfg.grid = Grid::parse(g)?;
        }
        if let Some(s) = self.temperature_solve {
            cfg.temperature_solve = s.solve();
        }
        if !(self.v_mps.is_finite() && self.v_mps.abs() <= 1000.0) {
            return Err(bad("--v-mps", self.v_mps, "must be finite, within [-1000, 1000] m/s (negative: rolling backwards; standstill v = 0: forces from creepage alone, no frictional heat)"));
        }
        if !(self.fn_kn.is_finite() && self.fn_kn > 0.0) {
            return Err(bad("--fn-kN", self.fn_kn, "must be finite and > 0 kN"));
        }
        match (self.a_mm, self.b_mm) {
            (Some(a), Some(b)) => {
                if !(a.is_finite() && a > 0.0) {
                    return Err(bad("--a-mm", a, "must be finite and > 0 mm"));
                }
                if !(b.is_finite() && b > 0.0) {
                    return Err(bad("--b-mm", b, "must be finite and > 0 mm"));
                }
                cfg.geometry = Geometry::SemiAxes {
                    a: a * 1e-3,
                    b: b * 1e-3,
                    fn_ref: self.fn_kn * 1e3,
                };
            }
            (None, None) => {}
            _ => {
                return Err(CreepError::Config {
                    source_name: "--a-mm/--b-mm".into(),
                    message: "give both semi-axes or neither".into(),
                })
            }
        }
        // the contact patch at this load: a geometry whose semi-axes or peak pressure the
        // model cannot use (e.g. --a-mm 1e300: NaN forces; 1e-300: infinite p0) is refused
        // here, naming the flags, not turned into a table of NaN
        // (at or below the lift-off load the engine returns zero forces without a patch)
        if self.fn_kn * 1e3 > creep_core::engine::F_LIFT_OFF {
            creep_core::engine::patch_for(&cfg, self.fn_kn * 1e3).map_err(|e| {
                let flags = if self.a_mm.is_some() {
                    "--a-mm/--b-mm with --fn-kN"
                } else {
                    "the geometry of the preset or --config with --fn-kN"
                };
                CreepError::Config {
                    source_name: flags.into(),
                    message: e.to_string(),
                }
            })?;
        }
        Ok(cfg)
    }

    /// With --tol: sets the grid of `cfg` chosen from the accuracy table and returns the
    /// chosen scheme (None without --tol). `dt`: the time step (s) of a transient command;
    /// `steady`: a steady command (curve, field: the rows of the schemes whose steady march
    /// they are, cells and cells-ho); `explicit_scheme`: the explicit --scheme, if any. An
    /// explicit --grid or --scheme (else the configuration's scheme other than cells, as in
    /// the FMU) restricts the choice to the table's rows with them; a
    /// --grid not in the table is used as given, with a note that its error is not
    /// tabulated. Prints the choice on stderr.
    fn apply_tol(
        &self,
        cfg: &mut Config,
        dt: Option<f64>,
        steady: bool,
        explicit_scheme: Option<Scheme>,
    ) -> Result<Option<Scheme>, CreepError> {
        let Some(tol) = self.tol else {
            return Ok(None);
        };
        if cfg.model != creep_core::ModelKind::Ecf {
            return Err(CreepError::Config {
                source_name: "--tol".into(),
                message: format!(
                    "the accuracy table is measured for the ECF model, not {}: give --grid instead",
                    cfg.model.name()
                ),
            });
        }
        let grid = self.grid.as_ref().map(|_| cfg.grid);
        // the explicit --scheme, else the configuration's (as the FMU's rel_tol)
        let file_scheme =
            tolerance::restricting_scheme(cfg, steady).filter(|_| explicit_scheme.is_none());
        let scheme = explicit_scheme.or(file_scheme);
        let filter = Filter {
            preset: tolerance::scope_of(cfg),
            nx: grid.map(|g| g.nx),
            ny: grid.map(|g| g.ny),
            scheme,
            steady,
        };
        let dt = dt.filter(|d| d.is_finite() && *d > 0.0);
        match tolerance::choose(tol, self.v_mps, dt, filter) {
            Ok(c) => {
                cfg.grid = Grid { nx: c.nx, ny: c.ny };
                let what = if steady {
                    " (steady: cells or cells-ho)"
                } else {
                    ""
                };
                let given = if grid.is_some() || explicit_scheme.is_some() {
                    " (within the explicit --grid/--scheme)".to_string()
                } else if let Some(s) = file_scheme {
                    format!(" (within the configuration's scheme {})", s.name())
                } else {
                    String::new()
                };
                let level = if c.met { "note" } else { "warning" };
                eprintln!("{level}: --tol {tol}{what}{given}: {}", c.message());
                Ok(Some(c.scheme))
            }
            Err(CreepError::Config { .. }) if grid.is_some() || scheme.is_some() => {
                let with = match (explicit_scheme, file_scheme) {
                    (Some(s), _) => format!(" and --scheme {}", s.name()),
                    (None, Some(s)) => format!(" and the configuration's scheme {}", s.name()),
                    (None, None) => String::new(),
                };
                eprintln!(
                    "note: --tol {tol}: the accuracy table has no row with the explicit --grid {}x{}{with}: its error is not measured; running with the explicit settings",
                    cfg.grid.nx,
                    cfg.grid.ny,
                );
                Ok(scheme)
            }
            Err(e) => Err(e),
        }
    }

    /// A model with the extra column values set.
    fn model(&self, cfg: &Config) -> Result<Model, CreepError> {
        let mut m = Model::new(cfg)?;
        let mut ex = Vec::new();
        for e in &self.extra {
            let (n, v) = e.split_once('=').ok_or_else(|| CreepError::Config {
                source_name: "--extra".into(),
                message: format!("'{e}': expected NAME=VALUE"),
            })?;
            let x: f64 = v.parse().map_err(|_| CreepError::Config {
                source_name: "--extra".into(),
                message: format!("'{e}': value is not a number"),
            })?;
            if !x.is_finite() {
                return Err(CreepError::Config {
                    source_name: "--extra".into(),
                    message: format!("'{e}': the value must be a finite number"),
                });
            }
            ex.push((n.to_string(), x));
        }
        m.set_extra(&ex)?;
        Ok(m)
    }

    fn inputs(&self, cx: f64) -> Inputs {
        Inputs {
            cx,
            cy: self.cy,
            spin: self.spin,
            v: self.v_mps,
            fn_n: self.fn_kn * 1e3,
            t_bulk: self.t_bulk_c,
        }
    }
}

/// Most time steps a command takes (10 million: hours of computing on a small grid, and a
/// table of about 2 GB).
const MAX_STEPS: f64 = 1e7;

/// Refuses a run of `steps` time steps beyond [`MAX_STEPS`] (e.g. --dt-ms 1e-300 asked for
/// 5e300 steps and ran forever), naming `flag` and its `value`.
fn check_step_count(flag: &str, value: f64, steps: f64) -> Result<(), CreepError> {
    if steps <= MAX_STEPS {
        Ok(())
    } else {
        Err(bad(
            flag,
            value,
            &format!("gives {steps:.3e} time steps; at most {MAX_STEPS:e}"),
        ))
    }
}

/// The error with the input's name `field` replaced by the flag the user wrote; other
/// errors (another input, a geometry, a formula) keep their names.
fn rename(e: CreepError, field: &str, flag: &str) -> CreepError {
    match e {
        CreepError::OutOfRange {
            field: f,
            value,
            expected,
        } if f == field => CreepError::OutOfRange {
            field: flag.into(),
            value,
            expected,
        },
        other => other,
    }
}

fn parse_list(s: &str) -> Result<Vec<f64>, CreepError> {
    let err = |m: String| CreepError::Config {
        source_name: "--cx".into(),
        message: m,
    };
    let num = |t: &str| -> Result<f64, CreepError> {
        let x: f64 = t
            .trim()
            .parse()
            .map_err(|_| err(format!("'{t}' is not a number")))?;
        if !x.is_finite() {
            return Err(err(format!("'{t}' is not finite")));
        }
        Ok(x)
    };
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() == 3 {
        let (a, b) = (num(parts[0])?, num(parts[1])?);
        let n: usize = parts[2]
            .trim()
            .parse()
            .map_err(|_| err(format!("'{}' is not a count", parts[2])))?;
        if !(1..=100_000).contains(&n) {
            return Err(err(format!("count {n} must be within [1, 100000]")));
        }
        if n == 1 {
            return Ok(vec![a]);
        }
        return Ok((0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect());
    }
    if parts.len() != 1 {
        return Err(err(format!(
            "'{s}': expected a comma separated list or start:stop:n"
        )));
    }
    s.split(',').map(num).collect()
}

/// The header of the output columns: creep-core's `OUTPUTS` in their CSV order.
fn out_header() -> String {
    creep_core::engine::io::csv_outputs()
        .iter()
        .map(|s| s.csv.header)
        .collect::<Vec<_>>()
        .join(",")
}

/// One row of the output columns (see [`out_header`]); Err where one is not finite (NaN or
/// inf), naming them: no table of NaN with exit status 0.
fn out_row(o: &Outputs) -> Result<String, CreepError> {
    let cols = creep_core::engine::io::csv_outputs();
    let bad: Vec<(&str, f64)> = cols
        .iter()
        .map(|s| (s.csv.header, (s.get)(o)))
        .filter(|(_, x)| !x.is_finite())
        .collect();
    if let Some(&(name, value)) = bad.first() {
        let all: Vec<String> = bad.iter().map(|(n, x)| format!("{n} = {x}")).collect();
        return Err(CreepError::OutOfRange {
            field: format!("output {name}"),
            value,
            expected: format!(
                "the model's outputs are not finite ({}) at the inputs given: they lie outside the range where the model is defined",
                all.join(", ")
            ),
        });
    }
    Ok(cols
        .iter()
        .map(|s| format!("{:.*}", s.csv.decimals, (s.get)(o) * s.csv.scale))
        .collect::<Vec<_>>()
        .join(","))
}

/// `ecf info`: the presets, the effects, the Rust effects linked in, and the tables of
/// inputs, outputs and parameters.
pub(crate) fn info(w: &mut Vec<u8>) -> std::io::Result<()> {
    writeln!(
        w,
        "presets: {}",
        creep_core::config::PRESETS
            .iter()
            .map(|p| p.0)
            .collect::<Vec<_>>()
            .join(", ")
    )?;
    writeln!(w, "\neffects:")?;
    for e in creep_core::effects::CATALOGUE {
        writeln!(w, "  {}: {}", e.name, e.description)?;
    }
    writeln!(w, "\ncustom effects written in Rust (\"custom_effects\": [{{\"name\": ..., \"params\": {{...}}}}]):")?;
    for e in creep_core::custom::catalogue() {
        writeln!(
            w,
            "  {} (scales {}): {}",
            e.name(),
            e.target().name(),
            e.description()
        )?;
        for (n, d, lo, hi, m) in e.params() {
            writeln!(w, "    {n}: default {d}, bounds [{lo}, {hi}], {m}")?;
        }
    }
    writeln!(w, "\ninputs (name, unit, default, range, meaning):")?;
    for s in creep_core::engine::io::INPUTS {
        writeln!(
            w,
            "  {:<22} {:<9} {:>10} [{}, {}]  {}",
            s.name, s.unit, s.default, s.min, s.max, s.description
        )?;
    }
    writeln!(w, "\noutputs (name, unit, meaning):")?;
    for s in creep_core::engine::io::OUTPUTS {
        writeln!(w, "  {:<22} {:<9} {}", s.name, s.unit, s.description)?;
    }
    writeln!(w, "\nparameters (name, unit, default, bounds, meaning):")?;
    for s in creep_core::params::SPECS {
        writeln!(
            w,
            "  {:<22} {:<9} {:>10} [{}, {}]  {} (effect {})",
            s.name, s.unit, s.default, s.min, s.max, s.description, s.effect
        )?;
    }
    Ok(())
}
