//! Parts that move (SPEC K1): a part's pose over time from its motion — a hinge, a slide,
//! a periodic oscillation or a sampled 6-DOF path — composed with its parent's, with the
//! velocity from the motion analytically. The mesh of a part stays in its reference
//! placement (the one the scene gives); contact maps hose points into it
//! ([`crate::contact`]), and whatever is mounted on a part is held at its reference pose
//! carried by the part's ([`crate::loads::Mount`]).

mod hierarchy;
mod hinge;
mod part_move;
mod periodic;
mod pose;
mod profile;
mod sampled_path;
mod slide;

pub use hierarchy::PartKinematics;
pub use hinge::Hinge;
pub use part_move::{MovedPart, PartMove, PartMoves, Turns};
pub use periodic::{Oscillation, Periodic};
pub use pose::{Placement, Pose, Twist};
pub use profile::Profile;
pub use sampled_path::SampledPath;
pub use slide::Slide;

use serde::{Deserialize, Serialize};

/// How a part moves, in its parent's reference placement (the world's for a part without
/// a parent).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PartMotion {
    Hinge(Hinge),
    Slide(Slide),
    Periodic(Periodic),
    SampledPath(SampledPath),
}

impl PartMotion {
    /// Why the motion cannot be used, if it cannot (axes not unit-length and finite,
    /// profiles or samples broken).
    pub fn check(&self) -> Result<(), String> {
        let unit = |v: glam::DVec3, what: &str| {
            if v.is_finite() && (v.length() - 1.0).abs() < 1e-9 {
                Ok(())
            } else {
                Err(format!("{what} must be a unit vector, got {v:?}"))
            }
        };
        match self {
            PartMotion::Hinge(h) => {
                unit(h.axis, "hinge axis")?;
                if !h.point.is_finite() {
                    return Err("hinge point is not finite".into());
                }
                h.angle.check()
            }
            PartMotion::Slide(s) => {
                unit(s.direction, "slide direction")?;
                s.distance.check()
            }
            PartMotion::Periodic(p) => {
                let all = p.translation.iter().chain(&p.rotation);
                if !p.centre.is_finite()
                    || all.clone().any(|o| {
                        !(o.amplitude.is_finite() && o.frequency.is_finite() && o.phase.is_finite())
                    })
                {
                    return Err("periodic motion: centre, amplitudes, frequencies and phases must be finite".into());
                }
                Ok(())
            }
            PartMotion::SampledPath(s) => s.check(),
        }
    }

    /// The pose and twist at time `t`.
    pub fn placement_at(&self, t: f64) -> Placement {
        match self {
            PartMotion::Hinge(h) => h.placement_at(t),
            PartMotion::Slide(s) => s.placement_at(t),
            PartMotion::Periodic(p) => p.placement_at(t),
            PartMotion::SampledPath(s) => s.placement_at(t),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    /// Every motion's twist is the derivative of its pose: the velocity field
    /// ω × (x − T) + Ṫ matches the finite difference of a point's image.
    fn twist_matches_pose(m: &PartMotion, t: f64) {
        let h = 1e-6;
        let x = DVec3::new(0.4, -0.3, 0.8);
        let now = m.placement_at(t);
        let numeric =
            (m.placement_at(t + h).pose.apply(x) - m.placement_at(t - h).pose.apply(x)) / (2.0 * h);
        let analytic = now.velocity_at(now.pose.apply(x));
        assert!(
            (numeric - analytic).length() < 1e-6 * (1.0 + numeric.length()),
            "{m:?} at {t}: {numeric:?} vs {analytic:?}"
        );
    }

    fn motions() -> Vec<PartMotion> {
        vec![
            PartMotion::Hinge(Hinge {
                point: DVec3::new(1.0, 0.5, 0.0),
                axis: DVec3::new(0.0, 0.6, 0.8),
                angle: Profile::ramp(0.0, 1.2, 0.1, 2.0),
            }),
            PartMotion::Slide(Slide {
                direction: DVec3::X,
                distance: Profile::UniformAcceleration {
                    start_time: 0.0,
                    initial_rate: 0.2,
                    acceleration: 1.5,
                },
            }),
            PartMotion::Periodic(Periodic {
                centre: DVec3::new(0.2, 0.3, 0.5),
                translation: [
                    Oscillation {
                        amplitude: 0.01,
                        frequency: 2.0,
                        phase: 0.3,
                    },
                    Oscillation::default(),
                    Oscillation {
                        amplitude: 0.005,
                        frequency: 1.0,
                        phase: 0.0,
                    },
                ],
                rotation: [
                    Oscillation {
                        amplitude: 0.05,
                        frequency: 1.5,
                        phase: 0.0,
                    },
                    Oscillation {
                        amplitude: 0.03,
                        frequency: 1.0,
                        phase: 1.0,
                    },
                    Oscillation {
                        amplitude: 0.02,
                        frequency: 0.5,
                        phase: 0.2,
                    },
                ],
            }),
            PartMotion::SampledPath(SampledPath {
                times: vec![0.0, 0.5, 1.2, 2.0],
                positions: vec![
                    DVec3::ZERO,
                    DVec3::new(0.1, 0.0, 0.02),
                    DVec3::new(0.15, 0.05, 0.0),
                    DVec3::new(0.0, 0.1, 0.0),
                ],
                rotations: vec![
                    DQuat::IDENTITY,
                    DQuat::from_rotation_z(0.2),
                    DQuat::from_rotation_x(0.3) * DQuat::from_rotation_z(0.1),
                    DQuat::from_rotation_y(-0.2),
                ],
                centre: DVec3::new(0.3, 0.0, 0.1),
            }),
        ]
    }

    #[test]
    fn every_motions_twist_is_the_rate_of_its_pose() {
        for m in motions() {
            m.check().unwrap();
            for t in [0.3, 0.77, 1.5] {
                twist_matches_pose(&m, t);
            }
        }
    }

    #[test]
    fn sampled_path_passes_through_its_samples() {
        let PartMotion::SampledPath(s) = &motions()[3] else {
            unreachable!()
        };
        for k in 0..s.times.len() {
            let p = s.placement_at(s.times[k]).pose;
            let c = s.centre;
            assert!((p.apply(c) - (c + s.positions[k])).length() < 1e-12);
            assert!(p.rotation.abs_diff_eq(s.rotations[k], 1e-12));
        }
    }

    #[test]
    fn a_child_moves_with_its_parent_and_its_twist_is_the_rate() {
        let m = motions();
        let kin = PartKinematics::new(
            vec![Some(m[2].clone()), Some(m[0].clone())],
            vec![None, Some(0)],
        )
        .unwrap();
        let x = DVec3::new(0.7, 0.1, -0.2);
        for t in [0.4, 1.1] {
            let h = 1e-6;
            let none = &PartMoves::NONE;
            let child = kin.placement_at(1, t, none);
            let expect = kin
                .placement_at(0, t, none)
                .pose
                .apply(m[0].placement_at(t).pose.apply(x));
            assert!((child.pose.apply(x) - expect).length() < 1e-12);
            let numeric = (kin.placement_at(1, t + h, none).pose.apply(x)
                - kin.placement_at(1, t - h, none).pose.apply(x))
                / (2.0 * h);
            let analytic = child.velocity_at(child.pose.apply(x));
            assert!((numeric - analytic).length() < 1e-6);
        }
        let cycle = PartKinematics::new(vec![None, None], vec![Some(1), Some(0)]);
        assert!(cycle.unwrap_err().contains("cycle"));
    }
}
