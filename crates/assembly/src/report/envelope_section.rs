//! The report's swept-envelope section (SPEC K2): per hose its envelope over the motion
//! (file, voxels, volume), its clearance to each part that stands still beside the
//! smallest clearance recorded over time, and a picture of the envelopes over the parts
//! in the three views. The picture fills the pixels the occupied voxels cover (each
//! voxel's centre projected, a square of the voxel's projected size around it), one
//! `<rect>` per run of pixels in a row.

use super::part_outline::{PartOutline, View};
use super::scene_picture::{draw_parts, Frame};
use super::svg::escape;
use crate::sweep::envelope::SweptEnvelopes;
use crate::sweep::SweepSummary;
use glam::DVec3;
use std::fmt::Write as _;

/// The picture's pixels (as the scene pictures').
const PIXELS: (usize, usize) = (300, 250);
/// The envelopes' colours, hose by hose.
const COLOURS: [&str; 4] = ["#036", "#a40", "#070", "#707"];

/// Appends the section for `envelopes` of `sweep` to `s`, the parts drawn at `posed`
/// (an instant and every part's outline at its pose then), else `at_rest` where the scene
/// placed them.
pub fn envelope_section(
    s: &mut String,
    envelopes: &SweptEnvelopes,
    sweep: &SweepSummary,
    posed: Option<&(f64, Vec<PartOutline>)>,
    at_rest: &[PartOutline],
) {
    s.push_str("<h2>Swept envelopes</h2>");
    if let Some(why) = &envelopes.refused {
        let _ = write!(s, "<p>No envelope: {}.</p>", escape(why));
        return;
    }
    let h = envelopes.voxel_m;
    let _ = write!(
        s,
        "<p>The volume each hose's tube took at some checked instant of the motion: voxels of {:.1} mm \
         whose centre lies within r + 1.33 h of a centre-line sample; the surface of their cubes \
         (one STL per hose) contains every recorded tube and reaches at most about 2.4 voxels beyond it. \
         Clearances to the parts that stand still; ",
        1e3 * h
    );
    if envelopes.moving_parts.is_empty() {
        s.push_str("no part moves.</p>");
    } else {
        let names: Vec<String> = envelopes
            .moving_parts
            .iter()
            .map(|p| format!("'{}'", escape(p)))
            .collect();
        let _ = write!(
            s,
            "the clearance to {} (moving) is the one of each instant, in <code>motion.csv</code> and the plots above.</p>",
            names.join(", ")
        );
    }
    s.push_str("<table><tr><th>hose</th><th>files</th><th>voxels</th><th>volume [cm³]</th><th>triangles</th><th>closed</th></tr>");
    for e in &envelopes.hoses {
        let _ = write!(
            s,
            "<tr><td>{}</td><td><a href=\"{stl}\">{stl}</a>, <a href=\"{glb}\">{glb}</a></td><td>{}</td><td>{:.1}</td><td>{}</td><td>{}</td></tr>",
            escape(&e.hose),
            e.voxels,
            1e6 * e.volume_m3,
            e.triangles,
            if e.closed { "yes" } else { "no" },
            stl = escape(&e.stl),
            glb = escape(&e.glb),
        );
    }
    s.push_str("</table>");
    s.push_str("<table><tr><th>hose</th><th>part</th><th>envelope clearance [mm]</th><th>smallest over time [mm]</th></tr>");
    for e in &envelopes.hoses {
        let hose = sweep.hose_names.iter().position(|n| *n == e.hose);
        for c in &e.clearance {
            let part = sweep.part_names.iter().position(|n| *n == c.part);
            let over_time = sweep
                .pairs
                .iter()
                .position(|&(hh, p)| Some(hh) == hose && Some(p) == part)
                .map(|k| {
                    sweep
                        .rows()
                        .map(|r| sweep.pair_value(r, k))
                        .fold(f64::INFINITY, f64::min)
                })
                .filter(|v| v.is_finite())
                .map_or("—".to_string(), |v| format!("{:.1}", 1e3 * v));
            let _ = write!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{:.1}</td><td>{over_time}</td></tr>",
                escape(&e.hose),
                escape(&c.part),
                1e3 * c.clearance_m
            );
        }
    }
    s.push_str("</table>");
    if envelopes.hoses.is_empty() {
        return;
    }
    let parts = match posed {
        Some((time, parts)) => {
            let at = sweep
                .position_at(*time)
                .map_or(String::new(), |p| format!(", {}", escape(&p)));
            let _ = write!(
                s,
                "<div><p style=\"margin:0.5em 0 0 0\">The envelopes over the parts, drawn where they were at the worst bend (t = {time:.2} s{at}):</p>"
            );
            parts.as_slice()
        }
        None => {
            s.push_str("<div><p style=\"margin:0.5em 0 0 0\">The envelopes over the parts (where the scene placed them):</p>");
            at_rest
        }
    };
    for (k, view) in View::all().iter().enumerate() {
        let centre = |v: [i64; 3]| view.project(DVec3::from_array(v.map(|x| x as f64 * h)));
        let frame = Frame::around(
            envelopes
                .hoses
                .iter()
                .flat_map(|e| [e.bounds_m[0], e.bounds_m[1]])
                .map(|p| view.project(DVec3::from_array(p))),
        );
        frame.open(s);
        draw_parts(s, parts, k, |q| frame.px(q));
        // a cube of side h seen along an axis is h wide, obliquely up to √2 h
        let half = 0.5 * h * frame.scale() * if k < 2 { 1.0 } else { 1.42 };
        for (j, e) in envelopes.hoses.iter().enumerate() {
            let (w, hgt) = PIXELS;
            let mut covered = vec![false; w * hgt];
            for v in e.grid.voxels() {
                let (x, y) = frame.px(centre(v));
                let clip = |a: f64, n: usize| a.clamp(0.0, n as f64 - 1.0) as usize;
                let (x0, x1) = (clip((x - half).round(), w), clip((x + half).round(), w));
                let (y0, y1) = (clip((y - half).round(), hgt), clip((y + half).round(), hgt));
                for row in covered.chunks_mut(w).take(y1 + 1).skip(y0) {
                    row[x0..=x1].fill(true);
                }
            }
            let colour = COLOURS[j % COLOURS.len()];
            let _ = write!(
                s,
                "<g fill=\"{colour}\" fill-opacity=\"0.45\"><title>{}</title>",
                escape(&e.hose)
            );
            for (y, row) in covered.chunks(w).enumerate() {
                let mut x = 0;
                while x < w {
                    if !row[x] {
                        x += 1;
                        continue;
                    }
                    let start = x;
                    while x < w && row[x] {
                        x += 1;
                    }
                    let _ = write!(
                        s,
                        "<rect x=\"{start}\" y=\"{y}\" width=\"{}\" height=\"1\"/>",
                        x - start
                    );
                }
            }
            s.push_str("</g>");
        }
        let _ = write!(
            s,
            "<text x=\"4\" y=\"12\" font-size=\"10\">{}</text></svg>",
            view.name
        );
    }
    s.push_str("</div>");
}
