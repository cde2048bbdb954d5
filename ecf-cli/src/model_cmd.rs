//! The model commands of `ecf`: `curve`, `step`, `sine`, `field` and `info`, each writing its CSV (or text) into the output buffer.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::Args;
use creep_core::commands::{self, bad, check_step_count, field_of, rename, ModelSetup};
use creep_core::scheme::{Scheme, SCHEMES};
use creep_core::tolerance;
use creep_core::{CreepError, FieldPoint, Outputs};
use std::io::Write;
use std::path::PathBuf;

/// The `--scheme` values: the rows of the scheme table (`steady`: only the schemes that change
/// a steady state), each with its help line.
fn scheme_parser(steady: bool) -> impl TypedValueParser<Value = Scheme> {
    let values = SCHEMES
        .iter()
        .filter(move |r| r.steady || !steady)
        .map(|r| PossibleValue::new(r.name).help(r.help));
    PossibleValuesParser::new(values).try_map(|s| Scheme::by_name(&s).ok_or("not a scheme"))
}

#[derive(Args, Clone)]
pub(crate) struct TransientArgs {
    /// How a time step advances the bristles: cells (reference), continuous (faster) or
    /// cells-ho (higher-order rules along each move; see docs/model.md sections 3 and 9).
    /// Default: the scheme --tol chooses, else the configuration's (cells-ho for ECF, cells
    /// for FASTSIM, unless --config names another)
    #[arg(long, value_parser = scheme_parser(false))]
    scheme: Option<Scheme>,
}

impl TransientArgs {
    /// The scheme given explicitly, if any.
    fn explicit(&self) -> Option<Scheme> {
        self.scheme
    }
}

#[derive(Args, Clone)]
pub(crate) struct SteadyArgs {
    /// How the steady march integrates a move: cells or cells-ho (higher-order rules along
    /// each move; docs/model.md section 3.3). Default: the scheme --tol chooses among
    /// these two, else the configuration's (cells-ho for ECF, cells for FASTSIM, unless
    /// --config names another)
    #[arg(long, value_parser = scheme_parser(true))]
    scheme: Option<Scheme>,
}

impl SteadyArgs {
    /// The scheme given explicitly, if any.
    fn explicit(&self) -> Option<Scheme> {
        self.scheme
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
    /// to its tolerance, the reference) or predictor (a predictor-corrector in two or three
    /// evaluations of the material law, within 0.025 % of exact on the accuracy benchmark;
    /// docs/model.md section 6). Default: the configuration's (predictor)
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

/// The choice of --tol and the model's warnings on stderr.
fn warn((note, warnings): (Option<String>, Vec<String>)) {
    if let Some(n) = note {
        eprintln!("{n}");
    }
    for msg in warnings {
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
        let s = self.m.setup();
        writeln!(w, "cx,{}", out_header()).map_err(io)?;
        let mut row =
            |_: usize, _: f64, c: f64, o: &Outputs| writeln!(w, "{c},{}", out_row(o)).map_err(io);
        // the higher-order rules change the steady march too
        let cx = || parse_list(&self.cx);
        warn(commands::curve(&s, self.st.explicit(), cx, &mut row)?);
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
        let (m, dt_ms) = (self.m.setup(), self.dt_ms);
        let check = || {
            let at = parse_instants(at)?;
            if !(dt_ms.is_finite() && dt_ms > 0.0) {
                return Err(bad("--dt-ms", dt_ms, "must be finite and > 0 ms"));
            }
            let latest = at.iter().copied().fold(0.0, f64::max);
            check_step_count("--dt-ms", dt_ms, latest / dt_ms)?;
            Ok(at)
        };
        let (prepared, at) = m.prepare(Some(dt_ms * 1e-3), false, self.tr.explicit(), check)?;
        let (mut model, note) = (prepared.model, prepared.note);
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
        warn((note, model.take_warnings()));
        Ok(())
    }

    /// The time series t_s,cx,outputs over `--duration-ms`.
    fn series(&self, w: &mut Vec<u8>) -> Result<(), CreepError> {
        writeln!(w, "t_s,cx,{}", out_header()).map_err(io)?;
        let mut row = |k: usize, t: f64, c: f64, o: &Outputs| {
            if k == 0 {
                writeln!(w, "0,{c},{}", out_row(o)).map_err(io)
            } else {
                writeln!(w, "{t:.8},{c},{}", out_row(o)).map_err(io)
            }
        };
        warn(commands::step_series(
            &self.m.setup(),
            self.tr.explicit(),
            (self.cx_from, self.cx_to),
            self.duration_ms,
            self.dt_ms,
            &mut row,
        )?);
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
        writeln!(w, "t_s,cx,{}", out_header()).map_err(io)?;
        let mut row = |k: usize, t: f64, c: f64, o: &Outputs| {
            if k == 0 {
                writeln!(w, "0,{c},{}", out_row(o)).map_err(io)
            } else {
                writeln!(w, "{t:.8},{c:.8},{}", out_row(o)).map_err(io)
            }
        };
        warn(commands::sine(
            &self.m.setup(),
            self.tr.explicit(),
            (self.cm, self.ca, self.freq_hz),
            (self.cycles, self.steps_per_cycle),
            &mut row,
        )?);
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
        let (f, note, warnings) = commands::field(&self.m.setup(), self.st.explicit(), self.cx)?;
        writeln!(
            w,
            "x_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime"
        )
        .map_err(io)?;
        for p in f {
            writeln!(w, "{:.5},{}", p.x * 1e3, field_values(&p)).map_err(io)?;
        }
        warn((note, warnings));
        Ok(())
    }
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

impl ModelArgs {
    /// The model run's set-up of the flags.
    fn setup(&self) -> ModelSetup {
        ModelSetup {
            model: self.model.clone(),
            preset: self.preset.clone(),
            config: self.config.clone().map(commands::ConfigSource::File),
            mu: self.mu,
            v_mps: self.v_mps,
            fn_kn: self.fn_kn,
            a_mm: self.a_mm,
            b_mm: self.b_mm,
            grid: self.grid.clone(),
            tol: self.tol,
            temperature_solve: self
                .temperature_solve
                .map(crate::TemperatureSolveArg::solve),
            cy: self.cy,
            spin: self.spin,
            t_bulk_c: self.t_bulk_c,
            params: self.params.clone(),
            extra: self.extra.clone(),
        }
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

/// One row of the output columns (see [`out_header`]), checked finite by the run.
fn out_row(o: &Outputs) -> String {
    creep_core::engine::io::csv_outputs()
        .iter()
        .map(|s| format!("{:.*}", s.csv.decimals, (s.get)(o) * s.csv.scale))
        .collect::<Vec<_>>()
        .join(",")
}

/// `ecf info`: the presets, the effects, the Rust effects linked in, and the tables of
/// inputs, outputs and parameters.
pub(crate) fn info(w: &mut Vec<u8>) -> std::io::Result<()> {
    w.write_all(commands::info_text().as_bytes())
}
