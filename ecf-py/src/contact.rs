//! `ecf.Contact`: one stateful contact — steady states, time steps, fields along the strips, and its state saved to and restored from bytes.

use crate::runs::{field_table, push_outputs};
use crate::{py_err, SetupArgs};
use creep_core::commands::{check_outputs, field_of, Prepared};
use creep_core::{Inputs, Model};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// A transient contact of creep-core ([`Model`]) with its current inputs.
#[pyclass(module = "ecf._ecf")]
struct Contact {
    model: Model,
    inputs: Inputs,
    note: Option<String>,
}

/// New values of the inputs (None: keep the current one).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct InputArgs {
    cx: Option<f64>,
    cy: Option<f64>,
    spin: Option<f64>,
    v_mps: Option<f64>,
    fn_kn: Option<f64>,
    t_bulk_c: Option<f64>,
}

impl InputArgs {
    fn apply(&self, i: &mut Inputs) {
        let set = |d: &mut f64, v: Option<f64>| {
            if let Some(x) = v {
                *d = x;
            }
        };
        set(&mut i.cx, self.cx);
        set(&mut i.cy, self.cy);
        set(&mut i.spin, self.spin);
        set(&mut i.v, self.v_mps);
        set(&mut i.fn_n, self.fn_kn.map(|f| f * 1e3));
        set(&mut i.t_bulk, self.t_bulk_c);
    }
}

impl Contact {
    /// Runs `f` on the model without the GIL with the inputs updated by `new` (restored
    /// where the model refuses them); the outputs in their CSV columns.
    fn run(
        &mut self,
        py: Python<'_>,
        new: InputArgs,
        f: impl FnOnce(&mut Model, &Inputs) -> creep_core::Result<creep_core::Outputs> + Send,
    ) -> PyResult<Vec<f64>> {
        let mut inp = self.inputs;
        new.apply(&mut inp);
        let model = &mut self.model;
        let o = py
            .detach(move || {
                let o = f(model, &inp)?;
                check_outputs(&o)?;
                Ok(o)
            })
            .map_err(py_err)?;
        self.inputs = inp;
        let mut v = Vec::new();
        push_outputs(&mut v, &o);
        Ok(v)
    }
}

#[pymethods]
impl Contact {
    /// A contact of the set-up (as `ecf.curve`'s keywords) at creepage `cx`, not yet run.
    #[new]
    fn new(py: Python<'_>, setup: SetupArgs, cx: f64) -> PyResult<Self> {
        let (s, scheme) = setup.split(false)?;
        let prepared = py.detach(|| s.prepare(None, false, scheme, || Ok(())));
        let (Prepared { model, note }, ()) = prepared.map_err(py_err)?;
        Ok(Contact {
            model,
            inputs: s.inputs(cx),
            note,
        })
    }

    /// The steady state of the inputs (updated by `new`): the outputs in CSV order.
    fn steady(&mut self, py: Python<'_>, new: InputArgs) -> PyResult<Vec<f64>> {
        self.run(py, new, |m, i| m.steady(i))
    }

    /// One time step of `dt_s` seconds under the inputs (updated by `new`).
    fn step(&mut self, py: Python<'_>, dt_s: f64, new: InputArgs) -> PyResult<Vec<f64>> {
        self.run(py, new, move |m, i| m.step(dt_s, i))
    }

    /// The fields along y = 0 now: column names and row-major float64 bytes.
    fn field<'py>(&self, py: Python<'py>) -> PyResult<(Vec<String>, Bound<'py, PyBytes>)> {
        let f = field_of(&self.model).map_err(py_err)?;
        Ok(field_table(py, &f))
    }

    /// The complete state as bytes (creep-core's state format, with the configuration).
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.model.save_state())
    }

    /// Restores a state from `state()` of a contact with the same configuration.
    fn restore(&mut self, data: &[u8]) -> PyResult<()> {
        self.model.load_state(data).map_err(py_err)?;
        // the inputs the state was saved at
        if let Model::Bristle(c) = &self.model {
            self.inputs = c.inputs();
        } else if let Model::Polach { inputs, .. } = &self.model {
            self.inputs = *inputs;
        }
        Ok(())
    }

    /// Simulated time, s.
    #[getter]
    fn time_s(&self) -> f64 {
        self.model.time()
    }

    /// The current inputs: cx, cy, spin (1/m), v_mps, fn_kN, t_bulk_C.
    #[getter]
    fn inputs(&self) -> Vec<(String, f64)> {
        let i = &self.inputs;
        [
            ("cx", i.cx),
            ("cy", i.cy),
            ("spin", i.spin),
            ("v_mps", i.v),
            ("fn_kN", i.fn_n / 1e3),
            ("t_bulk_C", i.t_bulk),
        ]
        .iter()
        .map(|(n, x)| (n.to_string(), *x))
        .collect()
    }

    /// The configuration as JSON text.
    #[getter]
    fn config_json(&self) -> String {
        self.model.config().to_json().to_string()
    }

    /// The scheme of the time steps (None for Polach).
    #[getter]
    fn scheme(&self) -> Option<&'static str> {
        self.model.scheme().map(|s| s.name())
    }

    /// The note on the grid and scheme that `tol` chose (None without `tol`).
    #[getter]
    fn note(&self) -> Option<String> {
        self.note.clone()
    }

    /// The model's warnings since the last call.
    fn take_warnings(&mut self) -> Vec<String> {
        self.model.take_warnings()
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Contact>()
}
