//! The element tangent by the explicit kernel's algebra, four elements at a time.
//!
//! [`crate::rod::tangent`] differentiates the reference load function
//! [`BeamElement::loads_of`] (quaternion rotations, the log map by atan2 or its series,
//! generic dual arithmetic in which constants are duals too). This module differentiates,
//! in forward mode with the same 9 dual components (δx_b, δθ_a, δθ_b), the algebra of the
//! four-element kernel [`crate::rod::element_block`] — the same element law, reorganised but
//! not approximated:
//!
//! * the end frames' increments are seeded directly: for r = exp(δθ) q c (c the rest
//!   offset), ∂r/∂δθₖ = ½ (eₖ, 0) ⊗ r₀ = ½ (w₀ eₖ + eₖ × v₀, −v₀ₖ) for r₀ = (v₀, w₀),
//!   constant quaternions, instead of a dual quaternion product;
//! * the element frame's rotation matrix is formed once and rotates the four vectors;
//! * the log map is θ = 4 atan(y)/y · v/(1 + w), y² = |v|²/(1 + w)², and the tangent
//!   operator's coefficient c(θ) of J_l⁻ᵀ is its Bernoulli series (the kernel's series and
//!   ranges, [`crate::rod::element_block`]); a series f(t) of a dual t is applied by the chain
//!   rule, f(t₀) + f′(t₀) δt, both by Horner in f64;
//! * products by constants are products by f64, not by constant duals;
//! * four elements are differentiated at once, one per lane of
//!   [`LaneDual`] (dual numbers whose parts are four-lane [`F4`]s), so that each dual
//!   operation is a few 256-bit instructions for four elements.
//!
//! Lanes outside the series' ranges (relative end rotations beyond ≈ 0.75 rad, a chord
//! antiparallel to the mean frame's axis, non-finite input) are flagged, and the caller
//! differentiates the reference for them instead. The tangent equals the reference's to
//! rounding (a test checks this on random elements).
//!
//! Plain `+ − × ÷ √` only (no fused multiply–add), so the copy compiled for AVX2
//! (`block_tangent_rows`) gives the same bits as the portable one.

use crate::autodiff::{Dual, LaneDual, Quat, Scalar, V3};
use crate::rod::element::{BeamElement, ElementEnds};
use crate::rod::element_block::{Kernel, ATAN_OVER_Y, JACOBIAN_C, JACOBIAN_T2_MAX, LOG_Y2_MAX};
use crate::rod::lane_arith::Lane4;
use crate::rod::lanes::{F4, M4};
use glam::{DMat3, DQuat, DVec3};

/// Dual components: δx_b (0..3), δθ_a (3..6), δθ_b (6..9), as in [`crate::rod::tangent`].
pub(crate) const N: usize = 9;
pub(crate) type D9 = Dual<N>;
type L<F> = LaneDual<N, F>;

/// The loads of one element as duals: force on a, moment on a, force on b, moment on b;
/// and the axial force N.
pub(crate) type LoadRows = ([V3<D9>; 4], f64);

/// The loads of four elements as lane duals (rows as in [`LoadRows`]), their axial
/// forces, and the lanes outside the kernel's series.
pub(crate) struct BlockRows {
    pub rows: [V3<L<F4>>; 4],
    pub axial: F4,
    pub outside: M4,
}

/// Σ cₖ tᵏ for the lane duals `t`: value and derivative by Horner.
#[inline(always)]
fn series<F: Lane4>(t: L<F>, coeffs: &[f64]) -> L<F> {
    let n = coeffs.len();
    let (mut p, mut dp) = (F::splat(coeffs[n - 1]), F::splat(0.0));
    for &c in coeffs[..n - 1].iter().rev() {
        dp = dp * t.re + p;
        p = p * t.re + F::splat(c);
    }
    t.apply(p, dp)
}

/// 1/√t for the lane duals `t`.
#[inline(always)]
fn inv_sqrt<F: Lane4>(t: L<F>) -> L<F> {
    let s = F::splat(1.0) / t.re.sqrt();
    t.apply(s, s * F::splat(-0.5) / t.re)
}

