//! The calibration page: for every test an SVG plot of the data, the linear range
//! shaded, the fitted line, and the residuals; tables of the results; the material entry.
//! One self-contained HTML file, no scripts.

use crate::fit::TestFit;
use crate::law_fit::LawFit;
use crate::material_entry::{num, Derived, MaterialResult};
use std::fmt::Write as _;

/// `s` with the characters HTML may not hold as they are escaped.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Round tick positions covering [lo, hi]: steps of 1, 2 or 5 × 10^k, about 6 of them.
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = (hi - lo).abs().max(1e-300);
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let mut t = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while t <= hi + 1e-9 * step && out.len() < 50 {
        out.push(if t.abs() < 1e-12 * step { 0.0 } else { t });
        t += step;
    }
    out
}

/// Plot frame: maps data (display units) to pixels.
pub(crate) struct Frame {
    pub(crate) w: f64,
    pub(crate) h: f64,
    pub(crate) left: f64,
    pub(crate) right: f64,
    pub(crate) top: f64,
    pub(crate) bottom: f64,
    pub(crate) x0: f64,
    pub(crate) x1: f64,
    pub(crate) y0: f64,
    pub(crate) y1: f64,
}

impl Frame {
    pub(crate) fn px(&self, x: f64) -> f64 {
        self.left + (self.w - self.left - self.right) * (x - self.x0) / (self.x1 - self.x0)
    }
    pub(crate) fn py(&self, y: f64) -> f64 {
        self.h
            - self.bottom
            - (self.h - self.top - self.bottom) * (y - self.y0) / (self.y1 - self.y0)
    }

    /// Axes, grid, ticks and labels.
    pub(crate) fn axes(&self, svg: &mut String, x_label: &str, y_label: &str) {
        let (l, r, t, b) = (
            self.left,
            self.w - self.right,
            self.top,
            self.h - self.bottom,
        );
        for x in ticks(self.x0, self.x1) {
            let p = self.px(x);
            let _ = write!(
                svg,
                "<line x1=\"{p:.1}\" y1=\"{t}\" x2=\"{p:.1}\" y2=\"{b}\" stroke=\"#eee\"/><text x=\"{p:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">{}</text>",
                b + 14.0,
                num(x)
            );
        }
        for y in ticks(self.y0, self.y1) {
            let p = self.py(y);
            let _ = write!(
                svg,
                "<line x1=\"{l}\" y1=\"{p:.1}\" x2=\"{r}\" y2=\"{p:.1}\" stroke=\"#eee\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"end\">{}</text>",
                l - 4.0,
                p + 4.0,
                num(y)
            );
        }
        let _ = write!(
            svg,
            "<rect x=\"{l}\" y=\"{t}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" stroke=\"#888\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" text-anchor=\"middle\">{}</text>\
             <text x=\"14\" y=\"{:.1}\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 14 {:.1})\">{}</text>",
            r - l,
            b - t,
            0.5 * (l + r),
            self.h - 6.0,
            escape(x_label),
            0.5 * (t + b),
            0.5 * (t + b),
            escape(y_label)
        );
    }
}

/// Every k-th index so that at most `max` points are drawn (the range's ends always).
pub(crate) fn thin(n: usize, max: usize) -> Vec<usize> {
    let k = n.div_ceil(max).max(1);
    (0..n).filter(|i| i % k == 0 || *i == n - 1).collect()
}

/// The data with the linear range shaded and the fitted line.
pub fn curve_plot(t: &TestFit) -> String {
    let c = &t.curve;
    let xs: Vec<f64> = c.x.iter().map(|v| v * c.x_scale).collect();
    let ys: Vec<f64> = c.y.iter().map(|v| v * c.y_scale).collect();
    let (xmin, xmax) = min_max(&xs);
    let (ymin, ymax) = min_max(&ys);
    let pad_x = 0.03 * (xmax - xmin).max(1e-300);
    let pad_y = 0.05 * (ymax - ymin).max(1e-300);
    let f = Frame {
        w: 760.0,
        h: 400.0,
        left: 72.0,
        right: 16.0,
        top: 28.0,
        bottom: 42.0,
        x0: xmin.min(0.0) - pad_x,
        x1: xmax + pad_x,
        y0: ymin.min(0.0) - pad_y,
        y1: ymax + pad_y,
    };
    let mut svg = format!(
        "<svg width=\"{}\" height=\"{}\" xmlns=\"http://www.w3.org/2000/svg\" font-family=\"sans-serif\">",
        f.w, f.h
    );
    let r = &t.range;
    let (a, b) = (f.px(xs[r.first_row]), f.px(xs[r.last_row]));
    let _ = write!(
        svg,
        "<rect x=\"{a:.1}\" y=\"{}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#d8f0d8\"/>",
        f.top,
        (b - a).max(1.0),
        f.h - f.top - f.bottom
    );
    f.axes(&mut svg, c.x_label, c.y_label);
    for i in thin(xs.len(), 3000) {
        let inside = i >= r.first_row && i <= r.last_row;
        let _ = write!(
            svg,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"2.2\" fill=\"{}\"/>",
            f.px(xs[i]),
            f.py(ys[i]),
            if inside { "#1f4e99" } else { "#999" }
        );
    }
    // the line, solid over the range and dashed beyond it
    let line = |x_si: f64| (t.line.intercept + t.line.slope * x_si) * c.y_scale;
    let (xa, xb) = (c.x[r.first_row], c.x[r.last_row]);
    let x_end = c.x.last().copied().unwrap_or(xb);
    let x_start = c.x.first().copied().unwrap_or(xa);
    let seg = |svg: &mut String, x1: f64, x2: f64, dash: &str| {
        let _ = write!(
            svg,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#c00\" stroke-width=\"{}\"{dash}/>",
            f.px(x1 * c.x_scale),
            f.py(line(x1).clamp(f.y0, f.y1)),
            f.px(x2 * c.x_scale),
            f.py(line(x2).clamp(f.y0, f.y1)),
            if dash.is_empty() { 2.0 } else { 1.0 }
        );
    };
    seg(&mut svg, x_start, xa, " stroke-dasharray=\"5 4\"");
    seg(&mut svg, xb, x_end, " stroke-dasharray=\"5 4\"");
    seg(&mut svg, xa, xb, "");
    let _ = write!(
        svg,
        "<text x=\"{:.1}\" y=\"18\" font-size=\"12\">{} — {}: linear range (green), points used (blue), fit (red, dashed beyond the range)</text></svg>",
        f.left,
        escape(t.kind.name()),
        escape(&t.csv)
    );
    svg
}

