//! The shapes a searched form may take: one- and two-parameter factors of one variable, as formula text and as the log-factor the screening regression fits.
//!
//! Every shape is written in the variable's standardised value z = (X - r)/s, with r the mean
//! and s the standard deviation of X over the data (four significant digits, as written into
//! the configuration), so that its parameters have the same meaning for every variable. Each
//! shape contains "no effect" (factor 1) at a parameter value inside its bounds, so a form
//! never fits worse than the configuration without it.

/// A variable a form may depend on.
#[derive(Clone, Debug)]
pub(crate) struct Var {
    /// Name in the formula (`v_mps`, `abs(cx)`, a data column, ...).
    pub expr: String,
    /// Mean over the data (four significant digits).
    pub r: f64,
    /// Standard deviation over the data (four significant digits).
    pub s: f64,
    /// Smallest value over the data (four significant digits).
    pub min: f64,
    /// Every value > 0.
    pub positive: bool,
    /// The value of each row.
    pub x: Vec<f64>,
}

/// Four significant digits: the reference values are written into the configuration.
pub(crate) fn sig4(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        v
    } else {
        let e = 10f64.powi(3 - v.abs().log10().floor() as i32);
        (v * e).round() / e
    }
}

/// Floor of the linear shapes' factor (a strength never falls to 0).
const FLOOR: f64 = 0.01;

/// Width of the logistic step, in standard deviations of the variable.
const STEP_WIDTH: f64 = 0.25;

/// A shape of the factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    /// `max(1 + k z, 0.01)`.
    Linear,
    /// `1 / max(1 + k z, 0.01)`.
    Reciprocal,
    /// `exp(-k z)`.
    Exp,
    /// `(X / r)^k`, for a positive variable.
    Power,
    /// `max(1 + a (1 - exp(-max(X - min, 0) / (b s))), 0.01)`: a change by the fraction `a`
    /// that saturates over `b` standard deviations above the smallest value of the data
    /// (flat below it).
    Saturating,
    /// `max(1 + a / (1 + exp(-(z - c) / 0.25)), 0.01)`: a change by the fraction `a` above a
    /// threshold at `c` standard deviations from the mean, over a quarter of a standard
    /// deviation.
    Step,
}

impl Shape {
    /// Every shape, one-parameter ones first.
    pub const ALL: [Shape; 6] = [
        Shape::Linear,
        Shape::Reciprocal,
        Shape::Exp,
        Shape::Power,
        Shape::Saturating,
        Shape::Step,
    ];

    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Linear => "linear",
            Shape::Reciprocal => "reciprocal",
            Shape::Exp => "exp",
            Shape::Power => "power",
            Shape::Saturating => "saturating",
            Shape::Step => "step",
        }
    }

    /// The parameters: (name, lower bound, upper bound, value of "no effect").
    pub fn params(self) -> &'static [(&'static str, f64, f64, f64)] {
        match self {
            Shape::Linear | Shape::Reciprocal | Shape::Exp | Shape::Power => {
                &[("k", -3.0, 3.0, 0.0)]
            }
            Shape::Saturating => &[("a", -0.95, 3.0, 0.0), ("b", 0.05, 10.0, 1.0)],
            Shape::Step => &[("a", -0.95, 3.0, 0.0), ("c", -2.5, 2.5, 0.0)],
        }
    }

    /// Whether the shape applies to `v` (a power needs a positive variable).
    pub fn applies(self, v: &Var) -> bool {
        self != Shape::Power || (v.positive && v.r > 0.0)
    }

    /// The factor as formula text, in the parameters' names.
    pub fn factor(self, v: &Var) -> String {
        let (x, r, s, m) = (&v.expr, v.r, v.s, v.min);
        let z = format!("({x} - {r}) / {s}");
        match self {
            Shape::Linear => format!("max(1 + k * {z}, {FLOOR})"),
            Shape::Reciprocal => format!("1 / max(1 + k * {z}, {FLOOR})"),
            Shape::Exp => format!("exp(-k * {z})"),
            Shape::Power => format!("(max({x}, {}) / {r}) ^ k", r / 100.0),
            Shape::Saturating => {
                format!("max(1 + a * (1 - exp(-max({x} - {m}, 0) / (b * {s}))), {FLOOR})")
            }
            Shape::Step => {
                format!("max(1 + a / (1 + exp(-({z} - c) / {STEP_WIDTH})), {FLOOR})")
            }
        }
    }

    /// The smallest and the largest factor over the data's values of `v` with parameters `p`.
    pub fn factor_range(self, v: &Var, p: &[f64]) -> [f64; 2] {
        v.x.iter()
            .map(|&x| self.ln_factor(v, x, p).exp())
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], g| {
                [lo.min(g), hi.max(g)]
            })
    }

    /// ln of the factor at `x` with parameters `p`, as [`Shape::factor`] computes it.
    pub fn ln_factor(self, v: &Var, x: f64, p: &[f64]) -> f64 {
        let z = (x - v.r) / v.s;
        let g = match self {
            Shape::Linear => (1.0 + p[0] * z).max(FLOOR),
            Shape::Reciprocal => 1.0 / (1.0 + p[0] * z).max(FLOOR),
            Shape::Exp => return -p[0] * z,
            Shape::Power => return p[0] * (x.max(v.r / 100.0) / v.r).ln(),
            Shape::Saturating => {
                let u = (x - v.min).max(0.0) / (p[1] * v.s);
                (1.0 + p[0] * (1.0 - (-u).exp())).max(FLOOR)
            }
            Shape::Step => (1.0 + p[0] / (1.0 + (-(z - p[1]) / STEP_WIDTH).exp())).max(FLOOR),
        };
        g.ln()
    }
}

