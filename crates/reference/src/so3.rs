//! Small SO(3) toolkit: hat/vee maps, an accurate logarithm, the inverse right
//! Jacobian and geodesic interpolation.
//!
//! nalgebra's `Rotation3::scaled_axis` obtains the angle from `acos` of the trace,
//! which loses half the significant digits near the identity (an angle of 1e-9 rad
//! comes out with an absolute error of ~1e-8). The shooting residual needs the
//! rotation vector to ~1e-14, so the logarithm here uses `atan2(|w|, cos θ)`, with
//! `w` the axial vector of the skew part, and a separate branch near θ = π.

use nalgebra::{Matrix3, Rotation3, Vector3};

/// The hat map: `skew(v) * x == v × x`.
pub(crate) fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Axial vector of the skew-symmetric part of `a`, i.e. `vee((a − aᵀ)/2)`.
pub(crate) fn vee_skew_part(a: &Matrix3<f64>) -> Vector3<f64> {
    0.5 * Vector3::new(
        a[(2, 1)] - a[(1, 2)],
        a[(0, 2)] - a[(2, 0)],
        a[(1, 0)] - a[(0, 1)],
    )
}

/// Rotation vector ψ (axis · angle, angle in [0, π]) with `exp([ψ]×) = r`.
///
/// `r` must be (numerically) a rotation matrix; tiny departures from
/// orthogonality only perturb the result to the same order.
pub(crate) fn log(r: &Matrix3<f64>) -> Vector3<f64> {
    let w = vee_skew_part(r); // = sin θ · axis
    let c = ((r.trace() - 1.0) * 0.5).clamp(-1.0, 1.0); // = cos θ
    let s = w.norm();
    let theta = s.atan2(c);
    if c > -0.5 {
        // θ < 120°: the skew part determines the axis accurately.
        if s == 0.0 {
            return Vector3::zeros();
        }
        return w * (theta / s);
    }
    // Near θ = π: use the symmetric part, (r + rᵀ)/2 = c I + (1 − c) a aᵀ.
    let sym = (r + r.transpose()) * 0.5;
    let aat = (sym - Matrix3::identity() * c) / (1.0 - c);
    let i = (0..3)
        .max_by(|&i, &j| aat[(i, i)].total_cmp(&aat[(j, j)]))
        .unwrap_or(0);
    let mut axis: Vector3<f64> = aat.column(i).into();
    axis /= axis.norm();
    if axis.dot(&w) < 0.0 {
        axis = -axis;
    }
    axis * theta
}

/// Inverse of the right Jacobian of SO(3):
/// `log(exp(ψ) exp(δθ)) = ψ + J_r⁻¹(ψ) δθ + O(δθ²)`.
///
/// `J_r⁻¹(ψ) = I + ½[ψ]× + (1/θ² − (1 + cos θ)/(2θ sin θ)) [ψ]×²`, θ = |ψ|
/// (e.g. Chirikjian, "Stochastic Models, Information Theory, and Lie Groups",
/// vol. 2, ch. 10). Singular at θ = 2π, never reached since θ ≤ π.
pub(crate) fn right_jacobian_inverse(psi: &Vector3<f64>) -> Matrix3<f64> {
    let theta = psi.norm();
    let k = skew(psi);
    let coefficient = if theta < 1e-4 {
        // Series: 1/12 + θ²/720 + O(θ⁴).
        1.0 / 12.0 + theta * theta / 720.0
    } else {
        1.0 / (theta * theta) - (1.0 + theta.cos()) / (2.0 * theta * theta.sin())
    };
    Matrix3::identity() + k * 0.5 + k * k * coefficient
}

/// Geodesic interpolation `a · exp(t · log(aᵀ b))`, `t ∈ [0, 1]`.
pub(crate) fn interpolate(a: &Rotation3<f64>, b: &Rotation3<f64>, t: f64) -> Rotation3<f64> {
    let delta = log((a.inverse() * b).matrix());
    a * Rotation3::new(delta * t)
}

/// The rotation nearest to a matrix that is a rotation up to integration drift.
pub(crate) fn nearest_rotation(m: &Matrix3<f64>) -> Rotation3<f64> {
    Rotation3::from_matrix_eps(m, 1e-15, 50, Rotation3::from_matrix_unchecked(*m))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_inverts_exp_including_small_and_near_pi_angles() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        for &angle in &[
            0.0,
            1e-12,
            1e-9,
            1e-3,
            1.0,
            2.0,
            3.0,
            std::f64::consts::PI - 1e-5,
            std::f64::consts::PI,
        ] {
            let psi = axis * angle;
            let r = Rotation3::new(psi);
            let back = log(r.matrix());
            let err = if angle > 3.0 {
                // ±axis·π are the same rotation.
                (back - psi).norm().min((back + psi).norm())
            } else {
                (back - psi).norm()
            };
            assert!(err < 1e-13 * (1.0 + angle), "angle {angle}: error {err}");
        }
    }

    #[test]
    fn right_jacobian_inverse_matches_finite_differences() {
        let psi = Vector3::new(0.4, -1.1, 0.7);
        let jinv = right_jacobian_inverse(&psi);
        let r = Rotation3::new(psi);
        let h = 1e-6;
        for j in 0..3 {
            let mut d = Vector3::zeros();
            d[j] = h;
            let plus = log((r * Rotation3::new(d)).matrix());
            let minus = log((r * Rotation3::new(-d)).matrix());
            let column = (plus - minus) / (2.0 * h);
            assert!((column - jinv.column(j)).norm() < 1e-8);
        }
    }
}
