//! A posture of the manikin: the joint angles the scores read and the joint positions
//! the body of capsules is built on. Angles in radians, positions in world metres.

use glam::DVec3;

/// Which arm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    Right,
    Left,
}

impl Side {
    pub const BOTH: [Side; 2] = [Side::Right, Side::Left];

    /// Index into per-arm arrays: right 0, left 1.
    pub fn index(self) -> usize {
        match self {
            Side::Right => 0,
            Side::Left => 1,
        }
    }

    /// +1 for the left, −1 for the right: the sign of the lateral (left) coordinate
    /// pointing away from the body on this side.
    pub fn outward(self) -> f64 {
        match self {
            Side::Right => -1.0,
            Side::Left => 1.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Side::Right => "right",
            Side::Left => "left",
        }
    }
}

/// The trunk's rotation at the lumbar joint relative to upright \[rad\]: forward
/// flexion (negative: extension), lateral bending (positive: to the right), twist
/// (positive: turned to the left). Applied as twist · lateral · flexion.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct TrunkAngles {
    pub flexion: f64,
    pub lateral: f64,
    pub twist: f64,
}

/// One arm's pose.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ArmPose {
    /// The point the hand should hold, if this arm has one.
    pub target: Option<DVec3>,
    /// Joint centres \[m\]: shoulder, elbow, wrist, and the grip centre (mid-hand).
    pub shoulder: DVec3,
    pub elbow: DVec3,
    pub wrist: DVec3,
    pub grip: DVec3,
    /// Elbow flexion from the straight arm \[rad\].
    pub elbow_flexion: f64,
    /// Upper arm's angle from the trunk's downward axis \[rad\]: 0 hanging, π/2
    /// horizontal, π straight up.
    pub elevation: f64,
    /// Upper arm's flexion in the trunk's sagittal plane \[rad\] (negative: extension).
    pub flexion: f64,
    /// Upper arm's abduction in the trunk's frontal plane \[rad\] (negative: adduction
    /// across the body).
    pub abduction: f64,
    /// Whether the hand works across the body's midline or out beyond its shoulder.
    pub across_or_out: bool,
    /// How far the grip centre stays from the target \[m\] (0 when reached), the
    /// shoulder's range included (an excess angle counts as its arc at full reach).
    pub residual: f64,
}

/// Joint centres of the trunk, head and legs \[m\].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Joints {
    /// Lumbar joint (taken at hip height, between the hips).
    pub lumbar: DVec3,
    /// Middle of the shoulder line (base of the neck).
    pub neck_base: DVec3,
    /// The chin's level on the neck axis (top of the neck segment).
    pub chin: DVec3,
    /// Head centre (at eye level).
    pub head: DVec3,
    /// Hip, knee, ankle joints, right then left.
    pub hips: [DVec3; 2],
    pub knees: [DVec3; 2],
    pub ankles: [DVec3; 2],
}

/// How a seated posture sits (crate::seat), for the scores and the posture class.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Sitting {
    /// Height of the seat surface above the floor \[m\].
    pub seat_height: f64,
    /// Knee flexion from the straight leg \[rad\].
    pub knee_flexion: f64,
    /// Whether the feet rest on the floor (a seat no higher than the popliteal height).
    pub feet_on_floor: bool,
}

/// A whole posture: what inverse kinematics found.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Posture {
    pub trunk: TrunkAngles,
    /// Neck flexion relative to the trunk \[rad\] (negative: extension).
    pub neck_flexion: f64,
    /// Neck twist relative to the trunk \[rad\].
    pub neck_twist: f64,
    /// Right arm, then left.
    pub arms: [ArmPose; 2],
    pub joints: Joints,
    /// Seated on a seat (`None`: standing on straight legs).
    pub sitting: Option<Sitting>,
}

impl Posture {
    /// The larger residual of the two arms \[m\].
    pub fn worst_residual(&self) -> f64 {
        self.arms[0].residual.max(self.arms[1].residual)
    }
}
