//! A fixed small workload for instruction counting (valgrind --tool=callgrind): steady dry and FASTSIM at four creepages, then 20 transient dry steps of 0.1 ms at 20 m/s (cells march; `continuous`: the continuous scheme), on 80x21.
use creep_core::{Config, Grid, Inputs, Model};
fn main() {
    let what = std::env::args().nth(1).unwrap_or_else(|| "all".into());
    let mk = |p: &str| {
        let mut c = Config::preset(p).expect("preset");
        c.grid = Grid { nx: 80, ny: 21 };
        Model::new(&c).expect("model")
    };
    let mut s = 0.0;
    for p in ["dry", "fastsim"] {
        if what != "all" && what != p {
            continue;
        }
        let mut m = mk(p);
        for cx in [0.002, 0.02, 0.1, 0.3] {
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
    }
    if what == "all" || what == "transient" || what == "continuous" {
        let mut m = mk("dry");
        if what == "continuous" {
            m.set_scheme(creep_core::engine::Scheme::Continuous);
        }
        let i = Inputs {
            cx: 0.15,
            v: 20.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        m.steady(&i).expect("steady");
        for k in 0..20 {
            let j = Inputs {
                cx: 0.15 + 0.01 * (k as f64 * 0.3).sin(),
                ..i
            };
            s += m.step(1e-4, &j).expect("step").f;
        }
    }
    println!("{s}");
}
