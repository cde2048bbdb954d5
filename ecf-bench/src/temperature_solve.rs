//! The local temperature's solves side by side: each cheaper solve against the exact one on the same grid and scheme, in F_x, P_fric and the T_max rise, and its wall time against the exact solve's in the same run.
//!
//! Transient cases: every case of the accuracy benchmark ([`crate::accuracy::cases`]) and
//! the 50 Hz sine at 5 m/s (1 ms steps) and 30 m/s (0.25 ms steps) too, on the grids the
//! tolerance chooses among (10x3 ... 80x7) under `cells-ho` and `cells`. Steady cases:
//! presets dry, table4.1 and wet at 5, 10, 20 and 30 m/s, 16 creepages from 0.2 % to 30 %, on
//! the default grid 80x21 (`cells`) and the coarse `cells-ho` grids. Each difference is the
//! largest over the response (or the curve) in % of the exact solve's largest value (the T_max
//! rise: of its largest rise). The costs are medians of interleaved runs (exact, cheaper,
//! exact, ...) of the transient cases on one thread: the ratio (cheaper / exact; ratios
//! measured in one run survive a loaded machine), and each one's wall time / simulated time.
use crate::accuracy::{cases, config, run_solve, Case, Kind, FN};
use crate::median;
use creep_core::engine::Scheme;
use creep_core::thermal::TemperatureSolve;
use creep_core::{Contact, Inputs};

/// The acceptance limits of a cheaper solve against the exact one, % (F_x, T_max rise,
/// P_fric).
pub const LIMITS: [f64; 3] = [0.1, 0.5, 0.1];

/// The transient grids compared.
const GRIDS: [(usize, usize); 6] = [(10, 3), (14, 3), (20, 3), (20, 5), (40, 5), (80, 7)];

/// The steady grids compared, with their schemes.
const STEADY: [((usize, usize), Scheme); 4] = [
    ((80, 21), Scheme::CellsMarch),
    ((20, 3), Scheme::CellsHigher),
    ((20, 5), Scheme::CellsHigher),
    ((40, 5), Scheme::CellsHigher),
];

/// Per communication point (F_x, T_max - T_bulk, P_fric) of a run, and its wall time (s).
fn run(
    case: &Case,
    (nx, ny): (usize, usize),
    scheme: Scheme,
    solve: TemperatureSolve,
) -> (Vec<[f64; 3]>, f64) {
    let r = run_solve(case, nx, ny, scheme, Some(solve));
    (r.x, r.wall)
}

/// The largest difference of `b` from `a` per quantity, % of `a`'s largest magnitude.
fn diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|q| {
        let scale = a.iter().map(|x| x[q].abs()).fold(0.0, f64::max).max(1e-300);
        100.0
            * a.iter()
                .zip(b)
                .map(|(x, y)| (x[q] - y[q]).abs())
                .fold(0.0, f64::max)
            / scale
    })
}

/// Every transient case: the accuracy benchmark's and the sines at 5 and 30 m/s.
fn transient_cases() -> Vec<Case> {
    let mut all = cases();
    for preset in ["dry", "table4.1", "wet"] {
        for (v, dt) in [(5.0, 1e-3), (30.0, 2.5e-4)] {
            all.push(Case {
                preset,
                v,
                dt,
                kind: Kind::Sine {
                    mean: 0.02,
                    amp: 0.015,
                    f_hz: 50.0,
                },
            });
        }
    }
    all
}

