//! Agreement with published contact mechanics at the edges: Carter's 2-D theory for the line contact, the brush's closed form, and the signs of Kalker's linear theory under c_y and spin.
use crate::common::*;
use creep_core::{engine, kalker, Geometry, Inputs};
use std::f64::consts::PI;

/// G and nu of the presets (seed Tab. 4.1): 79.3 GPa... read from the configuration.
fn g_nu(cfg: &creep_core::Config) -> (f64, f64) {
    use creep_core::params::P;
    (cfg.params.si(P::G), cfg.params.si(P::Nu))
}

/// FASTSIM on a line contact (twin-disc geometry: R = 11.75 mm, 10 mm wide), nx cells.
fn fastsim_line(nx: usize) -> creep_core::Config {
    let mut cfg = with_grid(preset("fastsim"), nx, 1);
    cfg.geometry = Geometry::Line {
        r: 11.75e-3,
        width: 10e-3,
    };
    cfg
}

/// Carter (1926), 2-D rolling of cylinders; Johnson, Contact Mechanics (1985), Eq. 8.26:
/// for small creepage the tangential force per unit width is Q' = pi a G xi / (2 (1 - nu)),
/// i.e. pi G a b xi / (1 - nu) on a strip of width 2b.
#[test]
fn line_contact_slope_is_carters() {
    let cfg = fastsim_line(400);
    let (g, nu) = g_nu(&cfg);
    let fn_n = 20e3;
    let patch = engine::patch_for(&cfg, fn_n).unwrap();
    let xi = 1e-7;
    let o = steady(
        &cfg,
        &Inputs {
            cx: xi,
            v: 5.0,
            fn_n,
            ..Inputs::default()
        },
    );
    let carter = PI * g * patch.a * patch.b * xi / (1.0 - nu);
    let rel = (o.fx - carter) / carter;
    assert!(
        rel.abs() < 0.005,
        "F_x = {} N vs Carter {} N ({:+.3} %)",
        o.fx,
        carter,
        rel * 100.0
    );
}

/// The brush on a line contact in closed form: traction (a - x) xi / L_x from the leading
/// edge until it meets the Coulomb bound mu p0 sqrt(1 - x^2/a^2), the bound behind
/// (Kalker 1990, Sec. 2.5; the bound is concave, so the bristle never re-adheres):
/// F_x = 2b int_{-a}^{a} min((a - x) xi / L_x, mu p(x)) dx, integrated here by a fine
/// midpoint rule, independent of the engine's march. The engine's FASTSIM on 400 cells must
/// follow it over the whole curve.
#[test]
fn line_contact_fastsim_follows_the_brush_closed_form() {
    use creep_core::params::P;
    let cfg = fastsim_line(400);
    let (g, nu) = g_nu(&cfg);
    let mu = cfg.params.si(P::Mu);
    let fn_n = 20e3;
    let patch = engine::patch_for(&cfg, fn_n).unwrap();
    let (a, b, p0) = (patch.a, patch.b, patch.p0);
    let (lx, _) = kalker::line_flexibilities(a, g, nu);
    let closed = |xi: f64| {
        let n = 200_000;
        let dx = 2.0 * a / n as f64;
        let mut s = 0.0;
        for i in 0..n {
            let x = -a + (i as f64 + 0.5) * dx;
            let bound = mu * p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
            s += ((a - x) * xi / lx).min(bound) * dx;
        }
        2.0 * b * s
    };
    // saturation creepage of the brush: xi_s = mu p0 L / a (the line meets the bound at x = 0)
    let xi_s = mu * p0 * lx / a;
    for k in [0.02, 0.1, 0.3, 0.6, 1.0, 2.0, 5.0] {
        let xi = k * xi_s;
        let o = steady(
            &cfg,
            &Inputs {
                cx: xi,
                v: 5.0,
                fn_n,
                ..Inputs::default()
            },
        );
        let c = closed(xi);
        let rel = (o.fx - c) / (mu * fn_n);
        assert!(
            rel.abs() < 0.005,
            "xi = {xi:.3e}: F_x = {} N vs closed form {} N ({:+.3} % of mu F_N)",
            o.fx,
            c,
            rel * 100.0
        );
    }
}

/// Kalker's linear theory (Kalker 1990, Eq. 2.46 and Tab. E.3), in Kalker's convention (the
/// traction on body 1): F_x = -G c^2 C11 xi, F_y = -G c^2 C22 eta - G c^3 C23 phi,
/// M_z = G c^3 C23 eta - G c^4 C33 phi, c = sqrt(ab). The project reports the force on the
/// wheel, the negative (docs/fmu.md, "Sign conventions"): F_y = G c^2 C22 c_y + G c^3 C23
/// spin and M_z of the sign of -c_y and of +spin. FASTSIM reproduces C22 and C23 (its
/// flexibilities are made for them); M_z is checked in sign (FASTSIM has no C33).
#[test]
fn lateral_and_spin_signs_follow_kalker() {
    let cfg = with_grid(preset("fastsim"), 100, 51);
    let (g, nu) = g_nu(&cfg);
    let fn_n = 110e3;
    let patch = engine::patch_for(&cfg, fn_n).unwrap();
    let (a, b) = (patch.a, patch.b);
    let c = (a * b).sqrt();
    let k = kalker::coefficients(a, b, nu).unwrap();
    let eta = 1e-6;
    let o = steady(
        &cfg,
        &Inputs {
            cy: eta,
            v: 5.0,
            fn_n,
            ..Inputs::default()
        },
    );
    let fy_k = g * c * c * k.c22 * eta;
    assert!(
        ((o.fy - fy_k) / fy_k).abs() < 0.01,
        "F_y(c_y) = {} N vs {} N",
        o.fy,
        fy_k
    );
    assert!(o.mz < 0.0, "M_z(c_y > 0) = {} N m must be negative", o.mz);
    let phi = 1e-4; // 1/m
    let o = steady(
        &cfg,
        &Inputs {
            spin: phi,
            v: 5.0,
            fn_n,
            ..Inputs::default()
        },
    );
    let fy_k = g * c * c * c * k.c23 * phi;
    assert!(
        ((o.fy - fy_k) / fy_k).abs() < 0.02,
        "F_y(spin) = {} N vs {} N",
        o.fy,
        fy_k
    );
    assert!(o.mz > 0.0, "M_z(spin > 0) = {} N m must be positive", o.mz);
}
