//! Prints how far a transient run at constant inputs settles from the steady curve, per preset, creepage, speed and time step (arg "notemp": temperature off; env SETP=NAME=VALUE,...).
use creep_core::{Config, Effect, Inputs, Model};
fn main() {
    let notemp = std::env::args().nth(1).is_some();
    for name in ["table4.1", "dry", "fastsim"] {
        let mut cfg = Config::preset(name).unwrap();
        if notemp {
            cfg.effects.remove(Effect::Temperature);
        }
        if let Ok(kv) = std::env::var("SETP") {
            for item in kv.split(',') {
                let (k, v) = item.split_once('=').unwrap();
                cfg.params
                    .set_by_name(
                        k,
                        if v == "inf" {
                            f64::INFINITY
                        } else {
                            v.parse().unwrap()
                        },
                    )
                    .unwrap();
            }
        }
        if std::env::var_os("NOP").is_some() {
            cfg.effects.remove(Effect::PressureDependence);
        }
        for v in [5.0, 20.0] {
            for cx in [0.002, 0.05, 0.3] {
                let i = Inputs {
                    cx,
                    v,
                    fn_n: 110e3,
                    ..Inputs::default()
                };
                let target = Model::new(&cfg).unwrap().steady(&i).unwrap().f;
                let mut line = format!("{name:9} v={v:4} cx={cx:5}: steady {target:.5}");
                for dt in [1e-6, 1e-5, 1e-4, 1e-3] {
                    let mut m = Model::new(&cfg).unwrap();
                    m.steady(&Inputs { cx: 0.0, ..i }).unwrap();
                    let mut t = 0.0;
                    while t < 4.0 * 7.63e-3 / v {
                        m.step(dt, &i).unwrap();
                        t += dt;
                    }
                    let f = m.outputs().f;
                    line += &format!("  dt={dt:e}: {:+.2}%", 100.0 * (f - target) / target);
                }
                println!("{line}");
            }
        }
    }
}
