//! Reading a file a user named (every reader reads regular files only,
//! up to a size limit). Scene files and the files they reference, STEP files, KBL
//! files, calibration specs and CSVs and session logs all come through
//! [`read_regular_file`] (or [`read_regular_text`]):
//!
//! - only a regular file is read: a FIFO, a device such as `/dev/zero`, a socket or a
//!   folder is refused — also behind a link — *before* it is opened (opening a FIFO
//!   would block until a writer comes), and checked again on the opened file (the name
//!   may have been swapped in between; the file is opened non-blocking, so a FIFO
//!   swapped in cannot block either);
//! - at most `max_bytes` are read: checked before reading and enforced while reading
//!   (a file that grows meanwhile is cut off, not followed).
//!
//! Each reader states its own limit next to its format (for instance
//! [`MAX_LOG_BYTES`] for session logs); errors name the file and the reason.

use std::fmt;
use std::fs::{File, Metadata};
use std::io::Read;
use std::path::Path;

/// Largest session log read \[bytes\]: a day of a live session with a hand moved 90
/// times a second writes about 0.8 GB.
pub const MAX_LOG_BYTES: u64 = 1 << 30;

/// Why a file was not read; names the file.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {kind}")]
pub struct FileError {
    /// The file as named by the caller.
    pub path: String,
    pub kind: FileErrorKind,
}

/// Why a file was not read, without naming it (for messages that must not show paths).
#[derive(Debug, thiserror::Error)]
pub enum FileErrorKind {
    #[error("cannot read: {0}")]
    Open(std::io::Error),
    #[error("is {0}, not a regular file (only regular files are read)")]
    NotRegular(&'static str),
    #[error("has {len} bytes; at most {max} are read")]
    TooLarge { len: u64, max: u64 },
    #[error("cannot read: {0}")]
    Read(std::io::Error),
    #[error("is not UTF-8 text (byte {offset} is not)")]
    NotUtf8 { offset: usize },
}

impl FileErrorKind {
    /// As an I/O error: the system's own for a file that cannot be opened or read, else
    /// one saying why the file was not read.
    pub fn into_io(self) -> std::io::Error {
        match self {
            FileErrorKind::Open(e) | FileErrorKind::Read(e) => e,
            other => std::io::Error::other(other.to_string()),
        }
    }
}

/// Reads the regular file `path`, at most `max_bytes` of it (see the module).
pub fn read_regular_file(path: &Path, max_bytes: u64) -> Result<Vec<u8>, FileError> {
    let fail = |kind| FileError {
        path: path.display().to_string(),
        kind,
    };
    // metadata follows links: a link to a device or FIFO is refused here, unopened
    let meta = std::fs::metadata(path).map_err(|e| fail(FileErrorKind::Open(e)))?;
    check(&meta, max_bytes).map_err(fail)?;
    let file = open_without_blocking(path).map_err(|e| fail(FileErrorKind::Open(e)))?;
    let meta = file.metadata().map_err(|e| fail(FileErrorKind::Read(e)))?;
    check(&meta, max_bytes).map_err(fail)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| fail(FileErrorKind::Read(e)))?;
    if bytes.len() as u64 > max_bytes {
        return Err(fail(FileErrorKind::TooLarge {
            len: bytes.len() as u64,
            max: max_bytes,
        }));
    }
    Ok(bytes)
}

/// Reads the regular file `path` as UTF-8 text, at most `max_bytes` of it.
pub fn read_regular_text(path: &Path, max_bytes: u64) -> Result<String, FileError> {
    let bytes = read_regular_file(path, max_bytes)?;
    String::from_utf8(bytes).map_err(|e| FileError {
        path: path.display().to_string(),
        kind: FileErrorKind::NotUtf8 {
            offset: e.utf8_error().valid_up_to(),
        },
    })
}

/// A regular file within the size limit, or why not.
fn check(meta: &Metadata, max_bytes: u64) -> Result<(), FileErrorKind> {
    if !meta.is_file() {
        return Err(FileErrorKind::NotRegular(what_it_is(meta)));
    }
    if meta.len() > max_bytes {
        return Err(FileErrorKind::TooLarge {
            len: meta.len(),
            max: max_bytes,
        });
    }
    Ok(())
}

/// What a file that is not a regular file is, in words.
fn what_it_is(meta: &Metadata) -> &'static str {
    if meta.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

#[cfg(unix)]
fn open_without_blocking(path: &Path) -> std::io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

#[cfg(not(unix))]
fn open_without_blocking(path: &Path) -> std::io::Result<File> {
    File::open(path)
}

impl fmt::Display for ShownLimit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        if b >= 1024.0 * 1024.0 * 1024.0 {
            write!(f, "{:.1} GiB", b / (1024.0 * 1024.0 * 1024.0))
        } else if b >= 1024.0 * 1024.0 {
            write!(f, "{:.1} MiB", b / (1024.0 * 1024.0))
        } else {
            write!(f, "{} bytes", self.0)
        }
    }
}

/// A size limit \[bytes\] shown for people (`1.0 GiB`).
pub struct ShownLimit(pub u64);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_regular_file_within_the_limit() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.txt");
        std::fs::write(&p, "hello").unwrap();
        assert_eq!(read_regular_file(&p, 5).unwrap(), b"hello");
        assert_eq!(read_regular_text(&p, 100).unwrap(), "hello");
        let e = read_regular_file(&p, 4).unwrap_err();
        assert!(
            matches!(e.kind, FileErrorKind::TooLarge { len: 5, max: 4 }),
            "{e}"
        );
        assert!(e.to_string().contains("a.txt"), "{e}");
    }

    #[test]
    fn refuses_folders_devices_and_fifos_without_blocking() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_regular_file(dir.path(), 100).unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
        #[cfg(unix)]
        {
            let zero = dir.path().join("zero.csv");
            std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
            let e = read_regular_file(&zero, u64::MAX).unwrap_err();
            assert!(e.to_string().contains("a device"), "{e}");
            let fifo = dir.path().join("fifo.jsonl");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                let e = read_regular_file(&fifo, 100).unwrap_err();
                assert!(e.to_string().contains("FIFO"), "{e}");
            }
        }
    }

    #[test]
    fn text_that_is_not_utf8_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("b.csv");
        std::fs::write(&p, b"ab\xffcd").unwrap();
        let e = read_regular_text(&p, 100).unwrap_err();
        assert!(
            matches!(e.kind, FileErrorKind::NotUtf8 { offset: 2 }),
            "{e}"
        );
    }

    #[test]
    fn limits_are_shown_in_units() {
        assert_eq!(ShownLimit(MAX_LOG_BYTES).to_string(), "1.0 GiB");
        assert_eq!(ShownLimit(300).to_string(), "300 bytes");
    }
}