#[inline(always)]
fn scale_q<F: Lane4>(q: Quat<L<F>>, s: L<F>) -> Quat<L<F>> {
    Quat {
        x: q.x * s,
        y: q.y * s,
        z: q.z * s,
        w: q.w * s,
    }
}

#[inline(always)]
fn select_q<F: Lane4>(m: M4, a: Quat<L<F>>, b: Quat<L<F>>) -> Quat<L<F>> {
    Quat {
        x: L::select(m, a.x, b.x),
        y: L::select(m, a.y, b.y),
        z: L::select(m, a.z, b.z),
        w: L::select(m, a.w, b.w),
    }
}

/// Four lane constants from a function of the lane index.
#[inline(always)]
fn f4(f: impl Fn(usize) -> f64) -> F4 {
    F4([f(0), f(1), f(2), f(3)])
}

/// Lane constants `value`, component i with derivative `factor` in dual component
/// `first + i`.
#[inline(always)]
fn seeded_vector<F: Lane4>(value: [DVec3; 4], first: usize, factor: f64) -> V3<L<F>> {
    let mut out = V3::new(
        L::lanes(c4(|k| value[k].x)),
        L::lanes(c4(|k| value[k].y)),
        L::lanes(c4(|k| value[k].z)),
    );
    out.x.eps[first] = F::splat(factor);
    out.y.eps[first + 1] = F::splat(factor);
    out.z.eps[first + 2] = F::splat(factor);
    out
}

/// r = exp(δθ) r₀ seeded on δθ (dual components `first..first + 3`), lane by lane:
/// ∂r/∂δθᵢ = ½ (w₀ eᵢ + eᵢ × v₀, −v₀ᵢ).
#[inline(always)]
fn seeded_frame<F: Lane4>(r: [DQuat; 4], first: usize) -> Quat<L<F>> {
    let mut out = Quat {
        x: L::lanes(c4(|k| r[k].x)),
        y: L::lanes(c4(|k| r[k].y)),
        z: L::lanes(c4(|k| r[k].z)),
        w: L::lanes(c4(|k| r[k].w)),
    };
    for i in 0..3 {
        let e = DVec3::AXES[i];
        let mut dv = [DVec3::ZERO; 4];
        for (d, r) in dv.iter_mut().zip(&r) {
            *d = (e * r.w + e.cross(DVec3::new(r.x, r.y, r.z))) * 0.5;
        }
        out.x.eps[first + i] = c4(|k| dv[k].x);
        out.y.eps[first + i] = c4(|k| dv[k].y);
        out.z.eps[first + i] = c4(|k| dv[k].z);
        out.w.eps[first + i] = c4(|k| -0.5 * r[k].to_array()[i]);
    }
    out
}

/// Lane constants from a function of the lane index.
#[inline(always)]
fn c4<F: Lane4>(f: impl Fn(usize) -> f64) -> F {
    F::from_f4(f4(f))
}

/// The shallow arch's strain of one bending plane, (2a² − ab + 2b²)/30.
#[inline(always)]
fn plane<F: Lane4>(a: L<F>, b: L<F>) -> L<F> {
    (a * a * 2.0 - a * b + b * b * 2.0) * (1.0 / 30.0)
}

/// An end moment of one bending plane: (E I/l₀)(4 tₐ + 2 t_b) + (N l₀/30)(4 θₐ − θ_b).
#[inline(always)]
fn bend<F: Lane4>(ta: L<F>, tb: L<F>, th_a: L<F>, th_b: L<F>, k: F, k_arch: L<F>) -> L<F> {
    (ta * 4.0 + tb * 2.0).mul4(k) + (th_a * 4.0 - th_b) * k_arch
}

/// End `end`'s axes A of the four elements, by columns, as lane constants (the identity
/// for straight elements, [`crate::rod::element::EndAxes`]).
#[inline(always)]
fn end_axes<F: Lane4>(e: [&BeamElement; 4], end: usize) -> [[F; 3]; 3] {
    let m = e.map(|e| {
        e.end_axes
            .as_ref()
            .map_or(DMat3::IDENTITY, |axes| axes.0[end])
    });
    [0, 1, 2].map(|c| [0, 1, 2].map(|i| c4::<F>(|k| m[k].col(c)[i])))
}

