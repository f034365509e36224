//! The element tangent by the explicit kernel's algebra (issue 15, item 3).
//!
//! [`crate::tangent`] differentiates the reference load function
//! [`BeamElement::loads_of`] (quaternion rotations, the log map by atan2 or its series,
//! generic dual arithmetic in which constants are duals too). This module differentiates,
//! in forward mode with the same 9 dual components (δx_b, δθ_a, δθ_b), the algebra of the
//! four-element kernel [`crate::element_block`] — the same element law, reorganised but
//! not approximated:
//!
//! * the end frames' increments are seeded directly: for r = exp(δθ) q c (c the rest
//!   offset), ∂r/∂δθₖ = ½ (eₖ, 0) ⊗ r₀ = ½ (w₀ eₖ + eₖ × v₀, −v₀ₖ) for r₀ = (v₀, w₀),
//!   constant quaternions, instead of a dual quaternion product;
//! * the element frame's rotation matrix is formed once and rotates the four vectors;
//! * the log map is θ = 4 atan(y)/y · v/(1 + w), y² = |v|²/(1 + w)², and the tangent
//!   operator's coefficient c(θ) of J_l⁻ᵀ is its Bernoulli series (the kernel's series and
//!   ranges, [`crate::element_block`]); a series f(t) of a dual t is applied by the chain
//!   rule, f(t₀) + f′(t₀) δt, both by Horner in f64;
//! * products by constants are products by f64, not by constant duals.
//!
//! Configurations outside the series' ranges (relative end rotations beyond ≈ 0.75 rad, a
//! chord antiparallel to the mean frame's axis, non-finite input) return `None`, and the
//! caller differentiates the reference instead. The tangent equals the reference's to
//! rounding (a test checks this on random elements).
//!
//! Plain `+ − × ÷ √` only (no fused multiply–add), so the copy compiled for AVX2
//! ([`kernel_tangent_rows`]) gives the same bits as the portable one.

use crate::autodiff::{Dual, Quat, Scalar, V3};
use crate::element::{BeamElement, ElementEnds};
use crate::element_block::{Kernel, ATAN_OVER_Y, JACOBIAN_C, JACOBIAN_T2_MAX, LOG_Y2_MAX};
use glam::{DQuat, DVec3};

/// Dual components: δx_b (0..3), δθ_a (3..6), δθ_b (6..9), as in [`crate::tangent`].
pub(crate) const N: usize = 9;
pub(crate) type D9 = Dual<N>;

/// The loads of one element as duals: force on a, moment on a, force on b, moment on b;
/// and the axial force N.
pub(crate) type LoadRows = ([V3<D9>; 4], f64);

/// f(x) for the dual `x`, given f and f′ at its value (the chain rule).
#[inline(always)]
fn apply(x: D9, f: f64, df: f64) -> D9 {
    let mut eps = x.eps;
    for e in &mut eps {
        *e *= df;
    }
    Dual { re: f, eps }
}

/// Σ cₖ tᵏ for the dual `t`: value and derivative by Horner.
#[inline(always)]
fn series(t: D9, coeffs: &[f64]) -> D9 {
    let n = coeffs.len();
    let (mut p, mut dp) = (coeffs[n - 1], 0.0);
    for &c in coeffs[..n - 1].iter().rev() {
        dp = dp * t.re + p;
        p = p * t.re + c;
    }
    apply(t, p, dp)
}

/// 1/√t for the dual `t`.
#[inline(always)]
fn inv_sqrt(t: D9) -> D9 {
    let s = 1.0 / t.re.sqrt();
    apply(t, s, -0.5 * s / t.re)
}

#[inline(always)]
fn scale_q(q: Quat<D9>, s: D9) -> Quat<D9> {
    Quat {
        x: q.x * s,
        y: q.y * s,
        z: q.z * s,
        w: q.w * s,
    }
}

/// A constant vector whose component k has derivative `factor` in dual component
/// `first + k`.
#[inline(always)]
fn seeded_vector(value: DVec3, first: usize, factor: f64) -> V3<D9> {
    let mut out: V3<D9> = V3::cst(value);
    out.x.eps[first] = factor;
    out.y.eps[first + 1] = factor;
    out.z.eps[first + 2] = factor;
    out
}

