//! Grid convergence of the steady creep curves: each grid's largest error of f over c_x = 0.2 % ... 30 % against a 640x168 grid, per preset and speed.
//!
//! The default steady grid should be within 1 % of the converged limit for every preset at
//! 5-30 m/s and c_x from 0.2 % to 30 % (docs/model.md section 9.1). This prints, for presets dry, table4.1 and
//! wet at 5, 10, 20 and 30 m/s (F_N = 110 kN, a = 7.63 mm, b = 7.88 mm, T_bulk = 20 degC),
//! the largest |f / f_640x168 - 1| in % over 16 creepages spaced logarithmically from 0.2 % to
//! 30 %, on 20x5, 40x11, 80x21 (the default), 160x42 and 320x84, and the creepage where
//! 80x21's error is largest; then the same for coarse grids under the higher-order rules
//! (`cells-ho`) against the same `cells` reference. The reference is the finest grid, not an extrapolated limit: where
//! 160x42 and 320x84 are further from it than 80x21, the reference itself has not converged
//! (docs/model.md section 6, "Riding bristles": without that rule, dry's cells shorter than
//! about 27 um carried a yield-surface chatter).
use crate::accuracy::{config, FN};
use creep_core::engine::Scheme;
use creep_core::{Contact, Inputs};

/// The grids compared, coarse to fine; the last one is the reference.
const GRIDS: [(usize, usize); 6] = [
    (20, 5),
    (40, 11),
    (80, 21),
    (160, 42),
    (320, 84),
    (640, 168),
];

/// The coarse grids of the second table, with the higher-order rules (`cells-ho`), against
/// the same `cells` reference: the steady march under `Scheme::CellsHigher`.
const HO_GRIDS: [(usize, usize); 10] = [
    (10, 3),
    (20, 3),
    (20, 5),
    (40, 5),
    (80, 5),
    (40, 9),
    (80, 7),
    (120, 7),
    (160, 7),
    (80, 21),
];

/// f of `preset` at speed `v` (m/s) on an `nx` x `ny` grid at each creepage of `cx`, with
/// the default scheme (`cells`).
fn curve(preset: &str, v: f64, g: (usize, usize), cx: &[f64]) -> Vec<f64> {
    curve_in(preset, v, g, Scheme::CellsMarch, cx)
}

/// [`curve`] with the scheme `s`.
fn curve_in(preset: &str, v: f64, (nx, ny): (usize, usize), s: Scheme, cx: &[f64]) -> Vec<f64> {
    let mut c = Contact::new(&config(preset, nx, ny)).expect("contact");
    c.set_scheme(s);
    cx.iter()
        .map(|&cx| {
            let i = Inputs {
                cx,
                v,
                fn_n: FN,
                t_bulk: 20.0,
                ..Inputs::default()
            };
            c.steady(&i).expect("steady").f
        })
        .collect()
}

/// Prints the table (quick: dry and wet at 20 m/s, up to 320x84 as the reference).
pub fn table(quick: bool) {
    let n = 16;
    let cx: Vec<f64> = (0..n)
        .map(|k| 0.002 * (0.3f64 / 0.002).powf(k as f64 / (n - 1) as f64))
        .collect();
    let grids: &[(usize, usize)] = if quick { &GRIDS[..5] } else { &GRIDS };
    let (reference, compared) = grids.split_last().expect("grids");
    println!(
        "== steady grid convergence: largest |f / f_{}x{} - 1| over c_x = 0.2 ... 30 % (16 points), %",
        reference.0, reference.1
    );
    let head: Vec<String> = compared.iter().map(|(x, y)| format!("{x}x{y}")).collect();
    println!(
        "  {:>9} {:>4}  {}  c_x of 80x21's largest",
        "preset",
        "m/s",
        head.iter().map(|h| format!("{h:>7}")).collect::<String>()
    );
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
    // the reference curves, computed once for both tables
    let mut refs = Vec::new();
    for p in presets {
        for &v in speeds {
            let f_ref = curve(p, v, *reference, &cx);
            let mut cells = String::new();
            let mut where80 = f64::NAN;
            for &g in compared {
                let f = curve(p, v, g, &cx);
                let (mut worst, mut at) = (0.0f64, f64::NAN);
                for ((a, r), c) in f.iter().zip(&f_ref).zip(&cx) {
                    let e = (a / r - 1.0).abs() * 100.0;
                    if e > worst {
                        (worst, at) = (e, *c);
                    }
                }
                if g == (80, 21) {
                    where80 = at;
                }
                cells += &format!("{worst:>7.2}");
            }
            println!("  {p:>9} {v:>4}  {cells}  {:.3} %", where80 * 100.0);
            refs.push(f_ref);
        }
    }
    // the same reference, coarse grids under the higher-order rules (the grids `ecf diagnose`
    // may run instead of a costlier configuration grid, ecf-measure's LOOP_GRIDS)
    println!(
        "== the same with the higher-order rules (cells-ho) on coarse grids, against the cells reference {}x{}, %",
        reference.0, reference.1
    );
    let head: String = HO_GRIDS
        .iter()
        .map(|(x, y)| format!("{:>7}", format!("{x}x{y}")))
        .collect();
    println!("  {:>9} {:>4}  {head}", "preset", "m/s");
    let mut refs = refs.iter();
    for p in presets {
        for &v in speeds {
            let f_ref = refs.next().expect("one reference per preset and speed");
            let cells: String = HO_GRIDS
                .iter()
                .map(|&g| {
                    let f = curve_in(p, v, g, Scheme::CellsHigher, &cx);
                    let worst = f
                        .iter()
                        .zip(f_ref)
                        .map(|(a, r)| (a / r - 1.0).abs() * 100.0)
                        .fold(0.0f64, f64::max);
                    format!("{worst:>7.2}")
                })
                .collect();
            println!("  {p:>9} {v:>4}  {cells}");
        }
    }
}
