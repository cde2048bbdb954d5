//! Each fast path against the general path, with every catalogue effect switched on in turn: the path is either not taken or agrees with the general one.

use super::common::{preset, with_grid};
use creep_core::effects::{Effect, CATALOGUE};
use creep_core::engine::FastPath;
use creep_core::{Config, Contact, Inputs, Outputs};

/// A configuration on which `path` is taken, and how closely the general path must agree
/// with it (see [`agree`]).
fn base(path: FastPath) -> (Config, Tolerance) {
    match path {
        // the march of FASTSIM multiplies by reciprocals where the general update divides:
        // equal to rounding (as engine/mod.rs's own test of the steady march)
        FastPath::Coulomb => (preset("fastsim"), Tolerance::Rounding),
        // the scalar and the general temperature solve both stop at 1e-4 relative change of
        // the softening factors: 2e-4 between them (as tests/physics/softening_solve.rs)
        FastPath::Softening => (preset("table4.1"), Tolerance::Solve),
        // L_e once per move is the same number as L_e per trial temperature (divided by a
        // temperature factor of exactly 1): bit for bit
        FastPath::FixedLe => (preset("table4.1"), Tolerance::Exact),
        // the isothermal move is the general move's material and stress update without the
        // temperature solve: bit for bit, on the preset without its temperature
        FastPath::Cold => {
            let mut cfg = preset("table4.1");
            cfg.effects.remove(Effect::Temperature);
            (cfg, Tolerance::Exact)
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum Tolerance {
    Exact,
    Rounding,
    Solve,
}

/// Outputs of the fast (`a`) and the general (`b`) path within `tol`.
fn agree(what: &str, a: &Outputs, b: &Outputs, tol: Tolerance) {
    let pairs = [
        ("fx", a.fx, b.fx),
        ("fy", a.fy, b.fy),
        ("mz", a.mz, b.mz),
        ("p_fric", a.p_fric, b.p_fric),
        ("t_max", a.t_max, b.t_max),
        ("t_mean", a.t_mean, b.t_mean),
        ("frac_elastic", a.frac_elastic, b.frac_elastic),
        ("frac_plastic", a.frac_plastic, b.frac_plastic),
        ("frac_sliding", a.frac_sliding, b.frac_sliding),
    ];
    for (name, x, y) in pairs {
        let ok = match tol {
            Tolerance::Exact => x.to_bits() == y.to_bits(),
            Tolerance::Rounding => (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs())),
            Tolerance::Solve if name.starts_with("frac") => {
                // a bristle at a regime boundary may fall on either side within the tolerance
                (x - y).abs() <= 0.02
            }
            Tolerance::Solve => {
                // forces, moment and power within 2e-4 (plus 1 N, 1 N m, 1 W), temperature
                // rises within 2e-4 (plus 1 mK)
                let (x, y, floor) = if name.starts_with("t_") {
                    (x - 20.0, y - 20.0, 1e-3)
                } else {
                    (x, y, 1.0)
                };
                (x - y).abs() <= 2e-4 * x.abs().max(y.abs()) + floor
            }
        };
        assert!(ok, "{what}: {name} {x} (fast path) vs {y} (general path)");
    }
}

/// Steady states at four operating points, then 12 transient steps of changing creepage,
/// speed and load from the last one, on both contacts.
fn compare(what: &str, fast: &mut Contact, general: &mut Contact, tol: Tolerance) {
    for (cx, cy, spin, v) in [
        (0.002, 0.0, 0.0, 20.0),
        (0.02, 0.003, 0.0, 5.0),
        (-0.1, 0.0, 0.8, 30.0),
        (0.01, -0.002, -1.0, 12.0),
    ] {
        let i = Inputs {
            cx,
            cy,
            spin,
            v,
            fn_n: 110e3,
            ..Inputs::default()
        };
        let a = fast.steady(&i).expect("steady");
        let b = general.steady(&i).expect("steady");
        agree(&format!("{what} steady {i:?}"), &a, &b, tol);
    }
    for k in 0..12u32 {
        let i = Inputs {
            cx: 0.01 + 0.08 * (k as f64 * 0.7).sin().abs(),
            cy: 0.001 * (k as f64).cos(),
            v: if k < 6 { 12.0 } else { 25.0 },
            fn_n: 100e3 + 2e3 * k as f64,
            ..Inputs::default()
        };
        let dt = if k % 3 == 0 { 3e-4 } else { 7e-5 };
        let a = fast.step(dt, &i).expect("step");
        let b = general.step(dt, &i).expect("step");
        agree(&format!("{what} step {k}"), &a, &b, tol);
    }
}

/// For each fast path and each effect of the catalogue switched on in addition to the
/// path's base configuration: either the path is not taken, or the fast and the general path
/// agree within the path's tolerance. A new effect is off every path until it is added to
/// a path's supported set (creep-core/src/engine/fastpath.rs), and then this test holds
/// that addition to the general path's results.
#[test]
fn each_effect_is_off_a_fast_path_or_agrees_with_the_general_path() {
    for path in FastPath::ALL {
        let (cfg0, tol) = base(path);
        let mut taken = Vec::new();
        for info in CATALOGUE {
            let mut cfg = with_grid(cfg0.clone(), 16, 5);
            cfg.effects.insert(info.effect);
            let mut fast = Contact::new(&cfg).expect("contact");
            let mut general = Contact::new(&cfg).expect("contact");
            // the exact temperature solve on both: the paths agree within its tolerance (the
            // predictor-corrector's own agreement: tests/physics/temperature_solve.rs)
            for c in [&mut fast, &mut general] {
                c.set_temperature_solve(creep_core::thermal::TemperatureSolve::Exact);
            }
            // the other fast paths as the engine chooses them, on both contacts, except that
            // the scalar solve would return before the fixed L_e is used
            if path == FastPath::FixedLe {
                fast.set_fast_path(FastPath::Softening, false);
                general.set_fast_path(FastPath::Softening, false);
            }
            if !general.set_fast_path(path, false) {
                assert!(!fast.fast_path(path));
                continue;
            }
            assert!(fast.fast_path(path) && !general.fast_path(path));
            taken.push(info.name);
            compare(
                &format!("{path:?} + {}", info.name),
                &mut fast,
                &mut general,
                tol,
            );
        }
        // the base configuration itself takes the path (its own effects switched on again)
        assert!(
            !taken.is_empty(),
            "{path:?}: not taken with any effect switched on"
        );
        eprintln!("{path:?}: taken with {taken:?}");
    }
}

/// Under the higher-order rules a move's start node comes from the lattice cache (or from
/// the previous leading-edge sub-move) where the move starts on a node.
/// Computing every start node where its move starts gives the same outputs to rounding,
/// also across a reversal of the rolling direction and a lift-off, after which the node
/// states are reset where the bristles stand, between the nodes (where the cache would
/// give the wrong node: up to 2e-4 of F_x on wet).
#[test]
fn cached_start_nodes_change_nothing_across_reversal_and_lift_off() {
    use creep_core::engine::Scheme;
    for p in ["wet", "table4.1"] {
        let cfg = with_grid(preset(p), 10, 3);
        let run = |cache: bool| -> Vec<Outputs> {
            let mut c = Contact::new(&cfg).expect("contact");
            c.set_scheme(Scheme::CellsHigher);
            c.set_start_node_cache(cache);
            let i = |v: f64, fn_n: f64| Inputs {
                cx: 0.05,
                v,
                fn_n,
                ..Inputs::default()
            };
            c.steady(&i(20.0, 110e3)).expect("steady");
            // 0.1 ms steps of 2 mm (about 1.3 cells: the phase is rarely 0); reversed at
            // step 10, lifted off over steps 20-24, back in contact from 25
            (0..40)
                .map(|k| {
                    let v = if k < 10 { 20.0 } else { -20.0 };
                    let fn_n = if (20..25).contains(&k) { 0.0 } else { 110e3 };
                    c.step(1e-4, &i(v, fn_n)).expect("step")
                })
                .collect()
        };
        let (cached, computed) = (run(true), run(false));
        for (k, (a, b)) in cached.iter().zip(&computed).enumerate() {
            agree(&format!("{p} step {k}"), a, b, Tolerance::Rounding);
        }
        // the reversal and the re-contact did happen: forces against the new direction
        // the contact carries load before, after the reversal and after the re-contact (F_x
        // keeps its sign: the creepage is taken over |v|), nothing while lifted off
        for k in [5, 15, 35] {
            assert!(
                cached[k].fx > 0.5 * cached[5].fx,
                "{p} step {k}: {}",
                cached[k].fx
            );
        }
        assert_eq!(cached[22].fx, 0.0, "{p}: lifted off");
    }
}