/// r = exp(δθ) r₀ seeded on δθ (dual components `first..first + 3`):
/// ∂r/∂δθₖ = ½ (w₀ eₖ + eₖ × v₀, −v₀ₖ).
#[inline(always)]
fn seeded_frame(r: DQuat, first: usize) -> Quat<D9> {
    let mut out: Quat<D9> = Quat::cst(r);
    let v = DVec3::new(r.x, r.y, r.z);
    for k in 0..3 {
        let e = DVec3::AXES[k];
        let dv = (e * r.w + e.cross(v)) * 0.5;
        out.x.eps[first + k] = dv.x;
        out.y.eps[first + k] = dv.y;
        out.z.eps[first + k] = dv.z;
        out.w.eps[first + k] = -0.5 * v[k];
    }
    out
}

/// Rows of the rotation matrix of the unit quaternion `q`.
#[inline(always)]
fn rotation_matrix(q: Quat<D9>) -> [V3<D9>; 3] {
    let (x2, y2, z2) = (q.x * 2.0, q.y * 2.0, q.z * 2.0);
    let (xx, yy, zz) = (q.x * x2, q.y * y2, q.z * z2);
    let (xy, xz, yz) = (q.x * y2, q.x * z2, q.y * z2);
    let (wx, wy, wz) = (q.w * x2, q.w * y2, q.w * z2);
    let one = D9::cst(1.0);
    [
        V3::new(one - (yy + zz), xy - wz, xz + wy),
        V3::new(xy + wz, one - (xx + zz), yz - wx),
        V3::new(xz - wy, yz + wx, one - (xx + yy)),
    ]
}

#[inline(always)]
fn times(m: &[V3<D9>; 3], v: V3<D9>) -> V3<D9> {
    V3::new(m[0].dot(v), m[1].dot(v), m[2].dot(v))
}

#[inline(always)]
fn transpose_times(m: &[V3<D9>; 3], v: V3<D9>) -> V3<D9> {
    m[0].scale(v.x) + m[1].scale(v.y) + m[2].scale(v.z)
}

/// Rotation vector of a unit quaternion (the shorter of ±q) by the half-angle series, or
/// `None` beyond its range.
#[inline(always)]
fn log_map(q: Quat<D9>) -> Option<V3<D9>> {
    let q = if q.w.re < 0.0 { q.negate() } else { q };
    let w1 = q.w.re + 1.0;
    let r = apply(q.w, 1.0 / w1, -1.0 / (w1 * w1));
    let v = q.vector();
    let y2 = v.dot(v) * (r * r);
    if !(y2.re <= LOG_Y2_MAX) {
        return None;
    }
    Some(v.scale(series(y2, &ATAN_OVER_Y) * (r * 4.0)))
}

/// J_l(θ)⁻ᵀ M = M + ½ θ × M + c(θ) θ × (θ × M) by the series of c, or `None` beyond
/// its range.
#[inline(always)]
fn jacobian_inverse_transpose_times(theta: V3<D9>, moment: V3<D9>) -> Option<V3<D9>> {
    let t2 = theta.dot(theta);
    if !(t2.re <= JACOBIAN_T2_MAX) {
        return None;
    }
    let c = series(t2, &JACOBIAN_C);
    let txm = theta.cross(moment);
    Some(moment + txm.scale_f(0.5) + theta.cross(txm).scale(c))
}

