//! Settings chosen from measurements: the `--quality` presets (data, in
//! `assets/quality.toml`, picked from the bench's measurements) and `--target-error`, which
//! runs the bench's quick sweep on the current scene and keeps the cheapest configuration
//! accurate enough.

use shadowmap::bench::{self, BenchConfig, BenchOptions, BenchRow, Family};
use shadowmap::engine::{gl_limits, HeadlessContext};
use shadowmap::output::{Activity, Counter};
use shadowmap::settings::ShadowPatch;
use shadowmap::{Error, Result, Scene, ShadowSettings};

static PRESETS: &str = include_str!("../../assets/quality.toml");

/// A preset of shadow settings, from cheap to accurate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Quality {
    Low,
    Medium,
    High,
}

impl Quality {
    pub fn name(self) -> &'static str {
        match self {
            Quality::Low => "low",
            Quality::Medium => "medium",
            Quality::High => "high",
        }
    }

    /// The preset's settings (only the fields it gives).
    pub fn patch(self) -> Result<ShadowPatch> {
        let bad = |e: &dyn std::fmt::Display| {
            Error::Invalid(format!(
                "assets/quality.toml (built in), [{}]: {e}",
                self.name()
            ))
        };
        let mut tables: std::collections::BTreeMap<String, ShadowPatch> =
            toml::from_str(PRESETS).map_err(|e| bad(&e))?;
        tables
            .remove(self.name())
            .ok_or_else(|| bad(&"missing: expected a table for every preset"))
    }
}

/// The settings the sweep varies, as flags would give them: a configuration the bench
/// measured, to lay over the scene's settings.
pub fn patch_of(config: &BenchConfig) -> ShadowPatch {
    let s = &config.settings;
    if config.family == Family::Volumes {
        // No map: the map's settings would do nothing (and each earn a warning).
        return ShadowPatch {
            technique: Some(s.technique),
            ..ShadowPatch::default()
        };
    }
    let cube = matches!(config.family, Family::PointLayered | Family::PointSixPasses);
    ShadowPatch {
        map_size: Some(s.map_size),
        filter: Some(s.filter),
        bias_mode: Some(s.bias_mode),
        bias: Some(s.bias),
        bias_min: Some(s.bias_min),
        normal_offset: Some(s.normal_offset),
        polygon_offset: Some(s.polygon_offset),
        cull: Some(s.cull),
        depth_format: Some(s.depth_format),
        cascades: Some(s.cascades),
        caster_groups: Some(s.caster_groups),
        // The sweep's volumes row and its fixed-box tutorials differ from the base here.
        technique: Some(s.technique),
        fit: Some(s.fit),
        // Only where it does something (a flag that does nothing earns a warning).
        point_pass: cube.then_some(s.point_pass),
        ..ShadowPatch::default()
    }
}

/// Refuses a scene whose first light casts no shadow: the sweep measures that light.
pub fn check_first_light(scene: &Scene) -> Result<()> {
    match scene.light().casts_shadows() {
        true => Ok(()),
        false => Err(Error::Invalid(format!(
            "{}: the first light does not cast shadows (casts_shadows = false): the sweep \
             measures the first light; expected a scene whose first light casts",
            scene.source.display()
        ))),
    }
}

/// The cheapest row with an error of at most `target`, or the error saying none was.
pub fn cheapest_or_error(rows: &[BenchRow], target: f64) -> Result<&BenchRow> {
    bench::cheapest_under(rows, target).ok_or_else(|| {
        Error::Invalid(format!(
            "--target-error {target}: no configuration reached an error of {:.3}% or less \
             (best: {})",
            target * 100.0,
            rows.iter()
                .min_by(|a, b| a.error().total_cmp(&b.error()))
                .map_or("no configuration ran".to_string(), |r| r.error_text())
        ))
    })
}

/// What was chosen, in one line, and the flags that give it.
pub fn describe_choice(r: &BenchRow, target: f64) -> String {
    let s = &r.config.settings;
    let flags = match r.config.family {
        Family::Volumes => "--technique volumes".to_string(),
        Family::OneMap
        | Family::Soft
        | Family::Cascades
        | Family::Groups
        | Family::PointLayered
        | Family::PointSixPasses => {
            format!(
            "--map-size {} --filter {} --bias-mode {} --bias {} --bias-min {} --normal-offset {} \
             --polygon-offset {},{} --cull {} --depth-format {} --cascades {} --caster-groups {} \
             --fit {} --technique maps",
            s.map_size,
            s.filter.name(),
            s.bias_mode.name(),
            s.bias,
            s.bias_min,
            s.normal_offset,
            s.polygon_offset[0],
            s.polygon_offset[1],
            s.cull.name(),
            s.depth_format.name(),
            s.cascades,
            s.caster_groups,
            match s.fit {
                shadowmap::settings::Fit::Manual => "manual",
                shadowmap::settings::Fit::Scene => "scene",
            },
        ) + match patch_of(&r.config).point_pass {
                Some(shadowmap::settings::PointPass::SixPasses) => " --point-pass six-passes",
                Some(shadowmap::settings::PointPass::Layered) => " --point-pass layered",
                None => "",
            }
        }
    };
    format!(
        "cheapest configuration with error <= {:.3}%: {} ({:.2} ms a frame, {})\n  as \
         flags: {flags}",
        target * 100.0,
        r.label(),
        r.wall_ms.median,
        r.error_text(),
    )
}

