//! A shadow map's size: one side for the chapters' square maps, or width and height
//! (the shadow-playground's canvas-shaped maps), as scene files and `--map-size` spell it.

use serde::{Deserialize, Serialize};

/// A shadow map's size in texels. Square in the chapters (`map_size = 1024`, `--map-size
/// 1024`); the shadow-playground's maps have its canvas' shape (`map_size = [400, 300]`,
/// `--map-size 400x300`). Cube maps and cascade arrays are square and refuse other sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MapSize {
    pub width: u32,
    pub height: u32,
}

impl MapSize {
    /// A `side` x `side` map.
    pub const fn square(side: u32) -> MapSize {
        MapSize {
            width: side,
            height: side,
        }
    }

    pub fn is_square(self) -> bool {
        self.width == self.height
    }

    /// The smaller side: the coarser texels are along it.
    pub fn min_side(self) -> u32 {
        self.width.min(self.height)
    }

    /// The larger side.
    pub fn max_side(self) -> u32 {
        self.width.max(self.height)
    }

    /// Texels in the map.
    pub fn texels(self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// Width over height.
    pub fn aspect(self) -> f32 {
        self.width as f32 / self.height.max(1) as f32
    }

    /// At least `side` texels on each side (the `hi-res` step).
    pub fn at_least(self, side: u32) -> MapSize {
        MapSize {
            width: self.width.max(side),
            height: self.height.max(side),
        }
    }

    /// The side of a square map, or an error saying that `what` (a cube map, cascades)
    /// needs one: its faces and layers are square.
    pub fn square_side(self, what: &str) -> crate::Result<u32> {
        match self.is_square() {
            true => Ok(self.width),
            false => Err(crate::Error::Invalid(format!(
                "shadow.map_size = {self}: {what} needs a square map (its faces or layers are \
                 square); expected one number, like {}",
                self.max_side()
            ))),
        }
    }
}

impl MapSize {
    /// `1024^2` for a square map, `400x300` otherwise (for summaries).
    pub fn label(&self) -> String {
        match self.is_square() {
            true => format!("{}^2", self.width),
            false => self.to_string(),
        }
    }
}

impl std::fmt::Display for MapSize {
    /// `1024` for a square map, `400x300` otherwise (as `--map-size` takes it).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.is_square() {
            true => write!(f, "{}", self.width),
            false => write!(f, "{}x{}", self.width, self.height),
        }
    }
}

impl From<u32> for MapSize {
    fn from(side: u32) -> MapSize {
        MapSize::square(side)
    }
}

/// A square map's side equals the size of that square (the cube and cascade maps, square
/// by construction, compare their side with the settings' size).
impl PartialEq<MapSize> for u32 {
    fn eq(&self, size: &MapSize) -> bool {
        size.width == *self && size.height == *self
    }
}

impl Serialize for MapSize {
    /// A number for a square map, `[width, height]` otherwise.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.is_square() {
            true => s.serialize_u32(self.width),
            false => [self.width, self.height].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for MapSize {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<MapSize, D::Error> {
        struct V;
        const EXPECTED: &str = "a side in texels (like 1024) or [width, height] (like [400, 300])";
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = MapSize;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<MapSize, E> {
                u32::try_from(v)
                    .map(MapSize::square)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<MapSize, E> {
                u64::try_from(v)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Signed(v), &self))
                    .and_then(|v| self.visit_u64(v))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut a: A,
            ) -> Result<MapSize, A::Error> {
                let side = |v: Option<u32>, i| {
                    v.ok_or_else(|| serde::de::Error::invalid_length(i, &"[width, height]"))
                };
                let width = side(a.next_element::<u32>()?, 0)?;
                let height = side(a.next_element::<u32>()?, 1)?;
                if a.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    return Err(serde::de::Error::invalid_length(3, &"[width, height]"));
                }
                Ok(MapSize { width, height })
            }
        }
        d.deserialize_any(V)
    }
}

/// Parses `--map-size`: `N` (a square map) or `WxH`, e.g. `1024` or `400x300`.
pub fn parse_map_size(s: &str) -> Result<MapSize, String> {
    let err =
        || format!("'{s}': expected a side in texels like 1024, or WIDTHxHEIGHT like 400x300");
    let side = |t: &str| t.trim().parse::<u32>().map_err(|_| err());
    match s.split_once(['x', 'X']) {
        Some((w, h)) => Ok(MapSize {
            width: side(w)?,
            height: side(h)?,
        }),
        None => side(s).map(MapSize::square),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::ShadowSettings;

    #[test]
    fn map_sizes_read_as_one_number_or_two() {
        let wide = MapSize {
            width: 400,
            height: 300,
        };
        assert_eq!(parse_map_size("1024"), Ok(MapSize::square(1024)));
        assert_eq!(parse_map_size("400x300"), Ok(wide));
        for bad in ["", "x", "400x", "-1", "400x300x2", "1.5"] {
            let e = parse_map_size(bad).unwrap_err();
            assert!(
                e.contains("expected a side in texels like 1024"),
                "{bad}: {e}"
            );
        }
        let read = |t: &str| toml::from_str::<ShadowSettings>(t).map(|s| s.map_size);
        assert_eq!(read("map_size = 512").unwrap(), MapSize::square(512));
        assert_eq!(read("map_size = [400, 300]").unwrap(), wide);
        for bad in [
            "map_size = [400]",
            "map_size = [1, 2, 3]",
            "map_size = -4",
            "map_size = \"big\"",
        ] {
            let e = read(bad).unwrap_err().to_string();
            assert!(e.contains("map_size"), "{bad}: {e}");
        }
        // Written back as they were read; shown as the flag takes them.
        assert_eq!(serde_json::to_string(&wide).unwrap(), "[400,300]");
        assert_eq!(serde_json::to_string(&MapSize::square(64)).unwrap(), "64");
        assert_eq!(
            (wide.to_string(), MapSize::square(64).to_string()),
            ("400x300".into(), "64".into())
        );
        assert!(wide
            .square_side("cascades")
            .unwrap_err()
            .to_string()
            .contains("needs a square map"));
    }
}
