//! Seed Sec. 4.5.1: after a creepage step the force settles to the new steady value once every bristle entered after the step (t >= 2a/v).
use crate::common::*;
use creep_core::{Effect, Inputs, Model};

#[test]
fn step_0p1_to_1_percent_settles_after_2a_over_v() {
    let cfg = without(preset("table4.1"), Effect::Temperature);
    let v = 5.0;
    let a = 7.63e-3;
    let mut m = Model::new(&cfg).unwrap();
    m.steady(&vectron(0.001, v)).unwrap();
    let target = steady(&cfg, &vectron(0.01, v)).f;
    let dt = 1e-5;
    let t_settle = 2.0 * a / v;
    assert!((t_settle - 3.05e-3).abs() < 0.1e-3, "seed: 3.1 ms");
    let mut t = 0.0;
    let mut at_half = None;
    let mut settled_dev: f64 = 0.0;
    while t < 2.0 * t_settle {
        let o = m.step(dt, &vectron(0.01, v)).unwrap();
        t += dt;
        if at_half.is_none() && t >= a / v {
            at_half = Some(o.f);
        }
        if t >= t_settle + 1e-9 {
            let dev = (o.f - target).abs() / target;
            settled_dev = settled_dev.max(dev);
            assert!(dev < 0.005, "t = {t}: f = {} vs steady {target}", o.f);
        }
    }
    let f_half = at_half.unwrap();
    // "measurably away": at a/v half the bristles still carry the old creepage, so f is
    // below the new steady value by more than half the 0.5 % band that counts as settled,
    // and by several times what it deviates once settled (the lattice's ripple). The
    // converged gap is 0.52 % (320x21 and 640x41, 0.01 ms steps); a fixed 0.5 % threshold
    // sat within the default grid's error of it (0.48 % with the Gauss-Legendre strips,
    // 0.51 % with equal strips), so the test no longer asks for it.
    let half_dev = (target - f_half) / target;
    assert!(
        half_dev > 0.0025 && half_dev > 4.0 * settled_dev,
        "at t = a/v the response must still be transient: {f_half} vs {target} \
         ({:.3} % below it; settled within {:.3} %)",
        half_dev * 100.0,
        settled_dev * 100.0
    );
}

#[test]
fn steady_state_is_the_limit_of_the_transient_model() {
    // constant inputs, arbitrary (non-aligned) time steps, temperature on: after 3 a/v the
    // transient grid equals the steady march of its rules. The cell-by-cell schemes (one
    // sub-step per cell, as the march; the higher-order rules' march is their own) must
    // agree within 0.5 %; the continuous scheme (sub-steps of up to 8 cells, not aligned
    // with the march's, whose steady state is the cell-by-cell march) within the preset's
    // grid-convergence error of docs/model.md section 9 (80x21 vs 320x84: table4.1 0.75 %,
    // fastsim 0.18 %, wet 3.2 %: wet's tau_c1 halves every 1.3 K, so its discretisation
    // error is the largest).
    use creep_core::engine::Scheme;
    for (name, tol_cont) in [("table4.1", 0.0075), ("fastsim", 0.005), ("wet", 0.032)] {
        for cx in [0.002, 0.05, 0.3] {
            let i = Inputs {
                cx,
                v: 10.0,
                fn_n: 110e3,
                ..Inputs::default()
            };
            for (scheme, tol) in [
                (Scheme::CellsMarch, 0.005),
                (Scheme::CellsHigher, 0.005),
                (Scheme::Continuous, tol_cont),
            ] {
                let march = match scheme {
                    Scheme::CellsHigher => Scheme::CellsHigher,
                    _ => Scheme::CellsMarch,
                };
                let cfg = with_scheme(preset(name), march);
                let target = steady(&cfg, &i).f;
                let mut m = creep_core::Contact::new(&cfg).unwrap();
                m.set_scheme(scheme);
                m.steady(&Inputs { cx: 0.0, ..i }).unwrap();
                let mut t = 0.0;
                while t < 3.0 * 7.63e-3 / 10.0 {
                    m.step(3.7e-5, &i).unwrap();
                    t += 3.7e-5;
                }
                let f = m.outputs().f;
                assert!(
                    (f - target).abs() / target.abs() < tol,
                    "{name} cx = {cx} {scheme:?}: transient {f} vs steady {target}"
                );
            }
        }
    }
}