/// `--target-error E` for render and demo: the bench's quick sweep over the scene's view
/// at `size`, scored against the exact reference (10 timed frames a block), and the
/// cheapest configuration meeting `target`, as a patch of flags. Prints what it chose.
///
/// `given`: the settings given as flags. The search keeps to the configurations that have
/// them (`--technique maps` leaves out the volumes, `--map-size 1024` the other sizes), so
/// what is drawn is what was measured and the flags still hold.
pub fn choose_for_target(
    scene: &Scene,
    base: &ShadowSettings,
    size: (u32, u32),
    target: f64,
    given: &ShadowPatch,
) -> Result<ShadowPatch> {
    check_first_light(scene)?;
    let mut scene = scene.clone();
    // A still frame, as the bench times it.
    scene
        .items
        .iter_mut()
        .for_each(|i| i.spin = glam::Vec3::ZERO);
    scene.size = [size.0, size.1];
    let context = HeadlessContext::new()?;
    let gl = context.gl();
    let configs = keeping_flags(
        bench::sweep(base, true, gl_limits(gl).max_texture_size, scene.light()),
        given,
        target,
    )?;
    let opts = BenchOptions {
        width: size.0,
        height: size.1,
        warmup: 3,
        frames: 10,
        supersample: 1,
        band: 1,
        rays: shadowmap::compare::AREA_RAYS,
    };
    let activity = Activity::start(format!(
        "--target-error {target}: tracing the exact reference at {}x{}",
        size.0, size.1
    ));
    let reference = bench::bench_reference(gl, &scene, base, &opts)?;
    activity.done("");
    eprintln!(
        "--target-error {target}: timing and scoring {} configurations (bench --quick, {} \
         frames a block)",
        configs.len(),
        opts.frames
    );
    let mut counter = Counter::new(2 * configs.len() as u64);
    let rows = bench::run(gl, &scene, &configs, &reference, &opts, |p| {
        counter.step(&p.line())
    })?;
    counter.finish();
    let chosen = cheapest_or_error(&rows, target)?;
    println!("{}", describe_choice(chosen, target));
    let patch = patch_of(&chosen.config);
    // The demo's window comes next, on this thread.
    context.release();
    Ok(patch)
}

/// The configurations whose settings the flags in `given` leave unchanged; an error naming
/// the flags when none does.
fn keeping_flags(
    configs: Vec<BenchConfig>,
    given: &ShadowPatch,
    target: f64,
) -> Result<Vec<BenchConfig>> {
    let keeps = |c: &BenchConfig| {
        let mut s = c.settings;
        given.apply_to(&mut s);
        s == c.settings
    };
    let kept: Vec<BenchConfig> = configs.into_iter().filter(keeps).collect();
    if kept.is_empty() {
        return Err(Error::Invalid(format!(
            "--target-error {target}: no configuration of the quick sweep has the settings \
             given as flags ({}): give fewer of them, or leave out --target-error",
            given.given().join(", ")
        )));
    }
    Ok(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chosen_configuration_laid_over_the_scene_is_what_was_measured() {
        // The patch (and so the printed flags) must carry every setting the sweep varies:
        // without `caster_groups` a chosen caster-groups row was drawn as one map.
        for name in ["learnopengl", "point-shadows"] {
            let scene = Scene::load(name).unwrap();
            for c in bench::sweep(&scene.shadow, true, 16384, scene.light()) {
                let mut s = scene.shadow;
                patch_of(&c).apply_to(&mut s);
                assert_eq!(
                    Family::of(scene.light(), &s),
                    c.family,
                    "{name}: {}",
                    c.family.name()
                );
                if c.family != Family::Volumes {
                    assert_eq!(
                        (s.map_size, s.filter, s.cascades, s.caster_groups, s.fit),
                        (
                            c.settings.map_size,
                            c.settings.filter,
                            c.settings.cascades,
                            c.settings.caster_groups,
                            c.settings.fit
                        ),
                        "{name}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_search_keeps_to_the_configurations_the_flags_allow() {
        let scene = Scene::load("learnopengl").unwrap();
        let base = scene.shadow;
        let all = || bench::sweep(&base, true, 16384, scene.light());
        let maps = ShadowPatch {
            technique: Some(shadowmap::settings::ShadowTechnique::Maps),
            ..ShadowPatch::default()
        };
        let kept = keeping_flags(all(), &maps, 0.01).unwrap();
        assert!(kept.len() < all().len());
        assert!(kept.iter().all(|c| c.family != Family::Volumes));
        let size = ShadowPatch {
            map_size: Some(shadowmap::settings::MapSize::square(1024)),
            ..ShadowPatch::default()
        };
        let kept = keeping_flags(all(), &size, 0.01).unwrap();
        assert!(kept
            .iter()
            .all(|c| c.settings.map_size == shadowmap::settings::MapSize::square(1024)));
        let odd = ShadowPatch {
            map_size: Some(shadowmap::settings::MapSize::square(300)),
            ..ShadowPatch::default()
        };
        let e = keeping_flags(all(), &odd, 0.01).unwrap_err().to_string();
        assert_eq!(
            e,
            "--target-error 0.01: no configuration of the quick sweep has the settings given \
             as flags (map_size): give fewer of them, or leave out --target-error"
        );
        // No flags: every configuration.
        assert_eq!(
            keeping_flags(all(), &ShadowPatch::default(), 0.01)
                .unwrap()
                .len(),
            all().len()
        );
    }

    #[test]
    fn every_preset_is_valid_and_they_differ() {
        let settings: Vec<ShadowSettings> = [Quality::Low, Quality::Medium, Quality::High]
            .iter()
            .map(|q| {
                let mut s = ShadowSettings::default();
                q.patch().unwrap().apply_to(&mut s);
                s.validate_values().unwrap();
                s
            })
            .collect();
        assert_ne!(settings[0], settings[1]);
        assert_ne!(settings[1], settings[2]);
        assert!(settings[0].map_size.max_side() <= settings[2].map_size.max_side());
    }
}
