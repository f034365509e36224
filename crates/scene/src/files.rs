//! Where a scene may read its mesh files (and a glTF file's buffers) from, and how much
//! it may read. Every read goes through [`FileAccess::read`]:
//!
//! - only regular files are read (a FIFO, a device such as `/dev/zero` or a folder is
//!   refused before it is opened, also behind a link), and at most
//!   [`FileAccess::max_file_bytes`] of them, checked before reading and enforced while
//!   reading (a file that grows meanwhile is cut off, not followed) — the reading every
//!   reader shares, [`pliant_files::read_regular_file`];
//! - a *sandboxed* access (scenes sent by `pliant serve`'s clients) resolves every path
//!   inside its folder: no absolute paths, no `..`, and links are followed only if
//!   their target stays inside. Its errors never quote a path outside the sandbox nor
//!   the content of a file, and do not tell a missing file from an unreadable one.

use crate::step_cache::ConverterChoice;
use std::path::{Component, Path, PathBuf};

/// Default cap on one mesh file \[bytes\] (a 256 MiB STL holds about 5 million triangles,
/// the per-part limit [`crate::MAX_TRIANGLES`]).
pub const DEFAULT_MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;

/// How a scene's relative file names are resolved and read.
#[derive(Clone, Debug)]
pub struct FileAccess {
    /// The folder relative names are resolved against (the sandbox's root).
    base_dir: PathBuf,
    /// In a sandbox: the folder (inside the root) names are relative to.
    subdir: PathBuf,
    /// Confine every read to `base_dir` and keep errors free of paths and content.
    sandboxed: bool,
    /// Largest file read \[bytes\].
    pub max_file_bytes: u64,
    /// What converts a STEP file the cache lacks ([`crate::step_cache`]).
    converter: ConverterChoice,
}

impl FileAccess {
    /// Files named relative to `base_dir` (absolute names allowed): a scene on the
    /// user's own disk, loaded by the user.
    pub fn local(base_dir: &Path) -> FileAccess {
        FileAccess {
            base_dir: base_dir.to_path_buf(),
            subdir: PathBuf::new(),
            sandboxed: false,
            max_file_bytes: DEFAULT_MAX_FILE_BYTES,
            converter: ConverterChoice::default(),
        }
    }

    /// Files only inside `root` (a scene sent by a client of `pliant serve`).
    pub fn sandbox(root: &Path) -> FileAccess {
        FileAccess {
            base_dir: root.to_path_buf(),
            subdir: PathBuf::new(),
            sandboxed: true,
            max_file_bytes: DEFAULT_MAX_FILE_BYTES,
            converter: ConverterChoice::default(),
        }
    }

    /// The same access with another size cap.
    pub fn with_max_file_bytes(mut self, bytes: u64) -> FileAccess {
        self.max_file_bytes = bytes;
        self
    }

    /// The same access converting STEP files with `converter`.
    pub fn with_converter(mut self, converter: ConverterChoice) -> FileAccess {
        self.converter = converter;
        self
    }

    /// What converts a STEP file the cache lacks.
    pub fn converter(&self) -> ConverterChoice {
        self.converter
    }

    /// The folder relative names are resolved against.
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    /// Whether reads are confined to the base folder.
    pub fn is_sandboxed(&self) -> bool {
        self.sandboxed
    }

    /// The same access for names relative to the folder of the file `name` (a glTF
    /// file's buffers), still confined to the same sandbox.
    pub fn beside(&self, name: &str) -> FileAccess {
        let dir = Path::new(name).parent().unwrap_or(Path::new(""));
        let mut access = self.clone();
        if self.sandboxed {
            access.subdir = self.subdir.join(dir);
        } else {
            access.base_dir = self.base_dir.join(dir);
        }
        access
    }

    /// How a file name is shown in messages: as given in a sandbox, else the full path.
    pub fn shown(&self, name: &str) -> String {
        if self.sandboxed {
            name.to_string()
        } else {
            self.base_dir.join(name).display().to_string()
        }
    }

