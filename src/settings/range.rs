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
    AtLeast(T),
    /// Both ends included.
    FromTo(T, T),
    /// The low end included, the high one not.
    FromBelow(T, T),
    /// Neither end included.
    Between(T, T),
    /// The low end not included, the high one included.
    AboveTo(T, T),
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

    /// `low` or more.
    pub fn at_least(low: T) -> Range<T> {
        Range::of(Shape::AtLeast(low))
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

    /// More than `low`, at most `high`.
    pub fn above_to(low: T, high: T) -> Range<T> {
        Range::of(Shape::AboveTo(low, high))
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
                Shape::AtLeast(low) => v >= low,
                Shape::FromTo(low, high) => low <= v && v <= high,
                Shape::FromBelow(low, high) => low <= v && v < high,
                Shape::Between(low, high) => low < v && v < high,
                Shape::AboveTo(low, high) => low < v && v <= high,
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
            Shape::AtLeast(low) => format!("{a}finite number{s} >= {low}"),
            Shape::FromTo(low, high) => format!("{each}{low}{means} to {high}"),
            Shape::FromBelow(low, high) => format!("{each}{low}{means} to below {high}"),
            Shape::Between(low, high) => format!("{each}{unit}between {low} and {high}"),
            Shape::AboveTo(low, high) => format!("{each}above {low}, at most {high}"),
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

/// A setting's `--help` text: its documentation as clap would show it (the lines joined,
/// a last full stop dropped), then the numbers it takes, if they are bounded, so the help
/// and the refusal say one range.
pub fn help(doc: &[&str], takes: Option<String>) -> String {
    let text: Vec<&str> = doc.iter().map(|line| line.trim()).collect();
    let text = text.join(" ");
    let text = match text.strip_suffix('.') {
        Some(t) if !t.ends_with('.') => t,
        _ => text.as_str(),
    };
    match takes {
        Some(range) => format!("{text} [range: {range}]"),
        None => text.to_string(),
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
        let pair = Range::above_to(0.0f32, 42.0)
            .note("the floats' limit")
            .pair("[positive, negative]");
        assert!(pair.admits([42.0, 1e-3]) && !pair.admits([1.0, 0.0]));
        assert!(!pair.admits([42.5, 5.0]) && !pair.admits([f32::NAN, 5.0]));
        let e = check("exponents", [40.0f32, -5.0], &pair)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "shadow.exponents = [40.0, -5.0]: expected two numbers, each above 0, at most 42 \
             [positive, negative] (the floats' limit)"
        );
        let offset = Range::from_to(-1000.0f32, 1000.0).pair("[factor, units]");
        assert!(offset.admits([-1.0, 4.0]) && !offset.admits([1e9, 0.0]));
        assert_eq!(
            offset.expected(),
            "two numbers, each -1000 to 1000 [factor, units]"
        );
    }

    #[test]
    fn the_help_is_the_documentation_then_the_range() {
        let doc = [
            " Where the cascades split: 0 = uniform,",
            " 1 = logarithmic.",
        ];
        let lambda = Range::from_to(0.0f32, 1.0);
        assert_eq!(
            help(&doc, Some(lambda.expected())),
            "Where the cascades split: 0 = uniform, 1 = logarithmic [range: 0 to 1]"
        );
        assert_eq!(help(&[" Faces culled."], None), "Faces culled");
        assert_eq!(help(&[" Stops at 1.."], None), "Stops at 1..");
    }
}
