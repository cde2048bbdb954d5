//! Error type of the physics crate: every message names the field and the accepted range.

use thiserror::Error;

/// Errors raised by the creep force models and their configuration.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CreepError {
    /// An input or parameter is outside its accepted range.
    #[error("{field} = {}: {expected}", show_number(*.value))]
    OutOfRange {
        /// Name of the input, flag or parameter (as the user wrote it).
        field: String,
        /// Offending value.
        value: f64,
        /// What was expected, e.g. "must be finite and > 0 N".
        expected: String,
    },
    /// A name (preset, model, effect, parameter) is not known.
    #[error("unknown {kind} '{name}'; accepted: {accepted}")]
    Unknown {
        /// What kind of name ("preset", "model", "effect", "parameter").
        kind: String,
        /// The name given.
        name: String,
        /// The accepted names.
        accepted: String,
    },
    /// A configuration file or document is malformed.
    #[error("configuration {source_name}: {message}")]
    Config {
        /// File or document name.
        source_name: String,
        /// What is wrong, with line and column where known.
        message: String,
    },
    /// A measurement (data) file is malformed or cannot be read.
    #[error("data file {source_name}: {message}")]
    Data {
        /// File name.
        source_name: String,
        /// What is wrong, with line and column where known.
        message: String,
    },
    /// A fit failed: its result must not be used.
    #[error("fit failed: {0}")]
    Fit(String),
    /// A saved state could not be restored.
    #[error("state: {0}")]
    State(String),
}

/// A number as a message shows it: as Rust prints it where that is short, in exponent form
/// where it is very large or very small (1e300, not 301 digits).
pub fn show_number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Result alias of the physics crate.
pub type Result<T> = std::result::Result<T, CreepError>;

/// Checks that `value` is finite and inside `[lo, hi]`.
pub fn check_range(field: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(CreepError::OutOfRange {
            field: field.to_string(),
            value,
            expected: format!("must be finite and within [{lo}, {hi}] {unit}"),
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn check_positive(field: &str, value: f64, unit: &str) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CreepError::OutOfRange {
            field: field.to_string(),
            value,
            expected: format!("must be finite and > 0 {unit}"),
        })
    }
}
