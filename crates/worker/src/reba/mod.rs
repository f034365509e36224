//! REBA, the Rapid Entire Body Assessment (Hignett & McAtamney 2000): body-part scores
//! from joint angles, tables A, B and C ([`tables`]), load, coupling and activity, the
//! REBA score and its risk level. Angles in radians (compared with the method's degrees).
//!
//! The method's ranges, as published: trunk upright 1, 0–20° flexion or extension 2,
//! 20–60° flexion or over 20° extension 3, over 60° flexion 4 (+1 twisted or side-bent);
//! neck 0–20° flexion 1, over 20° flexion or in extension 2 (+1 twisted or side-bent);
//! legs bilateral weight bearing, walking or sitting 1, unilateral or unstable 2 (+1
//! knees flexed 30–60°, +2 over 60°); load under 5 kg 0, 5–10 kg 1, over 10 kg 2 (+1
//! shock or rapid build-up); upper arm 20° extension to 20° flexion 1, more extension
//! or 20–45° flexion 2, 45–90° 3, over 90° 4 (+1 abducted or rotated, +1 shoulder
//! raised, −1 supported); lower arm 60–100° 1, else 2; wrist 0–15° 1, more 2 (+1
//! deviated or twisted); coupling good 0, fair 1, poor 2, unacceptable 3; activity +1
//! each for a body part held static over a minute, small-range actions repeated over 4
//! times a minute, rapid large changes of posture or an unstable base. A range's upper
//! bound belongs to it.

pub mod tables;

use tables::{TABLE_A, TABLE_B, TABLE_C};

/// The hand's hold on the load (REBA's coupling score).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Coupling {
    /// Well fitting handle and a mid-range power grip: 0.
    Good,
    /// Hand hold acceptable but not ideal: 1.
    #[default]
    Fair,
    /// Hand hold not acceptable though possible: 2.
    Poor,
    /// Awkward, unsafe grip, no handles: 3.
    Unacceptable,
}

impl Coupling {
    pub fn score(self) -> u8 {
        self as u8
    }

    /// Reads `good`, `fair`, `poor` or `unacceptable`.
    pub fn parse(text: &str) -> Option<Coupling> {
        match text.trim().to_ascii_lowercase().as_str() {
            "good" => Some(Coupling::Good),
            "fair" => Some(Coupling::Fair),
            "poor" => Some(Coupling::Poor),
            "unacceptable" => Some(Coupling::Unacceptable),
            _ => None,
        }
    }
}

/// What REBA is scored from: the body and one arm.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct RebaInput {
    /// Trunk flexion \[rad\] (negative: extension).
    pub trunk: f64,
    pub trunk_twisted_or_side_bent: bool,
    /// Neck flexion relative to the trunk \[rad\] (negative: extension).
    pub neck: f64,
    pub neck_twisted_or_side_bent: bool,
    /// Weight on one leg, or an unstable posture.
    pub unilateral: bool,
    /// Knee flexion \[rad\] (not scored while sitting).
    pub knee_flexion: f64,
    pub sitting: bool,
    /// Load or force \[kg\] (force / g).
    pub load_kg: f64,
    pub shock: bool,
    /// Upper arm flexion from hanging \[rad\] (negative: extension).
    pub upper_arm: f64,
    pub arm_abducted_or_rotated: bool,
    pub shoulder_raised: bool,
    pub arm_supported: bool,
    /// Elbow flexion from the straight arm \[rad\].
    pub lower_arm: f64,
    /// Wrist flexion or extension magnitude \[rad\].
    pub wrist: f64,
    pub wrist_deviated_or_twisted: bool,
    pub coupling: Coupling,
    /// Activity score: 0 to 3 (static, repeated, rapid changes or unstable base).
    pub activity: u8,
}

