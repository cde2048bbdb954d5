//! The strips at eta and -eta are computed once while there is no spin (with or without lateral creepage): the results are bit-identical to computing every strip, through lateral creepage, spin, reversal, standstill, long steps, lift-off and a saved and restored state.
use crate::common::{self, with_grid};
use creep_core::engine::Scheme;
use creep_core::{Inputs, Model};

type Row = [u64; 8];

fn row(o: &creep_core::Outputs) -> Row {
    [
        o.fx,
        o.fy,
        o.mz,
        o.t_max,
        o.t_mean,
        o.p_fric,
        o.frac_sliding,
        o.frac_plastic,
    ]
    .map(f64::to_bits)
}

/// The outputs of a scenario, with the symmetric strips computed once (`mirror`) or each, on
/// `threads` threads, and the state saved at its end.
fn run(
    preset: &str,
    grid: (usize, usize),
    scheme: Scheme,
    mirror: bool,
    threads: usize,
) -> (Vec<Row>, Vec<u8>) {
    let mut c = Model::new(&with_grid(common::preset(preset), grid.0, grid.1)).expect("model");
    c.set_scheme(scheme);
    c.set_threads(threads).expect("threads");
    match &mut c {
        Model::Bristle(b) => b.set_mirror_strips(mirror),
        _ => panic!("{preset} is not a bristle model"),
    }
    let i = Inputs {
        cx: 0.003,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    };
    let mut out = vec![row(&c.steady(&i).expect("steady"))];
    let mut saved = Vec::new();
    for k in 0..90 {
        let j = Inputs {
            cx: 0.05 + 0.04 * (k as f64 * 0.3).sin(),
            // lateral creepage from step 10 to 49 (the strips stay equal in pairs), spin at
            // step 47: every strip is computed from then on, until the steady state at step 70
            cy: if (10..50).contains(&k) { 0.002 } else { 0.0 },
            spin: if k == 47 { 0.3 } else { 0.0 },
            fn_n: if k == 25 {
                0.0
            } else {
                110e3 * (1.0 + 0.1 * (k as f64 * 0.2).cos())
            },
            v: match k {
                30 => 0.0,
                35..=39 => -5.0,
                _ => 20.0,
            },
            ..i
        };
        if k == 70 {
            out.push(row(&c.steady(&j).expect("steady")));
        }
        if k == 80 {
            saved = c.save_state();
        }
        if k == 85 {
            // back to the state of step 80: it is symmetric again
            c.load_state(&saved).expect("load");
        }
        let dt = if k == 20 { 5e-3 } else { 1.3e-4 };
        out.push(row(&c.step(dt, &j).expect("step")));
        if let Model::Bristle(b) = &c {
            // equal in pairs (so computed once when on) except after the spin of step 47
            // until the steady state of step 70
            let equal = !(47..70).contains(&k);
            assert_eq!(b.strips_mirrored(), equal, "{preset} {scheme:?} step {k}");
        }
    }
    (out, c.save_state())
}

#[test]
fn mirrored_strips_are_bit_identical() {
    for preset in ["dry", "wet", "fastsim"] {
        for scheme in [Scheme::CellsHigher, Scheme::CellsMarch, Scheme::Continuous] {
            for grid in [(14, 3), (10, 4), (12, 7)] {
                let (each, each_state) = run(preset, grid, scheme, false, 1);
                // on two threads for one grid (the strips computed are shared among them)
                let threads = if grid.1 == 7 { 2 } else { 1 };
                let (once, once_state) = run(preset, grid, scheme, true, threads);
                assert_eq!(each.len(), once.len());
                for (k, (a, b)) in each.iter().zip(&once).enumerate() {
                    assert_eq!(a, b, "{preset} {scheme:?} {grid:?}: output {k}");
                }
                assert!(
                    each_state == once_state,
                    "{preset} {scheme:?} {grid:?}: state"
                );
            }
        }
    }
}
