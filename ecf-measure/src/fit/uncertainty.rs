//! Standard errors, correlations and the status of each fitted parameter at the optimum.

use super::{FreeParam, ModelFn, ParamStatus};
use creep_core::config::Config;
use creep_core::error::{CreepError, Result};
use nalgebra::DMatrix;

/// Status, standard error and correlations of each parameter, and the model evaluations used.
pub(super) type Uncertainty = (Vec<ParamStatus>, Vec<f64>, Vec<Vec<f64>>, usize);

/// Standard errors and correlations, computed the same way for every kind of parameter: the
/// Jacobian of the model values in parameter units (central differences, one-sided next to a
/// bound) at the optimum, s^2 = RSS/(n - k), covariance s^2 (J^T J)^-1 over the parameters
/// that are neither at a bound nor unidentifiable. At a bound: status AtLower/UpperBound,
/// standard error NaN. Unidentifiable (a zero Jacobian column, or a near-null direction of the
/// column-scaled J^T J, eigenvalue < 1e-10 of the largest): status NotIdentifiable, standard
/// error infinite. Correlations of excluded parameters are NaN.
pub(super) fn uncertainties(
    fitted: &Config,
    meas: &[f64],
    values: &[f64],
    model: ModelFn,
    free: &[FreeParam],
    start: &[f64],
) -> Result<Uncertainty> {
    let m = free.len();
    let mut status = vec![ParamStatus::Determined; m];
    let mut evals = 0;
    let mut cols: Vec<Option<Vec<f64>>> = vec![None; m];
    for (k, id) in free.iter().enumerate() {
        let (lo, hi) = id.bounds(fitted);
        let p = id.get(fitted);
        // the width of a finite interval, unless it is far wider than the values (then the
        // values' magnitude, as for a parameter bounded below only)
        let mag = p.abs().max(start[k].abs()).max(1e-9);
        let scale = if lo.is_finite() && hi.is_finite() && hi - lo < 1e3 * mag {
            hi - lo
        } else {
            mag
        };
        let tol = 1e-4 * scale;
        if p - lo <= tol {
            status[k] = ParamStatus::AtLowerBound;
            continue;
        }
        if hi - p <= tol {
            status[k] = ParamStatus::AtUpperBound;
            continue;
        }
        let h = (1e-3 * p.abs())
            .max(1e-6 * scale)
            .min(0.5 * (p - lo))
            .min(0.5 * (hi - p));
        let eval = |x: f64| -> Result<Vec<f64>> {
            let mut c = fitted.clone();
            id.set(&mut c, x)?;
            model(&c)
                .map_err(|e| CreepError::Fit(format!("uncertainty of {}: {e}", id.name(fitted))))
        };
        let (a, b) = (eval(p - h)?, eval(p + h)?);
        evals += 2;
        cols[k] = Some(a.iter().zip(&b).map(|(a, b)| (b - a) / (2.0 * h)).collect());
    }
    let n = meas.len();
    let rss: f64 = meas
        .iter()
        .zip(values)
        .map(|(a, b)| (a - b) * (a - b))
        .sum();
    let s2 = rss / (n - m) as f64;
    // column norms; zero columns are unidentifiable
    let norm: Vec<f64> = cols
        .iter()
        .map(|c| {
            c.as_ref()
                .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
                .unwrap_or(0.0)
        })
        .collect();
    let big = norm.iter().cloned().fold(0.0, f64::max);
    for k in 0..m {
        if status[k] == ParamStatus::Determined && norm[k] <= 1e-12 * big.max(1e-300) {
            status[k] = ParamStatus::NotIdentifiable;
        }
    }
    // near-null directions of the scaled normal matrix
    loop {
        let act: Vec<usize> = (0..m)
            .filter(|&k| status[k] == ParamStatus::Determined)
            .collect();
        if act.is_empty() {
            break;
        }
        let jn = DMatrix::from_fn(n, act.len(), |i, j| {
            cols[act[j]].as_ref().map(|c| c[i]).unwrap_or(0.0) / norm[act[j]]
        });
        let a = jn.transpose() * &jn;
        let eig = a.clone().symmetric_eigen();
        let lmax = eig.eigenvalues.iter().cloned().fold(0.0, f64::max);
        let (imin, lmin) =
            eig.eigenvalues
                .iter()
                .cloned()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |b, (i, l)| if l < b.1 { (i, l) } else { b },
                );
        if lmin > 1e-10 * lmax {
            break;
        }
        // the parameter with the largest share in the null direction cannot be determined
        let v = eig.eigenvectors.column(imin);
        let (jmax, _) =
            v.iter().enumerate().fold(
                (0, -1.0),
                |b, (j, x)| if x.abs() > b.1 { (j, x.abs()) } else { b },
            );
        status[act[jmax]] = ParamStatus::NotIdentifiable;
    }
    let mut se = vec![f64::NAN; m];
    let mut corr = vec![vec![f64::NAN; m]; m];
    for k in 0..m {
        if status[k] == ParamStatus::NotIdentifiable {
            se[k] = f64::INFINITY;
        }
    }
    let act: Vec<usize> = (0..m)
        .filter(|&k| status[k] == ParamStatus::Determined)
        .collect();
    if !act.is_empty() {
        let jn = DMatrix::from_fn(n, act.len(), |i, j| {
            cols[act[j]].as_ref().map(|c| c[i]).unwrap_or(0.0) / norm[act[j]]
        });
        let a = jn.transpose() * &jn;
        let inv = a.try_inverse().ok_or_else(|| {
            CreepError::Fit("the normal matrix of the determined parameters is singular".into())
        })?;
        for (i, &ki) in act.iter().enumerate() {
            se[ki] = (s2 * inv[(i, i)]).max(0.0).sqrt() / norm[ki];
            for (j, &kj) in act.iter().enumerate() {
                corr[ki][kj] = inv[(i, j)] / (inv[(i, i)] * inv[(j, j)]).sqrt();
            }
        }
    }
    Ok((status, se, corr, evals))
}
