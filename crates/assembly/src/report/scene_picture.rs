//! A picture of the scene at a hose's worst instant (SPEC V7): every hose's centre line
//! projected from above (x–y) and from the side (x–z) as inline SVG, the hose of interest
//! drawn thick, the worst place marked with a red circle.

use std::fmt::Write as _;

/// `hoses` are (first node, node count) of every hose in `positions` [m]; `focus` is the
/// index of the hose of interest; `mark` the point to circle [m].
pub fn scene_picture(
    title: &str,
    positions: &[[f64; 3]],
    hoses: &[(usize, usize)],
    focus: usize,
    mark: [f64; 3],
) -> String {
    let (w, h, pad) = (320.0, 260.0, 16.0);
    let mut svg = format!(
        "<div><p style=\"margin:0.5em 0 0 0\">{}</p>",
        title.replace('&', "&amp;").replace('<', "&lt;")
    );
    for (name, a, b) in [
        ("from above (x right, y up)", 0, 1),
        ("from the side (x right, z up)", 0, 2),
    ] {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in positions.iter().chain(std::iter::once(&mark)) {
            for (k, axis) in [a, b].into_iter().enumerate() {
                lo[k] = lo[k].min(p[axis]);
                hi[k] = hi[k].max(p[axis]);
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        let scale = ((w - 2.0 * pad) / span).min((h - 2.0 * pad) / span);
        let px = |p: &[f64; 3]| {
            (
                pad + (p[a] - lo[0]) * scale,
                h - pad - (p[b] - lo[1]) * scale,
            )
        };
        let _ = write!(
            svg,
            "<svg width=\"{w}\" height=\"{h}\" xmlns=\"http://www.w3.org/2000/svg\" style=\"border:1px solid #ddd;margin-right:8px\"><text x=\"4\" y=\"12\" font-size=\"10\">{name}</text>"
        );
        for (k, &(first, count)) in hoses.iter().enumerate() {
            let Some(nodes) = positions.get(first..first + count) else {
                continue;
            };
            let points: Vec<String> = nodes
                .iter()
                .map(|p| {
                    let (x, y) = px(p);
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let (stroke, width) = if k == focus {
                ("#036", 3.0)
            } else {
                ("#999", 1.5)
            };
            let _ = write!(
                svg,
                "<polyline fill=\"none\" stroke=\"{stroke}\" stroke-width=\"{width}\" points=\"{}\"/>",
                points.join(" ")
            );
        }
        let (mx, my) = px(&mark);
        let _ = write!(
            svg,
            "<circle cx=\"{mx:.1}\" cy=\"{my:.1}\" r=\"8\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/></svg>"
        );
    }
    svg.push_str("</div>");
    svg
}
