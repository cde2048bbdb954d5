//! Measurement files made from a known configuration, shared by the fit and diagnosis tests: steady curves at several operating points, creepages in a geometric series, with a given noise.
use creep_core::{Config, Inputs, Model};
use ecf_measure::measure::{Dataset, Defaults};

/// The curves of a synthetic file: one per operating point, `n` creepages each.
pub struct Curves<'a> {
    /// (speed m/s, normal force kN) of each curve.
    pub points: &'a [(f64, f64)],
    /// Creepages per curve: c_x = `cx0` x `ratio`^i, i = 0 .. n - 1.
    pub n: i32,
    /// The first creepage, -.
    pub cx0: f64,
    /// The ratio of successive creepages.
    pub ratio: f64,
    /// Rows per creepage, each with its own noise.
    pub repeat: usize,
    /// The series label of the curve at (speed, load).
    pub series: fn(f64, f64) -> String,
    /// The file name the rows are read as.
    pub name: &'a str,
}

/// The rows of `c` for `truth` (columns cx, f, series, v_mps, fn_kN; f the steady traction
/// coefficient plus `noise()` per row), read as a file.
pub fn curves_file(truth: &Config, c: &Curves, mut noise: impl FnMut() -> f64) -> Dataset {
    let mut csv = String::from("cx,f,series,v_mps,fn_kN\n");
    for &(v, fkn) in c.points {
        let mut m = Model::new(truth).unwrap();
        let series = (c.series)(v, fkn);
        for i in 0..c.n {
            let cx = c.cx0 * c.ratio.powi(i);
            let f = m
                .steady(&Inputs {
                    cx,
                    v,
                    fn_n: fkn * 1e3,
                    ..Inputs::default()
                })
                .unwrap()
                .f;
            for _ in 0..c.repeat {
                csv.push_str(&format!("{cx},{},{series},{v},{fkn}\n", f + noise()));
            }
        }
    }
    Dataset::from_csv_str(&csv, c.name, &Defaults::default()).unwrap()
}

/// Steady curves of `truth` at the speeds `v_mps` (m/s), F_N = 110 kN, `n` creepages each
/// (c_x = `cx0` x `ratio`^i), f plus `noise()` per row, read as the file `name` (series
/// `v<speed>`).
pub fn steady_curves(
    truth: &Config,
    v_mps: &[f64],
    n: i32,
    cx0: f64,
    ratio: f64,
    name: &str,
    noise: impl FnMut() -> f64,
) -> Dataset {
    let points: Vec<(f64, f64)> = v_mps.iter().map(|&v| (v, 110.0)).collect();
    let c = Curves {
        points: &points,
        n,
        cx0,
        ratio,
        repeat: 1,
        series: |v, _| format!("v{v}"),
        name,
    };
    curves_file(truth, &c, noise)
}

/// Deterministic, approximately normal noise of standard deviation `sd` (the sum of four
/// uniforms from an LCG that advances `seed`).
pub fn noise(seed: &mut u64, sd: f64) -> f64 {
    let mut s = 0.0;
    for _ in 0..4 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        s += ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5;
    }
    s * sd * 3.0f64.sqrt()
}

/// The deterministic noise of amplitude `sd` of the fit tests: sd ((k 7919 mod 13)/6 - 1)
/// for the k-th row (from 1).
pub fn comb_noise(sd: f64) -> impl FnMut() -> f64 {
    let mut k = 0usize;
    move || {
        k += 1;
        sd * ((k * 7919 % 13) as f64 / 6.0 - 1.0)
    }
}
