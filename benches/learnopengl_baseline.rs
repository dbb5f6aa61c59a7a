//! Our renderer on the built-in `learnopengl` scene (its own `[shadow]` settings) against
//! `LearnOpenGlBaseline`, a plain implementation of the tutorial's frame, in the same run:
//! both draw 800x600 frames in alternating blocks, each frame timed as wall time around
//! render + glFinish. Run with `cargo bench --bench learnopengl_baseline`;
//! `SHADOWMAP_BENCH_BLOCKS=N` changes the number of blocks per side (default 10).

use std::time::Instant;

use glam::Vec3;
use shadowmap::engine::baseline::LearnOpenGlBaseline;
use shadowmap::engine::{HeadlessContext, Outputs, RenderTarget};
use shadowmap::{Renderer, Scene, Target};

const WARM_UP: usize = 20;
const BLOCK: usize = 50;
const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;

fn time_block(frames: usize, mut frame: impl FnMut()) -> Vec<f64> {
    (0..frames)
        .map(|_| {
            let start = Instant::now();
            frame();
            start.elapsed().as_secs_f64() * 1000.0
        })
        .collect()
}

/// The value at quantile `q` (nearest rank) of `v`.
fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

fn main() -> shadowmap::Result<()> {
    if let Ok(n) = std::env::var("SHADOWMAP_EXP") {
        return experiment(&n);
    }
    let blocks: usize = match std::env::var("SHADOWMAP_BENCH_BLOCKS") {
        Ok(s) => s
            .parse()
            .ok()
            .filter(|&n| n > 0)
            .unwrap_or_else(|| panic!("SHADOWMAP_BENCH_BLOCKS={s}: expected a count >= 1")),
        Err(_) => 10,
    };
    let ctx = HeadlessContext::new()?;
    let gl = ctx.gl();
    let mut scene = Scene::load("learnopengl")?;
    for item in &mut scene.items {
        item.spin = Vec3::ZERO;
    }
    let settings = scene.shadow;
    let baseline = LearnOpenGlBaseline::new(gl)?;
    let mut renderer = Renderer::new(gl, &scene, &settings)?;
    let target = RenderTarget::new(gl, WIDTH, HEIGHT, Outputs::default())?;

    let mut base_frame = || {
        baseline.render_frame();
        baseline.finish();
    };
    let mut ours_error = None;
    let mut ours_frame = || {
        if let Err(e) = renderer.render(&scene, Target::Offscreen(&target)) {
            ours_error.get_or_insert(e);
        }
        renderer.finish();
    };
    time_block(WARM_UP, &mut base_frame);
    time_block(WARM_UP, &mut ours_frame);
    let (mut base_all, mut ours_all, mut pair_ratios) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..blocks {
        let base = time_block(BLOCK, &mut base_frame);
        let ours = time_block(BLOCK, &mut ours_frame);
        pair_ratios.push(quantile(&ours, 0.5) / quantile(&base, 0.5));
        base_all.extend(base);
        ours_all.extend(ours);
    }
    if let Some(e) = ours_error {
        return Err(e);
    }

    let base_image = baseline.read_colour();
    let ours_image = target.read_colour();
    let diff = base_image
        .iter()
        .zip(&ours_image)
        .map(|(a, b)| a.abs_diff(*b) as f64)
        .sum::<f64>()
        / base_image.len() as f64;

    println!(
        "learnopengl scene, {WIDTH}x{HEIGHT}, {blocks} blocks of {BLOCK} frames per side \
         (wall time to glFinish), on {}",
        ctx.device_name()
    );
    for (name, t) in [("baseline", &base_all), ("ours", &ours_all)] {
        println!(
            "  {name:9} median {:7.3} ms   p95 {:7.3} ms",
            quantile(t, 0.5),
            quantile(t, 0.95)
        );
    }
    println!(
        "  ours / baseline: {:.3} (medians); per block pair min {:.3} median {:.3} max {:.3}",
        quantile(&ours_all, 0.5) / quantile(&base_all, 0.5),
        quantile(&pair_ratios, 0.0),
        quantile(&pair_ratios, 0.5),
        quantile(&pair_ratios, 1.0)
    );
    println!("  image difference: {diff:.3} mean absolute per channel (0..255)");
    Ok(())
}

