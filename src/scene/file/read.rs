//! Reading with positions: serde reads from toml's tree of spans through
//! `serde_path_to_error`, and a refusal becomes an [`Error`] naming the field as the file
//! spells it, with toml's line and column.

use std::ops::Range;
use std::path::Path;

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use serde_path_to_error::Segment;
use toml::de::{DeValue, ValueDeserializer};
use toml::Spanned;

use crate::error::Error;

/// What reading needs besides the typed file: where it came from, for messages and
/// relative paths, and the document itself.
pub(super) struct Context<'a> {
    pub(super) source: &'a Path,
    pub(super) base: Option<&'a Path>,
    pub(super) text: &'a str,
    pub(super) root: &'a Spanned<DeValue<'a>>,
}

/// What serde or toml refused, and where.
pub(super) struct Refusal {
    /// The field's full name (`item[2] ("cube").scale`); empty for the document itself.
    pub(super) field: String,
    /// The bytes toml points at, when it points.
    pub(super) span: Option<Range<usize>>,
    /// serde's or toml's message, in the file's words.
    pub(super) message: String,
}

impl Context<'_> {
    pub(super) fn bad(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::in_field(self.source, field, message)
    }

    /// `values` must all be >= 0 (colours, intensities, ambient light).
    pub(super) fn non_negative(&self, field: &str, values: &[f32]) -> crate::error::Result<()> {
        if values.iter().any(|v| *v < 0.0) {
            let (shown, what) = match values {
                [v] => (v.to_string(), "a number"),
                _ => (format!("{values:?}"), "numbers"),
            };
            return Err(self.bad(field, format!("{shown}: expected {what} >= 0")));
        }
        Ok(())
    }

    /// "line L, column C" of the byte `offset`.
    pub(super) fn at(&self, offset: usize) -> String {
        let (line, col) = line_col(self.text, offset);
        format!("line {line}, column {col}")
    }

    /// Reads `T` from `value`: the document (`prefix` empty) or the light `prefix`.
    pub(super) fn read<'de, T: Deserialize<'de>>(
        &self,
        value: &Spanned<DeValue<'de>>,
        prefix: &str,
    ) -> std::result::Result<T, Refusal> {
        serde_path_to_error::deserialize(ValueDeserializer::from(value.clone())).map_err(|e| {
            let inner = e.inner();
            let mut field = field_name(value.get_ref(), prefix, e.path());
            // A missing key is no value on the path: add it to its table's name.
            if let Some(key) = backticked(inner.message(), "missing field `") {
                field = join(&field, key);
            }
            Refusal {
                field,
                span: inner.span(),
                message: friendly(inner.message()),
            }
        })
    }
}

impl Refusal {
    /// The error: `{file}: {field}: line L, column C: {message}`.
    pub(super) fn error(self, cx: &Context) -> Error {
        let message = match &self.span {
            Some(span) => format!("{}: {}", cx.at(span.start), self.message),
            None => self.message,
        };
        match self.field.as_str() {
            "" => Error::file(cx.source, message),
            _ => Error::in_field(cx.source, self.field, message),
        }
    }
}

/// A document toml cannot parse: its line and column, the text toml points at (toml's
/// messages do not quote it: "duplicate key"), and toml's message.
pub(super) fn syntax_error(e: &toml::de::Error, text: &str, source: &Path) -> Error {
    let message = e.message().trim_end();
    let Some(span) = e.span() else {
        return Error::file(source, message);
    };
    let (line, col) = line_col(text, span.start);
    let quoted = text
        .get(span)
        .filter(|t| !t.trim().is_empty() && t.len() <= 40 && !t.contains('\n'))
        .map_or(String::new(), |t| format!(", at `{t}`"));
    Error::file(
        source,
        format!("line {line}, column {col}{quoted}: {message}"),
    )
}

/// The field at `path` inside `node`, named as messages name it: keys joined by dots after
/// `prefix`, and an element `[i]`, or `[i] ("name")` when it has a name.
pub(super) fn field_name(node: &DeValue, prefix: &str, path: &serde_path_to_error::Path) -> String {
    let mut field = prefix.to_string();
    let mut node = Some(node);
    for segment in path.iter() {
        match segment {
            Segment::Map { key } => {
                field = join(&field, key);
                node = node.and_then(|n| n.get(key.as_str())).map(Spanned::get_ref);
            }
            // Tables in an array are told apart; numbers in one are the array's (toml's
            // column points at the number).
            Segment::Seq { index } => {
                node = node.and_then(|n| n.get(*index)).map(Spanned::get_ref);
                if node.is_some_and(DeValue::is_table) {
                    let name = node.and_then(|n| n.get("name")?.get_ref().as_str());
                    field.push_str(&element_label(*index, name));
                }
            }
            Segment::Enum { .. } | Segment::Unknown => {}
        }
    }
    field
}

