//! The scalar temperature solve of a softening layer (engine/softening.rs) against the general solve: the same states within the solve's tolerance, steady and transient.

use super::common::{preset, with_grid};
use creep_core::thermal::TemperatureSolve;
use creep_core::{Config, Contact, Inputs, Outputs};

/// Forces and moment within `rel` of the larger magnitude (plus 1 N, 1 N m), the
/// frictional power within `rel`, temperature rises within `rel` (plus 1 mK).
fn agree(what: &str, a: &Outputs, b: &Outputs, rel: f64) {
    for (name, x, y, floor) in [
        ("fx", a.fx, b.fx, 1.0),
        ("fy", a.fy, b.fy, 1.0),
        ("mz", a.mz, b.mz, 1.0),
        ("p_fric", a.p_fric, b.p_fric, 1.0),
        ("t_max", a.t_max - 20.0, b.t_max - 20.0, 1e-3),
        ("t_mean", a.t_mean - 20.0, b.t_mean - 20.0, 1e-3),
    ] {
        assert!(
            (x - y).abs() <= rel * x.abs().max(y.abs()) + floor,
            "{what}: {name} {x} (scalar solve) vs {y} (general solve)"
        );
    }
    for (name, x, y) in [
        ("frac_elastic", a.frac_elastic, b.frac_elastic),
        ("frac_sliding", a.frac_sliding, b.frac_sliding),
    ] {
        // a bristle at a regime boundary may fall on either side within the tolerance
        assert!((x - y).abs() <= 0.02, "{what}: {name} {x} vs {y}");
    }
}

/// Two contacts of `cfg`: (scalar solve, general solve). Asserts that the scalar solve
/// applies to `cfg` (else the comparison would compare the general solve with itself).
fn scalar_and_general(cfg: &Config, what: &str) -> (Contact, Contact) {
    let mut fast = Contact::new(cfg).unwrap();
    let mut general = Contact::new(cfg).unwrap();
    // the exact temperature solve on both: the two solves agree within its tolerance (the
    // predictor-corrector's own agreement: tests/physics/temperature_solve.rs)
    for c in [&mut fast, &mut general] {
        c.set_temperature_solve(TemperatureSolve::Exact);
    }
    assert!(
        general.set_softening_solve(false),
        "{what}: the scalar solve should apply"
    );
    (fast, general)
}

/// The steady states of both solves at `i` agree within 2e-4 ([`agree`]).
fn steady_agree(fast: &mut Contact, general: &mut Contact, i: &Inputs, what: &str) {
    let a = fast.steady(i).unwrap();
    let b = general.steady(i).unwrap();
    agree(what, &a, &b, 2e-4);
}

/// The softening-layer presets take the scalar solve, and the tolerance of both solves
/// (1e-4 relative change of the softening factors) bounds their difference: steady curves
/// with longitudinal, lateral and spin creepage at two speeds agree within 2e-4.
#[test]
fn scalar_solve_agrees_with_the_general_solve_in_steady_state() {
    for name in ["table4.1", "dry", "wet", "dry_sanded", "twin_disc"] {
        let cfg = with_grid(preset(name), 40, 11);
        let (mut fast, mut general) = scalar_and_general(&cfg, name);
        for v in [5.0, 30.0] {
            for (cx, cy, spin) in [
                (0.0005, 0.0, 0.0),
                (0.003, 0.0, 0.0),
                (0.02, 0.0, 0.0),
                (0.1, 0.0, 0.0),
                (0.35, 0.0, 0.0),
                (0.01, 0.004, 0.0),
                (0.02, -0.01, 1.5),
            ] {
                let i = Inputs {
                    cx,
                    cy,
                    spin,
                    v,
                    fn_n: 110e3,
                    ..Inputs::default()
                };
                steady_agree(&mut fast, &mut general, &i, &format!("{name} {i:?}"));
            }
        }
    }
}

/// On fine grids (cells shorter than about 25 um) a plastic bristle may ride on tau_c1 and a
/// damped release takes its reference at the predictor (docs/model.md section 6,
/// "Riding bristles"):
/// the general solve's; the scalar solve leaves those moves to it. Without that, dry's F_x on
/// 640x21 at 20 m/s and c_x 1 % differed by 1.3 % between the two (riding) and wet's T_max
/// rise at 30 m/s by 0.39 K (the reference).
#[test]
fn scalar_solve_agrees_with_the_general_solve_on_fine_grids() {
    for (name, v) in [("dry", 20.0), ("wet", 30.0)] {
        let cfg = with_grid(preset(name), 640, 21);
        let (mut fast, mut general) = scalar_and_general(&cfg, name);
        for cx in [0.005, 0.01, 0.05] {
            let i = Inputs {
                cx,
                v,
                fn_n: 110e3,
                ..Inputs::default()
            };
            let what = format!("{name} 640x21 {i:?}");
            steady_agree(&mut fast, &mut general, &i, &what);
        }
    }
}

