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
        for scheme in [Scheme::CellsMarch, Scheme::CellsHigher, Scheme::Continuous] {
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

/// A small deterministic generator (the test's own seeds; the engine never reads them).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Outputs of `steps` steps of the cell-by-cell schemes on a coarse grid, on `threads`
/// threads with the bristles of shared strips split by `weights` (None: adapted).
fn coarse_run(
    preset: &str,
    (nx, ny): (usize, usize),
    scheme: Scheme,
    spin: f64,
    threads: usize,
    weights: Option<Vec<f64>>,
    seed: u64,
) -> Vec<[u64; 6]> {
    let mut cfg = Config::preset(preset).expect("preset");
    cfg.grid = Grid { nx, ny };
    let mut c = Contact::new(&cfg).expect("contact");
    c.set_threads(threads).expect("threads");
    c.set_scheme(scheme);
    c.set_share_weights(weights);
    let i = Inputs {
        cx: 0.02,
        spin,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    c.steady(&i).expect("steady");
    let mut rng = Lcg(seed);
    let mut out = Vec::new();
    for _ in 0..80 {
        // creepage, speed and step size vary, so that 0 to 4 bristles enter per step,
        // steps end on and between lattice nodes, and the strips' phases drift apart
        let j = Inputs {
            cx: 0.002 + 0.2 * rng.next(),
            v: 5.0 + 25.0 * rng.next(),
            ..i
        };
        let dt = 2e-5 + 3e-4 * rng.next();
        let o = c.step(dt, &j).expect("step");
        out.push([o.fx, o.fy, o.mz, o.t_max, o.p_fric, o.frac_sliding].map(f64::to_bits));
    }
    out
}

#[test]
fn shared_strips_do_not_depend_on_the_share() {
    // who moves which bristle of a shared strip (the weights, held fixed here, drawn from
    // the test's seeds; extreme ones leave a thread nearly nothing) changes no bit of any
    // output, on the coarse grids where strips are shared, with and without spin (mirror
    // strips computed once or not), cell by cell and with the higher-order rules
    let mut rng = Lcg(20261206);
    for (preset, grid) in [("table4.1", (20, 3)), ("dry", (20, 5)), ("wet", (10, 3))] {
        for scheme in [Scheme::CellsHigher, Scheme::CellsMarch] {
            for spin in [0.0, 0.5] {
                let seed = (rng.next() * 1e9) as u64;
                let one = coarse_run(preset, grid, scheme, spin, 1, None, seed);
                for threads in [2, 3] {
                    let mut w: Vec<f64> = (0..threads).map(|_| 0.02 + rng.next()).collect();
                    let shares = [None, Some(w.clone()), {
                        w[0] = 1e-3;
                        Some(w.clone())
                    }];
                    for weights in shares {
                        let many =
                            coarse_run(preset, grid, scheme, spin, threads, weights.clone(), seed);
                        assert_eq!(
                            one, many,
                            "{preset} {grid:?} {scheme:?} spin {spin}: {threads} threads, \
                             weights {weights:?}"
                        );
                    }
                }
            }
        }
    }
}
