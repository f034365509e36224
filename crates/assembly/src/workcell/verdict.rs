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

use super::reason::{LoadAgainstLimit, Reason, WorkedFastener};
use super::tally::{HandPeak, RunSummary};
use crate::ergonomics::RiskZone;
use serde::Serialize;

/// Whether the study is over (every fastener should be fitted) or still running.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stage {
    Running,
    Final,
}

/// Feasible or not, with reasons: each line in words and, in `findings`, as a typed
/// value (`reasons[i]` is `findings.reasons[i]` worded, and so on).
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
    /// The same lines as typed values, for programs: which hand, hose or fastener, the
    /// value, the limit and when.
    pub findings: Findings,
}

/// A verdict's lines as typed values, list by list as [`Verdict`] words them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Findings {
    pub reasons: Vec<Reason>,
    pub pending: Vec<Reason>,
    pub warnings: Vec<Reason>,
    pub zones: Vec<Reason>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub worker: Vec<Reason>,
}

/// The fastener a hand worked (index in the run's fastener reports), if any.
fn worked_fastener(run: &RunSummary, fastener: Option<usize>) -> Option<WorkedFastener> {
    let f = run.fasteners.get(fastener?)?;
    Some(WorkedFastener {
        fastener: f.kind,
        name: f.name.clone(),
    })
}

/// A hand's worst load against its limit, if it has one.
fn worst_load(h: &HandPeak) -> Option<LoadAgainstLimit> {
    Some(LoadAgainstLimit {
        hand: h.hand,
        load: h.worst_kind?,
        value: h.worst_magnitude,
        limit: h.worst_limit,
        ratio: h.worst_ratio,
        time: h.worst_time,
        posture_class: h.worst_class,
    })
}

/// Where a finding goes: among the reasons when it decides, else among the warnings.
fn file(found: &mut Findings, decides: bool, line: Reason) {
    if decides {
        found.reasons.push(line);
    } else {
        found.warnings.push(line);
    }
}

