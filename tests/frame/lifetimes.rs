//! GL objects are freed by their owners: creating and dropping them many times leaves the
//! process's memory flat and their names deleted.

use crate::common;

use shadowmap::engine::check::object_exists;
use shadowmap::engine::{
    AdjacencyMesh, Mesh, MomentMap, RenderTarget, SamplesQuery, ShaderProgram, ShadowMap, Texture,
};
use shadowmap::geometry::MeshData;
use shadowmap::image_data::ImageData;
use shadowmap::settings::{DepthFormat, MapSize};
use shadowmap::shaders;
use shadowmap::shadows::volumes::Adjacency;

fn resident_kib() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
    statm
        .split_whitespace()
        .nth(1)
        .unwrap()
        .parse::<u64>()
        .unwrap()
        * 4
}

/// Runs `make` `n` times after a warm-up, and returns the resident-memory growth in KiB
/// between the end of the warm-up and the end.
fn growth(n: usize, mut make: impl FnMut()) -> i64 {
    for _ in 0..n / 10 {
        make();
    }
    let before = resident_kib() as i64;
    for _ in 0..n {
        make();
    }
    resident_kib() as i64 - before
}

/// A name, how many to make, and how to make (and drop) one.
type Case<'a> = (&'static str, usize, Box<dyn FnMut() + 'a>);

/// The process's resident memory is the measure, so the cases run in a process of their own
/// ([`objects_in_a_process_of_their_own`]): the area's other tests, running beside them,
/// would grow it too.
#[test]
fn ten_thousand_objects_leave_memory_flat_and_names_deleted() {
    let name = "lifetimes::objects_in_a_process_of_their_own";
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            name,
            "--exact",
            "--ignored",
            "--test-threads=1",
            "--nocapture",
        ])
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    eprintln!("{text}");
    assert!(out.status.success(), "the cases failed:\n{text}");
    assert!(text.contains("1 passed"), "the cases did not run:\n{text}");
}

#[test]
#[ignore = "run alone, in its own process, by ten_thousand_objects_leave_memory_flat_and_names_deleted"]
fn objects_in_a_process_of_their_own() {
    let ctx = common::context();
    let gl = ctx.gl();
    let cube = MeshData::cube();
    let image = ImageData::wood(64);
    let mut last = None;
    let mut last_moments = None;
    let cases: Vec<Case> = vec![
        (
            "shadow map 64^2",
            10_000,
            Box::new(|| {
                let m = ShadowMap::new(gl, 64, DepthFormat::D24).unwrap();
                last = Some(m.depth_map_texture().id());
            }),
        ),
        (
            "moment map 64^2 (two RGBA32F textures, a depth buffer, two framebuffers)",
            10_000,
            Box::new(|| {
                let m = MomentMap::new(gl, MapSize::square(64), 4).unwrap();
                last_moments = Some(m.texture().id());
            }),
        ),
        (
            "texture 64^2",
            10_000,
            Box::new(|| drop(Texture::from_image(gl, &image).unwrap())),
        ),
        (
            "mesh (cube)",
            10_000,
            Box::new(|| drop(Mesh::new(gl, &cube).unwrap())),
        ),
        (
            "mesh with adjacency (cube)",
            10_000,
            Box::new(|| {
                let adjacency = Adjacency::of(&cube);
                drop(AdjacencyMesh::new(gl, "cube", &cube.positions, &adjacency.indices).unwrap())
            }),
        ),
        (
            "samples-passed query",
            10_000,
            Box::new(|| drop(SamplesQuery::new(gl).unwrap())),
        ),
        (
            "render target 64x64",
            10_000,
            Box::new(|| drop(RenderTarget::new(gl, 64, 64, Default::default()).unwrap())),
        ),
        // Compiling is slow on a software driver; a tenth as many programs.
        (
            "program",
            1_000,
            Box::new(|| {
                drop(
                    ShaderProgram::new(gl, &shaders::depth_vert(), &shaders::depth_frag(), &[])
                        .unwrap(),
                )
            }),
        ),
    ];
    for (name, n, make) in cases {
        let kib = growth(n, make);
        eprintln!("{name}: {n} created and dropped, resident memory {kib:+} KiB");
        assert!(
            kib < 4096,
            "{name}: memory grew by {kib} KiB over {n} objects"
        );
    }
    shadowmap::engine::check_gl(gl, "creating and dropping objects").unwrap();
    // The last shadow map's texture name is gone with it.
    let id = last.expect("made at least one");
    assert!(
        !object_exists(gl, id),
        "a dropped texture is still a texture"
    );
    let id = last_moments.expect("made at least one");
    assert!(
        !object_exists(gl, id),
        "a dropped moment map's texture is still a texture"
    );
    let kept = Texture::colour(gl, 4, 4).unwrap();
    assert!(object_exists(gl, kept.id()), "a live texture must exist");
}
