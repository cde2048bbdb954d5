//! Save/restore of the full state, input validation and standstill.
use crate::common::*;
use creep_core::{Effect, Inputs, Model};

#[test]
fn saved_state_continues_bit_for_bit() {
    for name in ["table4.1", "fastsim", "polach"] {
        let cfg = preset(name);
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&vectron(0.02, 5.0)).unwrap();
        for k in 0..30 {
            m.step(1e-4, &vectron(0.02 + 0.001 * k as f64, 5.0))
                .unwrap();
        }
        let saved = m.save_state();
        let mut fresh = Model::new(&cfg).unwrap();
        fresh.load_state(&saved).unwrap();
        for k in 0..30 {
            let i = vectron(0.05 - 0.001 * k as f64, 5.0);
            let a = m.step(1.3e-4, &i).unwrap();
            let b = fresh.step(1.3e-4, &i).unwrap();
            assert_eq!(a, b, "{name}: step {k}");
        }
        // corrupt or foreign states are refused
        assert!(fresh.load_state(&saved[..saved.len() - 3]).is_err());
        let mut other = Model::new(&preset("dry")).unwrap();
        if name != "polach" {
            assert!(
                other.load_state(&saved).is_err(),
                "state of {name} must not load into dry"
            );
        }
    }
}

#[test]
fn bad_inputs_are_rejected_with_the_field_name() {
    let mut m = Model::new(&preset("table4.1")).unwrap();
    let cases = [
        (
            Inputs {
                v: -1001.0, // negative speeds roll backwards (reversed_rolling.rs); this is out of range
                ..vectron(0.01, 5.0)
            },
            "v",
        ),
        (
            Inputs {
                v: f64::NAN,
                ..vectron(0.01, 5.0)
            },
            "v",
        ),
        (
            Inputs {
                cx: f64::INFINITY,
                ..vectron(0.01, 5.0)
            },
            "cx",
        ),
        (
            Inputs {
                fn_n: f64::NAN,
                ..vectron(0.01, 5.0)
            },
            "F_N",
        ),
    ];
    for (i, field) in cases {
        let e = m.step(1e-4, &i).unwrap_err().to_string();
        assert!(e.starts_with(field), "{e}");
    }
    assert!(m.step(-1.0, &vectron(0.01, 5.0)).is_err());
}

#[test]
fn lift_off_gives_zero_forces_and_recovers() {
    let mut m = Model::new(&preset("table4.1")).unwrap();
    m.steady(&vectron(0.01, 5.0)).unwrap();
    let o = m
        .step(
            1e-4,
            &Inputs {
                fn_n: 0.0,
                ..vectron(0.01, 5.0)
            },
        )
        .unwrap();
    assert_eq!((o.fx, o.fy, o.mz, o.f), (0.0, 0.0, 0.0, 0.0));
    let o = m.step(1e-4, &vectron(0.01, 5.0)).unwrap();
    assert!(o.fx > 0.0 && o.fx.is_finite());
}

#[test]
fn standstill_is_the_v_to_0_limit_without_heat() {
    let cfg = preset("table4.1");
    let cold = without(cfg.clone(), Effect::Temperature);
    let f0 = f_of(&cfg, 0.01, 0.0);
    let f_slow = f_of(&cold, 0.01, 1e-3);
    assert!(
        (f0 - f_slow).abs() < 1e-6,
        "v = 0: {f0} vs v -> 0 without heat {f_slow}"
    );
    let o = steady(&cfg, &vectron(0.01, 0.0));
    assert_eq!(o.t_max, 20.0);
    // transient at standstill: nothing moves, the force is held
    let mut m = Model::new(&cfg).unwrap();
    let start = m.steady(&vectron(0.01, 5.0)).unwrap();
    let held = m.step(1e-3, &vectron(0.01, 0.0)).unwrap();
    assert!(
        (held.fx - start.fx).abs() / start.fx < 0.02,
        "{} vs {}",
        held.fx,
        start.fx
    );
    assert!(held.fx.is_finite());
}

#[test]
fn a_steady_state_in_mid_run_forgets_the_run_before_it() {
    // a step after steady(i) is the same whether the contact ran before or is new: the
    // steady state resets every bristle, its node state and the strip's part of a cell (the
    // FASTSIM march once kept the part, 6 % off in F_x on the next step)
    for name in ["fastsim", "dry"] {
        let cfg = with_grid(preset(name), 12, 4);
        let i = Inputs {
            cx: 0.004,
            v: 20.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        let mut run = Model::new(&cfg).unwrap();
        run.steady(&i).unwrap();
        for k in 0..3 {
            let j = Inputs {
                cx: 0.02 + 0.01 * k as f64,
                ..i
            };
            run.step(33e-6, &j).unwrap();
        }
        run.steady(&i).unwrap();
        let mut fresh = Model::new(&cfg).unwrap();
        fresh.steady(&i).unwrap();
        // small creepage: most bristles adhere, so their stresses depend on the distance moved
        let j = Inputs { cx: 0.0005, ..i };
        let (a, b) = (run.step(33e-6, &j).unwrap(), fresh.step(33e-6, &j).unwrap());
        assert_eq!(
            a.fx.to_bits(),
            b.fx.to_bits(),
            "{name}: {} vs {}",
            a.fx,
            b.fx
        );
        assert_eq!(a.t_max.to_bits(), b.t_max.to_bits(), "{name}");
    }
}
