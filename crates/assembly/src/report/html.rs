//! The report of a study (SPEC I5): the verdict — feasible or not and why — peak hand loads against the
//! ergonomic limits, the parts the hoses touched — as `report.json` for machines and a
//! self-contained `report.html` (inline SVG plots, no scripts) for people.

use super::drawing::Drawing;
use super::recorder::HandSample;
use super::svg::escape;
use crate::ergonomics::{ErgonomicLimits, ErgonomicProfile};
use crate::workcell::{RunSummary, Stage, Verdict};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Serialize)]
pub struct Report<'a> {
    pub scene: &'a str,
    pub ergonomics: &'a str,
    pub verdict: Verdict,
    pub run: &'a RunSummary,
    pub diverged: Option<&'a str>,
    /// The parts and envelopes as the pictures draw them: presentation, made once per
    /// report from the model ([`Drawing::of`]), not part of the run's record.
    #[serde(skip)]
    pub drawing: &'a Drawing,
}

/// Writes `report.json` and `report.html` of a run into the folder `out` (which must
/// exist), and the swept envelopes' STL files if it has any, and returns the verdict.
/// `drawing` holds the parts and envelopes for the pictures ([`Drawing::of`]); `samples` are the hand loads at
/// the recorded times; `profile` is the ergonomic profile the run was judged with (its
/// push limit is drawn on the stub and clip plots); `worker_series` the worker's posed
/// instants (SPEC E1–E2; empty without a worker) for the report's worker plot.
#[allow(clippy::too_many_arguments)]
pub fn write_reports(
    out: &Path,
    scene: &str,
    run: &RunSummary,
    drawing: &Drawing,
    diverged: Option<&str>,
    samples: &[HandSample],
    profile: &ErgonomicProfile,
    worker_series: &[crate::worker::WorkerSample],
) -> std::io::Result<Verdict> {
    let report = Report {
        scene,
        ergonomics: &run.ergonomics,
        verdict: Verdict::judge(run, diverged, Stage::Final),
        run,
        diverged,
        drawing,
    };
    if let Some(envelopes) = &drawing.envelopes {
        envelopes.write_surfaces(out)?;
    }
    let write = |name: &str, text: String| super::write_file(&out.join(name), text);
    super::write_json(&out.join("report.json"), &report)?;
    let push_limit = ErgonomicLimits::builtin()
        .map(|l| l.force_limits(profile, true).1)
        .unwrap_or(f64::NAN);
    write(
        "report.html",
        html(&report, samples, push_limit, worker_series),
    )?;
    Ok(report.verdict)
}

