//! Pieces shared by the report's inline SVG pictures and HTML text.

use std::fmt::Write as _;

/// `s` with the characters HTML and SVG text may not hold as they are escaped.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The opening of a `w` × `h` SVG picture with `title` written at the top left, `pad` in.
pub fn open(w: f64, h: f64, pad: f64, title: &str) -> String {
    let mut svg =
        format!("<svg width=\"{w}\" height=\"{h}\" xmlns=\"http://www.w3.org/2000/svg\">");
    let _ = write!(
        svg,
        "<text x=\"{pad}\" y=\"16\" font-size=\"13\">{}</text>",
        escape(title)
    );
    svg
}
