//! Normal contact: exact elliptic Hertz contact (seed Eq. 2.1-2.6) and line contact (Eq. 2.7).

use crate::config::{Config, Geometry};
use crate::error::{check_positive, check_range, CreepError, Result};
use crate::params::P;
use std::f64::consts::PI;

/// Complete elliptic integrals K(e) and E(e) of modulus `e` (0 <= e < 1), by the
/// arithmetic-geometric mean (converges quadratically; ~1e-15 relative).
pub fn elliptic_ke(e: f64) -> (f64, f64) {
    let k2 = e * e;
    let mut a = 1.0;
    let mut b = (1.0 - k2).sqrt();
    let mut c2_sum = 0.5 * k2; // sum 2^(n-1) c_n^2 with c_0^2 = k^2
    let mut pow2 = 0.5;
    for _ in 0..40 {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        let cn = 0.5 * (a - b);
        pow2 *= 2.0;
        c2_sum += pow2 * cn * cn;
        a = an;
        b = bn;
        if cn.abs() < 1e-16 * a {
            break;
        }
    }
    let k = PI / (2.0 * a);
    let ee = k * (1.0 - c2_sum);
    (k, ee)
}

/// Size and peak pressure of a contact patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// Semi-axis in rolling direction x, m.
    pub a: f64,
    /// Semi-axis in lateral direction y, m (for a line contact: half the contact width).
    pub b: f64,
    /// Maximum Hertz pressure, Pa.
    pub p0: f64,
    /// True for a line (2-D) contact: p = p0 sqrt(1 - x^2/a^2), uniform in y.
    pub line: bool,
}

impl Patch {
    /// Elliptic patch from given semi-axes and normal force (Eq. 2.6: p0 = 3 F_N / (2 pi a b)).
    pub fn from_semi_axes(a: f64, b: f64, fn_n: f64) -> Result<Self> {
        check_positive("a", a, "m")?;
        check_positive("b", b, "m")?;
        check_range("F_N", fn_n, 0.0, f64::MAX, "N")?;
        Ok(Patch {
            a,
            b,
            p0: 3.0 * fn_n / (2.0 * PI * a * b),
            line: false,
        })
    }

    /// Normal pressure at (x, y), Pa (Eq. 2.6; line contact: Eq. 2.7).
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let r = if self.line {
            x * x / (self.a * self.a)
        } else {
            x * x / (self.a * self.a) + y * y / (self.b * self.b)
        };
        if r >= 1.0 {
            0.0
        } else {
            self.p0 * (1.0 - r).sqrt()
        }
    }
}

/// Contact modulus E* of two bodies of the same material: 1/E* = 2 (1 - nu^2)/E, E = 2 G (1 + nu).
pub fn contact_modulus(g: f64, nu: f64) -> f64 {
    let e = 2.0 * g * (1.0 + nu);
    e / (2.0 * (1.0 - nu * nu))
}

