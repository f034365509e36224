//! What the Newton solvers said while a study ran (SPEC S1): the steps that did
//! not reach balance, and the unstable equilibria the static solver met and left
//! (buckling, a bifurcation). They go into `summary.json`, the verdict (an unconverged
//! step makes it "uncertain"), the live snapshot and Python — a study never hides that
//! its numbers rest on an unbalanced or unstable state.

use super::solver_doubt::{InstabilityNote, SolverDoubt};
use pliant_core::integrators::{StabilityEvent, StepStats};
use pliant_core::Model;
use serde::Serialize;

/// Instabilities kept with their mode shape (the count goes on past it).
pub const MAX_INSTABILITIES_KEPT: usize = 32;

/// A step whose Newton solve ended out of balance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Unconverged {
    /// Simulated (input) time at the end of the step \[s\].
    pub time: f64,
    /// Largest out-of-balance force on a free node \[N\] and the limit it had to meet.
    pub residual_force: f64,
    pub force_limit: f64,
    /// Largest out-of-balance moment \[N·m\] and its limit.
    pub residual_moment: f64,
    pub moment_limit: f64,
}

impl Unconverged {
    /// How far out of balance: the larger residual over its limit.
    pub fn ratio(&self) -> f64 {
        let r = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::INFINITY };
        r(self.residual_force, self.force_limit).max(r(self.residual_moment, self.moment_limit))
    }
}

/// An unstable equilibrium the static solver met at an input and left for the stable
/// branch nearby ([`pliant_core::integrators::stability`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Instability {
    /// Input time \[s\].
    pub time: f64,
    /// The hose (index) and its node where the unstable mode moves most.
    pub hose: usize,
    pub node: usize,
    /// Negative eigenvalues of the tangent there (1: one buckling mode passed).
    pub negative_eigenvalues: usize,
    /// A limit point: the load path's branch ended and the hose snapped through to a
    /// distant stable equilibrium (the mode is then the snap's displacement).
    pub limit_point: bool,
    /// Energy released by the first step off \[J\].
    pub energy_drop_j: f64,
    /// The mode: each node of that hose's translation, the largest of length 1.
    pub mode: Vec<[f64; 3]>,
}

/// Rollbacks kept in full (the count goes on past it).
pub const MAX_ROLLBACKS_KEPT: usize = 32;

/// A divergence a live session rolled back ([`super::Input::Rollback`]): the study goes on
/// from a healthy state, without the hands that held the diverging hose.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RolledBack {
    /// When it diverged and the time it went back to \[s\].
    pub diverged_at: f64,
    pub back_to: f64,
    /// The diverging hose and what was found.
    pub hose: String,
    pub reason: String,
    /// The hands released.
    pub released: Vec<super::HandNumber>,
}

/// The Newton solvers' account of a study.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SolverRecord {
    /// Most Newton iterations one step took.
    pub iterations_max: usize,
    /// Steps that ended out of balance, the first and the worst of them.
    pub unconverged_steps: u64,
    pub first_unconverged: Option<Unconverged>,
    pub worst_unconverged: Option<Unconverged>,
    /// Steps that ended on an equilibrium known to be unstable (it could not be left).
    pub unstable_steps: u64,
    /// Unstable equilibria met and left, and the first [`MAX_INSTABILITIES_KEPT`] of
    /// them in full.
    pub instability_count: u64,
    pub instabilities: Vec<Instability>,
    /// Implicit steps Newton could not converge, taken by the explicit solver instead
    /// (`pliant_core::integrators::fallback`), and the time of the first.
    pub explicit_fallback_steps: u64,
    pub first_explicit_fallback: Option<f64>,
    /// Divergences rolled back (any solver), and the first [`MAX_ROLLBACKS_KEPT`] of
    /// them in full.
    pub rollback_count: u64,
    pub rollbacks: Vec<RolledBack>,
}

impl SolverRecord {
    /// Takes in one step's statistics.
    pub fn record_step(&mut self, time: f64, stats: &StepStats) {
        self.iterations_max = self.iterations_max.max(stats.iterations);
        if !stats.converged {
            self.unconverged_steps += 1;
            let u = Unconverged {
                time,
                residual_force: stats.residual_force,
                force_limit: stats.force_limit,
                residual_moment: stats.residual_moment,
                moment_limit: stats.moment_limit,
            };
            self.first_unconverged.get_or_insert(u);
            if self.worst_unconverged.is_none_or(|w| u.ratio() > w.ratio()) {
                self.worst_unconverged = Some(u);
            }
        }
        if stats.unstable {
            self.unstable_steps += 1;
        }
        if stats.explicit_fallback > 0 {
            self.explicit_fallback_steps += 1;
            self.first_explicit_fallback.get_or_insert(time);
        }
    }

    /// Takes in the instabilities one step met and left.
    pub fn record_instabilities(&mut self, model: &Model, events: &[StabilityEvent]) {
        for e in events {
            self.instability_count += 1;
            if self.instabilities.len() < MAX_INSTABILITIES_KEPT {
                self.instabilities.push(instability(model, e));
            }
        }
    }

    /// Takes in a rollback.
    pub fn record_rollback(&mut self, rollback: RolledBack) {
        self.rollback_count += 1;
        if self.rollbacks.len() < MAX_ROLLBACKS_KEPT {
            self.rollbacks.push(rollback);
        }
    }

