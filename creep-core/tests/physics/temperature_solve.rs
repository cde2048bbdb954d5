//! The predictor-corrector temperature solve against the exact one (docs/model.md section 9): on the same grid and scheme, F_x and P_fric within 0.1 % and the T_max rise within 0.5 % over transient steps and steady curves.

use creep_core::config::Geometry;
use creep_core::engine::Scheme;
use creep_core::thermal::TemperatureSolve;
use creep_core::{Config, Contact, Grid, Inputs};

/// `preset` on an `nx` x `ny` grid in `scheme` with the temperature solve `solve`, semi-axes
/// 7.63 x 7.88 mm at 110 kN, every strip computed.
fn contact(
    preset: &str,
    (nx, ny): (usize, usize),
    scheme: Scheme,
    solve: TemperatureSolve,
) -> Contact {
    let mut cfg = Config::preset(preset).expect("preset");
    cfg.grid = Grid { nx, ny };
    cfg.geometry = Geometry::SemiAxes {
        a: 7.63e-3,
        b: 7.88e-3,
        fn_ref: 110e3,
    };
    cfg.temperature_solve = solve;
    let mut c = Contact::new(&cfg).expect("contact");
    c.set_scheme(scheme);
    c.set_mirror_strips(false);
    c
}

fn inputs(cx: f64, v: f64) -> Inputs {
    Inputs {
        cx,
        v,
        fn_n: 110e3,
        t_bulk: 20.0,
        ..Inputs::default()
    }
}

/// (F_x, T_max - T_bulk, P_fric) after each of `steps` steps of `dt` from the steady state at
/// c_x = `from` to c_x = `to`, at speed `v`.
fn step_response(
    c: &mut Contact,
    v: f64,
    dt: f64,
    (from, to): (f64, f64),
    steps: usize,
) -> Vec<[f64; 3]> {
    c.steady(&inputs(from, v)).expect("steady");
    (0..steps)
        .map(|_| {
            let o = c.step(dt, &inputs(to, v)).expect("step");
            [o.fx, o.t_max - 20.0, o.p_fric]
        })
        .collect()
}

/// The largest difference per quantity, % of the exact response's largest magnitude.
fn diff(exact: &[[f64; 3]], other: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|q| {
        let scale = exact.iter().map(|x| x[q].abs()).fold(0.0, f64::max);
        100.0
            * exact
                .iter()
                .zip(other)
                .map(|(x, y)| (x[q] - y[q]).abs())
                .fold(0.0, f64::max)
            / scale
    })
}

const LIMITS: [f64; 3] = [0.1, 0.5, 0.1];

/// Creepage steps of the accuracy benchmark on coarse grids (the predictor misses most there),
/// under the higher-order rules and cell by cell: within the limits, and not bit-identical
/// (the cheaper solve runs).
#[test]
fn the_predictor_corrector_agrees_with_the_exact_solve_after_creepage_steps() {
    for (preset, v, dt, cx, grid, scheme) in [
        (
            "table4.1",
            20.0,
            1e-4,
            (0.002, 0.05),
            (20, 3),
            Scheme::CellsHigher,
        ),
        (
            "table4.1",
            30.0,
            2.5e-4,
            (0.01, 0.15),
            (10, 3),
            Scheme::CellsHigher,
        ),
        (
            "wet",
            30.0,
            2.5e-4,
            (0.01, 0.15),
            (20, 3),
            Scheme::CellsMarch,
        ),
        ("dry", 5.0, 1e-3, (0.01, 0.15), (10, 3), Scheme::CellsHigher),
    ] {
        let steps = (12.0 * 7.63e-3 / v / dt) as usize;
        let run = |s| step_response(&mut contact(preset, grid, scheme, s), v, dt, cx, steps);
        let (exact, pc) = (
            run(TemperatureSolve::Exact),
            run(TemperatureSolve::PredictorCorrector),
        );
        let d = diff(&exact, &pc);
        for q in 0..3 {
            assert!(
                d[q] <= LIMITS[q],
                "{preset} {v} m/s {grid:?} {scheme:?}: differences {d:?} %"
            );
        }
        assert!(
            d[0] > 0.0,
            "{preset} {v} m/s {grid:?}: bit-identical, the predictor-corrector did not run"
        );
    }
}

/// Steady curves from 0.2 % to 30 % creepage at 5 and 30 m/s on the default grid (cells) and a
/// coarse grid under the higher-order rules: within the limits.
#[test]
fn the_predictor_corrector_agrees_with_the_exact_solve_on_steady_curves() {
    for preset in ["dry", "table4.1", "wet"] {
        for (grid, scheme) in [
            ((80, 21), Scheme::CellsMarch),
            ((20, 3), Scheme::CellsHigher),
        ] {
            for v in [5.0, 30.0] {
                let curve = |s| {
                    let mut c = contact(preset, grid, scheme, s);
                    [0.002, 0.01, 0.03, 0.1, 0.3]
                        .map(|cx| {
                            let o = c.steady(&inputs(cx, v)).expect("steady");
                            [o.fx, o.t_max - 20.0, o.p_fric]
                        })
                        .to_vec()
                };
                let d = diff(
                    &curve(TemperatureSolve::Exact),
                    &curve(TemperatureSolve::PredictorCorrector),
                );
                for q in 0..3 {
                    assert!(
                        d[q] <= LIMITS[q],
                        "{preset} {v} m/s {grid:?}: differences {d:?} %"
                    );
                }
            }
        }
    }
}

/// The temperature solve says how to compute, not what: a state saved by a model with one
/// solve loads into a model with the other, and continues there.
#[test]
fn a_state_loads_into_a_model_of_the_other_temperature_solve() {
    use creep_core::Model;
    let model = |s: TemperatureSolve| {
        let mut cfg = Config::preset("table4.1").expect("preset");
        cfg.grid = Grid { nx: 20, ny: 3 };
        cfg.temperature_solve = s;
        Model::new(&cfg).expect("model")
    };
    let mut pc = model(TemperatureSolve::PredictorCorrector);
    pc.steady(&inputs(0.01, 20.0)).expect("steady");
    pc.step(1e-4, &inputs(0.03, 20.0)).expect("step");
    let mut exact = model(TemperatureSolve::Exact);
    exact.load_state(&pc.save_state()).expect("the state loads");
    assert_eq!(exact.time().to_bits(), pc.time().to_bits());
    let (a, b) = (
        exact.step(1e-4, &inputs(0.03, 20.0)).expect("step").fx,
        pc.step(1e-4, &inputs(0.03, 20.0)).expect("step").fx,
    );
    assert!(
        (a / b - 1.0).abs() < 1e-3,
        "F_x {a} (exact) against {b} (predictor)"
    );
}
