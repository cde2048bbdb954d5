//! Prints the cost ratio (steady ECF with temperature) / FASTSIM on the same grid, measured interleaved in one run (medians).
use creep_core::{Config, Grid, Inputs, Model};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let grids = [(20, 11), (40, 21), (80, 21)];
    let creepages = [0.002, 0.02, 0.1, 0.3];
    println!("grid,creepage,fastsim_us,ecf_us,ratio_ecf_over_fastsim");
    for (nx, ny) in grids {
        let mk = |name: &str| {
            let mut c = Config::preset(name).expect("preset");
            c.grid = Grid { nx, ny };
            Model::new(&c).expect("model")
        };
        let (mut fs, mut ecf) = (mk("fastsim"), mk("table4.1"));
        let mut all = Vec::new();
        for cx in creepages {
            let i = Inputs {
                cx,
                v: 20.0,
                fn_n: 110e3,
                ..Inputs::default()
            };
            let (mut tf, mut te) = (Vec::new(), Vec::new());
            for _ in 0..41 {
                // interleaved so that machine noise hits both alike
                let t = Instant::now();
                for _ in 0..10 {
                    std::hint::black_box(fs.steady(&i).expect("fastsim"));
                }
                tf.push(t.elapsed().as_secs_f64() / 10.0);
                let t = Instant::now();
                for _ in 0..10 {
                    std::hint::black_box(ecf.steady(&i).expect("ecf"));
                }
                te.push(t.elapsed().as_secs_f64() / 10.0);
            }
            let (mf, me) = (median(tf), median(te));
            all.push(me / mf);
            println!(
                "{nx}x{ny},{cx},{:.1},{:.1},{:.2}",
                mf * 1e6,
                me * 1e6,
                me / mf
            );
        }
        println!("{nx}x{ny},median,,,{:.2}", median(all));
    }
}
