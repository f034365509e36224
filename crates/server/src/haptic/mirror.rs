//! The haptic stream's quasi-static mirror of the session (SPEC H1, P5): a copy of the
//! session's state — every hose, load case (the stubs' and clips' fixes and supports as
//! the session has them), contact memory and hand — re-synchronised from the session at
//! its snapshot rate, on which the haptic thread answers a hand pose with the static
//! equilibrium there (the [`StaticSolver`] the session's `static` solver uses: Newton on
//! the consistent tangent, Armijo line search, stable branch) and the load the hand
//! applies in it (dissertation eq. 5.2; [`pliant_assembly::Hand::load`]).
//!
//! Between two synchronisations each answer starts from the previous one (the pose moves
//! a little per millisecond, so Newton needs one or two iterations); a synchronisation
//! puts the mirror back on the session's newest state, so the two never drift apart by
//! more than one snapshot interval. The mirror changes nothing in the session: the pose
//! reaches the session as the hand's `move` (see [`super`]).
//!
//! Each pose is solved on the hand's component alone ([`component`], [`HandCut`]):
//! the part of the scene between the nodes held in all six degrees of freedom around the
//! hand, whose equilibrium does not depend on the rest. The cut is kept while its nodes
//! and load cases stay the same from one synchronisation to the next, and made again
//! otherwise.

use glam::{DQuat, DVec3};
use pliant_assembly::workcell::{HandNumber, HeldHand};
use pliant_core::integrators::statics::{StaticError, StaticReport};
use pliant_core::integrators::StaticSolver;
use pliant_core::{Model, State};
use std::sync::Arc;
use std::time::Instant;

use super::cut::HandCut;
use super::datagram::Status;
use pliant_core::integrators::component::component;
use pliant_core::integrators::cut::Cut;

/// What the session publishes for the mirror: its model, a copy of its state and hands.
#[derive(Clone)]
pub struct SessionCopy {
    pub model: Arc<Model>,
    pub state: State,
    pub hands: Vec<(HandNumber, HeldHand)>,
    /// Resets of the session so far (hands of an older epoch are gone).
    pub epoch: u64,
    /// Commands the session had applied when the copy was taken
    /// ([`crate::Session::send_counted`]).
    pub taken: u64,
}

/// The answer to one pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Answer {
    pub status: Status,
    pub force: DVec3,
    pub torque: DVec3,
    pub hose: u32,
    pub iterations: u16,
    pub session_time: f64,
    pub solve_seconds: f64,
}

impl Answer {
    fn status(status: Status, session_time: f64) -> Answer {
        Answer {
            status,
            force: DVec3::ZERO,
            torque: DVec3::ZERO,
            hose: u32::MAX,
            iterations: 0,
            session_time,
            solve_seconds: 0.0,
        }
    }
}

/// The mirror: the state it solves on, its hands and its solver.
pub struct Mirror {
    source: Arc<SessionCopy>,
    state: State,
    hands: Vec<(HandNumber, HeldHand)>,
    solver: StaticSolver,
    /// Whether poses are solved on the hand's component alone ([`Cut`]).
    cutting: bool,
    /// The component of the hand answered last, with its own solver.
    cut: Option<(HandNumber, HandCut, StaticSolver)>,
    /// The component a cut was refused for (solved whole until the next
    /// re-synchronisation).
    refused: Option<HandNumber>,
}

impl Mirror {
    /// A mirror of `source` (allocates the solver's buffers once).
    pub fn new(source: Arc<SessionCopy>) -> Result<Mirror, String> {
        let solver = StaticSolver::new(&source.model).map_err(|e| e.to_string())?;
        Ok(Mirror {
            state: source.state.clone(),
            hands: source.hands.clone(),
            source,
            solver,
            cutting: true,
            cut: None,
            refused: None,
        })
    }

    /// Whether poses are solved on the hand's component alone (the default) or on the
    /// whole scene; both give the same equilibrium to the solver's tolerance.
    pub fn set_cutting(&mut self, cutting: bool) {
        self.cutting = cutting;
        self.cut = None;
    }

    /// Nodes of the problem the last answer solved: its component's, or the whole
    /// scene's.
    pub fn solved_nodes(&self) -> usize {
        match &self.cut {
            Some((_, cut, _)) => cut.cut.nodes.len(),
            None => self.state.x.len(),
        }
    }

    /// Whether `source` is of the same model (else a new mirror is needed).
    pub fn same_model(&self, source: &SessionCopy) -> bool {
        Arc::ptr_eq(&self.source.model, &source.model)
    }

    /// Whether this mirror was synchronised from `source` already.
    pub fn synced_with(&self, source: &Arc<SessionCopy>) -> bool {
        Arc::ptr_eq(&self.source, source)
    }

    /// Puts the mirror on the session's newest state (same model).
    pub fn sync(&mut self, source: Arc<SessionCopy>) {
        self.state.clone_from(&source.state);
        self.hands.clone_from(&source.hands);
        self.source = source;
        self.refused = None;
        // the component again on the new state: the same nodes and load cases keep the
        // cut (put on the new state), anything else makes a new one at the next answer
        if let Some((hand, cut, _)) = &mut self.cut {
            let kept = self
                .hands
                .iter()
                .find(|(k, _)| k == hand)
                .is_some_and(|(_, held)| {
                    let seeds: Vec<usize> = held.hand.held_nodes().collect();
                    let nodes = component(&self.source.model, &self.state, &seeds);
                    cut.cut.refresh(&self.state, &nodes)
                });
            if !kept {
                self.cut = None;
            }
        }
    }

