//! The verdict of an assembly study (SPEC I5) — the one implementation behind
//! `pliant run`, the live session's running verdict and the Python API: feasible or not,
//! and why. A divergence, or a hand whose peak push or pull exceeds the limit value of
//! the profile, makes it infeasible; at the end of a study a stub or clip not fitted does
//! too, while a study still running lists them as still to do. A hand's twist and bending
//! moment above their guide values are warnings (dissertation section 3.3.3: "never
//! reasons for an installation to fail"), unless the profile's `moments_decide` makes
//! them count like the force. With a worker in the scene (SPEC E1), a hand target out of
//! its reach or a body segment inside a part makes it infeasible too (unless the
//! worker's `decide` is off), and the worst RULA and REBA scores are reported.

use super::tally::{RunSummary, ZoneNote};
use crate::ergonomics::{LoadKind, RiskZone};
use serde::Serialize;

/// Whether the study is over (every fastener should be fitted) or still running.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Running,
    Final,
}

/// Feasible or not, with reasons.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Verdict {
    /// `None` while no hand has acted (nothing to judge).
    pub feasible: Option<bool>,
    /// Why: each exceeded limit, the fasteners not fitted (final stage), the parts
    /// touched, or the worst load when all are within limits.
    pub reasons: Vec<String>,
    /// Stubs and clips not yet fitted (running stage).
    pub pending: Vec<String>,
    /// What an engineer should look at but what does not decide feasibility: twist and
    /// bending above their guide or limit values when moments do not decide.
    pub warnings: Vec<String>,
    /// Some step's solve ended out of balance or on an unstable equilibrium: the loads
    /// the verdict rests on are not trustworthy there (the reasons say where).
    pub uncertain: bool,
    /// The standard that judged the hand forces (push and pull), e.g.
    /// "EN 1005-3:2002+A1:2008".
    pub standard: String,
    /// Under EN 1005-3: each hand's peak push and pull with its risk zone, in words.
    pub zones: Vec<String>,
    /// With a worker in the scene (SPEC E1–E2): who, and the worst RULA and REBA scores
    /// and when, in words. What the worker could not do (out of reach, body collisions)
    /// is among the reasons (or the warnings, when the worker does not decide).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub worker: Vec<String>,
}

/// A peak push or pull against EN 1005-3, in words: value, zone, m_r and how F_R came.
fn describe_zone(hand: usize, z: &ZoneNote) -> String {
    let (l, j) = (&z.limit, &z.judgement);
    let bound = match j.zone {
        RiskZone::Recommended => format!("m_r = F/F_R = {:.2} ≤ {}", j.m_r, l.recommended_max),
        RiskZone::NotRecommended => format!(
            "{} < m_r = F/F_R = {:.2} ≤ {}",
            l.recommended_max, j.m_r, l.not_recommended_max
        ),
        RiskZone::ToBeAvoided => {
            format!("m_r = F/F_R = {:.2} > {}", j.m_r, l.not_recommended_max)
        }
    };
    format!(
        "hand {hand}: {} of {:.1} N at t = {:.2} s is {} ({bound}; EN 1005-3, {}: F_R = {:.1} N = F_Br {:.1} N · m_v {} · m_f {} · m_d {}, F_B = {:.0} N)",
        kind_name(z.kind),
        z.magnitude,
        z.time,
        j.zone.words().to_uppercase(),
        z.action,
        l.f_r,
        l.f_br,
        l.m_v,
        l.m_f,
        l.m_d,
        l.f_b,
    )
}

fn kind_name(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Bending => "bending moment",
        k => k.name(),
    }
}

fn unit(kind: LoadKind) -> &'static str {
    kind.unit()
}

/// What the hand was doing at its worst moment, for the reasons' text: the fastener it
/// worked (index in the run's fastener reports), if any.
fn worked_fastener(run: &RunSummary, fastener: Option<usize>) -> String {
    match fastener.and_then(|i| run.fasteners.get(i)) {
        Some(f) if f.kind == "stub" => format!(" — pressing the hose end onto stub '{}'", f.name),
        Some(f) if f.kind == "connector" => format!(" — plugging connector '{}'", f.name),
        Some(f) => format!(" — pressing the hose into {} '{}'", f.kind, f.name),
        None => String::new(),
    }
}

