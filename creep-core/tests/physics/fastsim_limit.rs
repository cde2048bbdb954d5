//! ECF with tau_c1 = tau_c2 = mu p, no temperature, L_e = 0 is FASTSIM; FASTSIM saturates at mu.
use crate::common::*;
use creep_core::{kalker, Config, Effect};

/// ECF's own 3BL material law driven into the Coulomb limit: equal critical stresses with a
/// pressure coefficient so small that 1 - exp(-p c) = p c (1 - pc/2 ...) and tau_c0 = mu / c,
/// so tau_c1 = tau_c2 = mu p within 0.05 %; no temperature, no layer elasticity.
fn ecf_coulomb_limit(mu: f64) -> Config {
    let mut cfg = preset("table4.1");
    cfg.effects.remove(Effect::Temperature);
    cfg.effects.remove(Effect::LayerElasticity);
    let c = 1e-3; // 1/GPa
    for n in ["tau_c1_p_per_GPa", "tau_c2_p_per_GPa"] {
        cfg.params.set_by_name(n, c).unwrap();
    }
    for n in ["tau_c1_0_GPa", "tau_c2_0_GPa"] {
        cfg.params.set_by_name(n, mu / c).unwrap();
    }
    cfg
}

#[test]
fn ecf_in_the_coulomb_limit_equals_fastsim_within_half_a_percent() {
    let mu = 0.25;
    let ecf = ecf_coulomb_limit(mu);
    let fastsim = preset("fastsim");
    for cx in [1e-4, 5e-4, 1e-3, 2e-3, 4e-3, 1e-2, 0.05, 0.3] {
        let fe = f_of(&ecf, cx, 5.0);
        let ff = f_of(&fastsim, cx, 5.0);
        assert!(
            (fe - ff).abs() / ff < 0.005,
            "cx = {cx}: ECF limit {fe} vs FASTSIM {ff}"
        );
    }
}

#[test]
fn engine_fastsim_equals_textbook_fastsim() {
    let (a, b, fn_n, mu) = (7.63e-3, 7.88e-3, 110e3, 0.25);
    let c = kalker::coefficients(a, b, 0.28).unwrap();
    let (lx, ly, _) = kalker::flexibilities(a, b, 79.3e9, &c);
    let cfg = preset("fastsim");
    let (nx, ny) = (cfg.grid.nx, cfg.grid.ny);
    for (cx, cy) in [
        (1e-3, 0.0),
        (3e-3, 0.0),
        (2e-3, 1e-3),
        (0.0, 2e-3),
        (0.05, 0.01),
    ] {
        let o = steady(
            &cfg,
            &creep_core::Inputs {
                cx,
                cy,
                v: 5.0,
                fn_n,
                ..Default::default()
            },
        );
        let (rx, ry) = reference_fastsim(
            &RefCase {
                a,
                b,
                fn_n,
                mu,
                lx,
                ly,
                nx,
                ny,
            },
            cx,
            cy,
        );
        let scale = (rx * rx + ry * ry).sqrt();
        assert!(
            (o.fx - rx).abs() / scale < 0.005 && (o.fy - ry).abs() / scale < 0.005,
            "({cx}, {cy}): engine ({}, {}) vs reference ({rx}, {ry})",
            o.fx,
            o.fy
        );
    }
}

#[test]
fn fastsim_saturates_at_mu() {
    for mu in [0.25, 0.6] {
        let mut cfg = preset("fastsim");
        cfg.params.set_by_name("mu", mu).unwrap();
        let mut prev = 0.0;
        for cx in [1e-3, 1e-2, 0.1, 0.5, 1.0] {
            let f = f_of(&cfg, cx, 10.0);
            // the discrete integral of the bound mu p over the nodes differs from mu F_N by the
            // quadrature error of the pressure (< 0.2 % on the default grid)
            assert!(f <= mu * 1.002, "f = {f} above mu = {mu}");
            assert!(f >= prev - 1e-12, "FASTSIM curve must not fall");
            prev = f;
        }
        assert!(
            (prev - mu).abs() < 0.002 * mu,
            "f(100 %) = {prev}, expected -> mu = {mu}"
        );
    }
}
