//! Rolling backwards (v < 0) is the mirror image of rolling forwards, and a transient run through v = 0 keeps the bristles in the contact.
use crate::common::*;
use creep_core::{Inputs, Model};

/// Mirror x -> -x with creepages over |v|: c_x -> -c_x, c_y -> c_y, spin -> -spin; the
/// forces map F_x -> -F_x, F_y -> F_y, M_z -> -M_z. So for the same creepages, rolling
/// backwards gives F_x(-v; c_x, c_y, spin) = -F_x(v; -c_x, c_y, -spin), etc.
#[test]
fn steady_forces_are_the_mirror_image() {
    for name in ["fastsim", "dry", "table4.1", "polach"] {
        let cfg = with_grid(preset(name), 40, 11);
        for (cx, cy, spin) in [(0.004, 0.0, 0.0), (-0.02, 0.003, 0.5), (0.1, -0.01, -2.0)] {
            let back = steady(
                &cfg,
                &Inputs {
                    cx,
                    cy,
                    spin,
                    v: -20.0,
                    ..Inputs::default()
                },
            );
            let fwd = steady(
                &cfg,
                &Inputs {
                    cx: -cx,
                    cy,
                    spin: -spin,
                    v: 20.0,
                    ..Inputs::default()
                },
            );
            let eq = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
            assert!(
                eq(back.fx, -fwd.fx),
                "{name}: F_x {} vs {}",
                back.fx,
                -fwd.fx
            );
            assert!(eq(back.fy, fwd.fy), "{name}: F_y {} vs {}", back.fy, fwd.fy);
            assert!(
                eq(back.mz, -fwd.mz),
                "{name}: M_z {} vs {}",
                back.mz,
                -fwd.mz
            );
            assert!(eq(back.t_max, fwd.t_max) && eq(back.p_fric, fwd.p_fric));
            // the force on the wheel has the sign of its creepage either way (same magnitude
            // only where the model is odd in c_x: FASTSIM; ECF's heat partition depends on
            // the wheel speed |v| (1 + c_x) of the mirrored frame)
            assert!(back.fx * cx >= 0.0, "{name}: F_x {} for c_x {cx}", back.fx);
        }
    }
}

/// A shunting move: steady forwards at 2 m/s, decelerate through v = 0 to -2 m/s with the
/// creepage held, in 0.1 ms steps. The bristles in the contact stay in it: right after the
/// reversal the force is still that of the loaded grid (no jump to zero), and after the
/// contact has rolled 2a backwards it is the steady state of rolling backwards.
#[test]
fn transient_run_through_standstill_keeps_the_bristles() {
    let cfg = with_grid(preset("dry"), 40, 11);
    let mut m = Model::new(&cfg).unwrap();
    let cx = 0.003;
    let at = |v: f64| Inputs {
        cx,
        v,
        ..Inputs::default()
    };
    let f0 = m.steady(&at(2.0)).unwrap().fx;
    let dt = 1e-4;
    let mut v: f64 = 2.0;
    let mut last = f0;
    let mut max_jump: f64 = 0.0;
    while v > -2.0 {
        v = (v - 0.2).max(-2.0);
        let o = m.step(dt, &at(v)).unwrap();
        max_jump = max_jump.max((o.fx - last).abs());
        last = o.fx;
        assert!(o.fx.is_finite());
    }
    // a reset grid would drop by the whole force at the reversal
    assert!(
        max_jump < 0.5 * f0.abs(),
        "jump {max_jump} N against F_x {f0} N"
    );
    // roll 2a backwards (a = 7.63 mm at 110 kN) at constant inputs: the steady state
    let a = m.outputs().a;
    let n = (2.2 * a / (2.0 * dt)).ceil() as usize;
    let mut o = m.outputs();
    for _ in 0..n {
        o = m.step(dt, &at(-2.0)).unwrap();
    }
    let s = Model::new(&cfg).unwrap().steady(&at(-2.0)).unwrap();
    assert!(
        (o.fx - s.fx).abs() < 0.01 * s.fx.abs(),
        "after 2a: F_x {} vs steady {}",
        o.fx,
        s.fx
    );
}

/// The state of a contact rolling backwards survives save and restore.
#[test]
fn reversed_state_round_trips() {
    let cfg = with_grid(preset("dry"), 20, 5);
    let mut m = Model::new(&cfg).unwrap();
    let i = Inputs {
        cx: 0.01,
        v: -5.0,
        ..Inputs::default()
    };
    m.steady(&i).unwrap();
    m.step(1e-4, &Inputs { cx: 0.02, ..i }).unwrap();
    let saved = m.save_state();
    let mut r = Model::new(&cfg).unwrap();
    r.load_state(&saved).unwrap();
    let j = Inputs { cx: 0.015, ..i };
    let a = m.step(1e-4, &j).unwrap();
    let b = r.step(1e-4, &j).unwrap();
    assert_eq!(a, b);
}

/// Reversing the direction without rolling (a zero-length step) changes nothing physical:
/// the mirrored grid carries the same forces, and reversing back gives them again. Not to
/// rounding: a zero-length step re-evaluates every bristle at its node, and the material of
/// the node nearest the trailing edge is taken no closer to it than half a cell (docs/model.md
/// section 3), which after the mirror applies to other bristles; on 40x11 that moves the
/// forces by about 1e-3 of |F| (F_y under spin) and M_z by about 1e-3 of a |F|: the test
/// allows 0.5 % of these scales.
#[test]
fn zero_time_reversal_keeps_forces() {
    for name in ["fastsim", "dry"] {
        let cfg = with_grid(preset(name), 40, 11);
        let mut m = Model::new(&cfg).unwrap();
        let i = Inputs {
            cx: 0.01,
            cy: 0.002,
            spin: 0.3,
            v: 2.0,
            ..Inputs::default()
        };
        m.steady(&i).unwrap();
        m.step(1e-4, &i).unwrap();
        let f = m.step(0.0, &i).unwrap();
        let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 5e-3 * scale;
        let scale = f.fx.hypot(f.fy);
        let b = m.step(0.0, &Inputs { v: -2.0, ..i }).unwrap();
        assert!(m_reversed(&m));
        assert!(
            close(b.fx, f.fx, scale) && close(b.fy, f.fy, scale),
            "{name}: {b:?} vs {f:?}"
        );
        // the moment on the scale of its lever arm a |F| (a wrong mirror of the slots would
        // shift every lever arm by cells: 5 % of a per cell on 40x11)
        assert!(
            close(b.mz, f.mz, b.a * scale),
            "{name}: M_z {} vs {}",
            b.mz,
            f.mz
        );
        let c = m.step(0.0, &i).unwrap();
        assert!(!m_reversed(&m));
        assert!(
            close(c.fx, f.fx, scale) && close(c.fy, f.fy, scale),
            "{name}: {c:?} vs {f:?}"
        );
    }
}

fn m_reversed(m: &Model) -> bool {
    match m {
        Model::Bristle(c) => c.reversed(),
        Model::Polach { .. } => false,
    }
}
