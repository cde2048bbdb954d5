//! Odd symmetry f(-c) = -f(c) of every model, longitudinal and lateral.
//!
//! The only physical asymmetry is the heat partition of Eq. 4.30: the wheel's
//! circumferential speed v_w = v (1 + c_x) is higher in traction than in braking, so more
//! heat flows into the wheel and its surface (the bristle) is hotter. With the temperature
//! effect, f(c) + f(-c) is therefore small and of that sign; without it, exactly zero.
use crate::common::*;
use creep_core::Effect;

#[test]
fn every_model_is_odd_in_creepage() {
    for name in ["fastsim", "polach", "table4.1", "dry", "wet", "dry_sanded"] {
        for thermal in [false, true] {
            let mut cfg = preset(name);
            if !thermal {
                cfg.effects.remove(Effect::Temperature);
            }
            let heated = cfg.has(Effect::Temperature);
            for c in [1e-4, 2e-3, 0.02, 0.15, 0.5] {
                let p = steady(&cfg, &vectron(c, 10.0));
                let n = steady(&cfg, &vectron(-c, 10.0));
                let asym = (p.fx + n.fx) / p.fx.abs().max(1.0);
                if heated {
                    // traction heats the wheel more: |f(+c)| <= |f(-c)|, and by no more than the
                    // relative change of the heat partition itself (softening is sublinear in heat)
                    let alpha = |cx: f64| {
                        let vw = (1.0_f64 + cx).sqrt();
                        vw / (vw + 1.0)
                    };
                    let bound = (alpha(c) - alpha(-c)) / alpha(-c);
                    assert!(
                        asym <= 1e-12 && -asym <= bound,
                        "{name} cx = ±{c}: {} vs {} ({asym}, bound {bound})",
                        p.fx,
                        n.fx
                    );
                    assert!(
                        p.t_max >= n.t_max - 1e-9,
                        "{name}: traction side must not be cooler"
                    );
                } else {
                    assert!(asym.abs() <= 1e-9, "{name} cx = ±{c}: {} vs {}", p.fx, n.fx);
                }
                // lateral creepage does not change v_w: exact symmetry in every case
                let py = steady(
                    &cfg,
                    &creep_core::Inputs {
                        cy: c,
                        v: 10.0,
                        fn_n: 110e3,
                        ..Default::default()
                    },
                );
                let ny = steady(
                    &cfg,
                    &creep_core::Inputs {
                        cy: -c,
                        v: 10.0,
                        fn_n: 110e3,
                        ..Default::default()
                    },
                );
                assert!(
                    (py.fy + ny.fy).abs() <= 1e-9 * py.fy.abs().max(1.0),
                    "{name} cy = ±{c}"
                );
                assert!(
                    p.fx.signum() == c.signum() && py.fy > 0.0,
                    "{name}: force along the creepage"
                );
            }
        }
    }
}