    /// Whether the study's numbers rest on a state out of balance or unstable, or on a
    /// session that diverged (rolled back: what the released hands were doing was cut
    /// short).
    pub fn uncertain(&self) -> bool {
        self.unconverged_steps > 0 || self.unstable_steps > 0 || self.rollback_count > 0
    }

    /// Why the study is uncertain (empty when it is not).
    pub fn warnings(&self) -> Vec<SolverDoubt> {
        let mut out = Vec::new();
        if let (Some(first), Some(worst)) = (self.first_unconverged, self.worst_unconverged) {
            out.push(SolverDoubt::OutOfBalance {
                steps: self.unconverged_steps,
                first,
                worst,
            });
        }
        if self.unstable_steps > 0 {
            out.push(SolverDoubt::Unstable {
                steps: self.unstable_steps,
            });
        }
        if let Some(first) = self.rollbacks.first() {
            out.push(SolverDoubt::RolledBack {
                count: self.rollback_count,
                first: first.clone(),
            });
        }
        out
    }

    /// The instabilities met, and the implicit steps taken explicitly (buckling and a
    /// fallback are information, not a failure).
    pub fn instability_notes(&self, hose_name: impl Fn(usize) -> String) -> Vec<InstabilityNote> {
        let mut out: Vec<InstabilityNote> = self
            .instabilities
            .iter()
            .map(|i| {
                if i.limit_point {
                    InstabilityNote::SnappedThrough {
                        hose: hose_name(i.hose),
                        time: i.time,
                        node: i.node,
                    }
                } else {
                    InstabilityNote::Buckled {
                        hose: hose_name(i.hose),
                        time: i.time,
                        node: i.node,
                        negative_eigenvalues: i.negative_eigenvalues,
                    }
                }
            })
            .collect();
        let more = self
            .instability_count
            .saturating_sub(self.instabilities.len() as u64);
        if more > 0 {
            out.push(InstabilityNote::More { count: more });
        }
        if let Some(first_time) = self.first_explicit_fallback {
            out.push(InstabilityNote::ExplicitFallback {
                steps: self.explicit_fallback_steps,
                first_time,
            });
        }
        out
    }
}

/// A stability event of the core solver, on its hose.
fn instability(model: &Model, e: &StabilityEvent) -> Instability {
    let (hose, first, nodes) = model
        .hoses
        .iter()
        .enumerate()
        .find(|(_, h)| h.nodes().contains(&e.node))
        .map(|(k, h)| (k, h.first_node, h.nodes()))
        .unwrap_or((0, 0, 0..0));
    let largest = nodes
        .clone()
        .map(|i| e.mode.get(i).map_or(0.0, |m| m.length()))
        .fold(0.0, f64::max);
    let scale = if largest > 0.0 { 1.0 / largest } else { 0.0 };
    Instability {
        time: e.time,
        hose,
        node: e.node - first,
        negative_eigenvalues: e.negative_eigenvalues,
        limit_point: e.limit_point,
        energy_drop_j: e.energy_drop,
        mode: nodes
            .map(|i| e.mode.get(i).map_or([0.0; 3], |m| (*m * scale).to_array()))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workcell::{Reason, RunSummary, Stage, Verdict};

    fn out_of_balance(time: f64, residual_force: f64) -> (f64, StepStats) {
        let stats = StepStats {
            iterations: 60,
            residual_force,
            force_limit: 1e-6,
            residual_moment: 0.0,
            moment_limit: 1e-7,
            converged: false,
            ..Default::default()
        };
        (time, stats)
    }

    /// Unconverged steps are counted, the first and the worst kept, and the verdict
    /// built on them says UNCERTAIN with the reason first.
    #[test]
    fn unconverged_steps_make_the_verdict_uncertain() {
        let mut record = SolverRecord::default();
        let fine = StepStats {
            iterations: 3,
            converged: true,
            ..Default::default()
        };
        record.record_step(0.01, &fine);
        assert!(!record.uncertain() && record.warnings().is_empty());
        for (t, r) in [(0.02, 1e-3), (0.03, 5e-3), (0.04, 2e-3)] {
            let (time, stats) = out_of_balance(t, r);
            record.record_step(time, &stats);
        }
        assert_eq!(record.unconverged_steps, 3);
        assert_eq!(record.iterations_max, 60);
        assert_eq!(record.first_unconverged.unwrap().time, 0.02);
        assert_eq!(record.worst_unconverged.unwrap().time, 0.03);
        let warnings = record.warnings();
        assert_eq!(warnings.len(), 1);
        assert!(
            warnings[0]
                .to_string()
                .contains("3 step(s), first at t = 0.020 s"),
            "{warnings:?}"
        );
        let run = RunSummary {
            solver_warnings: warnings.clone(),
            ..Default::default()
        };
        let verdict = Verdict::judge(&run, None, Stage::Final);
        assert!(verdict.uncertain);
        assert_eq!(verdict.word(), "not assessed (UNCERTAIN)");
        assert_eq!(verdict.reasons[0], warnings[0].to_string());
        assert_eq!(
            verdict.findings.reasons[0],
            Reason::Solver(warnings[0].clone())
        );
        let certain = Verdict::judge(&RunSummary::default(), None, Stage::Final);
        assert!(!certain.uncertain);
        assert_eq!(certain.word(), "not assessed");
    }
}
