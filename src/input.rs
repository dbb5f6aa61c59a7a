//! Reading the files a user names (scenes, models, textures) without trusting them: only
//! regular files, and never more than a stated number of bytes. A FIFO would block the
//! loader forever and `/dev/zero` would grow memory until the machine gives up; both are
//! refused before they are opened.
//!
//! Also here: [`check_args`], the examples' command lines checked before any work.

use std::io::Read;
use std::path::Path;
use std::process::ExitCode;

use crate::error::{Error, Result};

/// The largest scene file read (a scene is a page of TOML; this is already absurd).
pub const SCENE_LIMIT: u64 = 64 << 20;
/// The largest OBJ model read (several million triangles).
pub const OBJ_LIMIT: u64 = 512 << 20;

/// Reads the whole of `path`, which must be a regular file (after following symbolic links)
/// of at most `limit` bytes.
///
/// `what` names the file's role in messages, e.g. "scene file", "OBJ model", "texture":
/// every error reads `{path}: cannot read {what}: {reason}`, where the reason is the
/// system's ("No such file or directory (os error 2)"), "it is not a regular file but a
/// FIFO", or "it is larger than the limit of 64 MiB".
pub fn read_regular_file(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>> {
    let fail = |reason: String| Error::file(path, format!("cannot read {what}: {reason}"));
    let too_big = || {
        fail(format!(
            "it is larger than the limit of {}",
            size_text(limit)
        ))
    };
    let meta = std::fs::metadata(path).map_err(|e| fail(e.to_string()))?;
    if !meta.is_file() {
        return Err(fail(format!(
            "it is not a regular file but {}",
            kind_of(&meta.file_type())
        )));
    }
    if meta.len() > limit {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(|e| fail(e.to_string()))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // One byte past the limit tells a file that grew since `metadata` from one that fits.
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| fail(e.to_string()))?;
    if bytes.len() as u64 > limit {
        return Err(too_big());
    }
    Ok(bytes)
}

/// Turns bytes read from `path` into text, or says where the first byte that is not UTF-8
/// is (`{path}: cannot read {what}: line 3, column 7: byte 0xff is not UTF-8 text`).
pub fn utf8_text(path: &Path, bytes: Vec<u8>, what: &str) -> Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        let good = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = &bytes[..good];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        // Columns count characters, as an editor shows them; the prefix is valid UTF-8.
        let column = String::from_utf8_lossy(&before[line_start..])
            .chars()
            .count()
            + 1;
        // error_len() is None when the text stops in the middle of a character.
        let shown = match (e.utf8_error().error_len(), bytes.get(good)) {
            (Some(_), Some(b)) => format!("byte {b:#04x} is not UTF-8 text"),
            _ => String::from("the file ends inside a UTF-8 character"),
        };
        Error::file(
            path,
            format!("cannot read {what}: line {line}, column {column}: {shown}"),
        )
    })
}

/// `read_regular_file` then `utf8_text`.
pub fn read_text_file(path: &Path, limit: u64, what: &str) -> Result<String> {
    utf8_text(path, read_regular_file(path, limit, what)?, what)
}

/// "64 MiB" for whole mebibytes, bytes otherwise.
fn size_text(bytes: u64) -> String {
    if bytes >= 1 << 20 && bytes.is_multiple_of(1 << 20) {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

fn kind_of(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a folder"
    } else {
        "something else"
    }
}

/// The examples' command lines, before any work: `--help` (or `-h`) prints the usage and
/// succeeds; an option the example does not take, or a wrong count of arguments (`count`),
/// is refused with the usage and exit status 2.
pub fn check_args(
    args: &[String],
    count: std::ops::RangeInclusive<usize>,
    usage: &str,
) -> std::result::Result<(), ExitCode> {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{usage}");
        return Err(ExitCode::SUCCESS);
    }
    let problem = match args
        .iter()
        .find(|a| a.starts_with('-') && a.parse::<f64>().is_err())
    {
        Some(option) => format!("unknown option '{option}'"),
        None if !count.contains(&args.len()) => format!(
            "expected {} argument{}, got {}",
            match count.start() == count.end() {
                true => count.start().to_string(),
                false => format!("{} to {}", count.start(), count.end()),
            },
            if *count.end() == 1 { "" } else { "s" },
            args.len()
        ),
        None => return Ok(()),
    };
    eprintln!("error: {problem}\n\n{usage}");
    Err(ExitCode::from(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("shadowmap-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    #[test]
    fn devices_and_folders_are_refused_without_reading() {
        let e = read_regular_file(Path::new("/dev/zero"), 100, "scene file")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "/dev/zero: cannot read scene file: it is not a regular file but a character device"
        );
        let e = read_regular_file(Path::new("/"), 100, "OBJ model")
            .unwrap_err()
            .to_string();
        assert!(e.ends_with("is not a regular file but a folder"), "{e}");
    }

    #[test]
    fn the_limit_is_inclusive_and_named() {
        let path = temp("ten.txt", b"0123456789");
        assert_eq!(read_regular_file(&path, 10, "x").unwrap().len(), 10);
        let e = read_regular_file(&path, 9, "scene file")
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with("cannot read scene file: it is larger than the limit of 9 bytes"),
            "{e}"
        );
        assert_eq!(size_text(64 << 20), "64 MiB");
    }

    #[test]
    fn bad_utf8_names_line_and_column() {
        let path = Path::new("s.toml");
        let e = utf8_text(
            path,
            b"a = 1\nb = \"\xc3\xa9\xff\"\n".to_vec(),
            "scene file",
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "s.toml: cannot read scene file: line 2, column 7: byte 0xff is not UTF-8 text"
        );
        let e = utf8_text(path, b"ab\xe2\x82".to_vec(), "scene file")
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with("line 1, column 3: the file ends inside a UTF-8 character"),
            "{e}"
        );
    }
}
