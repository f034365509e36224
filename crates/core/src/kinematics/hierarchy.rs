//! Parts in a hierarchy: a part may move with a parent (a door on a body, a tool on a robot
//! link). A child's motion is given in its parent's reference placement, so its pose is
//! the parent's composed with its own, P = P_parent ∘ P_own, and its twist follows
//! ([`Placement::carrying`]). A part moved by inputs ([`PartMoves`]) has those moves as
//! its own motion. A part with neither motion, moves nor parent stands still.

use super::part_move::PartMoves;
use super::pose::Placement;
use super::PartMotion;

/// Every part's motion and parent, checked to form a forest (no cycles).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PartKinematics {
    motions: Vec<Option<PartMotion>>,
    parents: Vec<Option<usize>>,
    /// Whether each part moves (it has a motion, may be moved by inputs, or has an
    /// ancestor that does).
    moves: Vec<bool>,
}

impl PartKinematics {
    /// The kinematics of parts with these motions and parents (indices of other parts);
    /// errors name the part by index.
    pub fn new(
        motions: Vec<Option<PartMotion>>,
        parents: Vec<Option<usize>>,
    ) -> Result<Self, String> {
        let n = motions.len();
        Self::with_movable(motions, parents, vec![false; n])
    }

    /// As [`Self::new`], with the parts inputs may move (`movable`, one per part).
    pub fn with_movable(
        motions: Vec<Option<PartMotion>>,
        parents: Vec<Option<usize>>,
        movable: Vec<bool>,
    ) -> Result<Self, String> {
        let n = motions.len();
        if parents.len() != n || movable.len() != n {
            return Err(format!(
                "{} parents and {} movable flags for {n} parts",
                parents.len(),
                movable.len()
            ));
        }
        for (k, m) in motions.iter().enumerate() {
            if let Some(m) = m {
                m.check().map_err(|e| format!("part {k}: {e}"))?;
            }
        }
        let mut moves = vec![false; n];
        for k in 0..n {
            let mut at = k;
            let mut depth = 0;
            loop {
                moves[k] |= motions[at].is_some() || movable[at];
                match parents[at] {
                    None => break,
                    Some(p) if p >= n => {
                        return Err(format!("part {at}: parent {p} is not a part"))
                    }
                    Some(p) => at = p,
                }
                depth += 1;
                if depth > n {
                    return Err(format!("part {k}: its parents form a cycle"));
                }
            }
        }
        Ok(PartKinematics {
            motions,
            parents,
            moves,
        })
    }

    /// Part `k`'s own motion (in its parent's reference placement), if it has one.
    pub fn motion(&self, k: usize) -> Option<&PartMotion> {
        self.motions.get(k).and_then(Option::as_ref)
    }

    /// Whether part `k` moves.
    pub fn moves(&self, k: usize) -> bool {
        self.moves.get(k).copied().unwrap_or(false)
    }

    /// Whether any part moves.
    pub fn any_moves(&self) -> bool {
        self.moves.iter().any(|&m| m)
    }

    /// Part `k`'s pose and twist at time `t`, moved by `moves` (the state's; identity
    /// for a part that stands still).
    pub fn placement_at(&self, k: usize, t: f64, moves: &PartMoves) -> Placement {
        if !self.moves(k) {
            return Placement::default();
        }
        let own = match &self.motions[k] {
            Some(m) => m.placement_at(t),
            None => moves.placement_at(k, t).unwrap_or_default(),
        };
        match self.parents[k] {
            Some(p) => self.placement_at(p, t, moves).carrying(&own),
            None => own,
        }
    }

    /// Writes every part's placement at `t` (poses) with the twist at `t_rate` (the
    /// explicit step takes the twist at mid-step) into `out` (one per part).
    pub fn place_all(&self, t: f64, t_rate: f64, moves: &PartMoves, out: &mut [Placement]) {
        for (k, p) in out.iter_mut().enumerate() {
            let pose = self.placement_at(k, t, moves).pose;
            let twist = if t_rate == t {
                self.placement_at(k, t, moves).twist
            } else {
                self.placement_at(k, t_rate, moves).twist
            };
            *p = Placement { pose, twist };
        }
    }

    /// Part `k`'s parent, if it has one.
    pub fn parent(&self, k: usize) -> Option<usize> {
        self.parents.get(k).copied().flatten()
    }

    pub fn len(&self) -> usize {
        self.motions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.motions.is_empty()
    }
}