/// Residuals of the points in the linear range, with ±2σ of the noise estimate.
pub fn residual_plot(t: &TestFit) -> String {
    let c = &t.curve;
    let r = &t.range;
    let xs: Vec<f64> = (r.first_row..=r.last_row)
        .map(|i| c.x[i] * c.x_scale)
        .collect();
    let res: Vec<f64> = (r.first_row..=r.last_row)
        .map(|i| (c.y[i] - t.line.intercept - t.line.slope * c.x[i]) * c.y_scale)
        .collect();
    let (xmin, xmax) = min_max(&xs);
    let (rmin, rmax) = min_max(&res);
    let lim = rmin
        .abs()
        .max(rmax.abs())
        .max(2.0 * r.noise_std)
        .max(1e-300)
        * 1.1;
    let f = Frame {
        w: 760.0,
        h: 200.0,
        left: 72.0,
        right: 16.0,
        top: 24.0,
        bottom: 42.0,
        x0: xmin - 0.03 * (xmax - xmin).max(1e-300),
        x1: xmax + 0.03 * (xmax - xmin).max(1e-300),
        y0: -lim,
        y1: lim,
    };
    let mut svg = format!(
        "<svg width=\"{}\" height=\"{}\" xmlns=\"http://www.w3.org/2000/svg\" font-family=\"sans-serif\">",
        f.w, f.h
    );
    f.axes(
        &mut svg,
        c.x_label,
        &format!("residual [{}]", unit_of(c.y_label)),
    );
    residual_marks(&mut svg, &f, (&xs, &res), 2.0 * r.noise_std);
    let _ = write!(
        svg,
        "<text x=\"{:.1}\" y=\"16\" font-size=\"12\">residuals in the linear range; dashed: ±2σ of the scatter estimated from the whole curve</text></svg>",
        f.left
    );
    svg
}

/// The residuals `res` at `xs` as points, between dashed lines at ±`band`.
pub(crate) fn residual_marks(svg: &mut String, f: &Frame, (xs, res): (&[f64], &[f64]), band: f64) {
    for s in [band, -band] {
        let _ = write!(
            svg,
            "<line x1=\"{}\" y1=\"{1:.1}\" x2=\"{2}\" y2=\"{1:.1}\" stroke=\"#c80\" stroke-dasharray=\"4 3\"/>",
            f.left,
            f.py(s),
            f.w - f.right
        );
    }
    for i in thin(xs.len(), 3000) {
        let _ = write!(
            svg,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"2\" fill=\"#1f4e99\"/>",
            f.px(xs[i]),
            f.py(res[i])
        );
    }
}

pub(crate) fn unit_of(label: &str) -> &str {
    label
        .rfind('[')
        .map(|i| label[i + 1..].trim_end_matches(']'))
        .unwrap_or("")
}

pub(crate) fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        })
}

pub(crate) fn row(s: &mut String, k: &str, v: &str) {
    let _ = write!(s, "<tr><th>{}</th><td>{}</td></tr>", escape(k), escape(v));
}

pub(crate) fn material_row(s: &mut String, key: &str, d: &Derived) {
    let (what, text) = match (&d.source, &d.assumption) {
        (Some(t), _) => ("source", t.as_str()),
        (None, Some(a)) => ("assumption", a.as_str()),
        _ => ("", ""),
    };
    let ci = d
        .ci95
        .map(|c| format!("{} – {}", num(c[0]), num(c[1])))
        .unwrap_or_default();
    let _ = write!(
        s,
        "<tr><th>{}</th><td>{}</td><td>{}</td><td class=\"{}\">{}: {}</td></tr>",
        escape(key),
        num(d.value),
        escape(&ci),
        what,
        what,
        escape(text)
    );
}

