//! The measurement loop on files with a known hidden effect: diagnose names it, adding it brings the error to the noise level; with no hidden effect nothing is claimed.
use crate::common::*;
use crate::curves::{curves_file, noise, Curves};
use creep_core::{Config, Effect, Geometry, Inputs, Model};
use ecf_measure::diagnose::diagnose;
use ecf_measure::fit::{default_free, fit};
use ecf_measure::measure::{Dataset, Defaults};

/// Steady curves of `truth` at the given (speed, load) points, 12 creepages each, with noise.
fn steady_file(truth: &Config, points: &[(f64, f64)], sd: f64) -> Dataset {
    let mut seed = 11;
    let c = Curves {
        points,
        n: 12,
        cx0: 0.0015,
        ratio: 1.55,
        repeat: 1,
        series: |v, fkn| format!("v{v}_F{fkn}"),
        name: "synthetic.csv",
    };
    curves_file(truth, &c, || noise(&mut seed, sd))
}

fn coarse(name: &str) -> Config {
    with_grid(preset(name), 20, 7)
}

fn noise_cv(data: &Dataset, sd: f64) -> f64 {
    100.0 * sd / (data.rows.iter().map(|r| r.f).sum::<f64>() / data.rows.len() as f64)
}

/// Asserts that a CV(RMSE) (%) is within 1.5 times the noise of `sd` on `data`.
fn assert_at_noise(what: &str, cv: f64, data: &Dataset, sd: f64) {
    let noise = noise_cv(data, sd);
    assert!(cv < 1.5 * noise, "{what}: {cv} % vs noise {noise} %");
}

#[test]
fn hidden_temperature_is_found_and_fixes_the_error() {
    // the truth lacks pressure dependence and layer elasticity too, so that the configuration
    // under test (truth without temperature) has three candidates to choose from
    let mut truth = coarse("table4.1");
    truth.effects.remove(Effect::PressureDependence);
    truth.effects.remove(Effect::LayerElasticity);
    let sd = 0.002;
    let data = steady_file(&truth, &[(5.0, 110.0), (10.0, 110.0), (20.0, 110.0)], sd);
    let mut cfg = truth.clone();
    cfg.effects.remove(Effect::Temperature);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    assert_eq!(d.folds_by, "v_mps");
    assert_eq!(d.candidates.len(), 3);
    assert_eq!(d.candidates[0].effect, "temperature", "{:#?}", d.candidates);
    assert_eq!(
        d.missing_effect.as_deref(),
        Some("temperature"),
        "{}",
        d.verdict
    );
    let speedish = [
        "frictional_power_W",
        "slip_velocity_mps",
        "v_mps",
        "model_T_max_C",
        "cx",
    ];
    assert!(
        speedish.contains(&d.correlations[0].variable.as_str()),
        "{:?}",
        d.correlations[0]
    );
    // add it, refit: error at the noise level
    let mut fixed = cfg.clone();
    fixed.effects.insert(Effect::Temperature);
    let r = fit(&fixed, &data, &default_free(&fixed), 2, &|_| {}).unwrap();
    assert_at_noise("after", r.cv_rmse_pct_after, &data, sd);
}

#[test]
fn hidden_pressure_dependence_is_found_with_several_loads() {
    let mut truth = coarse("table4.1");
    truth.effects.remove(Effect::Temperature);
    // stronger granular behaviour than Tab. 4.1 so that the load dependence is clear
    truth.params.set_by_name("tau_c1_p_per_GPa", 3.0).unwrap();
    truth.params.set_by_name("tau_c2_p_per_GPa", 3.0).unwrap();
    truth.params.set_by_name("tau_c1_0_GPa", 0.25).unwrap();
    truth.params.set_by_name("tau_c2_0_GPa", 0.6).unwrap();
    truth.geometry = Geometry::SemiAxes {
        a: 7.63e-3,
        b: 7.88e-3,
        fn_ref: 110e3,
    };
    let sd = 0.002;
    let data = steady_file(&truth, &[(10.0, 30.0), (10.0, 70.0), (10.0, 110.0)], sd);
    let mut cfg = truth.clone();
    cfg.effects.remove(Effect::PressureDependence);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    assert_eq!(d.folds_by, "fn_kN");
    assert_eq!(
        d.candidates[0].effect, "pressure_dependence",
        "{:#?}",
        d.candidates
    );
    assert_eq!(
        d.missing_effect.as_deref(),
        Some("pressure_dependence"),
        "{}",
        d.verdict
    );
    let mut fixed = cfg.clone();
    fixed.effects.insert(Effect::PressureDependence);
    let free = [
        creep_core::params::P::Tc10,
        creep_core::params::P::Tc20,
        creep_core::params::P::Tc1P,
        creep_core::params::P::Tc2P,
    ];
    let r = fit(&fixed, &data, &free, 2, &|_| {}).unwrap();
    assert_at_noise("after", r.cv_rmse_pct_after, &data, sd);
}

