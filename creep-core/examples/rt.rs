//! Quick real-time factors of transient ECF (dry, 80x21, c_x = 15 %) and steady ns/cell, for development.
use creep_core::{Config, Grid, Inputs, Model};
use std::time::Instant;

fn main() {
    let preset = std::env::args().nth(1).unwrap_or_else(|| "dry".into());
    let sim: f64 = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.02);
    for (v, dt) in [(5.0, 1e-3), (20.0, 1e-4), (30.0, 2.5e-4)] {
        let mut c = Config::preset(&preset).expect("preset");
        c.grid = Grid { nx: 80, ny: 21 };
        let mut m = Model::new(&c).expect("model");
        let i = Inputs {
            cx: 0.15,
            v,
            fn_n: 110e3,
            ..Inputs::default()
        };
        m.steady(&i).expect("steady");
        let n = (sim / dt).round() as usize;
        let t = Instant::now();
        let mut f = 0.0;
        for k in 0..n {
            let j = Inputs {
                cx: 0.15 + 0.01 * ((k as f64) * 0.3).sin(),
                ..i
            };
            f += m.step(dt, &j).expect("step").f;
        }
        let w = t.elapsed().as_secs_f64();
        println!(
            "transient {preset} v={v} dt={dt}: wall/sim = {:.2}  (mean f {:.5})",
            w / (n as f64 * dt),
            f / n as f64
        );
    }
    for p in ["fastsim", "dry", "table4.1"] {
        let mut c = Config::preset(p).expect("preset");
        c.grid = Grid { nx: 80, ny: 21 };
        let mut m = Model::new(&c).expect("model");
        let mut ts = Vec::new();
        for cx in [0.002, 0.02, 0.1, 0.3] {
            let i = Inputs {
                cx,
                v: 20.0,
                fn_n: 110e3,
                ..Inputs::default()
            };
            let t = Instant::now();
            for _ in 0..20 {
                std::hint::black_box(m.steady(&i).expect("steady"));
            }
            ts.push(t.elapsed().as_secs_f64() / 20.0 / (81.0 * 21.0) * 1e9);
        }
        println!(
            "steady {p}: ns/cell {:?}",
            ts.iter().map(|x| x.round()).collect::<Vec<_>>()
        );
    }
}
