//! A translucent item is one of the crossings its light's translucent map holds, at its own
//! depth. Read there, the lookup's four texels split on its own step and it shades itself
//! in specks, as a depth map's surface does without a bias; the lookup reads a little
//! nearer the light (`self_shadow_lift`). AVSM stores each crossing exactly, so a tilted
//! sheet alone under the light must then get all of it, as with `volumetric = "off"`.

use crate::common;

use std::path::Path;

use shadowmap::scene::file::parse;
use shadowmap::settings::{TranslucentReceivers, Volumetric};
use shadowmap::shadows::volumetric::self_shadow_lift;
use shadowmap::Scene;

/// A sheet of opacity 0.5 tilted 12 degrees under a light from nearly overhead, over
/// nothing: every pixel that is not the clear colour is the sheet.
fn tilted_sheet() -> Scene {
    let text = "size = [320, 240]\nclear_colour = [0.0, 0.0, 0.0]\n\
         [camera]\nposition = [0.0, 4.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\
         [light]\ndirection = [0.15, 1.0, 0.1]\nshadow_pos_mult = 8.0\n\
         ortho = { left = -5.0, right = 5.0, bottom = -5.0, top = 5.0, near = -1.0, far = 12.0 }\n\
         [shadow]\nlight_view = \"look-at\"\nbias = 0.005\n\
         [[item]]\nname = \"sheet\"\nmesh = \"plane\"\nscale = [1.5, 1.0, 1.0]\n\
         rotation = [0.0, 0.0, 12.0]\ncolour = [1.0, 0.7, 0.2, 1.0]\nopacity = 0.5\n";
    parse(text, Path::new("sheet.toml"), None).unwrap_or_else(|e| panic!("{e}"))
}

use common::translucent_frame as frame;

#[test]
fn a_tilted_sheet_alone_does_not_shade_itself_under_avsm() {
    let mut scene = tilted_sheet();
    let lit = frame(&mut scene, Volumetric::Off, TranslucentReceivers::Pixel);
    let sheet = lit
        .colour
        .rgba
        .chunks(4)
        .filter(|p| p[..3] != [0; 3])
        .count();
    assert!(sheet > 5_000, "{sheet} pixels of the sheet");
    for receivers in [TranslucentReceivers::Pixel, TranslucentReceivers::Vertex] {
        let avsm = frame(&mut scene, Volumetric::Avsm, receivers);
        let pixels = lit.colour.rgba.chunks(4).zip(avsm.colour.rgba.chunks(4));
        let darker = pixels
            .filter(|(a, b)| a.iter().zip(*b).any(|(a, b)| a.abs_diff(*b) > 1))
            .count();
        assert_eq!(
            darker, 0,
            "{receivers:?}: {darker} of {sheet} pixels shaded"
        );
    }
}

#[test]
fn the_lift_is_two_of_the_translucent_maps_texels() {
    let size = |n| shadowmap::settings::MapSize::square(n);
    assert_eq!(self_shadow_lift(0.01, size(1024), size(1024)), 0.02);
    assert_eq!(self_shadow_lift(0.01, size(1024), size(256)), 0.08);
}
