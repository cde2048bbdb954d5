//! Measurement files made from a known configuration: steady curves at several speeds, 110 kN, creepages in a geometric series, with a given noise (shared by the fit and diagnosis tests).
use creep_core::{Config, Inputs, Model};
use ecf_measure::measure::{Dataset, Defaults};

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
    mut noise: impl FnMut() -> f64,
) -> Dataset {
    let mut csv = String::from("cx,f,series,v_mps,fn_kN\n");
    for &v in v_mps {
        let mut m = Model::new(truth).unwrap();
        for i in 0..n {
            let cx = cx0 * ratio.powi(i);
            let f = m
                .steady(&Inputs {
                    cx,
                    v,
                    fn_n: 110e3,
                    ..Inputs::default()
                })
                .unwrap()
                .f;
            csv.push_str(&format!("{cx},{},v{v},{v},110\n", f + noise()));
        }
    }
    Dataset::from_csv_str(&csv, name, &Defaults::default()).unwrap()
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
