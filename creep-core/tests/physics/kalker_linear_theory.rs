//! Small-creepage slope of every bristle model equals Kalker's linear theory F = G a b C c.
use crate::common::*;
use creep_core::kalker;

#[test]
fn small_creepage_slope_is_kalkers_within_1_percent() {
    let (a, b, g, nu) = (7.63e-3, 7.88e-3, 79.3e9, 0.28);
    let c = kalker::coefficients(a, b, nu).unwrap();
    let c0 = 1e-6;
    for name in ["fastsim", "table4.1", "dry", "wet"] {
        let cfg = preset(name);
        let o = steady(
            &cfg,
            &creep_core::Inputs {
                cx: c0,
                v: 5.0,
                fn_n: 110e3,
                ..Default::default()
            },
        );
        let kalker_fx = g * a * b * c.c11 * c0;
        let rel = (o.fx - kalker_fx).abs() / kalker_fx;
        assert!(
            rel < 0.01,
            "{name}: F_x = {} N vs Kalker {} N ({:.3} %)",
            o.fx,
            kalker_fx,
            rel * 100.0
        );
        let o = steady(
            &cfg,
            &creep_core::Inputs {
                cy: c0,
                v: 5.0,
                fn_n: 110e3,
                ..Default::default()
            },
        );
        let kalker_fy = g * a * b * c.c22 * c0;
        let rel = (o.fy - kalker_fy).abs() / kalker_fy;
        assert!(
            rel < 0.01,
            "{name}: F_y = {} N vs Kalker {} N ({:.3} %)",
            o.fy,
            kalker_fy,
            rel * 100.0
        );
    }
}

#[test]
fn slope_follows_the_coefficient_for_other_shapes() {
    // a/b = 0.5 and 2 (a_le_b and a_gt_b halves of the table)
    for (a, b) in [(5e-3, 10e-3), (10e-3, 5e-3)] {
        let mut cfg = preset("fastsim");
        cfg.geometry = creep_core::Geometry::SemiAxes {
            a,
            b,
            fn_ref: 100e3,
        };
        let c = kalker::coefficients(a, b, 0.28).unwrap();
        let o = steady(
            &cfg,
            &creep_core::Inputs {
                cx: 1e-6,
                v: 5.0,
                fn_n: 100e3,
                ..Default::default()
            },
        );
        let k = 79.3e9 * a * b * c.c11 * 1e-6;
        assert!(
            (o.fx - k).abs() / k < 0.01,
            "a/b = {}: {} vs {}",
            a / b,
            o.fx,
            k
        );
    }
}
