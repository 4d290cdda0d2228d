//! Over ~600 lines on purpose (by a few): one reader walks the whole tree, with its error
//! wording and did-you-mean in one place, so every path reports alike.
//!
//! The strict reader of the scene schema: any tree of plain values (a Python dict, a parsed
//! TOML file) becomes the serde types of [`super`], or an error naming the full path, the
//! value and the rule, e.g. `pulleys[0].radious = 'radious': unknown key, did you mean
//! 'radius'? (known keys here: ...)` or `belt.elements = 89.0: expected a whole number`.
//!
//! Values are shown as Python shows them (`'text'`, `None`, `True`, `1e+16`), since the
//! scene reaches the engine from Python dicts and TOML files read in Python.

use crate::error::{BeltError, BeltResult};
use serde::de::{
    self, DeserializeOwned, DeserializeSeed, Deserializer, Expected, IntoDeserializer, MapAccess,
    SeqAccess, Unexpected, Visitor,
};
use std::fmt::{self, Display, Write};

/// Deepest nesting a scene value may have. The schema itself is five levels deep
/// (`pulleys[0].drive.start_curve.speed`); a deeper value is refused before it is read.
pub const MAX_DEPTH: usize = 16;

/// A plain value, as a dict, a list or a TOML file holds it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// `None` (Python), absent in TOML.
    Null,
    /// `true` / `false`.
    Bool(bool),
    /// A whole number.
    Int(i64),
    /// A number.
    Float(f64),
    /// Text.
    Str(String),
    /// A list.
    Seq(Vec<Value>),
    /// A table, its keys in order.
    Map(Vec<(String, Value)>),
    /// A value of a kind no scene key takes, as its holder shows it (e.g. a Python object's
    /// `repr`).
    Other(String),
}

/// The text Python's `repr` gives for `x` (shortest round-trip digits; exponent form below
/// 1e-4 and from 1e16 on).
pub fn python_float(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0.0" } else { "0.0" }.into();
    }
    // `{:e}` gives the shortest digits that round-trip: "-1.2345e-7".
    let sci = format!("{x:e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let (sign, mantissa) = match mantissa.strip_prefix('-') {
        Some(m) => ("-", m),
        None => ("", mantissa),
    };
    let digits: String = mantissa.chars().filter(|c| *c != '.').collect();
    if (-4..16).contains(&exp) {
        let n = digits.len() as i32;
        if exp < 0 {
            format!("{sign}0.{}{digits}", "0".repeat((-exp - 1) as usize))
        } else if exp + 1 >= n {
            format!("{sign}{digits}{}.0", "0".repeat((exp + 1 - n) as usize))
        } else {
            let (a, b) = digits.split_at((exp + 1) as usize);
            format!("{sign}{a}.{b}")
        }
    } else {
        let m = if digits.len() > 1 {
            format!("{}.{}", &digits[..1], &digits[1..])
        } else {
            digits
        };
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{sign}{m}e{esign}{:02}", exp.abs())
    }
}

/// The text Python's `repr` gives for a string.
pub fn python_str(s: &str) -> String {
    let quote = if s.contains('\'') && !s.contains('"') {
        '"'
    } else {
        '\''
    };
    let mut out = String::with_capacity(s.len() + 2);
    out.push(quote);
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c == quote => {
                out.push('\\');
                out.push(c);
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                let _ = write!(out, "\\x{:02x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

/// Longest text of a value shown in a message.
const SHOWN_CHARS: usize = 200;

impl Display for Value {
    /// As Python's `repr` shows it, cut after about 200 characters.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        self.show(&mut out);
        if out.chars().count() > SHOWN_CHARS {
            let cut: String = out.chars().take(SHOWN_CHARS).collect();
            return write!(f, "{cut}...");
        }
        f.write_str(&out)
    }
}

impl Value {
    fn show(&self, out: &mut String) {
        if out.len() > 4 * SHOWN_CHARS {
            return;
        }
        match self {
            Value::Null => out.push_str("None"),
            Value::Bool(b) => out.push_str(if *b { "True" } else { "False" }),
            Value::Int(i) => {
                let _ = write!(out, "{i}");
            }
            Value::Float(x) => out.push_str(&python_float(*x)),
            Value::Str(s) => out.push_str(&python_str(s)),
            Value::Seq(items) => {
                out.push('[');
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        out.push_str(", ");
                    }
                    v.show(out);
                }
                out.push(']');
            }
            Value::Map(items) => {
                out.push('{');
                for (i, (k, v)) in items.iter().enumerate() {
                    if i > 0 {
                        out.push_str(", ");
                    }
                    out.push_str(&python_str(k));
                    out.push_str(": ");
                    v.show(out);
                }
                out.push('}');
            }
            Value::Other(s) => out.push_str(s),
        }
    }
}

