//! The loader's messages: each names its field and says what the field takes.

use super::*;
use crate::scene::{Camera, Light};

const LIGHT: &str = "[light]\nangle = 45.0\n";

/// The error for `text` as a scene file in /tmp: (its field, its whole message).
fn fails(text: &str) -> (Option<String>, String) {
    match parse(text, Path::new("s.toml"), Some(Path::new("/tmp"))) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => (e.field().map(String::from), e.to_string()),
    }
}

/// Asserts the error names `field` and its message contains `fragment`.
fn refuses(text: &str, field: &str, fragment: &str) {
    let (f, message) = fails(text);
    assert_eq!(f.as_deref(), Some(field), "{message}");
    assert!(
        message.starts_with(&format!("s.toml: {field}: ")),
        "{message}"
    );
    assert!(message.contains(fragment), "{message}\n  lacks: {fragment}");
}

#[test]
fn a_lights_size_is_read_and_checked_for_its_kind() {
    let sun = parse(
        "[light]\nangle = 45.0\nsize = 0.53\n",
        Path::new("s.toml"),
        None,
    )
    .unwrap();
    assert_eq!(sun.lights[0].size(), 0.53);
    refuses(
        "[light]\nangle = 45.0\nsize = 90.0\n",
        "light.size",
        "90: expected an angular diameter in degrees (the sun: 0.53) under 90",
    );
    refuses(
        "[light]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\nsize = -0.5\n",
        "light.size",
        "-0.5: expected a radius in world units >= 0 and under 1000 (0 = a point)",
    );
    refuses(
        "[light]\nangle = 45.0\n[steps]\nlight_size = 120.0\n",
        "steps.light_size",
        "120: expected an angular diameter in degrees",
    );
    refuses(
        "[light]\nangle = 45.0\n[steps]\nlist = \"book\"\n",
        "steps.list",
        "unknown variant `book`, expected one of `chapters`, `playground`, `volumetric`",
    );
}

#[test]
fn every_built_in_scene_loads() {
    for name in Scene::builtin_names() {
        let scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            !scene.lights.is_empty() && !scene.items.is_empty(),
            "{name}"
        );
    }
    let three = Scene::load("three-lights").unwrap();
    let kinds: Vec<&str> = three
        .lights
        .iter()
        .map(|l| match l {
            Light::Directional(_) => "directional",
            Light::Spot(_) => "spot",
            Light::Point(_) => "point",
        })
        .collect();
    assert_eq!(kinds, ["directional", "spot", "point", "point"]);
    // No `kind` is a directional light, in [light] and in [[lights]] alike.
    for text in [LIGHT, "[[lights]]\nangle = 45.0\n"] {
        let s = parse(text, Path::new("s.toml"), None).unwrap();
        assert!(matches!(s.lights[..], [Light::Directional(_)]), "{text}");
    }
}

#[test]
fn a_camera_target_becomes_the_books_angles() {
    let text = format!("{LIGHT}[camera]\nposition = [0.0, 4.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n");
    let s = parse(&text, Path::new("s.toml"), None).unwrap();
    let want = Camera::look_at(Vec3::new(0.0, 4.0, 9.0), Vec3::ZERO).unwrap();
    assert_eq!(s.camera.rotation, want.rotation);
    // Looking down at the origin from above and behind: pitch down, no yaw, no roll.
    assert!((s.camera.rotation.x - (4.0f32 / 9.0).atan().to_degrees()).abs() < 1e-4);
    assert_eq!((s.camera.rotation.y, s.camera.rotation.z), (0.0, 0.0));
    refuses(
        &format!("{LIGHT}[camera]\nrotation = [10.0, 0.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n"),
        "camera",
        "rotation and target are both given",
    );
    refuses(
        &format!("{LIGHT}[camera]\nposition = [1.0, 2.0, 3.0]\ntarget = [1.0, 2.0, 3.0]\n"),
        "camera.target",
        "the camera's own position",
    );
    refuses(
        &format!("{LIGHT}[camera]\ntarget = [1.0, 2.0]\n"),
        "camera.target",
        "expected exactly 3 numbers",
    );
}