/// Aᵀ v for lane-constant columns `a`.
#[inline(always)]
fn read_axes<F: Lane4>(a: &[[F; 3]; 3], v: V3<L<F>>) -> V3<L<F>> {
    V3::new(
        column_dot(&a[0], v),
        column_dot(&a[1], v),
        column_dot(&a[2], v),
    )
}

/// c · v for a lane-constant column `c`.
#[inline(always)]
fn column_dot<F: Lane4>(c: &[F; 3], v: V3<L<F>>) -> L<F> {
    v.x.mul4(c[0]) + v.y.mul4(c[1]) + v.z.mul4(c[2])
}

/// c s for a lane-constant column `c`.
#[inline(always)]
fn column_times<F: Lane4>(c: &[F; 3], s: L<F>) -> V3<L<F>> {
    V3::new(s.mul4(c[0]), s.mul4(c[1]), s.mul4(c[2]))
}

/// A v for lane-constant columns `a`.
#[inline(always)]
fn back_axes<F: Lane4>(a: &[[F; 3]; 3], v: V3<L<F>>) -> V3<L<F>> {
    column_times(&a[0], v.x) + column_times(&a[1], v.y) + column_times(&a[2], v.z)
}

#[inline(always)]
fn select_v<F: Lane4>(m: M4, a: V3<L<F>>, b: V3<L<F>>) -> V3<L<F>> {
    V3::new(
        L::select(m, a.x, b.x),
        L::select(m, a.y, b.y),
        L::select(m, a.z, b.z),
    )
}

/// The linear law's end moment at end a for end rotations `ta`, `tb` (their ends' axes):
/// (−torque, (EI₁/l)(4 tₐ + 2 t_b), (EI₂/l)(4 tₐ + 2 t_b)); `k` = EI₁/l, EI₂/l.
#[inline(always)]
fn linear_moment<F: Lane4>(ta: V3<L<F>>, tb: V3<L<F>>, torque: L<F>, k: [F; 2]) -> V3<L<F>> {
    V3::new(
        torque,
        (ta.y * 4.0 + tb.y * 2.0).mul4(k[0]),
        (ta.z * 4.0 + tb.z * 2.0).mul4(k[1]),
    )
}

/// The shallow arch's end moment at end a for the slopes `sa`, `sb`: (N l₀/30)(4 θₐ − θ_b).
#[inline(always)]
fn arch_moment<F: Lane4>(sa: V3<L<F>>, sb: V3<L<F>>, k_arch: L<F>) -> V3<L<F>> {
    V3::new(
        L::cst(0.0),
        (sa.y * 4.0 - sb.y) * k_arch,
        (sa.z * 4.0 - sb.z) * k_arch,
    )
}

/// The local end moments (element frame axes) of elements curved at rest: the linear law
/// on the end rotations `t` read in the ends' `axes` (Aₖᵀ θₖ), its moments turned back
/// (Aₖ Mₖ), plus the shallow arch's moments of the `slopes` against the chord; `k` holds
/// EI₁/l, EI₂/l, GJ/l (as the kernel, [`crate::rod::element_block`]).
#[inline(always)]
fn curved_local_moments<F: Lane4>(
    axes: &[[[F; 3]; 3]; 2],
    t: [V3<L<F>>; 2],
    slopes: [V3<L<F>>; 2],
    k: [F; 3],
    k_arch: L<F>,
) -> (V3<L<F>>, V3<L<F>>) {
    let ta = read_axes(&axes[0], t[0]);
    let tb = read_axes(&axes[1], t[1]);
    let torque = (tb.x - ta.x).mul4(k[2]);
    let kb = [k[0], k[1]];
    let [sa, sb] = slopes;
    (
        back_axes(&axes[0], linear_moment(ta, tb, -torque, kb)) + arch_moment(sa, sb, k_arch),
        back_axes(&axes[1], linear_moment(tb, ta, torque, kb)) + arch_moment(sb, sa, k_arch),
    )
}