    /// Whether the session holds `hand`.
    pub fn holds(&self, hand: HandNumber) -> bool {
        self.hands.iter().any(|(k, _)| *k == hand)
    }

    /// The session's epoch this mirror was synchronised in.
    pub fn epoch(&self) -> u64 {
        self.source.epoch
    }

    /// The static equilibrium with `hand` at `position` (and `orientation`, kept when
    /// `None`) and the load the hand applies there. A failed solve puts the mirror back
    /// on the session's state.
    pub fn answer(
        &mut self,
        hand: HandNumber,
        position: DVec3,
        orientation: Option<DQuat>,
    ) -> Answer {
        let time = self.state.time;
        let Some((_, held)) = self.hands.iter_mut().find(|(k, _)| *k == hand) else {
            return Answer::status(Status::NotHeld, self.source.state.time);
        };
        let orientation = orientation.unwrap_or_else(|| held.pose_at(time).1);
        // the pose is held from now on: no aim (the session's speed limits belong to the
        // session's dynamics, the mirror answers for the pose itself)
        held.aim = None;
        held.hand.set_pose(position, orientation);
        held.hand.update(&mut self.state, time);
        if self.cutting && self.refused != Some(hand) && Cut::carries(&self.source.model) {
            if let Some(answer) = self.answer_on_cut(hand, position, orientation) {
                return answer;
            }
            self.refused = Some(hand);
        }
        let start = Instant::now();
        let solved = self.solver.solve(&self.source.model, &mut self.state);
        let solve_seconds = start.elapsed().as_secs_f64();
        let load = solved.as_ref().ok().map(|_| {
            let (_, held) = self
                .hands
                .iter()
                .find(|(k, _)| *k == hand)
                .expect("found above");
            let load = held.hand.load(&self.source.model, &self.state);
            (load.force, load.torque, load.hose)
        });
        self.finish(solved, load, solve_seconds)
    }

    /// The answer on the hand's component ([`Cut`]), made for this hand if the last
    /// one was another's; `None` when the scene cannot be cut (then it is solved whole).
    fn answer_on_cut(
        &mut self,
        hand: HandNumber,
        position: DVec3,
        orientation: DQuat,
    ) -> Option<Answer> {
        if self.cut.as_ref().is_some_and(|(k, ..)| *k != hand) {
            let (_, cut, _) = self.cut.take().expect("checked");
            cut.cut.write_back(&mut self.state);
        }
        if self.cut.is_none() {
            let (_, held) = self.hands.iter().find(|(k, _)| *k == hand)?;
            let seeds: Vec<usize> = held.hand.held_nodes().collect();
            let nodes = component(&self.source.model, &self.state, &seeds);
            let cut = HandCut::new(&self.source.model, &self.state, nodes, held)?;
            let mut solver = StaticSolver::new(&cut.cut.model).ok()?;
            // the cut is one component already
            solver.options.split = false;
            self.cut = Some((hand, cut, solver));
        }
        let (_, HandCut { cut, hand: held }, solver) = self.cut.as_mut().expect("made above");
        let time = cut.state.time;
        held.hand.set_pose(position, orientation);
        held.hand.update(&mut cut.state, time);
        let start = Instant::now();
        let solved = solver.solve(&cut.model, &mut cut.state);
        let solve_seconds = start.elapsed().as_secs_f64();
        let load = solved.as_ref().ok().map(|_| {
            let load = held.hand.load(&cut.model, &cut.state);
            (load.force, load.torque, cut.hose_of[load.hose])
        });
        Some(self.finish(solved, load, solve_seconds))
    }

    /// The answer of a solve that gave `load` (force, torque, scene hose).
    fn finish(
        &mut self,
        solved: Result<StaticReport, StaticError>,
        load: Option<(DVec3, DVec3, usize)>,
        solve_seconds: f64,
    ) -> Answer {
        let session_time = self.source.state.time;
        match (solved, load) {
            (Ok(report), Some((force, torque, hose))) => {
                if !(force.is_finite() && torque.is_finite()) {
                    self.put_back();
                    return Answer {
                        solve_seconds,
                        ..Answer::status(Status::SolveFailed, session_time)
                    };
                }
                Answer {
                    status: if report.converged {
                        Status::Ok
                    } else {
                        Status::NotConverged
                    },
                    force,
                    torque,
                    hose: hose as u32,
                    iterations: report.iterations.min(u16::MAX as usize) as u16,
                    session_time,
                    solve_seconds,
                }
            }
            _ => {
                self.put_back();
                Answer {
                    solve_seconds,
                    ..Answer::status(Status::SolveFailed, session_time)
                }
            }
        }
    }

    fn put_back(&mut self) {
        self.state.clone_from(&self.source.state);
        self.hands.clone_from(&self.source.hands);
        self.cut = None;
    }
}
