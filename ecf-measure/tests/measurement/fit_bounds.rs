//! Fits that never end worse than they started (docs/measurements.md): starts on a bound move off it when the data pull inward, stay at it (flagged) when the data push outward, bounds far from the solution do not change where a fit ends, and a fit ending worse than its start fails.
use crate::common::{preset, with_grid};
use creep_core::Config;
use ecf_measure::fit::{fit_generic, fit_params, FreeParam, ParamStatus};
use ecf_measure::measure::Dataset;

/// Steady curves of `truth` at 5, 12 and 20 m/s, 10 creepages each, plus deterministic noise
/// of amplitude `sd`.
fn file(truth: &Config, sd: f64) -> Dataset {
    let n = crate::curves::comb_noise(sd);
    crate::curves::steady_curves(truth, &[5.0, 12.0, 20.0], 10, 0.001, 1.7, "bounds.csv", n)
}

/// `cfg` with the layer's strengths falling with speed, tau_c x 1/(1 + k (v - 5)/15), k starting
/// at `k` within [`min`, `max`].
fn with_fall(cfg: &Config, k: f64, min: f64, max: f64) -> Config {
    let mut j = cfg.to_json();
    let fe = |t: &str| {
        serde_json::json!({"name": format!("fall_{t}"), "target": t,
            "factor": "1 / (1 + k * (v_mps - 5) / 15)",
            "params": {"k": {"value": k, "min": min, "max": max}}})
    };
    j["formula_effects"] = serde_json::json!([fe("tau_c1")]);
    Config::from_json_str(&j.to_string(), "fall.json").unwrap()
}

fn fit_k(start: &Config, data: &Dataset) -> ecf_measure::fit::FitResult {
    let free = [FreeParam::resolve(start, "fall_tau_c1.k").unwrap()];
    fit_params(start, data, &free, 2, &|_| {}).unwrap()
}

#[test]
fn starts_on_just_inside_and_far_from_the_bounds_end_at_the_same_value() {
    let base = with_grid(preset("dry"), 20, 7);
    let truth = with_fall(&base, 2.4, 0.0, 20.0);
    let data = file(&truth, 0.002);
    // (start, min, max): on the lower bound, just inside it, far from both bounds, a huge upper
    // bound, on the upper bound
    let cases = [
        (0.0, 0.0, 20.0),
        (0.0, -0.01, 20.0),
        (1.0, -5.0, 50.0),
        (0.0, -0.01, 1e9),
        (20.0, 0.0, 20.0),
    ];
    let fits: Vec<_> = cases
        .iter()
        .map(|&(k, lo, hi)| fit_k(&with_fall(&base, k, lo, hi), &data))
        .collect();
    for (c, r) in cases.iter().zip(&fits) {
        let p = &r.params[0];
        eprintln!(
            "start {c:?}: k = {} ± {} ({} starts, {} evaluations), CV(RMSE) {:.3} % -> {:.3} %",
            p.value, p.stderr, r.starts, r.evaluations, r.cv_rmse_pct_before, r.cv_rmse_pct_after
        );
        assert_eq!(r.status, vec![ParamStatus::Determined], "{c:?}: {p:?}");
        assert!(p.stderr.is_finite() && p.stderr > 0.0, "{c:?}: {p:?}");
        assert!(r.cv_rmse_pct_after < r.cv_rmse_pct_before, "{c:?}");
        // the known value within four standard errors
        assert!((p.value - 2.4).abs() < 4.0 * p.stderr, "{c:?}: {p:?}");
    }
    let (k0, se0) = (fits[2].params[0].value, fits[2].params[0].stderr);
    for (c, r) in cases.iter().zip(&fits) {
        let k = r.params[0].value;
        assert!((k - k0).abs() < se0, "{c:?}: {k} vs {k0} ± {se0}");
    }
}

#[test]
fn a_start_on_a_bound_stays_there_flagged_when_the_data_push_outward() {
    let base = with_grid(preset("dry"), 20, 7);
    // the strengths rise with speed (k < 0) while k may not fall below 0
    let truth = with_fall(&base, -0.3, -0.5, 20.0);
    let data = file(&truth, 0.002);
    for (k, lo, hi) in [(0.0, 0.0, 20.0), (5.0, 0.0, 20.0)] {
        let r = fit_k(&with_fall(&base, k, lo, hi), &data);
        let p = &r.params[0];
        assert_eq!(
            r.status,
            vec![ParamStatus::AtLowerBound],
            "start {k}: {p:?}"
        );
        assert_eq!(p.value, 0.0, "start {k}");
        assert!(p.stderr.is_nan());
        assert!(r.cv_rmse_pct_after <= r.cv_rmse_pct_before);
        // the data push k outward: the run on the bound ends the fit, no spread starts
        assert_eq!(r.starts, 2, "start {k}");
    }
}

#[test]
fn a_fit_ending_worse_than_its_start_fails() {
    // a made-up model: its best point is exactly the start, on the lower bound, and any step
    // inside climbs to a broad valley that is worse (0.2 above the measured values at best)
    let cfg = with_fall(&with_grid(preset("dry"), 20, 7), 0.0, 0.0, 20.0);
    let id = FreeParam::resolve(&cfg, "k").unwrap();
    let meas = vec![1.0; 8];
    let model = move |c: &Config| -> creep_core::error::Result<Vec<f64>> {
        let k = id.get(c);
        let g = (k / 1e-4).min(1.0) * (0.2 + 0.01 * (k - 5.0) * (k - 5.0));
        Ok(vec![1.0 + g; 8])
    };
    let e = fit_generic(&cfg, "made-up", &meas, &model, &[id], &|_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("fit failed") && e.contains("worse than it started") && e.contains("k = 0"),
        "{e}"
    );
    // the same model started inside the valley ends in it: a success
    let inside = with_fall(&with_grid(preset("dry"), 20, 7), 3.0, 0.0, 20.0);
    let r = fit_generic(&inside, "made-up", &meas, &model, &[id], &|_| {}).unwrap();
    assert!((r.params[0].value - 5.0).abs() < 1e-3, "{:?}", r.params);
}