    /// The path `name` stands for, checked against the sandbox (if any).
    pub fn resolve(&self, name: &str) -> Result<PathBuf, String> {
        let relative = Path::new(name);
        if !self.sandboxed {
            return Ok(self.base_dir.join(relative));
        }
        for part in relative.components() {
            match part {
                Component::Normal(_) | Component::CurDir => {}
                Component::ParentDir => {
                    return Err("`..` is not allowed in a scene sent to the server: name files inside the served scene's folder".to_string())
                }
                Component::RootDir | Component::Prefix(_) => {
                    return Err("absolute paths are not allowed in a scene sent to the server: name files inside the served scene's folder".to_string())
                }
            }
        }
        let hidden = || "no such file in the served scene's folder".to_string();
        let root = self.base_dir.canonicalize().map_err(|_| hidden())?;
        let path = root
            .join(&self.subdir)
            .join(relative)
            .canonicalize()
            .map_err(|_| hidden())?;
        if !path.starts_with(&root) {
            return Err("the file is a link leading outside the served scene's folder".to_string());
        }
        Ok(path)
    }

    /// Reads the regular file `name` (relative to the base folder), at most
    /// [`FileAccess::max_file_bytes`].
    pub fn read(&self, name: &str) -> Result<Vec<u8>, String> {
        let path = self.resolve(name)?;
        let unreadable = |e: std::io::Error| {
            if self.sandboxed {
                "cannot be read in the served scene's folder".to_string()
            } else {
                format!("cannot read {}: {e}", path.display())
            }
        };
        pliant_files::read_regular_file(&path, self.max_file_bytes).map_err(|e| match e.kind {
            pliant_files::FileErrorKind::NotRegular(_) => {
                "is not a regular file (only regular mesh files are read)".to_string()
            }
            pliant_files::FileErrorKind::TooLarge { len, max } => too_large(len, max),
            pliant_files::FileErrorKind::Open(e) | pliant_files::FileErrorKind::Read(e) => {
                unreadable(e)
            }
            kind => kind.to_string(),
        })
    }
}

fn too_large(len: u64, cap: u64) -> String {
    format!(
        "the file has {} bytes; at most {cap} are read (raise the limit with --max-mesh-bytes)",
        len
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pliant-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("inner")).unwrap();
        dir
    }

    #[test]
    fn sandbox_refuses_absolute_parent_and_links_out() {
        let dir = folder("sandbox");
        std::fs::write(dir.join("inner/a.obj"), "v 0 0 0\n").unwrap();
        let outside = folder("outside");
        std::fs::write(outside.join("secret.obj"), "secret line\n").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(outside.join("secret.obj"), dir.join("link.obj")).unwrap();
        let s = FileAccess::sandbox(&dir);
        assert_eq!(s.read("inner/a.obj").unwrap(), b"v 0 0 0\n");
        assert_eq!(s.read("./inner/a.obj").unwrap(), b"v 0 0 0\n");
        let abs = outside.join("secret.obj").display().to_string();
        let e = s.read(&abs).unwrap_err();
        assert!(e.contains("absolute"), "{e}");
        let e = s.read("inner/../../outside/secret.obj").unwrap_err();
        assert!(e.contains("`..`"), "{e}");
        #[cfg(unix)]
        {
            let e = s.read("link.obj").unwrap_err();
            assert!(e.contains("outside") && !e.contains("secret"), "{e}");
        }
        // missing and unreadable look alike and name no path
        let e = s.read("inner/missing.obj").unwrap_err();
        assert!(!e.contains(&dir.display().to_string()), "{e}");
        let e2 = s.read("inner/a.obj/x.obj").unwrap_err();
        assert_eq!(e, e2);
        // the same names are fine for a local scene
        assert!(FileAccess::local(&dir).read("link.obj").is_ok() || cfg!(not(unix)));
        assert!(FileAccess::local(&dir).read(&abs).is_ok());
    }

    #[test]
    fn only_regular_files_within_the_cap() {
        let dir = folder("cap");
        std::fs::write(dir.join("big.stl"), vec![b'x'; 1000]).unwrap();
        let local = FileAccess::local(&dir);
        assert_eq!(local.read("big.stl").unwrap().len(), 1000);
        let e = local
            .clone()
            .with_max_file_bytes(999)
            .read("big.stl")
            .unwrap_err();
        assert!(e.contains("1000 bytes") && e.contains("999"), "{e}");
        let e = local.read("inner").unwrap_err();
        assert!(e.contains("not a regular file"), "{e}");
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/dev/zero", dir.join("zero.stl")).unwrap();
            let e = local.read("zero.stl").unwrap_err();
            assert!(e.contains("not a regular file"), "{e}");
            let fifo = dir.join("fifo.obj");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                // refused without opening it (opening a FIFO would block)
                let e = local.read("fifo.obj").unwrap_err();
                assert!(e.contains("not a regular file"), "{e}");
            }
        }
    }
}
