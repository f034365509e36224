//! RULA and REBA of a manikin posture: the joint angles inverse kinematics found, the
//! hands' forces as the load, and what the model does not know — wrist straight, wrist
//! twist mid-range, shoulders not raised, arms unsupported, standing evenly on both feet
//! with straight knees — filled in as neutral (module [`crate::ik`]'s limits).
//!
//! The legs: standing evenly on straight legs, or seated ([`crate::seat`]). RULA's leg
//! score (McAtamney & Corlett 1993, step 11: "if legs and feet are well supported and in
//! an evenly balanced posture" 1, "if not" 2) is 1 standing and seated with the feet on
//! the floor, 2 seated with the feet hanging above it (a seat higher than the popliteal
//! height). REBA's (Hignett & McAtamney 2000, table 1, legs: "bilateral weight bearing,
//! walking or sitting" 1) is 1 for every seated posture, and its knee-flexion
//! additions (+1 at 30–60°, +2 over 60°) are for standing postures only: they do not
//! apply seated (the knees of a seated worker are flexed by the seat, not loaded).
//!
//! The methods leave "twisted", "side-bent" and "abducted" to the observer's eye; here
//! they are flagged when the angle exceeds [`ADJUSTMENT_ANGLE`] (10°, a modelling
//! choice). Each arm is scored with its own hand's force (RULA scores each arm
//! separately; REBA's load is the force of both hands together) and the worse arm is
//! reported.

use crate::posture::{Posture, Side};
use crate::reba::{self, Coupling, RebaInput, RebaScore};
use crate::rula::{self, RulaInput, RulaScore};

/// The angle beyond which a body part counts as twisted, side-bent or abducted \[rad\]
/// (10°; a modelling choice, module doc).
pub const ADJUSTMENT_ANGLE: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Standard gravity \[m/s²\], to turn a hand force into the methods' kilograms.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// What the methods need beyond the posture.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ScoreOptions {
    /// The posture is held over a minute or repeated over 4 times a minute (RULA's
    /// muscle use and static force, REBA's activity).
    pub static_or_repeated: bool,
    /// REBA's coupling.
    pub coupling: Coupling,
}

/// Both scores of one posture, for its worse arm.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct PostureScores {
    pub rula: RulaScore,
    pub reba: RebaScore,
}

/// RULA's input for `side` of `posture` with `force` \[N\] in its hand.
pub fn rula_input(posture: &Posture, side: Side, force: f64, options: &ScoreOptions) -> RulaInput {
    let arm = &posture.arms[side.index()];
    let t = &posture.trunk;
    RulaInput {
        upper_arm: arm.flexion,
        arm_abducted: arm.abduction > ADJUSTMENT_ANGLE,
        lower_arm: arm.elbow_flexion,
        across_midline_or_out: arm.across_or_out,
        neck: posture.neck_flexion,
        neck_twisted: posture.neck_twist.abs() > ADJUSTMENT_ANGLE,
        trunk: t.flexion,
        trunk_twisted: t.twist.abs() > ADJUSTMENT_ANGLE,
        trunk_side_bent: t.lateral.abs() > ADJUSTMENT_ANGLE,
        legs_balanced: posture.sitting.is_none_or(|s| s.feet_on_floor),
        static_or_repeated: options.static_or_repeated,
        load_kg: force / STANDARD_GRAVITY,
        ..Default::default()
    }
}

/// REBA's input for `side` of `posture` with `total_force` \[N\] in both hands.
pub fn reba_input(
    posture: &Posture,
    side: Side,
    total_force: f64,
    options: &ScoreOptions,
) -> RebaInput {
    let arm = &posture.arms[side.index()];
    let t = &posture.trunk;
    RebaInput {
        trunk: t.flexion,
        trunk_twisted_or_side_bent: t.twist.abs().max(t.lateral.abs()) > ADJUSTMENT_ANGLE,
        neck: posture.neck_flexion,
        neck_twisted_or_side_bent: posture.neck_twist.abs() > ADJUSTMENT_ANGLE,
        load_kg: total_force / STANDARD_GRAVITY,
        upper_arm: arm.flexion,
        arm_abducted_or_rotated: arm.abduction > ADJUSTMENT_ANGLE,
        lower_arm: arm.elbow_flexion,
        sitting: posture.sitting.is_some(),
        knee_flexion: posture.sitting.map_or(0.0, |s| s.knee_flexion),
        coupling: options.coupling,
        activity: options.static_or_repeated as u8,
        ..Default::default()
    }
}

/// The scores of `posture` with hand forces `forces` \[N\] (right, left): each arm that
/// has a target is scored (the right one when neither has), the worse kept.
pub fn score_posture(posture: &Posture, forces: [f64; 2], options: &ScoreOptions) -> PostureScores {
    let total = forces[0] + forces[1];
    let mut best: Option<PostureScores> = None;
    for side in Side::BOTH {
        let working = posture.arms[side.index()].target.is_some();
        let none = posture.arms.iter().all(|a| a.target.is_none());
        // the arms that work; the right one when neither does
        let scored = working || (none && side == Side::Right);
        if !scored {
            continue;
        }
        let r = rula::score(&rula_input(posture, side, forces[side.index()], options));
        let e = reba::score(&reba_input(posture, side, total, options));
        let s = best.get_or_insert(PostureScores { rula: r, reba: e });
        if r.grand > s.rula.grand {
            s.rula = r;
        }
        if e.reba > s.reba.reba {
            s.reba = e;
        }
    }
    best.unwrap_or_default()
}
