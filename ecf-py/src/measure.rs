//! The measurement loop: `ecf.compare`, `ecf.diagnose` and `ecf.fit`, each run on a worker thread that reports its progress and stops at Ctrl-C, and returning the command line's JSON.

use crate::{config_source, py_err, EcfError};
use creep_core::commands::loop_config;
use creep_core::{Config, CreepError};
use ecf_measure::measure::Data;
use ecf_measure::report as rep;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;

/// The measurement file (a path, or CSV text with a name) and the configuration, as the
/// Python layer passes them (a dict with every key, None where not given).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct DataArgs {
    data_path: Option<std::path::PathBuf>,
    data_text: Option<String>,
    data_name: String,
    config_path: Option<std::path::PathBuf>,
    config_json: Option<String>,
    preset: Option<String>,
    grid: Option<String>,
    threads: Option<usize>,
    v_mps: Option<f64>,
    fn_kn: Option<f64>,
    cx_unit: Option<String>,
}

/// What a job needs, owned (it runs on its own thread).
struct Loaded {
    cfg: Config,
    data: Data,
    threads: usize,
    loop_grid: bool,
    /// The data's name in messages (the file's path, else the name given).
    name: String,
}

impl DataArgs {
    /// The configuration and data, read and checked as the command line reads them.
    fn load(self) -> PyResult<Loaded> {
        let src = config_source(self.config_path, self.config_json)?;
        let threads = self
            .threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
            .max(1);
        let loop_grid = self.grid.is_none();
        let name = match &self.data_path {
            Some(p) => p.display().to_string(),
            None => self.data_name.clone(),
        };
        let read = || -> creep_core::Result<(Config, Data)> {
            let cfg = loop_config(src.as_ref(), self.preset.as_deref(), self.grid.as_deref())?;
            let defaults = rep::data_defaults(self.v_mps, self.fn_kn, self.cx_unit.as_deref())?;
            let data = match (&self.data_path, &self.data_text) {
                (Some(p), _) => ecf_measure::measure::read_data(p, &defaults)?,
                (None, Some(t)) => {
                    ecf_measure::measure::read_data_text(t, &self.data_name, &defaults)?
                }
                (None, None) => {
                    return Err(CreepError::Config {
                        source_name: "data".into(),
                        message: "give a file path or a DataFrame".into(),
                    })
                }
            };
            Ok((cfg, data))
        };
        let (cfg, data) = read().map_err(py_err)?;
        Ok(Loaded {
            cfg,
            data,
            threads,
            loop_grid,
            name,
        })
    }
}

/// A job's message to the Python thread.
enum Msg<T> {
    Progress(String),
    Done(creep_core::Result<T>),
}

/// The payload that unwinds a cancelled job's thread (never reaches Python).
struct Cancelled;

/// Runs `job` on its own thread while this one waits without the GIL, handing each progress
/// text to `progress` (a Python callable) and checking Ctrl-C every 50 ms. At Ctrl-C, or
/// when `progress` raises, the exception is returned at once and the job stops at its next
/// progress report (its thread unwinds there, with no message; nothing crosses into
/// Python).
fn run_job<T: Send + 'static>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    job: impl FnOnce(&(dyn Fn(String) + Sync)) -> creep_core::Result<T> + Send + 'static,
) -> PyResult<T> {
    let (tx, rx) = mpsc::channel::<Msg<T>>();
    let cancel = Arc::new(AtomicBool::new(false));
    let stop = cancel.clone();
    std::thread::Builder::new()
        .name("ecf-loop".into())
        .spawn(move || {
            let to_python = tx.clone();
            let report = move |m: String| {
                if stop.load(Ordering::Relaxed) {
                    std::panic::resume_unwind(Box::new(Cancelled));
                }
                let _ = to_python.send(Msg::Progress(m));
            };
            let r = job(&report);
            let _ = tx.send(Msg::Done(r));
        })
        .map_err(|e| EcfError::new_err(format!("cannot start the worker thread: {e}")))?;
    let mut rx = rx;
    loop {
        let (m, back) = py.detach(move || (rx.recv_timeout(Duration::from_millis(50)), rx));
        rx = back;
        let outcome = match m {
            Ok(Msg::Done(r)) => return r.map_err(py_err),
            Ok(Msg::Progress(s)) => match &progress {
                Some(cb) => cb.call1(py, (s,)).map(|_| ()),
                None => Ok(()),
            },
            Err(mpsc::RecvTimeoutError::Timeout) => Ok(()),
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(EcfError::new_err(
                    "the computation stopped without a result",
                ))
            }
        };
        if let Err(e) = outcome.and_then(|()| py.check_signals()) {
            cancel.store(true, Ordering::Relaxed);
            return Err(e);
        }
    }
}

