//! The values a number setting takes, declared beside the setting in `shadow_settings!`:
//! validation and its messages ("shadow.bias = -1: expected a finite number >= 0") read
//! them, for the scene file's tables and the flags alike.

use std::fmt::{Debug, Display};

/// A setting's number type.
pub trait Number: Copy + PartialOrd + Display {
    /// NaN and the infinities would reach the shaders as garbage: no range takes them.
    fn finite(self) -> bool;
}

impl Number for f32 {
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl Number for u32 {
    fn finite(self) -> bool {
        true
    }
}

#[derive(Debug, Clone, Copy)]
enum Shape<T> {
    Any,
    AtLeast(T),
    Above(T),
    /// Both ends included.
    FromTo(T, T),
    /// The low end included, the high one not.
    FromBelow(T, T),
    /// Neither end included.
    Between(T, T),
}

/// The finite numbers a setting takes, and the words its message says them with.
#[derive(Debug, Clone)]
pub struct Range<T> {
    shape: Shape<T>,
    /// What the low end means, said after it ("1 (one map) to 4").
    low_means: &'static str,
    /// Said before an open range ("degrees between 0 and 180").
    unit: &'static str,
    /// Said after the range, in brackets.
    note: String,
}

impl<T: Number> Range<T> {
    fn of(shape: Shape<T>) -> Range<T> {
        Range {
            shape,
            low_means: "",
            unit: "",
            note: String::new(),
        }
    }

    /// Every finite number.
    pub fn any() -> Range<T> {
        Range::of(Shape::Any)
    }

    /// `low` or more.
    pub fn at_least(low: T) -> Range<T> {
        Range::of(Shape::AtLeast(low))
    }

    /// More than `low`.
    pub fn above(low: T) -> Range<T> {
        Range::of(Shape::Above(low))
    }

    /// `low` to `high`, both included.
    pub fn from_to(low: T, high: T) -> Range<T> {
        Range::of(Shape::FromTo(low, high))
    }

    /// `low` (included) to below `high`.
    pub fn from_below(low: T, high: T) -> Range<T> {
        Range::of(Shape::FromBelow(low, high))
    }

    /// Strictly between `low` and `high`.
    pub fn between(low: T, high: T) -> Range<T> {
        Range::of(Shape::Between(low, high))
    }

    pub fn low_means(self, means: &'static str) -> Range<T> {
        Range {
            low_means: means,
            ..self
        }
    }

    pub fn unit(self, unit: &'static str) -> Range<T> {
        Range { unit, ..self }
    }

    pub fn note(self, note: impl Into<String>) -> Range<T> {
        Range {
            note: note.into(),
            ..self
        }
    }

    /// A setting of two numbers, each in this range; `parts` names them.
    pub fn pair(self, parts: &'static str) -> Pair<T> {
        Pair { each: self, parts }
    }

    pub fn contains(&self, v: T) -> bool {
        v.finite()
            && match self.shape {
                Shape::Any => true,
                Shape::AtLeast(low) => v >= low,
                Shape::Above(low) => v > low,
                Shape::FromTo(low, high) => low <= v && v <= high,
                Shape::FromBelow(low, high) => low <= v && v < high,
                Shape::Between(low, high) => low < v && v < high,
            }
    }

    /// What the range takes, for "expected ...": one number, or with `plural` each of
    /// several.
    fn says(&self, plural: bool) -> String {
        let (a, s) = if plural { ("", "s") } else { ("a ", "") };
        let means = match self.low_means {
            "" => String::new(),
            m => format!(" ({m})"),
        };
        let unit = match self.unit {
            "" => String::new(),
            u => format!("{u} "),
        };
        let each = if plural { "numbers, each " } else { "" };
        match self.shape {
            Shape::Any => format!("{a}finite number{s}"),
            Shape::AtLeast(low) => format!("{a}finite number{s} >= {low}"),
            Shape::Above(low) => format!("{a}number{s} > {low}"),
            Shape::FromTo(low, high) => format!("{each}{low}{means} to {high}"),
            Shape::FromBelow(low, high) => format!("{each}{low}{means} to below {high}"),
            Shape::Between(low, high) => format!("{each}{unit}between {low} and {high}"),
        }
    }

