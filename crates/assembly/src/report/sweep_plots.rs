//! The report's range-of-motion section: over the motion coordinate, each hose's bend
//! (κ · minimum bend radius against 1), twist and axial force, the clearance of the hose
//! and part pairs that came nearest, and the largest fixing force.

use super::profile_plot::{line_plot, Limit};
use super::svg::escape;
use crate::sweep::{SweepSummary, AXIAL_FORCE, BEND_RATIO, TWIST};
use std::fmt::Write as _;

/// Clearance plots drawn at most (the pairs that came nearest).
pub const MAX_CLEARANCE_PLOTS: usize = 8;

/// Appends the section for `sweep` to `s`.
pub fn sweep_section(s: &mut String, sweep: &SweepSummary) {
    let Some(c) = &sweep.coordinate else {
        return;
    };
    let rows: Vec<&[f64]> = sweep.rows().collect();
    if rows.is_empty() {
        return;
    }
    let (unit, factor) = c.kind.unit();
    let xs: Vec<f64> = rows.iter().map(|r| r[1] * factor).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let label = format!("{} {} ({unit})", c.part_name, c.kind.name());
    let axis = (xs.as_slice(), lo, hi.max(lo + 1e-9), label.as_str());
    s.push_str("<h2>Range of motion</h2>");
    let _ = write!(
        s,
        "<p>Every checked instant against the {} of part '{}' (<code>motion.csv</code>).",
        c.kind.name(),
        escape(&c.part_name)
    );
    if let Some(extremes) = sweep.extremes() {
        let _ = write!(s, " {}.", escape(&extremes.to_string()));
    }
    s.push_str("</p>");
    let series = |f: &dyn Fn(&[f64]) -> f64| -> Vec<f64> { rows.iter().map(|r| f(r)).collect() };
    for (h, name) in sweep.hose_names.iter().enumerate() {
        let checked = sweep
            .allowed_radius
            .get(h)
            .is_some_and(|a| a.iter().any(|&r| r > 0.0));
        if checked {
            let bend = series(&|r| SweepSummary::hose_value(r, h, BEND_RATIO));
            s.push_str(&line_plot(
                &format!("hose '{name}': largest ratio of a beam's minimum bend radius to its radius (above 1 breaks it, red)"),
                axis,
                &bend,
                Limit::Level(1.0),
                false,
                "",
            ));
        }
        let twist = series(&|r| SweepSummary::hose_value(r, h, TWIST).to_degrees());
        s.push_str(&line_plot(
            &format!(
                "hose '{name}': largest twist, limit {:.1} °/m (red)",
                sweep.twist_limit.to_degrees()
            ),
            axis,
            &twist,
            Limit::Level(sweep.twist_limit.to_degrees()),
            false,
            "°/m",
        ));
        let force = series(&|r| SweepSummary::hose_value(r, h, AXIAL_FORCE));
        s.push_str(&line_plot(
            &format!("hose '{name}': largest axial force"),
            axis,
            &force,
            Limit::None,
            false,
            "N",
        ));
    }
    let mut nearest: Vec<(usize, f64)> = (0..sweep.pairs.len())
        .map(|k| {
            let least = rows
                .iter()
                .map(|r| sweep.pair_value(r, k))
                .fold(f64::INFINITY, f64::min);
            (k, least)
        })
        .collect();
    nearest.sort_by(|a, b| a.1.total_cmp(&b.1));
    for &(k, least) in nearest.iter().take(MAX_CLEARANCE_PLOTS) {
        let (h, p) = sweep.pairs[k];
        let gap = series(&|r| 1e3 * sweep.pair_value(r, k));
        s.push_str(&line_plot(
            &format!(
                "clearance of hose '{}' to part '{}' (smallest {:.1} mm{})",
                sweep.hose_names[h],
                sweep.part_names[p],
                1e3 * least,
                sweep.min_clearance.map_or(String::new(), |m| format!(
                    "; minimum {:.1} mm, red",
                    1e3 * m
                ))
            ),
            axis,
            &gap,
            sweep
                .min_clearance
                .map_or(Limit::None, |m| Limit::Level(1e3 * m)),
            false,
            "mm",
        ));
    }
    let fixing = series(&|r| r[sweep.stride - 1]);
    s.push_str(&line_plot(
        "largest fixing force (fixes, mounts, clips, stubs, hands)",
        axis,
        &fixing,
        Limit::None,
        false,
        "N",
    ));
}