/// The screening's linearised model of a fold. Row i misses the measurement by
/// `miss[i] + sens[i] (c + ln g(x[i]) - lam[i])` in the traction coefficient, where `lam[i]`
/// is the log-factor that brings the model onto the measurement, `sens[i]` the traction
/// coefficient's slope in it, `miss[i]` what is left at `lam[i]` (0 unless the factor was out
/// of reach) and `c` the target's level, which stands in for the refit of its parameters.
pub(crate) struct Rows<'a> {
    pub lam: &'a [f64],
    pub sens: &'a [f64],
    pub miss: &'a [f64],
}

impl Rows<'_> {
    /// Row `i`'s miss at log-factor `l` and level `c`.
    fn residual(&self, i: usize, l: f64, c: f64) -> f64 {
        self.miss[i] + self.sens[i] * (c + l - self.lam[i])
    }
}

/// A shape fitted to some rows: its parameters and the level.
#[derive(Clone, Debug)]
pub(crate) struct Fitted {
    pub p: Vec<f64>,
    pub level: f64,
}

/// The level that minimises the sum of squares of rows `idx` with the shape at `p`, and that
/// sum.
fn profile(shape: Shape, v: &Var, rows: &Rows, idx: &[usize], p: &[f64]) -> (f64, f64) {
    let l: Vec<f64> = idx.iter().map(|&i| shape.ln_factor(v, v.x[i], p)).collect();
    let (mut num, mut den) = (0.0, 0.0);
    for (&i, li) in idx.iter().zip(&l) {
        num += rows.residual(i, *li, 0.0) * rows.sens[i];
        den += rows.sens[i] * rows.sens[i];
    }
    let c = if den > 0.0 { -num / den } else { 0.0 };
    let ss = idx
        .iter()
        .zip(&l)
        .map(|(&i, li)| rows.residual(i, *li, c).powi(2))
        .sum();
    (c, ss)
}

/// Fits `shape` in `v` to rows `idx`: a grid over the parameters' bounds, then golden-section
/// refinement of one parameter at a time around the best grid point.
pub(crate) fn fit(shape: Shape, v: &Var, rows: &Rows, idx: &[usize]) -> Fitted {
    let spec = shape.params();
    let eval = |p: &[f64]| profile(shape, v, rows, idx, p).1;
    let n = if spec.len() == 1 { 61 } else { 21 };
    let axis = |k: usize| -> Vec<f64> {
        let (lo, hi, none) = (spec[k].1, spec[k].2, spec[k].3);
        let mut a: Vec<f64> = (0..n)
            .map(|j| lo + (hi - lo) * j as f64 / (n - 1) as f64)
            .collect();
        a.push(none);
        a
    };
    let mut best = spec.iter().map(|q| q.3).collect::<Vec<_>>();
    let mut best_ss = eval(&best);
    if spec.len() == 1 {
        for a in axis(0) {
            let ss = eval(&[a]);
            if ss < best_ss {
                (best, best_ss) = (vec![a], ss);
            }
        }
    } else {
        for a in axis(0) {
            for b in axis(1) {
                let ss = eval(&[a, b]);
                if ss < best_ss {
                    (best, best_ss) = (vec![a, b], ss);
                }
            }
        }
    }
    // golden-section refinement, one parameter at a time, within a grid cell either side
    for _sweep in 0..if spec.len() == 1 { 1 } else { 3 } {
        for k in 0..spec.len() {
            let (lo, hi) = (spec[k].1, spec[k].2);
            let h = (hi - lo) / (n - 1) as f64;
            let (mut a, mut b) = ((best[k] - h).max(lo), (best[k] + h).min(hi));
            let g = (5f64.sqrt() - 1.0) / 2.0;
            let at = |t: f64, best: &[f64]| {
                let mut p = best.to_vec();
                p[k] = t;
                eval(&p)
            };
            for _ in 0..30 {
                let (x1, x2) = (b - g * (b - a), a + g * (b - a));
                if at(x1, &best) < at(x2, &best) {
                    b = x2;
                } else {
                    a = x1;
                }
            }
            let t = 0.5 * (a + b);
            let ss = at(t, &best);
            if ss < best_ss {
                best[k] = t;
                best_ss = ss;
            }
        }
    }
    let level = profile(shape, v, rows, idx, &best).0;
    Fitted { p: best, level }
}