#[test]
fn no_hidden_effect_no_claim() {
    let mut truth = coarse("table4.1");
    truth.effects.remove(Effect::Temperature);
    let data = steady_file(&truth, &[(5.0, 110.0), (20.0, 110.0)], 0.002);
    let d = diagnose(&truth, &data, 2, &|_| {}).unwrap();
    assert!(
        d.missing_effect.is_none(),
        "{}\n{:#?}",
        d.verdict,
        d.candidates
    );
    for c in &d.candidates {
        assert!(
            c.heldout_cv_rmse_pct > 0.75 * d.baseline_heldout_cv_rmse_pct,
            "{} improves too much: {:?}",
            c.effect,
            c
        );
    }
}

#[test]
fn hidden_transient_response_is_found_in_time_series() {
    // periodic creepage (seed Sec. 4.5.2) at two speeds, measured with the transient model;
    // the configuration under test is quasi-steady
    let truth = coarse("table4.1");
    let sd = 0.002;
    let mut csv = String::from("cx,f,series,v_mps,fn_kN,t_s\n");
    let mut seed = 5;
    for v in [5.0, 10.0] {
        let mut m = Model::new(&truth).unwrap();
        let (cm, ca, f0) = (0.2, 0.15, 100.0);
        let dt = 1.0 / (f0 * 40.0);
        m.steady(&Inputs {
            cx: cm,
            v,
            fn_n: 110e3,
            ..Inputs::default()
        })
        .unwrap();
        csv.push_str(&format!(
            "{cm},{},s{v},{v},110,0\n",
            m.outputs().f + noise(&mut seed, sd)
        ));
        for k in 1..=120 {
            let t = k as f64 * dt;
            let cx = cm + ca * (2.0 * std::f64::consts::PI * f0 * t).sin();
            let f =
                m.step(
                    dt,
                    &Inputs {
                        cx,
                        v,
                        fn_n: 110e3,
                        ..Inputs::default()
                    },
                )
                .unwrap()
                .f + noise(&mut seed, sd);
            csv.push_str(&format!("{cx},{f},s{v},{v},110,{t}\n"));
        }
    }
    let data = Dataset::from_csv_str(&csv, "series.csv", &Defaults::default()).unwrap();
    let mut cfg = truth.clone();
    cfg.effects.remove(Effect::Transient);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    assert_eq!(d.candidates[0].effect, "transient", "{:#?}", d.candidates);
    assert_eq!(
        d.missing_effect.as_deref(),
        Some("transient"),
        "{}",
        d.verdict
    );
    assert!(d.correlations.iter().any(|c| c.variable == "dcx_dt_per_s"));
    // with it (no parameter to fit) the error is at the noise level
    let mut fixed = cfg.clone();
    fixed.effects.insert(Effect::Transient);
    let p = ecf_measure::evaluate::predict(&fixed, &data, 2).unwrap();
    let cmp = ecf_measure::evaluate::compare(&data, &p);
    assert_at_noise("with it", cmp.cv_rmse_pct, &data, sd);
}

