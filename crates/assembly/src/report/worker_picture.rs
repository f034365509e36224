//! A picture of the worker's worst posture (SPEC E2; the instant of the worst RULA score):
//! the manikin's capsules drawn to scale over the parts' silhouettes, in the three views
//! of the scene pictures (from above, from the side, from the front right above), framed
//! on the manikin and its hand targets (red circles).

use super::part_outline::{PartOutline, View};
use super::svg::escape;
use glam::DVec3;
use pliant_worker::{capsules, Body, Posture};
use std::fmt::Write as _;

/// The picture of `posture` of `body` with `parts`' outlines behind it.
pub fn worker_picture(
    title: &str,
    body: &Body,
    posture: &Posture,
    parts: &[PartOutline],
) -> String {
    let (w, h, pad) = (300.0, 250.0, 16.0);
    let caps = capsules(body, posture);
    let targets: Vec<DVec3> = posture.arms.iter().filter_map(|a| a.target).collect();
    let mut svg = format!("<div><p style=\"margin:0.5em 0 0 0\">{}</p>", escape(title));
    for (k, view) in View::all().iter().enumerate() {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let points = caps
            .iter()
            .flat_map(|c| [(c.a, c.radius), (c.b, c.radius)])
            .chain(targets.iter().map(|t| (*t, 0.0)));
        for (p, r) in points {
            let q = view.project(p);
            for i in 0..2 {
                lo[i] = lo[i].min(q[i] - r);
                hi[i] = hi[i].max(q[i] + r);
            }
        }
        let span = 1.1 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        let scale = ((w - 2.0 * pad) / span).min((h - 2.0 * pad) / span);
        let px = |p: DVec3| {
            let q = view.project(p);
            (
                0.5 * w + (q[0] - centre[0]) * scale,
                0.5 * h - (q[1] - centre[1]) * scale,
            )
        };
        let _ = write!(
            svg,
            "<svg width=\"{w}\" height=\"{h}\" xmlns=\"http://www.w3.org/2000/svg\" style=\"border:1px solid #ddd;margin-right:8px;overflow:hidden\">"
        );
        for part in parts {
            let pts: Vec<String> = part.hulls[k]
                .iter()
                .map(|&q| {
                    let x = 0.5 * w + (q[0] - centre[0]) * scale;
                    let y = 0.5 * h - (q[1] - centre[1]) * scale;
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let _ = write!(
                svg,
                "<polygon fill=\"#ddd6c8\" stroke=\"#a89f8c\" points=\"{}\"><title>{}</title></polygon>",
                pts.join(" "),
                escape(&part.name)
            );
        }
        for c in &caps {
            let ((xa, ya), (xb, yb)) = (px(c.a), px(c.b));
            let _ = write!(
                svg,
                "<line x1=\"{xa:.1}\" y1=\"{ya:.1}\" x2=\"{xb:.1}\" y2=\"{yb:.1}\" stroke=\"#c9a27e\" stroke-opacity=\"0.85\" stroke-width=\"{:.1}\" stroke-linecap=\"round\"><title>{}</title></line>",
                (2.0 * c.radius * scale).max(1.0),
                escape(&c.segment.name())
            );
        }
        for t in &targets {
            let (x, y) = px(*t);
            let _ = write!(
                svg,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"6\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/>"
            );
        }
        let _ = write!(
            svg,
            "<text x=\"4\" y=\"12\" font-size=\"10\">{}</text></svg>",
            view.name
        );
    }
    svg.push_str("</div>");
    svg
}
