//! Measures how smooth the transient outputs are in the inputs: finite-difference derivatives of F_x, F_y, M_z with relative increments 1e-4..1e-8, and the jump of F_x per ulp of c_x.
//!
//! Usage: `cargo run --release -p creep-core --example smoothness [preset] [steps] [--once]`
//! (`--once`: one trajectory only, for `valgrind --tool=callgrind`)
//! (defaults: dry, 47 steps of 1 ms from the steady state at v = 10 m/s, c_x = -0.5 %,
//! F_N = 110 kN, c_y and spin 0 unless ECF_CY, ECF_SPIN say otherwise; docs/model.md section 6,
//! "Tolerance of the temperature solve").
//! Derivatives are central differences; increments are relative to the input's value (to
//! 0.005 for c_x, c_y, 0.5 1/m for spin where the value is 0).
use creep_core::{Config, Inputs, Model, Outputs};

/// Outputs after `steps` steps of 1 ms from the steady state of `i`, every step at `i`
/// with c_x raised by `ramp_ulps` ulps per step (0: constant inputs).
fn run(preset: &str, i: &Inputs, steps: usize, ramp_ulps: usize) -> Outputs {
    let mut m = Model::new(&Config::preset(preset).expect("preset")).expect("model");
    let mut out = m.steady(i).expect("steady");
    let mut j = *i;
    for _ in 0..steps {
        for _ in 0..ramp_ulps {
            j.cx = j.cx.next_up();
        }
        out = m.step(1e-3, &j).expect("step");
    }
    out
}

/// An f64 from the environment, else `default`.
fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map(String::as_str).unwrap_or("dry");
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(47);
    let base = Inputs {
        cx: -0.005,
        cy: env("ECF_CY", 0.0),
        spin: env("ECF_SPIN", 0.0),
        v: 10.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let o0 = run(preset, &base, steps, 0);
    if args.iter().any(|a| a == "--once") {
        // one trajectory only (for instruction counts)
        println!("{preset}, {steps} steps: F_x = {:.9} N", o0.fx);
        return;
    }
    let o1 = run(preset, &base, steps, 1);
    println!(
        "{preset}, {steps} steps of 1 ms: F_x = {:.6} N; c_x raised 1 ulp per step: dF_x = {:.3e} N ({:.2e} relative), dP_fric = {:.3e} W",
        o0.fx,
        o1.fx - o0.fx,
        (o1.fx - o0.fx) / o0.fx.abs(),
        o1.p_fric - o0.p_fric
    );
    let mut one = base;
    one.cx = base.cx.next_up();
    let ou = run(preset, &one, steps, 0);
    println!(
        "c_x one ulp ({:.1e}) higher throughout: dF_x = {:.3e} N",
        one.cx - base.cx,
        ou.fx - o0.fx
    );
    type Get = fn(&Outputs) -> f64;
    let outs: [(&str, Get); 3] = [("F_x", |o| o.fx), ("F_y", |o| o.fy), ("M_z", |o| o.mz)];
    type Set = fn(&mut Inputs, f64);
    // (name, setter, value, scale of the increment where the value is 0)
    let ins: [(&str, Set, f64, f64); 4] = [
        ("c_x", |i, x| i.cx = x, base.cx, 0.005),
        ("c_y", |i, x| i.cy = x, base.cy, 0.005),
        ("spin", |i, x| i.spin = x, base.spin, 0.5),
        ("F_N", |i, x| i.fn_n = x, base.fn_n, 110e3),
    ];
    for (iname, set, x0, scale) in ins {
        let mut rows = Vec::new();
        for e in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
            let d = if x0 == 0.0 { scale } else { x0.abs() } * e;
            let (mut ip, mut im) = (base, base);
            set(&mut ip, x0 + d);
            set(&mut im, x0 - d);
            let (op, om) = (run(preset, &ip, steps, 0), run(preset, &im, steps, 0));
            rows.push((e, outs.map(|(_, g)| (g(&op) - g(&om)) / (2.0 * d))));
        }
        for (k, (oname, _)) in outs.iter().enumerate() {
            let ds: Vec<f64> = rows.iter().map(|r| r.1[k]).collect();
            // spread: (max - min) / |estimate at 1e-6|, over all increments and over 1e-5..1e-8
            let spread = |d: &[f64]| {
                let (lo, hi) = d
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                        (l.min(*x), h.max(*x))
                    });
                (hi - lo) / ds[2].abs()
            };
            let (all, fine) = (spread(&ds), spread(&ds[1..]));
            print!("d{oname}/d{iname}: ");
            for d in &ds {
                print!("{d:.6e} ");
            }
            println!(" | spread 1e-4..1e-8: {all:.2e}, 1e-5..1e-8: {fine:.2e}");
        }
    }
}