fn experiment(names: &str) -> shadowmap::Result<()> {
    let ctx = HeadlessContext::new()?;
    let gl = ctx.gl();
    let mut scene = Scene::load("learnopengl")?;
    for item in &mut scene.items {
        item.spin = Vec3::ZERO;
    }
    let settings = scene.shadow;
    let mut sides: Vec<(String, LearnOpenGlBaseline)> =
        vec![("plain".into(), LearnOpenGlBaseline::new(gl)?)];
    for n in names.split(',') {
        let (vs, fs) = if n.starts_with("real") {
            let mut defines = settings.shader_defines();
            for (k, v) in [
                ("LIGHT_POSITIONAL", "1"),
                ("SPOT_CONE", "0"),
                ("BLINN", "1"),
            ] {
                defines.push((k.into(), v.into()));
            }
            let with = |text: &str| {
                let (first, rest) = text.split_once('\n').unwrap();
                let mut out = format!("{first}\n");
                for (k, v) in &defines {
                    out.push_str(&format!("#define {k} {v}\n"));
                }
                out + rest
            };
            let vs = with(&shadowmap::shaders::scene_vert().text)
                .replace(
                    "layout (location = 1) in vec2 texCoord;",
                    "layout (location = 2) in vec2 texCoord;",
                )
                .replace(
                    "layout (location = 2) in vec3 vertexNormal;",
                    "layout (location = 1) in vec3 vertexNormal;",
                );
            let mut fs = with(&shadowmap::shaders::scene_frag().text);
            if n.contains("notex") {
                fs = fs.replace(
                    "material.hasTexture == 1 ? texture(textureSampler, outTexCoord)",
                    "true ? texture(textureSampler, outTexCoord)",
                );
            }
            if n.contains("pow") {
                fs = fs.replace(
                    "pow(max(specularAngle, 0.0), specularPower)",
                    "pow(max(specularAngle, 0.0), 64.0)",
                );
            }
            if n.contains("cbias") {
                fs = fs.replace(
                    "max(bias * (1.0 - dot(normal, toLightDir)), biasMin)",
                    "max(0.05 * (1.0 - dot(normal, toLightDir)), 0.005)",
                );
            }
            (vs, fs)
        } else if n.contains("ourglsl") {
            our_glsl(&settings)
        } else if n.starts_with("churn") || n.starts_with("unif") || n.starts_with("idx") {
            let s = std::fs::read_to_string("/tmp/exp/plain2.vert").unwrap();
            (s, std::fs::read_to_string("/tmp/exp/plain2.frag").unwrap())
        } else if n == "ourglsl" {
            our_glsl(&settings)
        } else {
            (
                std::fs::read_to_string(format!("/tmp/exp/{n}.vert")).unwrap(),
                std::fs::read_to_string(format!("/tmp/exp/{n}.frag")).unwrap(),
            )
        };
        sides.push((n.into(), LearnOpenGlBaseline::with_shaders(gl, &vs, &fs)?));
    }
    let mut renderer = Renderer::new(gl, &scene, &settings)?;
    let target = RenderTarget::new(gl, WIDTH, HEIGHT, Outputs::default())?;
    let n = sides.len() + 1;
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); n];
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); n];
    let blocks: usize = std::env::var("SHADOWMAP_BENCH_BLOCKS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    for b in 0..=blocks {
        let mut med = vec![0.0; n];
        for k in 0..n {
            let i = (k + b) % n;
            let frames = if b == 0 { WARM_UP } else { BLOCK };
            let t = if i < sides.len() {
                let base = &sides[i].1;
                let name = sides[i].0.clone();
                let (churn, unif, idx) = (
                    name.contains("churn"),
                    name.contains("unif"),
                    name.contains("idx"),
                );
                let real = name.starts_with("real");
                time_block(frames, || {
                    if real {
                        base.render_real_uniforms()
                    } else if churn || unif || idx {
                        base.render_variant(churn, unif, idx)
                    } else {
                        base.render_frame()
                    };
                    base.finish();
                })
            } else {
                time_block(frames, || {
                    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
                    renderer.finish();
                })
            };
            med[i] = quantile(&t, 0.5);
            if b > 0 {
                times[i].extend(t);
            }
        }
        if b > 0 {
            for i in 0..n {
                ratios[i].push(med[i] / med[0]);
            }
        }
    }
    if let Ok(solo) = std::env::var("SHADOWMAP_EXP_SOLO") {
        let i: usize = solo.parse().unwrap();
        for _ in 0..600 {
            if i < sides.len() {
                let b = &sides[i].1;
                let name = &sides[i].0;
                if name.starts_with("real") {
                    b.render_real_uniforms()
                } else if name.contains("churn") || name.contains("unif") || name.contains("idx") {
                    b.render_variant(
                        name.contains("churn"),
                        name.contains("unif"),
                        name.contains("idx"),
                    )
                } else {
                    b.render_frame()
                };
                b.finish();
            } else {
                renderer.render(&scene, Target::Offscreen(&target)).unwrap();
                renderer.finish();
            }
        }
        return Ok(());
    }
    if std::env::var("SHADOWMAP_EXP_CPU").is_ok() {
        let ticks = || {
            let st = std::fs::read_to_string("/proc/self/stat").unwrap();
            let f: Vec<&str> = st.rsplit_once(')').unwrap().1.split_whitespace().collect();
            f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()
        };
        let mut cpu = vec![0.0; n];
        for round in 0..8 {
            for k in 0..n {
                let i = (k + round) % n;
                let t0 = ticks();
                for _ in 0..100 {
                    if i < sides.len() {
                        let b = &sides[i].1;
                        let name = &sides[i].0;
                        if name.starts_with("real") {
                            b.render_real_uniforms()
                        } else if name.contains("churn")
                            || name.contains("unif")
                            || name.contains("idx")
                        {
                            b.render_variant(
                                name.contains("churn"),
                                name.contains("unif"),
                                name.contains("idx"),
                            )
                        } else {
                            b.render_frame()
                        };
                        b.finish();
                    } else {
                        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
                        renderer.finish();
                    }
                }
                cpu[i] += (ticks() - t0) * 10.0 / 800.0;
            }
        }
        for i in 0..n {
            println!(
                "cpu {:8} {:.3} ms/frame (all threads)",
                sides.get(i).map(|s| s.0.as_str()).unwrap_or("ours"),
                cpu[i]
            );
        }
    }
    let mut sub = [Vec::new(), Vec::new()];
    for _ in 0..200 {
        let t = Instant::now();
        sides[0].1.render_frame();
        sub[0].push(t.elapsed().as_secs_f64() * 1000.0);
        sides[0].1.finish();
        let t = Instant::now();
        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
        sub[1].push(t.elapsed().as_secs_f64() * 1000.0);
        renderer.finish();
    }
    let mut dep = [Vec::new(), Vec::new()];
    for _ in 0..10 {
        for _ in 0..50 {
            let t = Instant::now();
            sides[0].1.depth_only();
            sides[0].1.finish();
            dep[0].push(t.elapsed().as_secs_f64() * 1000.0);
        }
        for _ in 0..50 {
            let t = Instant::now();
            renderer.render_depth_map(&scene).unwrap();
            renderer.finish();
            dep[1].push(t.elapsed().as_secs_f64() * 1000.0);
        }
    }
    let mut ds = [Vec::new(), Vec::new()];
    for _ in 0..300 {
        let t = Instant::now();
        sides[0].1.depth_only();
        ds[0].push(t.elapsed().as_secs_f64() * 1000.0);
        sides[0].1.finish();
        let t = Instant::now();
        renderer.render_depth_map(&scene).unwrap();
        ds[1].push(t.elapsed().as_secs_f64() * 1000.0);
        renderer.finish();
    }
    println!(
        "depth submit: plain {:.4} ms ours {:.4} ms",
        quantile(&ds[0], 0.5),
        quantile(&ds[1], 0.5)
    );
    println!(
        "depth only: plain {:.4} ms ours {:.4} ms",
        quantile(&dep[0], 0.5),
        quantile(&dep[1], 0.5)
    );
    println!(
        "submit only: plain {:.4} ms ours {:.4} ms",
        quantile(&sub[0], 0.5),
        quantile(&sub[1], 0.5)
    );
    let plain = quantile(&times[0], 0.5);
    let plain_img = sides[0].1.read_colour();
    for (i, t) in times.iter().enumerate() {
        let name = sides.get(i).map(|s| s.0.as_str()).unwrap_or("ours");
        let img = sides
            .get(i)
            .map(|s| s.1.read_colour())
            .unwrap_or_else(|| target.read_colour());
        shadowmap::image_data::ImageData {
            width: WIDTH,
            height: HEIGHT,
            rgba: img.clone(),
        }
        .save_png(std::path::Path::new(&format!("/tmp/exp/{name}.png")))
        .unwrap();
        let diff = img
            .iter()
            .zip(&plain_img)
            .map(|(a, b)| a.abs_diff(*b) as f64)
            .sum::<f64>()
            / img.len() as f64;
        println!(
            "{name:8} median {:7.3} ms  ratio {:.3}  block ratios q1 {:.3} med {:.3} q3 {:.3}  diff {diff:.3}",
            quantile(t, 0.5),
            quantile(t, 0.5) / plain, quantile(&ratios[i], 0.25), quantile(&ratios[i], 0.5), quantile(&ratios[i], 0.75)
        );
    }
    Ok(())
}

