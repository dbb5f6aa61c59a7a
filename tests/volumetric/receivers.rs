//! Translucent receivers tested per vertex (`translucent_receivers = "vertex"`): a
//! translucent sheet under a translucent caster receives the light it lets through as it
//! does per pixel; the opaque receivers' tests stay per pixel, bit for bit; and where no item
//! is translucent, or no light's test can run per vertex, the setting says it does nothing.

use crate::common;

use std::path::Path;

use shadowmap::frame::Frame;
use shadowmap::scene::file::parse;
use shadowmap::settings::{Filter, ShadowSettings, TranslucentReceivers, Volumetric};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::Scene;

/// A floor lit from nearly overhead, a 6 x 6 translucent sheet (opacity 0.4) at y = 4.5
/// over all of it, above the camera (so it is not in view), and at y = 0 a 2 x 2 orange
/// sheet of opacity 0.5 that receives and casts nothing: all of it lies behind the big sheet
/// alone, where every technique is exact.
fn covered_sheet() -> Scene {
    let items = "\
         [[item]]\nname = \"cover\"\nmesh = \"plane\"\nposition = [0.0, 4.5, 0.0]\nscale = 3.0\n\
         colour = [1.0, 1.0, 1.0, 1.0]\nopacity = 0.4\n\
         [[item]]\nname = \"sheet\"\nmesh = \"plane\"\nposition = [0.0, 0.0, 0.0]\n\
         colour = [1.0, 0.5, 0.0, 1.0]\nopacity = 0.5\ncasts_shadows = false\n";
    let text = format!("{}{items}", common::OVERHEAD_FLOOR);
    parse(&text, Path::new("covered.toml"), None).unwrap_or_else(|e| panic!("{e}"))
}

use common::translucent_frame as frame;

/// The largest channel difference and the mean one (over every channel) between two frames.
fn difference(a: &Frame, b: &Frame) -> (u8, f64) {
    let pairs = a.colour.rgba.iter().zip(&b.colour.rgba);
    let d: Vec<u8> = pairs.map(|(x, y)| x.abs_diff(*y)).collect();
    let mean = d.iter().map(|v| f64::from(*v)).sum::<f64>() / d.len() as f64;
    (d.iter().copied().max().unwrap_or(0), mean)
}

#[test]
fn a_sheet_behind_a_translucent_caster_receives_the_same_light_per_vertex_as_per_pixel() {
    let mut scene = covered_sheet();
    // The middle of the frame shows the small sheet, over the floor.
    let green = |f: &Frame| f32::from(f.colour.rgba[(120 * 320 + 160) * 4 + 1]);
    let bare = frame(&mut scene, Volumetric::Off, TranslucentReceivers::Pixel);
    for volumetric in [Volumetric::Osm, Volumetric::Fom, Volumetric::Avsm] {
        let pixel = frame(&mut scene, volumetric, TranslucentReceivers::Pixel);
        let vertex = frame(&mut scene, volumetric, TranslucentReceivers::Vertex);
        let (max, mean) = difference(&pixel, &vertex);
        // Both take 0.6 of the light at every point of the sheet: the same to one step.
        assert!(
            max <= 1 && mean < 0.01,
            "{volumetric:?}: max {max}, mean {mean}"
        );
        // And it is the cover's shadow they take: darker than with the cover casting nothing.
        println!(
            "{volumetric:?}: max {max}, mean {mean}, green {} against {}",
            green(&vertex),
            green(&bare)
        );
        assert!(
            green(&vertex) < green(&bare) - 10.0,
            "{volumetric:?}: {} against {}",
            green(&vertex),
            green(&bare)
        );
    }
}

#[test]
fn per_vertex_receivers_leave_every_opaque_receiver_s_test_as_it_was() {
    let mut smoke = common::frozen("smoke");
    for volumetric in [
        Volumetric::Off,
        Volumetric::Osm,
        Volumetric::Fom,
        Volumetric::Avsm,
    ] {
        let pixel = frame(&mut smoke, volumetric, TranslucentReceivers::Pixel);
        let vertex = frame(&mut smoke, volumetric, TranslucentReceivers::Vertex);
        // The visibility output holds the opaque receivers' tests (translucent items keep
        // the receivers under them): the same floats.
        assert_eq!(pixel.visibility, vertex.visibility, "{volumetric:?}");
        // The puffs and the glass themselves differ.
        assert!(pixel.colour.rgba != vertex.colour.rgba, "{volumetric:?}");
    }
    let mut dummy = common::frozen("dummy");
    let pixel = frame(&mut dummy, Volumetric::Off, TranslucentReceivers::Pixel);
    let vertex = frame(&mut dummy, Volumetric::Off, TranslucentReceivers::Vertex);
    assert!(pixel.colour.rgba == vertex.colour.rgba);
}

fn idle_why(scene: &Scene, settings: &ShadowSettings) -> Option<String> {
    let plan = ShadowPlan::decide(&scene.lights, settings);
    let idle = plan.idle_in(scene);
    let found = idle
        .into_iter()
        .find(|i| i.setting == "translucent_receivers");
    found.map(|i| i.why)
}

#[test]
fn translucent_receivers_says_where_it_does_nothing() {
    let vertex = |scene: &Scene, filter| ShadowSettings {
        translucent_receivers: TranslucentReceivers::Vertex,
        filter,
        ..scene.shadow
    };
    let dummy = common::frozen("dummy");
    assert_eq!(
        idle_why(&dummy, &vertex(&dummy, Filter::Pcf3x3)).as_deref(),
        Some(
            "the scene has no translucent item (opacity below 1): every receiver is opaque and \
             tested per pixel"
        )
    );
    let smoke = common::frozen("smoke");
    assert_eq!(idle_why(&smoke, &vertex(&smoke, Filter::Pcf3x3)), None);
    assert_eq!(idle_why(&smoke, &vertex(&smoke, Filter::Vsm)), None);
    assert_eq!(
        idle_why(&smoke, &vertex(&smoke, Filter::Pcss)).as_deref(),
        Some(
            "no light's test can run per vertex: only a 2D depth or moment map's test runs per \
             vertex, and not one that reads the pixel itself (pcss, poisson-rotated, vssm, \
             msm-soft: its screen derivatives or its position)"
        )
    );
}

#[test]
fn every_filter_whose_test_runs_per_vertex_compiles_in_the_vertex_shader() {
    let mut scene = covered_sheet();
    let filters = Filter::ALL
        .into_iter()
        .chain(Filter::SOFT)
        .chain(Filter::MOMENTS);
    let mut per_vertex = 0;
    for filter in filters {
        scene.shadow.filter = filter;
        let settings = ShadowSettings {
            volumetric: Volumetric::Osm,
            translucent_receivers: TranslucentReceivers::Vertex,
            ..scene.shadow
        };
        if filter.moments() || idle_why(&scene, &settings).is_some() {
            continue;
        }
        per_vertex += 1;
        // The soft filters' library is a vertex shader's too: it compiles, and the sheet
        // takes the cover's light per vertex as per pixel.
        let pixel = frame(&mut scene, Volumetric::Osm, TranslucentReceivers::Pixel);
        let vertex = frame(&mut scene, Volumetric::Osm, TranslucentReceivers::Vertex);
        let (max, mean) = difference(&pixel, &vertex);
        assert!(
            max <= 2 && mean < 0.05,
            "{}: max {max}, mean {mean}",
            filter.name()
        );
    }
    assert!(per_vertex >= 7, "{per_vertex} filters ran per vertex");
}