/// The residuals of rows `idx` under a fitted shape.
pub(crate) fn residuals(shape: Shape, v: &Var, rows: &Rows, idx: &[usize], f: &Fitted) -> Vec<f64> {
    idx.iter()
        .map(|&i| rows.residual(i, shape.ln_factor(v, v.x[i], &f.p), f.level))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn var(x: Vec<f64>) -> Var {
        let n = x.len() as f64;
        let r = x.iter().sum::<f64>() / n;
        let s = (x.iter().map(|v| (v - r).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        Var {
            expr: "X".into(),
            r,
            s,
            min: x.iter().copied().fold(f64::INFINITY, f64::min),
            positive: x.iter().all(|v| *v > 0.0),
            x,
        }
    }

    #[test]
    fn every_shape_has_no_effect_inside_its_bounds() {
        let v = var(vec![1.0, 2.0, 5.0]);
        for s in Shape::ALL {
            let none: Vec<f64> = s.params().iter().map(|q| q.3).collect();
            for q in s.params() {
                assert!(q.1 <= q.3 && q.3 <= q.2, "{s:?}");
            }
            for x in [1.0, 2.0, 5.0] {
                assert_eq!(s.ln_factor(&v, x, &none), 0.0, "{s:?}");
            }
        }
    }

    #[test]
    fn the_screening_fit_recovers_a_saturating_truth_and_prefers_it() {
        // rows whose needed log-factor is a saturating shape of X plus a level: the saturating
        // fit finds it to the last digits, a linear one misses
        let x: Vec<f64> = (0..40).map(|i| 0.15 * i as f64).collect();
        let v = var(x.clone());
        let truth = [-0.4, 0.8];
        let lam: Vec<f64> = x
            .iter()
            .map(|&xi| 0.1 + Shape::Saturating.ln_factor(&v, xi, &truth))
            .collect();
        let sens = vec![0.3; x.len()];
        let miss = vec![0.0; x.len()];
        let rows = Rows {
            lam: &lam,
            sens: &sens,
            miss: &miss,
        };
        let idx: Vec<usize> = (0..x.len()).collect();
        let f = fit(Shape::Saturating, &v, &rows, &idx);
        assert!((f.p[0] - truth[0]).abs() < 1e-3, "{:?}", f.p);
        assert!((f.p[1] - truth[1]).abs() < 1e-2, "{:?}", f.p);
        assert!((f.level - 0.1).abs() < 1e-3, "{}", f.level);
        let lin = fit(Shape::Linear, &v, &rows, &idx);
        let ss = |s: Shape, f: &Fitted| -> f64 {
            residuals(s, &v, &rows, &idx, f).iter().map(|r| r * r).sum()
        };
        let (ss_sat, ss_lin) = (ss(Shape::Saturating, &f), ss(Shape::Linear, &lin));
        assert!(ss_lin > 100.0 * ss_sat.max(1e-12), "{ss_lin} vs {ss_sat}");
    }

    #[test]
    fn the_formula_text_computes_the_screened_factor() {
        let v = var(vec![3.0, 4.5, 7.0, 9.0]);
        for s in Shape::ALL {
            let p: Vec<f64> = s.params().iter().map(|q| 0.3 * q.1 + 0.7 * q.2).collect();
            let names: Vec<creep_core::formula::FormulaParam> = s
                .params()
                .iter()
                .zip(&p)
                .map(|(q, val)| creep_core::formula::FormulaParam {
                    name: q.0.into(),
                    value: *val,
                    min: q.1,
                    max: q.2,
                })
                .collect();
            let text = s.factor(&v).replace("X", "xcol");
            let fe = creep_core::formula::FormulaEffect::new(
                "t",
                creep_core::formula::Target::TauC2,
                &text,
                names,
            )
            .unwrap();
            for x in [3.0, 5.0, 9.0] {
                let op = creep_core::modifier::OperatingPoint {
                    v_mps: 1.0,
                    fn_kn: 1.0,
                    cx: 0.0,
                    cy: 0.0,
                    spin_per_m: 0.0,
                    t_bulk_c: 20.0,
                    columns: &[],
                };
                use creep_core::Modifier;
                let g = fe.factor(&creep_core::modifier::LocalState::default(), &op, &[x]);
                let want = s.ln_factor(&v, x, &p).exp();
                assert!(
                    (g - want).abs() < 1e-12 * want,
                    "{s:?} at {x}: {g} vs {want}"
                );
            }
        }
    }
}
