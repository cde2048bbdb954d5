//! Prints how much the communication step (1 x 1 ms vs 10 x 0.1 ms after a creepage step, 20 m/s) changes the outputs, per grid, against the grid's own error (vs 4x refined). Args: [cells|continuous] [preset, default table4.1] [v m/s, default 20].
use creep_core::{Config, Contact, Grid, Inputs};
fn main() {
    let arg = |k: usize| std::env::args().nth(k);
    let preset = arg(2).unwrap_or_else(|| "table4.1".into());
    let v: f64 = arg(3).and_then(|s| s.parse().ok()).unwrap_or(20.0);
    let i0 = Inputs {
        cx: 0.002,
        v,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let i = Inputs {
        cx: 0.02,
        cy: 0.001,
        ..i0
    };
    for (nx, ny) in [(24, 7), (40, 21), (80, 21)] {
        let mut cfg = Config::preset(&preset).expect("preset");
        cfg.grid = Grid { nx, ny };
        let mk = || {
            let mut c = Contact::new(&cfg).expect("contact");
            if arg(1).as_deref() == Some("continuous") {
                c.set_scheme(creep_core::engine::Scheme::Continuous);
            }
            c.steady(&i0).expect("steady");
            c
        };
        let (mut one, mut ten) = (mk(), mk());
        let a = one.step(1e-3, &i).expect("step");
        let mut b = a;
        for _ in 0..10 {
            b = ten.step(1e-4, &i).expect("step");
        }
        let mut fine_cfg = cfg.clone();
        fine_cfg.grid = Grid {
            nx: 4 * nx,
            ny: 4 * ny,
        };
        let f = Contact::new(&fine_cfg)
            .expect("contact")
            .steady(&i)
            .expect("steady");
        for (n, x, y, r) in [
            ("Fx", a.fx, b.fx, f.fx),
            ("P_fric", a.p_fric, b.p_fric, f.p_fric),
            ("T_max", a.t_max, b.t_max, f.t_max),
        ] {
            println!(
                "{nx}x{ny} {n}: comm-step {:+.2} %, grid error {:+.2} %",
                100.0 * (y - x) / x,
                100.0 * (x - r) / r
            );
        }
    }
}