/// Prints both tables for `solve` against the exact solve; returns the largest differences
/// (F_x, T_max rise, P_fric, %) over every case. `quick`: three cases, grids up to 20x5, the
/// steady curves of dry and wet at 20 m/s; `reps`: interleaved runs per cell for the costs.
pub fn table(solve: TemperatureSolve, quick: bool, reps: usize) -> [f64; 3] {
    let mut worst = [0.0f64; 3];
    // every cell's cost ratio, and the summed wall times (exact, cheaper) per scheme
    let mut ratios: Vec<f64> = Vec::new();
    let mut sums = [[0.0f64; 2]; 2];
    let all = transient_cases();
    let cases: Vec<Case> = if quick {
        vec![all[1], all[5], all[11]]
    } else {
        all
    };
    let grids: &[(usize, usize)] = if quick { &GRIDS[2..4] } else { &GRIDS };
    println!(
        "== temperature solve '{}' against 'exact' on the same grid: largest difference over the response, % of exact's largest (F_x, T_max rise, P_fric); wall time {} / exact (median of {reps} interleaved pairs)",
        solve.name(),
        solve.name()
    );
    println!(
        "   {:<52} {:>6} {:>9} {:>8} {:>8} {:>8} {:>7} {:>8} {:>8}",
        "case",
        "grid",
        "scheme",
        "F_x",
        "T rise",
        "P_fric",
        "cost",
        "exact",
        solve.name()
    );
    for case in &cases {
        for &g in grids {
            for scheme in [Scheme::CellsHigher, Scheme::CellsMarch] {
                let (mut te, mut tc) = (Vec::new(), Vec::new());
                let (mut xe, mut xc) = (Vec::new(), Vec::new());
                for _ in 0..reps.max(1) {
                    let (x, t) = run(case, g, scheme, TemperatureSolve::Exact);
                    (xe, te) = (x, [te, vec![t]].concat());
                    let (x, t) = run(case, g, scheme, solve);
                    (xc, tc) = (x, [tc, vec![t]].concat());
                }
                let d = diff(&xe, &xc);
                for q in 0..3 {
                    worst[q] = worst[q].max(d[q]);
                }
                let ratio = median(tc.iter().zip(&te).map(|(c, e)| c / e).collect());
                ratios.push(ratio);
                let si = usize::from(scheme == Scheme::CellsMarch);
                sums[si][0] += te.iter().sum::<f64>();
                sums[si][1] += tc.iter().sum::<f64>();
                // wall time / simulated time of each (medians)
                let sim = case.steps() as f64 * case.dt;
                println!(
                    "   {:<52} {:>6} {:>9} {:>8.4} {:>8.4} {:>8.4} {:>7.3} {:>8.3} {:>8.3}",
                    case.name(),
                    format!("{}x{}", g.0, g.1),
                    scheme.name(),
                    d[0],
                    d[1],
                    d[2],
                    ratio,
                    median(te.clone()) / sim,
                    median(tc.clone()) / sim
                );
            }
        }
    }
    println!(
        "== cost {} / exact: median over the cells {:.3}; summed wall time cells-ho {:.3}, cells {:.3}",
        solve.name(),
        median(ratios),
        sums[0][1] / sums[0][0],
        sums[1][1] / sums[1][0]
    );
    let steady = steady_table(solve, quick);
    for q in 0..3 {
        worst[q] = worst[q].max(steady[q]);
    }
    println!(
        "== largest over every case: F_x {:.4} %, T_max rise {:.4} %, P_fric {:.4} % (limits {} / {} / {} %)",
        worst[0], worst[1], worst[2], LIMITS[0], LIMITS[1], LIMITS[2]
    );
    worst
}

/// The steady curves' differences (F_x, T_max rise, P_fric, % of exact's largest on the
/// curve), printed per preset, speed and grid; returns the largest.
fn steady_table(solve: TemperatureSolve, quick: bool) -> [f64; 3] {
    let n = 16;
    let cx: Vec<f64> = (0..n)
        .map(|k| 0.002 * (0.3f64 / 0.002).powf(k as f64 / (n - 1) as f64))
        .collect();
    let presets: &[&str] = if quick {
        &["dry", "wet"]
    } else {
        &["dry", "table4.1", "wet"]
    };
    let speeds: &[f64] = if quick {
        &[20.0]
    } else {
        &[5.0, 10.0, 20.0, 30.0]
    };
    println!(
        "== steady curves, c_x = 0.2 ... 30 % ({n} points): largest difference, % of exact's largest (F_x, T_max rise, P_fric)"
    );
    let mut worst = [0.0f64; 3];
    for p in presets {
        for &v in speeds {
            let mut line = format!("   {p:>9} {v:>4} m/s");
            for ((nx, ny), scheme) in STEADY {
                let curve = |s: TemperatureSolve| -> Vec<[f64; 3]> {
                    let mut c = Contact::new(&config(p, nx, ny)).expect("contact");
                    c.set_scheme(scheme);
                    c.set_temperature_solve(s);
                    cx.iter()
                        .map(|&cx| {
                            let o = c
                                .steady(&Inputs {
                                    cx,
                                    v,
                                    fn_n: FN,
                                    t_bulk: 20.0,
                                    ..Inputs::default()
                                })
                                .expect("steady");
                            [o.fx, o.t_max - 20.0, o.p_fric]
                        })
                        .collect()
                };
                let d = diff(&curve(TemperatureSolve::Exact), &curve(solve));
                for q in 0..3 {
                    worst[q] = worst[q].max(d[q]);
                }
                line += &format!(
                    "  {nx}x{ny} {}: {:.4} / {:.4} / {:.4}",
                    scheme.name(),
                    d[0],
                    d[1],
                    d[2]
                );
            }
            println!("{line}");
        }
    }
    worst
}
