//! Rotation helpers (SPEC P2, dissertation appendix A.2): the exponential map
//! (Rodrigues' formula) from rotation vectors to unit quaternions, its inverse, and the
//! tangent operator that turns moments conjugate to a rotation vector into spatial moments.

use crate::autodiff::{Quat, Scalar, V3};
use glam::{DQuat, DVec3, DVec4};

/// The unit quaternion in the direction of `q`, for any finite non-zero `q` — also one
/// whose squared length overflows ([1e200, 0, 0, 0]) or underflows: it is scaled by its
/// largest component first. `None` for a zero or non-finite `q`.
pub fn unit_quaternion(q: DQuat) -> Option<DQuat> {
    if !q.is_finite() {
        return None;
    }
    let largest = DVec4::from(q).abs().max_element();
    if largest == 0.0 {
        return None;
    }
    let unit = (DQuat::from_vec4(DVec4::from(q) / largest)).normalize();
    (unit.is_finite() && (unit.length() - 1.0).abs() < 1e-12).then_some(unit)
}

/// How far the length of an orientation quaternion read from outside (a client's hand
/// pose) may lie from 1 and still be taken as a rotation: |‖q‖ − 1| ≤ this. Room for
/// rounding (single-precision devices, printed digits), not for a scale.
pub const UNIT_QUATERNION_TOLERANCE: f64 = 1e-3;

/// Why a quaternion is not taken as an orientation ([`near_unit_quaternion`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum QuaternionError {
    /// A component is NaN or infinite.
    NonFinite,
    /// All components are zero.
    Zero,
    /// Its length lies further from 1 than [`UNIT_QUATERNION_TOLERANCE`].
    NotUnit { length: f64 },
}

impl std::fmt::Display for QuaternionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            QuaternionError::NonFinite => write!(f, "has a non-finite component"),
            QuaternionError::Zero => write!(f, "is zero"),
            QuaternionError::NotUnit { length } => write!(
                f,
                "has length {length:e}, not 1 (within {UNIT_QUATERNION_TOLERANCE})"
            ),
        }
    }
}

/// An orientation given from outside: `q` normalised when it is finite and its length
/// lies within [`UNIT_QUATERNION_TOLERANCE`] of 1, else why not.
pub fn near_unit_quaternion(q: DQuat) -> Result<DQuat, QuaternionError> {
    if !q.is_finite() {
        return Err(QuaternionError::NonFinite);
    }
    if q == DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0) {
        return Err(QuaternionError::Zero);
    }
    let length = q.length();
    if !((length - 1.0).abs() <= UNIT_QUATERNION_TOLERANCE) {
        return Err(QuaternionError::NotUnit { length });
    }
    unit_quaternion(q).ok_or(QuaternionError::NonFinite)
}

/// Exponential map: rotation vector φ (axis · angle, any magnitude) → unit quaternion.
/// Rodrigues' formula in quaternion form, q = (cos |φ|/2, sin(|φ|/2) φ/|φ|), with a
/// Taylor expansion near zero so tiny rotations keep full precision.
pub fn exp_map(phi: DVec3) -> DQuat {
    let angle_sq = phi.length_squared();
    let h2 = 0.25 * angle_sq; // (|φ|/2)²
                              // cos(h) and sin(h)/(2h) = ½ sinc(h): Taylor series below h = 0.05 (truncation
                              // error < 1e-19), where the step loop's per-step rotations almost always lie.
    let (c, s) = if h2 < 2.5e-3 {
        let c = 1.0 - h2 / 2.0 * (1.0 - h2 / 12.0 * (1.0 - h2 / 30.0 * (1.0 - h2 / 56.0)));
        let s = 0.5 * (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0 * (1.0 - h2 / 42.0 * (1.0 - h2 / 72.0))));
        (c, s)
    } else {
        let half = h2.sqrt();
        (half.cos(), half.sin() / (2.0 * half))
    };
    DQuat::from_xyzw(phi.x * s, phi.y * s, phi.z * s, c)
}

/// Logarithm map: unit quaternion → rotation vector of angle in [0, π] (the shorter of
/// q and −q). Uses atan2 so that small angles keep full relative precision.
pub fn log_map(q: DQuat) -> DVec3 {
    log_map_of(Quat::from(q)).into()
}

