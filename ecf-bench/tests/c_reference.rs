//! The C FASTSIM reference solves the same discretised problem as the project's steady FASTSIM (guard for the benchmark's ratios).
use creep_core::{Config, Grid, Inputs, Model};
use ecf_bench::Contact;

#[test]
fn c_reference_equals_project_fastsim() {
    let mut cfg = Config::preset("fastsim").unwrap();
    for (nx, ny) in [(40, 21), (80, 21), (17, 5)] {
        cfg.grid = Grid { nx, ny };
        let mut m = Model::new(&cfg).unwrap();
        for fn_n in [50e3, 110e3] {
            let c = Contact::new(&cfg, fn_n).unwrap();
            for (cx, cy, cs) in [
                (0.002, 0.0, 0.0),
                (0.02, 0.0, 0.0),
                (0.3, 0.0, 0.0),
                (0.001, 0.002, 0.5),
                (-0.01, -0.003, -2.0),
            ] {
                let o = m
                    .steady(&Inputs {
                        cx,
                        cy,
                        spin: cs,
                        v: 20.0,
                        fn_n,
                        ..Inputs::default()
                    })
                    .unwrap();
                let (fx, fy) = c.c_fastsim(nx, ny, cx, cy, cs);
                let scale = fx.hypot(fy);
                assert!(
                    (o.fx - fx).abs() <= 1e-9 * scale,
                    "{nx}x{ny} {cx} {cy} {cs}: Fx {} vs C {fx}",
                    o.fx
                );
                assert!(
                    (o.fy - fy).abs() <= 1e-9 * scale,
                    "{nx}x{ny} {cx} {cy} {cs}: Fy {} vs C {fy}",
                    o.fy
                );
            }
        }
    }
}
