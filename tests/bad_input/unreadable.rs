//! Inputs that are not regular files or are too large: refused without blocking or reading
//! them whole.

use std::path::Path;
use std::process::Command;

use crate::{bad_scene, case_dir, check_error, render, report};

/// `mkfifo path`: a named pipe, which blocks whoever opens it for reading until a writer
/// comes (none will).
fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
}

/// Runs `render` on a scene in `dir` (made by the caller) and checks the error.
fn bad_prepared(case: &str, dir: &Path, needles: &[&str]) -> Option<String> {
    let scene = dir.join("scene.toml");
    let (run, out) = render(case, Path::new("."), scene.to_str().unwrap(), &[]);
    check_error(case, &run, &out, needles)
}

#[test]
fn unreadable_inputs_are_refused_without_blocking() {
    let obj_scene = b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"model.obj\"\n";

    let fifo_scene = case_dir("fifo-scene-input");
    mkfifo(&fifo_scene.join("scene.toml"));

    let zero_scene = case_dir("zero-scene-input");
    std::os::unix::fs::symlink("/dev/zero", zero_scene.join("scene.toml")).unwrap();

    // 65 MiB without writing them: a sparse file.
    let huge_scene = case_dir("huge-scene-input");
    std::fs::File::create(huge_scene.join("scene.toml"))
        .unwrap()
        .set_len(65 << 20)
        .unwrap();

    let folder_scene = case_dir("folder-scene-input");
    std::fs::create_dir(folder_scene.join("scene.toml")).unwrap();

    let fifo_obj = case_dir("fifo-obj-input");
    std::fs::write(fifo_obj.join("scene.toml"), obj_scene).unwrap();
    mkfifo(&fifo_obj.join("model.obj"));

    let zero_obj = case_dir("zero-obj-input");
    std::fs::write(zero_obj.join("scene.toml"), obj_scene).unwrap();
    std::os::unix::fs::symlink("/dev/zero", zero_obj.join("model.obj")).unwrap();

    let huge_obj = case_dir("huge-obj-input");
    std::fs::write(huge_obj.join("scene.toml"), obj_scene).unwrap();
    std::fs::File::create(huge_obj.join("model.obj"))
        .unwrap()
        .set_len(513 << 20)
        .unwrap();

    let not_regular = "it is not a regular file but";
    report(vec![
        bad_prepared(
            "scene is a FIFO",
            &fifo_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a FIFO",
            ],
        ),
        bad_prepared(
            "scene is /dev/zero",
            &zero_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a character device",
            ],
        ),
        bad_prepared(
            "scene over 64 MiB",
            &huge_scene,
            &["scene.toml: cannot read scene file: it is larger than the limit of 64 MiB"],
        ),
        bad_prepared(
            "scene is a folder",
            &folder_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a folder",
            ],
        ),
        bad_prepared(
            "obj is a FIFO",
            &fifo_obj,
            &[
                "item[0].mesh: ",
                "model.obj: cannot read OBJ model: ",
                not_regular,
                "a FIFO",
            ],
        ),
        bad_prepared(
            "obj is /dev/zero",
            &zero_obj,
            &[
                "item[0].mesh: ",
                "model.obj: cannot read OBJ model: ",
                not_regular,
                "a character device",
            ],
        ),
        bad_prepared(
            "obj over 512 MiB",
            &huge_obj,
            &["model.obj: cannot read OBJ model: it is larger than the limit of 512 MiB"],
        ),
        bad_scene(
            "obj face of two vertices",
            "obj_degenerate_face.toml",
            &[
                "item[0].mesh: ",
                "obj_degenerate_face.obj: not a valid OBJ model at line 5: a face with 2 \
                 corners: expected at least three",
                "refused, not dropped",
            ],
        ),
        bad_scene(
            "obj index that wraps in 32 bits",
            "obj_index_wrap.toml",
            &[
                "obj_index_wrap.obj: not a valid OBJ model at line 5: face index out of \
                 range: '4294967297', but there are 3 'v' lines before it",
            ],
        ),
    ]);
}
