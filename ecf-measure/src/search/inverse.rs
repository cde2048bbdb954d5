//! The factor on a target that brings the model onto each measured row: a one-dimensional solve per row, all rows at once, with the traction coefficient's slope in it.
//!
//! For a configuration and a target (a layer strength, both strengths, L_p, L_e or mu), row
//! i's log-factor lam_i solves f_model(row i; target x exp(lam_i)) = f_i. The solve runs on
//! every row at once: the factor is a formula effect `exp(COLUMN)` of a data column that
//! holds each row's current lam, so each iteration is one prediction of the whole file
//! (secant steps from lam = 0 and lam = [`H`], at most [`MAX_STEP`] per iteration, within
//! +-[`LAM_MAX`]). The slope s_i = df/dlam at the solution weighs the row: where f barely
//! depends on the target, the row says little about the factor. A row whose measurement the
//! factor cannot reach keeps the bound and what is left there (`miss`).

use crate::evaluate::predict_with;
use crate::measure::Dataset;
use creep_core::config::Config;
use creep_core::error::Result;
use creep_core::formula::{FormulaEffect, Target};

/// The data column that carries each row's log-factor during the solve.
const COLUMN: &str = "ecf_search_log_factor";

/// Largest |lam|: factors between 1/5 and 5.
pub(crate) const LAM_MAX: f64 = 1.609_437_912_434_100_3;

/// Step of the first secant and of the slope at the solution.
const H: f64 = 0.05;

/// Largest change of lam per iteration.
const MAX_STEP: f64 = 0.7;

/// Secant iterations after the first slope.
const ITERATIONS: usize = 6;

/// A row converges when the model is this close to the measurement (traction coefficient).
const F_TOL: f64 = 2e-5;

/// Rows whose slope is below this (traction coefficient per unit lam) carry no weight.
const MIN_SLOPE: f64 = 1e-4;

/// The solve's result, one entry per row.
#[derive(Clone, Debug, Default)]
pub(crate) struct Inverse {
    /// Log-factor, -.
    pub lam: Vec<f64>,
    /// Slope df/dlam there, -.
    pub sens: Vec<f64>,
    /// What is left there, f_model - f (0 where the solve converged).
    pub miss: Vec<f64>,
    /// The configuration's own miss, f_model - f at lam = 0.
    pub base_miss: Vec<f64>,
    /// Model runs over the whole file.
    pub predictions: usize,
}

/// Solves for every row's log-factor on `target` under `cfg`.
pub(crate) fn solve(
    cfg: &Config,
    data: &Dataset,
    target: Target,
    threads: usize,
) -> Result<Inverse> {
    let fe = FormulaEffect::new(
        "ecf_search_factor",
        target,
        &format!("exp({COLUMN})"),
        vec![],
    )?;
    let mut c = cfg.clone();
    c.modifiers.push(creep_core::AnyModifier::Formula(fe));
    let meas: Vec<f64> = data.rows.iter().map(|r| r.f).collect();
    let n = meas.len();
    // the file with the log-factor column, whose values each run sets
    let mut d = data.clone();
    d.extra_names.push(COLUMN.to_string());
    for r in d.rows.iter_mut() {
        r.extra.push(0.0);
    }
    let mut predictions = 0;
    let mut model = |lam: &[f64]| -> Result<Vec<f64>> {
        predictions += 1;
        for (r, l) in d.rows.iter_mut().zip(lam) {
            if let Some(x) = r.extra.last_mut() {
                *x = *l;
            }
        }
        Ok(predict_with(&c, &d, threads, None)?
            .iter()
            .map(|p| p.f)
            .collect())
    };
    let zero = vec![0.0; n];
    let f0 = model(&zero)?;
    let fh = model(&vec![H; n])?;
    let mut slope: Vec<f64> = (0..n).map(|i| (fh[i] - f0[i]) / H).collect();
    let (mut l1, mut f1) = (zero, f0.clone());
    let done = |f: f64, m: f64, l: f64, s: f64| {
        (f - m).abs() < F_TOL
            || s.abs() < MIN_SLOPE
            || (l >= LAM_MAX && (f - m) * s < 0.0)
            || (l <= -LAM_MAX && (f - m) * s > 0.0)
    };
    for _ in 0..ITERATIONS {
        if (0..n).all(|i| done(f1[i], meas[i], l1[i], slope[i])) {
            break;
        }
        let next: Vec<f64> = (0..n)
            .map(|i| {
                if done(f1[i], meas[i], l1[i], slope[i]) {
                    return l1[i];
                }
                let step = (-(f1[i] - meas[i]) / slope[i]).clamp(-MAX_STEP, MAX_STEP);
                (l1[i] + step).clamp(-LAM_MAX, LAM_MAX)
            })
            .collect();
        let fnext = model(&next)?;
        for i in 0..n {
            if next[i] != l1[i] {
                let s = (fnext[i] - f1[i]) / (next[i] - l1[i]);
                // keep the last slope where the secant is flat or of the wrong sign
                if s.is_finite() && s * slope[i] > 0.0 {
                    slope[i] = s;
                }
            }
        }
        l1 = next;
        f1 = fnext;
    }
    // the slope at the solution, by a central difference
    let up: Vec<f64> = l1.iter().map(|l| l + H).collect();
    let dn: Vec<f64> = l1.iter().map(|l| l - H).collect();
    let (fu, fd) = (model(&up)?, model(&dn)?);
    let sens: Vec<f64> = (0..n)
        .map(|i| {
            let s = (fu[i] - fd[i]) / (2.0 * H);
            if s.abs() < MIN_SLOPE {
                0.0
            } else {
                s
            }
        })
        .collect();
    let miss: Vec<f64> = (0..n).map(|i| f1[i] - meas[i]).collect();
    let base_miss: Vec<f64> = (0..n).map(|i| f0[i] - meas[i]).collect();
    Ok(Inverse {
        lam: l1,
        sens,
        miss,
        base_miss,
        predictions,
    })
}
