//! Load cases (SPEC §3, table 5.1 of the dissertation): each acts on one node, can be
//! added and removed at run time, and several may act on one node at once (dead loads
//! add up; of several kinematic ones the most recently added holds the node).

mod dead_load;
mod drive;
mod fix;
mod motion;
mod mount;
mod support;
mod tie;

pub use dead_load::{DeadLoad, LoadRamp};
pub use drive::Drive;
pub use fix::Fix;
pub use motion::Motion;
pub use mount::Mount;
pub use support::{
    largest_safety_with_supports, support_reactions, Support, SupportLoad, SUPPORT_DAMPING,
    SUPPORT_FACTOR,
};
pub use tie::{Tie, TieLoad};

use crate::kinematics::{PartKinematics, PartMoves};
use glam::{DQuat, DVec3};
use serde::Serialize;

/// Handle of an active load case, for removing it later.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct LoadCaseId(pub u64);

/// One load case.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadCase {
    /// L1: node held in all six degrees of freedom.
    Fix(Fix),
    /// L2 + L3: node driven along a path and/or rotated over a duration, then held.
    Drive(Drive),
    /// Constant force and moment at a node (global axes).
    DeadLoad(DeadLoad),
    /// A fixing: node held by springs in some directions of a frame, free in the others
    /// (not kinematic: the node moves under its loads).
    Support(Support),
    /// Two nodes (of two hoses) held at a distance: a cable tie bundling the hoses. Its
    /// [`LoadCase::node`] is the first node; only its handle removes it.
    Tie(Tie),
    /// A node held to a part, carried with it as the part moves.
    Mount(Mount),
}

impl LoadCase {
    pub fn node(&self) -> usize {
        match self {
            LoadCase::Fix(f) => f.node,
            LoadCase::Drive(d) => d.node,
            LoadCase::DeadLoad(d) => d.node,
            LoadCase::Support(s) => s.node,
            LoadCase::Tie(t) => t.nodes[0],
            LoadCase::Mount(m) => m.node,
        }
    }

    /// The pose (position, orientation) a kinematic load case prescribes at time `t`, with
    /// the parts moving by `parts` and the inputs' `moves`.
    pub fn prescribed_pose(
        &self,
        t: f64,
        parts: &PartKinematics,
        moves: &PartMoves,
    ) -> Option<(DVec3, DQuat)> {
        match self {
            LoadCase::Fix(f) => Some((f.position, f.orientation)),
            LoadCase::Drive(d) => Some(d.pose_at(t)),
            LoadCase::Mount(m) => Some(m.pose_at(t, parts, moves)),
            LoadCase::DeadLoad(_) | LoadCase::Support(_) | LoadCase::Tie(_) => None,
        }
    }

    /// Whether the load case holds its node kinematically (fix, drive, mount).
    pub fn is_kinematic(&self) -> bool {
        matches!(
            self,
            LoadCase::Fix(_) | LoadCase::Drive(_) | LoadCase::Mount(_)
        )
    }
}

/// The active load cases of a state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadCases {
    cases: Vec<(LoadCaseId, LoadCase)>,
    next_id: u64,
}

impl LoadCases {
    /// Adds a load case and returns its handle.
    pub fn add(&mut self, case: LoadCase) -> LoadCaseId {
        let id = LoadCaseId(self.next_id);
        self.next_id += 1;
        self.cases.push((id, case));
        id
    }

    /// Removes a load case; returns it if it was active.
    pub fn remove(&mut self, id: LoadCaseId) -> Option<LoadCase> {
        let pos = self.cases.iter().position(|(i, _)| *i == id)?;
        Some(self.cases.remove(pos).1)
    }

    /// The load case with this handle, for updating it in place (e.g. a hand moving the
    /// pose a fix holds).
    pub fn get_mut(&mut self, id: LoadCaseId) -> Option<&mut LoadCase> {
        self.cases
            .iter_mut()
            .find(|(i, _)| *i == id)
            .map(|(_, c)| c)
    }

    /// Removes every load case on `node` that `pred` selects; returns how many. Ties stay
    /// (a hand grabbing a tied node does not cut the tie): only their handle removes them.
    pub fn remove_on_node(&mut self, node: usize, pred: impl Fn(&LoadCase) -> bool) -> usize {
        let before = self.cases.len();
        self.cases
            .retain(|(_, c)| matches!(c, LoadCase::Tie(_)) || !(c.node() == node && pred(c)));
        before - self.cases.len()
    }

    /// Removes what hands that let go left behind once it has fallen to zero by time `t`
    /// ([`DeadLoad::is_release`]); returns how many.
    pub fn remove_finished_releases(&mut self, t: f64) -> usize {
        let before = self.cases.len();
        self.cases.retain(|(_, c)| {
            !matches!(c, LoadCase::DeadLoad(d)
                if d.is_release() && d.ramp.is_some_and(|r| t >= r.start + r.duration))
        });
        before - self.cases.len()
    }

    /// When the last of what hands that let go left behind has fallen to zero, if any
    /// is left.
    pub fn latest_release_end(&self) -> Option<f64> {
        self.cases
            .iter()
            .filter_map(|(_, c)| match c {
                LoadCase::DeadLoad(d) if d.is_release() => d.ramp.map(|r| r.start + r.duration),
                _ => None,
            })
            .reduce(f64::max)
    }

    pub fn iter(&self) -> impl Iterator<Item = &(LoadCaseId, LoadCase)> {
        self.cases.iter()
    }

    /// The load cases, for updating them in place (e.g. a support's slip anchor).
    pub fn iter_mut(&mut self) -> impl Iterator<Item = &mut (LoadCaseId, LoadCase)> {
        self.cases.iter_mut()
    }

    pub fn is_empty(&self) -> bool {
        self.cases.is_empty()
    }

    /// Whether a kinematic load case (fix or drive) holds `node`.
    pub fn holds(&self, node: usize) -> bool {
        self.cases
            .iter()
            .any(|(_, c)| c.node() == node && c.is_kinematic())
    }

    /// Whether a load still changes at time `t`: a drive moving, or a dead load rising or
    /// falling along its ramp (a hand letting go, [`LoadRamp::smooth_fall`]).
    pub fn any_changing(&self, t: f64) -> bool {
        self.cases.iter().any(|(_, c)| match c {
            LoadCase::Drive(d) => !d.finished(t),
            LoadCase::DeadLoad(d) => d.ramp.is_some_and(|r| t < r.start + r.duration),
            _ => false,
        })
    }

    /// Whether any drive is still moving at time `t`.
    pub fn any_drive_moving(&self, t: f64) -> bool {
        self.cases
            .iter()
            .any(|(_, c)| matches!(c, LoadCase::Drive(d) if !d.finished(t)))
    }
}