/// The installation checks' section (SPEC V3, V7): the violations with time and place,
/// and per hose its curvature against the allowed curvature at the instant of its
/// smallest bend radius and its twist at the instant of its largest twist.
fn checks_section(s: &mut String, checks: &crate::checks::ChecksSummary, drawing: &Drawing) {
    use super::profile_plot::{profile_plot, Limit};
    s.push_str("<h2>Installation checks</h2>");
    if checks.enabled.is_empty() {
        s.push_str("<p>No installation check ran (switched off in <code>[checks]</code>).</p>");
        return;
    }
    let _ = write!(
        s,
        "<p>Checks run: {}; violations {}.</p>",
        checks.enabled.join(", "),
        if checks.decide {
            "decide feasibility"
        } else {
            "are warnings only"
        }
    );
    if checks.violations.is_empty() {
        s.push_str("<p>No violation.</p>");
    } else {
        s.push_str("<table><tr><th>check</th><th>hose</th><th>at s [mm]</th><th>t [s]</th><th>value</th><th>limit</th><th>violated from [s]</th><th>to [s]</th></tr>");
        for v in &checks.violations {
            let (value, limit) = match v.check.unit() {
                "m" => (
                    format!("{:.0} mm", 1e3 * v.value),
                    format!("{:.0} mm", 1e3 * v.limit),
                ),
                "rad/m" => (
                    format!("{:.1} °/m", v.value.to_degrees()),
                    format!("{:.1} °/m", v.limit.to_degrees()),
                ),
                _ => (format!("{:.1} N", v.value), format!("{:.1} N", v.limit)),
            };
            let name = match &v.at {
                Some(stub) => format!("{} (stub '{}')", v.check.name(), stub),
                None => v.check.name().to_string(),
            };
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{:.0}</td><td>{:.2}</td><td>{value}</td><td>{limit}</td><td>{:.2}</td><td>{:.2}</td></tr>",
                escape(&name),
                escape(&v.hose_name),
                1e3 * v.arc_length,
                v.time,
                v.first_time,
                v.last_time
            );
        }
        s.push_str("</table>");
    }
    let hoses: Vec<(usize, usize)> = checks
        .profiles
        .iter()
        .map(|p| (p.first_node, p.node_count))
        .collect();
    for v in checks
        .violations
        .iter()
        .filter(|v| v.check == crate::checks::CheckKind::BendRadius)
    {
        let Some(p) = checks.profiles.get(v.hose) else {
            continue;
        };
        // the worst beam's midpoint at the worst instant
        let Some(k) = p.arc_length.iter().position(|s| *s == v.arc_length) else {
            continue;
        };
        let Some(picture) = checks.pictures.of(v.hose) else {
            continue; // kept for the most severe hoses only (checks::MAX_SCENE_PICTURES)
        };
        let (a, b) = (p.first_node + k, p.first_node + k + 1);
        let (Some(xa), Some(xb)) = (picture.positions.get(a), picture.positions.get(b)) else {
            continue;
        };
        let mark = [0, 1, 2].map(|i| 0.5 * (xa[i] + xb[i]));
        s.push_str(&super::scene_picture::scene_picture(
            &format!(
                "The scene at t = {:.2} s, when hose '{}' was bent tightest ({:.0} mm at s = {:.0} mm, circled; minimum {:.0} mm), the parts where they were then:",
                v.time,
                v.hose_name,
                1e3 * v.value,
                1e3 * v.arc_length,
                1e3 * v.limit
            ),
            &picture.positions,
            &hoses,
            v.hose,
            mark,
            drawing.parts_for_picture(v.hose),
        ));
    }
    for p in &checks.profiles {
        if p.arc_length.len() < 2 {
            continue;
        }
        if p.min_bend_radius.is_finite() {
            let uniform = p.allowed_curvature.windows(2).all(|w| w[0] == w[1]);
            let (title, limit) = if uniform {
                (
                    format!(
                        "hose '{}': curvature at t = {:.2} s (smallest radius {:.0} mm) against the allowed 1/{:.0} mm (red)",
                        p.hose_name,
                        p.min_bend_radius_time,
                        1e3 * p.min_bend_radius,
                        1e3 * p.allowed_bend_radius
                    ),
                    Limit::Level(1.0 / p.allowed_bend_radius),
                )
            } else {
                (
                    format!(
                        "hose '{}': curvature at t = {:.2} s (furthest past its minimum: radius {:.0} mm where {:.0} mm is allowed) against each stretch's allowed curvature (red)",
                        p.hose_name,
                        p.min_bend_radius_time,
                        1e3 * p.min_bend_radius,
                        1e3 * p.allowed_bend_radius
                    ),
                    Limit::Along(&p.allowed_curvature),
                )
            };
            s.push_str(&profile_plot(
                &title,
                &p.arc_length,
                &p.curvature,
                limit,
                false,
                "1/m",
            ));
        }
        if p.max_twist > 0.0 {
            let deg: Vec<f64> = p.twist.iter().map(|t| t.to_degrees()).collect();
            s.push_str(&profile_plot(
                &format!(
                    "hose '{}': twist against the routed hose at t = {:.2} s, limit ±{:.1} °/m (red)",
                    p.hose_name,
                    p.max_twist_time,
                    p.twist_limit.to_degrees()
                ),
                &p.arc_length,
                &deg,
                Limit::Level(p.twist_limit.to_degrees()),
                true,
                "°/m",
            ));
        }
    }
}