/// [`log_map`] over any [`Scalar`] (for the tangent by automatic differentiation).
#[inline(always)]
pub fn log_map_of<T: Scalar>(q: Quat<T>) -> V3<T> {
    let q = if q.w.re() < 0.0 { q.negate() } else { q };
    let (v, w) = (q.vector(), q.w);
    let s2 = v.length_squared();
    let w2 = w * w;
    // angle/s = 2 atan(x)/(x w) with x = s/w; series of atan(x)/x below x = 0.05
    // (rotations under 0.1 rad, the usual deformation of one element; error < 1e-17)
    if s2.re() < 2.5e-3 * w2.re() {
        let x2 = s2 / w2;
        let one = T::cst(1.0);
        let atan_over_x = one
            - x2 * (one / 3.0 - x2 * (one / 5.0 - x2 * (one / 7.0 - x2 * (one / 9.0 - x2 / 11.0))));
        return v.scale(atan_over_x * 2.0 / w);
    }
    let s = s2.sqrt();
    let angle = s.atan2(w) * 2.0;
    v.scale(angle / s)
}

/// Moment conjugate to a change of the rotation vector θ, mapped to the moment conjugate
/// to a spatial (left) rotation increment: m = J_l(θ)⁻ᵀ M, with
/// J_l⁻¹(θ) = I − ½\[θ\]× + (1/θ² − (1 + cos θ)/(2 θ sin θ)) \[θ\]×²
/// (e.g. Bullo & Murray 1995; Ibrahimbegović 1997, eq. 2.19).
pub fn left_jacobian_inverse_transpose_times(theta: DVec3, moment: DVec3) -> DVec3 {
    left_jacobian_inverse_transpose_times_of(V3::from(theta), V3::from(moment)).into()
}

/// [`left_jacobian_inverse_transpose_times`] over any [`Scalar`].
#[inline(always)]
pub fn left_jacobian_inverse_transpose_times_of<T: Scalar>(theta: V3<T>, moment: V3<T>) -> V3<T> {
    let t2 = theta.length_squared();
    // c = 1/θ² − (1 + cos θ)/(2 θ sin θ) = 1/12 + θ²/720 + θ⁴/30240 + θ⁶/1209600 + …;
    // the series is used below θ² = 0.1 (truncation error < 3e-12 relative to c)
    let c = if t2.re() < 0.1 {
        (t2 * (t2 * (t2 / 1209600.0 + 1.0 / 30240.0) + 1.0 / 720.0)) + 1.0 / 12.0
    } else {
        let t = t2.sqrt();
        T::cst(1.0) / t2 - (t.cos() + 1.0) / (t * t.sin() * 2.0)
    };
    let txm = theta.cross(moment);
    moment + txm.scale_f(0.5) + theta.cross(txm).scale(c)
}

/// Quaternion rotating the unit vector `from` onto the unit vector `to` by the smallest
/// angle (parallel transport of a frame along a turning tangent): q ∝ (1 + a·b, a × b).
/// Unlike glam's `from_rotation_arc`, angles below 3e-8 rad are not rounded to zero — the
/// co-rotational frame must follow the chord exactly, or the rounding shows up as force
/// noise of order E I/l² · 1e-8.
pub fn rotation_between(from: DVec3, to: DVec3) -> DQuat {
    rotation_between_of(V3::from(from), V3::from(to)).into()
}

