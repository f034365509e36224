//! The worker's outputs (SPEC E1–E2): `worker.csv` (one row per posed instant, SI) and
//! the report's section — who stood where, reach, body collisions, the worst RULA and
//! REBA with their body-part scores, both scores plotted over time, and a picture of the
//! worst posture.

use super::svg::escape;
use crate::worker::{WorkerSample, WorkerSummary};
use std::fmt::Write as _;

/// `worker.csv`: time, per arm the hand it follows and its reach residual (empty without
/// a target), RULA grand score, REBA score, trunk and neck angles, per arm the upper arm
/// and elbow flexion, the deepest body collision, the posture class (whose rows judge
/// the hand forces).
pub fn worker_csv(series: &[WorkerSample]) -> String {
    let mut s = String::from(
        "time_s,right_hand,right_residual_m,left_hand,left_residual_m,rula,reba,trunk_flexion_rad,trunk_lateral_rad,trunk_twist_rad,neck_flexion_rad,right_upper_arm_rad,left_upper_arm_rad,right_elbow_rad,left_elbow_rad,collision_depth_m,posture_class\n",
    );
    let opt = |v: Option<usize>| v.map_or(String::new(), |h| h.to_string());
    let optf = |v: Option<f64>| v.map_or(String::new(), |r| format!("{r:.6}"));
    for w in series {
        let _ = writeln!(
            s,
            "{:.6},{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{}",
            w.time,
            opt(w.hand[0]),
            optf(w.residual[0]),
            opt(w.hand[1]),
            optf(w.residual[1]),
            w.rula,
            w.reba,
            w.trunk_flexion,
            w.trunk_lateral,
            w.trunk_twist,
            w.neck_flexion,
            w.upper_arm[0],
            w.upper_arm[1],
            w.elbow[0],
            w.elbow[1],
            w.collision_depth,
            w.posture_class.name()
        );
    }
    s
}

/// RULA (0–7) and REBA (0–15) over time, both on a 0–15 axis.
fn score_plot(series: &[WorkerSample]) -> String {
    let (w, h, pad) = (640.0, 220.0, 40.0);
    let t_max = series.iter().map(|s| s.time).fold(1e-9, f64::max);
    let x = |t: f64| pad + (w - 2.0 * pad) * t / t_max;
    let y = |v: f64| h - pad - (h - 2.0 * pad) * v / 15.0;
    let line = |f: &dyn Fn(&WorkerSample) -> u8| {
        series
            .iter()
            .map(|s| format!("{:.1},{:.1}", x(s.time), y(f(s) as f64)))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut svg = super::svg::open(
        w,
        h,
        pad,
        "RULA (blue, 1–7) and REBA (orange, 1–15) over time",
    );
    let _ = write!(
        svg,
        "<line x1=\"{pad}\" y1=\"{0}\" x2=\"{1}\" y2=\"{0}\" stroke=\"#888\"/><line x1=\"{pad}\" y1=\"{pad}\" x2=\"{pad}\" y2=\"{0}\" stroke=\"#888\"/>",
        h - pad,
        w - pad
    );
    let _ = write!(
        svg,
        "<text x=\"{}\" y=\"{}\" font-size=\"11\">{t_max:.1} s</text><text x=\"2\" y=\"{}\" font-size=\"11\">15</text>",
        w - pad - 20.0,
        h - pad + 15.0,
        pad + 4.0
    );
    let _ = write!(
        svg,
        "<polyline fill=\"none\" stroke=\"#036\" stroke-width=\"1.5\" points=\"{}\"/><polyline fill=\"none\" stroke=\"#d60\" stroke-width=\"1.5\" points=\"{}\"/></svg>",
        line(&|s| s.rula),
        line(&|s| s.reba)
    );
    svg
}

/// The report's worker section; `parts` the parts' outlines for the picture of the worst
/// posture.
pub fn worker_section(
    s: &mut String,
    w: &WorkerSummary,
    series: &[WorkerSample],
    parts: &[super::part_outline::PartOutline],
) {
    s.push_str("<h2>Worker</h2>");
    let b = &w.body;
    let _ = write!(
        s,
        "<p>{} (stature {:.0} mm, shoulder height {:.0} mm, arm reach to the grip {:.0} mm; data/anthropometry.toml), ",
        escape(&w.who),
        1e3 * b.stature,
        1e3 * b.dims.shoulder_height,
        1e3 * b.arm_reach()
    );
    match &w.placement {
        Some(p) => {
            let _ = write!(
                s,
                "{} at ({:.3}, {:.3}, {:.3}) m facing ({:.2}, {:.2}, {:.2}); posed at {} instants.</p>",
                match w.seat {
                    Some(seat) => format!("seated on a seat {:.0} mm high", 1e3 * seat.height),
                    None => "standing".to_string(),
                },
                p.position.x, p.position.y, p.position.z, p.forward.x, p.forward.y, p.forward.z, w.instants
            );
        }
        None => s.push_str("never placed: no hand acted.</p>"),
    }
    let c = &w.class_instants;
    if w.instants > 0 {
        let _ = write!(
            s,
            "<p>Posture class (it chooses the rows of the push and pull tables): standing upright at {} instants, bent trunk at {}, arms above shoulder at {}, sitting at {}, sitting with bent trunk at {}.</p>",
            c.upright, c.bent_trunk, c.arms_above_shoulder, c.sitting, c.sitting_bent_trunk
        );
    }
    let findings = w.findings();
    if findings.is_empty() {
        s.push_str("<p>Every hand target within reach; no body collision.</p>");
    } else {
        s.push_str("<ul>");
        for f in &findings {
            let _ = write!(s, "<li>{}</li>", escape(&f.describe()));
        }
        s.push_str("</ul>");
    }
    if let (Some(r), Some(e)) = (w.worst_rula, w.worst_reba) {
        let (r, e) = (r, e);
        let _ = write!(
            s,
            "<table><tr><th>method</th><th>worst</th><th>at [s]</th><th>body-part scores</th></tr>\
             <tr><td>RULA</td><td>{}</td><td>{:.2}</td><td>upper arm {}, lower arm {}, wrist {}, twist {}, A {}, muscle {}, force {}; neck {}, trunk {}, legs {}, B {}</td></tr>\
             <tr><td>REBA</td><td>{}</td><td>{:.2}</td><td>trunk {}, neck {}, legs {}, A {} + load {}; upper arm {}, lower arm {}, wrist {}, B {} + coupling {}; C {} + activity {}</td></tr></table>",
            r.score.grand, r.time, r.score.upper_arm, r.score.lower_arm, r.score.wrist, r.score.wrist_twist,
            r.score.posture_a, r.score.muscle_use, r.score.force, r.score.neck, r.score.trunk, r.score.legs, r.score.posture_b,
            e.score.reba, e.time, e.score.trunk, e.score.neck, e.score.legs, e.score.posture_a, e.score.load,
            e.score.upper_arm, e.score.lower_arm, e.score.wrist, e.score.posture_b, e.score.coupling, e.score.score_c, e.score.activity
        );
    }
    if series.len() > 1 {
        s.push_str(&score_plot(series));
    }
    if let (Some(p), Some(r)) = (&w.worst_posture, w.worst_rula) {
        s.push_str(&super::worker_picture::worker_picture(
            &format!(
                "The worst posture (RULA {} at t = {:.2} s; the parts where they were then); hand targets circled:",
                r.score.grand, r.time
            ),
            &w.body,
            p,
            parts,
        ));
    }
}
