//! Every file the program writes goes through [`write_file`], so a full disk, a missing
//! folder or a device that refuses bytes is an error naming the path, never a silent
//! success. The checks in [`check_output_file`] and [`check_output_dir`] run before any
//! rendering, so a bad path costs nothing and leaves nothing behind.
//!
//! Also here: [`Activity`], the progress a long command shows on standard error.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::error::{Error, Result};

/// Writes `bytes` to `path` and reports any failure, including the last flush.
///
/// A regular file (or a new one) is written to a temporary file in the same folder and
/// renamed over the target, so a failed write never leaves half a file under the real name.
/// Anything else that already exists (a device such as `/dev/full` or `/dev/stdout`, a FIFO)
/// is written in place. `what` says what the file is in the message ("the image").
pub fn write_file(path: &Path, what: &str, bytes: &[u8]) -> Result<()> {
    write_files(&[(path, what, bytes)])
}

/// Writes several files as one: every regular file is first written in full to a
/// temporary file beside it, then devices are written, and only when all of that worked are
/// the temporary files renamed into place. A failure (a full disk, `/dev/full`) leaves none
/// of the regular files behind (a temporary file not yet renamed is removed when dropped);
/// the error names the path that failed.
pub fn write_files(files: &[(&Path, &str, &[u8])]) -> Result<()> {
    let mut staged = Vec::new();
    let mut devices = Vec::new();
    for &(path, what, bytes) in files {
        let fail = |e: std::io::Error| Error::file(path, format!("cannot write {what}: {e}"));
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => {
                return Err(Error::file(
                    path,
                    format!("cannot write {what}: it is a folder; expected a file name"),
                ))
            }
            // A device or a pipe (also behind a link, as /dev/stdout is): in place.
            Ok(m) if !m.is_file() => devices.push((path, what, bytes)),
            _ => {
                // Through a symbolic link, replace the file it names, not the link.
                let target = link_target(path);
                let temp = write_new(&target, bytes).map_err(fail)?;
                staged.push((temp, target, path, what));
            }
        }
    }
    for (path, what, bytes) in devices {
        write_in_place(path, bytes)
            .map_err(|e| Error::file(path, format!("cannot write {what}: {e}")))?;
    }
    for (temp, target, path, what) in staged {
        temp.persist(&target)
            .map_err(|e| Error::file(path, format!("cannot write {what}: {}", e.error)))?;
    }
    Ok(())
}

/// Where the chain of symbolic links at `path` ends (existing or not): the file to replace.
fn link_target(path: &Path) -> PathBuf {
    let mut at = path.to_path_buf();
    // A loop of links is the OS's to report; stop following after as many as it allows.
    for _ in 0..40 {
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => match std::fs::read_link(&at) {
                Ok(next) => at = parent_of(&at).join(next),
                Err(_) => break,
            },
            _ => break,
        }
    }
    at
}

fn write_in_place(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .truncate(true)
        .open(path)?;
    file.write_all(bytes)?;
    file.flush()
}

/// The permissions of any new file (the umask decides), where the platform has Unix modes;
/// elsewhere the temporary file's default already is.
fn new_file_permissions() -> Option<std::fs::Permissions> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        Some(std::fs::Permissions::from_mode(0o666))
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// Writes `bytes` to a new hidden file beside `target` (removed when dropped, unless
/// persisted) and makes sure they reached the disk: some file systems report a full disk
/// only when the data is synced.
fn write_new(target: &Path, bytes: &[u8]) -> std::io::Result<tempfile::NamedTempFile> {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // As a file made by `File::create`: the umask decides (not tempfile's owner-only).
    if let Some(permissions) = new_file_permissions() {
        builder.permissions(permissions);
    }
    let mut file = builder.tempfile_in(parent_of(target))?;
    file.write_all(bytes)?;
    file.flush()?;
    file.as_file().sync_all()?;
    Ok(file)
}

/// The image formats an output file name may ask for (by its extension).
pub const IMAGE_EXTENSIONS: &[&str] = &["png"];

