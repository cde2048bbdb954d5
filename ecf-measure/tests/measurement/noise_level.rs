//! The noise level estimated from the data alone: from repeated operating points, and from a local cubic along each curve, on files made with known noise.
use crate::common::{preset, with_grid};
use crate::curves::{curves_file, noise, Curves};
use creep_core::Config;
use ecf_measure::measure::{Dataset, Defaults};
use ecf_measure::noise::estimate;

/// Curves of `truth` at 5, 10, 20 m/s, 12 creepages each (each `repeat` times), with noise.
fn file(truth: &Config, sd: f64, repeat: usize, seed: u64) -> Dataset {
    file_n(truth, sd, repeat, seed, 12, 1.55)
}

/// Curves of `truth` at 5, 10, 20 m/s, `n` creepages from 0.15 % in ratios `q` (each `repeat`
/// times), with noise.
fn file_n(truth: &Config, sd: f64, repeat: usize, seed: u64, n: i32, q: f64) -> Dataset {
    let mut seed = seed;
    let c = Curves {
        points: &[(5.0, 110.0), (10.0, 110.0), (20.0, 110.0)],
        n,
        cx0: 0.0015,
        ratio: q,
        repeat,
        series: |v, _| format!("v{v}"),
        name: "noisy.csv",
    };
    curves_file(truth, &c, || noise(&mut seed, sd))
}

#[test]
fn noise_is_estimated_from_curves_and_from_repeats() {
    let truth = with_grid(preset("dry"), 20, 7);
    // the noise-free curves of 24 creepages: what a local cubic cannot follow (the curve's own
    // bending between samples) is the estimator's floor
    let floor = estimate(&file_n(&truth, 0.0, 1, 1, 24, 1.245))
        .unwrap()
        .sd_f;
    eprintln!("no noise: {floor:.5}");
    assert!(floor < 5e-4, "{floor}");
    for sd in [0.002, 0.005, 0.01] {
        for seed in [3, 11] {
            let n = estimate(&file_n(&truth, sd, 1, seed, 24, 1.245)).expect("curves");
            eprintln!(
                "sd {sd} seed {seed}: curves {:.5} ({} points, {:.3} %)",
                n.sd_f, n.dof, n.cv_rmse_pct
            );
            assert!(n.method.contains("local cubic"), "{}", n.method);
            assert_eq!(n.dof, 60);
            assert!(
                n.sd_f > 0.75 * sd && n.sd_f < 1.5 * sd,
                "sd {sd}, seed {seed}: estimated {}",
                n.sd_f
            );
            let r = estimate(&file(&truth, sd, 2, seed)).expect("36 repeats");
            eprintln!("sd {sd} seed {seed}: repeats {:.5} ({} dof)", r.sd_f, r.dof);
            assert!(r.method.contains("repeated"), "{}", r.method);
            assert_eq!(r.dof, 36);
            assert!(
                r.sd_f > 0.75 * sd && r.sd_f < 1.3 * sd,
                "sd {sd}, seed {seed}: estimated {}",
                r.sd_f
            );
        }
    }
    // too few points on every curve: no estimate
    let short = Dataset::from_csv_str(
        "cx,f,v_mps,fn_kN\n0.01,0.3,5,110\n0.02,0.32,5,110\n0.04,0.33,5,110\n",
        "short.csv",
        &Defaults::default(),
    )
    .unwrap();
    assert!(estimate(&short).is_none());
}
