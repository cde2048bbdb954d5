//! Strips advanced on several threads give exactly the results of one thread (strips share no mutable state).
use creep_core::engine::Scheme;
use creep_core::{Config, Contact, Grid, Inputs, Model};

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

/// Outputs (bits) and saved states of 120 steps of every kind on `threads` threads with the
/// bristles of shared strips split by `weights` (None: adapted): load changes, lateral
/// creepage, standstill, reversal, a step of length 0, a lift-off, a step longer than the
/// contact, steady restarts, and steps of whole cells of strip 0 (ending on its lattice
/// node: FASTSIM's march of new bristles then takes its Coulomb path).
#[allow(clippy::too_many_arguments)]
fn every_kind_of_step(
    preset: &str,
    (nx, ny): (usize, usize),
    scheme: Scheme,
    spin: f64,
    threads: usize,
    weights: Option<Vec<f64>>,
    seed: u64,
    (march, mirror): (bool, bool),
) -> (Vec<[u64; 6]>, Vec<Vec<u8>>) {
    let mut cfg = Config::preset(preset).expect("preset");
    cfg.grid = Grid { nx, ny };
    let mut c = Contact::new(&cfg).expect("contact");
    c.set_threads(threads).expect("threads");
    c.set_scheme(scheme);
    c.set_share_weights(weights);
    c.set_march_new_bristles(march);
    c.set_mirror_strips(mirror);
    let cell0 = 2.0 * c.strip_half_lengths()[0] * c.patch_for(110e3).expect("patch").a / nx as f64;
    let mut m = Model::Bristle(Box::new(c));
    let i = Inputs {
        cx: 0.02,
        spin,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    m.steady(&i).expect("steady");
    let mut rng = Lcg(seed);
    let (mut out, mut states) = (Vec::new(), Vec::new());
    for k in 0..120 {
        let fn_n = if k == 50 {
            0.0
        } else {
            110e3 * (0.7 + 0.6 * rng.next())
        };
        let (mut v, mut dt) = (5.0 + 25.0 * rng.next(), 2e-5 + 3e-4 * rng.next());
        match k {
            20 => v = 0.0,
            30..=33 => v = -(3.0 + 10.0 * rng.next()),
            40 => dt = 0.0,
            60 => dt = 1e-2,
            _ => {}
        }
        let mut j = Inputs {
            cx: 0.002 + 0.2 * rng.next(),
            cy: if k % 7 == 0 { 0.003 } else { 0.0 },
            v,
            fn_n,
            ..i
        };
        if k == 70 || k == 95 {
            m.steady(&j).expect("steady");
        }
        if (70..80).contains(&k) || (95..100).contains(&k) {
            // 1 to 5 whole cells of strip 0 at the load of `cell0`
            j = Inputs {
                v: 20.0,
                fn_n: 110e3,
                ..j
            };
            dt = (1 + (rng.next() * 5.0) as usize) as f64 * cell0 / 20.0;
        }
        let o = m.step(dt, &j).expect("step");
        out.push([o.fx, o.fy, o.mz, o.t_max, o.p_fric, o.frac_sliding].map(f64::to_bits));
        states.push(m.save_state());
    }
    (out, states)
}

#[test]
fn shared_strips_do_not_depend_on_the_share() {
    // who moves which bristle of a shared strip changes no bit of any output or of the saved
    // state after any step: adapted splits and fixed ones drawn from the test's seeds (one
    // leaving a thread 0.1 % of the bristles), 2 and 3 threads, on coarse grids (ny = 1 and 2
    // share every strip between 2 and 3 threads), cells and cells-ho, with and without spin,
    // the march of new bristles off, mirror strips computed each
    let mut rng = Lcg(20261206);
    for preset in ["table4.1", "dry", "wet", "fastsim"] {
        for grid in [(20, 3), (20, 5), (10, 3), (8, 2), (12, 1)] {
            for scheme in [Scheme::CellsHigher, Scheme::CellsMarch] {
                for spin in [0.0, 0.5] {
                    for opts in [(true, true), (false, true), (true, false)] {
                        let seed = (rng.next() * 1e9) as u64;
                        let run = |threads, weights| {
                            every_kind_of_step(
                                preset, grid, scheme, spin, threads, weights, seed, opts,
                            )
                        };
                        let (one, one_states) = run(1, None);
                        for threads in [2, 3] {
                            let mut w: Vec<f64> = (0..threads).map(|_| 0.02 + rng.next()).collect();
                            let fixed = Some(w.clone());
                            w[0] = 1e-3;
                            for weights in [None, fixed, Some(w.clone())] {
                                let (many, many_states) = run(threads, weights.clone());
                                let what = format!(
                                    "{preset} {grid:?} {scheme:?} spin {spin}, march and mirror \
                                     {opts:?}: {threads} threads, weights {weights:?}"
                                );
                                assert_eq!(one, many, "{what}");
                                for (k, (a, b)) in one_states.iter().zip(&many_states).enumerate() {
                                    assert!(a == b, "state after step {k} differs: {what}");
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}
