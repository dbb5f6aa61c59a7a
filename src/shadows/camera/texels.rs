//! Where a world box lands in a light's map, in whole texels: what a patch of a cached map
//! redraws and what a translucent map's lookup reads.

use glam::{DMat4, DVec3};

use super::fitted::corners;
use crate::engine::PixelRect;
use crate::settings::MapSize;
use crate::shadows::ShadowView;

/// A rectangle of map texels, `x0..x1` by `y0..y1` (half-open) from the bottom-left corner,
/// GL's way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TexelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl TexelRect {
    /// The whole of a `size` map.
    pub fn whole(size: MapSize) -> TexelRect {
        TexelRect {
            x0: 0,
            y0: 0,
            x1: size.width,
            y1: size.height,
        }
    }

    pub fn is_empty(self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    pub fn texels(self) -> u64 {
        match self.is_empty() {
            true => 0,
            false => u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0),
        }
    }

    /// The smallest rectangle holding both (an empty one adds nothing).
    pub fn union(self, other: TexelRect) -> TexelRect {
        match (self.is_empty(), other.is_empty()) {
            (true, _) => other,
            (_, true) => self,
            _ => TexelRect {
                x0: self.x0.min(other.x0),
                y0: self.y0.min(other.y0),
                x1: self.x1.max(other.x1),
                y1: self.y1.max(other.y1),
            },
        }
    }

    /// Grown by `by` texels on every side, clipped to a `size` map (empty stays empty).
    pub fn grown(self, by: u32, size: MapSize) -> TexelRect {
        if self.is_empty() {
            return self;
        }
        TexelRect {
            x0: self.x0.saturating_sub(by),
            y0: self.y0.saturating_sub(by),
            x1: self.x1.saturating_add(by).min(size.width),
            y1: self.y1.saturating_add(by).min(size.height),
        }
    }

    /// Whether they share a texel.
    pub fn overlaps(self, other: TexelRect) -> bool {
        !self.is_empty()
            && !other.is_empty()
            && self.x0 < other.x1
            && other.x0 < self.x1
            && self.y0 < other.y1
            && other.y0 < self.y1
    }

    pub fn pixels(self) -> PixelRect {
        PixelRect {
            x: self.x0,
            y: self.y0,
            width: self.x1.saturating_sub(self.x0),
            height: self.y1.saturating_sub(self.y0),
        }
    }
}

/// The texels of a `size` map seen through `view` that the world box `lo..hi` can cover:
/// its corners' light-space rectangle widened to whole texels, clipped to the map. A texel
/// is drawn when its centre is inside a triangle, so this holds every texel the box's
/// contents can write with half a texel to spare. A box reaching behind a perspective
/// light's eye (or not a number) can cover the whole map.
pub fn footprint(view: &ShadowView, size: MapSize, lo: DVec3, hi: DVec3) -> TexelRect {
    let clip = view.projection.as_dmat4() * view.view64;
    footprint_in(clip, size, lo, hi)
}

fn footprint_in(clip: DMat4, size: MapSize, lo: DVec3, hi: DVec3) -> TexelRect {
    let (w, h) = (f64::from(size.width), f64::from(size.height));
    let mut min = glam::DVec2::INFINITY;
    let mut max = glam::DVec2::NEG_INFINITY;
    for c in corners(lo, hi) {
        let p = clip * c.extend(1.0);
        if p.w <= 0.0 || !p.is_finite() {
            return TexelRect::whole(size);
        }
        // Normalised device coordinates to the map's texels (the viewport is the map).
        let t = glam::DVec2::new((p.x / p.w + 1.0) * 0.5 * w, (p.y / p.w + 1.0) * 0.5 * h);
        min = min.min(t);
        max = max.max(t);
    }
    // Clamped before the cast, so a box far off the map is an empty rectangle at its edge.
    let texel = |v: f64, side: f64| v.clamp(0.0, side) as u32;
    TexelRect {
        x0: texel(min.x.floor(), w),
        y0: texel(min.y.floor(), h),
        x1: texel(max.x.ceil(), w),
        y1: texel(max.y.ceil(), h),
    }
}
