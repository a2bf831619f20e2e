//! A value's serialized form as hashable tokens: what serde says of it (field names, variant
//! indices, numbers, strings), every `f64` as its bits. Equal fingerprints mean equal serialized
//! forms, as equal JSON texts did, without formatting text; and like them a fingerprint follows
//! every field the engine serializes, so a parameter added to the engine's structs counts in the
//! explorer's cache keys (`cache_key.rs`) without an edit there.
//!
//! A hand-written `serde::Serializer` (about 150 lines) rather than a dependency: the crates that
//! do this (serde-hashkey) are not in the dependency tree, and this one needs no options.

use std::fmt::Display;

use serde::ser::{self, Serialize};

/// An `f64` as its bits, −0 taken as +0 (equal values give equal keys; the values keyed are
/// checked finite before any work starts).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Bits(u64);

impl From<f64> for Bits {
    fn from(x: f64) -> Self {
        Self(if x == 0.0 { 0 } else { x.to_bits() })
    }
}

/// One step of a serialized form.
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
    /// The start of a sequence, tuple or map of this many elements (if known).
    Open(Option<usize>),
    Close,
    /// What a value's `Serialize` reported instead (never for the engine's types).
    Refused(String),
}

/// A value's serialized form as tokens (see the module doc).
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct Fingerprint(Vec<Token>);

impl Fingerprint {
    /// The fingerprint of `value`.
    pub fn of<T: Serialize + ?Sized>(value: &T) -> Self {
        let mut f = Fingerprint::default();
        if let Err(e) = value.serialize(&mut f) {
            f.0.push(Token::Refused(e.0));
        }
        f
    }

    fn push(&mut self, t: Token) {
        self.0.push(t);
    }
}

/// A value that could not be serialized (its own `Serialize` refused).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct Refused(String);

impl ser::Error for Refused {
    fn custom<T: Display>(msg: T) -> Self {
        Refused(msg.to_string())
    }
}

impl ser::Serializer for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Self;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    fn serialize_bool(self, v: bool) -> Result<(), Refused> {
        self.push(Token::Bool(v));
        Ok(())
    }
    fn serialize_i8(self, v: i8) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_i16(self, v: i16) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_i32(self, v: i32) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_i64(self, v: i64) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_i128(self, v: i128) -> Result<(), Refused> {
        self.push(Token::Int(v));
        Ok(())
    }
    fn serialize_u8(self, v: u8) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_u16(self, v: u16) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_u32(self, v: u32) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_u64(self, v: u64) -> Result<(), Refused> {
        self.push(Token::Int(v.into()));
        Ok(())
    }
    fn serialize_f32(self, v: f32) -> Result<(), Refused> {
        self.push(Token::Float(f64::from(v).into()));
        Ok(())
    }
    fn serialize_f64(self, v: f64) -> Result<(), Refused> {
        self.push(Token::Float(v.into()));
        Ok(())
    }
    fn serialize_char(self, v: char) -> Result<(), Refused> {
        self.push(Token::Char(v));
        Ok(())
    }
    fn serialize_str(self, v: &str) -> Result<(), Refused> {
        self.push(Token::Str(v.to_string()));
        Ok(())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<(), Refused> {
        self.push(Token::Bytes(v.to_vec()));
        Ok(())
    }
    fn serialize_none(self) -> Result<(), Refused> {
        self.push(Token::None);
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Refused> {
        self.push(Token::Some);
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Refused> {
        self.push(Token::Unit);
        Ok(())
    }
    fn serialize_unit_struct(self, name: &'static str) -> Result<(), Refused> {
        self.push(Token::Name(name));
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, index: u32, _: &'static str) -> Result<(), Refused> {
        self.push(Token::Variant(index));
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, name: &'static str, value: &T) -> Result<(), Refused> {
        self.push(Token::Name(name));
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        index: u32,
        _: &'static str,
        value: &T,
    ) -> Result<(), Refused> {
        self.push(Token::Variant(index));
        value.serialize(self)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Self, Refused> {
        self.push(Token::Open(len));
        Ok(self)
    }
    fn serialize_tuple(self, len: usize) -> Result<Self, Refused> {
        self.push(Token::Open(Some(len)));
        Ok(self)
    }
    fn serialize_tuple_struct(self, name: &'static str, len: usize) -> Result<Self, Refused> {
        self.push(Token::Name(name));
        self.push(Token::Open(Some(len)));
        Ok(self)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        index: u32,
        _: &'static str,
        len: usize,
    ) -> Result<Self, Refused> {
        self.push(Token::Variant(index));
        self.push(Token::Open(Some(len)));
        Ok(self)
    }
    fn serialize_map(self, len: Option<usize>) -> Result<Self, Refused> {
        self.push(Token::Open(len));
        Ok(self)
    }
    fn serialize_struct(self, name: &'static str, _: usize) -> Result<Self, Refused> {
        // Not the length: a field skipped when it is at its default is simply not there.
        self.push(Token::Name(name));
        self.push(Token::Open(None));
        Ok(self)
    }
    fn serialize_struct_variant(self, _: &'static str, index: u32, _: &'static str, _: usize) -> Result<Self, Refused> {
        self.push(Token::Variant(index));
        self.push(Token::Open(None));
        Ok(self)
    }
}

impl ser::SerializeSeq for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Refused> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeTuple for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Refused> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeTupleStruct for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Refused> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeTupleVariant for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Refused> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeMap for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Refused> {
        key.serialize(&mut **self)
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Refused> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeStruct for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), Refused> {
        self.push(Token::Name(key));
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
    }
}

impl ser::SerializeStructVariant for &mut Fingerprint {
    type Ok = ();
    type Error = Refused;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), Refused> {
        self.push(Token::Name(key));
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Refused> {
        self.push(Token::Close);
        Ok(())
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
