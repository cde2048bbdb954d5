//! Runs many steady FASTSIM solves on 80x21 (for profilers such as callgrind or perf).
use creep_core::{Config, Grid, Inputs, Model};
fn main() {
    let mut c = Config::preset("fastsim").expect("preset");
    c.grid = Grid { nx: 80, ny: 21 };
    let mut m = Model::new(&c).expect("model");
    let mut s = 0.0;
    for k in 0..4000 {
        let cx = 0.002 + 0.3 * (k % 20) as f64 / 20.0;
        let i = Inputs {
            cx,
            v: 20.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        s += m.steady(&i).expect("steady").f;
    }
    println!("{s}");
}