/// Transient steps of several lengths with varying creepage, speed and load: the two
/// solves stay together (their differences do not grow over 40 steps), in all schemes
/// (the continuous one weighs the start stress in the dissipation of its long sub-steps;
/// under the higher-order rules the scalar path solves their hardening law by the general
/// search, and wet has a temperature coefficient of L_p).
#[test]
fn scalar_solve_agrees_with_the_general_solve_in_transient_steps() {
    use creep_core::engine::Scheme;
    // the continuous scheme's long sub-steps carry more self-heating per solve, and the
    // solves' differences grow over the steps to about 1.5e-3 (the build before its
    // weighted dissipation and one-cell last piece: 3e-3 in T_max)
    let tol_c = 2e-3;
    for (name, scheme, tol) in [
        ("table4.1", Scheme::CellsMarch, 2e-4),
        ("dry", Scheme::CellsMarch, 2e-4),
        ("table4.1", Scheme::Continuous, tol_c),
        ("dry", Scheme::Continuous, tol_c),
        ("table4.1", Scheme::CellsHigher, 2e-4),
        ("dry", Scheme::CellsHigher, 2e-4),
        ("wet", Scheme::CellsHigher, 2e-4),
    ] {
        let cfg = with_grid(preset(name), 30, 9);
        let mut fast = Contact::new(&cfg).unwrap();
        let mut general = Contact::new(&cfg).unwrap();
        for c in [&mut fast, &mut general] {
            c.set_temperature_solve(TemperatureSolve::Exact);
        }
        fast.set_scheme(scheme);
        general.set_scheme(scheme);
        general.set_softening_solve(false);
        let i0 = Inputs {
            cx: 0.01,
            v: 5.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        fast.steady(&i0).unwrap();
        general.steady(&i0).unwrap();
        let mut k = 0u32;
        // the scalar path was taken: it solves to the tolerance, not to the last bit
        let mut differ = false;
        for (dt, v) in [(2e-6, 5.0), (3.3e-4, 5.0), (1e-4, 20.0), (7e-5, 12.0)] {
            for _ in 0..10 {
                k += 1;
                let i = Inputs {
                    cx: 0.01 + 0.1 * (k as f64 * 0.7).sin().abs(),
                    cy: 0.001 * (k as f64).cos(),
                    v,
                    fn_n: 100e3 + 2e3 * k as f64,
                    ..Inputs::default()
                };
                let a = fast.step(dt, &i).unwrap();
                let b = general.step(dt, &i).unwrap();
                agree(&format!("{name} {scheme:?} step {k} dt {dt}"), &a, &b, tol);
                differ |= a.fx != b.fx || a.t_max != b.t_max;
            }
        }
        assert!(differ, "{name} {scheme:?}: the scalar solve was not taken");
    }
}

/// Without temperature there is nothing to solve: the scalar path does not apply (nor to
/// the Coulomb bound of FASTSIM).
#[test]
fn scalar_solve_applies_only_to_a_softening_layer_with_temperature() {
    let mut cold = preset("dry");
    cold.effects.remove(creep_core::Effect::Temperature);
    assert!(!Contact::new(&cold).unwrap().set_softening_solve(false));
    assert!(!Contact::new(&preset("fastsim"))
        .unwrap()
        .set_softening_solve(false));
}

/// tau_c1 softening more slowly than tau_c2 (as fits of the temperature coefficients give):
/// the span tau_c2 - tau_c1 closes some 5 K above the bulk here (at the peak pressure), where the law turns
/// perfectly plastic; moves whose root lies beyond it take the general solve. Both agree.
#[test]
fn scalar_solve_where_heating_closes_the_hardening_span() {
    let mut cfg = with_grid(preset("dry"), 30, 9);
    for (name, value) in [
        ("tau_c1_0_GPa", 0.6),
        ("tau_c1_T_per_C", 0.0),
        ("tau_c2_T_per_C", 0.02),
    ] {
        cfg.params.set_by_name(name, value).expect("parameter");
    }
    let (mut fast, mut general) = scalar_and_general(&cfg, "this layer");
    for cx in [0.001, 0.005, 0.02, 0.1, 0.3] {
        for v in [5.0, 30.0] {
            let i = Inputs {
                cx,
                v,
                fn_n: 110e3,
                ..Inputs::default()
            };
            steady_agree(&mut fast, &mut general, &i, &format!("cx {cx} v {v}"));
        }
    }
}

/// Formula effects of the operating point (here a data column) scale the strengths by
/// constants: the scalar solve applies and agrees with the general one. A formula of the
/// local temperature does not keep the layer's law a known function of T: general solve.
#[test]
fn scalar_solve_with_formula_effects_of_the_operating_point() {
    let config = |factor: &str| {
        let text = format!(
            r#"{{"preset": "dry", "grid": {{"nx": 30, "ny": 9}},
            "formula_effects": [{{"name": "f", "target": "tau_c2", "factor": "{factor}",
            "params": {{"k": {{"value": 0.3, "min": -1, "max": 1}}}}}}]}}"#
        );
        Config::from_json_str(&text, "test").expect("config")
    };
    let cfg = config("1 - k * (humidity - 50) / 50");
    let (mut fast, mut general) = scalar_and_general(&cfg, "this layer");
    for (h, cx) in [(20.0, 0.004), (50.0, 0.03), (80.0, 0.2)] {
        let cols = [("humidity".to_string(), h)];
        fast.set_extra(&cols).unwrap();
        general.set_extra(&cols).unwrap();
        let i = Inputs {
            cx,
            v: 10.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        let what = format!("humidity {h} cx {cx}");
        steady_agree(&mut fast, &mut general, &i, &what);
    }
    let local = config("1 - k * (T_C - 20) / 500");
    assert!(!Contact::new(&local).unwrap().set_softening_solve(false));
}
