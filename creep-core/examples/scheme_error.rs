//! Prints, for the continuous and the cell-by-cell scheme at several communication steps, F_x, P_fric, T_max and T_mean (rises) 2 ms after a creepage step at 20 m/s on 80x21 against the steady state of a 4x refined grid. Arg: [preset] (default table4.1).
use creep_core::engine::Scheme;
use creep_core::{Config, Contact, Grid, Inputs};
fn main() {
    let preset = std::env::args().nth(1).unwrap_or("table4.1".into());
    let i0 = Inputs {
        cx: 0.002,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let i = Inputs {
        cx: 0.02,
        cy: 0.001,
        ..i0
    };
    let mk = |nx, ny| {
        let mut cfg = Config::preset(&preset).expect("preset");
        cfg.grid = Grid { nx, ny };
        Contact::new(&cfg).expect("c")
    };
    let fine = mk(320, 84).steady(&i).unwrap();
    let e = |x: f64, y: f64| 100.0 * (x - y) / y;
    let show = |n: &str, c: &creep_core::Outputs| {
        println!(
            "{n:>22}: Fx {:+.3}% P {:+.3}% Tmax {:+.3}% Tmean {:+.3}%",
            e(c.fx, fine.fx),
            e(c.p_fric, fine.p_fric),
            e(c.t_max - 20.0, fine.t_max - 20.0),
            e(c.t_mean - 20.0, fine.t_mean - 20.0)
        )
    };
    show("steady 80x21", &mk(80, 21).steady(&i).unwrap());
    for (sch, name) in [(Scheme::CellsMarch, "cells"), (Scheme::Continuous, "cont")] {
        for h in [1e-6f64, 1e-5, 2e-5, 4e-5, 1e-4, 2.5e-4] {
            let mut c = mk(80, 21);
            c.set_scheme(sch);
            c.steady(&i0).unwrap();
            let n = (2e-3 / h).round() as usize;
            let mut o = None;
            for _ in 0..n {
                o = Some(c.step(h, &i).unwrap());
            }
            show(&format!("{name} h={h:.0e}"), &o.unwrap());
        }
    }
}