/// Exact elliptic Hertz solution from the equivalent radii of curvature `rx`, `ry` (m) in
/// rolling and lateral direction (1/R = sum of both bodies' curvatures, Eq. 2.1), normal
/// force `fn_n` (N), shear modulus `g` (Pa) and Poisson's ratio `nu` (Eq. 2.2).
///
/// The seed reads F1(g), F2(g) off a figure; here the eccentricity e solves
/// B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)) (a the major semi-axis, gap = A x^2 + B y^2,
/// A = 1/(2 R_major-direction)), and a^3 = 3 F_N E(e) / (2 pi E* (A + B) (b/a)^2).
pub fn hertz_from_curvatures(rx: f64, ry: f64, fn_n: f64, g: f64, nu: f64) -> Result<Patch> {
    check_positive("R_x", rx, "m")?;
    check_positive("R_y", ry, "m")?;
    check_positive("F_N", fn_n, "N")?;
    let estar = contact_modulus(g, nu);
    let ax = 1.0 / (2.0 * rx);
    let by = 1.0 / (2.0 * ry);
    // Major axis along the direction of smaller gap coefficient.
    let (small, large) = if ax <= by { (ax, by) } else { (by, ax) };
    let ratio = large / small; // >= 1
    let e = if (ratio - 1.0).abs() < 1e-12 {
        0.0
    } else {
        // Bisection on e in (0, 1): h(e) = ((1/(1-e^2)) E - K)/(K - E) increases from 1 to inf.
        let h = |e: f64| {
            let (k, ee) = elliptic_ke(e);
            ((ee / (1.0 - e * e)) - k) / (k - ee)
        };
        let (mut lo, mut hi) = (1e-9_f64, 1.0 - 1e-15);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if h(mid) < ratio {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let (_k, ee) = elliptic_ke(e);
    let kk = (1.0 - e * e).sqrt(); // minor/major
    let major = (3.0 * fn_n * ee / (2.0 * PI * estar * (small + large) * kk * kk)).cbrt();
    let minor = kk * major;
    let (a, b) = if ax <= by {
        (major, minor)
    } else {
        (minor, major)
    };
    Patch::from_semi_axes(a, b, fn_n)
}

/// Line contact of two cylinders (twin-disc) with equivalent radius `r` (m), line load
/// `fn_line` (N/m) and contact width `width` (m) (Eq. 2.7): a = sqrt(4 F' R / (pi E*)),
/// p0 = 2 F' / (pi a).
pub fn line_contact(r: f64, fn_line: f64, width: f64, g: f64, nu: f64) -> Result<Patch> {
    check_positive("R", r, "m")?;
    check_positive("F_N,Line", fn_line, "N/m")?;
    check_positive("width", width, "m")?;
    let estar = contact_modulus(g, nu);
    let a = (4.0 * fn_line * r / (PI * estar)).sqrt();
    Ok(Patch {
        a,
        b: 0.5 * width,
        p0: 2.0 * fn_line / (PI * a),
        line: true,
    })
}

/// Smallest and largest semi-axis of a contact patch, m (1 nm .. 10 m): far outside the
/// wheel-rail and twin-disc range on both sides, and inside the range where the bristle grid,
/// the pressure and the forces stay finite (a semi-axis of 1e300 mm gave NaN forces, one of
/// 1e-300 mm an infinite peak pressure). The floor lies below the half-width of a line
/// contact at the lift-off load [`crate::engine::F_LIFT_OFF`] (about 0.1 um for twin_disc,
/// whose half-width grows like sqrt(F_N)), so every load the engine does not treat as
/// lift-off has a usable patch.
pub const SEMI_AXIS_RANGE_M: (f64, f64) = (1e-9, 10.0);

/// Contact patch of a configuration at a normal force; refuses a patch whose semi-axes lie
/// outside [`SEMI_AXIS_RANGE_M`] or whose peak pressure is not finite, naming the geometry.
pub fn patch_for(cfg: &Config, fn_n: f64) -> Result<Patch> {
    let patch = patch_of_geometry(cfg, fn_n)?;
    let (lo, hi) = SEMI_AXIS_RANGE_M;
    let what = match cfg.geometry {
        Geometry::SemiAxes { .. } => "the semi-axes given (scaled by (F_N/F_N,ref)^(1/3))",
        Geometry::Curvatures { .. } => "Hertz's solution for the radii given",
        Geometry::Line { .. } => "the line contact's radius and width",
    };
    for (name, x) in [
        ("contact semi-axis a (m)", patch.a),
        ("contact semi-axis b (m)", patch.b),
    ] {
        if !(x >= lo && x <= hi) {
            return Err(CreepError::OutOfRange {
                field: name.into(),
                value: x,
                expected: format!(
                    "at F_N = {fn_n} N, from {what}: must be within [{lo:.0e}, {hi}] m ([{:.0e}, {}] mm)",
                    lo * 1e3,
                    hi * 1e3
                ),
            });
        }
    }
    if !patch.p0.is_finite() {
        return Err(CreepError::OutOfRange {
            field: "peak pressure p0 (Pa)".into(),
            value: patch.p0,
            expected: format!("at F_N = {fn_n} N, from {what}: must be finite"),
        });
    }
    Ok(patch)
}

fn patch_of_geometry(cfg: &Config, fn_n: f64) -> Result<Patch> {
    let p = &cfg.params;
    match cfg.geometry {
        Geometry::SemiAxes { a, b, fn_ref } => {
            let s = (fn_n / fn_ref).cbrt();
            Patch::from_semi_axes(a * s, b * s, fn_n)
        }
        Geometry::Curvatures { rx, ry } => {
            hertz_from_curvatures(rx, ry, fn_n, p.si(P::G), p.si(P::Nu))
        }
        Geometry::Line { r, width } => {
            line_contact(r, fn_n / width, width, p.si(P::G), p.si(P::Nu))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elliptic_integrals_known_values() {
        let (k, e) = elliptic_ke(0.0);
        assert!((k - PI / 2.0).abs() < 1e-14 && (e - PI / 2.0).abs() < 1e-14);
        // m = e^2 = 0.5: K = 1.854074677301372, E = 1.350643881047675
        let (k, e) = elliptic_ke(0.5_f64.sqrt());
        assert!((k - 1.854_074_677_301_372).abs() < 1e-12, "K = {k}");
        assert!((e - 1.350_643_881_047_675).abs() < 1e-12, "E = {e}");
    }

    #[test]
    fn seed_check_p0() {
        let p = Patch::from_semi_axes(7.63e-3, 7.88e-3, 110e3).unwrap();
        assert!((p.p0 / 1e9 - 0.874).abs() < 0.001, "p0 = {}", p.p0);
    }

    #[test]
    fn circular_contact_matches_closed_form() {
        let (g, nu) = (79.3e9, 0.28);
        let p = hertz_from_curvatures(0.5, 0.5, 100e3, g, nu).unwrap();
        let a = (3.0 * 100e3 * 0.5 / (4.0 * contact_modulus(g, nu))).cbrt();
        assert!((p.a - a).abs() / a < 1e-9 && (p.b - a).abs() / a < 1e-9);
    }

    #[test]
    fn hertz_force_balance_and_cube_root_scaling() {
        let (g, nu) = (79.3e9, 0.28);
        let p1 = hertz_from_curvatures(0.46, 0.3, 110e3, g, nu).unwrap();
        let p2 = hertz_from_curvatures(0.46, 0.3, 50e3, g, nu).unwrap();
        let s = (50.0_f64 / 110.0).cbrt();
        assert!((p2.a / p1.a - s).abs() < 1e-9 && (p2.b / p1.b - s).abs() < 1e-9);
        // larger radius in x -> longer axis in x
        assert!(p1.a > p1.b);
        // Seed's 50 kN semi-axes are the cube-root scaling of the 110 kN ones.
        assert!((7.63 * s - 5.87).abs() < 0.01 && (7.88 * s - 6.06).abs() < 0.01);
    }
}
