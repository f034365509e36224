//! The consistent tangent stiffness of one element, by forward-mode automatic
//! differentiation of the element's own load function ([`BeamElement::loads_of`]):
//! the 12 inputs are the increments u = (δx_a, δθ_a, δx_b, δθ_b) — translations and
//! spatial (left) rotation increments, q ← exp(δθ) q — and the result is
//! K = −∂(f_a, m_a, f_b, m_b)/∂u at u = 0. Because it differentiates exactly the loads the
//! explicit solver applies, including the co-rotational frame, the J_l⁻ᵀ moment map and
//! the bimodular axial law, Newton iterations converge quadratically and all solvers
//! share one equilibrium.
//!
//! With `rate_factor` c ≠ 0 the velocities depend on the increments as v = v₀ + c δx,
//! ω = ω₀ + c δθ (c = γ/(β Δt) in Newmark's scheme), so the stiffness-proportional
//! damping's tangent is included too.
//!
//! The loads depend on the end positions and velocities only through x_b − x_a and
//! v_b − v_a (a rigid translation changes nothing), so ∂/∂x_a = −∂/∂x_b: only 9 of the 12
//! increments are carried as dual components (δx_b, δθ_a, δθ_b), a quarter less work in
//! every dual operation.
//!
//! The solvers' tangent ([`element_tangent`], [`block_tangent`]) differentiates the same
//! loads in the algebra of the explicit kernel, four elements at a time
//! ([`crate::rod::tangent_kernel`]); elements whose relative rotations lie beyond that
//! kernel's series use the reference differentiation here ([`reference_tangent`]). The
//! two agree to rounding (≤ 1e-10 of the largest entry of a kind; a test checks this on
//! random elements).

use crate::autodiff::{Quat, Scalar, V3};
use crate::rod::element::{BeamElement, ElementEnds, ElementLoads, ElementLoadsOf};
use crate::rod::element_block::Kernel;
use crate::rod::inelastic::{HistoryView, Inelastic, InelasticElements};
use crate::rod::tangent_kernel::{block_tangent_rows, BlockRows, LoadRows, D9};
use glam::{DQuat, DVec3};
use nalgebra::SMatrix;

/// 12 × 12 element tangent, rows/columns ordered (x_a, θ_a, x_b, θ_b).
pub type ElementTangent = SMatrix<f64, 12, 12>;

/// Dual component and sign of column `j` of the 12 × 12 tangent.
fn column_source(j: usize) -> (usize, f64) {
    match j {
        0..3 => (j, -1.0), // δx_a: minus δx_b (translation invariance)
        3..6 => (j, 1.0),
        6..9 => (j - 6, 1.0),
        _ => (j - 3, 1.0),
    }
}

/// The loads and K = −∂loads/∂u into `out`, from `value(block, c)` and
/// `derivative(block, c, source)`: component c of load block (f_a, m_a, f_b, m_b) and its
/// derivative by dual component `source`.
#[inline(always)]
fn fill(
    value: impl Fn(usize, usize) -> f64,
    derivative: impl Fn(usize, usize, usize) -> f64,
    axial_force: f64,
    out: &mut (ElementLoads, ElementTangent),
) {
    let (loads, k) = out;
    for block in 0..4 {
        for c in 0..3 {
            for j in 0..12 {
                let (source, sign) = column_source(j);
                k[(3 * block + c, j)] = -sign * derivative(block, c, source);
            }
        }
    }
    let vector = |block: usize| DVec3::from_array([0, 1, 2].map(|c| value(block, c)));
    *loads = ElementLoads {
        force: [vector(0), vector(2)],
        moment: [vector(1), vector(3)],
        axial_force,
    };
}

/// [`fill`] from the loads as duals on the 9 increments.
fn from_rows((rows, axial_force): &LoadRows, out: &mut (ElementLoads, ElementTangent)) {
    let comp = |block: usize, c: usize| [rows[block].x, rows[block].y, rows[block].z][c];
    fill(
        |b, c| comp(b, c).re,
        |b, c, s| comp(b, c).eps[s],
        *axial_force,
        out,
    );
}

