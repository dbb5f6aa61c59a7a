//! Scene files are TOML as TOML: a table, an inline table and dotted keys say the same
//! thing, and load to the same scene and the same picture.

use crate::common;

use std::path::Path;

use shadowmap::scene::file::parse;
use shadowmap::scene::Light;
use shadowmap::Scene;

/// One scene (a camera, a spot light with its own shadow table, two items) written with
/// `[tables]`.
const TABLES: &str = r#"
[camera]
position = [0.0, 3.0, 7.0]
target = [0.0, 0.0, 0.0]
fov = 50.0

[light]
kind = "spot"
position = [2.0, 5.0, 2.0]
target = [0.0, 0.0, 0.0]
fov = 60.0
near = 1.0
far = 20.0

[light.shadow]
filter = "pcf5x5"
bias = 0.002

[[item]]
mesh = "plane"
scale = 6.0

[[item]]
name = "cube"
mesh = "cube"
position = [0.0, 0.5, 0.0]
colour = [0.8, 0.3, 0.2, 1.0]
"#;

/// The same with inline tables.
const INLINE: &str = r#"
camera = { position = [0.0, 3.0, 7.0], target = [0.0, 0.0, 0.0], fov = 50.0 }
light = { kind = "spot", position = [2.0, 5.0, 2.0], target = [0.0, 0.0, 0.0], fov = 60.0, near = 1.0, far = 20.0, shadow = { filter = "pcf5x5", bias = 0.002 } }
item = [
    { mesh = "plane", scale = 6.0 },
    { name = "cube", mesh = "cube", position = [0.0, 0.5, 0.0], colour = [0.8, 0.3, 0.2, 1.0] },
]
"#;

/// The same with dotted keys.
const DOTTED: &str = r#"
camera.position = [0.0, 3.0, 7.0]
camera.target = [0.0, 0.0, 0.0]
camera.fov = 50.0
light.kind = "spot"
light.position = [2.0, 5.0, 2.0]
light.target = [0.0, 0.0, 0.0]
light.fov = 60.0
light.near = 1.0
light.far = 20.0
light.shadow.filter = "pcf5x5"
light.shadow.bias = 0.002

[[item]]
mesh = "plane"
scale = 6.0

[[item]]
name = "cube"
mesh = "cube"
position = [0.0, 0.5, 0.0]
colour = [0.8, 0.3, 0.2, 1.0]
"#;

fn load(text: &str) -> Scene {
    parse(text, Path::new("three-ways.toml"), None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn a_table_an_inline_table_and_dotted_keys_load_the_same_scene_and_frame() {
    let scenes = [TABLES, INLINE, DOTTED].map(load);
    // What was written, not the defaults.
    let first = &scenes[0];
    assert_eq!(first.camera.fov, 50.0);
    match &first.lights[..] {
        [Light::Spot(spot)] => assert_eq!((spot.fov, spot.far), (60.0, 20.0)),
        other => panic!("one spot light expected: {other:?}"),
    }
    assert_eq!(first.lights[0].shadow_patch().bias, Some(0.002));
    assert_eq!(first.items.len(), 2);
    assert_eq!(first.items[1].name, "cube");
    // Every value alike (Debug prints every float exactly).
    let shown = scenes.each_ref().map(|s| format!("{s:?}"));
    assert_eq!(shown[0], shown[1], "inline tables differ from tables");
    assert_eq!(shown[0], shown[2], "dotted keys differ from tables");

    let ctx = common::context();
    let frames = scenes.map(|mut scene| {
        let settings = scene.shadow;
        common::render(&ctx, &mut scene, &settings, 160, 90).colour
    });
    // The spot light lights the floor and the cube casts a shadow: not one flat colour.
    let distinct: std::collections::HashSet<&[u8]> = frames[0].rgba.chunks(4).collect();
    assert!(distinct.len() > 20, "{} colours", distinct.len());
    assert!(frames[0] == frames[1], "inline tables render differently");
    assert!(frames[0] == frames[2], "dotted keys render differently");
}

/// `depth_lookup` is a `[shadow]` key like the others (and a light's own); a value it does
/// not know is refused with the file, the field, the line and column, and the two it takes.
#[test]
fn the_shadow_table_takes_depth_lookup_and_refuses_a_bad_one_where_it_is() {
    use shadowmap::settings::DepthLookup;
    let scene = |shadow: &str| {
        format!("[light]\nangle = 45.0\n\n[shadow]\nfilter = \"pcf4x4-weighted\"\n{shadow}\n\n[[item]]\nmesh = \"cube\"\n")
    };
    let read = |text: &str| parse(text, Path::new("lookup.toml"), None);
    let linear = read(&scene("depth_lookup = \"linear\"")).unwrap();
    assert_eq!(linear.shadow.depth_lookup, DepthLookup::Linear);
    let default = read(&scene("")).unwrap();
    assert_eq!(default.shadow.depth_lookup, DepthLookup::Nearest);
    let own = read(
        "[light]\nangle = 45.0\nshadow.depth_lookup = \"linear\"\n\n[[item]]\nmesh = \"cube\"\n",
    )
    .unwrap();
    assert_eq!(
        own.lights[0].shadow_patch().depth_lookup,
        Some(DepthLookup::Linear)
    );
    let e = read(&scene("depth_lookup = \"bilinear\""))
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "lookup.toml: shadow.depth_lookup: line 6, column 16: unknown value `bilinear`: did \
         you mean `linear`?"
    );
}
