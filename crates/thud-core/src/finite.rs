//! The finite check every number of a result passes before a front end hands it out: a NaN
//! or ∞ anywhere in a result is an internal error, never a value. [`check`] walks anything
//! `Serialize` (the report records of [`crate::report`]) with the engine's one serializer walk
//! ([`crate::walk`]) and names the field that holds the first non-finite number. The command
//! line and the Python module both use it.

use serde::Serialize;

use crate::walk::{walk, Step, Stop};

/// A non-finite number found in a result, described as "NaN (field.path)".
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct NonFinite(pub String);

/// Checks every floating-point number in `v` is finite; the error names the field.
pub fn check<T: Serialize + ?Sized>(v: &T) -> Result<(), NonFinite> {
    walk(v, |path, step| match step {
        Step::Float(x) if !x.is_finite() && path.is_empty() => Err(Stop(format!("{x}"))),
        Step::Float(x) if !x.is_finite() => Err(Stop(format!("{x} ({})", path.join(".")))),
        _ => Ok(()),
    })
    .map_err(|e| NonFinite(e.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    struct Inner {
        spl_db: Option<f64>,
        ok: Vec<f64>,
    }

    #[derive(serde::Serialize)]
    struct Outer {
        n: usize,
        name: &'static str,
        inner: Inner,
    }

    #[test]
    fn a_nan_deep_inside_is_found_by_its_path() {
        let good = Outer { n: 1, name: "x", inner: Inner { spl_db: Some(3.0), ok: vec![1.0, 2.0] } };
        assert!(check(&good).is_ok());
        let none = Outer { inner: Inner { spl_db: None, ..good.inner }, ..good };
        assert!(check(&none).is_ok(), "None is not a number");
        let bad = Outer { n: 1, name: "x", inner: Inner { spl_db: Some(f64::NEG_INFINITY), ok: vec![] } };
        assert_eq!(check(&bad), Err(NonFinite("-inf (inner.spl_db)".into())));
        let v = vec![1.0, f64::NAN];
        assert!(check(&v).is_err());
    }
}
