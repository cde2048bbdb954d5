//! The search of formula-effect forms (docs/measurements.md, "The search"): on files whose truth has an effect outside the catalogue it proposes the right variable and target and a configuration that fits; on files with nothing missing it proposes nothing.
use crate::common::{preset, with_grid};
use crate::curves::{curves_file, noise, Curves};
use creep_core::Config;
use ecf_measure::diagnose::diagnose;
use ecf_measure::fit::{fit_params, FreeParam};
use ecf_measure::measure::Dataset;
use ecf_measure::search::Search;

/// Curves of `truth` at the (speed m/s, load kN) points, `n` creepages each, noise of `sd`.
fn file(truth: &Config, points: &[(f64, f64)], n: i32, sd: f64) -> Dataset {
    let mut seed = 5;
    let c = Curves {
        points,
        n,
        cx0: 0.0015,
        ratio: (0.25f64 / 0.0015).powf(1.0 / (n - 1) as f64),
        repeat: 1,
        series: |v, fkn| format!("v{v}F{fkn}"),
        name: "forms.csv",
    };
    curves_file(truth, &c, || noise(&mut seed, sd))
}

/// The six best forms of a search, on stderr.
fn print_forms(s: &Search) {
    for f in s.forms.iter().take(6) {
        eprintln!(
            "  {} x {}({}) held-out {:.2} % (screen {:.2} %), {}",
            f.target,
            f.shape,
            f.variable,
            f.heldout_cv_rmse_pct,
            f.screen_cv_rmse_pct,
            f.params_text()
        );
    }
}

/// `cfg` with `target` scaled by `factor` (parameter k = `k`).
fn with_formula(cfg: &Config, target: &str, factor: &str, k: f64) -> Config {
    let mut j = cfg.to_json();
    j["formula_effects"] = serde_json::json!([{"name": "hidden", "target": target,
        "factor": factor, "params": {"k": {"value": k, "min": -5, "max": 5}}}]);
    Config::from_json_str(&j.to_string(), "hidden.json").unwrap()
}

#[test]
fn a_strength_falling_with_speed_is_found_and_the_proposal_fits() {
    let cfg = with_grid(preset("dry"), 20, 7);
    let truth = with_formula(&cfg, "tau_c1", "1 / (1 + k * (v_mps - 5) / 15)", 1.5);
    let pts = [(5.0, 110.0), (10.0, 110.0), (15.0, 110.0), (20.0, 110.0)];
    let data = file(&truth, &pts, 12, 0.003);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    eprintln!("{}", d.verdict);
    let s = d
        .search
        .as_ref()
        .expect("not at the noise: the search runs");
    print_forms(s);
    eprintln!("{} of {} forms in {:.1} s", s.tried, s.total, s.seconds);
    assert_eq!(s.tried, s.total);
    assert_eq!(s.cost.shortlisted, ecf_measure::search::SHORTLIST);
    // every form reported once
    let mut keys: Vec<(&str, &str, &str)> = s
        .forms
        .iter()
        .map(|f| (f.target.as_str(), f.variable.as_str(), f.shape.as_str()))
        .collect();
    keys.sort();
    keys.dedup();
    assert_eq!((keys.len(), s.forms.len()), (s.total, s.total));
    let p = s.proposed.as_ref().expect("a form is proposed");
    assert_eq!(
        (p.target.as_str(), p.variable.as_str()),
        ("tau_c1", "v_mps")
    );
    let noise = d.noise.as_ref().unwrap().cv_rmse_pct;
    assert!(p.heldout_cv_rmse_pct < 0.75 * d.best_heldout_cv_rmse_pct);
    let kp = &p.params[0];
    assert!(kp.value.is_finite() && kp.stderr.is_finite() && kp.stderr > 0.0);
    // the reciprocal form is the truth's: it reaches the noise
    assert_eq!(p.shape, "reciprocal");
    assert!(
        p.heldout_cv_rmse_pct < 2.0 * noise,
        "{} vs {noise}",
        p.heldout_cv_rmse_pct
    );
    // the proposed configuration is read as any configuration and fits as it stands
    let text = s.proposed_config.as_ref().unwrap().to_string();
    let prop = Config::from_json_str(&text, "proposed.json").unwrap();
    let k = FreeParam::resolve(&prop, "form_tau_c1.k").unwrap();
    let r = fit_params(&prop, &data, &[k], 2, &|_| {}).unwrap();
    assert!(
        (r.params[0].value - kp.value).abs() < 3.0 * kp.stderr,
        "{:?}",
        r.params
    );
    assert!(r.cv_rmse_pct_after <= r.cv_rmse_pct_before * (1.0 + 1e-9));
    assert!(verdict_names(
        &d.verdict,
        "Proposed: tau_c1 x reciprocal in v_mps"
    ));
}

fn verdict_names(v: &str, what: &str) -> bool {
    v.contains(what)
}

#[test]
fn a_layer_weakening_with_load_is_found_in_a_load_variable() {
    let cfg = with_grid(preset("dry"), 20, 7);
    let truth = with_formula(&cfg, "tau_c2", "exp(-k * (fn_kN - 100) / 40)", 0.4);
    let pts = [(10.0, 50.0), (10.0, 80.0), (10.0, 110.0), (10.0, 150.0)];
    let data = file(&truth, &pts, 12, 0.003);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    eprintln!("{}", d.verdict);
    let s = d.search.as_ref().expect("the search runs");
    print_forms(s);
    let p = s.proposed.as_ref().expect("a form is proposed");
    // the load and the maximum pressure (which grows with it) are the same variable here
    assert!(
        ["fn_kN", "p_GPa"].contains(&p.variable.as_str()),
        "{}",
        p.variable
    );
    assert_eq!(p.target, "tau_c2");
}

#[test]
fn nothing_missing_nothing_proposed() {
    // 4 creepages per curve: no noise estimate, so the search runs; the truth is the
    // configuration: no form may be proposed
    let cfg = with_grid(preset("dry"), 20, 7);
    let pts = [
        (5.0, 90.0),
        (8.0, 110.0),
        (12.0, 90.0),
        (16.0, 110.0),
        (20.0, 90.0),
    ];
    let data = file(&cfg, &pts, 4, 0.003);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    eprintln!("{}", d.verdict);
    assert!(d.noise.is_none());
    let s = d
        .search
        .as_ref()
        .expect("no noise estimate: the search runs");
    assert!(s.tried > 0);
    assert!(
        s.proposed.is_none() && s.proposed_config.is_none(),
        "{}",
        d.verdict
    );
    assert!(d.verdict.contains("No form is proposed"), "{}", d.verdict);
}
