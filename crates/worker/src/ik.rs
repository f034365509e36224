//! Inverse kinematics of the manikin: both hands to their targets with the feet kept on
//! the floor, within the joint limits, deterministic and allocation-free.
//!
//! Each arm is solved analytically as a two-link chain (shoulder–elbow, elbow–grip
//! centre with the wrist straight): the law of cosines gives the elbow flexion for the
//! shoulder–target distance clamped to what the elbow's range allows, and the elbow is
//! put at the swivel angle that keeps it lowest (the elbow hangs under gravity; cf.
//! Tolani, Goswami & Badler, "Real-time inverse kinematics techniques for
//! anthropomorphic limbs", Graphical Models 62, 2000, for the swivel parametrisation).
//! The trunk's flexion, lateral bending and twist at the lumbar joint are found by a
//! fixed grid over their ranges of motion followed by a pattern search (Hooke & Jeeves
//! 1961) with a fixed number of halvings, minimising
//!
//!   cost = Σ_arms r² + |e − e*|² + λ (α² + β² + γ²),   λ = 10⁻⁸ m²/rad²,
//!
//! the middle term only with a head target (a VR headset: e the manikin's eyes, e* the
//! headset's; the neck then turns the head along the headset's gaze within its range),
//! r an arm's residual (how far its grip centre stays from the target, an excess over
//! the shoulder's extension limit counted as its arc at full reach): reaching comes
//! first, an upright trunk second (10⁻⁸ m²/rad² trades 30° of bending for 0.05 mm of
//! reach, and biases a reached target by well under a micrometre). The same targets always give the same posture bit for bit: the search
//! visits its points in a fixed order and keeps the first of equal costs.
//!
//! Seated ([`crate::seat`]), the lumbar joint is at the seated hip joints' height above
//! the placement's floor point, the pelvis stays on the seat and the same search bends
//! the trunk over it; the legs rest on the seat and the floor.
//!
//! What the model does not do: standing, knees and hips stay straight (no squatting or kneeling;
//! the feet stay where the worker was placed — a step moves the placement, [`crate::step`]), the wrist stays straight, the
//! shoulder girdle does not move (no shoulder raising or protraction), and the shoulder's
//! adduction and rotation are not limited.

use crate::anthropometry::Body;
use crate::placement::Placement;
use crate::posture::{ArmPose, Joints, Posture, Side, Sitting, TrunkAngles};
use crate::seat::Seat;
use glam::{DQuat, DVec3};

/// The weight of trunk rotation against reach in the cost \[m²/rad²\] (module doc).
pub const TRUNK_WEIGHT: f64 = 1e-8;

/// Grid points over each trunk angle's range (flexion, twist, lateral).
const GRID: [usize; 3] = [11, 7, 5];

/// Halvings of the pattern search's step.
const HALVINGS: usize = 12;

/// Where the user's head is and where it looks (a VR headset), for
/// [`Manikin::solve_with_head`]: the eyes' midpoint \[m\] and the gaze direction.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HeadTarget {
    pub eyes: DVec3,
    pub gaze: DVec3,
}

/// A worker's body standing at a placement, or seated there.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Manikin {
    pub body: Body,
    pub placement: Placement,
    /// The seat under the pelvis at the placement's floor point (`None`: standing).
    pub seat: Option<Seat>,
}

/// The trunk's frame in the world: unit forward, left, up axes.
#[derive(Clone, Copy, Debug)]
struct TrunkFrame {
    forward: DVec3,
    left: DVec3,
    up: DVec3,
}

impl Manikin {
    /// The worker standing at `placement`.
    pub fn new(body: Body, placement: Placement) -> Manikin {
        Manikin {
            body,
            placement,
            seat: None,
        }
    }

    /// The worker seated on `seat` at `placement` (its floor point under the pelvis).
    pub fn seated(body: Body, placement: Placement, seat: Seat) -> Manikin {
        Manikin {
            body,
            placement,
            seat: Some(seat),
        }
    }

    /// The same worker (standing or seated alike) at `placement`.
    pub fn at(&self, placement: Placement) -> Manikin {
        Manikin { placement, ..*self }
    }

    /// Height of the hip joints above the floor \[m\]: standing, the body's hip height;
    /// seated, the seat's ([`Seat::hip_height`]).
    pub fn hip_height(&self) -> f64 {
        self.seat
            .map_or(self.body.dims.hip_height, |s| s.hip_height(&self.body))
    }

    /// The lumbar joint: at the hips' height above the floor point.
    pub fn lumbar(&self) -> DVec3 {
        self.placement
            .point(DVec3::new(0.0, 0.0, self.hip_height()))
    }

