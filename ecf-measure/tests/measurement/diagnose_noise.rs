//! Verdicts that know the noise: the best model is said to be at the noise level when nothing is missing, and N times above it when an effect outside the catalogue is.
use crate::common::{preset, with_grid};
use crate::curves::{noise, steady_curves};
use creep_core::Config;
use ecf_measure::diagnose::diagnose;
use ecf_measure::measure::Dataset;

/// Curves of `truth` at 5, 10 and 20 m/s, 14 creepages each, noise of `sd`.
fn file(truth: &Config, sd: f64) -> Dataset {
    let mut seed = 7;
    let n = move || noise(&mut seed, sd);
    steady_curves(truth, &[5.0, 10.0, 20.0], 14, 0.0015, 1.45, "noise.csv", n)
}

/// `cfg` with both strengths scaled by 1/(1 + k (v - 5)/15): a fall with speed no catalogue
/// effect has.
pub fn with_speed_fall(cfg: &Config, k: f64) -> Config {
    let mut j = cfg.to_json();
    let fe = |t: &str| {
        serde_json::json!({"name": format!("fall_{t}"), "target": t,
            "factor": "1 / (1 + k * (v_mps - 5) / 15)",
            "params": {"k": {"value": k, "min": -0.5, "max": 20}}})
    };
    j["formula_effects"] = serde_json::json!([fe("tau_c1"), fe("tau_c2")]);
    Config::from_json_str(&j.to_string(), "fall.json").unwrap()
}

#[test]
fn the_verdict_says_whether_the_best_model_is_at_the_noise() {
    let cfg = with_grid(preset("dry"), 20, 7);
    let sd = 0.004;
    // nothing missing: at the noise
    let d = diagnose(&cfg, &file(&cfg, sd), 2, &|_| {}).unwrap();
    let n = d.noise.clone().expect("curves of 14 points");
    eprintln!("nothing missing: {}", d.verdict);
    assert!(n.sd_f > 0.5 * sd && n.sd_f < 2.0 * sd, "{n:?}");
    assert_eq!(d.at_noise, Some(true), "{}", d.verdict);
    assert!(d.verdict.contains("at the noise level"), "{}", d.verdict);
    // strengths falling with speed, outside the catalogue: still N times the noise
    let truth = with_speed_fall(&cfg, 1.0);
    let d = diagnose(&cfg, &file(&truth, sd), 2, &|_| {}).unwrap();
    eprintln!("speed fall: {}", d.verdict);
    assert_eq!(d.at_noise, Some(false), "{}", d.verdict);
    let t = d.times_noise.unwrap();
    assert!(t > 3.0, "{t}");
    assert!(
        d.verdict.contains(&format!("{t:.1} times the noise level"))
            && d.verdict.contains("something is still missing")
            && d.verdict.contains("v_mps"),
        "{}",
        d.verdict
    );
    let j = serde_json::to_value(&d).unwrap();
    assert_eq!(j["at_noise"], false);
    assert!(j["noise"]["cv_rmse_pct"].as_f64().unwrap() > 0.0);
}
