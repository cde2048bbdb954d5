//! Runs many steady ECF solves (for profilers such as callgrind or perf).
use creep_core::{Config, Inputs, Model};
fn main() {
    let mut m = Model::new(&Config::preset("table4.1").expect("preset")).expect("model");
    let mut s = 0.0;
    for k in 0..200 {
        let cx = 0.002 + 0.3 * (k % 20) as f64 / 20.0;
        s += m
            .steady(&Inputs {
                cx,
                v: 20.0,
                fn_n: 110e3,
                ..Inputs::default()
            })
            .expect("steady")
            .f;
    }
    println!("{s}");
}