/// The element's loads as duals on the increments, by the kernel's algebra (eq. of
/// [`crate::element`]), or `None` outside the kernel's series.
#[inline(always)]
fn rows(e: &BeamElement, ends: &ElementEnds, beta: f64, rate: f64) -> Option<LoadRows> {
    let l0 = e.rest_length;
    // chord and end frames
    let chord = seeded_vector(ends.x[1] - ends.x[0], 0, 1.0);
    let length = chord.dot(chord).sqrt();
    let inv_length = D9::cst(1.0) / length;
    let e1 = chord.scale(inv_length);
    let ra0 = ends.q[0] * e.rest_offset_a;
    let rb0 = ends.q[1] * e.rest_offset_b;
    let ra = seeded_frame(ra0, 3);
    let rb = seeded_frame(rb0, 6);
    let rb = if ra0.dot(rb0) < 0.0 { rb.negate() } else { rb };
    // element frame: the mean of the end frames, turned onto the chord (Crisfield 1990)
    let sum = ra.add(rb);
    let mean = scale_q(sum, inv_sqrt(sum.dot(sum)));
    let (y2, z2) = (mean.y * 2.0, mean.z * 2.0);
    let x_axis = V3::new(
        D9::cst(1.0) - (mean.y * y2 + mean.z * z2),
        mean.x * y2 + mean.w * z2,
        mean.x * z2 - mean.w * y2,
    );
    let w_turn = x_axis.dot(e1) + 1.0;
    if !(w_turn.re >= 1e-12 && length.re <= f64::MAX) {
        return None;
    }
    let turn = Quat::from_parts(x_axis.cross(e1), w_turn);
    let turn = scale_q(turn, inv_sqrt(turn.dot(turn)));
    let frame = turn * mean;
    let frame = scale_q(frame, inv_sqrt(frame.dot(frame)));
    let inv = frame.conjugate();
    let theta_a = log_map(inv * ra)?;
    let theta_b = log_map(inv * rb)?;
    let rot = rotation_matrix(frame);

    // strain (chord and shallow arch) and the deformation rates
    let plane = |a: D9, b: D9| (a * a * 2.0 - a * b + b * b * 2.0) * (1.0 / 30.0);
    let arch = plane(theta_a.y, theta_b.y) + plane(theta_a.z, theta_b.z);
    let strain = (length - l0) * (1.0 / l0) + arch;
    let dv = seeded_vector(ends.v[1] - ends.v[0], 0, rate);
    let (wa, wb) = (
        seeded_vector(ends.w[0], 3, rate),
        seeded_vector(ends.w[1], 6, rate),
    );
    let strain_rate = e1.dot(dv) * (1.0 / l0);
    let spin = e1.cross(dv).scale(inv_length) + e1.scale(e1.dot(wa + wb) * 0.5);
    let rate_a = transpose_times(&rot, wa - spin);
    let rate_b = transpose_times(&rot, wb - spin);

    // local law
    let ea = if strain.re >= 0.0 {
        e.axial_stiffness_tension
    } else {
        e.axial_stiffness_compression
    };
    let elastic_axial = strain * ea;
    let axial = elastic_axial + strain_rate * (beta * ea);
    let ta = theta_a + rate_a.scale_f(beta);
    let tb = theta_b + rate_b.scale_f(beta);
    let torque = (tb.x - ta.x) * (e.torsion_stiffness / l0);
    let k_arch = elastic_axial * (l0 / 30.0);
    let (k1, k2) = (e.bending_stiffness[0] / l0, e.bending_stiffness[1] / l0);
    // (E I/l₀)(4 tₐ + 2 t_b) + (N l₀/30)(4 θₐ − θ_b), and a ↔ b
    let bend = |ta: D9, tb: D9, th_a: D9, th_b: D9, k: f64| {
        (ta * 4.0 + tb * 2.0) * k + (th_a * 4.0 - th_b) * k_arch
    };
    let ma_local = V3::new(
        -torque,
        bend(ta.y, tb.y, theta_a.y, theta_b.y, k1),
        bend(ta.z, tb.z, theta_a.z, theta_b.z, k2),
    );
    let mb_local = V3::new(
        torque,
        bend(tb.y, ta.y, theta_b.y, theta_a.y, k1),
        bend(tb.z, ta.z, theta_b.z, theta_a.z, k2),
    );

    // moments conjugate to spatial rotation increments, global axes; forces from them
    let ma = times(&rot, jacobian_inverse_transpose_times(theta_a, ma_local)?);
    let mb = times(&rot, jacobian_inverse_transpose_times(theta_b, mb_local)?);
    let sum = ma + mb;
    let twist = e1.scale(sum.dot(e1) * 0.5);
    let force_b = sum.cross(e1).scale(inv_length) - e1.scale(axial);
    Some(([-force_b, twist - ma, force_b, twist - mb], axial.re))
}

/// [`rows`] compiled for AVX2 + FMA (the same bits: no fused operations are used).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn rows_avx2(e: &BeamElement, ends: &ElementEnds, beta: f64, rate: f64) -> Option<LoadRows> {
    rows(e, ends, beta, rate)
}

/// [`rows`] as portable code.
#[inline(never)]
fn rows_portable(e: &BeamElement, ends: &ElementEnds, beta: f64, rate: f64) -> Option<LoadRows> {
    rows(e, ends, beta, rate)
}

/// The element's loads as duals on the 9 increments (velocities v = v₀ + c δx,
/// ω = ω₀ + c δθ with c = `rate`), by the kernel's algebra on the fastest kernel this
/// CPU runs; `None` outside the kernel's series (use the reference there).
pub(crate) fn kernel_tangent_rows(
    kernel: Kernel,
    e: &BeamElement,
    ends: &ElementEnds,
    beta: f64,
    rate: f64,
) -> Option<LoadRows> {
    match kernel {
        #[cfg(target_arch = "x86_64")]
        Kernel::Avx2Fma if Kernel::detect() == Kernel::Avx2Fma => {
            // SAFETY: the CPU has AVX2 and FMA (checked just above; the check is cached).
            unsafe { rows_avx2(e, ends, beta, rate) }
        }
        _ => rows_portable(e, ends, beta, rate),
    }
}