fn join(field: &str, key: &str) -> String {
    match field {
        "" => key.to_string(),
        _ => format!("{field}.{key}"),
    }
}

/// `[i]`, with the element's `name` when it has one: `[2] ("cube")`.
pub(super) fn element_label(index: usize, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("[{index}] ({n:?})"),
        None => format!("[{index}]"),
    }
}

/// "1 value given", "3 values given".
pub(super) fn given(n: usize) -> String {
    let s = if n == 1 { "" } else { "s" };
    format!("{n} value{s} given")
}

pub(super) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    (line, col)
}

/// The name inside the first backticks after `prefix` in a serde message
/// ("unknown field `shininess`, expected ...").
pub(super) fn backticked<'m>(message: &'m str, prefix: &str) -> Option<&'m str> {
    let rest = &message[message.find(prefix)? + prefix.len()..];
    rest.split('`').next()
}

/// serde's "unknown field `mapsize`, expected one of `technique`, ..." (every field of
/// the table) as "unknown field `mapsize`: did you mean `map_size`?" when one name is a
/// slip away; likewise for an unknown value ("unknown variant").
fn near_name(message: &str) -> Option<String> {
    let (head, list) = message.split_once(", expected ")?;
    let (what, given) = [("unknown field `", "field"), ("unknown variant `", "value")]
        .iter()
        .find_map(|(prefix, what)| Some((*what, backticked(head, prefix)?)))?;
    let names = list.split('`').skip(1).step_by(2);
    let guess = crate::settings::suggest::did_you_mean(given, names)?;
    Some(format!("unknown {what} `{given}`: did you mean `{guess}`?"))
}

/// serde names Rust types ("expected f32"); say what to write instead.
fn friendly(message: &str) -> String {
    let named = [
        ("expected f32", "expected a number"),
        ("expected f64", "expected a number"),
        (
            "expected u32",
            "expected a whole number from 0 to 4294967295",
        ),
        ("expected u64", "expected a whole number >= 0"),
        ("expected a boolean", "expected true or false"),
        ("expected a map", "expected a table"),
        ("expected a sequence", "expected an array"),
        (
            "expected struct OrthoCoords",
            "expected a table { left, right, bottom, top, near, far }",
        ),
    ];
    if let Some(short) = near_name(message) {
        return short;
    }
    let mut m = named
        .iter()
        .fold(message.to_string(), |m, (from, to)| m.replace(from, to));
    // Any other struct is one of this module's tables.
    if let Some(i) = m.find("expected struct ") {
        let rest = &m[i + "expected struct ".len()..];
        let end = rest
            .find(|c: char| !c.is_alphanumeric())
            .unwrap_or(rest.len());
        m = format!("{}expected a table{}", &m[..i], &rest[end..]);
    }
    m
}

/// Every value of the document, refusing numbers no field may hold wherever they are: NaN,
/// infinities, and values beyond the f32 every field is read into. Also a `shadow` table's
/// `polygon_offset` of other than two numbers, which `ShadowSettings`' `[f32; 2]` would
/// cut to its first two.
pub(super) struct Numbers;

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(Place::Any).map(|()| Numbers)
    }
}

/// Where a value sits, as far as [`Numbers`] cares.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    Any,
    Shadow,
    PolygonOffset,
}

impl<'de> DeserializeSeed<'de> for Place {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

/// Visitor methods that take any value of their type.
macro_rules! accept {
    ($($visit:ident: $t:ty),*) => {
        $(fn $visit<E>(self, _: $t) -> Result<(), E> { Ok(()) })*
    };
}

impl<'de> Visitor<'de> for Place {
    type Value = ();
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a TOML value")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<(), E> {
        if !v.is_finite() {
            return Err(E::custom(format!("{v} is not a finite number")));
        }
        if (v as f32).is_infinite() {
            return Err(E::custom(format!(
                "{v:e} is too large: expected a number within +-{:e} (32-bit floats)",
                f32::MAX
            )));
        }
        Ok(())
    }
    // Whatever else a value is, it is no number to refuse.
    accept!(visit_i64: i64, visit_u64: u64, visit_i128: i128, visit_u128: u128);
    accept!(visit_bool: bool, visit_str: &str);
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let mut n = 0;
        while seq.next_element_seed(Place::Any)?.is_some() {
            n += 1;
        }
        if self == Place::PolygonOffset && n != 2 {
            return Err(de::Error::custom(format!(
                "{}: expected exactly 2 numbers [factor, units]",
                given(n)
            )));
        }
        Ok(())
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            let place = match (self, key.as_str()) {
                (_, "shadow") => Place::Shadow,
                (Place::Shadow, "polygon_offset") => Place::PolygonOffset,
                _ => Place::Any,
            };
            map.next_value_seed(place)?;
        }
        Ok(())
    }
}