/// Where a value sits in the scene, built on the stack while reading and printed only for
/// an error.
#[derive(Clone, Copy)]
struct Path<'a> {
    parent: Option<&'a Path<'a>>,
    seg: Seg<'a>,
}

#[derive(Clone, Copy)]
enum Seg<'a> {
    Root(&'a str),
    Key(&'a str),
    Index(usize),
}

impl<'a> Path<'a> {
    fn key(&'a self, key: &'a str) -> Path<'a> {
        Path {
            parent: Some(self),
            seg: Seg::Key(key),
        }
    }

    fn index(&'a self, i: usize) -> Path<'a> {
        Path {
            parent: Some(self),
            seg: Seg::Index(i),
        }
    }

    fn render(&self, out: &mut String) {
        if let Some(p) = self.parent {
            p.render(out);
        }
        match self.seg {
            Seg::Root(name) => out.push_str(name),
            Seg::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(k);
            }
            Seg::Index(i) => {
                let _ = write!(out, "[{i}]");
            }
        }
    }

    fn text(&self) -> String {
        let mut s = String::new();
        self.render(&mut s);
        s
    }
}

/// Marks a message built by [`rule`], so that the reader can take it apart again.
const MARK: char = '\u{1f}';

/// The message of an error found by a conversion inside the schema (e.g. the `friction`
/// table): the key under the value being read (`".static"`, or `""` for the value itself),
/// the value as shown, and the rule. The reader prefixes the path.
pub(crate) fn rule(sub: &str, value: impl Display, rule: impl Display) -> String {
    format!("{MARK}{sub}{MARK}{value}{MARK}{rule}")
}

#[derive(Debug)]
enum Kind {
    /// The value has the wrong type; `expected` says what it should be.
    Type(String),
    UnknownKey {
        key: String,
        known: &'static [&'static str],
    },
    Missing(&'static str),
    /// Any other message (serde's own).
    Message(String),
    /// A rule broken, from [`rule`].
    Rule {
        sub: String,
        value: String,
        rule: String,
    },
}

/// An error while reading a scene; becomes a [`BeltError::InvalidParameter`].
#[derive(Debug)]
pub struct ReadError {
    /// Field and value, set by the innermost reader that sees the error.
    placed: Option<(String, String)>,
    kind: Kind,
}

impl ReadError {
    fn at(mut self, path: &Path<'_>, value: &Value) -> Self {
        if self.placed.is_none() {
            let field = path.text();
            self.placed = Some(match &self.kind {
                Kind::Missing(name) if field.is_empty() => (name.to_string(), "missing".into()),
                Kind::Missing(name) => (format!("{field}.{name}"), "missing".into()),
                Kind::UnknownKey { key, .. } => (field, python_str(key)),
                Kind::Rule { sub, value, .. } => (format!("{field}{sub}"), value.clone()),
                Kind::Type(_) | Kind::Message(_) => (field, value.to_string()),
            });
        }
        self
    }

    fn rule_text(&self) -> String {
        match &self.kind {
            Kind::Type(expected) => format!("expected {expected}"),
            Kind::UnknownKey { key, known } => {
                crate::suggest::unknown_key_rule(key, known.iter().copied())
            }
            Kind::Missing(_) => "required".into(),
            Kind::Message(m) => m.clone(),
            Kind::Rule { rule, .. } => rule.clone(),
        }
    }
}

