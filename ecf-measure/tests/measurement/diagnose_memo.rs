//! The shortcuts of `diagnose` change nothing: memoised predictions and fits are bit-identical to the plain ones, and the diagnosis does not depend on the number of threads.
use crate::common::*;
use creep_core::formula::{FormulaEffect, FormulaParam, Target};
use creep_core::Config;
use creep_core::Modifier;
use ecf_measure::diagnose::{diagnose, diagnose_with};
use ecf_measure::evaluate::{predict, predict_with, Memo};
use ecf_measure::fit::{default_free, fit_params, fit_params_with, FitOptions, FreeParam};
use ecf_measure::measure::{Dataset, Defaults};

fn humid() -> Dataset {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/measurements/humid.csv");
    Dataset::from_file(&path, &Defaults::default()).expect("humid.csv")
}

/// The worked example's configuration on a coarse grid, plus a formula effect on the
/// humidity column (so that the data column is part of the operating point).
fn with_formula(cfg: &Config) -> (Config, Vec<FreeParam>) {
    let mut c = cfg.clone();
    c.modifiers.push(creep_core::AnyModifier::Formula(
        FormulaEffect::new(
            "tau_c2_by_humidity",
            Target::TauC2,
            "exp(k * (humidity - 50) / 16.3)",
            vec![FormulaParam {
                name: "k".into(),
                value: 0.0,
                min: -3.0,
                max: 3.0,
            }],
        )
        .expect("formula"),
    ));
    let mut free: Vec<FreeParam> = default_free(&c)
        .into_iter()
        .map(FreeParam::Builtin)
        .collect();
    free.push(FreeParam::Modifier {
        effect: 0,
        param: 0,
    });
    (c, free)
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn memoised_predictions_are_bit_identical() {
    let data = humid();
    let (cfg, _) = with_formula(&with_grid(preset("dry"), 12, 5));
    let plain = predict(&cfg, &data, 1).unwrap();
    let memo = Memo::new();
    let first = predict_with(&cfg, &data, 2, Some(&memo)).unwrap();
    // 36 rows, 36 operating points (12 creepages x 3 humidities)
    assert_eq!(memo.counts(), (0, 36));
    let second = predict_with(&cfg, &data, 1, Some(&memo)).unwrap();
    assert_eq!(
        memo.counts(),
        (36, 36),
        "the second call looks every point up"
    );
    // the configuration without the formula: the humidity column does not matter, so only
    // 12 operating points, none of them known (another configuration)
    let base = with_grid(preset("dry"), 12, 5);
    let b = predict_with(&base, &data, 1, Some(&memo)).unwrap();
    assert_eq!(memo.counts(), (36, 48));
    assert_eq!(b, predict(&base, &data, 2).unwrap());
    // another value of one parameter is another configuration
    let mut other = cfg.clone();
    other.modifiers[0].set_param(0, -0.1);
    let o = predict_with(&other, &data, 1, Some(&memo)).unwrap();
    assert_eq!(memo.counts(), (36, 84));
    assert_eq!(o, predict(&other, &data, 1).unwrap());
    assert_ne!(o, plain);
    for (p, (a, b)) in plain.iter().zip(first.iter().zip(&second)) {
        assert_eq!(p.f.to_bits(), a.f.to_bits());
        assert_eq!(p.f.to_bits(), b.f.to_bits());
        assert_eq!(p, a);
        assert_eq!(p, b);
    }
}

#[test]
fn memoised_fit_without_uncertainties_gives_the_same_fit() {
    let data = humid();
    let (cfg, free) = with_formula(&with_grid(preset("dry"), 12, 5));
    let plain = fit_params(&cfg, &data, &free, 2, &|_| {}).unwrap();
    let memo = Memo::new();
    let opts = FitOptions {
        skip_uncertainties: true,
        memo: Some(&memo),
        tolerance: None,
    };
    let fast = fit_params_with(&cfg, &data, &free, 1, &opts, &|_| {}).unwrap();
    let values = |r: &ecf_measure::fit::FitResult| -> Vec<f64> {
        r.params.iter().map(|p| p.value).collect()
    };
    assert_eq!(bits(&values(&plain)), bits(&values(&fast)));
    assert_eq!(
        plain.cv_rmse_pct_after.to_bits(),
        fast.cv_rmse_pct_after.to_bits()
    );
    assert_eq!(plain.config, fast.config);
    assert_eq!(plain.termination, fast.termination);
    // the memo saved work: the final model values (the best point) were looked up
    let (hits, misses) = memo.counts();
    assert!(hits >= 36, "{hits} hits, {misses} misses");
    // a second fit with the same memo repeats the first one from the memo alone
    let again = fit_params_with(&cfg, &data, &free, 2, &opts, &|_| {}).unwrap();
    assert_eq!(memo.counts().1, misses, "nothing new evaluated");
    assert_eq!(bits(&values(&again)), bits(&values(&plain)));
    assert!(fast.status.is_empty() && !plain.status.is_empty());
}

#[test]
fn diagnosis_does_not_depend_on_the_thread_count() {
    let data = humid();
    // cell by cell: on 10x5 under ECF's default higher-order rules the best model is at the
    // data's noise and the search of formula forms, part of what is compared, does not run
    let cfg = creep_core::Config {
        scheme: creep_core::engine::Scheme::CellsMarch,
        ..with_grid(preset("dry"), 10, 5)
    };
    let one = diagnose(&cfg, &data, 1, &|_| {}).unwrap();
    let three = diagnose(&cfg, &data, 3, &|_| {}).unwrap();
    // everything but the wall time the search of formula forms took (it runs here: on this
    // grid the best model is not at the data's noise)
    let json = |d: &ecf_measure::diagnose::Diagnosis| {
        let mut v = serde_json::to_value(d).unwrap();
        let s = v["search"]
            .as_object_mut()
            .expect("a search of formula forms");
        assert!(s.remove("seconds").is_some_and(|t| t.as_f64().is_some()));
        assert!(s
            .remove("cost")
            .is_some_and(|c| c["threads"].as_u64().is_some()));
        // and the verdict's "... with every free parameter, in N s"
        let verdict = v["verdict"].as_str().expect("verdict").to_string();
        let at = verdict
            .find("every free parameter, in ")
            .expect("the search's time")
            + 25;
        let end = at + verdict[at..].find(" s").expect("seconds");
        v["verdict"] = format!("{}{}", &verdict[..at], &verdict[end..]).into();
        v.to_string()
    };
    assert_eq!(json(&one), json(&three));
    assert!(!one.candidates.is_empty());
}

#[test]
fn the_looser_fit_tolerance_changes_no_printed_figure() {
    let data = humid();
    let cfg = with_grid(preset("dry"), 10, 5);
    let strict = diagnose_with(&cfg, &data, 2, None, &|_| {}).unwrap();
    let loose = diagnose(&cfg, &data, 2, &|_| {}).unwrap();
    assert_eq!(strict.missing_effect, loose.missing_effect);
    assert_eq!(strict.candidates.len(), loose.candidates.len());
    // printed with two decimals: the differences are far below 0.005
    let close = |a: f64, b: f64, what: &str| {
        assert!((a - b).abs() < 1e-3, "{what}: {a} vs {b}");
    };
    close(
        strict.baseline_heldout_cv_rmse_pct,
        loose.baseline_heldout_cv_rmse_pct,
        "baseline held-out",
    );
    for (s, l) in strict.candidates.iter().zip(&loose.candidates) {
        assert_eq!(s.effect, l.effect, "ranking");
        close(s.heldout_cv_rmse_pct, l.heldout_cv_rmse_pct, &s.effect);
        close(s.fitted_cv_rmse_pct, l.fitted_cv_rmse_pct, &s.effect);
    }
}
