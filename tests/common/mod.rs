//! Shared by the integration tests: a headless context and scene shortcuts.
#![allow(dead_code)]

pub mod step_frames;

use glam::Vec3;
use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::{render_frames, Frame};
use shadowmap::{Scene, ShadowSettings};

/// Scoring a `width` x `height` frame of the first light against the exact reference:
/// one sample a pixel, a one-pixel edge band.
pub fn frame_options(width: u32, height: u32) -> shadowmap::compare::CompareOptions {
    banded_options(width, height, 1)
}

/// The same with an edge band of `band` pixels (the area light traced with the usual rays).
pub fn banded_options(width: u32, height: u32, band: usize) -> shadowmap::compare::CompareOptions {
    shadowmap::compare::CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width,
        height,
        supersample: 1,
        band,
        light: 0,
    }
}

/// A fresh, empty folder for one case of an area's tests, under cargo's temporary folder.
pub fn case_dir(area: &str, case: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(area)
        .join(case.replace(|c: char| !c.is_ascii_alphanumeric(), "_"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A headless EGL context; every test that draws makes its own (contexts are per thread).
pub fn context() -> HeadlessContext {
    HeadlessContext::new().unwrap_or_else(|e| panic!("headless EGL context: {e}"))
}

/// The DummyGame with its cube frozen, the light at `angle` degrees.
pub fn dummy(angle: f32) -> Scene {
    let mut scene = Scene::load("dummy").unwrap();
    for item in &mut scene.items {
        item.spin = Vec3::ZERO;
    }
    scene.set_light_angle(angle);
    scene
}

/// A built-in scene with every item's spin stopped.
pub fn frozen(name: &str) -> Scene {
    let mut scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    for item in &mut scene.items {
        item.spin = Vec3::ZERO;
    }
    scene
}

/// Renders one frame with visibility and G-buffer outputs.
pub fn render(
    ctx: &HeadlessContext,
    scene: &mut Scene,
    settings: &ShadowSettings,
    width: u32,
    height: u32,
) -> Frame {
    let outputs = Outputs {
        visibility: true,
        gbuffer: true,
    };
    render_frames(ctx.gl(), scene, settings, width, height, 1, outputs)
        .unwrap_or_else(|e| panic!("render: {e}"))
}

/// Pixels that show the DummyGame's plane (y = -1, facing up): (world position, visibility).
pub fn plane_pixels(frame: &Frame) -> Vec<(Vec3, f32)> {
    let pos = frame.world_positions().unwrap();
    let nrm = frame.normals.as_ref().unwrap();
    let vis = frame.visibility.as_ref().unwrap();
    (0..pos.len())
        .filter_map(|i| {
            let p = Vec3::from(pos[i]);
            let n = Vec3::from(nrm[i]);
            let v = vis[i]?;
            ((p.y + 1.0).abs() < 1e-3 && n.y > 0.99).then_some((p, v))
        })
        .collect()
}

/// The `shadowmap` binary under test.
pub fn bin() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_shadowmap"))
}

/// Runs `cmd` and returns its standard output; fails the test with its standard error if it
/// did not succeed or panicked.
pub fn stdout_of(cmd: &mut std::process::Command) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{cmd:?} failed: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// [`stdout_of`] for a demo run with `--require-window`. An X server under load can refuse
/// one connection among many; a refusal is tried again twice, half a second apart, and any
/// other failure fails at once.
pub fn window_stdout_of(cmd: &mut std::process::Command) -> String {
    for attempt in 1..=3 {
        let out = cmd
            .output()
            .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
        let stderr = String::from_utf8_lossy(&out.stderr);
        if out.status.success() {
            assert!(!stderr.contains("panicked"), "{stderr}");
            let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
            // The demo's own report that a window drew the frames (the headless fallback
            // prints no such line): "... window through GLX on X11)".
            assert!(
                stdout.contains("; window through "),
                "{cmd:?} drew no window: {stdout}"
            );
            return stdout;
        }
        let refused = stderr.contains("--require-window: no window");
        assert!(
            refused && attempt < 3,
            "{cmd:?} failed (attempt {attempt}): {stderr}"
        );
        eprintln!("attempt {attempt}: {stderr}");
        std::thread::sleep(std::time::Duration::from_millis(500));
    }
    unreachable!("the third attempt returns or fails")
}

/// The largest fraction of receiver pixels whose visibility changes when only the camera a
/// light's box (or cascades) is fitted to moves by `step`, 2`step`, ... (`steps` moves,
/// each along (1, 0, 0.5)), the view itself staying put: what shimmer would show.
pub fn shimmer(
    ctx: &HeadlessContext,
    scene: &Scene,
    settings: &ShadowSettings,
    (width, height): (u32, u32),
    step: f32,
    steps: u32,
) -> f64 {
    let render = |dx: f32| {
        let mut sc = scene.clone();
        sc.fit_camera = Some(shadowmap::scene::Camera {
            position: scene.camera.position + Vec3::new(dx, 0.0, dx * 0.5),
            ..scene.camera
        });
        shadowmap::compare::render_visibility(ctx.gl(), &sc, settings, width, height, 0)
            .unwrap_or_else(|e| panic!("render: {e}"))
            .visibility
            .unwrap_or_default()
    };
    let first = render(0.0);
    let receivers = first.iter().filter(|p| p.is_some()).count().max(1);
    (1..=steps)
        .map(|k| {
            let v = render(k as f32 * step);
            first.iter().zip(&v).filter(|(a, b)| a != b).count() as f64 / receivers as f64
        })
        .fold(0.0, f64::max)
}

/// How a frame with the HUD differs from the same frame without it, split at a rectangle
/// (x0, y0, x1, y1) in pixels where the HUD must stay.
#[derive(Debug)]
pub struct HudDifference {
    /// Pixels that changed inside the rectangle.
    pub inside: usize,
    /// Of those, pixels that became bright white (glyph cores) where the scene was not.
    pub glyphs: usize,
    /// Pixels that changed outside the rectangle (there should be none).
    pub outside: usize,
}

pub fn hud_difference(
    with: &image::RgbaImage,
    without: &image::RgbaImage,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
) -> HudDifference {
    assert_eq!(with.dimensions(), without.dimensions());
    let bright = |p: &image::Rgba<u8>| p[0] > 200 && p[1] > 200 && p[2] > 200;
    let mut d = HudDifference {
        inside: 0,
        glyphs: 0,
        outside: 0,
    };
    for (x, y, p) in with.enumerate_pixels() {
        let q = without.get_pixel(x, y);
        if p == q {
            continue;
        }
        if (x0..x1).contains(&x) && (y0..y1).contains(&y) {
            d.inside += 1;
            d.glyphs += usize::from(bright(p) && !bright(q));
        } else {
            d.outside += 1;
        }
    }
    d
}

/// What a run of the binary gave.
pub struct Run {
    pub success: bool,
    pub stdout: String,
    pub stderr: String,
}

/// Runs the binary in `cwd` with a time limit: a run that does not end in time (a FIFO
/// read, say) is killed and fails the test, naming `case`.
pub fn run_binary(
    case: &str,
    cwd: &std::path::Path,
    args: &[&str],
    limit: std::time::Duration,
) -> Run {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = Vec::new();
            let _ = r.read_to_end(&mut s);
            String::from_utf8_lossy(&s).into_owned()
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("[{case}] hangs: no exit after {limit:?} (shadowmap {args:?})");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Run {
        success: status.success(),
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

/// The CRC-32 PNG chunks carry.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// One PNG chunk: length, kind, body, CRC.
pub fn png_chunk(kind: &[u8; 4], body: &[u8]) -> Vec<u8> {
    let mut c = (body.len() as u32).to_be_bytes().to_vec();
    c.extend_from_slice(kind);
    c.extend_from_slice(body);
    let crc = crc32(&c[4..]);
    c.extend_from_slice(&crc.to_be_bytes());
    c
}

/// A PNG whose header claims `width` x `height` RGBA pixels with correct CRCs, and only a
/// few bytes of image data (a file small on disk that would be huge decoded).
pub fn png_claiming(width: u32, height: u32) -> Vec<u8> {
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]); // 8 bits, RGBA, deflate, no filter, no interlace
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(png_chunk(b"IHDR", &ihdr));
    // A zlib stream of a few zero bytes, far too short for the claimed size.
    png.extend(png_chunk(
        b"IDAT",
        &[
            0x78, 0x9c, 0x63, 0x60, 0x00, 0x02, 0x00, 0x00, 0x05, 0x00, 0x01,
        ],
    ));
    png.extend(png_chunk(b"IEND", &[]));
    png
}

/// One frame of `scene` under `settings` scored against the exact reference.
pub fn compared(
    scene: &Scene,
    settings: &ShadowSettings,
    o: &shadowmap::compare::CompareOptions,
) -> shadowmap::compare::Comparison {
    let ctx = context();
    shadowmap::compare::compare(ctx.gl(), scene, settings, o)
        .unwrap_or_else(|e| panic!("compare: {e}"))
}

/// Mean penumbra widths in pixels, (truth, rendered), across the shadow edges left of x = 0
/// and right of it (tests/data/contact.toml: the low slab, then the high one), from a
/// `width` x `height` comparison under a sized light.
pub fn penumbra_widths_by_side(
    c: &shadowmap::compare::Comparison,
    width: usize,
    height: usize,
) -> ((f64, f64), (f64, f64)) {
    let truth = &c.reference.area.as_ref().expect("a sized light").pixels;
    let vis = c.frame.visibility.as_deref().unwrap_or_default();
    let profiles = shadowmap::reference::penumbra_profiles(width, height, vis, truth);
    let side = |right: bool| {
        let p: Vec<_> = profiles
            .iter()
            .filter(|p| (c.reference.world_position(p.y * width + p.x).x > 0.0) == right)
            .collect();
        assert!(p.len() > 40, "{} edges on one side", p.len());
        let n = p.len() as f64;
        (
            p.iter().map(|p| p.truth_px).sum::<f64>() / n,
            p.iter().map(|p| p.rendered_px).sum::<f64>() / n,
        )
    };
    (side(false), side(true))
}

/// A scene file's start: a 3 x 3 floor at y = -1 lit from nearly overhead by a directional
/// light whose map covers it, seen from above; items follow.
pub const OVERHEAD_FLOOR: &str = "size = [320, 240]\n\
     [camera]\nposition = [0.0, 4.0, 3.0]\ntarget = [0.0, -1.0, 0.0]\n\
     [light]\ndirection = [0.15, 1.0, 0.1]\nshadow_pos_mult = 8.0\n\
     ortho = { left = -5.0, right = 5.0, bottom = -5.0, top = 5.0, near = -1.0, far = 12.0 }\n\
     [shadow]\nlight_view = \"look-at\"\nbias = 0.005\n\
     [[item]]\nname = \"floor\"\nmesh = \"plane\"\nposition = [0.0, -1.0, 0.0]\nscale = 3.0\n";

/// A 320 x 240 frame of `scene` with its translucent casters cast by `volumetric` and its
/// translucent items tested per pixel or per vertex (`receivers`).
pub fn translucent_frame(
    scene: &mut Scene,
    volumetric: shadowmap::settings::Volumetric,
    receivers: shadowmap::settings::TranslucentReceivers,
) -> Frame {
    let settings = ShadowSettings {
        volumetric,
        translucent_receivers: receivers,
        ..scene.shadow
    };
    render(&context(), scene, &settings, 320, 240)
}