    /// Upright trunk: where each shoulder joint is \[m\].
    pub fn shoulder_upright(&self, side: Side) -> DVec3 {
        let b = &self.body;
        self.placement.point(DVec3::new(
            0.0,
            side.outward() * 0.5 * b.dims.shoulder_width,
            self.hip_height() + b.dims.shoulder_height - b.dims.hip_height,
        ))
    }

    fn frame(&self, t: TrunkAngles) -> TrunkFrame {
        let q = DQuat::from_axis_angle(DVec3::Z, t.twist)
            * DQuat::from_axis_angle(DVec3::X, t.lateral)
            * DQuat::from_axis_angle(DVec3::Y, t.flexion);
        let p = &self.placement;
        TrunkFrame {
            forward: p.vector(q * DVec3::X),
            left: p.vector(q * DVec3::Y),
            up: p.vector(q * DVec3::Z),
        }
    }

    fn shoulder(&self, f: &TrunkFrame, side: Side) -> DVec3 {
        let b = &self.body;
        self.lumbar()
            + f.left * (side.outward() * 0.5 * b.dims.shoulder_width)
            + f.up * (b.dims.shoulder_height - b.dims.hip_height)
    }

    /// One arm reaching for `target` from its shoulder in trunk frame `f`.
    fn arm(&self, f: &TrunkFrame, side: Side, target: Option<DVec3>) -> ArmPose {
        let b = &self.body;
        let s = self.shoulder(f, side);
        let down = -self.placement.up;
        let outward = f.left * side.outward();
        let (a, c) = (b.dims.upper_arm, b.dims.forearm + b.grip_offset());
        let Some(t) = target else {
            // hanging under gravity
            let elbow = s + down * a;
            let wrist = elbow + down * b.dims.forearm;
            return self.arm_pose(
                f,
                side,
                s,
                elbow,
                wrist,
                wrist + down * b.grip_offset(),
                None,
                0.0,
            );
        };
        let v = t - s;
        let d = v.length();
        let dir = if d > 1e-12 { v / d } else { f.forward };
        let cos_max = b.limits.elbow_flexion.cos();
        let d_min = (a * a + c * c + 2.0 * a * c * cos_max).max(0.0).sqrt();
        let d_r = d.clamp(d_min, a + c);
        let cos_psi = ((a * a + d_r * d_r - c * c) / (2.0 * a * d_r)).clamp(-1.0, 1.0);
        let (sin_psi, cos_psi) = (cos_psi.acos().sin(), cos_psi);
        // the swivel: the elbow as low as it can be
        let mut n = down - down.dot(dir) * dir;
        if n.length_squared() < 1e-12 {
            n = outward - outward.dot(dir) * dir;
        }
        let n = n.normalize_or(f.up.cross(dir).normalize_or(DVec3::Z));
        let elbow = s + a * (cos_psi * dir + sin_psi * n);
        let grip = s + dir * d_r;
        let fd = (grip - elbow).normalize_or(dir);
        let wrist = elbow + fd * b.dims.forearm;
        self.arm_pose(f, side, s, elbow, wrist, grip, Some(t), (d - d_r).abs())
    }

    /// The angles of an arm from its joint positions; `gap` the reach residual before
    /// the shoulder's limits are counted.
    #[allow(clippy::too_many_arguments)]
    fn arm_pose(
        &self,
        f: &TrunkFrame,
        side: Side,
        shoulder: DVec3,
        elbow: DVec3,
        wrist: DVec3,
        grip: DVec3,
        target: Option<DVec3>,
        gap: f64,
    ) -> ArmPose {
        let b = &self.body;
        let outward = f.left * side.outward();
        let ua = (elbow - shoulder).normalize_or(-f.up);
        let fa = (grip - elbow).normalize_or(ua);
        let (cf, co, cu) = (ua.dot(f.forward), ua.dot(outward), ua.dot(f.up));
        let elevation = (-cu).clamp(-1.0, 1.0).acos();
        // behind the frontal plane: extension, the angle back from hanging
        let extension = (-cf).clamp(0.0, 1.0).asin();
        let flexion = if cf < 0.0 && cu < 0.0 {
            -extension
        } else {
            elevation
        };
        let abduction = co.clamp(-1.0, 1.0).asin();
        let excess = (extension - b.limits.shoulder_extension).max(0.0);
        let elbow_flexion = ua.dot(fa).clamp(-1.0, 1.0).acos();
        let lateral = (grip - self.lumbar()).dot(outward);
        let residual = if target.is_some() {
            gap + excess * b.arm_reach()
        } else {
            0.0
        };
        ArmPose {
            target,
            shoulder,
            elbow,
            wrist,
            grip,
            elbow_flexion,
            elevation,
            flexion,
            abduction,
            across_or_out: target.is_some() && (lateral < 0.0 || lateral > b.dims.shoulder_width),
            residual,
        }
    }

