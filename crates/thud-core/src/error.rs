//! The engine's error type: one variant per way an input can fail, each naming the parameter
//! (as spelled on the command line) so that the front ends can point at what the user typed.
//!
//! Every variant displays as `invalid {param}: {what is wrong and what is valid}`, the one-line
//! form the command line prints; [`ThudError::param`] gives the parameter's name alone.

use thiserror::Error;

/// An input the physics cannot accept, or a request it cannot answer.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ThudError {
    /// A value out of its valid range or not a finite number. `param` is the user-facing name of
    /// the parameter; `message` says what is wrong and what is valid.
    #[error("invalid {param}: {message}")]
    Invalid { param: String, message: String },

    /// A value outside its parameter's range ([`crate::limits::Range`]), or not a finite
    /// number: `value` in `unit` (`shown` as the messages print it), `what` the parameter is
    /// for people, `range` its valid span.
    #[error("invalid {param}: {}", out_of_range(*value, shown, unit, what, range))]
    OutOfRange { param: String, value: f64, shown: String, unit: &'static str, what: &'static str, range: String },

    /// Two parameters given together that contradict each other (`why`).
    #[error("invalid {param}: cannot be combined with {with}: {why}")]
    Conflict { param: String, with: String, why: &'static str },

    /// A parameter given without one it needs.
    #[error("invalid {param}: needs {needs} as well")]
    Requires { param: String, needs: String },

    /// A run stopped before it finished (an interrupt, or a newer request in the explorer).
    #[error("cancelled: the run was stopped before it finished")]
    Cancelled,

    /// A quantity whose number does not parse; `example` shows one that does.
    #[error("invalid {param}: '{text}' is not a number (expected e.g. {example})")]
    NotANumber { param: String, text: String, example: &'static str },

    /// A quantity with a unit its kind does not have (`known`: the accepted units, comma separated;
    /// `plain_unit`: the unit of a bare number).
    #[error("invalid {param}: unknown unit '{unit}' in '{text}'; use {known} or a plain number in {plain_unit}")]
    UnknownUnit { param: String, unit: String, text: String, known: String, plain_unit: &'static str },

    /// A material name that is not in the materials table (`known`: the table's names);
    /// `param` is the parameter that named it (`sphere`, `plate`, or `material` when unknown).
    #[error("invalid {param}: unknown material '{name}'; known: {known}")]
    UnknownMaterial { param: String, name: String, known: String },

    /// A restitution that no contact damping c1 ≥ 0 reaches for this contact.
    #[error("invalid restitution: {restitution}; not reachable")]
    RestitutionUnreachable { restitution: f64 },

    /// A design whose run has no impact, asked for the sound of its impacts.
    #[error("invalid u0: the design has no impact to hear; give an impact speed with --u0")]
    NoImpact,
}

impl ThudError {
    /// A value of `param` out of range (or not finite); `message` says what is valid.
    #[must_use]
    pub fn invalid(param: impl Into<String>, message: impl Into<String>) -> Self {
        Self::Invalid { param: param.into(), message: message.into() }
    }

    /// The user-facing name of the parameter at fault (as spelled on the command line).
    #[must_use]
    pub fn param(&self) -> &str {
        match self {
            Self::Invalid { param, .. }
            | Self::NotANumber { param, .. }
            | Self::UnknownUnit { param, .. }
            | Self::OutOfRange { param, .. }
            | Self::Conflict { param, .. }
            | Self::Requires { param, .. }
            | Self::UnknownMaterial { param, .. } => param,
            Self::Cancelled => "",
            Self::RestitutionUnreachable { .. } => "restitution",
            Self::NoImpact => "u0",
        }
    }

    /// The same error naming the parameter `param` (as a front end spells it: `--mass`,
    /// `mass`); errors not about a named parameter are returned unchanged.
    #[must_use]
    pub fn renamed(self, param: impl Into<String>) -> Self {
        match self {
            Self::Invalid { message, .. } => Self::Invalid { param: param.into(), message },
            Self::OutOfRange { value, shown, unit, what, range, .. } => {
                Self::OutOfRange { param: param.into(), value, shown, unit, what, range }
            }
            Self::Conflict { with, why, .. } => Self::Conflict { param: param.into(), with, why },
            Self::Requires { needs, .. } => Self::Requires { param: param.into(), needs },
            Self::NotANumber { text, example, .. } => Self::NotANumber { param: param.into(), text, example },
            Self::UnknownUnit { unit, text, known, plain_unit, .. } => {
                Self::UnknownUnit { param: param.into(), unit, text, known, plain_unit }
            }
            Self::UnknownMaterial { name, known, .. } => Self::UnknownMaterial { param: param.into(), name, known },
            other => other,
        }
    }

    /// What is wrong and what is valid: the message after `invalid {param}: `.
    #[must_use]
    pub fn detail(&self) -> String {
        let full = self.to_string();
        let prefix = format!("invalid {}: ", self.param());
        full.strip_prefix(&prefix).map_or_else(|| full.clone(), str::to_string)
    }
}

/// "1e308 kg is out of range; the ball mass m must be 0.0001 to 100 kg" (or "NaN is not a
/// finite number; …").
fn out_of_range(value: f64, shown: &str, unit: &str, what: &str, range: &str) -> String {
    let unit = if unit.is_empty() || !value.is_finite() { String::new() } else { format!(" {unit}") };
    let how = if value.is_finite() { "is out of range" } else { "is not a finite number" };
    format!("{shown}{unit} {how}; the {what} must be {range}")
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every variant reads `invalid {param}: …` with the parameter `param()` names.
    #[test]
    fn every_variant_names_its_parameter_first() {
        let all = [
            ThudError::invalid("gap", "-1 m; must be a finite number > 0"),
            ThudError::NotANumber { param: "mass".into(), text: "x".into(), example: "40.5g" },
            ThudError::UnknownUnit {
                param: "mass".into(),
                unit: "lb".into(),
                text: "3lb".into(),
                known: "kg, g".into(),
                plain_unit: "kg",
            },
            ThudError::UnknownMaterial {
                param: "sphere".into(),
                name: "unobtainium".into(),
                known: "steel, acrylic".into(),
            },
            ThudError::RestitutionUnreachable { restitution: 0.5 },
            ThudError::NoImpact,
            ThudError::OutOfRange {
                param: "gap".into(),
                value: -1.0,
                shown: "-1".into(),
                unit: "m",
                what: "clearance d",
                range: "1 to 2 m".into(),
            },
            ThudError::Conflict { param: "radius".into(), with: "density".into(), why: "the radius follows" },
            ThudError::Requires { param: "plate".into(), needs: "sphere".into() },
        ];
        for e in all {
            let text = e.to_string();
            let prefix = format!("invalid {}: ", e.param());
            assert!(text.starts_with(&prefix) && text.len() > prefix.len(), "{text:?}");
            assert!(!text.contains('\n'), "{text:?}");
        }
    }

    #[test]
    fn invalid_keeps_the_one_line_form() {
        let e = ThudError::invalid("dt", "0 s; must be a finite number > 0");
        assert_eq!(e.to_string(), "invalid dt: 0 s; must be a finite number > 0");
        assert_eq!(e.param(), "dt");
        assert_eq!(check_range("theta", 91.0, 0.0, 90.0, "deg").unwrap_err().param(), "theta");
    }
}
