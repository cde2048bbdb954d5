//! Runs transient ECF steps (for profilers such as callgrind or perf).
use creep_core::{Config, Inputs, Model};
fn main() {
    let v: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20.0);
    let mut m = Model::new(&Config::preset("table4.1").expect("preset")).expect("model");
    let i = Inputs {
        cx: 0.15,
        v,
        fn_n: 110e3,
        ..Inputs::default()
    };
    m.steady(&i).expect("steady");
    let mut s = 0.0;
    for k in 0..20 {
        let j = Inputs {
            cx: 0.15 + 0.02 * ((k as f64) * 0.3).sin(),
            ..i
        };
        s += m.step(1e-3, &j).expect("step").f;
    }
    println!("{s}");
}
