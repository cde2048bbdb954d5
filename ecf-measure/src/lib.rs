//! ecf-measure: the measurement loop on top of creep-core — read measurement files, compare a configuration with them, fit its parameters, diagnose which physical effect is missing.
//!
//! The loop of docs/measurements.md: [`measure`] reads files (CSV rows of creepage and
//! measured traction, or high-pressure-torsion curves, [`hpt`]); [`evaluate`] predicts every
//! row with creep-core's steady model and scores the difference (CV(RMSE), Eq. 2.9, and the
//! other statistics in [`stats`]); [`fit`] fits free parameters by Levenberg-Marquardt with standard errors and correlations;
//! [`diagnose`] tries the catalogue's effects and reports which lowers the held-out error
//! (the residual correlations in [`residuals`], the folds and held-out scoring it shares with
//! the search of formula forms, [`search`], in [`heldout`]).
//! The physics crate creep-core and the FMU do not depend on this crate.
#![forbid(unsafe_code)]
#![warn(missing_docs)]
#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

pub mod diagnose;
pub mod evaluate;
pub mod fit;
pub mod heldout;
pub mod hpt;
pub mod measure;
pub mod noise;
pub mod report;
pub mod residuals;
pub mod search;
pub mod stats;