#[test]
fn hidden_effect_of_an_extra_column_is_found_by_residuals_and_a_formula_fixes_it() {
    // truth: the layer's shear strength falls with air humidity, an effect no catalogue entry has
    let base = coarse("dry");
    let truth_json = r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
        "formula_effects": [{"name": "humid", "target": "tau_c2", "factor": "1 - k * (humidity - 50) / 50",
                             "params": {"k": {"value": 0.3, "min": -1, "max": 1}}}]}"#;
    let truth = Config::from_json_str(truth_json, "truth").unwrap();
    let sd = 0.002;
    let mut csv = String::from("cx,f,series,v_mps,fn_kN,humidity\n");
    let mut seed = 3;
    for h in [30.0, 50.0, 70.0] {
        let mut m = Model::new(&truth).unwrap();
        m.set_extra(&[("humidity".to_string(), h)]).unwrap();
        for i in 0..12 {
            let cx = 0.0015 * 1.55f64.powi(i);
            let f =
                m.steady(&Inputs {
                    cx,
                    v: 10.0,
                    fn_n: 110e3,
                    ..Inputs::default()
                })
                .unwrap()
                .f + noise(&mut seed, sd);
            csv.push_str(&format!("{cx},{f},h{h},10,110,{h}\n"));
        }
    }
    let data = Dataset::from_csv_str(&csv, "humid.csv", &Defaults::default()).unwrap();
    let d = diagnose(&base, &data, 2, &|_| {}).unwrap();
    assert_eq!(
        d.correlations[0].variable, "humidity",
        "{:?}",
        d.correlations
    );
    // first: the registered Rust effect that uses the humidity column (it has exactly the
    // hidden form); it reaches the noise, so the search of formula forms does not run
    assert_eq!(
        d.candidates[0].effect, "Rust effect humidity_softening",
        "{:#?}",
        d.candidates
    );
    assert!(d.missing_effect.is_some(), "{}", d.verdict);
    assert_at_noise(
        &format!("{:?}", d.candidates[0]),
        d.candidates[0].fitted_cv_rmse_pct,
        &data,
        sd,
    );
    // without the Rust effect's column name the search finds the column and the form
    let renamed = Dataset::from_csv_str(
        &csv.replace(",humidity\n", ",rel_humidity\n"),
        "humid.csv",
        &Defaults::default(),
    )
    .unwrap();
    let d = diagnose(&base, &renamed, 2, &|_| {}).unwrap();
    let p = d
        .search
        .as_ref()
        .and_then(|s| s.proposed.as_ref())
        .unwrap_or_else(|| panic!("a form is proposed: {}", d.verdict));
    assert_eq!(p.variable, "rel_humidity", "{}", d.verdict);
    assert_at_noise("the proposed form", p.heldout_cv_rmse_pct, &renamed, sd);
    // the user writes the formula and fits its parameter from a wrong start: noise level
    let user = Config::from_json_str(
        &truth_json.replace("\"value\": 0.3", "\"value\": 0.0"),
        "user",
    )
    .unwrap();
    let free = vec![ecf_measure::fit::FreeParam::resolve(&user, "humid.k").unwrap()];
    let r = ecf_measure::fit::fit_params(&user, &data, &free, 2, &|_| {}).unwrap();
    assert_at_noise("after", r.cv_rmse_pct_after, &data, sd);
    assert!(
        (r.params[0].value - 0.3).abs() < 4.0 * r.params[0].stderr + 0.02,
        "k = {} ± {}",
        r.params[0].value,
        r.params[0].stderr
    );
}

#[test]
fn transient_only_effects_are_not_counted_as_off_on_steady_rows() {
    // everything but the transient-only effects on: steady rows leave nothing to add
    let mut cfg = coarse("dry");
    cfg.effects.remove(Effect::ElasticUnloading);
    cfg.effects.remove(Effect::Transient);
    let data = steady_file(&cfg, &[(5.0, 110.0), (20.0, 110.0)], 0.002);
    let d = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    assert!(d.catalogue_all_on, "{}", d.verdict);
    assert!(
        d.verdict.contains("Every catalogue effect"),
        "{}",
        d.verdict
    );
    // one effect that acts on steady rows off: the note is not given
    let mut less = cfg.clone();
    less.effects.remove(Effect::PressureDependence);
    let d = diagnose(&less, &data, 2, &|_| {}).unwrap();
    assert!(!d.catalogue_all_on, "{}", d.verdict);
}