/// JSON text, pretty as the command line prints it.
fn pretty(v: &serde_json::Value) -> creep_core::Result<String> {
    serde_json::to_string_pretty(v).map_err(|e| CreepError::State(e.to_string()))
}

/// `ecf compare --json`: the comparison of the configuration with the data, as JSON text.
#[pyfunction]
fn compare(py: Python<'_>, args: DataArgs) -> PyResult<String> {
    let l = args.load()?;
    run_job(py, None, move |_| match &l.data {
        Data::Rows(d) => pretty(&rep::compare_rows(&l.cfg, d, l.threads)?.to_json(&l.cfg, d)?),
        Data::Hpt(rows) => pretty(&rep::compare_hpt(&l.cfg, rows).to_json(rows.len())),
    })
}

/// `ecf diagnose --json`: the diagnosis as JSON text, and the configuration with the
/// proposed formula effect as the command line writes it to `--out` (None: none proposed).
#[pyfunction]
#[pyo3(signature = (args, progress=None))]
fn diagnose(
    py: Python<'_>,
    args: DataArgs,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, Option<String>)> {
    let l = args.load()?;
    run_job(py, progress, move |report| {
        let Data::Rows(data) = &l.data else {
            return Err(CreepError::Data {
                source_name: "data".into(),
                message: "a high-pressure-torsion file (p_MPa, u_mm, tau_MPa): use ecf compare or ecf fit".into(),
            });
        };
        let o = ecf_measure::diagnose::Options {
            loop_grid: l.loop_grid,
            ..ecf_measure::diagnose::Options::new(l.threads)
        };
        let d = ecf_measure::diagnose::diagnose_opts(&l.cfg, data, &o, &|s| report(s.to_string()))?;
        let proposed = match d.search.as_ref().and_then(|s| s.proposed_config.as_ref()) {
            Some(c) => Some(
                serde_json::to_string_pretty(c).map_err(|e| CreepError::State(e.to_string()))?
                    + "\n",
            ),
            None => None,
        };
        let v = serde_json::to_value(&d).map_err(|e| CreepError::State(e.to_string()))?;
        Ok((pretty(&v)?, proposed))
    })
}

/// `ecf fit --json`: the fit's JSON text (`out`: the path it names) and the fitted
/// configuration's document as `--out` receives it.
#[pyfunction]
#[pyo3(signature = (args, free=None, bounds=Vec::new(), out=None, progress=None))]
fn fit(
    py: Python<'_>,
    args: DataArgs,
    free: Option<String>,
    bounds: Vec<String>,
    out: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, String)> {
    let l = args.load()?;
    run_job(py, progress, move |report| {
        let (r, warnings) = match &l.data {
            Data::Hpt(rows) => {
                let (cfg, fp) = rep::fit_setup(
                    &l.cfg,
                    free.as_deref(),
                    &bounds,
                    ecf_measure::hpt::default_free(),
                )?;
                (
                    ecf_measure::hpt::fit(&cfg, &l.name, rows, &fp, &|_| {})?,
                    Vec::new(),
                )
            }
            Data::Rows(data) => {
                let default = ecf_measure::fit::default_free(&l.cfg);
                let (cfg, fp) = rep::fit_setup(&l.cfg, free.as_deref(), &bounds, default)?;
                let names: Vec<String> = fp.iter().map(|p| p.name(&cfg)).collect();
                let n_rows = data.rows.len();
                let each = |n: usize| {
                    report(format!(
                        "fitting {}: {n} model evaluations of {n_rows} rows",
                        names.join(", ")
                    ))
                };
                let r = ecf_measure::fit::fit_params(&cfg, data, &fp, l.threads, &each)?;
                let (_, w) = ecf_measure::evaluate::predict_warned(&r.config, data, l.threads)?;
                (r, w)
            }
        };
        let doc = pretty(&rep::fitted_document(&r, &warnings))? + "\n";
        Ok((pretty(&rep::fit_json(&r, &warnings, out.as_deref()))?, doc))
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    Ok(())
}
