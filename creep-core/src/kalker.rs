//! Kalker's creepage coefficients C11, C22, C23 of the linear theory (Kalker 1990, Tab. E.3), embedded.
//!
//! Table lookup: linear in g = min(a/b, b/a) between rows, quadratic (Lagrange) in nu of
//! 1/C through nu = 0, 0.25, 0.5 (the table's own recommendation). Below g = 0.1 the
//! asymptotic behaviour of Kalker's theory is used, matched to the table at g = 0.1:
//! * a <= b (contact long laterally), g = a/b -> 0: C11 -> pi^2/(4(1-nu)), C22 -> pi^2/4,
//!   approached like 1/ln(16/g^2); C23 ~ pi sqrt(g)/(3(1-nu)) times the table's ratio at 0.1.
//! * a > b (contact long in rolling direction), g = b/a -> 0: C11, C22 ~ 1/(g ln(16/g^2)) and
//!   C23 ~ g^k with k the log-slope of the table between g = 0.1 and 0.2.
//!
//! These asymptotic forms are documented in `docs/model.md`; inside the table (0.1 <= g <= 1)
//! the result is the interpolated table.

use crate::error::{check_range, Result};
use std::f64::consts::PI;
use std::sync::OnceLock;

const CSV: &str = include_str!("../data/kalker_coefficients.csv");
const NUS: [f64; 3] = [0.0, 0.25, 0.5];

/// Kalker's three creepage coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KalkerCoefficients {
    /// Longitudinal creepage coefficient C11.
    pub c11: f64,
    /// Lateral creepage coefficient C22.
    pub c22: f64,
    /// Spin-lateral coupling coefficient C23.
    pub c23: f64,
}

struct Table {
    /// [case][g index][nu index] -> (C11, C22, C23); case 0: a <= b, 1: a > b.
    rows: [[[[f64; 3]; 3]; 10]; 2],
}

fn table() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| {
        let mut rows = [[[[f64::NAN; 3]; 3]; 10]; 2];
        for line in CSV.lines() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with("case") {
                continue;
            }
            let f: Vec<&str> = line.split(',').collect();
            // The file is embedded at compile time and checked by a unit test.
            let case = if f[0] == "a_le_b" { 0 } else { 1 };
            let num = |i: usize| f[i].trim().parse::<f64>().unwrap_or(f64::NAN);
            let gi = ((num(1) * 10.0).round() as usize).saturating_sub(1).min(9);
            let ni = ((num(2) * 4.0).round() as usize).min(2);
            rows[case][gi][ni] = [num(3), num(4), num(5)];
        }
        Table { rows }
    })
}

/// Quadratic Lagrange interpolation of 1/C in nu through the three table values.
fn interp_nu(c: [f64; 3], nu: f64) -> f64 {
    let y = [1.0 / c[0], 1.0 / c[1], 1.0 / c[2]];
    let (x0, x1, x2) = (NUS[0], NUS[1], NUS[2]);
    let l0 = (nu - x1) * (nu - x2) / ((x0 - x1) * (x0 - x2));
    let l1 = (nu - x0) * (nu - x2) / ((x1 - x0) * (x1 - x2));
    let l2 = (nu - x0) * (nu - x1) / ((x2 - x0) * (x2 - x1));
    1.0 / (y[0] * l0 + y[1] * l1 + y[2] * l2)
}

/// Table value at row `gi` (g = 0.1 (gi + 1)) for `case`, interpolated in nu.
fn row(case: usize, gi: usize, nu: f64) -> [f64; 3] {
    let t = table();
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let c = [
            t.rows[case][gi][0][k],
            t.rows[case][gi][1][k],
            t.rows[case][gi][2][k],
        ];
        *o = interp_nu(c, nu);
    }
    out
}

fn lambda(g: f64) -> f64 {
    (16.0 / (g * g)).ln()
}

