//! Seed Fig. 4.8: ECF `table4.1` at 20 m/s, 110 kN shows steep rise (R1), moderate rise (R2), a maximum and a falling branch (R3).
use crate::common::*;

#[test]
fn table41_curve_has_the_three_regimes() {
    let cfg = preset("table4.1");
    let cs: Vec<f64> = (0..=200)
        .map(|i| 0.5 * (i as f64 / 200.0).powi(2))
        .collect();
    let f: Vec<f64> = cs.iter().map(|&c| f_of(&cfg, c, 20.0)).collect();
    let slope = |c0: f64, c1: f64| (f_of(&cfg, c1, 20.0) - f_of(&cfg, c0, 20.0)) / (c1 - c0);
    let r1 = slope(0.0, 5e-4);
    let r2 = slope(0.01, 0.02);
    assert!(r2 > 0.0, "R2 must still rise: slope {r2}");
    assert!(
        r1 > 20.0 * r2,
        "R1 slope {r1} must be far steeper than R2 slope {r2}"
    );
    let (imax, fmax) =
        f.iter().enumerate().fold(
            (0, f64::MIN),
            |acc, (i, &v)| if v > acc.1 { (i, v) } else { acc },
        );
    let cmax = cs[imax];
    assert!(cmax > 0.02 && cmax < 0.2, "maximum at cx = {cmax}");
    assert!(fmax > 0.2 && fmax < 0.5, "f_max = {fmax}");
    // falling branch up to 50 %: monotonically decreasing after the maximum, clearly below it at the end
    for i in imax + 1..f.len() {
        assert!(
            f[i] < f[i - 1] + 1e-9,
            "R3 must fall: f({}) = {} > f({}) = {}",
            cs[i],
            f[i],
            cs[i - 1],
            f[i - 1]
        );
    }
    assert!(
        f[f.len() - 1] < 0.7 * fmax,
        "f(50 %) = {} vs f_max = {fmax}",
        f[f.len() - 1]
    );
}
