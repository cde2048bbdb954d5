//! The noise level of a measurement file, estimated from the data alone: from repeated operating points, else from the residuals of a local smooth fit along each curve.
//!
//! Repeated operating points (rows equal in everything but the measured value) give the
//! pooled standard deviation within the repeats directly; five degrees of freedom or more
//! are needed. Otherwise each curve (steady rows of one series, condition, speed and load,
//! ordered by creepage; time series ordered by time) is followed by a local cubic: every
//! inner point is predicted from its two neighbours on either side (Lagrange cubic in
//! asinh(c_x / 0.001), i.e. about ln c_x above 0.1 %, or in time) and the prediction error
//! scaled by its own noise factor. The median of the squared scaled errors divided by 0.4549
//! (the median of a squared standard normal) is the noise variance: the median passes over
//! the few points of the steep rise where the curve itself bends faster than a cubic
//! follows.

use crate::measure::Dataset;
use crate::stats::{cv_pct, mean, median};

/// Median of a squared standard normal variate.
const MEDIAN_CHI2_1: f64 = 0.454_936_4;

/// Degrees of freedom (repeats) or scaled errors (curves) needed for an estimate.
pub const MIN_DOF: usize = 5;

/// An estimate of the noise of the measured traction coefficient.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Noise {
    /// Standard deviation of the measured traction coefficient, - (F_x/F_N).
    pub sd_f: f64,
    /// The same as a CV(RMSE), %: what a perfect model would score (100 sd / mean f).
    pub cv_rmse_pct: f64,
    /// How it was estimated, in words.
    pub method: String,
    /// Degrees of freedom (repeats) or number of scaled errors (curves) behind it.
    pub dof: usize,
}

/// Estimates the noise of `data`; `None` when the file has neither enough repeats nor curves
/// of five points or more.
pub fn estimate(data: &Dataset) -> Option<Noise> {
    let mean_f = mean(&data.rows.iter().map(|r| r.f).collect::<Vec<_>>());
    let cv = |sd: f64| cv_pct(sd, mean_f);
    if let Some((sd, dof)) = repeats(data) {
        return Some(Noise {
            sd_f: sd,
            cv_rmse_pct: cv(sd),
            method: format!("repeated operating points ({dof} degrees of freedom)"),
            dof,
        });
    }
    let (sd, n) = along_curves(data)?;
    Some(Noise {
        sd_f: sd,
        cv_rmse_pct: cv(sd),
        method: format!("a local cubic along each curve ({n} points)"),
        dof: n,
    })
}

/// Pooled standard deviation within repeated steady operating points, with its degrees of
/// freedom (at least [`MIN_DOF`]).
fn repeats(data: &Dataset) -> Option<(f64, usize)> {
    let mut groups: std::collections::HashMap<Vec<u64>, Vec<f64>> = Default::default();
    for r in data.rows.iter().filter(|r| r.t.is_none()) {
        let mut key = vec![
            r.cx.to_bits(),
            r.cy.to_bits(),
            r.spin.to_bits(),
            r.v.to_bits(),
            r.fn_n.to_bits(),
            r.t_bulk.to_bits(),
        ];
        key.extend(r.extra.iter().map(|x| x.to_bits()));
        key.extend(r.condition.bytes().map(u64::from));
        groups.entry(key).or_default().push(r.f);
    }
    let (mut ss, mut dof) = (0.0, 0);
    for g in groups.values().filter(|g| g.len() > 1) {
        let m = mean(g);
        ss += g.iter().map(|y| (y - m) * (y - m)).sum::<f64>();
        dof += g.len() - 1;
    }
    (dof >= MIN_DOF).then(|| ((ss / dof as f64).sqrt(), dof))
}

/// Median-based noise from leave-one-out cubic predictions along each curve, with the number
/// of scaled errors (at least [`MIN_DOF`]).
fn along_curves(data: &Dataset) -> Option<(f64, usize)> {
    type Curve = Vec<(f64, f64)>;
    let mut curves: Vec<(String, Curve)> = Vec::new();
    for r in &data.rows {
        let (key, x) = match r.t {
            Some(t) => (format!("t|{}", r.series), t),
            None => (
                format!(
                    "s|{}|{}|{}|{}|{}",
                    r.series,
                    r.condition,
                    r.v.to_bits(),
                    r.fn_n.to_bits(),
                    r.t_bulk.to_bits()
                ),
                (r.cx / 1e-3).asinh(),
            ),
        };
        match curves.iter_mut().find(|(k, _)| *k == key) {
            Some((_, c)) => c.push((x, r.f)),
            None => curves.push((key, vec![(x, r.f)])),
        }
    }
    let mut e2 = Vec::new();
    for (_, mut c) in curves {
        c.sort_by(|a, b| a.0.total_cmp(&b.0));
        // repeated abscissae: averaged would change the noise; keep distinct ones only
        c.dedup_by(|a, b| a.0 == b.0);
        for i in 2..c.len().saturating_sub(2) {
            let x0 = c[i].0;
            let nb = [c[i - 2], c[i - 1], c[i + 1], c[i + 2]];
            let mut pred = 0.0;
            let mut w2 = 0.0;
            for (j, (xj, yj)) in nb.iter().enumerate() {
                let w: f64 = nb
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| *k != j)
                    .map(|(_, (xk, _))| (x0 - xk) / (xj - xk))
                    .product();
                pred += w * yj;
                w2 += w * w;
            }
            let e = (c[i].1 - pred) / (1.0 + w2).sqrt();
            if e.is_finite() {
                e2.push(e * e);
            }
        }
    }
    if e2.len() < MIN_DOF {
        return None;
    }
    let n = e2.len();
    Some(((median(&mut e2) / MEDIAN_CHI2_1).sqrt(), n))
}