#[test]
fn arrays_of_the_wrong_length_are_refused() {
    let exactly = |n: usize, k: usize| format!("{n} values given: expected exactly {k} numbers");
    refuses(
        &format!("size = [64, 48, 7]\n{LIGHT}"),
        "size",
        &exactly(3, 2),
    );
    refuses(
        &format!("{LIGHT}[camera]\nposition = [1.0, 2.0, 3.0, 4.0]\n"),
        "camera.position",
        &format!("line 4, column 12: {}", exactly(4, 3)),
    );
    refuses(
        &format!("clear_colour = [0.0, 0.0, 0.0, 0.0, 1.0]\n{LIGHT}"),
        "clear_colour",
        &exactly(5, 3),
    );
    refuses(
        &format!("{LIGHT}colour = [1.0, 1.0, 1.0, 1.0]\n"),
        "light.colour",
        &exactly(4, 3),
    );
    refuses(
        &format!("{LIGHT}[shadow]\npolygon_offset = [1.0, 2.0, 3.0]\n"),
        "shadow.polygon_offset",
        &format!("line 4, column 18: {} [factor, units]", exactly(3, 2)),
    );
    refuses(
        &format!("{LIGHT}[[item]]\nname = \"ball\"\nmesh = \"sphere\"\ndetail = [8, 8, 8]\n"),
        "item[0] (\"ball\").detail",
        &exactly(3, 2),
    );
    refuses(
        &format!(
            "{LIGHT}[[item]]\nmesh = \"cube\"\n\
             scatter = {{ count = 2, area = [0.0, 1.0, 0.0, 1.0, 5.0] }}\n"
        ),
        "item[0].scatter.area",
        &exactly(5, 4),
    );
    refuses(
        &format!("{LIGHT}[[item]]\nmesh = \"cube\"\ncolour = [1.0, 1.0, 1.0, 1.0, 1.0]\n"),
        "item[0].colour",
        &exactly(5, 4),
    );
    refuses(
        &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nscale = [1.0, 2.0, 3.0, 4.0]\n"),
        "item[0].scale",
        &exactly(4, 3),
    );
    refuses(
        &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nposition = [1.0]\n"),
        "item[0].position",
        "1 value given: expected exactly 3 numbers",
    );
}

#[test]
fn numbers_no_field_takes_are_refused_anywhere() {
    refuses(
        &format!("{LIGHT}[steps]\nbias = nan\n"),
        "steps.bias",
        "line 4, column 8: NaN is not a finite number",
    );
    refuses(
        &format!("{LIGHT}[shadow]\nperspective_fov = -nan\n"),
        "shadow.perspective_fov",
        "line 4, column 19: NaN is not a finite number",
    );
    refuses(
        &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nspin = [0.0, inf, 0.0]\n"),
        "item[0].spin",
        "line 5, column 14: inf is not a finite number",
    );
    refuses(
        &format!("{LIGHT}[camera]\nfar = 1e39\n"),
        "camera.far",
        "line 4, column 7: 1e39 is too large: expected a number within +-3.4028235e38 (32-bit \
         floats)",
    );
    refuses(
        &format!("{LIGHT}[steps]\nbias = -0.5\n"),
        "steps.bias",
        "-0.5: expected 0 to 1",
    );
}

#[test]
fn negative_light_and_overflowing_boxes_are_refused() {
    refuses(
        &format!("ambient = [-0.1, 0.0, 0.0]\n{LIGHT}"),
        "ambient",
        "[-0.1, 0.0, 0.0]: expected numbers >= 0",
    );
    refuses(
        &format!("specular_power = -2.0\n{LIGHT}"),
        "specular_power",
        "-2: expected a number > 0",
    );
    refuses(
        &format!("{LIGHT}intensity = -1.0\n"),
        "light.intensity",
        "-1: expected a number >= 0",
    );
    refuses(
        "[[lights]]\nangle = 1.0\n[[lights]]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
         colour = [1.0, -1.0, 1.0]\n",
        "lights[1].colour",
        "[1.0, -1.0, 1.0]: expected numbers >= 0",
    );
    refuses(
        "[light]\nangle = 45.0\northo = { left = -3e38, right = 3e38, bottom = -1.0, \
         top = 1.0, near = 0.0, far = 1.0 }\n",
        "light.ortho",
        "right - left overflows 32-bit floats",
    );
    refuses(
        &format!(
            "{LIGHT}[[item]]\nmesh = \"cube\"\n\
             scatter = {{ count = 2, area = [-3e38, 3e38, 0.0, 1.0] }}\n"
        ),
        "item[0].scatter.area",
        "the area's width overflows 32-bit floats",
    );
}

