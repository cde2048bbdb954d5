//! Prints the wall time of one transient ECF step (1 ms at 5 and 20 m/s, c_x = 15 %) per grid: median of repeated steps.
use creep_core::{Config, Grid, Inputs, Model};
use std::time::Instant;

fn main() {
    println!("v_mps,grid,us_per_1ms_step,real_time_factor");
    for v in [5.0, 20.0] {
        for (nx, ny) in [(20, 7), (20, 11), (40, 11), (40, 21), (80, 21)] {
            let mut c = Config::preset("table4.1").expect("preset");
            c.grid = Grid { nx, ny };
            let mut m = Model::new(&c).expect("model");
            let i = Inputs {
                cx: 0.15,
                v,
                fn_n: 110e3,
                ..Inputs::default()
            };
            m.steady(&i).expect("steady");
            let mut t = Vec::new();
            for k in 0..60 {
                let j = Inputs {
                    cx: 0.15 + 0.02 * ((k as f64) * 0.3).sin(),
                    ..i
                };
                let s = Instant::now();
                m.step(1e-3, &j).expect("step");
                t.push(s.elapsed().as_secs_f64());
            }
            t.sort_by(f64::total_cmp);
            let med = t[t.len() / 2];
            println!("{v},{nx}x{ny},{:.0},{:.2}", med * 1e6, 1e-3 / med);
        }
    }
}
