//! RULA, the Rapid Upper Limb Assessment (McAtamney & Corlett 1993): body-part scores
//! from joint angles, tables A, B and C ([`tables`]), muscle use and force, the grand
//! score and its action level. Angles in radians (compared with the method's degrees).
//!
//! The method's ranges, as published: upper arm 20° extension to 20° flexion 1, more
//! extension or 20–45° flexion 2, 45–90° 3, over 90° 4 (+1 shoulder raised, +1
//! abducted, −1 supported); lower arm 60–100° 1, else 2 (+1 across the midline or out
//! to the side); wrist neutral 1, up to 15° 2, more 3 (+1 deviated); wrist twist
//! mid-range 1, near the end 2; neck 0–10° 1, 10–20° 2, over 20° 3, in extension 4 (+1
//! twisted, +1 side-bent); trunk upright 1, 0–20° 2, 20–60° 3, over 60° 4 (+1 twisted,
//! +1 side-bent); legs supported and balanced 1, else 2. Muscle use +1 when the posture
//! is mainly static (held over a minute) or repeated over 4 times a minute. Force, as the
//! paper words it: under 2 kg intermittent 0; 2–10 kg intermittent 1; 2–10 kg static or
//! repeated 2, and more than 10 kg intermittent 2 too; more than 10 kg static or repeated
//! 3, and a shock or a force with a rapid build-up 3 whatever its size (the later
//! one-page worksheets round this to "more than 10 kg: 3"; the paper is followed). A
//! range's upper bound belongs to it (20° is score 1, 10 kg is 2–10 kg).

pub mod tables;

use tables::{TABLE_A, TABLE_B, TABLE_C};

/// What RULA is scored from: one arm (the method scores each arm separately) and the
/// body.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct RulaInput {
    /// Upper arm flexion from hanging \[rad\] (negative: extension).
    pub upper_arm: f64,
    pub shoulder_raised: bool,
    pub arm_abducted: bool,
    pub arm_supported: bool,
    /// Elbow flexion from the straight arm \[rad\].
    pub lower_arm: f64,
    pub across_midline_or_out: bool,
    /// Wrist flexion or extension magnitude \[rad\] (0: neutral).
    pub wrist: f64,
    pub wrist_deviated: bool,
    pub wrist_twist_near_end: bool,
    /// Neck flexion relative to the trunk \[rad\] (negative: extension).
    pub neck: f64,
    pub neck_twisted: bool,
    pub neck_side_bent: bool,
    /// Trunk flexion \[rad\] (0 or less: upright).
    pub trunk: f64,
    pub trunk_twisted: bool,
    pub trunk_side_bent: bool,
    /// Legs and feet supported and the weight evenly balanced.
    pub legs_balanced: bool,
    /// Mainly static posture (held over a minute) or repeated over 4 times a minute.
    pub static_or_repeated: bool,
    /// Load or force in the hand \[kg\] (force / g).
    pub load_kg: f64,
    /// Shock or a force with a rapid build-up.
    pub shock: bool,
}

/// Every score RULA's worksheet fills in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct RulaScore {
    pub upper_arm: u8,
    pub lower_arm: u8,
    pub wrist: u8,
    pub wrist_twist: u8,
    /// Posture score A (table A).
    pub posture_a: u8,
    pub muscle_use: u8,
    pub force: u8,
    /// Score C = A + muscle use + force.
    pub wrist_and_arm: u8,
    pub neck: u8,
    pub trunk: u8,
    pub legs: u8,
    /// Posture score B (table B).
    pub posture_b: u8,
    /// Score D = B + muscle use + force.
    pub neck_trunk_leg: u8,
    /// The grand score (table C), 1–7.
    pub grand: u8,
    /// 1: acceptable; 2: investigate further; 3: investigate and change soon; 4:
    /// investigate and change immediately.
    pub action_level: u8,
}

/// The force/load score for `load_kg` \[kg\].
pub fn force_score(load_kg: f64, static_or_repeated: bool, shock: bool) -> u8 {
    if shock {
        3
    } else if load_kg < 2.0 {
        0
    } else {
        let heavy = (load_kg > 10.0) as u8;
        1 + static_or_repeated as u8 + heavy
    }
}

/// The upper arm's score before adjustments.
pub fn upper_arm_position(flexion_deg: f64) -> u8 {
    if flexion_deg < -20.0 {
        2
    } else if flexion_deg <= 20.0 {
        1
    } else if flexion_deg <= 45.0 {
        2
    } else if flexion_deg <= 90.0 {
        3
    } else {
        4
    }
}

/// The neck's score before adjustments.
pub fn neck_position(flexion_deg: f64) -> u8 {
    if flexion_deg < 0.0 {
        4
    } else if flexion_deg <= 10.0 {
        1
    } else if flexion_deg <= 20.0 {
        2
    } else {
        3
    }
}

/// The trunk's score before adjustments.
pub fn trunk_position(flexion_deg: f64) -> u8 {
    if flexion_deg <= 0.0 {
        1
    } else if flexion_deg <= 20.0 {
        2
    } else if flexion_deg <= 60.0 {
        3
    } else {
        4
    }
}

/// The grand score's action level.
pub fn action_level(grand: u8) -> u8 {
    match grand {
        0..=2 => 1,
        3..=4 => 2,
        5..=6 => 3,
        _ => 4,
    }
}

/// RULA's scores for `input`.
pub fn score(input: &RulaInput) -> RulaScore {
    let deg = f64::to_degrees;
    let flag = |b: bool| b as u8;
    let upper_arm = (upper_arm_position(deg(input.upper_arm))
        + flag(input.shoulder_raised)
        + flag(input.arm_abducted))
    .saturating_sub(flag(input.arm_supported))
    .clamp(1, 6);
    let la = deg(input.lower_arm);
    let lower_arm = (if (60.0..=100.0).contains(&la) { 1 } else { 2 }
        + flag(input.across_midline_or_out))
    .min(3);
    let w = deg(input.wrist.abs());
    let wrist = (if w == 0.0 {
        1
    } else if w <= 15.0 {
        2
    } else {
        3
    } + flag(input.wrist_deviated))
    .min(4);
    let wrist_twist = 1 + flag(input.wrist_twist_near_end);
    let posture_a = TABLE_A[upper_arm as usize - 1][lower_arm as usize - 1][wrist as usize - 1]
        [wrist_twist as usize - 1];
    let muscle_use = flag(input.static_or_repeated);
    let force = force_score(input.load_kg, input.static_or_repeated, input.shock);
    let wrist_and_arm = posture_a + muscle_use + force;
    let neck =
        (neck_position(deg(input.neck)) + flag(input.neck_twisted) + flag(input.neck_side_bent))
            .min(6);
    let trunk = (trunk_position(deg(input.trunk))
        + flag(input.trunk_twisted)
        + flag(input.trunk_side_bent))
    .min(6);
    let legs = if input.legs_balanced { 1 } else { 2 };
    let posture_b = TABLE_B[neck as usize - 1][trunk as usize - 1][legs as usize - 1];
    let neck_trunk_leg = posture_b + muscle_use + force;
    let grand = TABLE_C[wrist_and_arm.min(8) as usize - 1][neck_trunk_leg.min(7) as usize - 1];
    RulaScore {
        upper_arm,
        lower_arm,
        wrist,
        wrist_twist,
        posture_a,
        muscle_use,
        force,
        wrist_and_arm,
        neck,
        trunk,
        legs,
        posture_b,
        neck_trunk_leg,
        grand,
        action_level: action_level(grand),
    }
}
