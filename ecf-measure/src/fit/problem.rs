//! One least-squares problem for the Levenberg-Marquardt solver: the configuration at a point of the mapped parameters, its residuals and their forward-difference Jacobian.

use super::map::Map;
use super::{FreeParam, ModelFn};
use creep_core::config::Config;
use creep_core::error::{CreepError, Result};
use levenberg_marquardt::LeastSquaresProblem;
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};

/// The fit as the solver sees it: residuals model - measured over the mapped parameters z.
pub(super) struct Problem<'a> {
    pub(super) base: Config,
    pub(super) meas: Vec<f64>,
    pub(super) model: ModelFn<'a>,
    pub(super) free: Vec<FreeParam>,
    pub(super) maps: Vec<Map>,
    pub(super) z: DVector<f64>,
    pub(super) progress: &'a (dyn Fn(usize) + Sync),
    pub(super) evals: &'a std::cell::Cell<usize>,
    pub(super) error: std::cell::RefCell<Option<CreepError>>,
    /// The last point evaluated and its residuals: the Jacobian at the current point reuses
    /// them (the solver asks for the residuals at a point before the Jacobian there).
    pub(super) last: std::cell::RefCell<Option<(DVector<f64>, DVector<f64>)>>,
}

impl Problem<'_> {
    /// The configuration at the mapped point `z` (each value clamped to its bounds).
    pub(super) fn config_at(&self, z: &DVector<f64>) -> Result<Config> {
        let mut c = self.base.clone();
        for (k, id) in self.free.iter().enumerate() {
            let (lo, hi) = id.bounds(&self.base);
            let v = self.maps[k].to_p(z[k]).clamp(lo, hi);
            id.set(&mut c, v)?;
        }
        Ok(c)
    }
    fn residuals_at(&self, z: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.evals.get() + 1;
        self.evals.set(n);
        (self.progress)(n);
        let r = self.config_at(z).and_then(|c| (self.model)(&c));
        match r {
            Ok(p) => {
                if let Some(k) = p.iter().position(|x| !x.is_finite()) {
                    *self.error.borrow_mut() = Some(CreepError::Fit(format!(
                        "the model value of point {} is {} at {}",
                        k + 1,
                        p[k],
                        self.describe(z)
                    )));
                    return None;
                }
                let r =
                    DVector::from_iterator(p.len(), p.iter().zip(&self.meas).map(|(m, y)| m - y));
                *self.last.borrow_mut() = Some((z.clone(), r.clone()));
                Some(r)
            }
            Err(e) => {
                *self.error.borrow_mut() = Some(e);
                None
            }
        }
    }
}

impl Problem<'_> {
    fn describe(&self, z: &DVector<f64>) -> String {
        self.free
            .iter()
            .enumerate()
            .map(|(k, id)| format!("{} = {}", id.name(&self.base), self.maps[k].to_p(z[k])))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;
    fn set_params(&mut self, x: &DVector<f64>) {
        self.z.copy_from(x);
    }
    fn params(&self) -> DVector<f64> {
        self.z.clone()
    }
    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals_at(&self.z)
    }
    fn jacobian(&self) -> Option<DMatrix<f64>> {
        // the residuals at the current point: those of the last evaluation when it was at
        // exactly this point (bit for bit), as the model is a function of the point alone
        let cached = self.last.borrow().as_ref().and_then(|(z, r)| {
            let same = z.len() == self.z.len()
                && z.iter()
                    .zip(self.z.iter())
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            same.then(|| r.clone())
        });
        let r0 = match cached {
            Some(r) => r,
            None => self.residuals_at(&self.z)?,
        };
        let mut j = DMatrix::zeros(r0.len(), self.z.len());
        for k in 0..self.z.len() {
            let h = 1e-3 * self.z[k].abs().max(1.0);
            let mut z = self.z.clone();
            z[k] += h;
            let r = self.residuals_at(&z)?;
            j.set_column(k, &((r - &r0) / h));
        }
        Some(j)
    }
}
