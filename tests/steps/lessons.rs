//! Every step shows its lesson on screen: the pixels it changes against the step before.

use super::*;

/// The scenes the step lists were written for: the chapters' on the DummyGame and on
/// LearnOpenGL's, the playground's and the translucent casters' on their own. (Other scenes take the chapters' list too,
/// without stages of their own.)
const STEP_SCENES: [&str; 4] = ["dummy", "learnopengl", "playground", "smoke"];

/// A pixel has changed when a channel moved by more than this many levels of 255.
const CHANGED_LEVELS: i32 = 8;

/// A step shows its lesson when at least this share of the frame's pixels change (an edge
/// that softens or moves changes a few hundred pixels of a 320-pixel-wide frame).
const VISIBLE_SHARE: f64 = 0.0005;

/// A step that says it keeps its predecessor's picture changes fewer than this share of the
/// pixels (a few isolated ones).
const SAME_SHARE: f64 = 0.0001;

/// Of a staged step's changed pixels, at least this share lie in the region its caption
/// names.
const IN_REGION_SHARE: f64 = 0.9;

/// `scene` seen as step `st` is shown, drawn with `settings` 320 pixels wide in the scene's
/// aspect: the colours and each pixel's world position (NaN where no geometry).
fn staged_frame(
    ctx: &shadowmap::engine::HeadlessContext,
    scene: &Scene,
    st: &steps::Step,
    settings: &ShadowSettings,
) -> (Vec<u8>, Vec<[f32; 3]>) {
    let mut staged = scene.clone();
    st.set_stage(&mut staged, false).unwrap();
    let outputs = Outputs {
        visibility: false,
        gbuffer: true,
    };
    let height = 320 * staged.size[1] / staged.size[0];
    let frame = render_frames(ctx.gl(), &mut staged, settings, 320, height, 1, outputs)
        .unwrap_or_else(|e| panic!("{} / {}: {e}", scene.name, st.name));
    let positions = frame.world_positions().unwrap();
    (frame.colour.rgba, positions)
}

/// The pixels (by index) whose colours differ by more than [`CHANGED_LEVELS`].
fn changed_pixels(a: &[u8], b: &[u8]) -> Vec<usize> {
    let far = |p: &[u8], q: &[u8]| {
        (0..3).any(|k| (i32::from(p[k]) - i32::from(q[k])).abs() > CHANGED_LEVELS)
    };
    a.chunks_exact(4)
        .zip(b.chunks_exact(4))
        .enumerate()
        .filter_map(|(i, (p, q))| far(p, q).then_some(i))
        .collect()
}

/// Where a step's caption says its change shows, as a test of a pixel's world position:
/// outside the light's box or beyond its far plane for the over-sampling steps, on the floor
/// (at the contact, not on the caster) for culling; `None` for the whole frame.
fn named_region(
    scene: &Scene,
    st: &steps::Step,
    settings: &ShadowSettings,
) -> Option<Box<dyn Fn(Vec3) -> bool>> {
    let mut staged = scene.clone();
    st.set_stage(&mut staged, false).unwrap();
    match st.name {
        "over-sampling-repeat" | "over-sampling-book" | "over-sampling" => {
            let sv = shadowmap::shadows::light_camera(&staged, 0, settings);
            let m = sv.projection * sv.view;
            Some(Box::new(move |p| {
                let q = m.project_point3(p);
                q.x.abs() > 1.0 || q.y.abs() > 1.0 || q.z > 1.0
            }))
        }
        "cull-front" => {
            let floor = staged
                .items
                .iter()
                .find(|i| ["plane", "floor"].contains(&&*i.name));
            let y = floor.unwrap().position.y;
            Some(Box::new(move |p: Vec3| (p.y - y).abs() < 0.01))
        }
        _ => None,
    }
}

