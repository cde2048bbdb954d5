//! `ecf`: command-line front of creep-core and ecf-measure — creep curves, transient steps, periodic creepage and contact fields as CSV.

#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

use clap::{Args, Parser, Subcommand};
use creep_core::{Config, CreepError, Grid};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const UNITS: &str = "Units: creepages cx, cy dimensionless (0.01 = 1 %), spin 1/m, speed m/s, \
normal force kN, semi-axes mm, time s (t_s) or ms (--duration-ms), forces N (Fx_N, Fy_N), \
moment N m (Mz_Nm), temperatures degC, power W, pressure/stress Pa.";

#[derive(Parser)]
#[command(name = "ecf", version, about = "Wheel-rail creep forces: ECF (third body layer + flash temperature), FASTSIM and Polach", after_help = UNITS)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Steady creep curve f(cx): CSV cx,f,Fx_N,...
    Curve(model_cmd::CurveArgs),
    /// Transient response to a creepage step at t = 0 (seed Sec. 4.5.1): CSV t_s,cx,f,...
    Step(model_cmd::StepArgs),
    /// Periodic creepage cx = cm + ca sin(2 pi f t) (seed Sec. 4.5.2, Eq. 4.37): CSV t_s,cx,f,...
    Sine(model_cmd::SineArgs),
    /// Fields along y = 0 at steady state (seed Fig. 4.9/4.10): CSV x_mm,tau_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime
    Field(model_cmd::FieldArgs),
    /// Lists presets, effects, inputs, outputs and parameters with units, defaults and bounds
    Info,
    /// Compares a configuration with a measurement file: CV(RMSE) (Eq. 2.9) overall, per group and regime; PNG plots
    Compare {
        #[command(flatten)]
        d: DataArgs,
        /// Print the comparison as JSON ({"cv_rmse_pct": x, "groups": [...], ...})
        #[arg(long)]
        json: bool,
        /// Directory for PNG plots (measured vs model per series, residuals over every variable)
        #[arg(long)]
        plots: Option<PathBuf>,
    },
    /// Which physical effect is missing? Residual correlations, each catalogue effect added, refitted and scored on held-out groups
    Diagnose {
        #[command(flatten)]
        d: DataArgs,
        /// Print the diagnosis as JSON ({"baseline_cv_rmse_pct": x, "candidates": [...], "correlations": [...]})
        #[arg(long)]
        json: bool,
        /// Where to write the configuration with the proposed formula effect, when the search of formula forms proposes one (nothing is written otherwise)
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// One self-contained HTML page: comparison, diagnosis and plots; with --compare-with, before and after side by side
    Report {
        #[command(flatten)]
        d: DataArgs,
        /// A second configuration (e.g. the fitted one) shown beside the first
        #[arg(long)]
        compare_with: Option<PathBuf>,
        /// Output HTML file
        #[arg(long)]
        out: PathBuf,
    },
    /// Fits parameters to a measurement file (Eq. 5.1, bounded Levenberg-Marquardt) and writes the fitted configuration
    Fit {
        #[command(flatten)]
        d: DataArgs,
        /// Parameters to fit, comma separated (names as in `ecf info`); default: the layer strengths and hardening scale (+ their temperature coefficients)
        #[arg(long)]
        free: Option<String>,
        /// Narrow a parameter's bounds for this fit, NAME=MIN:MAX (repeatable), e.g. tau_c2_0_GPa=0.2:2
        #[arg(
            long = "bound",
            value_name = "NAME=MIN:MAX",
            allow_hyphen_values = true
        )]
        bounds: Vec<String>,
        /// Where to write the fitted configuration JSON (left untouched when the fit fails)
        #[arg(long)]
        out: PathBuf,
        /// Print the result as JSON
        #[arg(long)]
        json: bool,
    },
}

/// The number of cores this process may run on (its CPU affinity), at least 1.
fn default_threads() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

#[derive(Args, Clone)]
struct DataArgs {
    /// Measurement CSV (columns cx, f [, series, condition, v_mps, fn_kN, a_mm, b_mm, cy, cs_per_m, t_s, t_bulk_C, extra numeric columns])
    data: PathBuf,
    /// Configuration JSON file
    #[arg(long)]
    config: Option<PathBuf>,
    /// Preset (instead of --config)
    #[arg(long)]
    preset: Option<String>,
    /// Bristle grid NXxNY (overrides the configuration's)
    #[arg(long)]
    grid: Option<String>,
    /// Worker threads (default: the cores this process may run on; results do not depend on it)
    #[arg(long, default_value_t = default_threads())]
    threads: usize,
    /// Speed of every row, m/s, for a data file without a speed column (no silent default)
    #[arg(long)]
    v_mps: Option<f64>,
    /// Normal force of every row, kN, for a data file without a load column (no silent default)
    #[arg(long = "fn-kN", visible_alias = "fn-kn")]
    fn_kn: Option<f64>,
    /// Unit of creepage columns whose header gives none: 1 (dimensionless, 0.01 = 1 %) or percent
    #[arg(long)]
    cx_unit: Option<String>,
    /// Do not print the column mapping of the data file on stderr
    #[arg(long)]
    quiet: bool,
}

impl DataArgs {
    /// The configuration and the measurement file, read once.
    fn load(&self) -> Result<(Config, Data), CreepError> {
        let cfg = self.config_only()?;
        let defaults =
            ecf_measure::report::data_defaults(self.v_mps, self.fn_kn, self.cx_unit.as_deref())?;
        Ok((
            cfg,
            measure_cmd::read_data(&self.data, &defaults, self.quiet)?,
        ))
    }