/// [`fill`] from lane `lane` of the four elements' loads as lane duals.
fn from_lane(rows: &BlockRows, lane: usize, out: &mut (ElementLoads, ElementTangent)) {
    let comp = |b: usize, c: usize| {
        let v = &rows.rows[b];
        [&v.x, &v.y, &v.z][c]
    };
    fill(
        |b, c| comp(b, c).re.0[lane],
        |b, c, s| comp(b, c).eps[s].0[lane],
        rows.axial.0[lane],
        out,
    );
}

/// exp(δθ) q to first order in δθ: (½ δθ, 1) ⊗ q, exact in its derivative at δθ = 0.
fn seeded_rotation(q: DQuat, first: usize) -> Quat<D9> {
    let half = seeded_vector(DVec3::ZERO, first, 0.5);
    Quat::from_parts(half, D9::cst(1.0)) * Quat::cst(q)
}

fn seeded_vector(value: DVec3, first: usize, factor: f64) -> V3<D9> {
    let comp = |k: usize, re: f64| {
        let mut d = D9::cst(re);
        d.eps[first + k] = factor;
        d
    };
    V3::new(comp(0, value.x), comp(1, value.y), comp(2, value.z))
}

/// The reference loads as duals: [`BeamElement::loads_of`] on seeded increments.
fn reference_rows(
    element: &BeamElement,
    ends: &ElementEnds,
    beta: f64,
    rate_factor: f64,
) -> LoadRows {
    seeded_rows(ends, rate_factor, |(x, q, v, w)| {
        element.loads_of(x, q, v, w, beta)
    })
}

/// Poses and velocities of an element's ends as duals.
type SeededEnds = ([V3<D9>; 2], [Quat<D9>; 2], [V3<D9>; 2], [V3<D9>; 2]);

/// The loads `loads` gives at `ends` as duals on the seeded increments.
fn seeded_rows(
    ends: &ElementEnds,
    rate_factor: f64,
    loads: impl FnOnce(SeededEnds) -> ElementLoadsOf<D9>,
) -> LoadRows {
    let x = [V3::cst(ends.x[0]), seeded_vector(ends.x[1], 0, 1.0)];
    let q = [seeded_rotation(ends.q[0], 3), seeded_rotation(ends.q[1], 6)];
    let v = [V3::cst(ends.v[0]), seeded_vector(ends.v[1], 0, rate_factor)];
    let w = [
        seeded_vector(ends.w[0], 3, rate_factor),
        seeded_vector(ends.w[1], 6, rate_factor),
    ];
    let l = loads((x, q, v, w));
    (
        [l.force[0], l.moment[0], l.force[1], l.moment[1]],
        l.axial_force,
    )
}

/// The loads of four elements at `ends` and their tangents K = −∂loads/∂u: by the
/// kernel's algebra four at a time ([`crate::rod::tangent_kernel`]), by the reference for
/// elements whose relative rotations its series do not cover. Fewer than four elements
/// repeat the last one in the lanes beyond `count`; `out` receives `count` results.
pub fn block_tangent(
    elements: [&BeamElement; 4],
    ends: [&ElementEnds; 4],
    count: usize,
    beta: f64,
    rate_factor: f64,
    out: &mut [(ElementLoads, ElementTangent); 4],
) {
    let rows = block_tangent_rows(Kernel::detect(), elements, ends, beta, rate_factor);
    for (k, out) in out.iter_mut().enumerate().take(count) {
        if rows.outside.lane(k) {
            from_rows(
                &reference_rows(elements[k], ends[k], beta, rate_factor),
                out,
            );
        } else {
            from_lane(&rows, k, out);
        }
    }
}

