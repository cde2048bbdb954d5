//! Strips advanced on several threads give exactly the results of one thread (strips share no mutable state).
use creep_core::engine::Scheme;
use creep_core::{Config, Contact, Grid, Inputs};

fn run(preset: &str, threads: usize, scheme: Scheme) -> Vec<[f64; 6]> {
    let mut cfg = Config::preset(preset).expect("preset");
    cfg.grid = Grid { nx: 40, ny: 13 };
    let mut c = Contact::new(&cfg).expect("contact");
    c.set_threads(threads).expect("threads");
    assert_eq!(c.threads(), threads.max(1));
    c.set_scheme(scheme);
    let i = Inputs {
        cx: 0.003,
        cy: 0.002,
        spin: 0.4,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let mut out = Vec::new();
    let o = c.steady(&i).expect("steady");
    out.push([o.fx, o.fy, o.mz, o.t_max, o.p_fric, o.frac_sliding]);
    // a creepage step, a load change, a step longer than the contact, standstill, reversal
    for k in 0..60 {
        let j = Inputs {
            cx: 0.05 + 0.02 * (k as f64 * 0.3).sin(),
            fn_n: 110e3 * (1.0 + 0.1 * (k as f64 * 0.2).cos()),
            v: match k {
                30 => 0.0,
                40..=44 => -5.0,
                _ => 20.0,
            },
            ..i
        };
        let dt = if k == 20 { 5e-3 } else { 1.3e-4 };
        let o = c.step(dt, &j).expect("step");
        out.push([o.fx, o.fy, o.mz, o.t_max, o.p_fric, o.frac_sliding]);
    }
    out
}

#[test]
fn threads_do_not_change_results() {
    for preset in ["dry", "table4.1", "fastsim"] {
        for scheme in [Scheme::CellsMarch, Scheme::Continuous] {
            let one = run(preset, 1, scheme);
            for threads in [2, 3] {
                let many = run(preset, threads, scheme);
                assert_eq!(one, many, "{preset} {scheme:?} with {threads} threads");
            }
        }
    }
}

#[test]
fn threads_is_one_unless_set() {
    let c = Contact::new(&Config::preset("dry").expect("preset")).expect("contact");
    assert_eq!(c.threads(), 1);
}
