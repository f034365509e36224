//! Parts moved by inputs (a timeline's `move_part` and `rotate_part`, a live client, a
//! script): each move takes the part from its pose when the move is given, turned by a
//! rotation vector φ about a fixed pivot w and shifted by d, over a duration with the
//! quintic smooth-step s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ (zero rate and acceleration at both
//! ends, as every timeline motion), then holds the end pose.
//!
//! With R_s = exp(s φ) and the start pose (R₀, T₀): R(s) = R_s R₀ and
//! T(s) = R_s (T₀ − w) + w + s d. Its twist is ω = ṡ φ and
//! Ṫ = ω × R_s (T₀ − w) + ṡ d, the rigid velocity field of [`super::Pose`].
//!
//! The moves are part of the state ([`crate::State::part_moves`]), so checkpoints,
//! rollbacks and replays carry them; the model only says which parts may be moved
//! ([`crate::spec::RigidPartSpec::movable`]).

use super::pose::{Placement, Pose, Twist};
use crate::math::exp_map;
use glam::DVec3;

/// One move of a part, in its parent's reference placement (the world's without a
/// parent).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartMove {
    /// The part's own pose when the move was given.
    pub start: Pose,
    /// The point that stays put while the part turns \[m\].
    pub pivot: DVec3,
    /// The whole turn, a rotation vector \[rad\] (any angle).
    pub turn: DVec3,
    /// The whole shift \[m\].
    pub shift: DVec3,
    pub start_time: f64,
    /// \[s\], > 0.
    pub duration: f64,
}

/// Quintic smooth-step s(τ) and its rate ds/dτ, τ clamped to [0, 1].
pub(crate) fn smooth_step(tau: f64) -> (f64, f64) {
    let t = tau.clamp(0.0, 1.0);
    (
        t * t * t * (10.0 + t * (-15.0 + 6.0 * t)),
        30.0 * t * t * (1.0 - t) * (1.0 - t),
    )
}

impl PartMove {
    /// The pose and twist at time `t` (the start pose before the move, the end pose after).
    pub fn placement_at(&self, t: f64) -> Placement {
        let tau = (t - self.start_time) / self.duration;
        if tau <= 0.0 {
            return Placement {
                pose: self.start,
                twist: Twist::default(),
            };
        }
        let (s, ds) = smooth_step(tau);
        let rate = if (0.0..1.0).contains(&tau) {
            ds / self.duration
        } else {
            0.0
        };
        let turned = exp_map(s * self.turn);
        let arm = turned * (self.start.translation - self.pivot);
        let angular = rate * self.turn;
        Placement {
            pose: Pose {
                rotation: (turned * self.start.rotation).normalize(),
                translation: arm + self.pivot + s * self.shift,
            },
            twist: Twist {
                linear: angular.cross(arm) + rate * self.shift,
                angular,
            },
        }
    }

    /// Whether the part is still moving at `t`.
    pub fn moving_at(&self, t: f64) -> bool {
        t < self.start_time + self.duration
    }
}

/// The moved parts' state: per part its last move and how far it has turned about one
/// axis in all (for a turn *to* an angle). Empty until a part is moved.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PartMoves {
    moves: Vec<Option<MovedPart>>,
}

/// A part's last move and its turns once that move has ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovedPart {
    pub last: PartMove,
    pub turned: Turns,
}

/// How a part has turned from where the scene placed it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Turns {
    /// Not at all.
    Never,
    /// About one unit axis, by `angle` \[rad\] in all (several turns count).
    About { axis: DVec3, angle: f64 },
    /// About more than one axis.
    Mixed,
}

impl Turns {
    /// These turns and one more by rotation vector `turn`.
    pub fn and(self, turn: DVec3) -> Turns {
        let angle = turn.length();
        if angle == 0.0 {
            return self;
        }
        let axis = turn / angle;
        match self {
            Turns::Never => Turns::About { axis, angle },
            Turns::About { axis: a, angle: b } if parallel(a, axis) => Turns::About {
                axis: a,
                angle: b + angle * a.dot(axis).signum(),
            },
            _ => Turns::Mixed,
        }
    }