/// An SVG line plot of force over time with the limit drawn as a dashed line; samples are
/// (time \[s\], force \[N\], limit \[N\]).
fn plot(title: &str, samples: &[(f64, f64, f64)]) -> String {
    let (w, h, pad) = (640.0, 220.0, 40.0);
    let t_max = samples.iter().map(|s| s.0).fold(1e-9, f64::max);
    let y_max = samples.iter().map(|s| s.1.max(s.2)).fold(1e-9, f64::max) * 1.1;
    let x = |t: f64| pad + (w - 2.0 * pad) * t / t_max;
    let y = |v: f64| h - pad - (h - 2.0 * pad) * v / y_max;
    let line = |f: &dyn Fn(&(f64, f64, f64)) -> f64| {
        samples
            .iter()
            .map(|s| format!("{:.1},{:.1}", x(s.0), y(f(s))))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut svg = super::svg::open(w, h, pad, title);
    let _ = write!(
        svg,
        "<line x1=\"{pad}\" y1=\"{0}\" x2=\"{1}\" y2=\"{0}\" stroke=\"#888\"/>",
        h - pad,
        w - pad
    );
    let _ = write!(
        svg,
        "<line x1=\"{pad}\" y1=\"{pad}\" x2=\"{pad}\" y2=\"{}\" stroke=\"#888\"/>",
        h - pad
    );
    let _ = write!(
        svg,
        "<text x=\"{}\" y=\"{}\" font-size=\"11\">{:.1} s</text>",
        w - pad - 20.0,
        h - pad + 15.0,
        t_max
    );
    let _ = write!(
        svg,
        "<text x=\"2\" y=\"{}\" font-size=\"11\">{:.0} N</text>",
        pad + 4.0,
        y_max
    );
    let _ = write!(
        svg,
        "<polyline fill=\"none\" stroke=\"#c00\" stroke-dasharray=\"6 4\" points=\"{}\"/>",
        line(&|s| s.2)
    );
    let _ = write!(
        svg,
        "<polyline fill=\"none\" stroke=\"#036\" stroke-width=\"1.5\" points=\"{}\"/>",
        line(&|s| s.1)
    );
    svg.push_str("</svg>");
    svg
}

/// The human-readable report.
/// `push_limit` is the profile's push limit value, drawn on the stub and clip plots (the
/// worker pushes hoses on and in).
pub fn html(
    report: &Report,
    samples: &[HandSample],
    push_limit: f64,
    worker_series: &[crate::worker::WorkerSample],
) -> String {
    let v = &report.verdict;
    let (word, colour) = match v.feasible {
        Some(true) => ("FEASIBLE", "#070"),
        Some(false) => ("NOT FEASIBLE", "#b00"),
        None => ("NOT ASSESSED", "#555"),
    };
    let mut s = String::new();
    let _ = write!(
        s,
        "<!doctype html><html><head><meta charset=\"utf-8\"><title>Pliant report: {0}</title>\
         <style>body{{font-family:sans-serif;max-width:760px;margin:2em auto}}td,th{{padding:2px 8px;text-align:right}}\
         th{{background:#eee}}</style></head><body><h1>{0}</h1>\
         <p style=\"font-size:1.6em;color:{colour}\"><b>{word}</b></p><ul>",
        escape(report.scene)
    );
    for r in &v.reasons {
        let _ = write!(s, "<li>{}</li>", escape(r));
    }
    s.push_str("</ul>");
    if !v.warnings.is_empty() {
        s.push_str("<h2>Warnings</h2><p>These do not decide feasibility.</p><ul>");
        for w in &v.warnings {
            let _ = write!(s, "<li>{}</li>", escape(w));
        }
        s.push_str("</ul>");
    }
    let _ = write!(
        s,
        "<p>Ergonomic profile: {}</p><p>Hand forces judged by: <b>{}</b></p>",
        escape(report.ergonomics),
        escape(&v.standard)
    );
    if !v.zones.is_empty() {
        s.push_str("<h2>EN 1005-3 risk zones</h2><p>Each hand's peak push and pull against the recommended force limit F_R (recommended ≤ 0.5 F_R, not recommended ≤ 0.7 F_R, to be avoided above).</p><ul>");
        for z in &v.zones {
            let _ = write!(s, "<li>{}</li>", escape(z));
        }
        s.push_str("</ul>");
    }
    let run = report.run;
    if !run.hand_peaks.is_empty() {
        s.push_str("<h2>Hands</h2><table><tr><th>hand</th><th>peak |F| [N]</th><th>at [s]</th><th>peak |T| [N·m]</th><th>at [s]</th><th>peak twist [N·m]</th><th>peak bending [N·m]</th><th>worst deciding</th><th>of limit</th></tr>");
        for h in &run.hand_peaks {
            let kind = h.worst_kind.map(|k| k.name()).unwrap_or_default();
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.3}</td><td>{:.2}</td><td>{:.3}</td><td>{:.3}</td><td>{kind}</td><td>{:.0} %</td></tr>",
                h.hand, h.max_force, h.max_force_time, h.max_torque, h.max_torque_time, h.twist.magnitude, h.bending.magnitude, 100.0 * h.worst_ratio
            );
        }
        s.push_str("</table>");
        for h in &run.hand_peaks {
            let mine: Vec<(f64, f64, f64)> = samples
                .iter()
                .filter(|x| x.hand == h.hand)
                .map(|x| (x.time, x.force, x.limit))
                .collect();
            if mine.len() > 1 {
                s.push_str(&plot(
                    &format!("hand {}: |F| (blue) and its limit (red, dashed)", h.hand),
                    &mine,
                ));
            }
        }
    }
    if !run.fasteners.is_empty() {
        s.push_str("<h2>Stubs and clips</h2><table><tr><th>kind</th><th>name</th><th>peak force [N]</th><th>at [s]</th><th>final state</th><th>holding force at the end [N]</th></tr>");
        for f in &run.fasteners {
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{:.1}</td><td>{:.2}</td><td>{}</td><td>{:.1}</td></tr>",
                f.kind,
                escape(&f.name),
                f.max_force,
                f.max_force_time,
                f.final_state,
                f.holding_force
            );
        }
        s.push_str("</table>");
        for (k, f) in run.fasteners.iter().enumerate() {
            let mine: Vec<(f64, f64, f64)> = run
                .fastener_series
                .iter()
                .filter(|x| x.fastener == k)
                .map(|x| (x.time, x.force, push_limit))
                .collect();
            if mine.iter().any(|p| p.1 > 0.0) {
                let title = format!(
                    "{} '{}': force on the hose (blue), push limit (red, dashed)",
                    f.kind, f.name
                );
                s.push_str(&plot(&title, &mine));
            }
        }
    }
    if !run.peaks.is_empty() {
        s.push_str("<h2>Fixed and driven nodes</h2><table><tr><th>hose</th><th>node</th><th>peak |F| [N]</th><th>at [s]</th><th>peak |M| [N·m]</th><th>at [s]</th></tr>");
        for p in &run.peaks {
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.3}</td><td>{:.2}</td></tr>",
                p.hose, p.node, p.max_force, p.max_force_time, p.max_moment, p.max_moment_time
            );
        }
        s.push_str("</table>");
    }
    checks_section(&mut s, &run.checks, report.drawing);
    if let Some(w) = &run.worker {
        let parts = report.drawing.worker_parts.as_deref();
        super::worker_section::worker_section(
            &mut s,
            w,
            worker_series,
            parts.unwrap_or(&report.drawing.parts),
        );
    }
    if let Some(sweep) = &run.checks.sweep {
        super::sweep_plots::sweep_section(&mut s, sweep);
        if let Some(envelopes) = &report.drawing.envelopes {
            super::envelope_section::envelope_section(
                &mut s,
                envelopes,
                sweep,
                report.drawing.envelope_parts.as_ref(),
                &report.drawing.parts,
            );
        }
    }
    s.push_str("<h2>Contact with parts</h2>");
    if run.contacts.is_empty() {
        s.push_str("<p>No hose touched a part.</p>");
    } else {
        s.push_str("<table><tr><th>part</th><th>from [s]</th><th>to [s]</th><th>steps</th></tr>");
        for c in &run.contacts {
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{}</td></tr>",
                escape(&c.part),
                c.first_time,
                c.last_time,
                c.steps
            );
        }
        let _ = write!(
            s,
            "</table><p>Largest total contact force {:.2} N at t = {:.2} s.</p>",
            run.max_contact_force, run.max_contact_force_time
        );
    }
    s.push_str("</body></html>\n");
    s
}
