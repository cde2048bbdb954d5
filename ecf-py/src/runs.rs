//! The model runs as tables: steady curve, step and sine responses and the steady field, each a row-major block of f64 with the command line's column names.

use crate::{SetupArgs, SignalCheck};
use creep_core::commands::{self, Row};
use creep_core::{FieldPoint, Outputs};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// A table as Python receives it: column names, the values row-major as native-endian f64
/// bytes, the tolerance's note (None without tol) and the model's warnings.
type Table<'py> = (
    Vec<String>,
    Bound<'py, PyBytes>,
    Option<String>,
    Vec<String>,
);

/// The output columns' names (creep-core's CSV headers, in their order).
pub(crate) fn output_columns() -> Vec<String> {
    creep_core::engine::io::csv_outputs()
        .iter()
        .map(|s| s.csv.header.to_string())
        .collect()
}

/// Appends the outputs in their CSV columns and units (value times the column's scale).
pub(crate) fn push_outputs(v: &mut Vec<f64>, o: &Outputs) {
    for s in creep_core::engine::io::csv_outputs() {
        v.push((s.get)(o) * s.csv.scale);
    }
}

/// f64 values as native-endian bytes.
pub(crate) fn to_bytes(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_ne_bytes()).collect()
}

/// f64 values of native-endian bytes (the Python layer sends contiguous float64 arrays).
pub(crate) fn from_bytes(b: &[u8]) -> PyResult<Vec<f64>> {
    if !b.len().is_multiple_of(8) {
        return Err(crate::EcfError::new_err("an array of float64 was expected"));
    }
    Ok(b.chunks_exact(8)
        .map(|c| f64::from_ne_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// Runs `run` without the GIL, collecting the rows it hands out (time, creepage, outputs;
/// time only where `with_t`), checking Ctrl-C between rows.
fn table<'py>(
    py: Python<'py>,
    with_t: bool,
    run: impl FnOnce(Row) -> creep_core::Result<(Option<String>, Vec<String>)> + Send,
) -> PyResult<Table<'py>> {
    let (vals, res, sig) = py.detach(|| {
        let mut sig = SignalCheck::new();
        let mut vals: Vec<f64> = Vec::new();
        let mut row = |_: usize, t: f64, c: f64, o: &Outputs| {
            sig.check()?;
            if with_t {
                vals.push(t);
            }
            vals.push(c);
            push_outputs(&mut vals, o);
            Ok(())
        };
        let res = run(&mut row);
        (vals, res, sig)
    });
    let (note, warnings) = sig.finish(res)?;
    let mut cols: Vec<String> = if with_t {
        vec!["t_s".into(), "cx".into()]
    } else {
        vec!["cx".into()]
    };
    cols.extend(output_columns());
    Ok((cols, PyBytes::new(py, &to_bytes(&vals)), note, warnings))
}

/// `ecf curve`: the steady outputs at each creepage of `cx` (float64 bytes).
#[pyfunction]
fn curve<'py>(py: Python<'py>, setup: SetupArgs, cx: &[u8]) -> PyResult<Table<'py>> {
    let (s, scheme) = setup.split(true)?;
    let cx = from_bytes(cx)?;
    for &c in &cx {
        if !c.is_finite() {
            return Err(crate::EcfError::new_err(format!("cx: '{c}' is not finite")));
        }
    }
    table(py, false, move |row| {
        commands::curve(&s, scheme, || Ok(cx), row)
    })
}

/// `ecf step`: the response to a creepage step from `cx_from` to `cx_to`.
#[pyfunction]
fn step_series<'py>(
    py: Python<'py>,
    setup: SetupArgs,
    cx_from: f64,
    cx_to: f64,
    duration_ms: f64,
    dt_ms: f64,
) -> PyResult<Table<'py>> {
    let (s, scheme) = setup.split(false)?;
    table(py, true, move |row| {
        commands::step_series(&s, scheme, (cx_from, cx_to), duration_ms, dt_ms, row)
    })
}

/// `ecf sine`: periodic creepage cx = cm + ca sin(2 pi f t).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn sine<'py>(
    py: Python<'py>,
    setup: SetupArgs,
    cm: f64,
    ca: f64,
    freq_hz: f64,
    cycles: u32,
    steps_per_cycle: u32,
) -> PyResult<Table<'py>> {
    let (s, scheme) = setup.split(false)?;
    table(py, true, move |row| {
        commands::sine(
            &s,
            scheme,
            (cm, ca, freq_hz),
            (cycles, steps_per_cycle),
            row,
        )
    })
}

/// The names of the field columns.
pub(crate) const FIELD_COLUMNS: [&str; 8] = [
    "x_mm",
    "tau_Pa",
    "tau_x_Pa",
    "tau_c1_Pa",
    "tau_c2_Pa",
    "p_Pa",
    "T_C",
    "regime",
];

/// A field as a row-major table of [`FIELD_COLUMNS`] (a strength without limit: inf).
pub(crate) fn field_table<'py>(
    py: Python<'py>,
    f: &[FieldPoint],
) -> (Vec<String>, Bound<'py, PyBytes>) {
    let mut v = Vec::with_capacity(f.len() * FIELD_COLUMNS.len());
    for p in f {
        v.extend([
            p.x * 1e3,
            p.tau,
            p.tau_x,
            p.tau_c1,
            p.tau_c2,
            p.p,
            p.t,
            f64::from(p.regime),
        ]);
    }
    (
        FIELD_COLUMNS.iter().map(|s| s.to_string()).collect(),
        PyBytes::new(py, &to_bytes(&v)),
    )
}

/// `ecf field`: the steady fields along y = 0 at creepage `cx`.
#[pyfunction]
fn field<'py>(py: Python<'py>, setup: SetupArgs, cx: f64) -> PyResult<Table<'py>> {
    let (s, scheme) = setup.split(true)?;
    let r = py.detach(move || commands::field(&s, scheme, cx));
    let (f, note, warnings) = r.map_err(crate::py_err)?;
    let (cols, b) = field_table(py, &f);
    Ok((cols, b, note, warnings))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(curve, m)?)?;
    m.add_function(wrap_pyfunction!(step_series, m)?)?;
    m.add_function(wrap_pyfunction!(sine, m)?)?;
    m.add_function(wrap_pyfunction!(field, m)?)?;
    Ok(())
}
