//! Embeds the built browser viewer (`web/dist`, made by `scripts/build-web.sh`) into the
//! server binary so that `pliant serve` is self-contained. Writes `$OUT_DIR/web_assets.rs`:
//! a table of (URL path, bytes) with one `include_bytes!` per file. When the folder is
//! missing the table is empty and the server's `/` explains how to build the viewer.
//! `PLIANT_WEB_DIST` overrides the folder.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn main() {
    println!("cargo:rerun-if-env-changed=PLIANT_WEB_DIST");
    let dist = std::env::var_os("PLIANT_WEB_DIST")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("..")
                .join("..")
                .join("web")
                .join("dist")
        });
    // A directory is scanned for changes by cargo; a missing path reruns this script on
    // every build, so a viewer built later is picked up.
    println!("cargo:rerun-if-changed={}", dist.display());
    let mut files = Vec::new();
    if dist.join("index.html").is_file() {
        collect(&dist, &dist, &mut files);
    }
    files.sort();
    let mut out = String::from(
        "/// The embedded viewer files: URL path (without the leading `/`) and contents.\n\
         pub static WEB_ASSETS: &[(&str, &[u8])] = &[\n",
    );
    for (url, path) in &files {
        let _ = writeln!(
            out,
            "    ({url:?}, include_bytes!({:?})),",
            path.display().to_string()
        );
    }
    out.push_str("];\n");
    let target =
        Path::new(&std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR")).join("web_assets.rs");
    std::fs::write(target, out).expect("write web_assets.rs");
}

/// Every file under `dir`, as (path relative to `root` with `/` separators, absolute path).
fn collect(root: &Path, dir: &Path, files: &mut Vec<(String, PathBuf)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(root, &path, files);
        } else if let Ok(rel) = path.strip_prefix(root) {
            let url = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            let abs = path.canonicalize().unwrap_or(path.clone());
            files.push((url, abs));
        }
    }
}