/// [`rotation_between`] over any [`Scalar`].
#[inline(always)]
pub fn rotation_between_of<T: Scalar>(from: V3<T>, to: V3<T>) -> Quat<T> {
    let w = from.dot(to) + 1.0;
    if w.re() < 1e-12 {
        // antiparallel: half a turn about any axis normal to `from`
        let q = DQuat::from_axis_angle(from.re().any_orthonormal_vector(), std::f64::consts::PI);
        return Quat::cst(q);
    }
    Quat::from_parts(from.cross(to), w).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn unit_quaternion_survives_overflow_and_refuses_zero() {
        let q = unit_quaternion(DQuat::from_xyzw(1e200, 0.0, 0.0, 1e200)).unwrap();
        assert!((q.length() - 1.0).abs() < 1e-15);
        assert!((q.x - 0.5f64.sqrt()).abs() < 1e-15 && (q.w - 0.5f64.sqrt()).abs() < 1e-15);
        let tiny = unit_quaternion(DQuat::from_xyzw(0.0, 3e-320, 0.0, 0.0)).unwrap();
        assert_eq!(tiny.y, 1.0);
        assert!(unit_quaternion(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)).is_none());
        assert!(unit_quaternion(DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0)).is_none());
        assert!(unit_quaternion(DQuat::from_xyzw(f64::INFINITY, 0.0, 0.0, 1.0)).is_none());
    }

    #[test]
    fn only_near_unit_quaternions_are_orientations() {
        let q = near_unit_quaternion(DQuat::from_xyzw(0.0, 0.0, 0.6, 0.79999)).unwrap();
        assert!((q.length() - 1.0).abs() < 1e-15);
        let off = 1.0 + 2.0 * UNIT_QUATERNION_TOLERANCE;
        assert_eq!(
            near_unit_quaternion(DQuat::from_xyzw(0.0, 0.0, 0.0, off)),
            Err(QuaternionError::NotUnit { length: off })
        );
        assert!(matches!(
            near_unit_quaternion(DQuat::from_xyzw(1e200, 0.0, 0.0, 0.0)),
            Err(QuaternionError::NotUnit { .. })
        ));
        assert!(matches!(
            near_unit_quaternion(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.5)),
            Err(QuaternionError::NotUnit { .. })
        ));
        assert_eq!(
            near_unit_quaternion(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            Err(QuaternionError::Zero)
        );
        assert_eq!(
            near_unit_quaternion(DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0)),
            Err(QuaternionError::NonFinite)
        );
    }

    #[test]
    fn exp_log_round_trip_over_all_angles() {
        let axis = DVec3::new(1.0, -2.0, 0.5).normalize();
        for &angle in &[0.0, 1e-12, 1e-7, 1e-3, 0.5, 2.0, PI - 1e-6] {
            let phi = axis * angle;
            let back = log_map(exp_map(phi));
            assert!(
                (back - phi).length() <= 1e-14 + 1e-12 * angle,
                "angle {angle}: {back:?}"
            );
        }
    }

    #[test]
    fn exp_matches_glam_axis_angle_past_180_degrees() {
        let axis = DVec3::new(0.0, 0.6, 0.8);
        for &angle in &[3.5, 5.0, 7.0, 13.0] {
            let a = exp_map(axis * angle);
            let b = DQuat::from_axis_angle(axis, angle);
            let v = DVec3::new(0.3, 0.1, -0.7);
            assert!((a * v - b * v).length() < 1e-13);
        }
    }

    /// The series branches agree with the closed forms at their switch-over points.
    #[test]
    fn series_branches_match_closed_forms() {
        let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
        for &angle in &[0.0999, 0.1001, 0.09, 0.3] {
            let q = DQuat::from_axis_angle(axis, angle);
            assert!(
                (log_map(q) - axis * angle).length() < 1e-15,
                "log at {angle}"
            );
        }
        for &angle in &[0.0999, 0.1001, 0.05] {
            let a = exp_map(axis * angle);
            let b = DQuat::from_axis_angle(axis, angle);
            assert!((a - b).length() < 1e-16, "exp at {angle}");
        }
        let m = DVec3::new(0.2, 1.0, -0.4);
        for &t in &[0.3162, 0.3163] {
            let theta = axis * t;
            let closed = {
                let c = 1.0 / (t * t) - (1.0 + t.cos()) / (2.0 * t * t.sin());
                let txm = theta.cross(m);
                m + 0.5 * txm + c * theta.cross(txm)
            };
            let got = left_jacobian_inverse_transpose_times(theta, m);
            assert!((got - closed).length() < 1e-12, "J at {t}");
        }
    }

    #[test]
    fn rotation_between_keeps_tiny_angles() {
        let a = DVec3::X;
        let b = DVec3::new(1.0, 1e-9, 0.0).normalize();
        let q = rotation_between(a, b);
        assert!((q * a - b).length() < 1e-17);
        assert!((log_map(q).z - 1e-9).abs() < 1e-20);
    }

    #[test]
    fn jacobian_correction_vanishes_for_parallel_moment() {
        let t = DVec3::new(0.0, 0.0, 0.3);
        let m = DVec3::new(0.0, 0.0, 2.0);
        assert!((left_jacobian_inverse_transpose_times(t, m) - m).length() < 1e-15);
    }

    /// J_l⁻ᵀ checked against finite differences of the log map under left perturbation.
    #[test]
    fn jacobian_matches_finite_differences() {
        let theta = DVec3::new(0.4, -0.2, 0.7);
        let moment = DVec3::new(0.3, 1.1, -0.5);
        let q = exp_map(theta);
        let h = 1e-6;
        let mut expected = DVec3::ZERO;
        for k in 0..3 {
            let mut e = DVec3::ZERO;
            e[k] = h;
            let dp = log_map(exp_map(e) * q);
            let dm = log_map(exp_map(-e) * q);
            // d(M·θ)/dψ_k
            expected[k] = moment.dot((dp - dm) / (2.0 * h));
        }
        let got = left_jacobian_inverse_transpose_times(theta, moment);
        assert!((got - expected).length() < 1e-8, "{got:?} vs {expected:?}");
    }
}
