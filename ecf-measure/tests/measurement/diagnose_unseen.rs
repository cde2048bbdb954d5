//! The search of formula forms on files it was never tuned on (made by `hidden.rs` from seeds and truths the search never reads): it names the true variable and reaches the noise; on files with nothing missing it proposes nothing.
//!
//! A bounded sample of the sweep `bash scripts/loop-sweep.sh` (every case, 20 seeds of files
//! with nothing missing per preset): two hidden effects, one that scales both strengths with
//! speed, one in an extra column beside a distractor, and a threshold in the local
//! temperature that the noise estimate partly reads as noise; a threshold in the speed
//! between two of another rig's four speeds; and three files with nothing missing. The time
//! bound is lifted so that the result does not depend on the machine's speed.
use crate::hidden;
use ecf_measure::diagnose::{diagnose_opts, Options};

fn opts() -> Options {
    Options {
        search_seconds: 1e4,
        ..Options::new(2)
    }
}

fn check_case(name: &str, seed: u64) {
    check_case_in(&hidden::Layout::standard(), name, seed);
}

/// Hidden case `name`, its file in `layout` with noise from `seed`, the noise-free values and
/// the configuration under test (the case's preset).
fn case_file(
    layout: &hidden::Layout,
    name: &str,
    seed: u64,
) -> (
    hidden::Case,
    ecf_measure::measure::Dataset,
    Vec<f64>,
    creep_core::Config,
) {
    let c = hidden::cases()
        .into_iter()
        .find(|c| c.name == name)
        .expect("case");
    let truth = hidden::truth(c.preset, c.target, Some(c.factor));
    let (data, clean) = hidden::file_in(layout, &truth, c.column, c.distractor, seed);
    let cfg = creep_core::Config::preset(c.preset).unwrap();
    (c, data, clean, cfg)
}

fn check_case_in(layout: &hidden::Layout, name: &str, seed: u64) {
    let (c, data, clean, cfg) = case_file(layout, name, seed);
    let d = diagnose_opts(&cfg, &data, &opts(), &|_| {}).unwrap();
    eprintln!("{name}: {}", d.verdict);
    assert!(d.model_grid.is_some(), "the loop grid runs the model");
    let noise = hidden::true_noise_cv(&data, &clean);
    let s = d
        .search
        .as_ref()
        .expect("not at the noise: the search runs");
    assert_eq!(s.tried, s.total);
    let p = s.proposed.as_ref().expect("a form is proposed");
    assert!(
        c.variables.contains(&p.variable.as_str()),
        "{name}: proposed {} x {} in {}",
        p.target,
        p.shape,
        p.variable
    );
    // a real effect of the layer is not called a stand-in for a measurement error
    let [lo, hi] = p.factor_range;
    assert!(
        hi / lo <= ecf_measure::diagnose::FACTOR_SPAN && !d.verdict.contains("stand-in"),
        "{name}: factor from {lo} to {hi}"
    );
    assert!(
        p.heldout_cv_rmse_pct <= 1.3 * noise,
        "{name}: held-out {:.2} % against a noise of {noise:.2} %",
        p.heldout_cv_rmse_pct
    );
    // the proposal is a configuration with the user's grid, read as any other
    let text = s.proposed_config.as_ref().unwrap().to_string();
    let prop = creep_core::Config::from_json_str(&text, "proposed.json").unwrap();
    assert_eq!(prop.grid, cfg.grid);
    assert!(d.verdict.contains(&format!("in {}", p.variable)));
}

#[test]
fn both_strengths_falling_with_speed_are_found_at_the_noise() {
    check_case("speed-reciprocal-strengths", 7);
}

#[test]
fn a_saturating_effect_of_a_data_column_is_found_beside_a_distractor() {
    check_case("column-saturating-strengths", 8);
}

#[test]
fn a_threshold_in_the_local_temperature_is_found_though_it_bends_the_curves() {
    check_case("temperature-threshold-tau_c2", 9);
}

#[test]
fn a_speed_threshold_between_two_of_four_speeds_is_placed_by_the_other_load() {
    // 4 speeds x 2 loads: the folds are curves of speed x load, so that each fold's training
    // rows have both sides of the threshold at 14 m/s (between 12 and 18 m/s)
    check_case_in(&hidden::Layout::other(), "speed-threshold-tau_c2", 10);
}

#[test]
fn a_threshold_in_the_bulk_temperature_is_found() {
    // the file's t_bulk_C, one value per curve, is the model's bulk temperature: a variable
    // of the residual correlations, of the search and of formula effects
    check_case("bulk-threshold-tau_c2", 11);
}

/// Files of the presets dry, table4.1 and wet with nothing missing (seeds `seeds`), each with
/// `column` and a distractor: the diagnosis proposes nothing.
fn nothing_proposed(column: (&str, f64, f64), seeds: [u64; 3]) {
    for (preset, seed) in ["dry", "table4.1", "wet"].into_iter().zip(seeds) {
        let truth = hidden::truth(preset, "tau_c1", None);
        let (data, _) = hidden::file(&truth, Some(column), true, seed);
        let cfg = creep_core::Config::preset(preset).unwrap();
        let d = diagnose_opts(&cfg, &data, &opts(), &|_| {}).unwrap();
        let proposed = d.search.as_ref().and_then(|s| s.proposed.as_ref());
        assert!(proposed.is_none(), "{preset} seed {seed}: {}", d.verdict);
    }
}

#[test]
fn nothing_missing_nothing_proposed_over_noise_seeds() {
    nothing_proposed(("humidity", 20.0, 80.0), [31, 32, 33]);
}

#[test]
fn nothing_missing_nothing_proposed_with_a_bulk_temperature_per_curve() {
    // t_bulk_C varies (0-50 degC per curve) and is a variable of the search: the truth is the
    // preset at those temperatures, nothing is missing
    nothing_proposed((hidden::BULK, 0.0, 50.0), [41, 42, 43]);
}

#[test]
fn a_search_that_passes_its_time_bound_says_so() {
    // a bound of 1 s from the start of the diagnosis: the forms the search always fits take
    // longer, and the verdict says by how much the bound was passed
    let (_, data, _, cfg) = case_file(
        &hidden::Layout::standard(),
        "speed-reciprocal-strengths",
        12,
    );
    let o = Options {
        search_seconds: 1.0,
        ..Options::new(2)
    };
    let d = diagnose_opts(&cfg, &data, &o, &|_| {}).unwrap();
    let s = d.search.as_ref().expect("the search runs");
    assert!(s.past_bound_s >= 1.0, "{}", d.verdict);
    assert!(
        d.verdict.contains(&format!(
            "it ended {:.0} s past the time bound of 1 s",
            s.past_bound_s
        )),
        "{}",
        d.verdict
    );
}