#[test]
fn messages_say_what_a_field_takes() {
    let cube =
        format!("{LIGHT}[[item]]\nmesh = \"cube\"\n[[item]]\nname = \"cube\"\nmesh = \"cube\"\n");
    refuses(
        &format!("{cube}scale = \"big\"\n"),
        "item[1] (\"cube\").scale",
        "line 8, column 9: invalid type: string \"big\", expected a number > 0 or three \
         of them, [x, y, z]",
    );
    refuses(
        &format!("{cube}scale = -1.0\n"),
        "item[1] (\"cube\").scale",
        "-1: expected a finite number > 0",
    );
    refuses(
        &format!("{cube}reflectance = \"x\"\n"),
        "item[1] (\"cube\").reflectance",
        "invalid type: string \"x\", expected a number",
    );
    refuses(
        &format!("size = [1.5, 2]\n{LIGHT}"),
        "size",
        "expected a whole number from 0 to 4294967295",
    );
    refuses(
        &format!("{LIGHT}[[item]]\nmesh = \"cueb\"\n"),
        "item[0].mesh",
        "'cueb' is not a built-in mesh (cube, plane, sphere, terrain), and there is no \
         OBJ file at /tmp/cueb",
    );
    refuses(
        &format!("{LIGHT}[[item]]\nname = \"x\"\nposition = [0.0, 0.0, 0.0]\n"),
        "item[0] (\"x\").mesh",
        "line 3, column 1: missing field `mesh`",
    );
}

#[test]
fn each_light_kind_takes_its_own_fields() {
    refuses(
        "[[lights]]\nangle = 45.0\n[[lights]]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
         fov = 30.0\n",
        "lights[1].fov",
        "line 6, column 1: not used by a point light; it takes kind, colour, intensity, \
         position, near, far, oscillate, casts_shadows, size, shadow",
    );
    refuses(
        "[light]\nangle = 45.0\nshadow_pos_multi = 5.0\n",
        "light.shadow_pos_multi",
        "line 3, column 1: unknown field `shadow_pos_multi`: did you mean `shadow_pos_mult`?",
    );
    refuses(
        "[light]\nangle = 45.0\nbrightness = 5.0\n",
        "light.brightness",
        "line 3, column 1: unknown field; a directional light takes kind, colour",
    );
    refuses(
        "[light]\nkind = \"spot\"\nposition = [0.0, 1.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
         fov = 30.0\nfar = 5.0\n",
        "light.near",
        "a spot light needs it (the table at line 1)",
    );
    refuses(
        "[light]\nkind = \"spott\"\n",
        "light.kind",
        "line 2, column 8: \"spott\": expected \"directional\" (the default), \"spot\" or \"point\"",
    );
    refuses(
        "[light]\nangle = \"high\"\n",
        "light.angle",
        "line 2, column 9: invalid type: string \"high\", expected a number",
    );
    refuses(
        "[light]\nangle = 45.0\northo = { right = 1.0, bottom = -1.0, top = 1.0, near = 0.0, \
         far = 1.0 }\n",
        "light.ortho.left",
        "missing field `left`",
    );
    refuses(
        "[light]\nangle = 45.0\ndirection = [0.0, 1.0, 0.0]\n",
        "light",
        "expected exactly one of `angle`",
    );
}

