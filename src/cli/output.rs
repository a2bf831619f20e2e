//! Command output: one buffered writer on stdout whose errors propagate (a closed pipe ends the
//! command quietly, any other failure is reported), and the finite check every number passes
//! before it leaves — a NaN or ∞ anywhere in a result is an internal error, never a value.
//!
//! The check is done on the data where the data is at hand ([`check_finite`]: the engine's
//! [`crate::finite::check`] visits every number of anything `Serialize` through the one
//! serializer walk, [`crate::walk`] — needed because `serde_json` would print NaN as `null`,
//! indistinguishable from "no value") and on the text where only text is at hand
//! ([`non_finite_word`]: Rust formats a non-finite `f64` as `NaN`, `inf` or `-inf` whatever the
//! precision).

use std::io::{self, BufWriter, Stdout, Write};

use serde::Serialize;

use super::errors::CliError;
use crate::paper::{Table, Value};

/// Buffered stdout.
pub struct Out {
    w: BufWriter<Stdout>,
}

impl Default for Out {
    fn default() -> Self {
        Self::new()
    }
}

impl Out {
    pub fn new() -> Self {
        Out { w: BufWriter::with_capacity(1 << 16, io::stdout()) }
    }

    /// Writes text after checking it holds no non-finite number.
    pub fn text(&mut self, s: &str) -> Result<(), CliError> {
        check_text(s)?;
        self.w.write_all(s.as_bytes())?;
        Ok(())
    }

    /// Writes text that carries no results (a completion script, a man page) as it is.
    pub fn raw(&mut self, bytes: &[u8]) -> Result<(), CliError> {
        self.w.write_all(bytes)?;
        Ok(())
    }

    /// Writes `v` as pretty JSON and a newline, after checking every number in it is finite.
    pub fn json<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), CliError> {
        check_finite(v)?;
        serde_json::to_writer_pretty(&mut self.w, v).map_err(io::Error::from)?;
        self.w.write_all(b"\n")?;
        Ok(())
    }

    /// Writes one CSV row of numbers, after checking they are finite.
    pub fn csv_row(&mut self, values: &[f64]) -> Result<(), CliError> {
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(CliError::NonFinite(format!("{v} in a CSV row")));
        }
        let mut first = true;
        for v in values {
            if !first {
                self.w.write_all(b",")?;
            }
            first = false;
            write!(self.w, "{v}")?;
        }
        self.w.write_all(b"\n")?;
        Ok(())
    }

    /// Writes a table in `format`, after checking its numbers.
    pub fn table(&mut self, table: &Table, format: super::OutputFormat) -> Result<(), CliError> {
        check_table(table)?;
        match format {
            super::OutputFormat::Text => super::format::write_text(&mut self.w, table)?,
            super::OutputFormat::Csv => super::format::write_csv(&mut self.w, table)?,
            super::OutputFormat::Json => return self.json(&super::format::table_json(table)),
        }
        Ok(())
    }

    /// Flushes stdout; a failure here is reported like any other write.
    pub fn flush(&mut self) -> Result<(), CliError> {
        self.w.flush()?;
        Ok(())
    }
}

/// Checks that text holds no `NaN`, `inf` or `-inf` word.
pub fn check_text(s: &str) -> Result<(), CliError> {
    match non_finite_word(s) {
        Some(w) => Err(CliError::NonFinite(w.to_string())),
        None => Ok(()),
    }
}

/// The first word of `text` that is how Rust prints a non-finite number (`NaN`, `inf`).
pub fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !c.is_ascii_alphanumeric()).find(|w| *w == "NaN" || *w == "inf")
}

/// Checks every number of a paper/restitution table.
pub fn check_table(t: &Table) -> Result<(), CliError> {
    for row in t.rows.iter().chain(&t.summary) {
        for (v, c) in row.iter().zip(&t.columns) {
            if let Value::Num(x) = v {
                if !x.is_finite() {
                    return Err(CliError::NonFinite(format!("{x} (column {})", c.key)));
                }
            }
        }
    }
    check_text(&t.title)?;
    t.notes.iter().try_for_each(|n| check_text(n))
}
/// Checks every floating-point number in `v` is finite; the error names the field
/// ([`crate::finite::check`], the engine's).
pub fn check_finite<T: Serialize + ?Sized>(v: &T) -> Result<(), CliError> {
    crate::finite::check(v).map_err(|e| CliError::NonFinite(e.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The engine's check ([`crate::finite::check`], tested there) becomes the command line's
    /// `NonFinite` error, its path kept.
    #[test]
    fn a_non_finite_number_is_a_non_finite_error_naming_its_path() {
        assert!(check_finite(&vec![1.0, 2.0]).is_ok());
        match check_finite(&vec![1.0, f64::NAN]) {
            Err(CliError::NonFinite(m)) => assert!(m.starts_with("NaN"), "{m}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn text_with_non_finite_words_is_refused() {
        assert_eq!(non_finite_word("SPL NaN dB"), Some("NaN"));
        assert_eq!(non_finite_word("SPLmax -inf dB"), Some("inf"));
        assert_eq!(non_finite_word("1,inf\n"), Some("inf"));
        assert_eq!(non_finite_word("info: infinite 1.0e308 nan-free"), None);
    }
}
