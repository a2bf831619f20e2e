//! One walk over a value's serialized form: a serde `Serializer` that writes nothing and hands a
//! visitor each step of what a `Serialize` value says of itself — names of structs, fields and
//! variants (variants by index), every number (every `f64` as it is), strings, the start and end
//! of each sequence, map and struct — with the path of field and variant names down to it
//! (`inner.spl_db`). Two visitors use it: the finite check of every result ([`crate::finite`])
//! and the explorer's cache keys (the app's `tui/fingerprint.rs`). Both follow every field the
//! engine serializes, so a field added to the engine's structs is checked and keyed without an
//! edit there.
//!
//! A hand-written serializer rather than a dependency: serde has no "visit every value" walker,
//! and the crates that come near (serde-hashkey, serde_value) build a copy of the value and are
//! not in the dependency tree.

use std::fmt::Display;

use serde::ser::{self, Serialize};

/// One step of a value's serialized form, in the order serde gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step<'a> {
    Bool(bool),
    /// Any integer (`i8` to `u64`, `i128`; `u128` is refused, as serde does by default).
    Int(i128),
    /// Any float (an `f32` widened).
    Float(f64),
    Char(char),
    Str(&'a str),
    Bytes(&'a [u8]),
    None,
    /// `Some`: the value follows.
    Some,
    Unit,
    /// A named thing: a struct's (unit, newtype, tuple or plain) name, or a field's (the field's
    /// value follows).
    Name(&'static str),
    /// An enum's variant, by index (a newtype variant's value, or its fields, follow).
    Variant(u32),
    /// The start of a sequence, tuple or map of this many elements (if known), or of a struct's
    /// fields (never a length: a field skipped at its default is simply not there).
    Open(Option<usize>),
    /// The end of what the last open [`Step::Open`] started.
    Close,
}

/// Why a walk stopped: the visitor's reason, or the value's own `Serialize` refusing.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct Stop(pub String);

impl ser::Error for Stop {
    fn custom<T: Display>(msg: T) -> Self {
        Stop(msg.to_string())
    }
}

/// Walks `value`'s serialized form, calling `visit` with the path of field and variant names
/// down to each step (empty at the top) and the step; stops at the first error `visit` returns.
pub fn walk<T, F>(value: &T, visit: F) -> Result<(), Stop>
where
    T: Serialize + ?Sized,
    F: FnMut(&[&'static str], Step<'_>) -> Result<(), Stop>,
{
    value.serialize(&mut Walker { path: Vec::new(), visit })
}

/// The serializer: the path so far and the visitor.
struct Walker<F> {
    path: Vec<&'static str>,
    visit: F,
}

type R = Result<(), Stop>;

impl<F: FnMut(&[&'static str], Step<'_>) -> R> Walker<F> {
    fn step(&mut self, step: Step<'_>) -> R {
        (self.visit)(&self.path, step)
    }

    /// `value` walked with `name` on the path.
    fn under<T: Serialize + ?Sized>(&mut self, name: &'static str, value: &T) -> R {
        self.path.push(name);
        value.serialize(&mut *self)?;
        self.path.pop();
        Ok(())
    }

    /// A container of `steps` opened (with `name` on the path until it closes, if any).
    fn open(&mut self, name: Option<&'static str>, steps: &[Step<'_>]) -> R {
        for s in steps {
            self.step(*s)?;
        }
        self.path.extend(name);
        Ok(())
    }

    /// The container opened last closed (`named`: with a name on the path, taken off first).
    fn close(&mut self, named: bool) -> R {
        if named {
            self.path.pop();
        }
        self.step(Step::Close)
    }
}

impl<F: FnMut(&[&'static str], Step<'_>) -> R> ser::Serializer for &mut Walker<F> {
    type Ok = ();
    type Error = Stop;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Self;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    fn serialize_bool(self, v: bool) -> R {
        self.step(Step::Bool(v))
    }
    fn serialize_i8(self, v: i8) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_i16(self, v: i16) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_i32(self, v: i32) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_i64(self, v: i64) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_i128(self, v: i128) -> R {
        self.step(Step::Int(v))
    }
    fn serialize_u8(self, v: u8) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_u16(self, v: u16) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_u32(self, v: u32) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_u64(self, v: u64) -> R {
        self.step(Step::Int(v.into()))
    }
    fn serialize_f32(self, v: f32) -> R {
        self.step(Step::Float(f64::from(v)))
    }
    fn serialize_f64(self, v: f64) -> R {
        self.step(Step::Float(v))
    }
    fn serialize_char(self, v: char) -> R {
        self.step(Step::Char(v))
    }
    fn serialize_str(self, v: &str) -> R {
        self.step(Step::Str(v))
    }
    fn serialize_bytes(self, v: &[u8]) -> R {
        self.step(Step::Bytes(v))
    }
    fn serialize_none(self) -> R {
        self.step(Step::None)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> R {
        self.step(Step::Some)?;
        value.serialize(self)
    }
    fn serialize_unit(self) -> R {
        self.step(Step::Unit)
    }
    fn serialize_unit_struct(self, name: &'static str) -> R {
        self.step(Step::Name(name))
    }
    fn serialize_unit_variant(self, _: &'static str, index: u32, _: &'static str) -> R {
        self.step(Step::Variant(index))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, name: &'static str, value: &T) -> R {
        self.step(Step::Name(name))?;
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        index: u32,
        variant: &'static str,
        value: &T,
    ) -> R {
        self.step(Step::Variant(index))?;
        self.under(variant, value)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Self, Stop> {
        self.open(None, &[Step::Open(len)])?;
        Ok(self)
    }
    fn serialize_tuple(self, len: usize) -> Result<Self, Stop> {
        self.open(None, &[Step::Open(Some(len))])?;
        Ok(self)
    }
    fn serialize_tuple_struct(self, name: &'static str, len: usize) -> Result<Self, Stop> {
        self.open(None, &[Step::Name(name), Step::Open(Some(len))])?;
        Ok(self)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Self, Stop> {
        self.open(Some(variant), &[Step::Variant(index), Step::Open(Some(len))])?;
        Ok(self)
    }
    fn serialize_map(self, len: Option<usize>) -> Result<Self, Stop> {
        self.open(None, &[Step::Open(len)])?;
        Ok(self)
    }
    fn serialize_struct(self, name: &'static str, _: usize) -> Result<Self, Stop> {
        self.open(None, &[Step::Name(name), Step::Open(None)])?;
        Ok(self)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        index: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Self, Stop> {
        self.open(Some(variant), &[Step::Variant(index), Step::Open(None)])?;
        Ok(self)
    }
}

/// A compound of unnamed elements (a sequence, a tuple, a tuple struct or variant): each
/// element walked in turn; `variant` closes an enum variant's compound too.
macro_rules! unnamed {
    ($compound:ident, $method:ident, $variant:literal) => {
        impl<F: FnMut(&[&'static str], Step<'_>) -> R> ser::$compound for &mut Walker<F> {
            type Ok = ();
            type Error = Stop;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> R {
                value.serialize(&mut **self)
            }
            fn end(self) -> R {
                self.close($variant)
            }
        }
    };
}

unnamed!(SerializeSeq, serialize_element, false);
unnamed!(SerializeTuple, serialize_element, false);
unnamed!(SerializeTupleStruct, serialize_field, false);
unnamed!(SerializeTupleVariant, serialize_field, true);

impl<F: FnMut(&[&'static str], Step<'_>) -> R> ser::SerializeMap for &mut Walker<F> {
    type Ok = ();
    type Error = Stop;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> R {
        key.serialize(&mut **self)
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> R {
        value.serialize(&mut **self)
    }
    fn end(self) -> R {
        self.close(false)
    }
}

/// A compound of named fields (a struct or a struct variant): each field walked under its name.
macro_rules! named {
    ($compound:ident, $variant:literal) => {
        impl<F: FnMut(&[&'static str], Step<'_>) -> R> ser::$compound for &mut Walker<F> {
            type Ok = ();
            type Error = Stop;
            fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> R {
                self.step(Step::Name(key))?;
                self.under(key, value)
            }
            fn end(self) -> R {
                self.close($variant)
            }
        }
    };
}

named!(SerializeStruct, false);
named!(SerializeStructVariant, true);

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    enum Shape {
        Dot,
        Circle(f64),
        Pair(f64, f64),
        Box { w: f64, h: f64 },
    }

    #[derive(serde::Serialize)]
    struct Scene {
        name: &'static str,
        shapes: Vec<Shape>,
        scale: Option<f32>,
    }

    /// Each step with its path, as text.
    fn steps<T: Serialize>(v: &T) -> Vec<String> {
        let mut out = Vec::new();
        walk(v, |path, step| {
            out.push(format!("{} {step:?}", path.join(".")));
            Ok(())
        })
        .unwrap();
        out
    }

    #[test]
    fn every_step_comes_with_the_path_of_names_down_to_it() {
        let scene = Scene {
            name: "s",
            shapes: vec![Shape::Dot, Shape::Circle(1.0), Shape::Pair(2.0, 3.0), Shape::Box { w: 4.0, h: 5.0 }],
            scale: Some(0.5),
        };
        let want = [
            " Name(\"Scene\")",
            " Open(None)",
            " Name(\"name\")",
            "name Str(\"s\")",
            " Name(\"shapes\")",
            "shapes Open(Some(4))",
            "shapes Variant(0)",
            "shapes Variant(1)",
            "shapes.Circle Float(1.0)",
            "shapes Variant(2)",
            "shapes Open(Some(2))",
            "shapes.Pair Float(2.0)",
            "shapes.Pair Float(3.0)",
            "shapes Close",
            "shapes Variant(3)",
            "shapes Open(None)",
            "shapes.Box Name(\"w\")",
            "shapes.Box.w Float(4.0)",
            "shapes.Box Name(\"h\")",
            "shapes.Box.h Float(5.0)",
            "shapes Close",
            "shapes Close",
            " Name(\"scale\")",
            "scale Some",
            "scale Float(0.5)",
            " Close",
        ];
        assert_eq!(steps(&scene), want);
    }

    #[test]
    fn the_visitor_stops_the_walk_and_a_refusing_value_does_too() {
        let mut seen = 0;
        let stop = walk(&vec![1.0, 2.0, 3.0], |_, step| {
            seen += 1;
            if step == Step::Float(2.0) {
                Err(Stop("two".into()))
            } else {
                Ok(())
            }
        });
        assert_eq!(stop, Err(Stop("two".into())));
        assert_eq!(seen, 3, "Open, 1.0, 2.0: nothing after the stop");
        assert!(walk(&u128::MAX, |_, _| Ok(())).is_err(), "u128 is refused, as serde's default");
    }
}
