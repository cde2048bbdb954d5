//! Frictional heat is never negative; temperatures rise with creepage and speed (seed Sec. 4.2, Fig. 4.10).
use crate::common::*;
use creep_core::Model;

#[test]
fn heat_is_never_negative_even_when_unloading() {
    for name in ["table4.1", "wet", "fastsim"] {
        for rule in [false, true] {
            let mut cfg = preset(name);
            if rule {
                cfg.effects.insert(creep_core::Effect::ElasticUnloading);
            }
            let mut m = Model::new(&cfg).unwrap();
            m.steady(&vectron(0.05, 10.0)).unwrap();
            for k in 0..400 {
                let c = 0.05 * (k as f64 * 0.05).cos() - 0.01;
                let o = m.step(2e-5, &vectron(c, 10.0)).unwrap();
                assert!(o.p_fric >= 0.0, "{name}: P = {}", o.p_fric);
                assert!(
                    o.t_max >= 20.0 - 1e-9 && o.t_mean >= 20.0 - 1e-9,
                    "{name}: T below bulk temperature"
                );
                for p in m.field_y0().unwrap() {
                    assert!(p.t >= 20.0 - 1e-9);
                }
            }
        }
    }
}

#[test]
fn temperature_rises_with_creepage_and_speed() {
    let cfg = preset("table4.1");
    for v in [5.0, 10.0, 20.0] {
        let mut prev = 20.0;
        for c in [1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 0.5] {
            let t = steady(&cfg, &vectron(c, v)).t_max;
            assert!(t > prev, "v = {v}: T_max({c}) = {t} not above {prev}");
            prev = t;
        }
    }
    for c in [3e-3, 0.03, 0.3] {
        let t5 = steady(&cfg, &vectron(c, 5.0)).t_max;
        let t20 = steady(&cfg, &vectron(c, 20.0)).t_max;
        assert!(
            t20 > t5,
            "cx = {c}: T_max(20 m/s) = {t20} <= T_max(5 m/s) = {t5}"
        );
    }
}

#[test]
fn frictional_power_matches_force_times_slip_in_full_sliding() {
    // FASTSIM at large creepage: nearly all bristles slide, P = F_x v c_x (work of the creep force)
    let cfg = preset("fastsim");
    let o = steady(&cfg, &vectron(0.2, 10.0));
    let p = o.fx * 10.0 * 0.2;
    assert!(
        (o.p_fric - p).abs() / p < 0.02,
        "P_fric = {} vs F v c = {p}",
        o.p_fric
    );
}