    /// The angle turned about `axis` (a unit vector) in all, if every turn was about it
    /// (either way).
    pub fn about(self, axis: DVec3) -> Option<f64> {
        match self {
            Turns::Never => Some(0.0),
            Turns::About { axis: a, angle } if parallel(a, axis) => {
                Some(angle * a.dot(axis).signum())
            }
            _ => None,
        }
    }
}

/// Whether two unit axes are parallel or opposite.
fn parallel(a: DVec3, b: DVec3) -> bool {
    a.dot(b).abs() > 1.0 - 1e-9
}

impl MovedPart {
    /// The turns at time `t`: those once the last move has ended, less what of its turn
    /// is still to come.
    pub fn turned_at(&self, t: f64) -> Turns {
        let m = &self.last;
        let s = smooth_step((t - m.start_time) / m.duration).0;
        self.turned.and(-(1.0 - s) * m.turn)
    }
}

impl PartMoves {
    /// No part moved.
    pub const NONE: PartMoves = PartMoves { moves: Vec::new() };

    /// Part `k`'s moves, if it was moved.
    pub fn get(&self, k: usize) -> Option<&MovedPart> {
        self.moves.get(k).and_then(Option::as_ref)
    }

    /// Part `k`'s own placement at `t` by its moves (None: never moved).
    pub fn placement_at(&self, k: usize, t: f64) -> Option<Placement> {
        self.get(k).map(|m| m.last.placement_at(t))
    }

    /// Starts a move of part `k` (replacing any it has; `parts` the number of parts).
    pub fn set(&mut self, parts: usize, k: usize, moved: MovedPart) {
        if self.moves.len() < parts {
            self.moves.resize(parts, None);
        }
        self.moves[k] = Some(moved);
    }

    /// Whether any part is still moving at `t`.
    pub fn any_moving(&self, t: f64) -> bool {
        self.moves.iter().flatten().any(|m| m.last.moving_at(t))
    }

    /// Whether any part was moved.
    pub fn any(&self) -> bool {
        self.moves.iter().any(Option::is_some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn a_move() -> PartMove {
        PartMove {
            start: Pose {
                rotation: DQuat::from_rotation_x(0.3),
                translation: DVec3::new(0.1, -0.2, 0.4),
            },
            pivot: DVec3::new(0.5, 0.2, -0.1),
            turn: DVec3::new(0.0, 0.6, 0.8) * 2.0,
            shift: DVec3::new(0.05, 0.0, -0.02),
            start_time: 0.3,
            duration: 1.5,
        }
    }

    /// The twist is the rate of the pose: a point's velocity ω × (x − T) + Ṫ matches
    /// the central difference of its image.
    #[test]
    fn the_twist_is_the_rate_of_the_pose() {
        let m = a_move();
        let x = DVec3::new(0.4, -0.3, 0.8);
        for t in [0.31, 0.7, 1.05, 1.79] {
            let h = 1e-6;
            let numeric = (m.placement_at(t + h).pose.apply(x)
                - m.placement_at(t - h).pose.apply(x))
                / (2.0 * h);
            let now = m.placement_at(t);
            let analytic = now.velocity_at(now.pose.apply(x));
            assert!(
                (numeric - analytic).length() < 1e-7,
                "at {t}: {numeric:?} vs {analytic:?}"
            );
        }
    }

    /// Before the move the start pose, after it the start pose turned by φ about the pivot
    /// and shifted by d, at rest; the pivot only shifts.
    #[test]
    fn the_move_ends_turned_about_the_pivot_and_shifted() {
        let m = a_move();
        assert_eq!(m.placement_at(0.0).pose, m.start);
        let end = m.placement_at(10.0);
        assert_eq!(end.twist, Twist::default());
        let x = DVec3::new(-0.2, 0.7, 0.1);
        let expect = exp_map(m.turn) * (m.start.apply(x) - m.pivot) + m.pivot + m.shift;
        assert!((end.pose.apply(x) - expect).length() < 1e-14);
        let pivot_ref = m.start.inverse_apply(m.pivot);
        for t in [0.5, 1.0, 1.6] {
            let s = smooth_step((t - 0.3) / 1.5).0;
            let at = m.placement_at(t).pose.apply(pivot_ref);
            assert!((at - (m.pivot + s * m.shift)).length() < 1e-14);
        }
    }
}
