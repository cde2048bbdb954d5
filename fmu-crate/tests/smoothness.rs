//! Outputs smooth in the inputs (docs/fmu.md, "Derivatives and Jacobians"), as a master sees
//! them: finite-difference derivatives of F_x, F_y, M_z with respect to c_x, c_y, spin and F_N,
//! with relative increments 1e-4 ... 1e-8, agree within 1 %.
//!
//! Two ways of forming them:
//! - a master's Jacobian at a communication point: save the FMU state, step once with one
//!   input raised or lowered, read the outputs, restore (`fmi2GetFMUstate`/`fmi2SetFMUstate`);
//! - the sensitivity of a whole run: every step from the initialization at the raised or
//!   lowered input (as creep-core's `tests/physics/smoothness.rs` does for F_x and c_x).
//!
//! Where the whole-run sensitivity to F_N is not differentiable at the scale of the larger
//! increments, the test says so (see [`whole_run_in_fn_has_kinks_of_the_lattice_phase`]).

mod common;
use common::{Fmu, OK};

/// The operating point of `examples/fn_scan.rs` with lateral creepage and spin: dry preset on
/// the grid 80 x 21 cell by cell (scheme 3; given explicitly: the FMU's start value of rel_tol
/// would choose a coarse grid at this speed, and ECF's default scheme is the higher-order
/// rules, below), v = 10 m/s, c_x = -0.5 %, c_y = 0.1 %, spin = 0.05 1/m, F_N = 110 kN, steps
/// of 1 ms.
const BASE: [(&str, f64); 4] = [("cx", -0.005), ("cy", 0.001), ("spin", 0.05), ("FN", 110e3)];
const STEPS: usize = 20;
const DT: f64 = 1e-3;
const INCREMENTS: [f64; 5] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
const OUTS: [&str; 3] = ["Fx", "Fy", "Mz"];

/// An initialized instance at `BASE` with `input` set to `x` (none: all at `BASE`), cell by
/// cell.
fn start(name: &str, input: Option<(&str, f64)>) -> Fmu {
    start_in(name, input, 3)
}

/// [`start`] in the scheme of code `scheme` (the parameter `scheme`).
fn start_in(name: &str, input: Option<(&str, f64)>, scheme: i32) -> Fmu {
    let mut f = Fmu::new(name);
    assert_eq!(f.set_string("preset", "dry"), OK);
    assert_eq!(f.set_int("nx", 80), OK);
    assert_eq!(f.set_int("ny", 21), OK);
    assert_eq!(f.set_int("scheme", scheme), OK);
    for (n, x) in BASE {
        let x = match input {
            Some((m, y)) if m == n => y,
            _ => x,
        };
        assert_eq!(f.set_real(n, x), OK, "{n} = {x}");
    }
    assert_eq!(f.set_real("v", 10.0), OK);
    assert_eq!(f.init(), OK);
    f
}

fn outputs(f: &Fmu) -> [f64; 3] {
    OUTS.map(|n| f.get(n))
}

/// Central differences of the outputs in `input` by each of `INCREMENTS` (relative to the
/// input's base value), from `pair(raised, lowered)` of the outputs.
fn derivatives(
    input: &str,
    mut pair: impl FnMut(f64, f64) -> ([f64; 3], [f64; 3]),
) -> Vec<[f64; 3]> {
    let x0 = BASE.iter().find(|(n, _)| *n == input).expect("input").1;
    INCREMENTS
        .iter()
        .map(|e| {
            let h = x0.abs() * e;
            let (p, m) = pair(x0 + h, x0 - h);
            std::array::from_fn(|k| (p[k] - m[k]) / (2.0 * h))
        })
        .collect()
}

/// Every derivative of `d` agrees with the one at increment 1e-6 within `rel`.
fn agree(what: &str, d: &[[f64; 3]], outs: &[usize], rel: f64, from: usize) {
    for &k in outs {
        let r = d[2][k];
        for (e, row) in INCREMENTS.iter().zip(d).skip(from) {
            assert!(
                (row[k] - r).abs() <= rel * r.abs(),
                "d{}/d{what} by increment {e:e}: {} against {r} (1e-6); all: {:?}",
                OUTS[k],
                row[k],
                d.iter().map(|x| x[k]).collect::<Vec<_>>()
            );
        }
        assert!(r != 0.0 && r.is_finite(), "d{}/d{what} = {r}", OUTS[k]);
    }
}

/// A master's Jacobian at a communication point (after `STEPS` steps): each entry of the
/// 3 x 4 Jacobian by increments 1e-4 ... 1e-8 (1e-5 ... 1e-8 for F_N, whose larger
/// increment spans lattice kinks) agrees within 1 % with the one at 1e-6.
#[test]
fn a_masters_jacobian_at_a_communication_point_is_smooth() {
    masters_jacobian_agrees(3, 8);
}

/// The same under the higher-order rules (scheme 2, ECF's default), down to increments of
/// 1e-7: at 1e-8 of F_N the difference of M_z is 2.4 % off the derivative at 1e-6 (0.2 % at
/// 1e-7), an error growing 10x per decade of the increment, i.e. a fixed step of about 1e-9
/// N m in M_z near the base point. Not the temperature solves: a Newton step after the
/// hardening root's search, or a 1000x tighter temperature tolerance, leave the 1e-8 entry
/// unchanged to five digits; a lattice-phase kink (see the F_N test below) is the suspect.
#[test]
fn a_masters_jacobian_under_the_higher_order_rules_is_smooth_to_1e_7() {
    masters_jacobian_agrees(2, 7);
}