impl From<ReadError> for BeltError {
    fn from(e: ReadError) -> BeltError {
        let rule = e.rule_text();
        let (field, value) = e.placed.unwrap_or_default();
        let field = if field.is_empty() {
            "scene".into()
        } else {
            field
        };
        BeltError::InvalidParameter { field, value, rule }
    }
}

impl Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (field, value) = self.placed.clone().unwrap_or_default();
        write!(f, "{field} = {value}: {}", self.rule_text())
    }
}

impl std::error::Error for ReadError {}

/// What a serde `expected` says, in the words of the scene format.
fn friendly(exp: &dyn Expected) -> String {
    let s = exp.to_string();
    match s.as_str() {
        "f64" | "f32" => "a number".into(),
        "usize" | "u64" | "u32" | "u16" | "u8" | "i64" | "i32" => "a whole number".into(),
        "a boolean" => "true or false".into(),
        "a string" | "a borrowed string" => "a string".into(),
        "an array of length 2" | "a tuple of size 2" => "[x, y]".into(),
        "a sequence" => "a list".into(),
        _ if s.starts_with("struct ") || s == "a map" => "a table".into(),
        _ => s,
    }
}

impl de::Error for ReadError {
    fn custom<T: Display>(msg: T) -> Self {
        let msg = msg.to_string();
        let kind = match msg
            .strip_prefix(MARK)
            .map(|m| m.splitn(3, MARK).collect::<Vec<_>>())
        {
            Some(parts) if parts.len() == 3 => Kind::Rule {
                sub: parts[0].into(),
                value: parts[1].into(),
                rule: parts[2].into(),
            },
            _ => Kind::Message(msg),
        };
        ReadError { placed: None, kind }
    }

    fn invalid_type(_: Unexpected<'_>, exp: &dyn Expected) -> Self {
        ReadError {
            placed: None,
            kind: Kind::Type(friendly(exp)),
        }
    }

    fn invalid_value(unexp: Unexpected<'_>, exp: &dyn Expected) -> Self {
        let expected = match (unexp, friendly(exp).as_str()) {
            (Unexpected::Signed(_), "a whole number") => "a whole number ≥ 0".to_string(),
            (_, e) => e.to_string(),
        };
        ReadError {
            placed: None,
            kind: Kind::Type(expected),
        }
    }

    fn invalid_length(_: usize, exp: &dyn Expected) -> Self {
        Self::invalid_type(Unexpected::Seq, exp)
    }

    fn unknown_field(field: &str, expected: &'static [&'static str]) -> Self {
        ReadError {
            placed: None,
            kind: Kind::UnknownKey {
                key: field.into(),
                known: expected,
            },
        }
    }

    fn missing_field(field: &'static str) -> Self {
        ReadError {
            placed: None,
            kind: Kind::Missing(field),
        }
    }
}

/// Read `T` (a scene or any part of it) from `value`; messages name paths from `root`
/// (e.g. `"start_curve"`, or `""` for a whole scene). Only structure and types are checked
/// here: the rules on values are `validate`'s.
pub fn from_value<T: DeserializeOwned>(value: &Value, root: &str) -> BeltResult<T> {
    let path = Path {
        parent: None,
        seg: Seg::Root(root),
    };
    if let Some(deep) = too_deep(value, 0) {
        return Err(BeltError::invalid(
            if root.is_empty() { "scene" } else { root },
            format!("a value nested {deep} levels deep"),
            format!("nested deeper than any scene key ({MAX_DEPTH} levels at most)"),
        ));
    }
    T::deserialize(De { value, path: &path }).map_err(|e| e.at(&path, value).into())
}

fn too_deep(v: &Value, depth: usize) -> Option<usize> {
    if depth > MAX_DEPTH {
        return Some(depth);
    }
    match v {
        Value::Seq(items) => items.iter().find_map(|x| too_deep(x, depth + 1)),
        Value::Map(items) => items.iter().find_map(|(_, x)| too_deep(x, depth + 1)),
        _ => None,
    }
}

/// The serde deserializer over a [`Value`] that knows its path.
struct De<'v, 'p> {
    value: &'v Value,
    path: &'p Path<'p>,
}