/// The whole page.
pub fn page(
    origin: &str,
    fits: &[TestFit],
    laws: &[LawFit],
    m: &MaterialResult,
    material_toml: &str,
) -> String {
    let mut s = String::from(
        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Pliant calibration</title><style>\
         body{font-family:sans-serif;margin:24px;max-width:1000px;color:#222}\
         table{border-collapse:collapse;margin:8px 0 16px}th,td{border:1px solid #ccc;padding:3px 8px;text-align:left;font-size:13px;vertical-align:top}\
         th{background:#f4f4f4}.assumption{color:#a50}pre{background:#f6f6f6;padding:8px;font-size:12px;overflow-x:auto}\
         .warn{color:#a30}</style></head><body>",
    );
    let _ = write!(
        s,
        "<h1>Material calibration: {}</h1><p>From <code>{}</code>: {} test(s); tested section d<sub>i</sub> = {} mm, d<sub>a</sub> = {} mm. Method: least squares over the linear range, found automatically; inelastic laws fitted to the whole curve by nonlinear least squares (docs/calibration.md).</p>",
        escape(&m.name),
        escape(origin),
        fits.len() + laws.len(),
        num(m.d_inner_mm),
        num(m.d_outer_mm)
    );
    for w in &m.warnings {
        let _ = write!(s, "<p class=\"warn\">⚠ {}</p>", escape(w));
    }
    s.push_str("<h2>Material</h2><table><tr><th>key</th><th>value</th><th>95 % CI</th><th>provenance</th></tr>");
    material_row(&mut s, "e_tension_mpa", &m.e_tension_mpa);
    material_row(&mut s, "e_compression_mpa", &m.e_compression_mpa);
    if let Some(b) = &m.e_bending_mpa {
        material_row(&mut s, "e_bending_mpa", b);
    }
    material_row(&mut s, "poisson", &m.poisson);
    material_row(&mut s, "density_kg_m3", &m.density_kg_m3);
    if let Some(r) = &m.min_bend_radius_mm {
        material_row(&mut s, "min_bend_radius_mm", r);
    }
    if let Some(e) = &m.ei_n_m2 {
        material_row(&mut s, "EI of the tested section [N·m²]", e);
    }
    if let Some(g) = &m.gj_n_m2 {
        material_row(&mut s, "GJ of the tested section [N·m²]", g);
    }
    for (k, d) in m.laws.values() {
        material_row(&mut s, k, d);
    }
    s.push_str("</table>");
    for f in laws {
        s.push_str(&crate::law_html::section(f));
    }
    for t in fits {
        let r = &t.range;
        let _ = write!(
            s,
            "<h2>{} — <code>{}</code></h2>",
            escape(t.kind.name()),
            escape(&t.csv)
        );
        s.push_str(&curve_plot(t));
        s.push_str("<br>");
        s.push_str(&residual_plot(t));
        s.push_str("<table>");
        row(
            &mut s,
            &t.symbol,
            &format!("{} {}", num(t.value_display), t.unit),
        );
        row(
            &mut s,
            "95 % confidence interval",
            &format!(
                "{} – {} {} (± {:.2} %)",
                num(t.ci95_display[0]),
                num(t.ci95_display[1]),
                t.unit,
                50.0 * (t.ci95[1] - t.ci95[0]) / t.value.abs().max(1e-300)
            ),
        );
        row(
            &mut s,
            "standard error",
            &format!("{} {}", num(t.std_error * t.property.display().2), t.unit),
        );
        row(&mut s, "formula", &t.formula);
        row(
            &mut s,
            "linear range",
            &format!(
                "rows {}–{} of {} (CSV lines {}–{}), {} points; {} from {} to {}; {} from {} to {}",
                r.first_row + 1,
                r.last_row + 1,
                r.total_points,
                r.first_line,
                r.last_line,
                r.points,
                r.x_label,
                num(r.x_from),
                num(r.x_to),
                r.y_label,
                num(r.y_from),
                num(r.y_to)
            ),
        );
        row(
            &mut s,
            "residual",
            &format!(
                "RMS {} {u}, std. dev. (n−2) {} {u}; scatter of the curve σ ≈ {} {u}; R² = {:.6}",
                num(t.line.residual_rms * t.curve.y_scale),
                num(t.line.residual_std * t.curve.y_scale),
                num(r.noise_std),
                t.line.r_squared,
                u = unit_of(&r.y_label)
            ),
        );
        if t.flipped {
            row(
                &mut s,
                "note",
                "the curve was recorded with negative signs: magnitudes were fitted",
            );
        }
        s.push_str("</table>");
    }
    let _ = writeln!(
        s,
        "<h2>material.toml</h2><pre>{}</pre></body></html>",
        escape(material_toml)
    );
    s
}