#[inline(always)]
fn portable_dual<F: Lane4>(d: L<F>) -> L<F4> {
    let mut eps = [F4::ZERO; N];
    for (o, e) in eps.iter_mut().zip(d.eps) {
        *o = e.to_f4();
    }
    LaneDual {
        re: d.re.to_f4(),
        eps,
    }
}

/// Lane duals as portable lanes.
#[inline(always)]
fn portable<F: Lane4>(v: V3<L<F>>) -> V3<L<F4>> {
    V3::new(portable_dual(v.x), portable_dual(v.y), portable_dual(v.z))
}

/// Rows of the rotation matrix of the unit quaternion `q`.
#[inline(always)]
fn rotation_matrix<F: Lane4>(q: Quat<L<F>>) -> [V3<L<F>>; 3] {
    let (x2, y2, z2) = (q.x * 2.0, q.y * 2.0, q.z * 2.0);
    let (xx, yy, zz) = (q.x * x2, q.y * y2, q.z * z2);
    let (xy, xz, yz) = (q.x * y2, q.x * z2, q.y * z2);
    let (wx, wy, wz) = (q.w * x2, q.w * y2, q.w * z2);
    let one = L::cst(1.0);
    [
        V3::new(one - (yy + zz), xy - wz, xz + wy),
        V3::new(xy + wz, one - (xx + zz), yz - wx),
        V3::new(xz - wy, yz + wx, one - (xx + yy)),
    ]
}

#[inline(always)]
fn times<F: Lane4>(m: &[V3<L<F>>; 3], v: V3<L<F>>) -> V3<L<F>> {
    V3::new(m[0].dot(v), m[1].dot(v), m[2].dot(v))
}

#[inline(always)]
fn transpose_times<F: Lane4>(m: &[V3<L<F>>; 3], v: V3<L<F>>) -> V3<L<F>> {
    m[0].scale(v.x) + m[1].scale(v.y) + m[2].scale(v.z)
}

/// Rotation vector of unit quaternions (the shorter of ±q) by the half-angle series,
/// and the lanes within its range.
#[inline(always)]
fn log_map<F: Lane4>(q: Quat<L<F>>) -> (V3<L<F>>, M4) {
    let q = select_q(q.w.re.to_f4().lt(F4::ZERO), q.negate(), q);
    let w1 = q.w.re + F::splat(1.0);
    let r = F::splat(1.0) / w1;
    let r = q.w.apply(r, -(r * r));
    let v = q.vector();
    let y2 = v.dot(v) * (r * r);
    let ok = y2.re.to_f4().le(F4::splat(LOG_Y2_MAX));
    (v.scale(series(y2, &ATAN_OVER_Y) * (r * 4.0)), ok)
}

/// J_l(θ)⁻ᵀ M = M + ½ θ × M + c(θ) θ × (θ × M) by the series of c, and the lanes within
/// its range.
#[inline(always)]
fn jacobian_inverse_transpose_times<F: Lane4>(theta: V3<L<F>>, moment: V3<L<F>>) -> (V3<L<F>>, M4) {
    let t2 = theta.dot(theta);
    let ok = t2.re.to_f4().le(F4::splat(JACOBIAN_T2_MAX));
    let c = series(t2, &JACOBIAN_C);
    let txm = theta.cross(moment);
    (moment + txm.scale_f(0.5) + theta.cross(txm).scale(c), ok)
}

