//! Clearance memory for points that search the rigid environment each step (the
//! stiffened sections' nodes, [`super::penalty`]): a point found farther than its reach
//! from every part is remembered with how far it may move before it could touch — the
//! idea of Verlet neighbour lists (L. Verlet, Phys. Rev. 159, 98, 1967) for a list that
//! is empty, as [`super::coherence`] keeps it for the beams.
//!
//! The distance from a point to a fixed triangle is 1-Lipschitz in the point and at least
//! the distance to the triangle's bounding box. If the nearest triangle box lay `D` from
//! the anchor, a point that has moved less than `D − ρ` from it (with slack for
//! rounding) is farther than `ρ` from every triangle: a query within `ρ` would find
//! nothing, and is skipped — the same result as asking, to the last bit.

use super::environment::RigidEnvironment;
use super::triangle_set::TriangleSet;
use glam::DVec3;

/// How far (in reaches) a point looks for the nearest triangle box when anchored.
const FAR: f64 = 4.0;
/// Relative slack on distances for rounding (errs towards asking).
const SLACK: f64 = 1e-9;

/// Per point: where it was found clear and the square of how far it may move from there
/// (−∞: not known to be clear), for the environment `environment_key` describes.
#[derive(Clone, Debug, Default)]
pub struct Clearance {
    anchor: Vec<DVec3>,
    margin_squared: Vec<f64>,
    environment_key: (usize, usize),
}

impl Clearance {
    /// Memory for `points` points, none known to be clear.
    pub fn new(points: usize, env: &RigidEnvironment) -> Self {
        Clearance {
            anchor: vec![DVec3::ZERO; points],
            margin_squared: vec![f64::NEG_INFINITY; points],
            environment_key: env.key(),
        }
    }

    /// Forgets every point's clearance if the environment is not the one it was found
    /// for; once a step, before [`Self::is_clear`].
    pub(crate) fn follow(&mut self, env: &RigidEnvironment) {
        if self.environment_key != env.key() {
            self.environment_key = env.key();
            self.margin_squared.fill(f64::NEG_INFINITY);
        }
    }

    /// True if point `i`, now at `x`, is certainly farther than the reach it was
    /// anchored with from every triangle (it has moved less than its margin).
    pub(crate) fn is_clear(&self, i: usize, x: DVec3) -> bool {
        match (self.anchor.get(i), self.margin_squared.get(i)) {
            (Some(&anchor), Some(&m2)) => (x - anchor).length_squared() < m2,
            _ => false,
        }
    }

    /// Anchors point `i` at `x` with reach `reach`, after a query found no triangle
    /// within it: the nearest triangle box up to [`FAR`] reaches out bounds how far the
    /// point may move while still clear.
    pub(crate) fn anchor(&mut self, env: &RigidEnvironment, i: usize, x: DVec3, reach: f64) {
        if i >= self.anchor.len() {
            return;
        }
        let nearest = env.nearest_box(x, x, FAR * reach);
        let margin = nearest / (1.0 + SLACK) - reach * (1.0 + SLACK);
        self.anchor[i] = x;
        self.margin_squared[i] = if margin > 0.0 {
            margin * margin
        } else {
            f64::NEG_INFINITY
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::environment::test_plate;

    /// A point walking down onto a plate: whenever its memory calls it clear, a fresh
    /// query within its reach finds nothing; the memory spares most of the queries above
    /// the plate.
    #[test]
    fn a_point_taken_for_clear_finds_nothing() {
        let env = test_plate();
        let reach = 0.01;
        let mut memory = Clearance::new(1, &env);
        let (mut clear, mut found) = (0, 0);
        for k in 0..400 {
            let s = k as f64 * 0.002;
            let x = DVec3::new(0.3 * s.sin(), 0.2 * s.cos(), 0.06 - k as f64 * 1.5e-4);
            let hit = env.closest_point(x, reach);
            if memory.is_clear(0, x) {
                assert!(hit.is_none(), "step {k}: taken for clear at {x:?}");
                clear += 1;
            } else if hit.is_none() {
                memory.anchor(&env, 0, x, reach);
            } else {
                found += 1;
            }
        }
        assert!(clear > 200 && found > 0, "{clear} clear, {found} found");
    }
}
