//! The model runs of the command line and the Python package: a configuration from a preset or file with overrides, checked inputs, and the curve, step, sine and field runs that both print or return.
//!
//! The names in error messages are the command line's flags (`--v-mps`, `--cx-from`); the
//! Python package passes the same messages on.

use crate::config::{Config, Geometry, Grid};
use crate::engine::{FieldPoint, Inputs, Outputs, Scheme};
use crate::error::{CreepError, Result};
use crate::model::Model;
use crate::tolerance::{self, Filter};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Where a configuration comes from.
#[derive(Clone, Debug)]
pub enum ConfigSource {
    /// A configuration JSON file.
    File(PathBuf),
    /// Configuration JSON text, named `name` in error messages.
    Json {
        /// The JSON document.
        text: String,
        /// Its name in error messages.
        name: String,
    },
}

impl ConfigSource {
    /// The configuration it holds.
    pub fn load(&self) -> Result<Config> {
        match self {
            ConfigSource::File(p) => Config::from_file(p),
            ConfigSource::Json { text, name } => Config::from_json_str(text, name),
        }
    }
}

/// A configuration of exactly one of `config` and `preset`, with `grid` (NXxNY) over its
/// own: the set-up of the measurement loop's commands.
pub fn loop_config(
    config: Option<&ConfigSource>,
    preset: Option<&str>,
    grid: Option<&str>,
) -> Result<Config> {
    let mut cfg = match (config, preset) {
        (Some(c), None) => c.load()?,
        (None, Some(p)) => Config::preset(p)?,
        _ => {
            return Err(CreepError::Config {
                source_name: "--config/--preset".into(),
                message: "give exactly one of --config FILE or --preset NAME".into(),
            })
        }
    };
    if let Some(g) = grid {
        cfg.grid = Grid::parse(g)?;
    }
    Ok(cfg)
}

/// The model and operating point of a model run: everything of `ecf curve`, `step`, `sine`
/// and `field` but the creepages and the time steps.
#[derive(Clone, Debug)]
pub struct ModelSetup {
    /// Model without a preset or configuration: ecf, fastsim or polach (default ecf).
    pub model: String,
    /// Preset name (instead of `config`).
    pub preset: Option<String>,
    /// Configuration (instead of `preset`).
    pub config: Option<ConfigSource>,
    /// Coulomb friction coefficient (FASTSIM), dimensionless; None: the configuration's.
    pub mu: Option<f64>,
    /// Rolling speed, m/s (default 20; negative: rolling backwards).
    pub v_mps: f64,
    /// Normal force, kN (default 110, > 0).
    pub fn_kn: f64,
    /// Semi-axis in rolling direction at this load, mm (with `b_mm`); None: the geometry of
    /// the configuration.
    pub a_mm: Option<f64>,
    /// Lateral semi-axis at this load, mm (with `a_mm`).
    pub b_mm: Option<f64>,
    /// Bristle grid NXxNY; None: the configuration's.
    pub grid: Option<String>,
    /// Relative tolerance on F_x (a fraction) that chooses grid and scheme from the accuracy
    /// table (ECF only); None: off.
    pub tol: Option<f64>,
    /// How the local temperature of a bristle move is solved; None: the configuration's.
    pub temperature_solve: Option<crate::thermal::TemperatureSolve>,
    /// Lateral creepage, dimensionless (default 0).
    pub cy: f64,
    /// Spin creepage, 1/m (default 0).
    pub spin: f64,
    /// Bulk temperature, degC (default 20).
    pub t_bulk_c: f64,
    /// Parameter overrides NAME=VALUE (units as in the name).
    pub params: Vec<String>,
    /// Values of data columns read by formula or Rust effects, NAME=VALUE.
    pub extra: Vec<String>,
}

impl Default for ModelSetup {
    fn default() -> Self {
        ModelSetup {
            model: "ecf".into(),
            preset: None,
            config: None,
            mu: None,
            v_mps: 20.0,
            fn_kn: 110.0,
            a_mm: None,
            b_mm: None,
            grid: None,
            tol: None,
            temperature_solve: None,
            cy: 0.0,
            spin: 0.0,
            t_bulk_c: 20.0,
            params: Vec::new(),
            extra: Vec::new(),
        }
    }
}

/// A model ready to run: the model with its scheme set, and the note on the grid and scheme
/// that `tol` chose (None without `tol`; a line starting with "note:" or "warning:").
pub struct Prepared {
    /// The model.
    pub model: Model,
    /// The choice of `tol`, as the command line prints it on stderr.
    pub note: Option<String>,
}