#[test]
fn light_fields_are_what_serde_derives() {
    assert_eq!(
        build::light_fields(LightKind::Point),
        [
            "kind",
            "colour",
            "intensity",
            "position",
            "near",
            "far",
            "oscillate",
            "casts_shadows",
            "size",
            "shadow"
        ]
    );
    assert!(build::light_fields(LightKind::Spot)
        .iter()
        .any(|f| f == "target"));
    assert!(!build::light_fields(LightKind::Directional)
        .iter()
        .any(|f| f == "target"));
}

#[test]
fn fields_are_named_down_to_the_element_and_its_name() {
    refuses(
        "[[lights]]\nangle = 45.0\n[[lights]]\nangle = 30.0\n\
         shadow = { filter = \"pcf5x5\", polygon_offset = [1.0] }\n",
        "lights[1].shadow.polygon_offset",
        "line 5, column 48: 1 value given: expected exactly 2 numbers [factor, units]",
    );
    refuses(
        &format!(
            "{LIGHT}[[item]]\nmesh = \"x\"\n[[item]]\nname = \"b\"\nmesh = \"cube\"\nshiny = 1\n"
        ),
        "item[1] (\"b\").shiny",
        "line 8, column 1: unknown field `shiny`, expected one of `name`, `mesh`",
    );
    refuses(
        &format!(
            "{LIGHT}ortho = {{ left = -1.0, right = 1.0, bottom = -1.0, top = 1.0, near = 0.0, \
             far = 1.0, depth = 3.0 }}\n"
        ),
        "light.ortho.depth",
        "line 3, column 86: unknown field `depth`",
    );
    refuses(
        "camera.fov = \"wide\"\n[light]\nangle = 45.0\n",
        "camera.fov",
        "line 1, column 14: invalid type: string \"wide\", expected a number",
    );
    refuses(
        "light = 5\n",
        "light",
        "line 1, column 9: invalid type: integer `5`, expected a table",
    );
    let (field, message) = fails(&format!("{LIGHT}angle = 3.0\n"));
    assert_eq!(field, None);
    assert_eq!(
        message,
        "s.toml: line 3, column 1, at `angle`: duplicate key"
    );
}

#[test]
fn opacity_makes_an_item_translucent_and_is_checked() {
    let text = format!(
        "{LIGHT}[[item]]\nmesh = \"plane\"\nopacity = 0.25\n\
         [[item]]\nmesh = \"cube\"\nopacity = 0.5\ncasts_shadows = false\n[[item]]\nmesh = \"cube\"\n"
    );
    let scene = parse(&text, Path::new("s.toml"), None).unwrap();
    let [sheet, quiet, solid] = [0, 1, 2].map(|i| &scene.items[i]);
    assert_eq!(sheet.opacity, 0.25);
    // A translucent item stays out of the depth map; its technique casts it.
    assert!(sheet.is_translucent() && !sheet.casts_shadows && sheet.casts_translucent);
    assert!(!quiet.casts_shadows && !quiet.casts_translucent);
    assert!(!solid.is_translucent() && solid.casts_shadows && !solid.casts_translucent);
    for bad in ["0.0", "1.5", "-0.25"] {
        let (field, message) = fails(&format!(
            "{LIGHT}[[item]]\nname = \"glass\"\nmesh = \"plane\"\nopacity = {bad}\n"
        ));
        assert_eq!(field.as_deref(), Some("item[0] (\"glass\").opacity"));
        let shown = bad.parse::<f32>().unwrap();
        assert_eq!(
            message,
            format!(
                "s.toml: item[0] (\"glass\").opacity: {shown}: expected a number above 0 and \
                 at most 1 (1 = opaque)"
            )
        );
    }
}