/// The row of the tables a kind is judged against, for the reasons' text.
fn table(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Push => "table 3.7",
        LoadKind::Pull => "table 3.9",
        LoadKind::Twist => "screwdriver, table 3.11",
        LoadKind::Bending => "T-handle, table 3.11",
    }
}

impl Verdict {
    /// Judges a summary whose hand peaks were judged under the profile of interest
    /// ([`super::Tally::judge_hands`]).
    pub fn judge(run: &RunSummary, diverged: Option<&str>, stage: Stage) -> Verdict {
        let mut reasons = Vec::new();
        let mut pending = Vec::new();
        if let Some(d) = diverged {
            reasons.push(format!("the simulation stopped early: {d}"));
        }
        let mut exceeded = false;
        let mut warnings = Vec::new();
        let mut zones = Vec::new();
        for h in &run.hand_peaks {
            for z in &h.zones {
                let line = describe_zone(h.hand, z);
                if z.judgement.zone == RiskZone::NotRecommended {
                    warnings.push(line.clone());
                }
                zones.push(line);
            }
            if let Some(kind) = h.worst_kind {
                let zone = h.zones.iter().find(|z| z.kind == kind);
                if h.worst_ratio > 1.0 {
                    exceeded = true;
                    let working = worked_fastener(run, h.worst_fastener);
                    if let Some(z) = zone {
                        reasons.push(format!("{}{working}", describe_zone(h.hand, z)));
                    } else {
                        reasons.push(format!(
                        "hand {}: {} of {:.1} {u} at t = {:.2} s exceeds the limit {:.1} {u} ({}; {:.0} % of it){working}",
                        h.hand,
                        kind_name(kind),
                        h.worst_magnitude,
                        h.worst_time,
                        h.worst_limit,
                        table(kind),
                        100.0 * h.worst_ratio,
                        u = unit(kind),
                    ));
                    }
                }
            }
            for n in h
                .moment_notes
                .iter()
                .filter(|n| h.worst_kind != Some(n.kind) || n.magnitude <= n.limit)
            {
                let against = if n.magnitude > n.limit {
                    format!("above the limit {:.2} N·m", n.limit)
                } else {
                    format!(
                        "above the guide range (up to {:.2} N·m; limit {:.2} N·m)",
                        n.guide_hi, n.limit
                    )
                };
                warnings.push(format!(
                    "hand {}: {} of {:.2} N·m at t = {:.2} s is {against} ({}){}",
                    h.hand,
                    kind_name(n.kind),
                    n.magnitude,
                    n.time,
                    table(n.kind),
                    if n.magnitude > n.limit && !run.moments_decide {
                        " — guidance only: the dissertation (3.3.3) never fails an installation for twist or bending"
                    } else {
                        ""
                    },
                ));
            }
        }
        let mut unfitted = false;
        for f in run.fasteners.iter().filter(|f| !f.assembled) {
            match stage {
                Stage::Final => {
                    unfitted = true;
                    let wanted = match f.kind {
                        "stub" => "fixed on it",
                        "connector" => "plugged and latched",
                        _ => "seated in it",
                    };
                    reasons.push(format!(
                        "{} '{}': the hose did not end {wanted} (final state: {})",
                        f.kind, f.name, f.final_state
                    ));
                }
                Stage::Running => pending.push(format!(
                    "{} '{}' not yet fitted (state: {})",
                    f.kind, f.name, f.final_state
                )),
            }
        }
        // Installation checks (SPEC V3): the running ones always, the assembled state's
        // (tension at rest, straight length behind stubs) at the end only.
        // In a range-of-motion study each violation is placed on the motion coordinate,
        // and so is the worst of each quantity.
        let mut violated = false;
        let sweep = run.checks.sweep.as_ref();
        for v in &run.checks.violations {
            if stage == Stage::Running && v.check.at_end_only() {
                continue;
            }
            let line = match sweep.and_then(|s| s.position_at(v.time)) {
                Some(at) => format!("{}, at {at}", v.describe()),
                None => v.describe(),
            };
            if run.checks.decide {
                violated = true;
                reasons.push(line);
            } else {
                warnings.push(line);
            }
        }
        // The worker (SPEC E1–E2): reach and body collisions decide when the scene says
        // so; the posture scores are reported, and warned about when they call for change.
        let mut unworkable = false;
        let mut worker = Vec::new();
        if let Some(w) = &run.worker {
            for f in w.findings() {
                if w.decide {
                    unworkable = true;
                    reasons.push(f.describe());
                } else {
                    warnings.push(f.describe());
                }
            }
            match w.posture_line() {
                Some(line) => {
                    if w.posture_alarming() {
                        warnings.push(line.clone());
                    }
                    worker.push(line);
                }
                None => worker.push(format!("{}: not posed (no hand acted)", w.who)),
            }
        }
        if let Some(s) = sweep {
            for line in s.clearance_violations() {
                if run.checks.decide {
                    violated = true;
                    reasons.push(line);
                } else {
                    warnings.push(line);
                }
            }
            reasons.extend(s.describe());
        }
        if stage == Stage::Final {
            for c in &run.contacts {
                reasons.push(format!(
                    "contact with '{}' from t = {:.2} s to {:.2} s",
                    c.part, c.first_time, c.last_time
                ));
            }
        }
        // the solver's own doubts first: they qualify everything below
        reasons.splice(0..0, run.solver_warnings.iter().cloned());
        reasons.extend(run.instability_notes.iter().cloned());
        let judged = !run.hand_peaks.is_empty();
        // a range-of-motion study is judged by its checks, hands or none
        let swept = run.checks.sweep.is_some();
        let feasible = if diverged.is_some()
            || exceeded
            || violated
            || unworkable
            || ((judged || swept) && unfitted)
        {
            Some(false)
        } else if judged || swept {
            Some(true)
        } else {
            None
        };
        if swept && !judged && feasible == Some(true) {
            reasons.push(match stage {
                Stage::Final => "every stub, connector and clip was fitted, and every installation check passed at every position of the motion".into(),
                Stage::Running => "every installation check has passed so far".into(),
            });
        } else if !judged && !swept {
            reasons.push(match stage {
                Stage::Final => {
                    "no hand acted in this scene: there is no hand load to judge".into()
                }
                Stage::Running => "no hand has acted yet: nothing to judge".into(),
            });
        } else if feasible == Some(true) {
            let worst = run
                .hand_peaks
                .iter()
                .filter(|h| h.worst_kind.is_some())
                .max_by(|a, b| a.worst_ratio.total_cmp(&b.worst_ratio));
            let detail = worst
                .and_then(|h| Some((h, h.worst_kind?)))
                .map(|(h, kind)| {
                    format!(
                        "; the worst is hand {}'s {} of {:.1} {u}, {:.0} % of the limit {:.1} {u}",
                        h.hand,
                        kind_name(kind),
                        h.worst_magnitude,
                        100.0 * h.worst_ratio,
                        h.worst_limit,
                        u = unit(kind)
                    )
                })
                .unwrap_or_default();
            let checks = if run.checks.enabled.is_empty() {
                String::new()
            } else {
                format!(
                    ", and the installation checks ({}) passed",
                    run.checks.enabled.join(", ")
                )
            };
            let reached = match &run.worker {
                Some(w) if w.findings().is_empty() => format!(
                    ", and {} reached every hand target without a body collision",
                    w.who
                ),
                Some(_) => String::new(),
                None => String::new(),
            };
            reasons.push(match stage {
                Stage::Final => format!("every hand load stayed within its ergonomic limit value ({}), every stub, connector and clip was fitted{checks}{reached}", run.standard.title()),
                Stage::Running => format!("every hand load so far is within its ergonomic limit value{detail}"),
            });
        }
        Verdict {
            feasible,
            reasons,
            pending,
            warnings,
            uncertain: !run.solver_warnings.is_empty(),
            standard: run.standard.title().to_string(),
            zones,
            worker,
        }
    }

    /// "FEASIBLE", "NOT FEASIBLE" or "not assessed", with "(UNCERTAIN)" when a solve
    /// ended out of balance or unstable.
    pub fn word(&self) -> &'static str {
        match (self.feasible, self.uncertain) {
            (Some(true), false) => "FEASIBLE",
            (Some(false), false) => "NOT FEASIBLE",
            (None, false) => "not assessed",
            (Some(true), true) => "FEASIBLE (UNCERTAIN)",
            (Some(false), true) => "NOT FEASIBLE (UNCERTAIN)",
            (None, true) => "not assessed (UNCERTAIN)",
        }
    }
}
