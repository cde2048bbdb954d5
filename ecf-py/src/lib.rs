//! `ecf._ecf`: the extension module under the Python package `ecf` — creep-core's model runs and ecf-measure's loop, with no physics of its own.
//!
//! The Python layer (`python/ecf/__init__.py`) turns the bytes returned here into NumPy
//! arrays and DataFrames and the JSON text into result objects; every number comes from the
//! same library calls as the `ecf` command line (creep_core::commands, ecf_measure::report).

#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

mod contact;
mod measure;
mod runs;

use creep_core::commands::{ConfigSource, ModelSetup};
use creep_core::CreepError;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::time::{Duration, Instant};

pyo3::create_exception!(
    _ecf,
    EcfError,
    PyValueError,
    "Bad input or a model that cannot run at it; the message is the `ecf` command line's."
);

/// A creep-core error as `ecf.EcfError` (a `ValueError`), with the command line's message.
pub(crate) fn py_err(e: CreepError) -> PyErr {
    EcfError::new_err(e.to_string())
}

/// The model set-up as the Python layer passes it: a dict with every key (None where not
/// given); `params` and `extra` as NAME=VALUE texts.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct SetupArgs {
    model: String,
    preset: Option<String>,
    config_path: Option<std::path::PathBuf>,
    config_json: Option<String>,
    mu: Option<f64>,
    v_mps: f64,
    fn_kn: f64,
    a_mm: Option<f64>,
    b_mm: Option<f64>,
    grid: Option<String>,
    tol: Option<f64>,
    cy: f64,
    spin: f64,
    t_bulk_c: f64,
    params: Vec<String>,
    extra: Vec<String>,
    scheme: Option<String>,
}

/// The configuration source of a path or a JSON text (both given: an error naming both).
pub(crate) fn config_source(
    path: Option<std::path::PathBuf>,
    json: Option<String>,
) -> PyResult<Option<ConfigSource>> {
    match (path, json) {
        (Some(_), Some(_)) => Err(EcfError::new_err(
            "config: give a file path or a configuration dict, not both",
        )),
        (Some(p), None) => Ok(Some(ConfigSource::File(p))),
        (None, Some(text)) => Ok(Some(ConfigSource::Json {
            text,
            name: "config".into(),
        })),
        (None, None) => Ok(None),
    }
}

impl SetupArgs {
    /// The library's set-up and the explicit scheme (`steady`: cells or cells-ho only).
    pub(crate) fn split(
        self,
        steady: bool,
    ) -> PyResult<(ModelSetup, Option<creep_core::engine::Scheme>)> {
        let scheme = match self.scheme.as_deref() {
            None => None,
            Some(n) => match creep_core::engine::Scheme::by_name(n) {
                Some(creep_core::engine::Scheme::Continuous) if steady => {
                    return Err(EcfError::new_err(format!(
                        "scheme: '{n}' is not a steady scheme; give cells or cells-ho"
                    )))
                }
                Some(s) => Some(s),
                None => {
                    return Err(EcfError::new_err(format!(
                        "scheme: '{n}': expected {}",
                        creep_core::engine::Scheme::NAMES
                    )))
                }
            },
        };
        let setup = ModelSetup {
            model: self.model,
            preset: self.preset,
            config: config_source(self.config_path, self.config_json)?,
            mu: self.mu,
            v_mps: self.v_mps,
            fn_kn: self.fn_kn,
            a_mm: self.a_mm,
            b_mm: self.b_mm,
            grid: self.grid,
            tol: self.tol,
            temperature_solve: None,
            cy: self.cy,
            spin: self.spin,
            t_bulk_c: self.t_bulk_c,
            params: self.params,
            extra: self.extra,
        };
        Ok((setup, scheme))
    }
}

/// Checks Python's signals (Ctrl-C) at most every 20 ms from code that runs without the
/// GIL: the first error (a KeyboardInterrupt) is kept in `pending` and the run is stopped
/// by the error this returns.
pub(crate) struct SignalCheck {
    last: Instant,
    /// The Python exception that stopped the run.
    pub(crate) pending: Option<PyErr>,
}

impl SignalCheck {
    pub(crate) fn new() -> Self {
        SignalCheck {
            last: Instant::now(),
            pending: None,
        }
    }

    /// Err (and the exception kept) where Python has a signal to handle.
    pub(crate) fn check(&mut self) -> Result<(), CreepError> {
        if self.last.elapsed() < Duration::from_millis(20) {
            return Ok(());
        }
        self.last = Instant::now();
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => Ok(()),
            Err(e) => {
                self.pending = Some(e);
                Err(CreepError::State("interrupted".into()))
            }
        }
    }

    /// The result as Python sees it: the kept exception first, else the model's error.
    pub(crate) fn finish<T>(self, r: Result<T, CreepError>) -> PyResult<T> {
        match (self.pending, r) {
            (Some(e), _) => Err(e),
            (None, r) => r.map_err(py_err),
        }
    }
}

/// The text of `ecf info`.
#[pyfunction]
fn info_text() -> String {
    creep_core::commands::info_text()
}

/// The tables of `ecf info` as JSON: presets, effects, inputs, outputs (with their CSV
/// column, scale and decimals), parameters.
#[pyfunction]
fn info_json() -> String {
    use creep_core::engine::io::{csv_outputs, INPUTS};
    let outputs: Vec<serde_json::Value> = csv_outputs()
        .iter()
        .map(|s| {
            serde_json::json!({"name": s.name, "unit": s.unit, "description": s.description,
                "column": s.csv.header, "scale": s.csv.scale, "decimals": s.csv.decimals})
        })
        .collect();
    let inputs: Vec<serde_json::Value> = INPUTS
        .iter()
        .map(|s| {
            serde_json::json!({"name": s.name, "unit": s.unit, "default": s.default,
                "min": s.min, "max": s.max, "description": s.description})
        })
        .collect();
    let params: Vec<serde_json::Value> = creep_core::params::SPECS
        .iter()
        .map(|s| {
            serde_json::json!({"name": s.name, "unit": s.unit, "default": s.default,
                "min": s.min, "max": s.max, "description": s.description, "effect": s.effect})
        })
        .collect();
    let effects: Vec<serde_json::Value> = creep_core::effects::CATALOGUE
        .iter()
        .map(|e| serde_json::json!({"name": e.name, "description": e.description}))
        .collect();
    serde_json::json!({
        "version": env!("CARGO_PKG_VERSION"),
        "presets": creep_core::config::PRESETS.iter().map(|p| p.0).collect::<Vec<_>>(),
        "effects": effects,
        "inputs": inputs,
        "outputs": outputs,
        "params": params,
    })
    .to_string()
}

#[pymodule]
fn _ecf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("EcfError", m.py().get_type::<EcfError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(info_text, m)?)?;
    m.add_function(wrap_pyfunction!(info_json, m)?)?;
    runs::register(m)?;
    contact::register(m)?;
    measure::register(m)?;
    Ok(())
}
