//! An inline SVG plot of a quantity along a hose (arc length on x) against its limit
//! (a dashed line), for the report's installation checks (SPEC V3, V7).

use super::svg::escape;
use std::fmt::Write as _;

/// The limit a plot draws dashed in red.
#[derive(Clone, Copy, Debug)]
pub enum Limit<'a> {
    /// None drawn.
    None,
    /// One value throughout (none when not finite).
    Level(f64),
    /// One value per point of the x axis (a protected stretch of a harness has its own
    /// minimum bend radius).
    Along(&'a [f64]),
}

impl Limit<'_> {
    /// The largest finite value drawn (0 when none).
    fn top(&self) -> f64 {
        let values: &[f64] = match self {
            Limit::None => &[],
            Limit::Level(l) => std::slice::from_ref(l),
            Limit::Along(ls) => ls,
        };
        values
            .iter()
            .copied()
            .filter(|l| l.is_finite())
            .fold(0.0, f64::max)
    }
}

/// `values` per arc length `arc` \[m\]; `limit` drawn dashed (±limit when `symmetric`,
/// for signed quantities such as twist); `unit` labels the y axis.
pub fn profile_plot(
    title: &str,
    arc: &[f64],
    values: &[f64],
    limit: Limit,
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
    limit: Limit,
    symmetric: bool,
    unit: &str,
) -> String {
    let (w, h, pad) = (640.0, 220.0, 48.0);
    let span = (x_max - x_min).max(1e-12);
    let v_abs = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let top = v_abs.max(limit.top()).max(1e-12) * 1.1;
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
    let signs: &[f64] = if symmetric { &[1.0, -1.0] } else { &[1.0] };
    match limit {
        Limit::None => {}
        Limit::Level(l) if !l.is_finite() => {}
        Limit::Level(l) => {
            for sign in signs {
                let _ = write!(
                    svg,
                    "<line x1=\"{pad}\" y1=\"{0:.1}\" x2=\"{1}\" y2=\"{0:.1}\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>",
                    y(sign * l),
                    w - pad
                );
            }
        }
        Limit::Along(ls) => {
            for sign in signs {
                let points: Vec<String> = xs
                    .iter()
                    .zip(ls)
                    .filter(|(_, l)| l.is_finite())
                    .map(|(s, l)| format!("{:.1},{:.1}", x(*s), y(sign * l)))
                    .collect();
                let _ = write!(
                    svg,
                    "<polyline fill=\"none\" stroke=\"#c00\" stroke-dasharray=\"6 4\" points=\"{}\"/>",
                    points.join(" ")
                );
            }
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