    fn cost(&self, t: TrunkAngles, targets: &[Option<DVec3>; 2], head: Option<HeadTarget>) -> f64 {
        let f = self.frame(t);
        let mut c =
            TRUNK_WEIGHT * (t.flexion * t.flexion + t.lateral * t.lateral + t.twist * t.twist);
        if let Some(h) = head {
            let neck_base = self.neck_base(&f);
            let (flexion, twist) = self.neck_angles(&f, Some(h.gaze));
            let (_, eyes) = self.head_points(&f, neck_base, flexion, twist);
            c += (eyes - h.eyes).length_squared();
        }
        for side in Side::BOTH {
            if let Some(target) = targets[side.index()] {
                let r = self.arm(&f, side, Some(target)).residual;
                c += r * r;
            }
        }
        c
    }

    /// The posture reaching `targets` (right hand, left hand; `None`: the arm hangs).
    pub fn solve(&self, targets: [Option<DVec3>; 2]) -> Posture {
        self.solve_with_head(targets, None)
    }

    /// [`Self::solve`] with the eyes drawn towards a head target too, and the head
    /// looking along its gaze (module doc).
    pub fn solve_with_head(
        &self,
        targets: [Option<DVec3>; 2],
        head: Option<HeadTarget>,
    ) -> Posture {
        let l = &self.body.limits;
        let ranges = [
            (-l.trunk_extension, l.trunk_flexion),
            (-l.trunk_twist, l.trunk_twist),
            (-l.trunk_lateral, l.trunk_lateral),
        ];
        let mut best = [0.0; 3];
        let mut best_cost = self.cost(trunk_angles(best), &targets, head);
        if (targets.iter().any(Option::is_some) || head.is_some()) && best_cost > 0.0 {
            for i in 0..GRID[0] {
                for j in 0..GRID[1] {
                    for k in 0..GRID[2] {
                        let mut x = [0.0; 3];
                        for (axis, n) in [i, j, k].into_iter().enumerate() {
                            let (lo, hi) = ranges[axis];
                            x[axis] = lo + (hi - lo) * n as f64 / (GRID[axis] - 1) as f64;
                        }
                        let c = self.cost(trunk_angles(x), &targets, head);
                        if c < best_cost {
                            best_cost = c;
                            best = x;
                        }
                    }
                }
            }
            let mut step = [0.0; 3];
            for (axis, s) in step.iter_mut().enumerate() {
                let (lo, hi) = ranges[axis];
                *s = 0.5 * (hi - lo) / (GRID[axis] - 1) as f64;
            }
            (best, best_cost) = self.refine(best, best_cost, step, 1, &ranges, &targets, head);
            // the eyes can be met by many trunks (a lean made up by a twist): a second
            // search from upright, with long strides, finds the least bent one the grid's
            // cell may miss
            if head.is_some() {
                let upright = self.cost(trunk_angles([0.0; 3]), &targets, head);
                let step = ranges.map(|(lo, hi)| 0.25 * (hi - lo));
                let (x, c) = self.refine([0.0; 3], upright, step, 4, &ranges, &targets, head);
                if c < best_cost {
                    best = x;
                }
            }
        }
        self.posture_with_head(trunk_angles(best), targets, head)
    }

