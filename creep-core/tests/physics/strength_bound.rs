//! The tangential force never exceeds the layer's strength: |F_x| <= integral of tau_c2(p, T_B) over the contact, for every preset from 1 N to 1 MN.
//!
//! The bound holds to within the grid's quadrature of the pressure, which the test measures
//! rather than assumes: FASTSIM in full sliding on the same grid and geometry gives
//! mu (1 + e_q) F_N, where e_q is the relative error of the nodes' quadrature of p (+0.35 %
//! on 40x11, +0.09 % on 80x21, +0.02 % on 160x41: second order).
use crate::common::*;
use creep_core::{engine, Effect, Inputs};

/// Integral of the largest shear stress the layer can carry, tau_c2(p(x, y), T_B) (Eq. 4.4;
/// the flash temperature only softens it), or mu p for a Coulomb bound, over the Hertz patch.
fn strength(cfg: &creep_core::Config, fn_n: f64, t_b: f64) -> f64 {
    use creep_core::params::P;
    let patch = engine::patch_for(cfg, fn_n).unwrap();
    let (a, b, p0) = (patch.a, patch.b, patch.p0);
    let tau = |p: f64| {
        if cfg.has(Effect::Coulomb) {
            cfg.params.si(P::Mu) * p
        } else {
            engine::layer_material(cfg, p, t_b).tc2
        }
    };
    let n = 2000;
    if patch.line {
        // strip of width 2b, p = p0 sqrt(1 - (x/a)^2)
        let dx = 2.0 / n as f64;
        (0..n)
            .map(|i| {
                let x = -1.0 + (i as f64 + 0.5) * dx;
                tau(p0 * (1.0 - x * x).sqrt()) * dx * a * 2.0 * b
            })
            .sum()
    } else {
        // ellipse in polar rings: p = p0 sqrt(1 - r^2), area element 2 pi a b r dr
        let dr = 1.0 / n as f64;
        (0..n)
            .map(|i| {
                let r = (i as f64 + 0.5) * dr;
                tau(p0 * (1.0 - r * r).sqrt()) * 2.0 * std::f64::consts::PI * a * b * r * dr
            })
            .sum()
    }
}

#[test]
fn traction_never_exceeds_the_layers_strength() {
    for name in [
        "table4.1",
        "dry",
        "wet",
        "dry_sanded",
        "wet_sanded",
        "twin_disc",
        "fastsim",
    ] {
        let cfg = with_grid(preset(name), 40, 11);
        let mut fs = with_grid(preset("fastsim"), 40, 11);
        fs.geometry = cfg.geometry;
        let mut worst: f64 = 0.0;
        for fn_n in [1.0, 100.0, 1e3, 1e4, 1e5, 1e6] {
            // quadrature error of the pressure on this grid (FASTSIM saturated: f = mu (1 + e_q))
            let sat = steady(
                &fs,
                &Inputs {
                    cx: 10.0,
                    v: 20.0,
                    fn_n,
                    ..Inputs::default()
                },
            );
            let e_q = sat.f / fs.params.si(creep_core::params::P::Mu) - 1.0;
            assert!(e_q.abs() < 0.005, "{name}: quadrature error {e_q}");
            let cap = strength(&cfg, fn_n, 20.0) * (1.0 + e_q.max(0.0));
            for cx in [0.002, 0.02, 0.3, 1.0] {
                let o = steady(
                    &cfg,
                    &Inputs {
                        cx,
                        v: 20.0,
                        fn_n,
                        ..Inputs::default()
                    },
                );
                let r = o.fx.abs() / cap;
                worst = worst.max(r);
                assert!(
                    r <= 1.0 + 1e-9,
                    "{name}: F_N = {fn_n} N, c_x = {cx}: |F_x| = {} N > strength {cap} N (f = {})",
                    o.fx.abs(),
                    o.f
                );
            }
        }
        eprintln!("{name}: largest |F_x| / strength = {worst:.3}");
    }
}
