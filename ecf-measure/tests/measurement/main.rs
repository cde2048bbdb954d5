//! ecf-measure's tests: measurement files, fits that recover known parameters and their uncertainties, HPT, Rust effects, diagnosis of hidden effects.
//!
//! One test binary for all of them: each file is a module (one link instead of 7; CI time).

// the scenario helpers of creep-core's tests, one copy for both crates
#[path = "../../../creep-core/tests/physics/common/mod.rs"]
mod common;

mod curves;
mod custom_effect;
mod diagnose_hidden_effects;
mod diagnose_memo;
mod diagnose_noise;
mod diagnose_search;
mod diagnose_unseen;
mod fit_bounds;
mod fit_recovers_parameters;
mod fit_uncertainty;
mod hidden;
mod hpt;
mod measurement_files;
mod model_warnings;
mod noise_level;
