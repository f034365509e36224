//! The browser viewer's static files, embedded into the binary at compile time by
//! `build.rs` from `web/dist` (built by `scripts/build-web.sh`). When the binary was built
//! without them, `/` serves a page that says how to build the viewer.

use axum::http::{header, StatusCode, Uri};
use axum::response::{IntoResponse, Response};

include!(concat!(env!("OUT_DIR"), "/web_assets.rs"));

/// Shown at `/` when the viewer was not embedded.
const MISSING_VIEWER_HTML: &str = include_str!("missing_viewer.html");

/// Whether the viewer was embedded at compile time.
pub fn viewer_embedded() -> bool {
    find("index.html").is_some()
}

/// The embedded file at `path` (no leading `/`).
pub fn find(path: &str) -> Option<&'static [u8]> {
    WEB_ASSETS
        .binary_search_by(|(p, _)| (*p).cmp(path))
        .ok()
        .map(|i| WEB_ASSETS[i].1)
}

/// Content type by file extension.
pub fn content_type(path: &str) -> &'static str {
    let ext = path.rsplit_once('.').map_or("", |(_, e)| e);
    match ext {
        "html" => "text/html; charset=utf-8",
        "js" | "mjs" => "text/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "json" => "application/json",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "ico" => "image/x-icon",
        "wasm" => "application/wasm",
        "txt" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// `GET /` and every other path that is not `/ws`.
pub async fn static_file(uri: Uri) -> Response {
    let path = uri.path().trim_start_matches('/');
    let path = if path.is_empty() { "index.html" } else { path };
    match find(path) {
        Some(bytes) => {
            // Vite puts content hashes into the names under assets/: cache them for good.
            let cache = if path.starts_with("assets/") {
                "public, max-age=31536000, immutable"
            } else {
                "no-cache"
            };
            (
                [
                    (header::CONTENT_TYPE, content_type(path)),
                    (header::CACHE_CONTROL, cache),
                ],
                bytes,
            )
                .into_response()
        }
        None if path == "index.html" => (
            [(header::CONTENT_TYPE, "text/html; charset=utf-8")],
            MISSING_VIEWER_HTML,
        )
            .into_response(),
        None => (StatusCode::NOT_FOUND, "not found").into_response(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_sorted_and_types_are_known() {
        assert!(WEB_ASSETS.windows(2).all(|w| w[0].0 < w[1].0));
        assert_eq!(
            content_type("assets/index-x1.js"),
            "text/javascript; charset=utf-8"
        );
        assert_eq!(content_type("index.html"), "text/html; charset=utf-8");
        assert_eq!(content_type("noext"), "application/octet-stream");
    }
}
