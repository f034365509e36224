//! An inline SVG plot of a quantity along a hose (arc length on x) against its limit
//! (a dashed line), for the report's installation checks (SPEC V3, V7).

use super::svg::escape;
use std::fmt::Write as _;

/// `values` per arc length `arc` \[m\]; `limit` drawn dashed (±limit when `symmetric`,
/// for signed quantities such as twist); `unit` labels the y axis.
pub fn profile_plot(
    title: &str,
    arc: &[f64],
    values: &[f64],
    limit: f64,
    symmetric: bool,
    unit: &str,
) -> String {
    let s_max = arc.last().copied().unwrap_or(0.0).max(1e-9) * 1.02;
    let label = format!("s = {:.0} mm", 1e3 * s_max);
    line_plot(
        title,
        (arc, 0.0, s_max, &label),
        values,
        limit,
        symmetric,
        unit,
    )
}

/// `values` over `xs` drawn on an x axis from `x_min` to `x_max` labelled `x_label` at
/// its end; the rest as [`profile_plot`]. A range-of-motion study draws its quantities
/// over the motion coordinate with it.
pub fn line_plot(
    title: &str,
    (xs, x_min, x_max, x_label): (&[f64], f64, f64, &str),
    values: &[f64],
    limit: f64,
    symmetric: bool,
    unit: &str,
) -> String {
    let (w, h, pad) = (640.0, 220.0, 48.0);
    let span = (x_max - x_min).max(1e-12);
    let v_abs = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let top = v_abs
        .max(if limit.is_finite() { limit } else { 0.0 })
        .max(1e-12)
        * 1.1;
    let bottom = if symmetric { -top } else { 0.0 };
    let x = |s: f64| pad + (w - 2.0 * pad) * (s - x_min) / span;
    let y = |v: f64| h - pad - (h - 2.0 * pad) * (v - bottom) / (top - bottom);
    let mut svg = super::svg::open(w, h, pad, title);
    let _ = write!(
        svg,
        "<line x1=\"{pad}\" y1=\"{0:.1}\" x2=\"{1}\" y2=\"{0:.1}\" stroke=\"#888\"/>\
         <line x1=\"{pad}\" y1=\"{pad}\" x2=\"{pad}\" y2=\"{2}\" stroke=\"#888\"/>",
        y(0.0),
        w - pad,
        h - pad
    );
    let _ = write!(
        svg,
        "<text x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>\
         <text x=\"2\" y=\"{}\" font-size=\"11\">{:.3} {}</text>",
        w - pad - 60.0,
        h - pad + 15.0,
        escape(x_label),
        pad + 4.0,
        top,
        escape(unit)
    );
    if limit.is_finite() {
        for l in if symmetric {
            vec![limit, -limit]
        } else {
            vec![limit]
        } {
            let _ = write!(
                svg,
                "<line x1=\"{pad}\" y1=\"{0:.1}\" x2=\"{1}\" y2=\"{0:.1}\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>",
                y(l),
                w - pad
            );
        }
    }
    let points: Vec<String> = xs
        .iter()
        .zip(values)
        .map(|(s, v)| format!("{:.1},{:.1}", x(*s), y(*v)))
        .collect();
    let _ = write!(
        svg,
        "<polyline fill=\"none\" stroke=\"#036\" stroke-width=\"1.5\" points=\"{}\"/>",
        points.join(" ")
    );
    svg.push_str("</svg>");
    svg
}