/// Every step of every list, on the scene it was written for, changes the picture of the
/// step before it visibly (in the region its caption names, where it has a stage), both drawn
/// as the step is shown; or it says why it is the picture of the step it builds on, and is.
#[test]
fn every_step_shows_its_change_or_says_why_not() {
    let ctx = common::context();
    for name in STEP_SCENES {
        let mut sc = scene(name);
        sc.camera = sc.steps_camera();
        sc.use_steps_light_size();
        let list = steps::of(&sc);
        let mut base = steps::start(&sc);
        for (i, st) in list.iter().enumerate() {
            let settings = step(&sc, st.name);
            let before = match (i, st.same_picture_on(&sc)) {
                (_, Some(_)) => base,
                (0, None) => steps::start(&sc),
                (_, None) => step(&sc, list[i - 1].name),
            };
            let (now, positions) = staged_frame(&ctx, &sc, st, &settings);
            let (was, _) = staged_frame(&ctx, &sc, st, &before);
            let changed = changed_pixels(&now, &was);
            let share = changed.len() as f64 / (now.len() / 4) as f64;
            let region = named_region(&sc, st, &settings);
            let region = region.filter(|_| st.same_picture_on(&sc).is_none());
            let inside = region.as_ref().map(|keep| {
                let n = changed
                    .iter()
                    .filter(|&&i| keep(Vec3::from(positions[i])))
                    .count();
                n as f64 / changed.len().max(1) as f64
            });
            let most = now
                .iter()
                .zip(&was)
                .map(|(a, b)| a.abs_diff(*b))
                .max()
                .unwrap_or(0);
            eprintln!(
                "{name} {}: {:.3}% of pixels changed (at most by {most} levels){}",
                st.name,
                share * 100.0,
                inside.map_or(String::new(), |s| format!(
                    ", {:.1}% of them where its caption says",
                    s * 100.0
                ))
            );
            match st.same_picture_on(&sc) {
                Some(why) => assert!(
                    share < SAME_SHARE,
                    "{name} {}: says it is the same picture ({why}), but {} pixels change",
                    st.name,
                    changed.len()
                ),
                None => assert!(
                    share >= VISIBLE_SHARE,
                    "{name} {}: {:.3}% of pixels change, under {}%",
                    st.name,
                    share * 100.0,
                    VISIBLE_SHARE * 100.0
                ),
            }
            if let Some(s) = inside {
                assert!(
                    s >= IN_REGION_SHARE,
                    "{name} {}: {s} in its region",
                    st.name
                );
            }
            if st.cumulative {
                base = settings;
            }
        }
    }
}

/// `render --help` (for `--step`) and `steps --help` say which scenes take which steps: each
/// list's line names exactly the built-in scenes that load with it, and the next line its
/// steps in order.
#[test]
fn the_help_names_each_scenes_steps() {
    for command in ["render", "steps"] {
        let help = common::stdout_of(common::bin().args([command, "--help"]));
        // The help wraps to the terminal: read it as one run of words.
        let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
        let mut listed: Vec<String> = Vec::new();
        for list in [
            StepList::Chapters,
            StepList::Playground,
            StepList::Volumetric,
        ] {
            let scenes: Vec<Scene> = Scene::builtin_names()
                .into_iter()
                .map(|n| Scene::load(n).unwrap())
                .filter(|s| s.steps.list == list)
                .collect();
            let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
            let head = format!("{} (scenes {}):", list.name(), names.join(", "));
            let at = flat.find(&head);
            let at = at.unwrap_or_else(|| panic!("{command} --help lacks '{head}':\n{help}"));
            let steps: Vec<&str> = steps::of(&scenes[0]).iter().map(|s| s.name).collect();
            let after = flat[at + head.len()..].trim_start();
            assert!(
                after.starts_with(&steps.join(", ")),
                "{command} --help: after '{head}': {after}"
            );
            listed.extend(names.iter().map(|n| n.to_string()));
        }
        listed.sort_unstable();
        let mut all: Vec<String> = Scene::builtin_names()
            .iter()
            .map(|n| n.to_string())
            .collect();
        all.sort_unstable();
        assert_eq!(listed, all, "{command} --help: every built-in scene once");
    }
}
