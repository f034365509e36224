//! The manikin's body as capsules (a segment with a radius) on the joint centres of a
//! posture, for collision checks against parts: head, neck, trunk, pelvis, upper arms,
//! forearms, hands, thighs, shanks. The radii are the data table's (estimates, see its
//! header); feet are left out (they stand on the floor).

use crate::anthropometry::{Body, SegmentRadii};
use crate::posture::{Posture, Side};
use glam::DVec3;

/// A body segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Segment {
    Head,
    Neck,
    Trunk,
    Pelvis,
    UpperArm(Side),
    Forearm(Side),
    Hand(Side),
    Thigh(Side),
    Shank(Side),
}

impl Segment {
    /// "head", "right forearm", …
    pub fn name(self) -> String {
        match self {
            Segment::Head => "head".into(),
            Segment::Neck => "neck".into(),
            Segment::Trunk => "trunk".into(),
            Segment::Pelvis => "pelvis".into(),
            Segment::UpperArm(s) => format!("{} upper arm", s.name()),
            Segment::Forearm(s) => format!("{} forearm", s.name()),
            Segment::Hand(s) => format!("{} hand", s.name()),
            Segment::Thigh(s) => format!("{} thigh", s.name()),
            Segment::Shank(s) => format!("{} shank", s.name()),
        }
    }

    /// The segment's capsule radius among `radii` \[m\].
    pub fn radius(self, radii: &SegmentRadii) -> f64 {
        match self {
            Segment::Head => radii.head,
            Segment::Neck => radii.neck,
            Segment::Trunk => radii.trunk,
            Segment::Pelvis => radii.pelvis,
            Segment::UpperArm(_) => radii.upper_arm,
            Segment::Forearm(_) => radii.forearm,
            Segment::Hand(_) => radii.hand,
            Segment::Thigh(_) => radii.thigh,
            Segment::Shank(_) => radii.shank,
        }
    }
}

/// One capsule: the points within `radius` of segment [a, b] \[m\].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Capsule {
    pub segment: Segment,
    pub a: DVec3,
    pub b: DVec3,
    pub radius: f64,
}

/// How many capsules a body has.
pub const CAPSULE_COUNT: usize = 14;

/// The segments in the order [`capsules`] gives their capsules.
pub const SEGMENTS: [Segment; CAPSULE_COUNT] = [
    Segment::Head,
    Segment::Neck,
    Segment::Trunk,
    Segment::Pelvis,
    Segment::UpperArm(Side::Right),
    Segment::UpperArm(Side::Left),
    Segment::Forearm(Side::Right),
    Segment::Forearm(Side::Left),
    Segment::Hand(Side::Right),
    Segment::Hand(Side::Left),
    Segment::Thigh(Side::Right),
    Segment::Thigh(Side::Left),
    Segment::Shank(Side::Right),
    Segment::Shank(Side::Left),
];

/// The capsules of `body` in `posture`, in the order of [`SEGMENTS`].
pub fn capsules(body: &Body, posture: &Posture) -> [Capsule; CAPSULE_COUNT] {
    let r = &body.radii;
    let j = &posture.joints;
    let cap = |segment, a, b, radius| Capsule {
        segment,
        a,
        b,
        radius,
    };
    let arm = |s: Side| &posture.arms[s.index()];
    let (rs, ls) = (Side::Right, Side::Left);
    let hand_end = |s: Side| {
        let a = arm(s);
        let d = (a.grip - a.wrist).normalize_or(DVec3::ZERO);
        a.wrist + d * (body.dims.hand - r.hand).max(0.0)
    };
    [
        cap(Segment::Head, j.head, j.head, r.head),
        cap(Segment::Neck, j.neck_base, j.chin, r.neck),
        // the trunk capsule ends a radius below the shoulder line, the pelvis's a
        // radius above the hips: the shoulders and hips are joints, not bulk
        cap(
            Segment::Trunk,
            j.lumbar,
            lerp_to(j.lumbar, j.neck_base, r.trunk),
            r.trunk,
        ),
        cap(Segment::Pelvis, j.hips[0], j.hips[1], r.pelvis),
        cap(
            Segment::UpperArm(rs),
            arm(rs).shoulder,
            arm(rs).elbow,
            r.upper_arm,
        ),
        cap(
            Segment::UpperArm(ls),
            arm(ls).shoulder,
            arm(ls).elbow,
            r.upper_arm,
        ),
        cap(
            Segment::Forearm(rs),
            arm(rs).elbow,
            arm(rs).wrist,
            r.forearm,
        ),
        cap(
            Segment::Forearm(ls),
            arm(ls).elbow,
            arm(ls).wrist,
            r.forearm,
        ),
        cap(Segment::Hand(rs), arm(rs).wrist, hand_end(rs), r.hand),
        cap(Segment::Hand(ls), arm(ls).wrist, hand_end(ls), r.hand),
        cap(Segment::Thigh(rs), j.hips[0], j.knees[0], r.thigh),
        cap(Segment::Thigh(ls), j.hips[1], j.knees[1], r.thigh),
        cap(Segment::Shank(rs), j.knees[0], j.ankles[0], r.shank),
        cap(Segment::Shank(ls), j.knees[1], j.ankles[1], r.shank),
    ]
}

/// The point `back` short of `b` on the way from `a` (`a` if the segment is shorter).
fn lerp_to(a: DVec3, b: DVec3, back: f64) -> DVec3 {
    let d = b - a;
    let len = d.length();
    if len <= back {
        a
    } else {
        a + d * ((len - back) / len)
    }
}