/// A master's Jacobian in the scheme of code `scheme`, with increments down to 1e-`finest`.
fn masters_jacobian_agrees(scheme: i32, finest: i32) {
    let mut f = start_in(&format!("jacobian-{scheme}"), None, scheme);
    for _ in 0..STEPS {
        assert_eq!(f.step(DT), OK);
    }
    let saved = f.get_state();
    let t = f.time;
    for (input, x0) in BASE {
        let mut one_step = |x: f64| {
            f.set_state(saved);
            assert_eq!(f.set_real(input, x), OK);
            assert_eq!(f.step(DT), OK);
            let o = outputs(&f);
            assert_eq!(f.set_real(input, x0), OK);
            f.time = t;
            o
        };
        let d = derivatives(input, |p, m| (one_step(p), one_step(m)));
        let d = &d[..(finest - 3) as usize];
        eprintln!("{input}: {d:?}");
        // F_N changes the semi-axes and with them the cells the step rolls: an increment
        // of 1e-4 of F_N spans lattice kinks (nodes changing regime). Measured with the
        // Gauss-Legendre strips (docs/model.md section 3.1): M_z's slope changes by 0.6-1.2 %
        // at each of four kinks between +1e-5 and +5e-5 of F_N, so the 1e-4 difference is 1.7 %
        // off the local derivative (F_x 0.05 %); increments from 1e-5 down stay between kinks.
        // (With equal strips no kink happened to fall within 1e-4 here.)
        let from = if input == "FN" { 1 } else { 0 };
        agree(input, d, &[0, 1, 2], 0.01, from);
    }
    f.free_state(saved);
}

/// The whole run at the raised or lowered input: F_x in c_x, F_y and M_z in c_y and spin
/// agree within 1 % over 1e-4 ... 1e-8.
#[test]
fn a_whole_run_is_smooth_in_the_creepages_and_spin() {
    let run = |input: &str, x: f64| {
        let mut f = start(&format!("run-{input}-{x:e}"), Some((input, x)));
        for _ in 0..STEPS {
            assert_eq!(f.step(DT), OK);
        }
        outputs(&f)
    };
    for (input, outs) in [("cx", &[0usize][..]), ("cy", &[1, 2]), ("spin", &[1, 2])] {
        let d = derivatives(input, |p, m| (run(input, p), run(input, m)));
        eprintln!("{input}: {d:?}");
        agree(input, &d, outs, 0.01, 0);
    }
}

/// The whole run at a raised or lowered F_N is differentiable only piecewise at the scale
/// of the larger increments. The bristle lattice is fixed in coordinates normalized by the
/// semi-axes, so it rolls v t / (2 a / nx) cells in a time t: F_N changes a (a ~ F_N^(1/3))
/// and with it the lattice's phase at time t by (cells rolled) / 3 per unit relative change
/// of F_N (about 1000 cells on the central strip after 20 ms here, more on the outer strips,
/// whose cells are shorter). The outputs ripple with the phase (the discretization: about
/// +-1 N of F_x per 1/20 cell, and a node that changes regime is a kink), so an increment
/// of 1e-4 or 1e-5 of F_N spans kinks and sees the ripple, not the derivative; the
/// increments 1e-6 ... 1e-8 stay between kinks and agree. A master's Jacobian (one step from
/// a saved state, above) is less affected: its perturbation rolls one step's cells only,
/// and only its 1e-4 increment spans kinks.
#[test]
fn whole_run_in_fn_has_kinks_of_the_lattice_phase() {
    let run = |x: f64| {
        let mut f = start(&format!("run-FN-{x:e}"), Some(("FN", x)));
        for _ in 0..STEPS {
            assert_eq!(f.step(DT), OK);
        }
        outputs(&f)
    };
    let d = derivatives("FN", |p, m| (run(p), run(m)));
    eprintln!("FN: {d:?}");
    // 1e-6, 1e-7, 1e-8: differentiable there
    agree("FN", &d, &[0], 0.01, 2);
}

/// No direct feedthrough at a communication point: the outputs are those of the completed
/// step, so an input set afterwards changes nothing until the next step (the reason
/// fmi2GetDirectionalDerivative, outputs with respect to inputs at the current instant,
/// would be identically zero here; docs/fmu.md, "Derivatives and Jacobians").
#[test]
fn outputs_at_a_communication_point_do_not_depend_on_inputs_set_since() {
    let mut f = start("feedthrough", None);
    assert_eq!(f.step(DT), OK);
    let before = common::OUTPUT_NAMES.map(|n| f.get(n).to_bits());
    for (n, x) in [
        ("cx", 0.02),
        ("cy", -0.003),
        ("spin", 0.4),
        ("FN", 90e3),
        ("v", 12.0),
    ] {
        assert_eq!(f.set_real(n, x), OK, "{n}");
    }
    assert_eq!(common::OUTPUT_NAMES.map(|n| f.get(n).to_bits()), before);
    // the next step does see them
    assert_eq!(f.step(DT), OK);
    assert_ne!(f.get("Fx").to_bits(), before[0]);
}