fn our_glsl(settings: &shadowmap::ShadowSettings) -> (String, String) {
    let mut defines = settings.shader_defines();
    for (k, v) in [
        ("LIGHT_POSITIONAL", "1"),
        ("SPOT_CONE", "0"),
        ("BLINN", "1"),
    ] {
        defines.push((k.into(), v.into()));
    }
    let with = |text: &str| {
        let (first, rest) = text.split_once('\n').unwrap();
        let mut out = format!("{first}\n");
        for (k, v) in &defines {
            out.push_str(&format!("#define {k} {v}\n"));
        }
        out + rest
    };
    let mut vs = with(&shadowmap::shaders::scene_vert().text);
    let mut fs = with(&shadowmap::shaders::scene_frag().text);
    for (a, b) in [
        ("uniform mat4 modelOriginMatrix;", "uniform mat4 model; uniform mat4 view; uniform mat4 projection; uniform mat4 lightSpace;\n#define modelOriginMatrix model\n#define modelViewMatrix (view * model)\n#define normalMatrix mat3(view * model)\n#define worldNormalMatrix mat3(model)\n#define projectionMatrix projection\n#define modelLightViewMatrix (lightSpace * model)\n#define orthoProjectionMatrix mat4(1.0)\n#define normalOffset 0.0\n"),
        ("layout (location = 1) in vec2 texCoord;", "layout (location = 2) in vec2 texCoord;"),
        ("layout (location = 2) in vec3 vertexNormal;", "layout (location = 1) in vec3 vertexNormal;"),
        ("uniform mat4 modelViewMatrix;", ""), ("uniform mat3 normalMatrix;", "//"), ("uniform mat3 worldNormalMatrix;", "//"),
        ("uniform mat4 projectionMatrix;", ""), ("uniform mat4 modelLightViewMatrix;", ""), ("uniform mat4 orthoProjectionMatrix;", ""), ("uniform float normalOffset;", "//"),
    ] { assert!(vs.contains(a), "{a}"); vs = vs.replace(a, b); }
    for (a, b) in [
        ("uniform sampler2D textureSampler;", "uniform sampler2D woodMap;\n#define textureSampler woodMap\nuniform vec3 viewPos; uniform vec3 lightPos;"),
        ("uniform Material material;", "#define material Material(vec4(1.0), int(viewPos.z) - 2, viewPos.z / 3.0)"),
        ("uniform Light light;", "#define light Light(vec3(0.1) * viewPos.z, viewPos.z / 3.0, vec3(0.0), lightPos - vec3(0.0, 0.0, viewPos.z), 0.0, vec3(0.0))"),
        ("uniform vec3 ambientLight;", "#define ambientLight (vec3(0.03) * viewPos.z)"),
        ("uniform float specularPower;", "#define specularPower (viewPos.z * 21.333334)"),
        ("uniform float bias;", "#define bias (viewPos.z / 60.0)"),
        ("uniform float biasMin;", "#define biasMin (viewPos.z / 600.0)"),
    ] { assert!(fs.contains(a), "{a}"); fs = fs.replace(a, b); }
    (vs, fs)
}
