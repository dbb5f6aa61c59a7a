//! A shadow map too large for the driver, refused before anything is drawn with how much
//! memory it needs and what the driver takes. A driver bounds each side
//! (`GL_MAX_TEXTURE_SIZE`) but may bound one texture's bytes lower still (Mesa's llvmpipe:
//! 1 GiB), which no query tells: so a large map is made once, and put back, before the
//! renderer asks for it, and where the driver refuses it the refusal says why.

use shadowmap::engine::Gl;
use shadowmap::settings::MapSize;
use shadowmap::shadows::kind::{Storage, DEPTH_TEXEL_BYTES};
use shadowmap::shadows::plan::{LightPlan, ShadowPlan};
use shadowmap::shadows::ShadowKind;
use shadowmap::{Error, Result, ShadowSettings};

/// Maps up to this size are not tried first: every driver of OpenGL 3.3 makes them, and
/// trying would cost every run a second allocation.
const TRIED_ABOVE_BYTES: u64 = 256 << 20;

/// The smallest side a smaller map is suggested at.
const SMALLEST_SUGGESTED: u32 = 256;

/// The storage a light of `kind` gets under `s`; `None` for a light with no map.
pub fn storage(kind: ShadowKind, s: &ShadowSettings) -> Option<Storage> {
    (kind.facts().storage)(s)
}

/// Bytes as the message says them: "4 GiB", "1.5 GiB", "512 MiB".
pub fn bytes_text(bytes: u64) -> String {
    let (value, unit) = match bytes >= 1 << 30 {
        true => (bytes as f64 / f64::from(1u32 << 30), "GiB"),
        false => (bytes as f64 / f64::from(1u32 << 20), "MiB"),
    };
    let text = format!("{value:.1}");
    format!("{} {unit}", text.trim_end_matches(".0"))
}

/// Makes every light's map that is over [`TRIED_ABOVE_BYTES`] once and puts it back; the
/// first the driver refuses is refused here, naming its settings ("shadow.NAME"), its
/// bytes, the driver's side limit and a smaller size the driver does make.
pub fn check(gl: &Gl, plan: &ShadowPlan, max_texture_size: u32) -> Result<()> {
    for (i, light) in plan.lights.iter().enumerate() {
        let Some(need) = storage(light.kind, &light.settings) else {
            continue;
        };
        if need.bytes <= TRIED_ABOVE_BYTES {
            continue;
        }
        if let Err(e) = light.kind.create(gl, &light.settings) {
            return Err(refusal(gl, i, light, &need, max_texture_size, &e));
        }
    }
    Ok(())
}

/// The message for light `i`'s map that the driver would not make (`e`: its own words).
fn refusal(
    gl: &Gl,
    i: usize,
    light: &LightPlan,
    need: &Storage,
    max_texture_size: u32,
    e: &Error,
) -> Error {
    let s = &light.settings;
    let smaller = match smaller_that_fits(gl, light) {
        Some((size, bytes)) => format!(
            "expected a smaller map, like shadow.map_size = {size} ({}, which the driver makes)",
            bytes_text(bytes)
        ),
        None => "expected a smaller map".to_string(),
    };
    Error::Invalid(format!(
        "shadow.map_size = {}: light {i}'s map ({}) needs {} of GPU memory \
         ({DEPTH_TEXEL_BYTES} bytes a depth texel), which the driver does not give, though \
         each side is within its GL_MAX_TEXTURE_SIZE of {max_texture_size}: {smaller} (the \
         driver: {e})",
        s.map_size,
        need.what,
        bytes_text(need.bytes)
    ))
}

/// The largest map the driver makes for `light`, with its bytes: the longer side a power
/// of two below the given one, halved until the driver makes it, the shape kept; `None` if
/// none down to [`SMALLEST_SUGGESTED`].
fn smaller_that_fits(gl: &Gl, light: &LightPlan) -> Option<(MapSize, u64)> {
    let size = light.settings.map_size;
    let longest = size.max_side();
    let mut top = longest.next_power_of_two() / 2;
    loop {
        if top < SMALLEST_SUGGESTED {
            return None;
        }
        let side = |n: u32| ((u64::from(n) * u64::from(top)) / u64::from(longest)).max(1) as u32;
        let smaller = MapSize {
            width: side(size.width),
            height: side(size.height),
        };
        let s = ShadowSettings {
            map_size: smaller,
            ..light.settings
        };
        if light.kind.create(gl, &s).is_ok() {
            return storage(light.kind, &s).map(|need| (smaller, need.bytes));
        }
        top /= 2;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shadowmap::settings::Filter;

    #[test]
    fn storage_counts_every_layer_and_face() {
        let s = ShadowSettings {
            map_size: MapSize::square(16384),
            cascades: 4,
            ..ShadowSettings::default()
        };
        let cascades = storage(ShadowKind::Cascades, &s).unwrap();
        assert_eq!(cascades.bytes, 4 << 30);
        assert_eq!(bytes_text(cascades.bytes), "4 GiB");
        assert_eq!(cascades.what, "shadow.cascades = 4 layers of 16384 x 16384");
        let cube = storage(ShadowKind::Cube, &s).unwrap();
        assert_eq!(bytes_text(cube.bytes), "6 GiB");
        let one = ShadowSettings {
            map_size: MapSize::square(8192),
            ..s
        };
        assert_eq!(
            bytes_text(storage(ShadowKind::Map, &one).unwrap().bytes),
            "256 MiB"
        );
        let cube = storage(ShadowKind::Cube, &one).unwrap();
        assert_eq!(bytes_text(cube.bytes), "1.5 GiB");
        let vsm = ShadowSettings {
            filter: Filter::Vsm,
            ..one
        };
        // Two RG32F targets and a depth buffer: 20 bytes a texel.
        assert_eq!(storage(ShadowKind::Moments, &vsm).unwrap().bytes, 20 << 26);
        assert_eq!(storage(ShadowKind::Volume, &s), None);
    }
}