    fn noted(&self, text: String) -> String {
        match self.note.as_str() {
            "" => text,
            note => format!("{text} ({note})"),
        }
    }
}

/// A setting of two numbers, each in `each`; `parts` names them ("[factor, units]").
#[derive(Debug, Clone)]
pub struct Pair<T> {
    each: Range<T>,
    parts: &'static str,
}

/// Bounds on a setting's value of type `V`.
pub trait Bounds<V> {
    fn admits(&self, v: V) -> bool;
    /// What comes after "expected".
    fn expected(&self) -> String;
    /// The value as the message shows it.
    fn show(&self, v: V) -> String;
}

impl<T: Number> Bounds<T> for Range<T> {
    fn admits(&self, v: T) -> bool {
        self.contains(v)
    }

    fn expected(&self) -> String {
        self.noted(self.says(false))
    }

    fn show(&self, v: T) -> String {
        v.to_string()
    }
}

impl<T: Number + Debug> Bounds<[T; 2]> for Pair<T> {
    fn admits(&self, v: [T; 2]) -> bool {
        v.iter().all(|&c| self.each.contains(c))
    }

    fn expected(&self) -> String {
        let each = self.each.says(true);
        self.each.noted(format!("two {each} {}", self.parts))
    }

    fn show(&self, v: [T; 2]) -> String {
        format!("{v:?}")
    }
}

/// Checks the setting `name`'s value against its bounds.
pub fn check<V, B: Bounds<V>>(name: &str, v: V, bounds: &B) -> crate::Result<()>
where
    V: Copy,
{
    match bounds.admits(v) {
        true => Ok(()),
        false => Err(crate::Error::Invalid(format!(
            "shadow.{name} = {}: expected {}",
            bounds.show(v),
            bounds.expected()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_take_their_values_and_say_which() {
        let blend = Range::from_to(0.0f32, 0.5);
        assert!(blend.contains(0.0) && blend.contains(0.5));
        assert!(!blend.contains(-0.1) && !blend.contains(0.6) && !blend.contains(f32::NAN));
        let bleed = Range::from_below(0.0f32, 1.0).low_means("off");
        assert!(bleed.contains(0.0) && !bleed.contains(1.0));
        assert_eq!(bleed.expected(), "0 (off) to below 1");
        let fov = Range::between(0.0f32, 180.0).unit("degrees");
        assert!(!fov.contains(0.0) && fov.contains(90.0) && !fov.contains(180.0));
        assert_eq!(fov.expected(), "degrees between 0 and 180");
        let bias = Range::at_least(0.0f32);
        assert!(bias.contains(0.0) && !bias.contains(-1.0) && !bias.contains(f32::INFINITY));
        let e = check("bias", -1.0f32, &bias).unwrap_err().to_string();
        assert_eq!(e, "shadow.bias = -1: expected a finite number >= 0");
        let taps = Range::from_to(1u32, 32).note("the points");
        assert_eq!(taps.expected(), "1 to 32 (the points)");
        let pair = Range::above(0.0f32)
            .note("each at most 42")
            .pair("[positive, negative]");
        assert!(pair.admits([1.0, 2.0]) && !pair.admits([1.0, 0.0]));
        let e = check("exponents", [40.0f32, -5.0], &pair)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "shadow.exponents = [40.0, -5.0]: expected two numbers > 0 [positive, negative] \
             (each at most 42)"
        );
        let any = Range::any().pair("[factor, units]");
        assert!(any.admits([-1.0f32, 4.0]) && !any.admits([f32::NAN, 0.0]));
        assert_eq!(any.expected(), "two finite numbers [factor, units]");
    }
}
