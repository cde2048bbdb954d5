//! Measures how F_x, F_y, M_z depend on the normal force F_N: central differences with
//! relative increments 1e-4..1e-8 and a fine scan of F_x around F_N, steady and after
//! transient steps (docs/fmu.md, "Derivatives and Jacobians").
//!
//! Usage: `cargo run --release -p ecf-fmu --example fn_scan [preset] [steps] [scan points]`
//! (defaults: dry, the preset's grid unless ECF_NX, ECF_NY, 47 steps of 1 ms from the steady state at v = 10 m/s, c_x = -0.5 %,
//! F_N = 110 kN; ECF_CY, ECF_SPIN, ECF_V, ECF_CX, ECF_FN, ECF_DT set those inputs).
use creep_core::{Config, Inputs, Model, Outputs};

fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// The preset, with the grid of ECF_NX, ECF_NY where they are set.
fn config(preset: &str) -> Config {
    let mut c = Config::preset(preset).expect("preset");
    c.grid.nx = env("ECF_NX", c.grid.nx as f64) as usize;
    c.grid.ny = env("ECF_NY", c.grid.ny as f64) as usize;
    c
}

/// Outputs after `steps` steps of `dt` from the steady state of `i`.
fn run(preset: &str, i: &Inputs, steps: usize, dt: f64) -> Outputs {
    let mut m = Model::new(&config(preset)).expect("model");
    let mut out = m.steady(i).expect("steady");
    for _ in 0..steps {
        out = m.step(dt, i).expect("step");
    }
    out
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map(String::as_str).unwrap_or("dry");
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(47);
    let points: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(0);
    let dt = env("ECF_DT", 1e-3);
    let base = Inputs {
        cx: env("ECF_CX", -0.005),
        cy: env("ECF_CY", 0.0),
        spin: env("ECF_SPIN", 0.0),
        v: env("ECF_V", 10.0),
        fn_n: env("ECF_FN", 110e3),
        ..Inputs::default()
    };
    // ECF_LAST set: F_N perturbed in the last step only (what a master forming a Jacobian at
    // a communication point does: restore the state, step with a perturbed input); else from
    // the start (the whole trajectory at the perturbed F_N)
    let last_only = std::env::var_os("ECF_LAST").is_some();
    let at = |fn_n: f64| {
        let mut i = base;
        i.fn_n = fn_n;
        if !last_only || steps == 0 {
            return run(preset, &i, steps, dt);
        }
        let mut m = Model::new(&config(preset)).expect("model");
        m.steady(&base).expect("steady");
        for _ in 0..steps - 1 {
            m.step(dt, &base).expect("step");
        }
        m.step(dt, &i).expect("step")
    };
    let f0 = base.fn_n;
    let o0 = at(f0);
    println!(
        "{preset}, {steps} steps of {dt} s: F_x = {:.9} N, a = {:.9e} m, b = {:.9e} m",
        o0.fx, o0.a, o0.b
    );
    for e in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
        let h = f0 * e;
        let (p, m) = (at(f0 + h), at(f0 - h));
        println!(
            "increment {e:.0e}: dF_x/dF_N = {:.6e}, dF_y/dF_N = {:.6e}, dM_z/dF_N = {:.6e}, one-sided +/-: {:.6e} {:.6e}",
            (p.fx - m.fx) / (2.0 * h),
            (p.fy - m.fy) / (2.0 * h),
            (p.mz - m.mz) / (2.0 * h),
            (p.fx - o0.fx) / h,
            (o0.fx - m.fx) / h
        );
    }
    if std::env::var_os("ECF_RIPPLE").is_some() {
        // constant inputs after the run: F_x over 2 cells of rolling in steps of 1/20 cell
        // (the lattice's phase moves, nothing else changes)
        let mut m = Model::new(&config(preset)).expect("model");
        m.steady(&base).expect("steady");
        for _ in 0..steps {
            m.step(dt, &base).expect("step");
        }
        let cfg = config(preset);
        let dx = 2.0 * o0.a / cfg.grid.nx as f64;
        let h = dx / 20.0 / base.v;
        let mut last = m.outputs().fx;
        for k in 0..40 {
            let o = m.step(h, &base).expect("step");
            println!(
                "ripple {k:2}: F_x = {:.6} N, change {:+.6} N, frac_plastic {:.6}, frac_sliding {:.6}",
                o.fx,
                o.fx - last,
                o.frac_plastic,
                o.frac_sliding
            );
            last = o.fx;
        }
    }
    if points > 0 {
        // F_x at F_N (1 + s), s from -2e-4 to 2e-4: the slope between neighbours
        let s: Vec<f64> = (0..=points)
            .map(|k| -2e-4 + 4e-4 * k as f64 / points as f64)
            .collect();
        let fx: Vec<f64> = s.iter().map(|s| at(f0 * (1.0 + s)).fx).collect();
        for k in 0..points {
            let slope = (fx[k + 1] - fx[k]) / (f0 * (s[k + 1] - s[k]));
            println!(
                "s = {:+.6e}: F_x = {:.9} N, slope to next = {:.6e}",
                s[k], fx[k], slope
            );
        }
    }
}