/// The element's loads at `ends` and their tangent K = −∂loads/∂u ([`block_tangent`]
/// for one element).
pub fn element_tangent(
    element: &BeamElement,
    ends: &ElementEnds,
    beta: f64,
    rate_factor: f64,
) -> (ElementLoads, ElementTangent) {
    let mut out = [(ElementLoads::default(), ElementTangent::zeros()); 4];
    block_tangent([element; 4], [ends; 4], 1, beta, rate_factor, &mut out);
    out[0]
}

/// The loads of inelastic `element` (law `inelastic`, committed history `history`) and
/// their tangent K = −∂loads/∂u: the consistent algorithmic tangent of its law, by
/// differentiating [`InelasticElements::loads_of`].
pub fn inelastic_tangent(
    hinges: &InelasticElements,
    (element, hinge): (&BeamElement, &Inelastic),
    history: HistoryView,
    ends: &ElementEnds,
    beta: f64,
    rate_factor: f64,
) -> (ElementLoads, ElementTangent) {
    let rows = seeded_rows(ends, rate_factor, |seeded| {
        hinges.loads_of(element, hinge, history, seeded, beta)
    });
    let mut out = (ElementLoads::default(), ElementTangent::zeros());
    from_rows(&rows, &mut out);
    out
}

/// [`element_tangent`] by differentiating the reference [`BeamElement::loads_of`] only.
pub fn reference_tangent(
    element: &BeamElement,
    ends: &ElementEnds,
    beta: f64,
    rate_factor: f64,
) -> (ElementLoads, ElementTangent) {
    let mut out = (ElementLoads::default(), ElementTangent::zeros());
    from_rows(&reference_rows(element, ends, beta, rate_factor), &mut out);
    out
}