/// The loads of four elements as lane duals on their increments, by the kernel's algebra
/// (the element law of [`crate::rod::element`]).
#[inline(always)]
fn rows<F: Lane4>(
    e: [&BeamElement; 4],
    ends: [&ElementEnds; 4],
    beta: f64,
    rate: f64,
) -> BlockRows {
    let l0: F = c4(|k| e[k].rest_length);
    let inv_l0 = F::splat(1.0) / l0;
    // chord and end frames
    let mut chord0 = [DVec3::ZERO; 4];
    let (mut dv0, mut wa0, mut wb0) = (chord0, chord0, chord0);
    let (mut ra0, mut rb0) = ([DQuat::IDENTITY; 4], [DQuat::IDENTITY; 4]);
    for k in 0..4 {
        let n = ends[k];
        chord0[k] = n.x[1] - n.x[0];
        dv0[k] = n.v[1] - n.v[0];
        (wa0[k], wb0[k]) = (n.w[0], n.w[1]);
        ra0[k] = n.q[0] * e[k].rest_offset_a;
        rb0[k] = n.q[1] * e[k].rest_offset_b;
    }
    let chord = seeded_vector::<F>(chord0, 0, 1.0);
    let length = chord.dot(chord).sqrt();
    let inv_length = L::<F>::cst(1.0) / length;
    let e1 = chord.scale(inv_length);
    let ra = seeded_frame::<F>(ra0, 3);
    let rb = seeded_frame::<F>(rb0, 6);
    let flip = ra.dot(rb).re.to_f4().lt(F4::ZERO);
    let rb = select_q(flip, rb.negate(), rb);
    // element frame: the mean of the end frames, turned onto the chord (Crisfield 1990)
    let sum = ra + rb;
    let mean = scale_q(sum, inv_sqrt(sum.dot(sum)));
    let (y2, z2) = (mean.y * 2.0, mean.z * 2.0);
    let x_axis = V3::new(
        L::cst(1.0) - (mean.y * y2 + mean.z * z2),
        mean.x * y2 + mean.w * z2,
        mean.x * z2 - mean.w * y2,
    );
    let w_turn = x_axis.dot(e1) + 1.0;
    let not_antiparallel = F4::splat(1e-12).le(w_turn.re.to_f4());
    let turn = Quat::from_parts(x_axis.cross(e1), w_turn);
    let turn = scale_q(turn, inv_sqrt(turn.dot(turn)));
    let frame = turn * mean;
    let frame = scale_q(frame, inv_sqrt(frame.dot(frame)));
    let inv = frame.conjugate();
    let (theta_a, ok_a) = log_map(inv * ra);
    let (theta_b, ok_b) = log_map(inv * rb);
    let rot = rotation_matrix(frame);

    // strain (chord and shallow arch) and the deformation rates
    // the slopes against the chord: from the rest shape, plus its own
    let slope = |i: usize| c4::<F>(|k| e[k].rest_slopes[i]);
    let (slope_a, slope_b) = (
        V3::new(
            theta_a.x,
            theta_a.y.add4(slope(0)),
            theta_a.z.add4(slope(1)),
        ),
        V3::new(
            theta_b.x,
            theta_b.y.add4(slope(2)),
            theta_b.z.add4(slope(3)),
        ),
    );
    let arch = (plane(slope_a.y, slope_b.y) + plane(slope_a.z, slope_b.z))
        .add4(-c4::<F>(|k| e[k].rest_arch));
    let strain = (length.add4(-l0)).mul4(inv_l0) + arch;
    let dv = seeded_vector(dv0, 0, rate);
    let wa = seeded_vector(wa0, 3, rate);
    let wb = seeded_vector(wb0, 6, rate);
    let strain_rate = e1.dot(dv).mul4(inv_l0);
    let spin = e1.cross(dv).scale(inv_length) + e1.scale(e1.dot(wa + wb) * 0.5);
    let rate_a = transpose_times(&rot, wa - spin);
    let rate_b = transpose_times(&rot, wb - spin);

    // local law
    let tension = F4::ZERO.le(strain.re.to_f4());
    let ea = F::select(
        tension,
        c4(|k| e[k].axial_stiffness_tension),
        c4(|k| e[k].axial_stiffness_compression),
    );
    let elastic_axial = strain.mul4(ea);
    let axial = elastic_axial + strain_rate.mul4(ea * F::splat(beta));
    let ta = theta_a + rate_a.scale_f(beta);
    let tb = theta_b + rate_b.scale_f(beta);
    // the bending and twist law acts over the rest axis's length
    let inv_axis = F::splat(1.0) / c4::<F>(|k| e[k].axis_length);
    let kt = c4::<F>(|k| e[k].torsion_stiffness) * inv_axis;
    let torque = (tb.x - ta.x).mul4(kt);
    let k_arch = elastic_axial.mul4(l0 * F::splat(1.0 / 30.0));
    let k1 = c4::<F>(|k| e[k].bending_stiffness[0]) * inv_axis;
    let k2 = c4::<F>(|k| e[k].bending_stiffness[1]) * inv_axis;
    // (E I/l₀)(4 tₐ + 2 t_b) + (N l₀/30)(4 θₐ − θ_b), and a ↔ b
    let curved_count = e.iter().filter(|e| e.end_axes.is_some()).count();
    let (ma_local, mb_local) = if curved_count == 4 {
        curved_local_moments(
            &[end_axes::<F>(e, 0), end_axes::<F>(e, 1)],
            [ta, tb],
            [slope_a, slope_b],
            [k1, k2, kt],
            k_arch,
        )
    } else {
        let ma = V3::new(
            -torque,
            bend(ta.y, tb.y, slope_a.y, slope_b.y, k1, k_arch),
            bend(ta.z, tb.z, slope_a.z, slope_b.z, k2, k_arch),
        );
        let mb = V3::new(
            torque,
            bend(tb.y, ta.y, slope_b.y, slope_a.y, k1, k_arch),
            bend(tb.z, ta.z, slope_b.z, slope_a.z, k2, k_arch),
        );
        if curved_count > 0 {
            let (ca, cb) = curved_local_moments(
                &[end_axes::<F>(e, 0), end_axes::<F>(e, 1)],
                [ta, tb],
                [slope_a, slope_b],
                [k1, k2, kt],
                k_arch,
            );
            let curved = M4([0, 1, 2, 3].map(|k| if e[k].end_axes.is_some() { !0 } else { 0 }));
            (select_v(curved, ca, ma), select_v(curved, cb, mb))
        } else {
            (ma, mb)
        }
    };

    // moments conjugate to spatial rotation increments, global axes; forces from them
    let (ma, okj_a) = jacobian_inverse_transpose_times(theta_a, ma_local);
    let (mb, okj_b) = jacobian_inverse_transpose_times(theta_b, mb_local);
    let (ma, mb) = (times(&rot, ma), times(&rot, mb));
    let sum = ma + mb;
    let twist = e1.scale(sum.dot(e1) * 0.5);
    let force_b = sum.cross(e1).scale(inv_length) - e1.scale(axial);
    let inside = ok_a
        .and(ok_b)
        .and(okj_a)
        .and(okj_b)
        .and(not_antiparallel)
        .and(length.re.to_f4().le(F4::splat(f64::MAX)));
    BlockRows {
        rows: [
            portable(-force_b),
            portable(twist - ma),
            portable(force_b),
            portable(twist - mb),
        ],
        axial: axial.re.to_f4(),
        outside: !inside,
    }
}

