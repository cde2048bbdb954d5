//! Outputs smooth in the inputs (docs/model.md section 6, "Tolerance of the temperature solve"): the temperature solve converges tightly enough that finite-difference derivatives do not see its tolerance.

use creep_core::thermal::TemperatureSolve;
use creep_core::{Config, Inputs, Model};

/// F_x (N) after `steps` transient steps of 1 ms from the steady state, dry preset,
/// v = 10 m/s, F_N = 110 kN, at longitudinal creepage `cx`, with the configuration's
/// temperature solve.
fn fx_after(cx: f64, steps: usize) -> f64 {
    fx_after_with(
        cx,
        steps,
        Config::preset("dry").expect("preset").temperature_solve,
    )
}

/// [`fx_after`] with the temperature solve `solve`.
fn fx_after_with(cx: f64, steps: usize, solve: TemperatureSolve) -> f64 {
    let i = Inputs {
        cx,
        v: 10.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let mut m = Model::new(&Config::preset("dry").expect("preset")).expect("model");
    m.set_temperature_solve(solve);
    let mut fx = m.steady(&i).expect("steady").fx;
    for _ in 0..steps {
        fx = m.step(1e-3, &i).expect("step").fx;
    }
    fx
}

/// One ulp of c_x moves F_x by a rounding-sized amount, not by the solve's tolerance (before
/// the fix: 3e-2 N at c_x = -0.5 %, 47 steps), and central differences with relative
/// increments 1e-5, 1e-6, 1e-7 agree within 1e-3 (before: they differed in sign).
#[test]
fn fx_is_smooth_in_cx() {
    let (cx, steps) = (-0.005, 20);
    let f0 = fx_after(cx, steps);
    let jump = (fx_after(cx.next_up(), steps) - f0).abs();
    assert!(
        jump < 1e-6,
        "F_x moved by {jump:e} N for one ulp of c_x (F_x = {f0} N)"
    );
    let d: Vec<f64> = [1e-5, 1e-6, 1e-7]
        .iter()
        .map(|e| {
            let h = cx.abs() * e;
            (fx_after(cx + h, steps) - fx_after(cx - h, steps)) / (2.0 * h)
        })
        .collect();
    for x in &d {
        assert!(
            ((x - d[1]) / d[1]).abs() < 1e-3,
            "dF_x/dc_x by increments 1e-5, 1e-6, 1e-7: {d:?} N"
        );
    }
    // a derivative, not noise: not zero and below Kalker's initial slope (about 4e8 N per
    // unit creepage). Its size here is a property of the grid, not of the smoothness: c_x =
    // 0.5 % at 10 m/s is the flat top of the dry curve (steady slope 2e4-8e4 N on 320x84),
    // where 80x21 gives -1.1e6 N without the cold crossing (docs/model.md section 4) and
    // -9.2e4 N with it; the agreement of the three increments above is the smoothness check.
    assert!(
        d[1].abs() > 1e4 && d[1].abs() < 1e9,
        "dF_x/dc_x = {} N",
        d[1]
    );
}

/// The ulp test of [`fx_is_smooth_in_cx`] over the creep curve: at 24 creepages from the
/// adhesion-dominated start (0.1 %) past the peak to full sliding (20 %), where bristles
/// cross from elastic to plastic at every place in the contact, one ulp of c_x never moves
/// F_x by more than a rounding-sized amount (a branch of the bristle law chosen by a label
/// rather than by the state would show here as a jump).
#[test]
fn fx_is_smooth_in_cx_along_the_curve() {
    let steps = 5;
    let mut worst = (0.0, 0.0);
    for k in 0..24 {
        let cx = -0.001 * 200f64.powf(k as f64 / 23.0);
        let f0 = fx_after(cx, steps);
        let jump = (fx_after(cx.next_up(), steps) - f0).abs();
        if jump > worst.0 {
            worst = (jump, cx);
        }
    }
    assert!(
        worst.0 < 1e-6,
        "F_x moved by {:e} N for one ulp of c_x at c_x = {}",
        worst.0,
        worst.1
    );
}

/// Both smoothness checks above under each temperature solve: the predictor-corrector takes
/// a count of evaluations fixed by the predictor's miss (blended between two and three), not
/// by a tolerance, so one ulp of c_x moves F_x by a rounding-sized amount and central
/// differences with relative increments 1e-5 ... 1e-7 agree within 1e-3.
#[test]
fn fx_is_smooth_in_cx_under_each_temperature_solve() {
    for solve in TemperatureSolve::ALL {
        let (cx, steps) = (-0.005, 20);
        let f = |x: f64| fx_after_with(x, steps, solve);
        let f0 = f(cx);
        let jump = (f(cx.next_up()) - f0).abs();
        assert!(
            jump < 1e-6,
            "{solve:?}: F_x moved by {jump:e} N for one ulp of c_x"
        );
        let d: Vec<f64> = [1e-5, 1e-6, 1e-7]
            .iter()
            .map(|e| {
                let h = cx.abs() * e;
                (f(cx + h) - f(cx - h)) / (2.0 * h)
            })
            .collect();
        for x in &d {
            assert!(
                ((x - d[1]) / d[1]).abs() < 1e-3,
                "{solve:?}: dF_x/dc_x by increments 1e-5, 1e-6, 1e-7: {d:?} N"
            );
        }
        for k in 0..12 {
            let cx = -0.001 * 200f64.powf(k as f64 / 11.0);
            let jump = (fx_after_with(cx.next_up(), 5, solve) - fx_after_with(cx, 5, solve)).abs();
            assert!(
                jump < 1e-6,
                "{solve:?}: F_x moved by {jump:e} N for one ulp of c_x at c_x = {cx}"
            );
        }
    }
}
