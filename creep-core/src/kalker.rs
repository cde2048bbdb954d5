//! Kalker's creepage coefficients C11, C22, C23 of the linear theory (Kalker 1990, Tab. E.3), embedded.
//!
//! Table lookup: linear in g = min(a/b, b/a) between rows, quadratic (Lagrange) in nu of
//! 1/C through nu = 0, 0.25, 0.5 (the table's own recommendation). Below g = 0.1 Kalker's
//! asymptotic expressions (Kalker 1990, App. E; as implemented in CONTACT's `linrol`,
//! eve70a/CONTACT `src/m_hertz.f90`), see [`asymptotic`], joined continuously to the table
//! at g = 0.1: C(g) = A(g) (1 + d (g / 0.1)^2) with d = T(0.1)/A(0.1) - 1 (|d| <= 6.4 %, C23 for a <= b at nu = 0.5), so
//! that C -> A as g -> 0 (within |d|/4 at g = 0.05, |d|/100 at g = 0.01).
//!
//! The line contact (a twin disc) does not use these coefficients: see
//! [`line_flexibilities`] (Carter's 2-D theory).

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

/// Kalker's asymptotic expressions for slender ellipses (Kalker 1990, App. E), [C11, C22,
/// C23] at g = min(a/b, b/a) -> 0; `a_le_b` for a contact long laterally (g = a/b), else
/// long in the rolling direction (g = b/a), with Lambda = ln(16/g^2):
/// * a <= b: C11 = pi^2/(4(1-nu)), C22 = pi^2/4,
///   C23 = pi sqrt(g)/(3(1-nu)) (1 + nu (ln(16/g) - 5));
/// * a > b: C11 = 2 pi/((Lambda - 2 nu) g) (1 + (3 - ln 4)/(Lambda - 2 nu)),
///   C22 = 2 pi/g (1 + (1-nu)(3 - ln 4)/((1-nu) Lambda + 2 nu))/((1-nu) Lambda + 2 nu),
///   C23 = 2 pi/(3 g^(3/2) ((1-nu) Lambda - 2 + 4 nu)).
pub fn asymptotic(a_le_b: bool, g: f64, nu: f64) -> [f64; 3] {
    if a_le_b {
        [
            PI * PI / (4.0 * (1.0 - nu)),
            PI * PI / 4.0,
            PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
        ]
    } else {
        let al = (16.0 / (g * g)).ln();
        let c = 3.0 - 4.0_f64.ln();
        let d22 = (1.0 - nu) * al + 2.0 * nu;
        [
            2.0 * PI / ((al - 2.0 * nu) * g) * (1.0 + c / (al - 2.0 * nu)),
            2.0 * PI / g * (1.0 + (1.0 - nu) * c / d22) / d22,
            2.0 * PI / (3.0 * g.powf(1.5) * ((1.0 - nu) * al - 2.0 + 4.0 * nu)),
        ]
    }
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
        let t = row(case, 0, nu);
        let a01 = asymptotic(case == 0, 0.1, nu);
        let ag = asymptotic(case == 0, g, nu);
        let w = (g / 0.1) * (g / 0.1);
        let mut c = [0.0; 3];
        for k in 0..3 {
            c[k] = ag[k] * (1.0 + (t[k] / a01[k] - 1.0) * w);
        }
        c
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

/// Flexibilities (L_x, L_y) of the brush on a line contact (a 2-D strip of half-length `a`,
/// m), m/Pa, consistent with Carter's 2-D theory: the brush's initial slope per unit width,
/// 2 a^2 xi / L, equals Carter's pi G a xi / (2 (1 - nu)) for L_x = 4 a (1 - nu)/(pi G);
/// laterally (anti-plane) L_y = 4 a/(pi G), the same limit without (1 - nu) as Kalker's
/// C22 = pi^2/4 against C11 = pi^2/(4(1-nu)) for g -> 0. (Kalker's elliptic flexibility
/// 8a/(3 C11 G) on a rectangle would be 3 pi/8 = 1.18 times too stiff.)
pub fn line_flexibilities(a: f64, g_mod: f64, nu: f64) -> (f64, f64) {
    (4.0 * a * (1.0 - nu) / (PI * g_mod), 4.0 * a / (PI * g_mod))
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
    fn asymptotes_are_continuous_and_tend_to_kalkers_expressions() {
        for nu in [0.0, 0.25, 0.28, 0.5] {
            for (a, b) in [(0.1, 1.0), (1.0, 0.1)] {
                // continuous at the join g = 0.1
                let at = coefficients(a, b, nu).unwrap();
                let below = coefficients(
                    a * if a < b { 0.99999 } else { 1.0 },
                    b * if a < b { 1.0 } else { 0.99999 },
                    nu,
                )
                .unwrap();
                for (x, y) in [
                    (at.c11, below.c11),
                    (at.c22, below.c22),
                    (at.c23, below.c23),
                ] {
                    assert!((x - y).abs() / x < 1e-4, "nu {nu} a {a} b {b}: {x} vs {y}");
                }
            }
            // towards the expressions as g -> 0: within |d| (g/0.1)^2, |d| <= 6.4 %
            for g in [0.05, 0.02, 0.01, 0.001] {
                for a_le_b in [true, false] {
                    let (a, b) = if a_le_b { (g, 1.0) } else { (1.0, g) };
                    let c = coefficients(a, b, nu).unwrap();
                    let e = asymptotic(a_le_b, g, nu);
                    let tol = 0.065 * (g / 0.1) * (g / 0.1) + 1e-12;
                    for (x, y) in [(c.c11, e[0]), (c.c22, e[1]), (c.c23, e[2])] {
                        assert!(
                            (x / y - 1.0).abs() <= tol,
                            "g {g} a<=b {a_le_b} nu {nu}: {x} vs expression {y}"
                        );
                    }
                }
            }
        }
        // Kalker's C11 for a > b at g = 0.01, nu = 0.25 from the expression: 62.4
        let c = coefficients(1.0, 0.01, 0.25).unwrap();
        assert!((c.c11 - 62.42).abs() < 0.05, "{}", c.c11);
        // the expressions meet Kalker's Table E.3 at g = 0.1 within 5.2 % (nu = 0.25)
        for a_le_b in [true, false] {
            let e = asymptotic(a_le_b, 0.1, 0.25);
            let t = if a_le_b {
                [3.31, 2.52, 0.473]
            } else {
                [11.7, 12.8, 14.6]
            };
            for k in 0..3 {
                assert!(
                    (e[k] / t[k] - 1.0).abs() < 0.052,
                    "{a_le_b} {k}: {} vs {}",
                    e[k],
                    t[k]
                );
            }
        }
    }
}
