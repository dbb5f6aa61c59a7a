//! A frame after the first makes no GL object and links no program: everything a run of
//! frames needs (the shadow mask's programs and target included) is made by then, so no
//! frame stalls on a shader compile.

use crate::common;

use shadowmap::engine::counters::{created, Created};
use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::renderer::{Renderer, Target};
use shadowmap::settings::{Filter, ShadowSettings, ShadowTechnique};
use shadowmap::Scene;

/// What frames 2..=10 of `scene` under `settings` made, after frame 1 (the scene's items
/// spinning, so maps are redrawn, patched and kept, and the mask written and read).
fn made_after_first_frame(name: &str, tweak: impl Fn(&mut ShadowSettings)) -> (Created, String) {
    let context = common::context();
    let gl = context.gl();
    let mut scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut settings = scene.shadow;
    tweak(&mut settings);
    scene.size = [160, 90];
    let target = RenderTarget::new(gl, 160, 90, Outputs::default()).unwrap();
    let mut renderer = Renderer::new(gl, &scene, &settings).unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    let after_first = created();
    for _ in 1..10 {
        scene.update();
        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    }
    let made = created().since(after_first);
    let uses = renderer.mask_uses();
    (made, format!("{name}: mask {uses:?}"))
}

#[test]
fn no_frame_after_the_first_makes_gl_objects() {
    for name in Scene::builtin_names() {
        let (made, what) = made_after_first_frame(name, |_| {});
        assert_eq!(made, Created::default(), "{what}");
    }
}

/// A settings change for a case.
type Tweak = dyn Fn(&mut ShadowSettings);

#[test]
fn no_frame_after_the_first_makes_gl_objects_with_other_techniques() {
    let cases: [(&str, &Tweak); 5] = [
        ("large", &|s| s.cascades = 4),
        ("playground", &|s| s.filter = Filter::Pcss),
        ("dummy", &|s| s.filter = Filter::Vsm),
        ("dummy", &|s| s.technique = ShadowTechnique::Volumes),
        ("learnopengl", &|s| s.shadow_cache = false),
    ];
    for (name, tweak) in cases {
        let (made, what) = made_after_first_frame(name, tweak);
        assert_eq!(made, Created::default(), "{what}");
    }
}

/// The mask is written in these runs, so the test above covers its programs and target.
#[test]
fn the_mask_is_written_and_read_in_a_still_scene() {
    let context = common::context();
    let gl = context.gl();
    let mut scene = common::frozen("learnopengl");
    scene.size = [160, 90];
    let settings = scene.shadow;
    let target = RenderTarget::new(gl, 160, 90, Outputs::default()).unwrap();
    let mut renderer = Renderer::new(gl, &scene, &settings).unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    let after_first = created();
    for _ in 1..4 {
        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    }
    assert_eq!(created(), after_first);
    let uses = renderer.mask_uses();
    assert!(uses.written == 1 && uses.read >= 2, "{uses:?}");
}
