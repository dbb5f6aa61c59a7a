//! The texture units of the scene program: the material's, each light's map, the cached
//! shadow mask, and each light's translucent and resolved maps after them.

use crate::scene::MAX_LIGHTS;

/// The material's texture unit; light `i`'s shadow map is on unit `1 + i`.
pub const MATERIAL_UNIT: u32 = 0;

/// The texture unit of the cached shadow mask (after every light's map).
pub const MASK_UNIT: u32 = 1 + MAX_LIGHTS as u32;

/// The texture unit of light `index`'s shadow map.
pub fn texture_unit(index: usize) -> u32 {
    1 + index as u32
}

/// The texture unit of light `index`'s translucent map (after the mask).
pub fn volumetric_unit(index: usize) -> u32 {
    MASK_UNIT + 1 + index as u32
}

/// The texture unit of light `index`'s resolved map (after the translucent maps).
pub fn resolved_unit(index: usize) -> u32 {
    volumetric_unit(MAX_LIGHTS) + index as u32
}
