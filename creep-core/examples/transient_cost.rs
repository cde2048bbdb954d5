//! Prints the cost of transient ECF (dry, c_x = 15 % with a small wobble, F_N = 110 kN) per grid, speed and communication step: wall time / simulated time. Args: [simulated s] [threads] [cells|continuous].
use creep_core::engine::Scheme;
use creep_core::{Config, Grid, Inputs, Model};
use std::time::Instant;

fn main() {
    let sim: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.05);
    let threads: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let scheme = match std::env::args().nth(3).as_deref() {
        Some("continuous") => Scheme::Continuous,
        _ => Scheme::CellsMarch,
    };
    println!("({threads} thread(s), scheme {scheme:?})");
    println!("| grid | v (m/s) | step 0.1 ms | step 0.25 ms | step 1 ms |");
    println!("|---|---|---|---|---|");
    for (nx, ny) in [(16, 9), (20, 11), (40, 21), (80, 21)] {
        for v in [5.0, 20.0, 30.0] {
            let mut row = format!("| {nx} x {ny} | {v} |");
            for dt in [1e-4, 2.5e-4, 1e-3] {
                let mut c = Config::preset("dry").expect("preset");
                c.grid = Grid { nx, ny };
                let mut m = Model::new(&c).expect("model");
                m.set_threads(threads).expect("threads");
                m.set_scheme(scheme);
                let i = Inputs {
                    cx: 0.15,
                    v,
                    fn_n: 110e3,
                    ..Inputs::default()
                };
                m.steady(&i).expect("steady");
                let n = ((sim / dt) as usize).max(10);
                let mut t = Vec::with_capacity(n);
                for k in 0..n {
                    let j = Inputs {
                        cx: 0.15 + 0.01 * ((k as f64) * 0.3).sin(),
                        ..i
                    };
                    let s = Instant::now();
                    m.step(dt, &j).expect("step");
                    t.push(s.elapsed().as_secs_f64());
                }
                t.sort_by(f64::total_cmp);
                let med = t[t.len() / 2];
                row += &format!(" {:.2} |", med / dt);
            }
            println!("{row}");
        }
    }
    println!("(wall time / simulated time, one contact; < 1 is faster than real time)");
}
