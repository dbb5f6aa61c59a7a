//! The chapters' debug views on the DummyGame, where they were hardest to read: the cascade
//! tints tell apart on its pure blue floor, and the depth view shows the cube against the
//! floor (the book's 20 x 20 box around a 5-unit scene left both nearly white).

use crate::common;

use shadowmap::ShadowSettings;

/// A pixel's hue in degrees and its saturation (HSV).
fn hue_saturation(p: &[u8]) -> (f32, f32) {
    let [r, g, b] = [p[0], p[1], p[2]].map(|c| f32::from(c) / 255.0);
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    if max <= 0.0 || max == min {
        return (0.0, 0.0);
    }
    let d = max - min;
    let h = match max {
        m if m == r => 60.0 * ((g - b) / d).rem_euclid(6.0),
        m if m == g => 60.0 * ((b - r) / d + 2.0),
        _ => 60.0 * ((r - g) / d + 4.0),
    };
    (h, d / max)
}

/// The mean hue (degrees) of the DummyGame's lit floor pixels of saturation 0.2 or more,
/// and the share of the floor they are.
fn floor_hue(settings: &ShadowSettings) -> (f32, f32) {
    let ctx = common::context();
    let mut scene = common::dummy(45.0);
    let frame = common::render(&ctx, &mut scene, settings, 320, 180);
    let pos = frame.world_positions().unwrap();
    let nrm = frame.normals.as_ref().unwrap();
    let vis = frame.visibility.as_ref().unwrap();
    let (mut floor, mut coloured, mut x, mut y) = (0, 0, 0.0f32, 0.0f32);
    for (i, p) in frame.colour.rgba.chunks_exact(4).enumerate() {
        let lit_floor =
            (pos[i][1] + 1.0).abs() < 1e-3 && nrm[i][1] > 0.99 && vis[i].is_some_and(|v| v > 0.5);
        if !lit_floor {
            continue;
        }
        floor += 1;
        let (h, s) = hue_saturation(p);
        if s >= 0.2 {
            coloured += 1;
            x += h.to_radians().cos();
            y += h.to_radians().sin();
        }
    }
    assert!(
        floor > 10_000,
        "the lit floor fills the view: {floor} pixels"
    );
    let hue = y.atan2(x).to_degrees().rem_euclid(360.0);
    (hue, coloured as f32 / floor as f32)
}

/// The difference of two hues in degrees (0 to 180).
fn hue_gap(a: f32, b: f32) -> f32 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

/// From the DummyGame's camera the floor lies in the last cascade: with 2, 3 and 4 cascades
/// tinted it is in the second, third and fourth, and each of those tints turns the pure
/// blue floor a hue of its own, at least 40 degrees from the others (a product with the
/// tint left all three the floor's blue, only darker).
#[test]
fn cascade_tints_tell_apart_on_the_blue_floor() {
    let scene = common::dummy(45.0);
    let plain = ShadowSettings {
        map_size: 512.into(),
        ..scene.shadow
    };
    let mut hues: Vec<f32> = Vec::new();
    for cascades in 2..=4 {
        let tinted = ShadowSettings {
            cascades,
            show_cascades: true,
            ..plain
        };
        let (hue, share) = floor_hue(&tinted);
        eprintln!("{cascades} cascades tinted: the floor's hue {hue:.0} ({share:.2} of it)");
        assert!(
            share > 0.9,
            "{cascades} cascades: {share} of the floor coloured"
        );
        for (k, other) in hues.iter().enumerate() {
            assert!(
                hue_gap(hue, *other) >= 40.0,
                "{cascades} cascades: hue {hue:.0} against {other:.0} (#{k})"
            );
        }
        hues.push(hue);
    }
}

/// The depth view of the DummyGame: the cube's texels against the floor's texels around it
/// differ by at least 40 grey levels (shown as stored, 21 units of depth over 255 levels,
/// they differed by 21).
#[test]
fn the_depth_view_shows_the_cube_against_the_floor() {
    const SIZE: u32 = 256;
    let ctx = common::context();
    let scene = common::dummy(45.0);
    let settings = ShadowSettings {
        map_size: SIZE.into(),
        show_depth_map: true,
        ..scene.shadow
    };
    // The map's raw depths with and without the cube: where they differ, the cube.
    let mut full = scene.clone();
    let view = common::render(&ctx, &mut full, &settings, SIZE, SIZE);
    let raw = view.depth_map.clone().expect("a 2D map").1;
    let mut floor_only = scene.clone();
    floor_only.items.retain(|i| i.name != "cube");
    let bare = common::render(&ctx, &mut floor_only, &settings, SIZE, SIZE)
        .depth_map
        .expect("a 2D map")
        .1;
    let cube: Vec<bool> = raw.iter().zip(&bare).map(|(a, b)| *a < b - 1e-4).collect();
    let n = SIZE as usize;
    // The floor's texels within 4 texels of the cube.
    let near_cube = |i: usize| {
        let (x, y) = ((i % n) as i64, (i / n) as i64);
        (-4..=4).any(|dy| {
            (-4..=4).any(|dx| {
                let (u, v) = (x + dx, y + dy);
                (0..n as i64).contains(&u)
                    && (0..n as i64).contains(&v)
                    && cube[(v * n as i64 + u) as usize]
            })
        })
    };
    let grey = |i: usize| f64::from(view.colour.rgba[4 * i]);
    let (mut cube_sum, mut cube_n, mut ring_sum, mut ring_n) = (0.0, 0, 0.0, 0);
    for i in 0..n * n {
        if cube[i] {
            cube_sum += grey(i);
            cube_n += 1;
        } else if raw[i] < 1.0 && (raw[i] - bare[i]).abs() < 1e-6 && near_cube(i) {
            ring_sum += grey(i);
            ring_n += 1;
        }
    }
    assert!(
        cube_n > 50 && ring_n > 50,
        "cube {cube_n}, floor {ring_n} texels"
    );
    let (cube_grey, ring_grey) = (cube_sum / cube_n as f64, ring_sum / ring_n as f64);
    eprintln!(
        "depth view: cube {cube_grey:.1} ({cube_n} texels), the floor around it {ring_grey:.1} \
         ({ring_n} texels)"
    );
    assert!(
        ring_grey - cube_grey >= 40.0,
        "cube {cube_grey:.1} against the floor {ring_grey:.1}"
    );
    // The caption's range: the casters' depths, inside the light's near..far.
    let range = view.depth_view_range.expect("a range for a 2D map");
    assert!(range.near <= range.black && range.black < range.white && range.white <= range.far);
    assert!(
        range.white - range.black < 0.5 * (range.far - range.near),
        "{range:?}"
    );
}