impl<'de> Deserializer<'de> for De<'_, '_> {
    type Error = ReadError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        let out = match self.value {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(*b),
            Value::Int(i) => visitor.visit_i64(*i),
            Value::Float(x) => visitor.visit_f64(*x),
            Value::Str(s) => visitor.visit_str(s),
            Value::Seq(items) => visitor.visit_seq(Seq {
                items: items.iter().enumerate(),
                path: self.path,
            }),
            Value::Map(items) => visitor.visit_map(Map {
                items: items.iter(),
                pending: None,
                path: self.path,
            }),
            Value::Other(s) => Err(de::Error::invalid_type(Unexpected::Other(s), &visitor)),
        };
        out.map_err(|e| e.at(self.path, self.value))
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        match self.value {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        match self.value {
            Value::Seq(items) if items.len() != len => Err(
                <ReadError as de::Error>::invalid_length(items.len(), &visitor)
                    .at(self.path, self.value),
            ),
            _ => self.deserialize_any(visitor),
        }
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        match self.value {
            // serde's derived structs also take a list of their fields in order, so `belt = []`
            // read as every default; a scene table is written with its keys.
            Value::Seq(_) => Err(
                <ReadError as de::Error>::invalid_type(Unexpected::Seq, &visitor)
                    .at(self.path, self.value),
            ),
            _ => self.deserialize_any(visitor),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        match self.value {
            Value::Str(s) => visitor
                .visit_enum(s.as_str().into_deserializer())
                .map_err(|e: ReadError| e.at(self.path, self.value)),
            _ => self.deserialize_any(visitor),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple_struct map identifier ignored_any
    }
}

struct Seq<'v, 'p> {
    items: std::iter::Enumerate<std::slice::Iter<'v, Value>>,
    path: &'p Path<'p>,
}

impl<'de> SeqAccess<'de> for Seq<'_, '_> {
    type Error = ReadError;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, ReadError> {
        let Some((i, value)) = self.items.next() else {
            return Ok(None);
        };
        let path = self.path.index(i);
        seed.deserialize(De { value, path: &path })
            .map(Some)
            .map_err(|e| e.at(&path, value))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

struct Map<'v, 'p> {
    items: std::slice::Iter<'v, (String, Value)>,
    pending: Option<&'v (String, Value)>,
    path: &'p Path<'p>,
}

impl<'de> MapAccess<'de> for Map<'_, '_> {
    type Error = ReadError;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, ReadError> {
        let Some(entry) = self.items.next() else {
            return Ok(None);
        };
        self.pending = Some(entry);
        let key: de::value::StrDeserializer<'_, ReadError> = entry.0.as_str().into_deserializer();
        let path = self.path.key(&entry.0);
        seed.deserialize(key)
            .map(Some)
            .map_err(|e| e.at(&path, &entry.1))
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, ReadError> {
        let Some((key, value)) = self.pending.take() else {
            return Err(de::Error::custom("a value read before its key"));
        };
        let path = self.path.key(key);
        seed.deserialize(De { value, path: &path })
            .map_err(|e| e.at(&path, value))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_as_python_shows_them() {
        let cases = [
            (89.0, "89.0"),
            (0.5, "0.5"),
            (1e16, "1e+16"),
            (1.5e16, "1.5e+16"),
            (123456789012345.6, "123456789012345.6"),
            (1e-4, "0.0001"),
            (1.5e-5, "1.5e-05"),
            (-2.5e-300, "-2.5e-300"),
            (1e9, "1000000000.0"),
            (-0.0, "-0.0"),
            (f64::INFINITY, "inf"),
            (0.1 + 0.2, "0.30000000000000004"),
        ];
        for (x, want) in cases {
            assert_eq!(python_float(x), want, "{x:e}");
        }
    }

    #[test]
    fn strings_as_python_shows_them() {
        assert_eq!(python_str("radius"), "'radius'");
        assert_eq!(python_str("it's"), "\"it's\"");
        assert_eq!(python_str("a\tb\\"), "'a\\tb\\\\'");
    }
}
