//! A value's serialized form as hashable tokens: what serde says of it (field names, variant
//! indices, numbers, strings), every `f64` as its bits. Equal fingerprints mean equal serialized
//! forms, as equal JSON texts did, without formatting text; and like them a fingerprint follows
//! every field the engine serializes, so a parameter added to the engine's structs counts in the
//! explorer's cache keys (`cache_key.rs`) without an edit there. The tokens are the steps of the
//! engine's one serializer walk ([`crate::walk`], which the finite check also takes), kept.

use serde::Serialize;

use crate::walk::{walk, Step};

/// An `f64` as its bits, −0 taken as +0 (equal values give equal keys; the values keyed are
/// checked finite before any work starts).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Bits(u64);

impl From<f64> for Bits {
    fn from(x: f64) -> Self {
        Self(if x == 0.0 { 0 } else { x.to_bits() })
    }
}

/// One step of a serialized form ([`Step`], owned and hashable).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum Token {
    Bool(bool),
    Int(i128),
    Float(Bits),
    Char(char),
    Str(String),
    Bytes(Vec<u8>),
    None,
    Some,
    Unit,
    /// A named thing: a struct's or variant's name, or a field's.
    Name(&'static str),
    Variant(u32),
    /// The start of a sequence, tuple or map of this many elements (if known), or of a struct.
    Open(Option<usize>),
    Close,
    /// What a value's `Serialize` reported instead (never for the engine's types).
    Refused(String),
}

impl From<Step<'_>> for Token {
    fn from(step: Step<'_>) -> Self {
        match step {
            Step::Bool(v) => Token::Bool(v),
            Step::Int(v) => Token::Int(v),
            Step::Float(v) => Token::Float(v.into()),
            Step::Char(v) => Token::Char(v),
            Step::Str(v) => Token::Str(v.to_string()),
            Step::Bytes(v) => Token::Bytes(v.to_vec()),
            Step::None => Token::None,
            Step::Some => Token::Some,
            Step::Unit => Token::Unit,
            Step::Name(v) => Token::Name(v),
            Step::Variant(v) => Token::Variant(v),
            Step::Open(v) => Token::Open(v),
            Step::Close => Token::Close,
        }
    }
}

/// A value's serialized form as tokens (see the module doc).
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct Fingerprint(Vec<Token>);

impl Fingerprint {
    /// The fingerprint of `value`.
    pub fn of<T: Serialize + ?Sized>(value: &T) -> Self {
        let mut tokens = Vec::new();
        if let Err(e) = walk(value, |_, step| {
            tokens.push(Token::from(step));
            Ok(())
        }) {
            tokens.push(Token::Refused(e.0));
        }
        Fingerprint(tokens)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    struct Forcing {
        #[serde(skip_serializing_if = "is_zero")]
        force_n: f64,
        #[serde(skip_serializing_if = "is_zero")]
        freq_hz: f64,
    }

    fn is_zero(x: &f64) -> bool {
        *x == 0.0
    }

    #[test]
    fn fields_skipped_at_their_default_are_told_apart_by_name() {
        let f = |force_n, freq_hz| Fingerprint::of(&Forcing { force_n, freq_hz });
        assert_ne!(f(1.0, 0.0), f(0.0, 1.0), "one field present, but not the same one");
        assert_eq!(f(1.0, 2.0), f(1.0, 2.0));
        assert_eq!(f(-0.0, 2.0), f(0.0, 2.0));
        assert_ne!(f(1.0, 2.0), f(1.0, 2.0 + f64::EPSILON * 2.0), "one bit of a value counts");
    }

    #[test]
    fn sequences_and_options_keep_their_shape() {
        assert_ne!(Fingerprint::of(&(vec![1, 2], vec![3])), Fingerprint::of(&(vec![1], vec![2, 3])));
        assert_ne!(Fingerprint::of(&Some(0u8)), Fingerprint::of(&None::<u8>));
        assert_ne!(Fingerprint::of(&("ab", "c")), Fingerprint::of(&("a", "bc")));
    }
}