    /// The pattern search from trunk angles `x` of cost `cost`: each of [`HALVINGS`]
    /// rounds tries a step up and down each axis in turn, keeping the first of equal
    /// costs, and sweeps again (up to `sweeps` times) while that helped; then the steps
    /// halve.
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        mut x: [f64; 3],
        mut cost: f64,
        mut step: [f64; 3],
        sweeps: usize,
        ranges: &[(f64, f64); 3],
        targets: &[Option<DVec3>; 2],
        head: Option<HeadTarget>,
    ) -> ([f64; 3], f64) {
        for _ in 0..HALVINGS {
            for _ in 0..sweeps {
                let before = cost;
                for axis in 0..3 {
                    for sign in [1.0, -1.0] {
                        let mut y = x;
                        let (lo, hi) = ranges[axis];
                        y[axis] = (y[axis] + sign * step[axis]).clamp(lo, hi);
                        let c = self.cost(trunk_angles(y), targets, head);
                        if c < cost {
                            cost = c;
                            x = y;
                        }
                    }
                }
                if cost == before {
                    break;
                }
            }
            for s in &mut step {
                *s *= 0.5;
            }
        }
        (x, cost)
    }

    /// The base of the neck (the middle of the shoulder line) in trunk frame `f`.
    fn neck_base(&self, f: &TrunkFrame) -> DVec3 {
        let b = &self.body;
        self.lumbar() + f.up * (b.dims.shoulder_height - b.dims.hip_height)
    }

    /// The neck's flexion and twist that turn the head to look along `gaze` (`None`:
    /// straight ahead), within the neck's range.
    fn neck_angles(&self, f: &TrunkFrame, gaze: Option<DVec3>) -> (f64, f64) {
        let l = &self.body.limits;
        let Some(g) = gaze else {
            return (0.0, 0.0);
        };
        let (ahead, aside) = (g.dot(f.forward), g.dot(f.left));
        // below the trunk's transverse plane, and round the trunk's axis
        let pitch = (-g.dot(f.up)).atan2(ahead.hypot(aside));
        let yaw = aside.atan2(ahead);
        (
            pitch.clamp(-l.neck_extension, l.neck_flexion),
            yaw.clamp(-l.neck_twist, l.neck_twist),
        )
    }

    /// The chin and the eyes' midpoint (the head joint) for the neck's angles.
    fn head_points(
        &self,
        f: &TrunkFrame,
        neck_base: DVec3,
        neck_flexion: f64,
        neck_twist: f64,
    ) -> (DVec3, DVec3) {
        let b = &self.body;
        let neck_q =
            DQuat::from_axis_angle(f.up, neck_twist) * DQuat::from_axis_angle(f.left, neck_flexion);
        let neck_axis = neck_q * f.up;
        (
            neck_base + neck_axis * (b.dims.chin_height - b.dims.shoulder_height),
            neck_base + neck_axis * (b.dims.eye_height - b.dims.shoulder_height),
        )
    }

    /// The whole posture at trunk angles `t` with the arms reaching for `targets`.
    pub fn posture(&self, t: TrunkAngles, targets: [Option<DVec3>; 2]) -> Posture {
        self.posture_with_head(t, targets, None)
    }

    /// [`Self::posture`], the head looking along `head`'s gaze if given (else at the
    /// middle of the targets).
    pub fn posture_with_head(
        &self,
        t: TrunkAngles,
        targets: [Option<DVec3>; 2],
        head: Option<HeadTarget>,
    ) -> Posture {
        let b = &self.body;
        let p = &self.placement;
        let f = self.frame(t);
        let arms = Side::BOTH.map(|side| self.arm(&f, side, targets[side.index()]));
        let lumbar = self.lumbar();
        let neck_base = self.neck_base(&f);
        let eyes_upright = neck_base + f.up * (b.dims.eye_height - b.dims.shoulder_height);
        // the headset's gaze, else the middle of the targets
        let mut middle = DVec3::ZERO;
        let mut count = 0.0;
        for target in targets.iter().flatten() {
            middle += *target;
            count += 1.0;
        }
        let gaze = match head {
            Some(h) => Some(h.gaze),
            None if count > 0.0 => Some(middle / count - eyes_upright),
            None => None,
        };
        let (neck_flexion, neck_twist) = self.neck_angles(&f, gaze);
        let (chin, head_joint) = self.head_points(&f, neck_base, neck_flexion, neck_twist);
        let (hips, knees, ankles, sitting) = match self.seat {
            Some(seat) => {
                let legs = seat.legs(b, p);
                let sitting = Sitting {
                    seat_height: seat.height,
                    knee_flexion: legs.knee_flexion,
                    feet_on_floor: legs.feet_on_floor(),
                };
                (legs.hips, legs.knees, legs.ankles, Some(sitting))
            }
            None => {
                let leg = |height: f64| {
                    Side::BOTH.map(|s| {
                        p.point(DVec3::new(
                            0.0,
                            s.outward() * 0.5 * b.dims.hip_width,
                            height,
                        ))
                    })
                };
                (
                    leg(b.dims.hip_height),
                    leg(b.dims.knee_height),
                    leg(b.dims.ankle_height),
                    None,
                )
            }
        };
        Posture {
            trunk: t,
            neck_flexion,
            neck_twist,
            arms,
            joints: Joints {
                lumbar,
                neck_base,
                chin,
                head: head_joint,
                hips,
                knees,
                ankles,
            },
            sitting,
        }
    }
}

/// Trunk angles from the search's coordinates (flexion, twist, lateral).
fn trunk_angles(x: [f64; 3]) -> TrunkAngles {
    TrunkAngles {
        flexion: x[0],
        twist: x[1],
        lateral: x[2],
    }
}

/// Which arm takes which hand target: the first two targets (in the caller's order, e.g.
/// by hand number), the one further to the worker's right to the right arm; a single
/// target to the arm on its side (the right on the midline). Targets beyond two are left
/// out — one worker has two hands.
pub fn assign_hands(placement: &Placement, targets: &[DVec3]) -> [Option<DVec3>; 2] {
    let lateral = |t: DVec3| placement.local(t - placement.position).y;
    match targets {
        [] => [None, None],
        [t] if lateral(*t) > 0.0 => [None, Some(*t)],
        [t] => [Some(*t), None],
        [a, b, ..] if lateral(*b) < lateral(*a) => [Some(*b), Some(*a)],
        [a, b, ..] => [Some(*a), Some(*b)],
    }
}