#[test]
fn a_scatter_with_a_height_fills_a_volume_and_moves_no_copy_across() {
    let scatter = |height: &str| {
        let text = format!(
            "{LIGHT}[[item]]\nmesh = \"sphere\"\nposition = [0.0, 2.0, 0.0]\n\
             scatter = {{ count = 50, seed = 3, area = [-1.0, 1.0, -1.0, 1.0]{height} }}\n"
        );
        parse(&text, Path::new("s.toml"), None).unwrap().items
    };
    let flat = scatter("");
    let cloud = scatter(", height = [-0.5, 1.5]");
    assert!(flat.iter().all(|i| i.position.y == 2.0));
    let ys: Vec<f32> = cloud.iter().map(|i| i.position.y).collect();
    assert!(ys.iter().all(|y| (1.5..=3.5).contains(y)), "{ys:?}");
    let spread =
        ys.iter().fold(f32::MIN, |a, b| a.max(*b)) - ys.iter().fold(f32::MAX, |a, b| a.min(*b));
    assert!(spread > 1.5, "heights spread over {spread}");
    for (a, b) in flat.iter().zip(&cloud) {
        assert_eq!((a.position.x, a.position.z), (b.position.x, b.position.z));
        assert_eq!((a.rotation, a.scale), (b.rotation, b.scale));
    }
    refuses(
        &format!(
            "{LIGHT}[[item]]\nmesh = \"cube\"\n\
             scatter = {{ count = 2, area = [0.0, 1.0, 0.0, 1.0], height = [1.0, 0.0] }}\n"
        ),
        "item[0].scatter.height",
        "[1.0, 0.0]: expected [y_min, y_max] with y_min <= y_max",
    );
}

#[test]
fn volumetric_is_refused_by_name_where_it_cannot_cast() {
    let point = "[light]\nkind = \"point\"\nposition = [0.0, 3.0, 0.0]\n";
    let (_, message) = fails(&format!("{point}[shadow]\nvolumetric = \"solid\"\n"));
    assert_eq!(
        message,
        "s.toml: shadow.volumetric = solid: light cannot use it: a point light's cube map \
         takes volumetric = \"off\" only"
    );
    let (_, message) = fails(&format!(
        "{LIGHT}[shadow]\nvolumetric = \"solid\"\ncascades = 2\n"
    ));
    assert!(
        message.contains("shadow.volumetric = solid: light cannot use it: cascades"),
        "{message}"
    );
    let (_, message) = fails(&format!("{LIGHT}[shadow]\nvolumetric = \"smoky\"\n"));
    assert!(message.contains("volumetric"), "{message}");
    assert!(
        message.contains("off") && message.contains("solid"),
        "{message}"
    );
    let ok = format!("{LIGHT}[shadow]\nvolumetric = \"solid\"\n");
    assert!(parse(&ok, Path::new("s.toml"), None).is_ok());
}

#[test]
fn named_views_lie_over_the_camera_and_the_opening_view_must_be_one() {
    let text = format!(
        "view = \"high\"\n{LIGHT}[camera]\nposition = [0.0, 0.0, 3.0]\nfov = 45.0\n\
         [views]\nhigh = {{ position = [0.0, 8.0, 8.0], target = [0.0, 0.0, 0.0] }}\ncode = {{}}\n"
    );
    let mut s = parse(&text, Path::new("s.toml"), None).unwrap();
    // The file's [camera] until a command opens the scene on its view.
    assert_eq!(s.camera.position, Vec3::new(0.0, 0.0, 3.0));
    assert_eq!(s.view("code").unwrap().position, s.camera.position);
    s.open_view(None).unwrap();
    assert_eq!(s.camera.position, Vec3::new(0.0, 8.0, 8.0));
    assert_eq!(s.camera.fov, 45.0, "fields left out are [camera]'s");
    s.open_view(Some("code")).unwrap();
    assert_eq!(s.camera.position, Vec3::new(0.0, 0.0, 3.0));
    assert_eq!(
        s.open_view(Some("low")).unwrap_err().to_string(),
        "--view low: the s scene's views are code, high"
    );
    refuses(
        &format!("view = \"low\"\n{LIGHT}[views]\nhigh = {{ fov = 30.0 }}\n"),
        "view",
        "\"low\": expected one of [views]: high",
    );
    refuses(
        &format!("view = \"low\"\n{LIGHT}"),
        "view",
        "\"low\": the file has no [views] table to name one of",
    );
    refuses(
        &format!("{LIGHT}[views]\nhigh = {{ fov = 0.0 }}\n"),
        "views.high.fov",
        "0: expected degrees between 0 and 180",
    );
}
