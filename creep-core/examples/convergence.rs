//! Prints the grid-convergence table of docs/model.md: f on the default grid and on a 4x refined grid.
use creep_core::{config::DEFAULT_GRID, Config, Grid, Inputs, Model};

fn main() {
    let g = DEFAULT_GRID;
    let fine = Grid {
        nx: 4 * g.nx,
        ny: 4 * g.ny,
    };
    println!(
        "| preset | v (m/s) | c_x | f default {}x{} | f refined {}x{} | difference |",
        g.nx, g.ny, fine.nx, fine.ny
    );
    println!("|---|---|---|---|---|---|");
    for name in ["table4.1", "dry", "wet", "fastsim"] {
        for v in [5.0, 20.0] {
            for cx in [0.001, 0.003, 0.01, 0.03, 0.1, 0.3] {
                let f = |grid: Grid| {
                    let mut c = Config::preset(name).expect("preset");
                    c.grid = grid;
                    Model::new(&c)
                        .expect("model")
                        .steady(&Inputs {
                            cx,
                            v,
                            fn_n: 110e3,
                            ..Inputs::default()
                        })
                        .expect("steady")
                        .f
                };
                let (a, b) = (f(g), f(fine));
                println!(
                    "| {name} | {v} | {cx} | {a:.4} | {b:.4} | {:+.2} % |",
                    100.0 * (a - b) / b
                );
            }
        }
    }
}
