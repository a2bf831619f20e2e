//! The one error type of the engine: a bad parameter, named, with the valid range.

use std::fmt;

/// An input the physics cannot accept. `param` is the user-facing name of the parameter
/// (as spelled on the command line), `message` says what is wrong and what is valid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ThudError {
    pub param: String,
    pub message: String,
}

impl ThudError {
    pub fn invalid(param: impl Into<String>, message: impl Into<String>) -> Self {
        Self { param: param.into(), message: message.into() }
    }
}

impl fmt::Display for ThudError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid {}: {}", self.param, self.message)
    }
}

impl std::error::Error for ThudError {}

/// `value` must be finite and > 0.
pub fn check_positive(param: &str, value: f64, unit: &str) -> Result<(), ThudError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ThudError::invalid(param, format!("{value} {unit}; must be a finite number > 0")))
    }
}

/// `value` must be finite and ≥ 0.
pub fn check_non_negative(param: &str, value: f64, unit: &str) -> Result<(), ThudError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(ThudError::invalid(param, format!("{value} {unit}; must be a finite number >= 0")))
    }
}

/// `value` must be finite and inside `[lo, hi]`.
pub fn check_range(param: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<(), ThudError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(ThudError::invalid(param, format!("{value} {unit}; must be between {lo} and {hi} {unit}")))
    }
}