#[test]
fn reverse_step_takes_longer_than_forward_step() {
    // seed Fig. 4.14 vs 4.16: 1 % -> 0.1 % approaches its steady state more slowly than 0.1 % -> 1 %
    let cfg = without(preset("table4.1"), Effect::Temperature);
    let settle = |from: f64, to: f64| {
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&vectron(from, 5.0)).unwrap();
        let target = steady(&cfg, &vectron(to, 5.0)).f;
        let start = m.outputs().f;
        let mut t = 0.0;
        loop {
            let o = m.step(1e-5, &vectron(to, 5.0)).unwrap();
            t += 1e-5;
            if (o.f - target).abs() <= 0.05 * (start - target).abs() || t > 0.01 {
                return t;
            }
        }
    };
    let up = settle(0.001, 0.01);
    let down = settle(0.01, 0.001);
    assert!(
        down > up,
        "1 % -> 0.1 % settles in {down} s, 0.1 % -> 1 % in {up} s"
    );
}

#[test]
fn marching_new_bristles_is_bit_identical_to_the_sub_step_loop() {
    use creep_core::Contact;
    for name in ["table4.1", "fastsim", "wet"] {
        let cfg = with_grid(preset(name), 30, 9);
        let mut fast = Contact::new(&cfg).unwrap();
        let mut plain = Contact::new(&cfg).unwrap();
        plain.set_march_new_bristles(false);
        let i0 = Inputs {
            cx: 0.01,
            v: 5.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        fast.steady(&i0).unwrap();
        plain.steady(&i0).unwrap();
        let mut k = 0u32;
        // step sizes from much less than one cell to more than the whole contact, varying speed and load
        for (dt, v) in [
            (2e-6, 5.0),
            (3.3e-4, 5.0),
            (1e-3, 20.0),
            (7e-5, 12.0),
            (5e-3, 3.0),
            (1e-3, 5.0),
        ] {
            for _ in 0..5 {
                k += 1;
                let i = Inputs {
                    cx: 0.01 + 0.1 * (k as f64 * 0.7).sin().abs(),
                    cy: 0.001 * (k as f64).cos(),
                    v,
                    fn_n: 100e3 + 2e3 * k as f64,
                    ..Inputs::default()
                };
                let a = fast.step(dt, &i).unwrap();
                let b = plain.step(dt, &i).unwrap();
                assert_eq!(a, b, "{name}: step {k} (dt = {dt}, v = {v})");
            }
        }
    }
}

#[test]
fn tiny_time_steps_at_high_creepage_stay_on_the_steady_state() {
    // Regression: with temperature, sub-steps far below the cell crossing time once let the
    // elastic-release heat run away (f dropped by up to 10 % at dt = 1 us, 30 % creepage).
    // Since the whole-cell commit (a step shorter than a cell makes no sub-cell move) this
    // grid no longer reaches the release weight theta: it passes with theta = 1. The sibling
    // below is the one that needs theta.
    let cfg = with_grid(preset("table4.1"), 160, 1);
    let i = vectron(0.3, 5.0);
    let target = steady(&cfg, &i).f;
    for dt in [1e-5, 1e-6, 2e-7] {
        let mut m = Model::new(&cfg).unwrap();
        m.steady(&i).unwrap();
        let mut t = 0.0;
        while t < 1e-3 {
            let o = m.step(dt, &i).unwrap();
            t += dt;
            assert!(
                (o.f - target).abs() / target < 0.005,
                "dt = {dt}, t = {t}: f = {} vs steady {target}",
                o.f
            );
        }
    }
}

/// The release weight theta (docs/model.md, section 6) on a fine grid: dry, a 320x7 grid at
/// 20 m/s (cells of 48 um, 2.4 us), c_x = 5 %, steps of 0.02 to 3.3 cells from the steady
/// state. A step that stops inside a cell reports the bristles moved over the part of the cell
/// travelled so far (docs/model.md, section 3), a move of a fraction of a microsecond whose
/// elastic-release feedback gain exceeds 1; theta damps it. Measured over a tenth of a
/// transit: f within 0.011 % of the steady f and T_max within 0.08 K of the steady T_max.
/// Bounds 0.03 % and 1 K. With theta forced to 1 (in both solves; with the softening solve
/// off, in the general move's `release_weight` alone) the partial moves run away: f 0.18 /
/// 0.18 / 0.14 / 0.05 % below the steady f and T_max 945 / 801 / 454 / 82 K above it at
/// 0.02 / 0.1 / 0.5 / 3.3 cells. (Theta forced to 1 in the softening solve alone changes
/// nothing here beyond 0.001 % in f, so the general move is run on its own as well.)
#[test]
fn sub_cell_steps_on_a_fine_grid_stay_on_the_steady_state() {
    use creep_core::Contact;
    let nx = 320;
    let cfg = with_grid(preset("dry"), nx, 7);
    let (cx, v) = (0.05, 20.0);
    let i = vectron(cx, v);
    let s = steady(&cfg, &i);
    let cell = 2.0 * s.a / nx as f64 / v;
    // the softening (scalar) solve on (the default) and off (every move the general solve)
    for softening in [true, false] {
        for frac in [0.02, 0.1, 0.5, 3.3] {
            let dt = frac * cell;
            let mut m = Contact::new(&cfg).unwrap();
            m.set_softening_solve(softening);
            m.steady(&i).unwrap();
            let (mut df, mut dtm) = (0.0f64, 0.0f64);
            let mut t = 0.0;
            while t < 0.1 * 2.0 * s.a / v {
                let o = m.step(dt, &i).unwrap();
                t += dt;
                df = df.max((o.f / s.f - 1.0).abs());
                dtm = dtm.max((o.t_max - s.t_max).abs());
            }
            assert!(
                df < 3e-4 && dtm < 1.0,
                "softening solve {softening}, dt = {frac} cells: f within {:.4} % and T_max \
                 within {dtm:.2} K of the steady state (f {}, T_max {})",
                df * 100.0,
                s.f,
                s.t_max
            );
        }
    }
}

/// Constant inputs from the steady state are a fixed point of the transient steps, whatever
/// the communication step: with steps of an eighth of a cell (each cell crossed in eight
/// parts), a single 320-cell strip at 5 m/s stays on its steady f at every whole cell to
/// rounding (measured 0 to 1e-12), and in between within 0.1 % (measured 3.2e-4: the grid's
/// quadrature with the bristles between the nodes, which does not accumulate). Each cell is
/// committed whole from the bristles' node states (docs/model.md section 3.2); when the
/// parts are committed one by one f drifts by +1.36 % over
/// three transits here.
#[test]
fn constant_inputs_stay_on_the_steady_state_when_steps_cut_the_cells() {
    let nx = 320;
    let mut m = Model::new(&with_grid(preset("dry"), nx, 1)).expect("model");
    let i = vectron(0.02, 5.0);
    let o = m.steady(&i).expect("steady");
    let (f0, a) = (o.f, o.a);
    let dt = 2.0 * a / nx as f64 / 5.0 / 8.0;
    let (mut at_cells, mut between) = (0.0f64, 0.0f64);
    for k in 1..=3 * nx * 8 {
        let d = (m.step(dt, &i).expect("step").f / f0 - 1.0).abs();
        if k % 8 == 0 {
            at_cells = at_cells.max(d);
        } else {
            between = between.max(d);
        }
    }
    assert!(at_cells < 1e-9, "at whole cells f moved by {at_cells:e}");
    assert!(between < 1e-3, "between cells f moved by {between:e}");
}
