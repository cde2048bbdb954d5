//! Fitting (Eq. 5.1) recovers hidden parameters from synthetic measurements to the noise level, with honest standard errors.
use crate::common::*;
use crate::curves::noise;
use creep_core::params::P;
use ecf_measure::evaluate::{compare, predict};
use ecf_measure::fit::fit;
use ecf_measure::measure::{Dataset, Defaults};

fn synthetic(truth: &creep_core::Config, sd: f64) -> Dataset {
    let mut csv = String::from("cx,f,series,v_mps,fn_kN\n");
    let mut seed = 7;
    for v in [5.0, 20.0] {
        for i in 0..14 {
            let cx = 0.001 * 1.6f64.powi(i);
            let f = f_of(truth, cx, v) + noise(&mut seed, sd);
            csv.push_str(&format!("{cx},{f},v{v},{v},110\n"));
        }
    }
    Dataset::from_csv_str(&csv, "synthetic.csv", &Defaults::default()).unwrap()
}

#[test]
fn fit_recovers_hidden_strengths_to_the_noise_level() {
    let start = with_grid(preset("table4.1"), 20, 7);
    let mut truth = start.clone();
    truth.params.set(P::Tc10, 0.36).unwrap();
    truth.params.set(P::Tc20, 0.95).unwrap();
    let sd = 0.002;
    let data = synthetic(&truth, sd);
    let before = compare(&data, &predict(&start, &data, 2).unwrap()).cv_rmse_pct;
    let r = fit(&start, &data, &[P::Tc10, P::Tc20], 2, &|_| {}).unwrap();
    let mean_f = data.rows.iter().map(|r| r.f).sum::<f64>() / data.rows.len() as f64;
    let noise_cv = 100.0 * sd / mean_f;
    assert!((r.cv_rmse_pct_before - before).abs() < 1e-9);
    assert!(
        r.cv_rmse_pct_after < 1.3 * noise_cv,
        "after {} % vs noise {} %",
        r.cv_rmse_pct_after,
        noise_cv
    );
    assert!(
        before > 3.0 * noise_cv,
        "the start must be visibly wrong: {before} %"
    );
    for p in &r.params {
        let (name, value, se) = (&p.name, &p.value, &p.stderr);
        let t = if name == "tau_c1_0_GPa" { 0.36 } else { 0.95 };
        assert!(
            (value - t).abs() < 4.0 * se + 1e-3,
            "{name}: {value} ± {se} vs truth {t}"
        );
        assert!(*se > 0.0 && se.is_finite());
    }
}
