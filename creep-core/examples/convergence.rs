//! Prints the grid-convergence table of docs/model.md: steady f on the default grid against 4x and 8x refined grids, every preset.
//!
//! `cargo run --release -p creep-core --example convergence` — for every preset, v = 5, 20
//! and 30 m/s, c_x = 0.2 % ... 30 %: f on the default grid with the model's default scheme,
//! on the default grid with the first-order cell-by-cell scheme (`cells`), and on the 4x (320x84) and 8x (640x168) refined grids with the default
//! scheme; the differences are in % of the 640x168 value, and "ref gap" (320x84 against
//! 640x168) bounds how far the reference itself is from the limit.
use creep_core::{
    config::{DEFAULT_GRID, PRESETS},
    engine::Scheme,
    Config, Grid, Inputs, Model,
};

fn main() {
    let g = DEFAULT_GRID;
    let g4 = Grid {
        nx: 4 * g.nx,
        ny: 4 * g.ny,
    };
    let g8 = Grid {
        nx: 8 * g.nx,
        ny: 8 * g.ny,
    };
    println!(
        "| preset | v (m/s) | c_x | f default {0}x{1} | f {2}x{3} | default vs {2}x{3} | {0}x{1} cells vs {2}x{3} | ref gap {4}x{5} vs {2}x{3} |",
        g.nx, g.ny, g8.nx, g8.ny, g4.nx, g4.ny
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut worst = Vec::new();
    for (name, _) in PRESETS {
        // the twin-disc rig's line contact carries a few kN (p0 = 1.5 GPa at 7 kN over 10 mm)
        let fn_n = if *name == "twin_disc" { 7e3 } else { 110e3 };
        let (mut w_def, mut w_cells, mut w_gap) = (0.0f64, 0.0f64, 0.0f64);
        for v in [5.0, 20.0, 30.0] {
            for cx in [0.002, 0.005, 0.01, 0.03, 0.1, 0.3] {
                let f = |grid: Grid, scheme: Option<Scheme>| {
                    let mut c = Config::preset(name).expect("preset");
                    c.grid = grid;
                    if let Some(s) = scheme {
                        c.scheme = s;
                    }
                    Model::new(&c)
                        .expect("model")
                        .steady(&Inputs {
                            cx,
                            v,
                            fn_n,
                            ..Inputs::default()
                        })
                        .expect("steady")
                        .f
                };
                let (a, a1, b4, b8) = (
                    f(g, None),
                    f(g, Some(Scheme::CellsMarch)),
                    f(g4, None),
                    f(g8, None),
                );
                let d = |x: f64| 100.0 * (x - b8) / b8;
                w_def = w_def.max(d(a).abs());
                w_cells = w_cells.max(d(a1).abs());
                w_gap = w_gap.max(d(b4).abs());
                println!(
                    "| {name} | {v} | {cx} | {a:.4} | {b8:.4} | {:+.2} % | {:+.2} % | {:+.2} % |",
                    d(a),
                    d(a1),
                    d(b4)
                );
            }
        }
        worst.push((name, w_def, w_cells, w_gap));
    }
    println!();
    println!("| preset | largest abs difference, default | 80x21 cells | ref gap |");
    println!("|---|---|---|---|");
    for (name, a, b, c) in worst {
        println!("| {name} | {a:.2} % | {b:.2} % | {c:.2} % |");
    }
}