/// An out-of-range error naming `field`.
pub fn bad(field: &str, value: f64, expected: &str) -> CreepError {
    CreepError::OutOfRange {
        field: field.into(),
        value,
        expected: expected.into(),
    }
}

/// Most time steps a run takes (10 million: hours of computing on a small grid, and a
/// table of about 2 GB).
pub const MAX_STEPS: f64 = 1e7;

/// Refuses a run of `steps` time steps beyond [`MAX_STEPS`] (e.g. --dt-ms 1e-300 asked for
/// 5e300 steps and ran forever), naming `flag` and its `value`.
pub fn check_step_count(flag: &str, value: f64, steps: f64) -> Result<()> {
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
pub fn rename(e: CreepError, field: &str, flag: &str) -> CreepError {
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

/// Err where an output is not finite (NaN or inf), naming them all: no table of NaN.
pub fn check_outputs(o: &Outputs) -> Result<()> {
    let bad: Vec<(&str, f64)> = crate::engine::io::csv_outputs()
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
    Ok(())
}

/// Splits NAME=VALUE of `flag`, the value a number (`inf` where `inf_ok`).
fn name_value<'a>(p: &'a str, flag: &str, inf_ok: bool) -> Result<(&'a str, f64)> {
    let err = |m: String| CreepError::Config {
        source_name: flag.into(),
        message: m,
    };
    let (n, v) = p
        .split_once('=')
        .ok_or_else(|| err(format!("'{p}': expected NAME=VALUE")))?;
    let x: f64 = if inf_ok && v == "inf" {
        f64::INFINITY
    } else {
        v.parse()
            .map_err(|_| err(format!("'{p}': value is not a number")))?
    };
    Ok((n, x))
}

impl ModelSetup {
    /// The configuration (a preset, a file or a model's defaults, with the overrides),
    /// checked.
    pub fn config(&self) -> Result<Config> {
        let mut cfg = match (&self.config, &self.preset) {
            (Some(_), Some(_)) => {
                return Err(CreepError::Config {
                    source_name: "--config/--preset".into(),
                    message: "give either --preset or --config, not both".into(),
                })
            }
            (Some(c), None) => c.load()?,
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
                .set(crate::params::P::Mu, mu)
                .map_err(|e| rename(e, "mu", "--mu"))?;
        }
        for p in &self.params {
            let (n, x) = name_value(p, "--param", true)?;
            cfg.params.set_by_name(n, x)?;
        }
        if let Some(g) = &self.grid {
            cfg.grid = Grid::parse(g)?;
        }
        if let Some(s) = self.temperature_solve {
            cfg.temperature_solve = s;
        }
        self.check_operating_point(&mut cfg)?;
        Ok(cfg)
    }

    /// Checks speed, load and semi-axes (setting the geometry of `a_mm`/`b_mm`) and that
    /// the contact patch at this load exists.
    fn check_operating_point(&self, cfg: &mut Config) -> Result<()> {
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
        if self.fn_kn * 1e3 > crate::engine::F_LIFT_OFF {
            crate::engine::patch_for(cfg, self.fn_kn * 1e3).map_err(|e| {
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
        Ok(())
    }

    /// With `tol`: sets the grid of `cfg` chosen from the accuracy table and returns the
    /// chosen scheme and the note on the choice ((None, None) without `tol`). `dt`: the time
    /// step (s) of a transient run; `steady`: a steady run (curve, field: the rows of the
    /// schemes whose steady march they are, cells and cells-ho); `explicit_scheme`: the
    /// explicit scheme, if any. An explicit grid or scheme (else the configuration's scheme
    /// other than cells, as in the FMU) restricts the choice to the table's rows with them;
    /// a grid not in the table is used as given, with a note that its error is not
    /// tabulated.
    pub fn apply_tol(
        &self,
        cfg: &mut Config,
        dt: Option<f64>,
        steady: bool,
        explicit_scheme: Option<Scheme>,
    ) -> Result<(Option<Scheme>, Option<String>)> {
        let Some(tol) = self.tol else {
            return Ok((None, None));
        };
        if cfg.model != crate::ModelKind::Ecf {
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
        let rows = tolerance::table()?;
        let filter = Filter {
            preset: tolerance::scope_in(&rows, cfg),
            nx: grid.map(|g| g.nx),
            ny: grid.map(|g| g.ny),
            scheme,
            steady,
        };
        let dt = dt.filter(|d| d.is_finite() && *d > 0.0);
        match tolerance::choose_in(&rows, tol, self.v_mps, dt, filter) {
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
                let note = format!("{level}: --tol {tol}{what}{given}: {}", c.message());
                Ok((Some(c.scheme), Some(note)))
            }
            Err(CreepError::Config { .. }) if grid.is_some() || scheme.is_some() => {
                let with = match (explicit_scheme, file_scheme) {
                    (Some(s), _) => format!(" and --scheme {}", s.name()),
                    (None, Some(s)) => format!(" and the configuration's scheme {}", s.name()),
                    (None, None) => String::new(),
                };
                let note = format!(
                    "note: --tol {tol}: the accuracy table has no row with the explicit --grid {}x{}{with}: its error is not measured; running with the explicit settings",
                    cfg.grid.nx,
                    cfg.grid.ny,
                );
                Ok((scheme, Some(note)))
            }
            Err(e) => Err(e),
        }
    }

    /// A model of `cfg` with the extra column values set.
    pub fn model(&self, cfg: &Config) -> Result<Model> {
        let mut m = Model::new(cfg)?;
        let mut ex = Vec::new();
        for e in &self.extra {
            let (n, x) = name_value(e, "--extra", false)?;
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

    /// The configuration, the grid and scheme `tol` chooses, and the model with its scheme:
    /// `scheme` when given, else the one `tol` chose, else the configuration's. `dt` and
    /// `steady` as in [`ModelSetup::apply_tol`]; `check` runs on the configuration before
    /// the tolerance is applied (the run's own argument checks, in the command line's order).
    pub fn prepare<T>(
        &self,
        dt: Option<f64>,
        steady: bool,
        scheme: Option<Scheme>,
        check: impl FnOnce() -> Result<T>,
    ) -> Result<(Prepared, T)> {
        let mut cfg = self.config()?;
        let checked = check()?;
        let (chosen, note) = self.apply_tol(&mut cfg, dt, steady, scheme)?;
        let mut model = self.model(&cfg)?;
        if let Some(s) = scheme.or(chosen) {
            model.set_scheme(s);
        }
        Ok((Prepared { model, note }, checked))
    }

    /// The inputs at creepage `cx` and the operating point.
    pub fn inputs(&self, cx: f64) -> Inputs {
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

/// One row of a run: the row number (0: the steady state before a transient run), time
/// (s; 0 in a curve), creepage and outputs, each checked finite.
pub type Row<'a> = &'a mut dyn FnMut(usize, f64, f64, &Outputs) -> Result<()>;

/// A steady curve: the outputs at each creepage that `cx` gives (called once the
/// configuration is read), handed to `row`. Returns the prepared model's note and the model's
/// warnings.
pub fn curve(
    s: &ModelSetup,
    scheme: Option<Scheme>,
    cx: impl FnOnce() -> Result<Vec<f64>>,
    row: Row,
) -> Result<(Option<String>, Vec<String>)> {
    let (Prepared { mut model, note }, cx) = s.prepare(None, true, scheme, cx)?;
    for (k, &c) in cx.iter().enumerate() {
        let o = model
            .steady(&s.inputs(c))
            .map_err(|e| rename(e, "cx", "--cx"))?;
        check_outputs(&o)?;
        row(k, 0.0, c, &o)?;
    }
    Ok((note, model.take_warnings()))
}

/// The response to a creepage step from `cx_from` (steady, row 0 at t = 0) to `cx_to` over
/// `duration_ms` in steps of `dt_ms`: row k at t = k dt. Returns note and warnings.
pub fn step_series(
    s: &ModelSetup,
    scheme: Option<Scheme>,
    (cx_from, cx_to): (f64, f64),
    duration_ms: f64,
    dt_ms: f64,
    row: Row,
) -> Result<(Option<String>, Vec<String>)> {
    let check = || {
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
        check_step_count("--dt-ms", dt_ms, duration_ms / dt_ms)
    };
    let (Prepared { mut model, note }, ()) = s.prepare(Some(dt_ms * 1e-3), false, scheme, check)?;
    let o = model
        .steady(&s.inputs(cx_from))
        .map_err(|e| rename(e, "cx", "--cx-from"))?;
    check_outputs(&o)?;
    row(0, 0.0, cx_from, &o)?;
    let n = (duration_ms / dt_ms).round() as usize;
    let dt = dt_ms * 1e-3;
    let inp = s.inputs(cx_to);
    inp.validate().map_err(|e| rename(e, "cx", "--cx-to"))?;
    for k in 1..=n {
        let o = model.step(dt, &inp)?;
        check_outputs(&o)?;
        row(k, k as f64 * dt, cx_to, &o)?;
    }
    Ok((note, model.take_warnings()))
}

/// Periodic creepage cx = cm + ca sin(2 pi f t) from the steady state at `cm` (row 0), for
/// `cycles` periods of `steps_per_cycle` steps; the creepage is held over each step at its
/// end value (Eq. 4.15). Returns note and warnings.
pub fn sine(
    s: &ModelSetup,
    scheme: Option<Scheme>,
    (cm, ca, freq_hz): (f64, f64, f64),
    (cycles, steps_per_cycle): (u32, u32),
    row: Row,
) -> Result<(Option<String>, Vec<String>)> {
    let check = || {
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
        )
    };
    let dt = 1.0 / (freq_hz * steps_per_cycle as f64);
    let (Prepared { mut model, note }, ()) = s.prepare(Some(dt), false, scheme, check)?;
    let o = model
        .steady(&s.inputs(cm))
        .map_err(|e| rename(e, "cx", "--cm"))?;
    check_outputs(&o)?;
    row(0, 0.0, cm, &o)?;
    for k in 1..=(cycles * steps_per_cycle) {
        let t = k as f64 * dt;
        // creepage held constant over the step at its end value (Eq. 4.15)
        let c = cm + ca * (2.0 * std::f64::consts::PI * freq_hz * t).sin();
        let o = model
            .step(dt, &s.inputs(c))
            .map_err(|e| rename(e, "cx", "--cm/--ca"))?;
        check_outputs(&o)?;
        row(k as usize, t, c, &o)?;
    }
    Ok((note, model.take_warnings()))
}

/// The fields along y = 0 of a bristle model (an error for Polach).
pub fn field_of(model: &Model) -> Result<Vec<FieldPoint>> {
    model.field_y0().ok_or_else(|| CreepError::Config {
        source_name: "--model".into(),
        message: "fields exist for the bristle models (ecf, fastsim), not for polach".into(),
    })
}

/// The steady fields along y = 0 at creepage `cx`, with note and warnings.
pub fn field(
    s: &ModelSetup,
    scheme: Option<Scheme>,
    cx: f64,
) -> Result<(Vec<FieldPoint>, Option<String>, Vec<String>)> {
    let (Prepared { mut model, note }, ()) = s.prepare(None, true, scheme, || Ok(()))?;
    model
        .steady(&s.inputs(cx))
        .map_err(|e| rename(e, "cx", "--cx"))?;
    let f = field_of(&model)?;
    Ok((f, note, model.take_warnings()))
}

/// The text of `ecf info`: the presets, the effects, the Rust effects linked in, and the tables of
/// inputs, outputs and parameters.
pub fn info_text() -> String {
    let mut w = String::new();
    let _ = writeln!(
        &mut w,
        "presets: {}",
        crate::config::PRESETS
            .iter()
            .map(|p| p.0)
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(&mut w, "\neffects:");
    for e in crate::effects::CATALOGUE {
        let _ = writeln!(&mut w, "  {}: {}", e.name, e.description);
    }
    let _ = writeln!(&mut w, "\ncustom effects written in Rust (\"custom_effects\": [{{\"name\": ..., \"params\": {{...}}}}]):");
    for e in crate::custom::catalogue() {
        let _ = writeln!(
            &mut w,
            "  {} (scales {}): {}",
            e.name(),
            e.target().name(),
            e.description()
        );
        for (n, d, lo, hi, m) in e.params() {
            let _ = writeln!(&mut w, "    {n}: default {d}, bounds [{lo}, {hi}], {m}");
        }
    }
    let _ = writeln!(&mut w, "\ninputs (name, unit, default, range, meaning):");
    for s in crate::engine::io::INPUTS {
        let _ = writeln!(
            &mut w,
            "  {:<22} {:<9} {:>10} [{}, {}]  {}",
            s.name, s.unit, s.default, s.min, s.max, s.description
        );
    }
    let _ = writeln!(&mut w, "\noutputs (name, unit, meaning):");
    for s in crate::engine::io::OUTPUTS {
        let _ = writeln!(&mut w, "  {:<22} {:<9} {}", s.name, s.unit, s.description);
    }
    let _ = writeln!(
        &mut w,
        "\nparameters (name, unit, default, bounds, meaning):"
    );
    for s in crate::params::SPECS {
        let _ = writeln!(
            &mut w,
            "  {:<22} {:<9} {:>10} [{}, {}]  {} (effect {})",
            s.name, s.unit, s.default, s.min, s.max, s.description, s.effect
        );
    }
    w
}
