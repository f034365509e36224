//! The calibration page's part for one fitted law: the data with the fitted law drawn
//! through them, the residuals along the curve with ±2 s, and the table of the
//! parameters with their intervals and the checks.

use crate::html::{escape, min_max, residual_marks, row, thin, unit_of, Frame};
use crate::law_fit::LawFit;
use std::fmt::Write as _;

fn svg_open(f: &Frame) -> String {
    format!(
        "<svg width=\"{}\" height=\"{}\" xmlns=\"http://www.w3.org/2000/svg\" font-family=\"sans-serif\">",
        f.w, f.h
    )
}

fn frame(xs: &[f64], ys: &[f64], h: f64) -> Frame {
    let (xmin, xmax) = min_max(xs);
    let (ymin, ymax) = min_max(ys);
    let pad_x = 0.03 * (xmax - xmin).max(1e-300);
    let pad_y = 0.05 * (ymax - ymin).max(1e-300);
    Frame {
        w: 760.0,
        h,
        left: 72.0,
        right: 16.0,
        top: 28.0,
        bottom: 42.0,
        x0: xmin - pad_x,
        x1: xmax + pad_x,
        y0: ymin - pad_y,
        y1: ymax + pad_y,
    }
}

/// The data (blue) and the fitted law (red, in the data's order).
pub fn curve_plot(l: &LawFit) -> String {
    let xs: Vec<f64> = l.x.iter().map(|v| v * l.x_scale).collect();
    let ys: Vec<f64> = l.y.iter().map(|v| v * l.y_scale).collect();
    let fs: Vec<f64> = l.fitted.iter().map(|v| v * l.y_scale).collect();
    let f = frame(&xs, &ys, 400.0);
    let mut svg = svg_open(&f);
    f.axes(&mut svg, &l.x_label, &l.y_label);
    let keep = thin(xs.len(), 3000);
    for &i in &keep {
        let _ = write!(
            svg,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"2\" fill=\"#1f4e99\"/>",
            f.px(xs[i]),
            f.py(ys[i])
        );
    }
    let points: Vec<String> = keep
        .iter()
        .filter(|&&i| i < fs.len())
        .map(|&i| format!("{:.1},{:.1}", f.px(xs[i]), f.py(fs[i].clamp(f.y0, f.y1))))
        .collect();
    let _ = write!(
        svg,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c00\" stroke-width=\"1.5\"/><text x=\"{:.1}\" y=\"18\" font-size=\"12\">{} — {}: data (blue), fitted law (red)</text></svg>",
        points.join(" "),
        f.left,
        escape(l.kind.name()),
        escape(&l.csv)
    );
    svg
}

/// The residuals (data − law) along the curve, with ±2 s of the fit.
pub fn residual_plot(l: &LawFit) -> String {
    let idx: Vec<f64> = (0..l.x.len()).map(|i| i as f64 + 1.0).collect();
    let res: Vec<f64> =
        l.y.iter()
            .zip(&l.fitted)
            .map(|(y, f)| (y - f) * l.y_scale)
            .collect();
    let band = 2.0 * l.fit.residual_std * l.y_scale;
    let lim = min_max(&res)
        .0
        .abs()
        .max(min_max(&res).1.abs())
        .max(band)
        .max(1e-300)
        * 1.1;
    let mut f = frame(&idx, &[-lim, lim], 200.0);
    f.y0 = -lim;
    f.y1 = lim;
    let mut svg = svg_open(&f);
    f.axes(
        &mut svg,
        "data row",
        &format!("residual [{}]", unit_of(&l.y_label)),
    );
    residual_marks(&mut svg, &f, (&idx, &res), band);
    let _ = write!(
        svg,
        "<text x=\"{:.1}\" y=\"16\" font-size=\"12\">residuals along the curve (in the order recorded); dashed: ±2 s of the fit</text></svg>",
        f.left
    );
    svg
}

/// The page's section for one law.
pub fn section(l: &LawFit) -> String {
    let mut s = format!(
        "<h2>{} — <code>{}</code></h2>",
        escape(l.kind.name()),
        escape(&l.csv)
    );
    s.push_str(&curve_plot(l));
    s.push_str("<br>");
    s.push_str(&residual_plot(l));
    s.push_str("<table>");
    for e in &l.fit.estimates {
        row(
            &mut s,
            &e.name,
            &format!(
                "{:.6e} (SI), 95 % CI {:.6e} – {:.6e}",
                e.value, e.ci95[0], e.ci95[1]
            ),
        );
    }
    row(&mut s, "law", &l.formula);
    row(
        &mut s,
        "fit",
        &format!(
            "{} points, residual std. dev. s = {:.4e} {}, {} iterations (Levenberg–Marquardt)",
            l.fit.points,
            l.fit.residual_std * l.y_scale,
            unit_of(&l.y_label),
            l.fit.iterations
        ),
    );
    for c in &l.checks {
        row(&mut s, "check", c);
    }
    s.push_str("</table>");
    s
}
