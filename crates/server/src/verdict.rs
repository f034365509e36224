//! The running verdict of a live session (SPEC I5, as far as the session has got):
//! feasible so far or not, and why. A hand whose peak push, pull or torque exceeds the
//! limit value of the current ergonomic profile makes the session infeasible, as does a
//! divergence; stubs and clips not yet fitted are listed as still to do.

use crate::ownership::HandId;
use crate::peaks::HandPeaks;
use crate::snapshot::FastenerSnapshot;
use pliant_assembly::ergonomics::{ErgonomicLimits, ErgonomicProfile, LoadKind};
use serde::Serialize;
use std::collections::BTreeMap;

/// Feasible so far or not, with reasons.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RunningVerdict {
    /// `None` while no hand has acted (nothing to judge yet).
    pub feasible: Option<bool>,
    /// Why: each exceeded limit, or the worst load so far when all are within limits.
    pub reasons: Vec<String>,
    /// Stubs and clips not yet fitted.
    pub pending: Vec<String>,
}

/// The limit value of `kind` under `profile` [N or N·m].
pub fn limit_of(limits: &ErgonomicLimits, profile: &ErgonomicProfile, kind: LoadKind) -> f64 {
    let (pop, duty) = (profile.population, profile.duty);
    match kind {
        LoadKind::Push => limits.push_limit(profile.push_posture, pop, duty),
        LoadKind::Pull => limits.pull_limit(profile.pull_posture, pop, duty),
        LoadKind::Torque => limits.torque_limit(profile.torque_grip, pop, duty),
    }
}

fn kind_name(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Push => "push",
        LoadKind::Pull => "pull",
        LoadKind::Torque => "torque",
    }
}

fn unit(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Torque => "N·m",
        _ => "N",
    }
}

impl RunningVerdict {
    /// Judges the peaks so far against `profile`'s limits.
    pub fn judge(
        peaks: &BTreeMap<HandId, HandPeaks>,
        limits: Option<&ErgonomicLimits>,
        profile: &ErgonomicProfile,
        fasteners: &[FastenerSnapshot],
        diverged: Option<&str>,
    ) -> RunningVerdict {
        let mut reasons = Vec::new();
        if let Some(d) = diverged {
            reasons.push(format!("the simulation diverged and was reset: {d}"));
        }
        // (ratio, hand, kind, magnitude, limit, time) of the worst load within limits
        let mut worst: Option<(f64, HandId, LoadKind, f64, f64, f64)> = None;
        let mut exceeded = false;
        if let Some(limits) = limits {
            for (&hand, p) in peaks {
                for (kind, peak) in p.each() {
                    let limit = limit_of(limits, profile, kind);
                    let ratio = peak.magnitude / limit;
                    if !ratio.is_finite() {
                        continue;
                    }
                    if ratio > 1.0 {
                        exceeded = true;
                        reasons.push(format!(
                            "hand {hand}: {} of {:.1} {u} at t = {:.2} s exceeds the limit {:.1} {u} ({:.0} % of it)",
                            kind_name(kind),
                            peak.magnitude,
                            peak.time,
                            limit,
                            100.0 * ratio,
                            u = unit(kind),
                        ));
                    } else if worst.is_none_or(|w| ratio > w.0) {
                        worst = Some((ratio, hand, kind, peak.magnitude, limit, peak.time));
                    }
                }
            }
        }
        let feasible = if diverged.is_some() || exceeded {
            Some(false)
        } else if peaks.is_empty() {
            None
        } else {
            Some(true)
        };
        if feasible.is_none() {
            reasons.push("no hand has acted yet: nothing to judge".into());
        } else if feasible == Some(true) {
            let detail = worst
                .map(|(r, hand, kind, m, l, _)| {
                    format!(
                        "; the worst so far is hand {hand}'s {} of {m:.1} {u}, {:.0} % of the limit {l:.1} {u}",
                        kind_name(kind),
                        100.0 * r,
                        u = unit(kind)
                    )
                })
                .unwrap_or_default();
            reasons.push(format!(
                "every hand load so far is within its ergonomic limit value{detail}"
            ));
        }
        let pending = fasteners
            .iter()
            .filter(|f| !f.report.assembled)
            .map(|f| {
                format!(
                    "{} '{}' not yet fitted (state: {})",
                    f.report.kind, f.report.name, f.report.final_state
                )
            })
            .collect();
        RunningVerdict {
            feasible,
            reasons,
            pending,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::peaks::Peak;

    #[test]
    fn exceeding_a_limit_is_infeasible_and_a_new_profile_rejudges() {
        let limits = ErgonomicLimits::builtin().unwrap();
        let women = ErgonomicProfile::default();
        let men = ErgonomicProfile {
            population: pliant_assembly::ergonomics::Population::Men,
            ..women
        };
        let pull_women = limit_of(limits, &women, LoadKind::Pull);
        let pull_men = limit_of(limits, &men, LoadKind::Pull);
        assert!(pull_women < pull_men);
        let mut peaks = BTreeMap::new();
        let between = 0.5 * (pull_women + pull_men);
        peaks.insert(
            3,
            HandPeaks {
                pull: Peak {
                    magnitude: between,
                    time: 1.5,
                },
                ..Default::default()
            },
        );
        let v = RunningVerdict::judge(&peaks, Some(limits), &women, &[], None);
        assert_eq!(v.feasible, Some(false));
        assert!(
            v.reasons[0].starts_with("hand 3: pull of"),
            "{:?}",
            v.reasons
        );
        let v = RunningVerdict::judge(&peaks, Some(limits), &men, &[], None);
        assert_eq!(v.feasible, Some(true));
        let v = RunningVerdict::judge(&BTreeMap::new(), Some(limits), &men, &[], None);
        assert_eq!(v.feasible, None);
        let v = RunningVerdict::judge(&BTreeMap::new(), Some(limits), &men, &[], Some("x"));
        assert_eq!(v.feasible, Some(false));
    }
}