    /// Like `load`, for commands that need creep measurements (not HPT curves).
    fn load_rows(&self) -> Result<(Config, ecf_measure::measure::Dataset), CreepError> {
        match self.load()? {
            (cfg, Data::Rows(d)) => Ok((cfg, d)),
            (_, Data::Hpt(_)) => Err(CreepError::Data {
                source_name: self.data.display().to_string(),
                message: "a high-pressure-torsion file (p_MPa, u_mm, tau_MPa): use ecf compare or ecf fit".into(),
            }),
        }
    }

    fn config_only(&self) -> Result<Config, CreepError> {
        let file = self
            .config
            .clone()
            .map(creep_core::commands::ConfigSource::File);
        creep_core::commands::loop_config(
            file.as_ref(),
            self.preset.as_deref(),
            self.grid.as_deref(),
        )
    }
}

/// `ecf report`: the HTML page of the comparison, the diagnosis and the plots, for one or two
/// configurations.
fn report(
    d: &DataArgs,
    compare_with: Option<&Path>,
    out: &Path,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    let (cfg, data) = d.load_rows()?;
    let second = match compare_with {
        Some(p) => {
            let mut c = Config::from_file(p)?;
            if let Some(g) = &d.grid {
                c.grid = Grid::parse(g)?;
            }
            Some((p.display().to_string(), c))
        }
        None => None,
    };
    let first_name = d
        .config
        .as_ref()
        .map(|p| p.display().to_string())
        .or(d.preset.clone())
        .unwrap_or_default();
    report_cmd::report(&cfg, &first_name, second.as_ref(), &data, d.threads, out)?;
    writeln!(w, "{}", out.display()).map_err(model_cmd::io)
}

/// `ecf fit`: creep measurements or high-pressure-torsion curves, by the file's kind.
fn fit(d: &DataArgs, req: &measure_cmd::FitRequest, w: &mut Vec<u8>) -> Result<(), CreepError> {
    match d.load()? {
        (cfg, Data::Hpt(rows)) => measure_cmd::fit_hpt(&cfg, &d.data, &rows, req, w),
        (cfg, Data::Rows(data)) => measure_cmd::fit(&cfg, &data, d.threads, req, w),
    }
}

/// `ecf compare`: creep measurements or high-pressure-torsion curves, by the file's kind.
fn compare(
    d: &DataArgs,
    json: bool,
    plots: Option<&Path>,
    w: &mut Vec<u8>,
) -> Result<(), CreepError> {
    match d.load()? {
        (cfg, Data::Hpt(rows)) => measure_cmd::compare_hpt(&cfg, &d.data, &rows, json, plots, w),
        (cfg, Data::Rows(data)) => measure_cmd::compare(&cfg, &data, d.threads, json, plots, w),
    }
}

/// Runs one command. The whole output is built first and printed only on success: nothing
/// half-written.
fn run(cli: Cli) -> Result<(), CreepError> {
    let mut w: Vec<u8> = Vec::new();
    match cli.cmd {
        Cmd::Curve(a) => a.run(&mut w)?,
        Cmd::Step(a) => a.run(&mut w)?,
        Cmd::Sine(a) => a.run(&mut w)?,
        Cmd::Field(a) => a.run(&mut w)?,
        Cmd::Compare { d, json, plots } => compare(&d, json, plots.as_deref(), &mut w)?,
        Cmd::Diagnose { d, json, out } => {
            let (cfg, data) = d.load_rows()?;
            let o = ecf_measure::diagnose::Options {
                loop_grid: d.grid.is_none(),
                ..ecf_measure::diagnose::Options::new(d.threads)
            };
            measure_cmd::diagnose(&cfg, &data, &o, json, out.as_deref(), &mut w)?;
        }
        Cmd::Report {
            d,
            compare_with,
            out,
        } => report(&d, compare_with.as_deref(), &out, &mut w)?,
        Cmd::Fit {
            d,
            free,
            bounds,
            out,
            json,
        } => {
            let req = measure_cmd::FitRequest {
                free: free.as_deref(),
                bounds: &bounds,
                out: &out,
                json,
            };
            fit(&d, &req, &mut w)?
        }
        Cmd::Info => model_cmd::info(&mut w).map_err(model_cmd::io)?,
    }
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    lock.write_all(&w).map_err(model_cmd::io)?;
    lock.flush().map_err(model_cmd::io)?;
    Ok(())
}

mod cleanup;
mod measure_cmd;
mod model_cmd;
mod plots;
mod report_cmd;

use ecf_measure::measure::Data;

/// Runs the `ecf` command line with the process's arguments; the exit code is 2 on an error
/// (printed to stderr). The `ecf` binary is this function; `scripts/build-fmu.sh --effects`
/// builds it again with a user's effect crate linked in.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    cleanup::install();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// How the local temperature of a bristle move is solved
/// (`creep_core::thermal::TemperatureSolve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum TemperatureSolveArg {
    /// The implicit solve to its tolerance (the reference)
    Exact,
    /// The predictor-corrector: two or three evaluations of the law per move
    Predictor,
}

impl TemperatureSolveArg {
    /// The engine's solve of the flag's value.
    pub(crate) fn solve(self) -> creep_core::thermal::TemperatureSolve {
        match self {
            TemperatureSolveArg::Exact => creep_core::thermal::TemperatureSolve::Exact,
            TemperatureSolveArg::Predictor => {
                creep_core::thermal::TemperatureSolve::PredictorCorrector
            }
        }
    }
}
