//! A picture of the scene at a hose's worst instant (SPEC V7): the parts' silhouettes
//! ([`PartOutline`]) and every hose's centre line, seen from above, from the side and
//! from the front right above, as inline SVG; the hose of interest drawn thick, the
//! worst place marked with a red circle. Each view is framed on the hoses (the parts are
//! cut at its border), so a large floor does not shrink the hoses to a dot.

use super::part_outline::{PartOutline, View};
use glam::DVec3;
use std::fmt::Write as _;

/// `hoses` are (first node, node count) of every hose in `positions` \[m\]; `focus` is the
/// index of the hose of interest; `mark` the point to circle \[m\]; `parts` the parts'
/// outlines.
pub fn scene_picture(
    title: &str,
    positions: &[[f64; 3]],
    hoses: &[(usize, usize)],
    focus: usize,
    mark: [f64; 3],
    parts: &[PartOutline],
) -> String {
    let mut svg = format!(
        "<div><p style=\"margin:0.5em 0 0 0\">{}</p>",
        title.replace('&', "&amp;").replace('<', "&lt;")
    );
    for (k, view) in View::all().iter().enumerate() {
        let at = |p: &[f64; 3]| view.project(DVec3::from_array(*p));
        let frame = Frame::around(positions.iter().chain(std::iter::once(&mark)).map(at));
        let px = |q: [f64; 2]| frame.px(q);
        frame.open(&mut svg);
        draw_parts(&mut svg, parts, k, px);
        for (j, &(first, count)) in hoses.iter().enumerate() {
            let Some(nodes) = positions.get(first..first + count) else {
                continue;
            };
            let points: Vec<String> = nodes
                .iter()
                .map(|p| {
                    let (x, y) = px(at(p));
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let (stroke, width) = if j == focus {
                ("#036", 3.0)
            } else {
                ("#777", 1.5)
            };
            let _ = write!(
                svg,
                "<polyline fill=\"none\" stroke=\"{stroke}\" stroke-width=\"{width}\" points=\"{}\"/>",
                points.join(" ")
            );
        }
        let (mx, my) = px(at(&mark));
        let _ = write!(
            svg,
            "<circle cx=\"{mx:.1}\" cy=\"{my:.1}\" r=\"8\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/><text x=\"4\" y=\"12\" font-size=\"10\">{}</text></svg>",
            view.name
        );
    }
    svg.push_str("</div>");
    svg
}

/// A view's picture frame: the points it is framed on fill it with a margin of a fifth
/// for what is around them.
pub(super) struct Frame {
    centre: [f64; 2],
    scale: f64,
}

/// A picture's width and height and the padding inside its border \[px\].
const SIZE: (f64, f64, f64) = (300.0, 250.0, 16.0);

impl Frame {
    /// Framed on `points` (picture coordinates \[m\]).
    pub(super) fn around(points: impl Iterator<Item = [f64; 2]>) -> Frame {
        let (w, h, pad) = SIZE;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in points {
            for i in 0..2 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        let span = 1.2 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        Frame {
            centre: [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])],
            scale: ((w - 2.0 * pad) / span).min((h - 2.0 * pad) / span),
        }
    }

    /// Pixels per metre.
    pub(super) fn scale(&self) -> f64 {
        self.scale
    }

    /// The pixel of picture coordinates `q` \[m\] (y down).
    pub(super) fn px(&self, q: [f64; 2]) -> (f64, f64) {
        let (w, h, _) = SIZE;
        (
            0.5 * w + (q[0] - self.centre[0]) * self.scale,
            0.5 * h - (q[1] - self.centre[1]) * self.scale,
        )
    }

    /// Opens the view's `<svg>`.
    pub(super) fn open(&self, svg: &mut String) {
        let (w, h, _) = SIZE;
        let _ = write!(
            svg,
            "<svg width=\"{w}\" height=\"{h}\" xmlns=\"http://www.w3.org/2000/svg\" style=\"border:1px solid #ddd;margin-right:8px;overflow:hidden\">"
        );
    }
}

/// Draws the silhouettes of `parts` in view `k`, far to near, through `px`.
pub(super) fn draw_parts(
    svg: &mut String,
    parts: &[PartOutline],
    k: usize,
    px: impl Fn([f64; 2]) -> (f64, f64),
) {
    let mut order: Vec<&PartOutline> = parts.iter().collect();
    order.sort_by(|a, b| a.depth[k].total_cmp(&b.depth[k]));
    for part in order {
        let points: Vec<String> = part.hulls[k]
            .iter()
            .map(|&q| {
                let (x, y) = px(q);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = write!(
            svg,
            "<polygon fill=\"#ddd6c8\" stroke=\"#a89f8c\" stroke-width=\"1\" points=\"{}\"><title>{}</title></polygon>",
            points.join(" "),
            part.name.replace('&', "&amp;").replace('<', "&lt;")
        );
    }
}