/// [`element_tangent`] by the kernel's algebra on `kernel`, `None` outside its series.
pub fn kernel_tangent(
    kernel: Kernel,
    element: &BeamElement,
    ends: &ElementEnds,
    beta: f64,
    rate_factor: f64,
) -> Option<(ElementLoads, ElementTangent)> {
    let rows = block_tangent_rows(kernel, [element; 4], [ends; 4], beta, rate_factor);
    (!rows.outside.lane(0)).then(|| {
        let mut out = (ElementLoads::default(), ElementTangent::zeros());
        from_lane(&rows, 0, &mut out);
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::exp_map;
    use crate::rod::element::rotate;
    use crate::{Material, Section};

    fn element() -> BeamElement {
        let mat = Material::isotropic(12e6, 0.49, 940.0);
        let sec = Section::new(0.01, 0.016);
        BeamElement::new(
            (0, 1),
            [DVec3::ZERO, DVec3::new(0.1, 0.0, 0.0)],
            [DQuat::IDENTITY; 2],
            &sec,
            &mat,
        )
    }

    fn perturbed(ends: &ElementEnds, j: usize, h: f64, rate: f64) -> ElementEnds {
        let mut e = *ends;
        let node = j / 6;
        let mut d = DVec3::ZERO;
        d[j % 3] = h;
        if j % 6 < 3 {
            e.x[node] += d;
            e.v[node] += rate * d;
        } else {
            e.q[node] = rotate(e.q[node], d);
            e.w[node] += rate * d;
        }
        e
    }

    fn flat(l: &ElementLoads) -> [f64; 12] {
        l.to_array()
    }

    /// The AD tangent equals central finite differences of the load function, for a
    /// large, generic deformation (bending, twist, stretch) with damping rates.
    #[test]
    fn tangent_matches_finite_differences() {
        let e = element();
        let ends = ElementEnds {
            x: [
                DVec3::new(0.001, -0.002, 0.0005),
                DVec3::new(0.097, 0.016, -0.009),
            ],
            q: [
                exp_map(DVec3::new(0.12, -0.25, 0.18)),
                exp_map(DVec3::new(-0.3, 0.27, -0.12)),
            ],
            v: [DVec3::new(0.1, -0.2, 0.3), DVec3::new(-0.4, 0.1, 0.0)],
            w: [DVec3::new(1.0, -0.5, 0.2), DVec3::new(0.3, 0.8, -1.1)],
        };
        let (beta, rate) = (2e-4, 150.0);
        let (loads, k) = element_tangent(&e, &ends, beta, rate);
        let plain = flat(&e.loads(&ends, beta));
        for (a, b) in flat(&loads).iter().zip(plain) {
            assert!((a - b).abs() < 1e-13 * (1.0 + b.abs()), "{a} vs {b}");
        }
        let h = 1e-7;
        let scale = k.abs().max();
        for j in 0..12 {
            let fp = flat(&e.loads(&perturbed(&ends, j, h, rate), beta));
            let fm = flat(&e.loads(&perturbed(&ends, j, -h, rate), beta));
            for i in 0..12 {
                let fd = -(fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (k[(i, j)] - fd).abs() < 1e-6 * scale,
                    "K[{i},{j}] = {} vs finite differences {fd}",
                    k[(i, j)]
                );
            }
        }
    }

    /// Node frames turned a quarter turn about the axis (a hose built with its section's
    /// y axis up) and bent about the global y axis: the tangent still matches.
    #[test]
    fn tangent_matches_finite_differences_for_turned_frames() {
        let quarter = DQuat::from_axis_angle(DVec3::X, std::f64::consts::FRAC_PI_2);
        let mat = Material::isotropic(12e6, 0.49, 940.0);
        let sec = Section::new(0.01, 0.016);
        let e = BeamElement::new(
            (0, 1),
            [DVec3::ZERO, DVec3::new(0.01, 0.0, 0.0)],
            [quarter; 2],
            &sec,
            &mat,
        );
        for bend in [0.0, 0.05, 0.3] {
            let ends = ElementEnds {
                x: [
                    DVec3::ZERO,
                    DVec3::new(0.01 * bend.cos(), 0.0, -0.01 * bend.sin()),
                ],
                q: [quarter, exp_map(DVec3::new(0.0, 2.0 * bend, 0.0)) * quarter],
                v: [DVec3::ZERO; 2],
                w: [DVec3::ZERO; 2],
            };
            let (_, k) = element_tangent(&e, &ends, 0.0, 0.0);
            let h = 1e-8;
            let scale = k.abs().max();
            for j in 0..12 {
                let fp = flat(&e.loads(&perturbed(&ends, j, h, 0.0), 0.0));
                let fm = flat(&e.loads(&perturbed(&ends, j, -h, 0.0), 0.0));
                for i in 0..12 {
                    let fd = -(fp[i] - fm[i]) / (2.0 * h);
                    assert!(
                        (k[(i, j)] - fd).abs() < 1e-5 * scale,
                        "bend {bend}: K[{i},{j}] = {} vs finite differences {fd}",
                        k[(i, j)]
                    );
                }
            }
        }
    }

    /// At rest the tangent is the linear beam stiffness: axial EA/l, bending 12EI/l³.
    #[test]
    fn rest_tangent_is_the_linear_stiffness() {
        let e = element();
        let ends = ElementEnds {
            x: [DVec3::ZERO, DVec3::new(0.1, 0.0, 0.0)],
            q: [DQuat::IDENTITY; 2],
            v: [DVec3::ZERO; 2],
            w: [DVec3::ZERO; 2],
        };
        let (_, k) = element_tangent(&e, &ends, 0.0, 0.0);
        let l = 0.1;
        let axial = e.axial_stiffness_tension / l;
        assert!((k[(6, 6)] - axial).abs() < 1e-9 * axial);
        let bend = 12.0 * e.bending_stiffness[1] / (l * l * l);
        assert!(
            (k[(7, 7)] - bend).abs() < 1e-9 * bend,
            "{} {bend}",
            k[(7, 7)]
        );
        let rot = 4.0 * e.bending_stiffness[1] / l;
        assert!((k[(5, 5)] - rot).abs() < 1e-9 * rot);
    }

    /// The kernel-algebra tangent ([`crate::rod::tangent_kernel`]) equals the reference tangent
    /// on random elements: within 1e-10 of the largest entry of the same kind (force or
    /// moment row, translation or rotation column), loads within 1e-12 of their scale.
    /// Large rigid rotations, relative rotations inside and beyond the kernel's series
    /// (beyond, `element_tangent` is the reference's, bit for bit), tension and
    /// compression of bimodular materials, damping with rate factors c ≠ 0, tubes and
    /// sections with unequal E I; the AVX2 and portable copies give the same bits.
    #[test]
    fn kernel_tangent_equals_the_reference() {
        use crate::rod::test_elements::{random_element, random_ends, Rng};
        let mut rng = Rng(27);
        let (mut inside, mut outside, mut tension, mut compression) = (0, 0, 0, 0);
        let mut worst: f64 = 0.0;
        for round in 0..6000 {
            let e = random_element(&mut rng, 0);
            let rest = (
                [DVec3::ZERO, DVec3::X * e.rest_length],
                [
                    e.rest_offset_a.inverse().normalize(),
                    e.rest_offset_b.inverse().normalize(),
                ],
            );
            let bend = [0.2, 0.7, 1.0, 2.5][round % 4];
            let ends = random_ends(&mut rng, &e, rest, bend);
            let (beta, rate) = if round % 3 == 0 {
                (0.0, 0.0)
            } else {
                (rng.range(0.0, 2e-5), rng.range(0.0, 3000.0))
            };
            let (want_loads, want) = reference_tangent(&e, &ends, beta, rate);
            let Some((loads, k)) = kernel_tangent(Kernel::detect(), &e, &ends, beta, rate) else {
                outside += 1;
                let (l, k) = element_tangent(&e, &ends, beta, rate);
                assert_eq!(l, want_loads);
                assert_eq!(k, want);
                continue;
            };
            inside += 1;
            if want_loads.axial_force >= 0.0 {
                tension += 1;
            } else {
                compression += 1;
            }
            let (_, portable) = kernel_tangent(Kernel::Portable, &e, &ends, beta, rate).unwrap();
            assert_eq!(k, portable, "AVX2 and portable copies differ");
            let (got_l, want_l) = (flat(&loads), flat(&want_loads));
            let kind = |i: usize| (i / 3) % 2;
            for group in 0..2 {
                let scale = (0..12)
                    .filter(|&i| kind(i) == group)
                    .map(|i| want_l[i].abs())
                    .fold(0.0, f64::max);
                for i in (0..12).filter(|&i| kind(i) == group) {
                    assert!(
                        (got_l[i] - want_l[i]).abs() <= 1e-12 * scale,
                        "round {round}: load {i} {} vs {}",
                        got_l[i],
                        want_l[i]
                    );
                }
            }
            for (rg, cg) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let entries = || {
                    (0..12).filter(move |&i| kind(i) == rg).flat_map(move |i| {
                        (0..12).filter(move |&j| kind(j) == cg).map(move |j| (i, j))
                    })
                };
                let scale = entries().map(|ij| want[ij].abs()).fold(0.0, f64::max);
                for ij in entries() {
                    let err = (k[ij] - want[ij]).abs() / scale;
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-10,
                        "round {round}: K{ij:?} = {} vs reference {} ({err:e})",
                        k[ij],
                        want[ij]
                    );
                }
            }
        }
        eprintln!(
            "kernel tangent: {inside} elements, reference: {outside}; tension {tension}, \
             compression {compression}; worst relative difference {worst:e}"
        );
        assert!(inside > 3000 && outside > 1000, "{inside} {outside}");
        assert!(
            tension > 500 && compression > 500,
            "{tension} {compression}"
        );
    }
}