/// Every score REBA's worksheet fills in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct RebaScore {
    pub trunk: u8,
    pub neck: u8,
    pub legs: u8,
    /// Table A.
    pub posture_a: u8,
    pub load: u8,
    /// Score A = table A + load.
    pub score_a: u8,
    pub upper_arm: u8,
    pub lower_arm: u8,
    pub wrist: u8,
    /// Table B.
    pub posture_b: u8,
    pub coupling: u8,
    /// Score B = table B + coupling.
    pub score_b: u8,
    /// Table C.
    pub score_c: u8,
    pub activity: u8,
    /// The REBA score = score C + activity, 1–15.
    pub reba: u8,
    /// 0 negligible, 1 low, 2 medium, 3 high, 4 very high.
    pub risk_level: u8,
}

/// The load/force score.
pub fn load_score(load_kg: f64, shock: bool) -> u8 {
    let base = if load_kg < 5.0 {
        0
    } else if load_kg <= 10.0 {
        1
    } else {
        2
    };
    base + shock as u8
}

/// The trunk's score before adjustment.
pub fn trunk_position(flexion_deg: f64) -> u8 {
    if flexion_deg == 0.0 {
        1
    } else if flexion_deg < -20.0 {
        3
    } else if flexion_deg <= 20.0 {
        2
    } else if flexion_deg <= 60.0 {
        3
    } else {
        4
    }
}

/// The upper arm's score before adjustments (as RULA's).
pub fn upper_arm_position(flexion_deg: f64) -> u8 {
    crate::rula::upper_arm_position(flexion_deg)
}

/// The REBA score's risk level.
pub fn risk_level(reba: u8) -> u8 {
    match reba {
        0..=1 => 0,
        2..=3 => 1,
        4..=7 => 2,
        8..=10 => 3,
        _ => 4,
    }
}

/// REBA's scores for `input`.
pub fn score(input: &RebaInput) -> RebaScore {
    let deg = f64::to_degrees;
    let flag = |b: bool| b as u8;
    let trunk = (trunk_position(deg(input.trunk)) + flag(input.trunk_twisted_or_side_bent)).min(5);
    let n = deg(input.neck);
    let neck = (if (0.0..=20.0).contains(&n) { 1 } else { 2 }
        + flag(input.neck_twisted_or_side_bent))
    .min(3);
    let knee = deg(input.knee_flexion);
    let knees = if input.sitting || knee < 30.0 {
        0
    } else if knee <= 60.0 {
        1
    } else {
        2
    };
    let legs = (1 + flag(input.unilateral) + knees).min(4);
    let posture_a = TABLE_A[trunk as usize - 1][neck as usize - 1][legs as usize - 1];
    let load = load_score(input.load_kg, input.shock);
    let score_a = (posture_a + load).min(12);
    let upper_arm = (upper_arm_position(deg(input.upper_arm))
        + flag(input.arm_abducted_or_rotated)
        + flag(input.shoulder_raised))
    .saturating_sub(flag(input.arm_supported))
    .clamp(1, 6);
    let la = deg(input.lower_arm);
    let lower_arm = if (60.0..=100.0).contains(&la) { 1 } else { 2 };
    let wrist = (if deg(input.wrist.abs()) <= 15.0 { 1 } else { 2 }
        + flag(input.wrist_deviated_or_twisted))
    .min(3);
    let posture_b = TABLE_B[upper_arm as usize - 1][lower_arm as usize - 1][wrist as usize - 1];
    let coupling = input.coupling.score();
    let score_b = (posture_b + coupling).min(12);
    let score_c = TABLE_C[score_a as usize - 1][score_b as usize - 1];
    let activity = input.activity.min(3);
    let reba = score_c + activity;
    RebaScore {
        trunk,
        neck,
        legs,
        posture_a,
        load,
        score_a,
        upper_arm,
        lower_arm,
        wrist,
        posture_b,
        coupling,
        score_b,
        score_c,
        activity,
        reba,
        risk_level: risk_level(reba),
    }
}
