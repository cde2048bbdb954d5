//! Fits on files made with known parameters: standard errors for every kind of parameter,
//! at-bound and non-identifiable parameters flagged separately, and failed fits reported as
//! failures (docs/measurements.md).
use crate::common::{preset, with_grid};
use creep_core::Config;
use ecf_measure::fit::{fit_params, FreeParam, ParamStatus};
use ecf_measure::measure::{Dataset, Defaults};

/// Steady curves of `truth` at 5 and 20 m/s, 12 creepages each, plus deterministic noise of
/// amplitude `sd`.
fn file(truth: &Config, sd: f64) -> Dataset {
    let n = crate::curves::comb_noise(sd);
    crate::curves::steady_curves(truth, &[5.0, 20.0], 12, 0.001, 1.6, "known.csv", n)
}

/// `cfg` with a formula effect tau_c2 x (1 + s (v - 10)/10), s in [-0.5, max].
fn with_slope(cfg: &Config, s: f64, max: f64) -> Config {
    let mut j = cfg.to_json();
    j["formula_effects"] = serde_json::json!([{"name": "slope", "target": "tau_c2",
        "factor": "1 + s * (v_mps - 10) / 10",
        "params": {"s": {"value": s, "min": -0.5, "max": max}}}]);
    Config::from_json_str(&j.to_string(), "slope.json").unwrap()
}

#[test]
fn registry_and_formula_parameters_get_standard_errors_the_same_way() {
    let truth = with_slope(&with_grid(preset("dry"), 20, 7), 0.05, 0.5);
    let data = file(&truth, 0.002);
    let mut start = with_slope(&truth, 0.0, 0.5);
    start.params.set_by_name("tau_c2_0_GPa", 0.8).unwrap();
    let free = [
        FreeParam::resolve(&start, "tau_c2_0_GPa").unwrap(),
        FreeParam::resolve(&start, "slope.s").unwrap(),
    ];
    let r = fit_params(&start, &data, &free, 2, &|_| {}).unwrap();
    assert_eq!(r.status, vec![ParamStatus::Determined; 2]);
    // the known values come back within four standard errors, which are small
    for (k, want) in [(0, 0.6909), (1, 0.05)] {
        let (name, got, se) = (&r.params[k].name, &r.params[k].value, &r.params[k].stderr);
        assert!(
            se.is_finite() && *se > 0.0 && *se < 0.1 * want,
            "{name}: se {se}"
        );
        assert!(
            (got - want).abs() < 4.0 * se,
            "{name}: {got} vs {want} ± {se}"
        );
    }
    assert!(r.correlation[0][1].is_finite() && r.correlation[0][1].abs() < 1.0);
    assert!((r.correlation[0][0] - 1.0).abs() < 1e-9);
}

#[test]
fn at_bound_and_not_identifiable_are_flagged_separately() {
    let mut truth = with_slope(&with_grid(preset("dry"), 20, 7), 0.05, 0.5);
    truth.effects.remove(creep_core::Effect::Temperature);
    let data = file(&truth, 0.002);
    // the slope may not exceed 0.01 while the data were made with 0.05: at its upper bound;
    // tau_c2_T_per_C does nothing without the temperature effect: not identifiable
    let start = with_slope(&truth, 0.0, 0.01);
    let free = [
        FreeParam::resolve(&start, "tau_c2_0_GPa").unwrap(),
        FreeParam::resolve(&start, "slope.s").unwrap(),
        FreeParam::resolve(&start, "tau_c2_T_per_C").unwrap(),
    ];
    let r = fit_params(&start, &data, &free, 2, &|_| {}).unwrap();
    assert_eq!(
        r.status,
        vec![
            ParamStatus::Determined,
            ParamStatus::AtUpperBound,
            ParamStatus::NotIdentifiable
        ],
        "{:?}",
        r.params
    );
    assert!(r.params[0].stderr.is_finite() && r.params[0].stderr > 0.0);
    assert!(r.params[1].stderr.is_nan());
    assert!(r.params[2].stderr.is_infinite());
    assert!((r.params[1].value - 0.01).abs() < 1e-4);
}

#[test]
fn failed_fits_are_errors_and_implausible_values_warned() {
    let truth = with_grid(preset("dry"), 20, 7);
    // measured f averaging 0: CV(RMSE) is undefined
    let mut csv = String::from("cx,f,v_mps,fn_kN\n");
    for i in 1..=6 {
        let c = 0.002 * i as f64;
        csv.push_str(&format!("{c},0.2\n-{c},-0.2\n").replace('\n', ",5,110\n"));
    }
    let zero = Dataset::from_csv_str(&csv, "zero.csv", &Defaults::default()).unwrap();
    let free = [FreeParam::resolve(&truth, "tau_c2_0_GPa").unwrap()];
    let e = fit_params(&truth, &zero, &free, 1, &|_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("fit failed") && e.contains("mean measured"),
        "{e}"
    );
    // a factor that becomes infinite at 5 m/s: the rows and the effect are named
    let data = file(&truth, 0.0);
    let mut j = truth.to_json();
    j["formula_effects"] = serde_json::json!([{"name": "pole", "target": "tau_c1",
        "factor": "1 / (v_mps - 5)", "params": {}}]);
    let bad = Config::from_json_str(&j.to_string(), "pole.json").unwrap();
    let e = fit_params(&bad, &data, &free, 1, &|_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("'pole'") && e.contains("line(s) 2, 3"), "{e}");
    // constant factors of -1 or NaN are refused when the configuration is read
    for f in ["-1", "0/0", "k"] {
        j["formula_effects"] = serde_json::json!([{"name": "c", "target": "L_p",
            "factor": f, "params": {"k": {"value": -1, "min": -2, "max": 2}}}]);
        let e = Config::from_json_str(&j.to_string(), "c.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("c.json") && e.contains(">= 0"), "{f}: {e}");
    }
    // a value outside its plausible range is warned about
    let wide = file(&truth, 0.0);
    let mut start = truth.clone();
    start.params.set_by_name("tau_c1_0_GPa", 0.003).unwrap();
    let free = [FreeParam::resolve(&start, "tau_c1_0_GPa").unwrap()];
    let mut narrow = start.clone();
    free[0].set_bounds(&mut narrow, 0.0, 0.002).unwrap_err();
    free[0].set_bounds(&mut narrow, 0.0, 0.004 * 1e3).unwrap();
    let r = fit_params(&narrow, &wide, &free, 1, &|_| {}).unwrap();
    assert!(
        r.warnings.iter().all(|w| !w.contains("plausible")),
        "{:?}",
        r.warnings
    );
    let mut low = start.clone();
    free[0].set_bounds(&mut low, 0.0, 0.004).unwrap();
    let r = fit_params(&low, &wide, &free, 1, &|_| {}).unwrap();
    assert_eq!(r.status[0], ParamStatus::AtUpperBound);
    assert!(r.params[0].value <= 0.004);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("tau_c1_0_GPa") && w.contains("plausible")),
        "{:?}",
        r.warnings
    );
}
