//! Consistency of the transient steps with the steady state: constant inputs from the steady state must stay on it, whatever the grid and the communication step.
//!
//! The steady state (`Contact::steady`, the march of every bristle from the leading edge under
//! constant inputs) is what a transient run reaches under those inputs, so stepping from it
//! with the same inputs should leave the outputs where they are. This measures how far they
//! move: presets dry, table4.1 and wet, c_x = 2 %, F_N = 110 kN, a = 7.63 mm, b = 7.88 mm,
//! T_bulk = 20 degC, at 5, 20 and 30 m/s, on 20x21 and the default 80x21, with communication
//! steps of 0.01, 0.1 and 1 ms, over three contact-transit times 2a/v (at least three steps).
//! Each cell: the friction coefficient's largest and final relative change, in %. The
//! measure needs no reference solution: a change is an inconsistency between how the steady
//! march and the transient steps cut a bristle's path (docs/model.md section 3.2, "Whole-cell commit").
use crate::accuracy::{config, A};
use creep_core::{Contact, Inputs};

/// Largest and final |f(t) / f_steady - 1| (%) of `steps` steps of `dt` (s) at constant
/// inputs from the steady state.
pub fn drift(preset: &str, v: f64, nx: usize, ny: usize, dt: f64) -> (f64, f64) {
    let mut c = Contact::new(&config(preset, nx, ny)).expect("contact");
    let inp = Inputs {
        cx: 0.02,
        v,
        fn_n: crate::accuracy::FN,
        t_bulk: 20.0,
        ..Inputs::default()
    };
    let f0 = c.steady(&inp).expect("steady").f;
    let steps = ((3.0 * 2.0 * A / v / dt).ceil() as usize).max(3);
    let (mut worst, mut last) = (0.0f64, 0.0);
    for _ in 0..steps {
        let f = c.step(dt, &inp).expect("step").f;
        last = (f / f0 - 1.0) * 100.0;
        worst = worst.max(last.abs());
    }
    (worst, last)
}

/// Prints the tables (quick: dry at 20 m/s on 20x21 only).
pub fn table(quick: bool) {
    grid_table(quick);
    if !quick {
        cut_cells_table();
    }
}

/// The drift on one strip (nx x 1, dry, 5 m/s) when every communication step is a fraction
/// 1/m of a cell, so that each cell is crossed in m pieces: on fine grids the pieces are
/// shorter than the release weight's threshold (docs/model.md, section 6).
fn cut_cells_table() {
    println!("== consistency: one strip, dry, 5 m/s, c_x = 2 %, communication step = cell time / m, change of f over three transit times, % (largest / final)");
    println!(
        "   {:>6} {:>18} {:>18} {:>18} {:>18}",
        "grid", "m = 1", "m = 2", "m = 4", "m = 8"
    );
    for nx in [160usize, 640] {
        let cell = 2.0 * A / nx as f64 / 5.0;
        let cells: Vec<String> = [1.0, 2.0, 4.0, 8.0]
            .iter()
            .map(|m| {
                let (w, l) = drift("dry", 5.0, nx, 1, cell / m);
                format!("{w:.3} / {l:+.3}")
            })
            .collect();
        println!(
            "   {:>6} {:>18} {:>18} {:>18} {:>18}",
            format!("{nx}x1"),
            cells[0],
            cells[1],
            cells[2],
            cells[3]
        );
    }
}

fn grid_table(quick: bool) {
    println!("== consistency: constant inputs (c_x = 2 %) from the steady state, change of f over three transit times, % (largest / final)");
    let presets: &[&str] = if quick {
        &["dry"]
    } else {
        &["dry", "table4.1", "wet"]
    };
    let speeds: &[f64] = if quick { &[20.0] } else { &[5.0, 20.0, 30.0] };
    let grids: &[(usize, usize)] = if quick {
        &[(20, 21)]
    } else {
        &[(20, 21), (80, 21)]
    };
    let dts = [1e-5, 1e-4, 1e-3];
    println!(
        "   {:>9} {:>5} {:>6} {:>18} {:>18} {:>18}",
        "preset", "m/s", "grid", "dt 0.01 ms", "dt 0.1 ms", "dt 1 ms"
    );
    for p in presets {
        for &v in speeds {
            for &(nx, ny) in grids {
                let cells: Vec<String> = dts
                    .iter()
                    .map(|&dt| {
                        let (w, l) = drift(p, v, nx, ny, dt);
                        format!("{w:.3} / {l:+.3}")
                    })
                    .collect();
                println!(
                    "   {:>9} {:>5} {:>6} {:>18} {:>18} {:>18}",
                    p,
                    v,
                    format!("{nx}x{ny}"),
                    cells[0],
                    cells[1],
                    cells[2]
                );
            }
        }
    }
}
