//! The settings' enums are named once, by their `clap::ValueEnum` derive (the values flags
//! take, listed with their documentation in `--help`). Scene files (serde), summaries and
//! reports (`name()`, `Display`) read the same names from there.

use std::marker::PhantomData;
use std::sync::OnceLock;

use clap::ValueEnum;

/// An enum whose values are named by clap.
pub trait ClapNamed: ValueEnum + PartialEq + 'static {
    /// Every value's name, in `value_variants()`'s order: built once, kept for the run.
    fn names() -> &'static [&'static str];

    /// This value's name.
    fn clap_name(&self) -> &'static str {
        let i = Self::value_variants()
            .iter()
            .position(|v| v == self)
            .expect("clap lists every value");
        Self::names()[i]
    }
}

/// Every value's name as clap gives it, kept in `owned` (the names are `'static` from then
/// on, as serde's messages want them).
pub fn names_of<T: ValueEnum>(
    owned: &'static OnceLock<Vec<String>>,
    names: &'static OnceLock<Vec<&'static str>>,
) -> &'static [&'static str] {
    names.get_or_init(|| {
        owned
            .get_or_init(|| {
                T::value_variants()
                    .iter()
                    .map(|v| v.to_possible_value().expect("no value is skipped"))
                    .map(|p| p.get_name().to_owned())
                    .collect()
            })
            .iter()
            .map(String::as_str)
            .collect()
    })
}

pub fn serialize<T: ClapNamed, S: serde::Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(v.clap_name())
}

/// Reads a value by its name; any other string is refused as serde's own enums refuse
/// one ("unknown variant `x`, expected one of `a`, `b`, `c`").
pub fn deserialize<'de, T: ClapNamed, D: serde::Deserializer<'de>>(d: D) -> Result<T, D::Error> {
    struct ByName<T>(PhantomData<T>);
    impl<T: ClapNamed> serde::de::Visitor<'_> for ByName<T> {
        type Value = T;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "one of `{}`", T::names().join("`, `"))
        }
        fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<T, E> {
            match T::names().iter().position(|n| *n == s) {
                Some(i) => Ok(T::value_variants()[i].clone()),
                None => Err(E::unknown_variant(s, T::names())),
            }
        }
    }
    d.deserialize_str(ByName(PhantomData))
}

/// Names the enums by clap: `name()`, `Display`, `Serialize` and `Deserialize` all read
/// the derive's names.
macro_rules! named_by_clap {
    ($($ty:ty),+ $(,)?) => {$(
        impl $crate::settings::names::ClapNamed for $ty {
            fn names() -> &'static [&'static str] {
                static OWNED: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
                static NAMES: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
                $crate::settings::names::names_of::<$ty>(&OWNED, &NAMES)
            }
        }

        impl $ty {
            /// The name flags, scene files and reports use (clap's).
            pub fn name(self) -> &'static str {
                $crate::settings::names::ClapNamed::clap_name(&self)
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl serde::Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                $crate::settings::names::serialize(self, s)
            }
        }

        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                $crate::settings::names::deserialize(d)
            }
        }
    )+};
}
pub(crate) use named_by_clap;

#[cfg(test)]
mod tests {
    use super::super::{DepthFormat, Filter, PointPass, ShadowSettings};

    #[test]
    fn scene_files_and_reports_use_the_flags_names() {
        use clap::ValueEnum;
        for f in Filter::value_variants() {
            let flag = f.to_possible_value().unwrap();
            assert_eq!(f.name(), flag.get_name());
            assert_eq!(f.to_string(), f.name());
            let json = serde_json::to_string(f).unwrap();
            assert_eq!(json, format!("\"{}\"", f.name()));
            assert_eq!(serde_json::from_str::<Filter>(&json).unwrap(), *f);
        }
        assert_eq!(
            (DepthFormat::D32F.name(), PointPass::SixPasses.name()),
            ("32f", "six-passes")
        );
        let read = |t: &str| toml::from_str::<ShadowSettings>(t).map_err(|e| e.to_string());
        let s = read("depth_format = \"16\"\nfilter = \"pcf4x4-weighted\"").unwrap();
        assert_eq!(
            (s.depth_format, s.filter),
            (DepthFormat::D16, Filter::Pcf4x4Weighted)
        );
        let e = read("depth_format = \"8\"").unwrap_err();
        assert!(
            e.contains("unknown variant `8`, expected one of `16`, `24`, `32f`"),
            "{e}"
        );
        let e = read("depth_format = 24").unwrap_err();
        assert!(e.contains("expected one of `16`, `24`, `32f`"), "{e}");
    }
}
