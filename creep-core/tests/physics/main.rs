//! creep-core's scenario tests: physics against limits, published results, symmetry, convergence, the seed's qualitative results, bounded work, threads, smoothness in the inputs.
//!
//! One test binary for all of them: each file is a module (one link instead of 16; CI time).

mod common;

mod bounded_work;
mod fast_paths;
mod fastsim_limit;
mod grid_convergence;
mod heat;
mod kalker_linear_theory;
mod mirrored_strips;
mod modifiers;
mod periodic_creepage;
mod published_references;
mod reversed_rolling;
mod smoothness;
mod softening_solve;
mod speed_and_load;
mod state_and_inputs;
mod state_fixtures;
mod strength_bound;
mod symmetry;
mod temperature_solve;
mod threads;
mod three_regimes;
mod transient_step;
mod wheel_slide;