/// [`rows`] compiled for AVX2 + FMA (the same bits: no fused operations are used).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn rows_avx2(
    e: [&BeamElement; 4],
    ends: [&ElementEnds; 4],
    beta: f64,
    rate: f64,
) -> BlockRows {
    rows::<crate::rod::lane_arith::Avx4>(e, ends, beta, rate)
}

/// [`rows`] as portable code.
#[inline(never)]
fn rows_portable(e: [&BeamElement; 4], ends: [&ElementEnds; 4], beta: f64, rate: f64) -> BlockRows {
    rows::<F4>(e, ends, beta, rate)
}

/// The loads of four elements as duals on their 9 increments each (velocities
/// v = v₀ + c δx, ω = ω₀ + c δθ with c = `rate`), by the kernel's algebra on `kernel`;
/// [`BlockRows::outside`] flags the lanes to be differentiated by the reference instead.
pub(crate) fn block_tangent_rows(
    kernel: Kernel,
    e: [&BeamElement; 4],
    ends: [&ElementEnds; 4],
    beta: f64,
    rate: f64,
) -> BlockRows {
    match kernel {
        #[cfg(target_arch = "x86_64")]
        Kernel::Avx2Fma if Kernel::detect() == Kernel::Avx2Fma => {
            // SAFETY: the CPU has AVX2 and FMA (checked just above; the check is cached).
            unsafe { rows_avx2(e, ends, beta, rate) }
        }
        _ => rows_portable(e, ends, beta, rate),
    }
}
