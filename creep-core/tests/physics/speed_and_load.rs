//! Seed Fig. 4.11: higher speed lowers the maximum and moves it to smaller creepage; higher load lowers it.
use crate::common::*;
use creep_core::{Config, Geometry, Inputs};

fn max_of(cfg: &Config, v: f64, fn_n: f64) -> (f64, f64) {
    let mut best = (0.0, f64::MIN);
    for i in 1..=400 {
        let c = 0.5 * (i as f64 / 400.0).powi(2);
        let f = steady(
            cfg,
            &Inputs {
                cx: c,
                v,
                fn_n,
                ..Inputs::default()
            },
        )
        .f;
        if f > best.1 {
            best = (c, f);
        }
    }
    best
}

#[test]
fn maximum_is_lower_and_earlier_at_higher_speed() {
    let cfg = preset("table4.1");
    let (c5, f5) = max_of(&cfg, 5.0, 110e3);
    let (c20, f20) = max_of(&cfg, 20.0, 110e3);
    assert!(
        f20 < f5,
        "f_max(20 m/s) = {f20} must be below f_max(5 m/s) = {f5}"
    );
    assert!(
        c20 < c5,
        "c_max(20 m/s) = {c20} must be below c_max(5 m/s) = {c5}"
    );
}

#[test]
fn maximum_is_lower_at_higher_load() {
    let mut cfg = preset("table4.1");
    let (_, f110) = max_of(&cfg, 20.0, 110e3);
    cfg.geometry = Geometry::SemiAxes {
        a: 5.87e-3,
        b: 6.06e-3,
        fn_ref: 50e3,
    };
    let (_, f50) = max_of(&cfg, 20.0, 50e3);
    assert!(
        f110 < f50,
        "f_max(110 kN) = {f110} must be below f_max(50 kN) = {f50}"
    );
}