/// Kalker's coefficients for semi-axes `a` (rolling direction) and `b` (lateral), and
/// Poisson's ratio `nu` in [0, 0.5].
pub fn coefficients(a: f64, b: f64, nu: f64) -> Result<KalkerCoefficients> {
    check_range("a", a, f64::MIN_POSITIVE, f64::MAX, "m")?;
    check_range("b", b, f64::MIN_POSITIVE, f64::MAX, "m")?;
    check_range("nu", nu, 0.0, 0.5, "-")?;
    let (case, g) = if a <= b { (0, a / b) } else { (1, b / a) };
    let c = if g >= 0.1 {
        let x = (g * 10.0 - 1.0).clamp(0.0, 9.0);
        let i = (x.floor() as usize).min(8);
        let w = x - i as f64;
        let lo = row(case, i, nu);
        let hi = row(case, i + 1, nu);
        [
            lo[0] + w * (hi[0] - lo[0]),
            lo[1] + w * (hi[1] - lo[1]),
            lo[2] + w * (hi[2] - lo[2]),
        ]
    } else {
        let r1 = row(case, 0, nu);
        if case == 0 {
            let lim11 = PI * PI / (4.0 * (1.0 - nu));
            let lim22 = PI * PI / 4.0;
            let s = lambda(0.1) / lambda(g);
            let c23_0 = PI * 0.1_f64.sqrt() / (3.0 * (1.0 - nu));
            [
                lim11 + (r1[0] - lim11) * s,
                lim22 + (r1[1] - lim22) * s,
                r1[2] / c23_0 * PI * g.sqrt() / (3.0 * (1.0 - nu)),
            ]
        } else {
            let r2 = row(case, 1, nu);
            let s = (0.1 * lambda(0.1)) / (g * lambda(g));
            let k23 = (r2[2] / r1[2]).ln() / 2.0_f64.ln();
            [r1[0] * s, r1[1] * s, r1[2] * (g / 0.1).powf(k23)]
        }
    };
    Ok(KalkerCoefficients {
        c11: c[0],
        c22: c[1],
        c23: c[2],
    })
}

/// Flexibilities of Kalker's simplified theory (model-spec §2): L_x = 8a/(3 C11 G),
/// L_y = 8a/(3 C22 G), L_s = pi a sqrt(a/b)/(4 C23 G), in m/Pa.
pub fn flexibilities(a: f64, b: f64, g_mod: f64, c: &KalkerCoefficients) -> (f64, f64, f64) {
    let lx = 8.0 * a / (3.0 * c.c11 * g_mod);
    let ly = 8.0 * a / (3.0 * c.c22 * g_mod);
    let ls = PI * a * (a / b).sqrt() / (4.0 * c.c23 * g_mod);
    (lx, ly, ls)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_complete_and_reproduced_at_nodes() {
        let t = table();
        for case in t.rows.iter() {
            for g in case.iter() {
                for n in g.iter() {
                    assert!(n.iter().all(|v| v.is_finite() && *v > 0.0));
                }
            }
        }
        let c = coefficients(1.0, 1.0, 0.25).unwrap();
        assert!(
            (c.c11 - 4.12).abs() < 1e-9
                && (c.c22 - 3.67).abs() < 1e-9
                && (c.c23 - 1.47).abs() < 1e-9
        );
        let c = coefficients(0.5, 1.0, 0.5).unwrap();
        assert!((c.c11 - 4.83).abs() < 1e-9);
        let c = coefficients(1.0, 0.3, 0.0).unwrap();
        assert!((c.c11 - 5.57).abs() < 1e-9 && (c.c23 - 3.79).abs() < 1e-9);
    }

    #[test]
    fn interpolation_is_between_neighbours() {
        let c = coefficients(7.63, 7.88, 0.28).unwrap();
        assert!(c.c11 > 4.01 && c.c11 < 4.3, "{c:?}");
        let lo = coefficients(1.0, 0.9, 0.28).unwrap().c11;
        let hi = coefficients(1.0, 0.8, 0.28).unwrap().c11;
        let mid = coefficients(1.0, 0.85, 0.28).unwrap().c11;
        assert!(mid > lo && mid < hi);
    }

    #[test]
    fn asymptotes_are_continuous_and_tend_to_limits() {
        for nu in [0.0, 0.28, 0.5] {
            for (a, b) in [(0.1, 1.0), (1.0, 0.1)] {
                let at = coefficients(a, b, nu).unwrap();
                let below = coefficients(
                    a * if a < b { 0.9999 } else { 1.0 },
                    b * if a < b { 1.0 } else { 0.9999 },
                    nu,
                )
                .unwrap();
                assert!((at.c11 - below.c11).abs() / at.c11 < 1e-3, "{nu} {a} {b}");
                assert!((at.c23 - below.c23).abs() / at.c23 < 1e-3);
            }
            let tiny = coefficients(1e-8, 1.0, nu).unwrap();
            let lim = PI * PI / (4.0 * (1.0 - nu));
            assert!(
                (tiny.c11 - lim).abs() / lim < 0.01,
                "{} vs {}",
                tiny.c11,
                lim
            );
            assert!(tiny.c23 < 1e-3);
            let long = coefficients(1.0, 0.01, nu).unwrap();
            assert!(long.c11 > coefficients(1.0, 0.1, nu).unwrap().c11);
        }
    }
}
