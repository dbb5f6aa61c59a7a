//! Property tests over the two parsers a user feeds files to: scene TOML and OBJ models.
//! Whatever the input, they return a value or an error, never panic; what they accept is
//! valid. Each test prints how many inputs it ran.

use std::cell::Cell;
use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use shadowmap::geometry::MeshData;
use shadowmap::scene::file::parse;

const CASES: u32 = 3000;

fn runner() -> TestRunner {
    TestRunner::new(Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    })
}

const DUMMY: &str = include_str!("../../assets/scenes/dummy.toml");

/// Numbers a scene or a model might hold, including the awkward ones.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f32>().prop_map(|v| format!("{v:?}")),
        (-10i64..10).prop_map(|v| v.to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e39".to_string()),
        Just("0".to_string()),
        Just("-0.0".to_string()),
        Just("\"x\"".to_string()),
    ]
}

#[test]
fn scene_parser_never_panics() {
    let count = Cell::new(0u32);
    // Arbitrary text.
    runner()
        .run(&".{0,400}", |text| {
            count.set(count.get() + 1);
            let _ = parse(&text, Path::new("fuzz.toml"), None);
            Ok(())
        })
        .unwrap();
    // The DummyGame's file with one value replaced: every field meets strange numbers.
    let numbers: Vec<usize> = DUMMY
        .match_indices(|c: char| c.is_ascii_digit())
        .map(|(i, _)| i)
        .collect();
    runner()
        .run(&(0..numbers.len(), number()), |(k, replacement)| {
            count.set(count.get() + 1);
            let at = numbers[k];
            let text = format!("{}{}{}", &DUMMY[..at], replacement, &DUMMY[at + 1..]);
            if let Ok(scene) = parse(&text, Path::new("fuzz.toml"), None) {
                // Whatever is accepted is usable: finite camera, positive scales.
                prop_assert!(scene.camera.near > 0.0 && scene.camera.near < scene.camera.far);
                prop_assert!(scene.items.iter().all(|i| i.scale.min_element() > 0.0));
                prop_assert!(scene.items.iter().all(|i| i.position.is_finite()));
            }
            Ok(())
        })
        .unwrap();
    // Random edits: delete or duplicate a span of the file.
    runner()
        .run(
            &(0..DUMMY.len(), 0usize..40, any::<bool>()),
            |(at, len, dup)| {
                count.set(count.get() + 1);
                let mut at = at.min(DUMMY.len());
                while !DUMMY.is_char_boundary(at) {
                    at -= 1;
                }
                let mut end = (at + len).min(DUMMY.len());
                while !DUMMY.is_char_boundary(end) {
                    end -= 1;
                }
                let text = if dup {
                    format!("{}{}", &DUMMY[..end], &DUMMY[at..])
                } else {
                    format!("{}{}", &DUMMY[..at], &DUMMY[end..])
                };
                let _ = parse(&text, Path::new("fuzz.toml"), None);
                Ok(())
            },
        )
        .unwrap();
    eprintln!("scene parser: {} inputs, no panic", count.get());
}

/// One OBJ line: vertices, texture coordinates, normals, faces (with any indices), junk.
fn obj_line() -> impl Strategy<Value = String> {
    let index = prop_oneof![
        (-6i64..12).prop_map(|i| i.to_string()),
        Just("x".to_string()),
        Just(String::new())
    ];
    let corner = (index.clone(), index.clone(), index).prop_map(|(a, b, c)| {
        match (b.is_empty(), c.is_empty()) {
            (true, true) => a,
            (false, true) => format!("{a}/{b}"),
            _ => format!("{a}/{b}/{c}"),
        }
    });
    prop_oneof![
        prop::collection::vec(number(), 2..5).prop_map(|n| format!("v {}", n.join(" "))),
        prop::collection::vec(number(), 1..4).prop_map(|n| format!("vt {}", n.join(" "))),
        prop::collection::vec(number(), 2..5).prop_map(|n| format!("vn {}", n.join(" "))),
        prop::collection::vec(corner, 0..7).prop_map(|c| format!("f {}", c.join(" "))),
        Just("o part".to_string()),
        Just("usemtl x".to_string()),
        Just("# comment".to_string()),
        ".{0,20}",
    ]
}

#[test]
fn obj_reader_never_panics_and_accepts_only_valid_meshes() {
    let count = Cell::new(0u32);
    runner()
        .run(&prop::collection::vec(obj_line(), 0..30), |lines| {
            count.set(count.get() + 1);
            let text = lines.join("\n");
            if let Ok(mesh) = MeshData::parse_obj(Path::new("fuzz.obj"), &text) {
                prop_assert!(mesh.validate().is_ok());
                let n = mesh.positions.len() as u32;
                prop_assert!(mesh.indices.iter().all(|&i| i < n));
                prop_assert!(mesh.normals.iter().flatten().all(|v| v.is_finite()));
            }
            Ok(())
        })
        .unwrap();
    runner()
        .run(&prop::collection::vec(any::<u8>(), 0..300), |bytes| {
            count.set(count.get() + 1);
            let text = String::from_utf8_lossy(&bytes);
            let _ = MeshData::parse_obj(Path::new("fuzz.obj"), &text);
            Ok(())
        })
        .unwrap();
    eprintln!("OBJ reader: {} inputs, no panic", count.get());
}