impl Verdict {
    /// Judges a summary whose hand peaks were judged under the profile of interest
    /// ([`super::Tally::judge_hands`]).
    pub fn judge(run: &RunSummary, diverged: Option<&str>, stage: Stage) -> Verdict {
        let mut found = Findings::default();
        // the solver's own doubts first: they qualify everything below
        found
            .reasons
            .extend(run.solver_warnings.iter().cloned().map(Reason::Solver));
        if let Some(d) = diverged {
            found.reasons.push(Reason::StoppedEarly {
                message: d.to_string(),
            });
        }
        let mut exceeded = false;
        for h in &run.hand_peaks {
            for z in &h.zones {
                let line = Reason::HandForceZone {
                    hand: h.hand,
                    zone: z.clone(),
                    working: None,
                };
                if z.judgement.zone == RiskZone::NotRecommended {
                    found.warnings.push(line.clone());
                }
                found.zones.push(line);
            }
            if let Some(load) = worst_load(h).filter(|l| l.ratio > 1.0) {
                exceeded = true;
                let working = worked_fastener(run, h.worst_fastener);
                found
                    .reasons
                    .push(match h.zones.iter().find(|z| z.kind == load.load) {
                        Some(z) => Reason::HandForceZone {
                            hand: h.hand,
                            zone: z.clone(),
                            working,
                        },
                        None => Reason::HandLoadOverLimit { load, working },
                    });
            }
            for n in h
                .moment_notes
                .iter()
                .filter(|n| h.worst_kind != Some(n.kind) || n.magnitude <= n.limit)
            {
                found.warnings.push(Reason::MomentAboveGuide {
                    hand: h.hand,
                    load: n.kind,
                    value: n.magnitude,
                    time: n.time,
                    guide_hi: n.guide_hi,
                    limit: n.limit,
                    moments_decide: run.moments_decide,
                });
            }
        }
        let mut unfitted = false;
        for f in run.fasteners.iter().filter(|f| !f.assembled) {
            match stage {
                Stage::Final => {
                    unfitted = true;
                    found.reasons.push(Reason::FastenerNotFitted {
                        fastener: f.kind,
                        name: f.name.clone(),
                        final_state: f.final_state,
                    });
                }
                Stage::Running => found.pending.push(Reason::FastenerPending {
                    fastener: f.kind,
                    name: f.name.clone(),
                    state: f.final_state,
                }),
            }
        }
        // Installation checks (SPEC V3): the running ones always, the assembled state's
        // (tension at rest, straight length behind stubs) at the end only.
        // In a range-of-motion study each violation is placed on the motion coordinate,
        // and so is the worst of each quantity.
        let decide = run.checks.decide;
        let sweep = run.checks.sweep.as_ref();
        let mut violated = false;
        for v in &run.checks.violations {
            if stage == Stage::Running && v.check.at_end_only() {
                continue;
            }
            violated |= decide;
            let line = Reason::CheckViolated {
                violation: v.clone(),
                position: sweep.and_then(|s| s.position_at(v.time)),
            };
            file(&mut found, decide, line);
        }
        // The worker (SPEC E1–E2): reach and body collisions decide when the scene says
        // so; the posture scores are reported, and warned about when they call for change.
        let mut unworkable = false;
        if let Some(w) = &run.worker {
            for finding in w.findings() {
                unworkable |= w.decide;
                file(&mut found, w.decide, Reason::Worker { finding });
            }
            match w.posture_note() {
                Some(note) => {
                    if note.alarming() {
                        found.warnings.push(Reason::Posture(note.clone()));
                    }
                    found.worker.push(Reason::Posture(note));
                }
                None => found.worker.push(Reason::NotPosed { who: w.who.clone() }),
            }
            found
                .worker
                .extend(w.steps.iter().cloned().map(Reason::Step));
            let unlisted = w.step_count.saturating_sub(w.steps.len() as u64);
            if unlisted > 0 {
                found.worker.push(Reason::MoreSteps { count: unlisted });
            }
        }
        if let Some(s) = sweep {
            for c in s.clearance_violations() {
                violated |= decide;
                file(&mut found, decide, Reason::ClearanceViolated(c));
            }
            if let Some(extremes) = s.extremes() {
                found.reasons.push(Reason::MotionExtremes(extremes));
            }
        }
        if stage == Stage::Final {
            found
                .reasons
                .extend(run.contacts.iter().map(|c| Reason::Contact {
                    part: c.part.clone(),
                    first_time: c.first_time,
                    last_time: c.last_time,
                }));
        }
        found.reasons.extend(
            run.instability_notes
                .iter()
                .cloned()
                .map(Reason::Instability),
        );
        let judged = !run.hand_peaks.is_empty();
        // a range-of-motion study is judged by its checks, hands or none
        let swept = sweep.is_some();
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
            found.reasons.push(Reason::ChecksPassed { stage });
        } else if !judged && !swept {
            found.reasons.push(Reason::NoHandActed { stage });
        } else if feasible == Some(true) {
            found.reasons.push(match stage {
                Stage::Final => Reason::WithinLimits {
                    standard: run.standard,
                    checks: run.checks.enabled.clone(),
                    reached: run
                        .worker
                        .as_ref()
                        .filter(|w| w.findings().is_empty())
                        .map(|w| w.who.clone()),
                },
                Stage::Running => Reason::WithinLimitsSoFar {
                    worst: run
                        .hand_peaks
                        .iter()
                        .filter_map(worst_load)
                        .max_by(|a, b| a.ratio.total_cmp(&b.ratio)),
                },
            });
        }
        Verdict::worded(
            feasible,
            found,
            !run.solver_warnings.is_empty(),
            run.standard.title(),
        )
    }

    /// The verdict of `findings`, each line worded by its `Display`.
    fn worded(
        feasible: Option<bool>,
        findings: Findings,
        uncertain: bool,
        standard: &str,
    ) -> Verdict {
        let words = |lines: &[Reason]| lines.iter().map(Reason::to_string).collect();
        Verdict {
            feasible,
            reasons: words(&findings.reasons),
            pending: words(&findings.pending),
            warnings: words(&findings.warnings),
            uncertain,
            standard: standard.to_string(),
            zones: words(&findings.zones),
            worker: words(&findings.worker),
            findings,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fastener_state::{FastenerKind, FastenerState};
    use crate::fasteners::FastenerReport;

    /// A clip left snapping: at the end a reason (not feasible), while running a pending
    /// fastener (feasible so far) — each decided as a typed line, worded by `Display`, and
    /// serialised both ways.
    #[test]
    fn a_fastener_not_fitted_decides_at_the_end_and_is_pending_while_running() {
        let run = RunSummary {
            hand_peaks: vec![HandPeak::default()],
            fasteners: vec![FastenerReport {
                name: "c".into(),
                kind: FastenerKind::Clip,
                final_state: FastenerState::Snapping,
                ..Default::default()
            }],
            ..Default::default()
        };
        let end = Verdict::judge(&run, None, Stage::Final);
        assert_eq!(end.feasible, Some(false));
        assert_eq!(
            end.findings.reasons,
            [Reason::FastenerNotFitted {
                fastener: FastenerKind::Clip,
                name: "c".into(),
                final_state: FastenerState::Snapping,
            }]
        );
        assert_eq!(
            end.reasons,
            ["clip 'c': the hose did not end seated in it (final state: snapping)"]
        );
        let json = serde_json::to_value(&end).unwrap();
        assert_eq!(json["reasons"][0], end.reasons[0].as_str());
        assert_eq!(
            json["findings"]["reasons"][0],
            serde_json::json!({
                "kind": "fastener_not_fitted",
                "fastener": "clip",
                "name": "c",
                "final_state": "snapping",
            })
        );

        let now = Verdict::judge(&run, None, Stage::Running);
        assert_eq!(now.feasible, Some(true));
        assert_eq!(now.pending, ["clip 'c' not yet fitted (state: snapping)"]);
        assert_eq!(
            now.findings.pending,
            [Reason::FastenerPending {
                fastener: FastenerKind::Clip,
                name: "c".into(),
                state: FastenerState::Snapping,
            }]
        );
        assert_eq!(
            now.findings.reasons,
            [Reason::WithinLimitsSoFar { worst: None }]
        );
        assert_eq!(
            now.reasons,
            ["every hand load so far is within its ergonomic limit value"]
        );
    }
}
