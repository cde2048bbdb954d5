//! Probes for instruction counts (`ecf-bench count CASE [NXxNY] [REPS]`, run by
//! `scripts/callgrind.sh` under `valgrind --tool=callgrind --toggle-collect='*measured_region*'`):
//! the work of one case inside [`measured_region`], after one warm-up pass outside it.
//!
//! Cases: `fastsim`, `dry`, `table4.1`, `wet`: the steady table's calls (v = 20 m/s, F_N = 110
//! kN, c_x = 0.2, 2, 10, 30 %), `REPS` times each; `c`: the C FASTSIM's calls for the same
//! creepages; `cells-ho`: a transient step of table4.1 at 20 m/s from c_x 0.2 % to 5 %, 50
//! steps of 0.1 ms under the higher-order rules (`ecf step --preset table4.1 --v-mps 20
//! --cx-from 0.002 --cx-to 0.05 --dt-ms 0.1 --grid 20x3 --scheme cells-ho`), `REPS` times.
//! Defaults: grid 40x21 (cells-ho: 20x3), REPS 1. `--temperature-solve exact|predictor`
//! anywhere: the local temperature's solve of the ECF cases (default: exact, the reference).
use creep_core::engine::Scheme;
use creep_core::{Config, Grid, Inputs, Model};
use ecf_bench::Contact;
use std::hint::black_box;

/// The steady table's creepages.
const CX: [f64; 4] = [0.002, 0.02, 0.10, 0.30];

/// Runs `f` `reps` times (the region callgrind counts).
#[inline(never)]
fn measured_region(f: &mut dyn FnMut() -> f64, reps: usize) -> f64 {
    let mut s = 0.0;
    for _ in 0..reps {
        s += f();
    }
    s
}

/// One warm-up call of `f` (allocations, caches), then [`measured_region`].
fn warm_then_measure(f: &mut dyn FnMut() -> f64, reps: usize) -> f64 {
    black_box(f());
    measured_region(f, reps)
}

fn model(preset: &str, nx: usize, ny: usize) -> Result<Model, String> {
    let mut c = Config::preset(preset).map_err(|e| e.to_string())?;
    c.grid = Grid { nx, ny };
    Model::new(&c).map_err(|e| e.to_string())
}

/// `ecf-bench count CASE [NXxNY] [REPS]`; prints the case and a checksum of its outputs.
pub fn run(args: &[String]) -> Result<(), String> {
    let usage = "usage: ecf-bench count fastsim|dry|table4.1|wet|c|cells-ho [NXxNY] [REPS] [--temperature-solve exact|predictor]";
    // --temperature-solve NAME anywhere: the local temperature's solve (default exact)
    let mut args = args.to_vec();
    let mut solve = creep_core::thermal::TemperatureSolve::Exact;
    if let Some(p) = args.iter().position(|a| a == "--temperature-solve") {
        let name = args.get(p + 1).ok_or(usage)?.clone();
        solve = creep_core::thermal::TemperatureSolve::by_name(&name)
            .ok_or_else(|| format!("'{name}' is not a temperature solve"))?;
        args.drain(p..p + 2);
    }
    let case = args.first().ok_or(usage)?.as_str();
    let (nx, ny) = match args.get(1) {
        Some(g) => g
            .split_once('x')
            .and_then(|(x, y)| Some((x.parse().ok()?, y.parse().ok()?)))
            .ok_or_else(|| format!("bad grid '{g}' ({usage})"))?,
        None if case == "cells-ho" => (20, 3),
        None => (40, 21),
    };
    let reps: usize = match args.get(2) {
        Some(r) => r.parse().map_err(|_| format!("bad REPS '{r}' ({usage})"))?,
        None => 1,
    };
    let (v, fn_n) = (20.0, 110e3);
    let steady = |cx: f64| Inputs {
        cx,
        v,
        fn_n,
        ..Inputs::default()
    };
    let sum = match case {
        "c" => {
            let cfg = Config::preset("fastsim").map_err(|e| e.to_string())?;
            let c = Contact::new(&cfg, fn_n).map_err(|e| e.to_string())?;
            warm_then_measure(
                &mut || {
                    CX.iter()
                        .map(|&cx| c.c_fastsim(nx, ny, black_box(cx), 0.0, 0.0).0)
                        .sum()
                },
                reps,
            )
        }
        "fastsim" | "dry" | "table4.1" | "wet" => {
            let mut m = model(case, nx, ny)?;
            m.set_temperature_solve(solve);
            warm_then_measure(
                &mut || {
                    CX.iter()
                        .map(|&cx| m.steady(&steady(black_box(cx))).map_or(f64::NAN, |o| o.fx))
                        .sum()
                },
                reps,
            )
        }
        "cells-ho" => {
            let mut m = model("table4.1", nx, ny)?;
            m.set_scheme(Scheme::CellsHigher);
            m.set_temperature_solve(solve);
            warm_then_measure(
                &mut || {
                    let mut fx = m.steady(&steady(0.002)).map_or(f64::NAN, |o| o.fx);
                    for _ in 0..50 {
                        fx += m.step(1e-4, &steady(0.05)).map_or(f64::NAN, |o| o.fx);
                    }
                    fx
                },
                reps,
            )
        }
        _ => return Err(usage.into()),
    };
    println!("{case} {nx}x{ny} x{reps}: checksum {sum:.6}");
    Ok(())
}
