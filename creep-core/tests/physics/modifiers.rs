//! Formula and Rust effects are two kinds of one modifier: the same factor written both ways gives the same forces to the bit, rolling forwards and backwards, where both see the user's operating point (v < 0, c_x with the user's sign).

use creep_core::custom::{CustomEffect, LocalState, OperatingPoint};
use creep_core::formula::Target;
use creep_core::{Config, Inputs, Model};

/// tau_c2 (1 - k sign(v) + k/2 sign(c_x)): a factor that tells the direction of rolling and
/// of the creepage apart.
#[derive(Debug)]
struct DirectionTest;

impl CustomEffect for DirectionTest {
    fn name(&self) -> &'static str {
        "test_direction"
    }
    fn description(&self) -> &'static str {
        "test only: tau_c2 scaled by the signs of the speed and of the creepage"
    }
    fn target(&self) -> Target {
        Target::TauC2
    }
    fn params(&self) -> &'static [(&'static str, f64, f64, f64, &'static str)] {
        &[("k", 0.1, 0.0, 0.5, "-")]
    }
    fn factor(&self, p: &[f64], _local: &LocalState, op: &OperatingPoint) -> f64 {
        1.0 - p[0] * (op.v_mps / op.v_mps.abs()) + p[0] * (op.cx / op.cx.abs()) / 2.0
    }
}

static DIRECTION_TEST: DirectionTest = DirectionTest;
creep_core::register_effect!(DIRECTION_TEST);

#[test]
fn a_formula_and_a_rust_effect_see_the_same_operating_point_in_both_directions() {
    let formula = Config::from_json_str(
        r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
            "formula_effects": [{"name": "dir", "target": "tau_c2",
              "factor": "1 - k * (v_mps / abs(v_mps)) + k * (cx / abs(cx)) / 2",
              "params": {"k": {"value": 0.1, "min": 0, "max": 0.5}}}]}"#,
        "formula",
    )
    .expect("formula config");
    let rust = Config::from_json_str(
        r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
            "custom_effects": [{"name": "test_direction", "params": {"k": 0.1}}]}"#,
        "rust",
    )
    .expect("rust config");
    let mut traction = Vec::new();
    for v in [10.0, -10.0] {
        for cx in [0.05, -0.05] {
            let i = Inputs {
                cx,
                v,
                fn_n: 80e3,
                ..Inputs::default()
            };
            let a = Model::new(&formula).unwrap().steady(&i).unwrap();
            let b = Model::new(&rust).unwrap().steady(&i).unwrap();
            assert_eq!(
                a.fx.to_bits(),
                b.fx.to_bits(),
                "v {v}, cx {cx}: {} vs {}",
                a.fx,
                b.fx
            );
            assert_eq!(a.p_fric.to_bits(), b.p_fric.to_bits(), "v {v}, cx {cx}");
            traction.push(a.f.abs());
        }
    }
    // the factor changes with either sign (0.95, 0.85, 1.15, 1.05 of tau_c2), and the
    // saturated traction follows it: a frame mix-up would swap these
    let [fwd_pos, fwd_neg, bwd_pos, bwd_neg] = [traction[0], traction[1], traction[2], traction[3]];
    assert!(bwd_pos > fwd_pos * 1.1, "{traction:?}");
    assert!(
        fwd_pos > fwd_neg * 1.05 && bwd_pos > bwd_neg * 1.05,
        "{traction:?}"
    );
}

#[test]
fn factors_multiply_formulas_first_whatever_the_list_order() {
    // three operating-point factors on tau_c2 whose product rounds differently in the other
    // order (k = 0.047 at v = 20 m/s, 80 kN: checked in f64)
    let mut cfg = Config::from_json_str(
        r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
            "formula_effects": [
              {"name": "a", "target": "tau_c2", "factor": "0.9137 + 0.00011 * v_mps"},
              {"name": "b", "target": "tau_c2", "factor": "1.0713 - 0.00031 * fn_kN"}],
            "custom_effects": [{"name": "test_direction", "params": {"k": 0.047}}]}"#,
        "order",
    )
    .expect("config");
    // at 30 % and 100 % creepage the force is mostly tau_c2 over the patch: one ulp of its
    // factor shows in the bits
    let i = Inputs {
        cx: 0.03,
        v: 20.0,
        fn_n: 80e3,
        ..Inputs::default()
    };
    let run = |cfg: &Config| {
        [0.03, 0.3, 1.0].map(|cx| {
            let o = Model::new(cfg)
                .unwrap()
                .steady(&Inputs { cx, ..i })
                .unwrap();
            [o.fx.to_bits(), o.p_fric.to_bits()]
        })
    };
    let want = run(&cfg);
    cfg.modifiers.rotate_right(1); // [Rust, a, b]
    assert!(matches!(cfg.modifiers[0], creep_core::AnyModifier::Rust(_)));
    assert_eq!(run(&cfg), want);
}

#[test]
fn a_factor_on_both_strengths_is_the_same_factor_on_each() {
    // one formula effect on "strengths" against the same factor written twice, on tau_c1 and
    // on tau_c2: the same forces to the bit, for an operating-point and a local factor; a
    // factor on one strength alone differs
    let cfg = |effects: &str| {
        Config::from_json_str(
            &format!(r#"{{"preset": "dry", "grid": {{"nx": 20, "ny": 5}}, "formula_effects": [{effects}]}}"#),
            "strengths",
        )
        .expect("config")
    };
    let run = |cfg: &Config| {
        [0.002, 0.03, 0.3].map(|cx| {
            let o = Model::new(cfg)
                .unwrap()
                .steady(&Inputs {
                    cx,
                    v: 20.0,
                    fn_n: 90e3,
                    ..Inputs::default()
                })
                .unwrap();
            [o.fx.to_bits(), o.t_max.to_bits()]
        })
    };
    for factor in ["0.8 + 0.004 * v_mps", "1 / (1 + (T_C - 20) / 300)"] {
        let both = cfg(&format!(
            r#"{{"name": "s", "target": "strengths", "factor": "{factor}"}}"#
        ));
        let each = cfg(&format!(
            r#"{{"name": "a", "target": "tau_c1", "factor": "{factor}"}},
               {{"name": "b", "target": "tau_c2", "factor": "{factor}"}}"#
        ));
        let one = cfg(&format!(
            r#"{{"name": "b", "target": "tau_c2", "factor": "{factor}"}}"#
        ));
        assert_eq!(run(&both), run(&each), "{factor}");
        assert_ne!(run(&both), run(&one), "{factor}");
    }
}