/// Checks, before any work, that `path` (given with `flag`) can be written: a known image
/// extension, an existing folder that accepts files, and not a folder itself.
pub fn check_output_image(flag: &str, path: &Path) -> Result<()> {
    check_not_a_folder(flag, path)?;
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some(e) if IMAGE_EXTENSIONS.contains(&e) => {}
        _ if is_device(path) => {}
        other => {
            return Err(Error::file(
                path,
                format!(
                    "cannot write {} images (given to {flag}); expected a file name ending in {}",
                    other.map_or("extension-less".to_string(), |e| format!(".{e}")),
                    IMAGE_EXTENSIONS
                        .iter()
                        .map(|e| format!(".{e}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ))
        }
    }
    check_output_file(flag, path, "the image")
}

/// A folder given where an image file belongs (an existing one, or a name ending in `/`):
/// said as a folder, with a file name in it to write instead.
fn check_not_a_folder(flag: &str, path: &Path) -> Result<()> {
    let text = path.as_os_str().to_string_lossy();
    let exists = std::fs::metadata(path).is_ok_and(|m| m.is_dir());
    if !exists && !text.ends_with('/') {
        return Ok(());
    }
    let instead = Path::new(text.trim_end_matches('/')).join(match flag {
        "--shadow-out" => "shadow.png",
        "--depth-out" => "depth.png",
        _ => "frame.png",
    });
    Err(Error::file(
        path,
        format!(
            "cannot write the image (given to {flag}): {}; expected a file name such as {}",
            match exists {
                true => "it is a folder",
                false => "it names a folder",
            },
            instead.display()
        ),
    ))
}

/// True for an existing path that is neither a file nor a folder (`/dev/stdout`, a FIFO):
/// written in place, whatever its name.
fn is_device(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Checks, before any work, that a file can be written at `path`: its folder exists and
/// accepts new files, and `path` is not a folder.
pub fn check_output_file(flag: &str, path: &Path, what: &str) -> Result<()> {
    let bad = |m: String| {
        Err(Error::file(
            path,
            format!("cannot write {what} (given to {flag}): {m}"),
        ))
    };
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => return bad("it is a folder; expected a file name".into()),
        Ok(m) if !m.is_file() => return Ok(()),
        _ => {}
    }
    if path.file_name().is_none() {
        return bad("expected a file name".into());
    }
    let folder = parent_of(path);
    match std::fs::metadata(&folder) {
        Ok(m) if m.is_dir() => probe(&folder).or_else(bad),
        Ok(_) => bad(format!("{} is a file, not a folder", folder.display())),
        Err(e) => bad(format!(
            "the folder {} does not exist ({e}); expected an existing folder",
            folder.display()
        )),
    }
}

/// Checks, before any work, that the output folder `dir` exists or can be created: the
/// nearest part of it that exists must be a folder that accepts new entries. Creates
/// nothing; [`create_output_dir`] does that when there is something to write.
pub fn check_output_dir(flag: &str, dir: &Path) -> Result<()> {
    let bad = |m: String| {
        Err(Error::file(
            dir,
            format!("cannot use it as the output folder (given to {flag}): {m}"),
        ))
    };
    let mut existing = dir.to_path_buf();
    loop {
        match std::fs::metadata(&existing) {
            Ok(m) if m.is_dir() => break,
            Ok(_) if existing == dir => return bad("it is a file; expected a folder".into()),
            Ok(_) => {
                return bad(format!(
                    "{} is a file, so no folder can be made inside it",
                    existing.display()
                ))
            }
            Err(_) => match existing.parent() {
                Some(p) if !p.as_os_str().is_empty() => existing = p.to_path_buf(),
                _ => {
                    existing = PathBuf::from(".");
                    break;
                }
            },
        }
    }
    probe(&existing).or_else(bad)
}

/// Creates the output folder (checked earlier by [`check_output_dir`]).
/// Creates `dir` and writes `files` (a name in it, what the file is, its bytes) there as
/// one batch ([`write_files`]: all of them or none).
pub fn write_into<B: AsRef<[u8]>>(dir: &Path, files: &[(&str, &str, B)]) -> Result<()> {
    create_output_dir(dir)?;
    let paths: Vec<PathBuf> = files.iter().map(|(name, ..)| dir.join(name)).collect();
    let batch: Vec<(&Path, &str, &[u8])> = files
        .iter()
        .zip(&paths)
        .map(|((_, what, bytes), path)| (path.as_path(), *what, bytes.as_ref()))
        .collect();
    write_files(&batch)
}

pub fn create_output_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::file(dir, format!("cannot create the output folder: {e}")))
}

/// The folder a file is written into (`.` for a bare file name).
fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Tries to create (and removes) a file in `folder`: permissions alone do not tell, since
/// root ignores them and some file systems (/proc) refuse new files whatever they say.
fn probe(folder: &Path) -> std::result::Result<(), String> {
    let probe = folder.join(format!(".shadowmap-probe.{}.tmp", std::process::id()));
    match std::fs::File::create(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(format!(
            "the folder {} does not accept new files ({e})",
            folder.display()
        )),
    }
}

/// What a long command is doing, on standard error: a spinner with the elapsed time on a
/// terminal; otherwise (a log, a pipe) one line, begun when it starts and ended with what came
/// of it.
pub struct Activity {
    bar: Option<indicatif::ProgressBar>,
    what: String,
    start: Instant,
    finished: bool,
}

impl Activity {
    /// Starts showing `what` ("tracing the reference") at once.
    pub fn start(what: impl Into<String>) -> Activity {
        let what = what.into();
        let bar = match std::io::stderr().is_terminal() {
            true => {
                let bar = indicatif::ProgressBar::new_spinner();
                bar.set_style(
                    indicatif::ProgressStyle::with_template("{spinner} {msg} [{elapsed}]")
                        .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
                );
                bar.set_message(what.clone());
                bar.enable_steady_tick(Duration::from_millis(120));
                Some(bar)
            }
            false => {
                // The line is ended by `done` (or by the drop of an unfinished activity), so
                // a log shows each activity once, with its result.
                eprint!("{what} ... ");
                None
            }
        };
        Activity {
            bar,
            what,
            start: Instant::now(),
            finished: false,
        }
    }

    /// Ends the activity saying how long it took in all and, if given, what came of it.
    pub fn done(mut self, result: &str) {
        let secs = self.start.elapsed().as_secs_f64();
        let outcome = match result.is_empty() {
            true => format!("done in {secs:.1} s"),
            false => format!("{result}; {secs:.1} s in all"),
        };
        self.finished = true;
        match &self.bar {
            Some(bar) => bar.finish_with_message(format!("{}: {outcome}", self.what)),
            None => eprintln!("{outcome}"),
        }
    }
}

impl Drop for Activity {
    fn drop(&mut self) {
        // An activity dropped by an error leaves no spinner, and no line unended, behind.
        match &self.bar {
            Some(bar) if !bar.is_finished() => bar.finish_and_clear(),
            None if !self.finished => eprintln!("stopped"),
            _ => {}
        }
    }
}

/// A counted activity (the bench's configurations): a bar on a terminal, or a line per
/// step otherwise.
pub struct Counter {
    bar: Option<indicatif::ProgressBar>,
    len: u64,
    pos: u64,
}

impl Counter {
    pub fn new(len: u64) -> Counter {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new(len);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} [{elapsed} < {eta}] {msg}",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            bar
        });
        Counter { bar, len, pos: 0 }
    }

    /// One more step done; `message` says what it was.
    pub fn step(&mut self, message: &str) {
        self.pos += 1;
        match &self.bar {
            Some(bar) => {
                bar.set_message(message.to_string());
                bar.inc(1);
            }
            None => eprintln!("[{}/{}] {message}", self.pos, self.len),
        }
    }

    pub fn finish(self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("shadowmap-output-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn writes_replace_and_leave_no_temporary_file() {
        let dir = scratch("replace");
        let path = dir.join("a.txt");
        write_file(&path, "the text", b"first").unwrap();
        write_file(&path, "the text", b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
        assert_eq!(names.len(), 1, "{names:?}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    #[cfg(unix)]
    fn a_written_file_gets_the_permissions_of_any_new_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("mode");
        let (plain, written) = (dir.join("plain.txt"), dir.join("written.txt"));
        std::fs::write(&plain, b"x").unwrap();
        write_file(&written, "the text", b"x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode();
        assert_eq!(mode(&written), mode(&plain));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    #[cfg(unix)]
    fn a_full_device_is_an_error_naming_the_path() {
        let err = write_file(Path::new("/dev/full"), "the image", &[0u8; 70_000]).unwrap_err();
        let text = err.to_string();
        assert!(
            text.starts_with("/dev/full: cannot write the image: "),
            "{text}"
        );
    }

    #[test]
    #[cfg(unix)]
    fn a_link_keeps_pointing_at_the_file_it_names() {
        let dir = scratch("link");
        let link = dir.join("link.png");
        std::os::unix::fs::symlink("real.png", &link).unwrap();
        write_file(&link, "the image", b"one").unwrap();
        write_file(&link, "the image", b"two").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(dir.join("real.png")).unwrap(), b"two");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_batch_with_one_failure_leaves_none_of_its_files() {
        let dir = scratch("batch");
        let (a, b) = (dir.join("a.png"), dir.join("b.json"));
        std::fs::write(&b, b"old").unwrap();
        let full = Path::new("/dev/full");
        let err = write_files(&[
            (&a, "the image", &[1u8; 100_000]),
            (&b, "the file", b"new"),
            (full, "the image", &[2u8; 100_000]),
        ])
        .unwrap_err()
        .to_string();
        assert!(
            err.starts_with("/dev/full: cannot write the image"),
            "{err}"
        );
        assert!(!a.exists(), "a.png was written");
        assert_eq!(std::fs::read(&b).unwrap(), b"old", "b.json was replaced");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
        assert_eq!(names.len(), 1, "temporary files left: {names:?}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_file_in_place_of_a_folder_is_refused_before_and_during_writing() {
        let dir = scratch("file-parent");
        let file = dir.join("plain");
        std::fs::write(&file, b"x").unwrap();
        let inside = file.join("x.png");
        let e = check_output_image("--out", &inside)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cannot write the image (given to --out): ")
                && e.contains("is a file, not a folder"),
            "{e}"
        );
        assert!(write_file(&inside, "the image", b"x").is_err());
        let e = check_output_dir("--out-dir", &file.join("sub"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("is a file, so no folder can be made inside it"),
            "{e}"
        );
        let e = check_output_dir("--out-dir", &file)
            .unwrap_err()
            .to_string();
        assert!(e.contains("it is a file; expected a folder"), "{e}");
        // A missing folder that could be made is fine, and nothing is created by the check.
        check_output_dir("--out-dir", &dir.join("new/deeper")).unwrap();
        assert!(!dir.join("new").exists());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn image_names_need_a_known_extension() {
        let e = check_output_image("--out", Path::new("x.jpg"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("x.jpg: cannot write .jpg images (given to --out); expected a file name ending in .png"), "{e}");
        let e = check_output_image("--out", Path::new("x"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("cannot write extension-less images"), "{e}");
        check_output_image("--out", Path::new("/dev/null")).unwrap();
    }
}
