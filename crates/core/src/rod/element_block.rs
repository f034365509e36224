//! The element loads four elements at a time: the explicit solver's hot loop.
//!
//! [`BeamElement::loads_of`] is the reference — generic over the number type, so that the
//! Newton solvers differentiate it — and evaluates one element. Here the same element
//! law is evaluated for four elements of one hose at once, each in one lane of 256-bit
//! registers ([`crate::rod::lanes`]): the elements' constants are stored structure-of-arrays
//! in blocks of four ([`PackedElements`], built with the model), the node data are
//! gathered into lanes, and the loads are added to the nodes lane by lane in element
//! order — the order of the reference loop. The kernel is compiled twice, for AVX2 + FMA
//! (chosen at run time when the CPU has both) and portable; both give the same bits (see
//! [`crate::rod::lanes`]), so results never depend on the machine's instruction set.
//!
//! The algebra is the reference's, reorganised for speed but not approximated; results
//! agree with the reference to rounding (a test checks ≤ 1e-12 of each load's scale on
//! random large-rotation configurations):
//!
//! * a block whose rest offsets are all the identity — a hose straight at rest, whose
//!   node frames are its elements' frames — takes the node frames as the end frames
//!   without the two products q · 1 (which return a finite q exactly, but for the
//!   sign of a zero component);
//! * the element frame's rotation matrix is formed once and rotates the four vectors
//!   (end rates into the frame, end moments out of it) instead of four quaternion
//!   rotations;
//! * the element frame (the mean of the end frames turned onto the chord) is normalised
//!   once, at the end: the mean m = rₐ + r_b and the turn (x × e₁, 1 + x·e₁) stay
//!   unnormalised (the mean's x axis is the first column of the rotation matrix of m
//!   with 2/|m|² for the 2 of a unit quaternion), since normalising the product
//!   normalises both factors — two square roots and two divisions fewer on the
//!   kernel's longest dependency chain;
//! * the log map uses the half-angle identity θ = 4 atan(y)/y · v/(1 + w) with
//!   y = |v|/(1 + w) = tan(|θ|/4) for a unit quaternion (v, w), w ≥ 0, and the series of
//!   atan(y)/y to y²⁰ (truncation < 5e-18 for y² ≤ 0.035, i.e. |θ| ≤ 0.75 rad); the tangent
//!   operator's coefficient c(θ) = 1/θ² − (1 + cos θ)/(2 θ sin θ) its Bernoulli series
//!   Σ (−1)ⁿ⁺¹ B₂ₙ θ²ⁿ⁻²/(2n)! to θ¹⁶ (relative truncation < 3e-16 for θ² ≤ 0.6). Both
//!   ranges cover an element's relative rotations in any realistic scene, with no
//!   sin, cos or atan2;
//! * a lane outside those ranges (or with a chord antiparallel to the frame's axis, or
//!   not finite) is recomputed by the reference [`BeamElement::loads`]: exact for any
//!   configuration, and rare.

use crate::model::HoseInfo;
use crate::rod::element::{BeamElement, ElementEnds};
use crate::rod::lane_arith::Lane4;
use crate::rod::lanes::{gather3, gather4, lane, shift_up, F4, M34, M4, Q4, V4};
use crate::rod::node_lanes::NodeLanes;
use crate::rod::node_view::NodeView;
use glam::{DMat3, DQuat, DVec3};
use std::cell::RefCell;

/// Largest y² = tan²(|θ|/4) of the log map's series (|θ| ≤ 0.75 rad).
pub(crate) const LOG_Y2_MAX: f64 = 0.035;
/// atan(y)/y = Σ (−1)ᵏ y²ᵏ/(2k + 1), k = 0 … 10.
pub(crate) const ATAN_OVER_Y: [f64; 11] = [
    1.0,
    -1.0 / 3.0,
    1.0 / 5.0,
    -1.0 / 7.0,
    1.0 / 9.0,
    -1.0 / 11.0,
    1.0 / 13.0,
    -1.0 / 15.0,
    1.0 / 17.0,
    -1.0 / 19.0,
    1.0 / 21.0,
];
/// Largest θ² of the tangent operator's series (|θ| ≤ 0.77 rad).
pub(crate) const JACOBIAN_T2_MAX: f64 = 0.6;
/// c(θ) = 1/θ² − (1 + cos θ)/(2 θ sin θ) = Σ aₙ θ²ⁿ⁻², aₙ = (−1)ⁿ⁺¹ B₂ₙ/(2n)!, n = 1 … 9.
pub(crate) const JACOBIAN_C: [f64; 9] = [
    1.0 / 12.0,
    1.0 / 720.0,
    1.0 / 30240.0,
    1.0 / 1209600.0,
    1.0 / 47900160.0,
    691.0 / 1307674368000.0,
    1.0 / 74724249600.0,
    3617.0 / 10670622842880000.0,
    43867.0 / 5109094217170944000.0,
];

/// Four elements of one hose, their constants in lanes. A hose's last block repeats its
/// last element in the lanes beyond `lanes` (computed, never added to the nodes).
#[derive(Clone, Debug)]
pub struct ElementBlock {
    /// Global node indices of the elements' ends, and the elements' indices.
    pub node_a: [usize; 4],
    pub node_b: [usize; 4],
    pub element: [usize; 4],
    /// Lanes holding elements (1 … 4).
    pub lanes: usize,
    /// Four elements in a chain: element k joins nodes `node_a[0] + k` and `node_a[0] + k + 1`
    /// (a hose's interior; their loads are added to the five nodes at once, `add_chained`).
    pub chain: bool,
    rest_length: F4,
    inv_rest_length: F4,
    /// l₀/30 (the arch strain's moments).
    rest_length_30: F4,
    /// The rest slopes θ₀ (a.y, a.z, b.y, b.z) and their arch strain
    /// ([`BeamElement::rest_slopes`]).
    rest_slopes: [F4; 4],
    rest_arch: F4,
    axial_tension: F4,
    axial_compression: F4,
    /// EI₁/l, EI₂/l, GJ/l over the rest axis's length l ([`BeamElement::axis_length`]).
    bending_1: F4,
    bending_2: F4,
    torsion: F4,
    offset_a: Q4,
    offset_b: Q4,
    /// Every lane's rest offsets are the identity (a hose straight at rest whose node
    /// frames are its elements' frames): the end frames are the node frames.
    identity_offsets: bool,
    /// The lanes whose element is curved at rest, and whether some or all are: those read
    /// their bending and twist in their ends' axes A_a, A_b ([`crate::rod::element::EndAxes`];
    /// the identity in the other lanes).
    curved: M4,
    curved_lanes: CurvedLanes,
    end_axes_a: M34,
    end_axes_b: M34,
}

/// Which lanes of a block hold elements curved at rest: the kernel computes the
/// straight law, the curved one, or both and picks lane by lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurvedLanes {
    None,
    Some,
    All,
}

/// The model's elements in blocks of four, hose by hose (built with the model).
#[derive(Clone, Debug, Default)]
pub struct PackedElements {
    pub blocks: Vec<ElementBlock>,
    /// The blocks of hose h are `hose_blocks[h]..hose_blocks[h + 1]`.
    pub hose_blocks: Vec<usize>,
    /// Elements the packing was built for, yielding ones (not packed) included (a check
    /// that the model's elements are the packed ones).
    pub element_count: usize,
}

impl PackedElements {
    /// Packs `elements`, hose by hose.
    pub fn new(elements: &[BeamElement], hoses: &[HoseInfo]) -> Self {
        let mut blocks = Vec::with_capacity(elements.len().div_ceil(4) + hoses.len());
        let mut hose_blocks = Vec::with_capacity(hoses.len() + 1);
        hose_blocks.push(0);
        for h in hoses {
            let range = h.first_element..h.first_element + h.element_count;
            // inelastic elements are not packed: their law has a history
            // ([`crate::rod::inelastic`], added after the blocks)
            let ids: Vec<usize> = range.filter(|&k| elements[k].inelastic.is_none()).collect();
            for chunk in ids.chunks(4) {
                blocks.push(ElementBlock::new(elements, chunk));
            }
            hose_blocks.push(blocks.len());
        }
        PackedElements {
            blocks,
            hose_blocks,
            element_count: elements.len(),
        }
    }
}

impl ElementBlock {
    fn new(elements: &[BeamElement], ids: &[usize]) -> Self {
        let id = |k: usize| ids[k.min(ids.len() - 1)];
        let el = |k: usize| &elements[id(k)];
        let lanes = |f: &dyn Fn(&BeamElement) -> f64| F4([0, 1, 2, 3].map(|k| f(el(k))));
        let quat = |f: &dyn Fn(&BeamElement) -> DQuat| Q4 {
            x: lanes(&|e| f(e).x),
            y: lanes(&|e| f(e).y),
            z: lanes(&|e| f(e).z),
            w: lanes(&|e| f(e).w),
        };
        ElementBlock {
            node_a: [0, 1, 2, 3].map(|k| el(k).node_a),
            node_b: [0, 1, 2, 3].map(|k| el(k).node_b),
            element: [0, 1, 2, 3].map(id),
            lanes: ids.len(),
            chain: ids.len() == 4
                && (0..4).all(|k| {
                    el(k).node_a == el(0).node_a + k && el(k).node_b == el(0).node_a + k + 1
                }),
            rest_length: lanes(&|e| e.rest_length),
            inv_rest_length: lanes(&|e| 1.0 / e.rest_length),
            rest_length_30: lanes(&|e| e.rest_length / 30.0),
            rest_slopes: [0, 1, 2, 3].map(|i| lanes(&|e| e.rest_slopes[i])),
            rest_arch: lanes(&|e| e.rest_arch),
            axial_tension: lanes(&|e| e.axial_stiffness_tension),
            axial_compression: lanes(&|e| e.axial_stiffness_compression),
            bending_1: lanes(&|e| e.bending_stiffness[0] / e.axis_length),
            bending_2: lanes(&|e| e.bending_stiffness[1] / e.axis_length),
            torsion: lanes(&|e| e.torsion_stiffness / e.axis_length),
            offset_a: quat(&|e| e.rest_offset_a),
            offset_b: quat(&|e| e.rest_offset_b),
            identity_offsets: (0..4).all(|k| {
                el(k).rest_offset_a == DQuat::IDENTITY && el(k).rest_offset_b == DQuat::IDENTITY
            }),
            curved: M4([0, 1, 2, 3].map(|k| if el(k).end_axes.is_some() { !0 } else { 0 })),
            curved_lanes: match (0..4).filter(|&k| el(k).end_axes.is_some()).count() {
                0 => CurvedLanes::None,
                4 => CurvedLanes::All,
                _ => CurvedLanes::Some,
            },
            end_axes_a: end_axes(&|k| el(k), 0),
            end_axes_b: end_axes(&|k| el(k), 1),
        }
    }
}

/// End `end`'s axes of the elements `el(0 … 3)` in lanes (the identity for straight ones).
fn end_axes<'a>(el: &dyn Fn(usize) -> &'a BeamElement, end: usize) -> M34 {
    let m = |k: usize| el(k).end_axes.map_or(DMat3::IDENTITY, |axes| axes.0[end]);
    let column = |c: usize| {
        let v = |i: usize| F4([0, 1, 2, 3].map(|k| m(k).col(c)[i]));
        V4::new(v(0), v(1), v(2))
    };
    M34 {
        c: [column(0), column(1), column(2)],
    }
}

/// Loads of four elements (global axes).
#[derive(Clone, Copy, Debug)]
pub struct BlockLoads {
    pub force_a: V4,
    pub force_b: V4,
    pub moment_a: V4,
    pub moment_b: V4,
    /// Lanes the kernel's series do not cover (to be recomputed by the reference).
    pub outside: M4,
}

#[inline(always)]
fn horner(x: F4, coeffs: &[f64]) -> F4 {
    let mut p = F4::splat(coeffs[coeffs.len() - 1]);
    for &c in coeffs[..coeffs.len() - 1].iter().rev() {
        p = p.mul_add(x, F4::splat(c));
    }
    p
}

/// Rotation vector of unit quaternions (the shorter of ±q), and the lanes whose angle
/// the series covers.
#[inline(always)]
fn log_map(q: Q4) -> (V4, M4) {
    let neg = q.w.lt(F4::ZERO);
    let v = V4::select(neg, -q.vector(), q.vector());
    let w = neg.select(-q.w, q.w);
    let r = F4::splat(1.0) / (w + 1.0);
    let y2 = v.dot(v) * (r * r);
    let ok = y2.le(F4::splat(LOG_Y2_MAX));
    let scale = horner(y2, &ATAN_OVER_Y) * (r * 4.0);
    (v.scale(scale), ok)
}

/// J_l(θ)⁻ᵀ M = M + ½ θ × M + c(θ) θ × (θ × M), and the lanes the series covers.
#[inline(always)]
fn jacobian_inverse_transpose_times(theta: V4, moment: V4) -> (V4, M4) {
    let t2 = theta.dot(theta);
    let ok = t2.le(F4::splat(JACOBIAN_T2_MAX));
    let c = horner(t2, &JACOBIAN_C);
    let txm = theta.cross(moment);
    (
        theta
            .cross(txm)
            .scale_add(c, txm.scale_add(F4::splat(0.5), moment)),
        ok,
    )
}

/// The node data `a` of the elements' ends a (nodes `na`) and b (`nb`) in lanes, by
/// `gather`; for a chain block from its five consecutive nodes (one bounds check).
#[inline(always)]
fn ends<T, L>(
    a: &[T],
    chain: bool,
    na: [usize; 4],
    nb: [usize; 4],
    gather: impl Fn(&[T], [usize; 4]) -> L,
) -> (L, L) {
    if chain {
        let five = &a[na[0]..na[0] + 5];
        (gather(five, [0, 1, 2, 3]), gather(five, [1, 2, 3, 4]))
    } else {
        (gather(a, na), gather(a, nb))
    }
}

/// Where a block reads its elements' end data: positions, frames, velocities and
/// angular velocities of the ends a and b in lanes.
trait EndData {
    fn x(&self) -> (V4, V4);
    fn q(&self) -> (Q4, Q4);
    fn v(&self) -> (V4, V4);
    fn w(&self) -> (V4, V4);
}

/// Gathered from the node arrays (`na`, `nb`: the ends' indices in `c`'s arrays).
struct Gathered<'a> {
    c: &'a NodeView<'a>,
    chain: bool,
    na: [usize; 4],
    nb: [usize; 4],
}

impl EndData for Gathered<'_> {
    #[inline(always)]
    fn x(&self) -> (V4, V4) {
        ends(self.c.x, self.chain, self.na, self.nb, gather3)
    }
    #[inline(always)]
    fn q(&self) -> (Q4, Q4) {
        ends(self.c.q, self.chain, self.na, self.nb, gather4)
    }
    #[inline(always)]
    fn v(&self) -> (V4, V4) {
        ends(self.c.v, self.chain, self.na, self.nb, gather3)
    }
    #[inline(always)]
    fn w(&self) -> (V4, V4) {
        ends(self.c.w, self.chain, self.na, self.nb, gather3)
    }
}

/// A chained block's five nodes `n..n + 5` read from a window of node lanes that holds
/// them: plain loads, no shuffles.
struct Windowed<'a> {
    lanes: &'a NodeLanes,
    n: usize,
}

impl EndData for Windowed<'_> {
    #[inline(always)]
    fn x(&self) -> (V4, V4) {
        (self.lanes.x(self.n), self.lanes.x(self.n + 1))
    }
    #[inline(always)]
    fn q(&self) -> (Q4, Q4) {
        (self.lanes.q(self.n), self.lanes.q(self.n + 1))
    }
    #[inline(always)]
    fn v(&self) -> (V4, V4) {
        (self.lanes.v(self.n), self.lanes.v(self.n + 1))
    }
    #[inline(always)]
    fn w(&self) -> (V4, V4) {
        (self.lanes.w(self.n), self.lanes.w(self.n + 1))
    }
}

/// The loads of the four elements of block `b` in the configuration `c` (node indices
/// less `base` index `c`'s arrays), with stiffness-proportional damping `beta`.
#[inline(always)]
pub fn block_loads(b: &ElementBlock, c: &NodeView, base: usize, beta: f64) -> BlockLoads {
    let ends = Gathered {
        c,
        chain: b.chain,
        na: b.node_a.map(|i| i - base),
        nb: b.node_b.map(|i| i - base),
    };
    loads_from(b, &ends, beta)
}

/// [`block_loads`] of a chained block whose nodes `lanes` holds (`n`: its first node's
/// index in the view the window was filled from).
#[inline(always)]
fn chained_block_loads(b: &ElementBlock, lanes: &NodeLanes, n: usize, beta: f64) -> BlockLoads {
    loads_from(b, &Windowed { lanes, n }, beta)
}

/// The loads of block `b` with its end data from `ends`.
#[inline(always)]
fn loads_from(b: &ElementBlock, ends: &impl EndData, beta: f64) -> BlockLoads {
    // two instances of the kernel rather than a branch inside it, which the compiler
    // turns into computing the products and selecting
    if b.identity_offsets {
        loads_of_block::<true>(b, ends, beta)
    } else {
        loads_of_block::<false>(b, ends, beta)
    }
}

/// [`block_loads`], with `IDENTITY` the block's `identity_offsets`.
#[inline(always)]
fn loads_of_block<const IDENTITY: bool>(
    b: &ElementBlock,
    ends: &impl EndData,
    beta: f64,
) -> BlockLoads {
    let one = F4::splat(1.0);
    let (xa, xb) = ends.x();
    let (qa, qb) = ends.q();

    // chord, end frames, element frame (aligned mean of the end frames)
    let chord = xb - xa;
    let length = chord.dot(chord).sqrt();
    let inv_length = one / length;
    let e1 = chord.scale(inv_length);
    // q · 1 = q exactly (with fused multiply–adds; a zero component may change sign)
    let (ra, rb) = if IDENTITY {
        (qa, qb)
    } else {
        (qa * b.offset_a, qb * b.offset_b)
    };
    let flip = ra.dot(rb).lt(F4::ZERO);
    let rb = Q4 {
        x: flip.select(-rb.x, rb.x),
        y: flip.select(-rb.y, rb.y),
        z: flip.select(-rb.z, rb.z),
        w: flip.select(-rb.w, rb.w),
    };
    // the mean of the end frames, not normalised: m = rₐ + r_b, |m|² ≥ 2 after the flip
    let mean = Q4 {
        x: ra.x + rb.x,
        y: ra.y + rb.y,
        z: ra.z + rb.z,
        w: ra.w + rb.w,
    };
    // the mean frame's x axis: first column of the rotation matrix of m/|m|, whose
    // entries are quadratic in m, so 2/|m|² replaces the 2 of a unit quaternion's
    let two_by_norm2 = F4::splat(2.0) / mean.dot(mean);
    let (y2, z2) = (mean.y * two_by_norm2, mean.z * two_by_norm2);
    let x_axis = V4::new(
        one - mean.y.mul_add(y2, mean.z * z2),
        mean.x.mul_add(y2, mean.w * z2),
        mean.x.mul_add(z2, -(mean.w * y2)),
    );
    // smallest rotation of that axis onto the chord: ∝ (x × e₁, 1 + x·e₁), not
    // normalised either; the frame (turn · mean) is normalised once, as a product of
    // two quaternions whose norms are positive factors of its norm
    let w_turn = x_axis.dot(e1) + one;
    let not_antiparallel = F4::splat(1e-12).le(w_turn);
    let axis = x_axis.cross(e1);
    let turn = Q4 {
        x: axis.x,
        y: axis.y,
        z: axis.z,
        w: w_turn,
    };
    let frame = (turn * mean).normalize();
    let (theta_a, ok_a) = log_map(frame.conj_mul(ra));
    let (theta_b, ok_b) = log_map(frame.conj_mul(rb));
    let rot = M34::from_quat(frame);

    // strain (chord and shallow arch) and the deformation rates
    let plane = |a: F4, b: F4| {
        // (2a² − ab + 2b²)/30
        (a + a).mul_add(a, b.mul_add(b + b, -(a * b))) * (1.0 / 30.0)
    };
    // the slopes against the chord: from the rest shape, plus its own
    let [s_ay, s_az, s_by, s_bz] = b.rest_slopes;
    let (slope_a, slope_b) = (
        V4::new(theta_a.x, theta_a.y + s_ay, theta_a.z + s_az),
        V4::new(theta_b.x, theta_b.y + s_by, theta_b.z + s_bz),
    );
    let arch = plane(slope_a.y, slope_b.y) + plane(slope_a.z, slope_b.z) - b.rest_arch;
    let l0 = b.rest_length;
    let strain = (length - l0).mul_add(b.inv_rest_length, arch);
    let (va, vb) = ends.v();
    let (wa, wb) = ends.w();
    let dv = vb - va;
    let strain_rate = e1.dot(dv) * b.inv_rest_length;
    let spin = e1
        .cross(dv)
        .scale_add(inv_length, e1.scale(e1.dot(wa + wb) * 0.5));
    let rate_a = rot.mul_transpose(wa - spin);
    let rate_b = rot.mul_transpose(wb - spin);

    // local law
    let tension = F4::ZERO.le(strain);
    let ea = tension.select(b.axial_tension, b.axial_compression);
    let elastic_axial = strain * ea;
    let beta4 = F4::splat(beta);
    let axial = strain_rate.mul_add(ea * beta4, elastic_axial);
    let ta = rate_a.scale_add(beta4, theta_a);
    let tb = rate_b.scale_add(beta4, theta_b);
    let torque = (tb.x - ta.x) * b.torsion;
    let k_arch = elastic_axial * b.rest_length_30;
    let (two, four) = (F4::splat(2.0), F4::splat(4.0));
    // (E I/l₀)(4 tₐ + 2 t_b) + (N l₀/30)(4 θₐ − θ_b), and a ↔ b
    let bend = |ta: F4, tb: F4, th_a: F4, th_b: F4, k: F4| {
        let linear = ta.mul_add(four, tb * two) * k;
        th_a.mul_add(four, -th_b).mul_add(k_arch, linear)
    };
    let (ma_local, mb_local) = if b.curved_lanes == CurvedLanes::All {
        curved_local_moments(b, ta, tb, slope_a, slope_b, k_arch)
    } else {
        let ma = V4::new(
            -torque,
            bend(ta.y, tb.y, slope_a.y, slope_b.y, b.bending_1),
            bend(ta.z, tb.z, slope_a.z, slope_b.z, b.bending_2),
        );
        let mb = V4::new(
            torque,
            bend(tb.y, ta.y, slope_b.y, slope_a.y, b.bending_1),
            bend(tb.z, ta.z, slope_b.z, slope_a.z, b.bending_2),
        );
        if b.curved_lanes == CurvedLanes::Some {
            let (ca, cb) = curved_local_moments(b, ta, tb, slope_a, slope_b, k_arch);
            (V4::select(b.curved, ca, ma), V4::select(b.curved, cb, mb))
        } else {
            (ma, mb)
        }
    };

    // moments conjugate to spatial rotations, global axes; nodal loads
    let (ma, okj_a) = jacobian_inverse_transpose_times(theta_a, ma_local);
    let (mb, okj_b) = jacobian_inverse_transpose_times(theta_b, mb_local);
    let ma = rot.mul(ma);
    let mb = rot.mul(mb);
    let sum = ma + mb;
    let twist = e1.scale(sum.dot(e1) * 0.5);
    let force_b = sum.cross(e1).scale_add(inv_length, -e1.scale(axial));
    let inside = ok_a
        .and(ok_b)
        .and(okj_a)
        .and(okj_b)
        .and(not_antiparallel)
        .and(length.le(F4::splat(f64::MAX)));
    BlockLoads {
        force_a: -force_b,
        force_b,
        moment_a: twist - ma,
        moment_b: twist - mb,
        outside: !inside,
    }
}

/// The local end moments (element frame axes) of elements curved at rest: the linear law
/// on the end rotations `ta`, `tb` read in the ends' axes (Aₖᵀ θₖ), its moments turned back
/// (Aₖ Mₖ), plus the shallow arch's moments of the slopes against the chord, `slope_a`,
/// `slope_b` ([`BeamElement::loads_of`]).
#[inline(always)]
fn curved_local_moments(
    b: &ElementBlock,
    ta: V4,
    tb: V4,
    slope_a: V4,
    slope_b: V4,
    k_arch: F4,
) -> (V4, V4) {
    let ta = b.end_axes_a.mul_transpose(ta);
    let tb = b.end_axes_b.mul_transpose(tb);
    let torque = (tb.x - ta.x) * b.torsion;
    let (two, four) = (F4::splat(2.0), F4::splat(4.0));
    let linear_a = V4::new(
        -torque,
        ta.y.mul_add(four, tb.y * two) * b.bending_1,
        ta.z.mul_add(four, tb.z * two) * b.bending_2,
    );
    let linear_b = V4::new(
        torque,
        tb.y.mul_add(four, ta.y * two) * b.bending_1,
        tb.z.mul_add(four, ta.z * two) * b.bending_2,
    );
    let arch_a = V4::new(
        F4::ZERO,
        slope_a.y.mul_add(four, -slope_b.y) * k_arch,
        slope_a.z.mul_add(four, -slope_b.z) * k_arch,
    );
    let arch_b = V4::new(
        F4::ZERO,
        slope_b.y.mul_add(four, -slope_a.y) * k_arch,
        slope_b.z.mul_add(four, -slope_a.z) * k_arch,
    );
    (
        b.end_axes_a.mul(linear_a) + arch_a,
        b.end_axes_b.mul(linear_b) + arch_b,
    )
}

/// One element by the reference (lanes outside the kernel's series).
#[cold]
#[inline(never)]
fn reference_loads(e: &BeamElement, c: &NodeView, base: usize, beta: f64) -> [DVec3; 4] {
    let (a, b) = (e.node_a - base, e.node_b - base);
    let l = e.loads(
        &ElementEnds {
            x: [c.x[a], c.x[b]],
            q: [c.q[a], c.q[b]],
            v: [c.v[a], c.v[b]],
            w: [c.w[a], c.w[b]],
        },
        beta,
    );
    [l.force[0], l.force[1], l.moment[0], l.moment[1]]
}

/// Adds the end loads `a` (node a) and `b` (node b) of four chained elements to their
/// five nodes `out[0..5]` (element k joins `out[k]` and `out[k + 1]`) with the sums of the
/// lane-by-lane loop in element order, bit for bit: node k gets b of element k − 1, then
/// a of element k — (out[k] + b[k − 1]) + a[k], with −0.0 (x + (−0) = x for every x) for
/// the b that node 0 does not get.
/// The four nodes are moved into lanes and back by [`Lane4`]'s loads and stores (three
/// 256-bit loads or stores and seven shuffles for AVX).
#[inline(always)]
fn add_chained<L: Lane4>(a: V4, b: V4, out: &mut [DVec3]) {
    let out = &mut out[..5];
    let b_up = shift_up(-0.0, b);
    let four: &mut [DVec3; 4] = (&mut out[..4]).try_into().expect("four nodes");
    let [x, y, z] = L::load_vectors(four);
    let sum = |o: L, b: F4, a: F4| (o + L::from_f4(b)) + L::from_f4(a);
    let sum = [
        sum(x, b_up.x, a.x),
        sum(y, b_up.y, a.y),
        sum(z, b_up.z, a.z),
    ];
    L::store_vectors(sum, four);
    out[4] += lane(b, 3);
}

/// One call of [`add_loads`]: the loads of `blocks` go into `force` and `moment`,
/// element after element; `c`, `force` and `moment` hold nodes `base..`. Elements whose
/// node a `skip` selects (global index) are left out.
struct Job<'a, S> {
    blocks: &'a [ElementBlock],
    elements: &'a [BeamElement],
    c: &'a NodeView<'a>,
    base: usize,
    beta: f64,
    force: &'a mut [DVec3],
    moment: &'a mut [DVec3],
    skip: &'a S,
}

impl<S: Fn(usize) -> bool> Job<'_, S> {
    /// Runs the job, with `L` the lanes of the node window's transposes and of
    /// `add_chained`, and `window` the window (its contents are forgotten first).
    #[inline(always)]
    fn run<L: Lane4>(self, window: &mut NodeLanes) {
        let Job {
            blocks,
            elements,
            c,
            base,
            beta,
            force,
            moment,
            skip,
        } = self;
        window.clear();
        for b in blocks {
            let lanes = b.lanes;
            let mut active = [false; 4];
            for (k, a) in active.iter_mut().enumerate().take(lanes) {
                *a = !skip(b.node_a[k]);
            }
            if !active.contains(&true) {
                continue;
            }
            // through memory: stored as vectors, the loads are computed in 256-bit
            // registers; extracted lane by lane for `add_chained` without it, LLVM
            // computed the whole block lane by lane
            let l = if b.chain {
                let n = b.node_a[0] - base;
                window.hold::<L>(c, n, 5);
                std::hint::black_box(chained_block_loads(b, window, n, beta))
            } else {
                std::hint::black_box(block_loads(b, c, base, beta))
            };
            if b.chain && active == [true; 4] && !l.outside.any() {
                let n = b.node_a[0] - base;
                add_chained::<L>(l.force_a, l.force_b, &mut force[n..n + 5]);
                add_chained::<L>(l.moment_a, l.moment_b, &mut moment[n..n + 5]);
                continue;
            }
            for k in 0..lanes {
                if !active[k] {
                    continue;
                }
                let [fa, fb, ma, mb] = if l.outside.lane(k) {
                    reference_loads(&elements[b.element[k]], c, base, beta)
                } else {
                    [
                        lane(l.force_a, k),
                        lane(l.force_b, k),
                        lane(l.moment_a, k),
                        lane(l.moment_b, k),
                    ]
                };
                let (na, nb) = (b.node_a[k] - base, b.node_b[k] - base);
                force[na] += fa;
                force[nb] += fb;
                moment[na] += ma;
                moment[nb] += mb;
            }
        }
    }
}

/// [`Job::run`] compiled for AVX2 + FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn run_avx2_fma<S: Fn(usize) -> bool>(job: Job<S>, lanes: &mut NodeLanes) {
    job.run::<crate::rod::lane_arith::Avx4>(lanes)
}

/// [`Job::run`] as portable code.
#[inline(never)]
fn run_portable<S: Fn(usize) -> bool>(job: Job<S>, lanes: &mut NodeLanes) {
    job.run::<F4>(lanes)
}

thread_local! {
    /// Each thread's window of node lanes for [`add_loads`] (a fixed array: nothing is
    /// allocated).
    static NODE_LANES: RefCell<NodeLanes> = const { RefCell::new(NodeLanes::EMPTY) };
}

/// Which kernel [`add_loads`] runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// 256-bit AVX2 with fused multiply–add (x86-64 CPUs that have both).
    Avx2Fma,
    /// Portable code (any CPU; the same results).
    Portable,
}

impl Kernel {
    /// The fastest kernel this CPU runs.
    pub fn detect() -> Kernel {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            return Kernel::Avx2Fma;
        }
        Kernel::Portable
    }

    pub fn name(self) -> &'static str {
        match self {
            Kernel::Avx2Fma => "avx2+fma",
            Kernel::Portable => "portable",
        }
    }
}

/// Adds the internal loads of `blocks` (with damping `beta`) to `force` and `moment`,
/// whose entries — like `c`'s — are nodes `base..`; elements whose node a `skip` selects
/// are left out. Each node receives its elements' loads in element order.
#[allow(clippy::too_many_arguments)]
pub fn add_loads(
    kernel: Kernel,
    blocks: &[ElementBlock],
    elements: &[BeamElement],
    c: &NodeView,
    base: usize,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    skip: &impl Fn(usize) -> bool,
) {
    let job = Job {
        blocks,
        elements,
        c,
        base,
        beta,
        force,
        moment,
        skip,
    };
    NODE_LANES.with_borrow_mut(|lanes| match kernel {
        #[cfg(target_arch = "x86_64")]
        Kernel::Avx2Fma if Kernel::detect() == Kernel::Avx2Fma => {
            // SAFETY: the CPU has AVX2 and FMA (checked just above; the check is cached).
            unsafe { run_avx2_fma(job, lanes) }
        }
        _ => run_portable(job, lanes),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::exp_map;
    use crate::rod::inelastic::HistoryView;
    use crate::rod::test_elements::{random_element, random_ends, Rng};

    /// The kernel equals the reference `BeamElement::loads` to rounding: within 1e-12 of
    /// each load's scale (the largest force, the largest moment of the element), on random
    /// large-rotation configurations with tension and compression, damping, tubes and
    /// given sections, elements curved at rest and straight ones (blocks mixing both), and
    /// relative rotations inside and outside the kernel's series.
    #[test]
    fn kernel_equals_the_reference() {
        let mut rng = Rng(15);
        let (mut in_kernel, mut by_reference, mut tension, mut compression) = (0, 0, 0, 0);
        let mut worst: f64 = 0.0;
        for round in 0..4000 {
            let mut elements = Vec::new();
            let mut rests = Vec::new();
            for k in 0..4 {
                let mut e = random_element(&mut rng, k);
                if round % 4 == 1 && k % 2 == 0 {
                    // blocks mixing straight and curved elements
                    let l0 = e.rest_length;
                    e.set_rest_shape([DVec3::ZERO, DVec3::X * l0], [DQuat::IDENTITY; 2]);
                    assert!(e.end_axes.is_none());
                }
                // the rest frames this element was built from: recover them from its offsets
                // (any frames with the same offsets give the same element)
                let frame0 = DQuat::IDENTITY;
                let qa = (frame0 * e.rest_offset_a.inverse()).normalize();
                let qb = (frame0 * e.rest_offset_b.inverse()).normalize();
                let xa = DVec3::ZERO;
                let xb = frame0 * DVec3::X * e.rest_length;
                rests.push(([xa, xb], [qa, qb]));
                elements.push(e);
            }
            // mostly moderate bending (kernel), sometimes beyond its series (reference)
            let bend = if round % 5 == 0 { 2.5 } else { 0.7 };
            let ends: Vec<ElementEnds> = (0..4)
                .map(|k| random_ends(&mut rng, &elements[k], rests[k], bend))
                .collect();
            let beta = if round % 3 == 0 {
                0.0
            } else {
                rng.range(0.0, 2e-5)
            };
            let n = 8;
            let mut x = vec![DVec3::ZERO; n];
            let mut q = vec![DQuat::IDENTITY; n];
            let mut v = vec![DVec3::ZERO; n];
            let mut w = vec![DVec3::ZERO; n];
            for k in 0..4 {
                for j in 0..2 {
                    x[2 * k + j] = ends[k].x[j];
                    q[2 * k + j] = ends[k].q[j];
                    v[2 * k + j] = ends[k].v[j];
                    w[2 * k + j] = ends[k].w[j];
                }
            }
            let c = NodeView {
                x: &x,
                q: &q,
                v: &v,
                w: &w,
                inelastic_history: HistoryView::NONE,
            };
            let hose = HoseInfo {
                name: "h".into(),
                first_node: 0,
                node_count: n,
                first_element: 0,
                element_count: 4,
            };
            let packed = PackedElements::new(&elements, &[hose]);
            let l = block_loads(&packed.blocks[0], &c, 0, beta);
            for k in 0..4 {
                let reference = elements[k].loads(&ends[k], beta);
                if reference.axial_force >= 0.0 {
                    tension += 1;
                } else {
                    compression += 1;
                }
                if l.outside.lane(k) {
                    by_reference += 1;
                    continue;
                }
                in_kernel += 1;
                let got = [
                    lane(l.force_a, k),
                    lane(l.force_b, k),
                    lane(l.moment_a, k),
                    lane(l.moment_b, k),
                ];
                let want = [
                    reference.force[0],
                    reference.force[1],
                    reference.moment[0],
                    reference.moment[1],
                ];
                let f_scale = want[0].length().max(want[1].length());
                let m_scale = want[2].length().max(want[3].length());
                for i in 0..4 {
                    let scale = if i < 2 { f_scale } else { m_scale };
                    let err = (got[i] - want[i]).length() / scale;
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-12,
                        "round {round} lane {k} load {i}: {:?} vs {:?} ({err:e})",
                        got[i],
                        want[i]
                    );
                }
            }
        }
        eprintln!("kernel: {in_kernel} lanes, reference: {by_reference}; tension {tension}, compression {compression}; worst relative difference {worst:e}");
        assert!(
            in_kernel > 10_000 && by_reference > 1000,
            "{in_kernel} {by_reference}"
        );
        assert!(tension > 1000 && compression > 1000);
    }

    /// A chain of elements (a hose's interior, whose blocks add their loads to five nodes
    /// at once, `add_chained`) gets the same bits as from the lane-by-lane loop, on both
    /// kernels, with blocks inside the series and blocks with a lane beyond it.
    #[test]
    fn chained_blocks_add_the_lane_by_lane_sums() {
        let mut rng = Rng(21);
        let n_el = 23;
        let n = n_el + 1;
        let mut rest_x = vec![DVec3::ZERO];
        for k in 0..n_el {
            let step = (DVec3::X + rng.vec(0.3)).normalize() * rng.range(0.01, 0.05);
            rest_x.push(rest_x[k] + step);
        }
        let rest_q: Vec<DQuat> = (0..n).map(|_| exp_map(rng.rotation(3.0))).collect();
        let elements: Vec<BeamElement> = (0..n_el)
            .map(|k| {
                let mut e = random_element(&mut rng, k);
                let chord = rest_x[k + 1] - rest_x[k];
                let frame = DQuat::from_rotation_arc(DVec3::X, chord.normalize());
                (e.node_a, e.node_b) = (k, k + 1);
                e.rest_length = chord.length();
                e.rest_offset_a = (rest_q[k].inverse() * frame).normalize();
                e.rest_offset_b = (rest_q[k + 1].inverse() * frame).normalize();
                e
            })
            .collect();
        let x: Vec<DVec3> = rest_x.iter().map(|p| *p + rng.vec(0.002)).collect();
        // node 13 turned far: its two elements' block goes lane by lane
        let q: Vec<DQuat> = (0..n)
            .map(|i| {
                let turn = if i == 13 { 2.5 } else { 0.2 };
                (exp_map(rng.rotation(turn)) * rest_q[i]).normalize()
            })
            .collect();
        let v: Vec<DVec3> = (0..n).map(|_| rng.vec(2.0)).collect();
        let w: Vec<DVec3> = (0..n).map(|_| rng.vec(50.0)).collect();
        let hose = HoseInfo {
            name: "h".into(),
            first_node: 0,
            node_count: n,
            first_element: 0,
            element_count: n_el,
        };
        let chained = PackedElements::new(&elements, &[hose]);
        let mut lane_by_lane = chained.clone();
        for b in &mut lane_by_lane.blocks {
            b.chain = false;
        }
        let c = NodeView {
            x: &x,
            q: &q,
            v: &v,
            w: &w,
            inelastic_history: HistoryView::NONE,
        };
        let (mut fast, mut outside) = (0, 0);
        for b in &chained.blocks {
            let l = block_loads(b, &c, 0, 1e-5);
            fast += (b.chain && !l.outside.any()) as usize;
            outside += l.outside.any() as usize;
        }
        assert!(fast >= 3 && outside >= 1, "{fast} {outside}");
        for kernel in [Kernel::detect(), Kernel::Portable] {
            let start = [DVec3::ONE, -DVec3::ONE];
            assert_eq!(
                load_bits(kernel, &chained, &elements, &c, start),
                load_bits(kernel, &lane_by_lane, &elements, &c, start)
            );
        }
    }

    /// The AVX2 + FMA kernel and the portable one give the same bits.
    #[test]
    fn kernels_agree_bit_for_bit() {
        let mut rng = Rng(3);
        let (elements, nodes) = seven_elements(&mut rng, |k| if k == 3 { 2.5 } else { 0.6 });
        let packed = PackedElements::new(&elements, &[nodes.hose()]);
        let c = nodes.view();
        let start = [DVec3::ZERO; 2];
        let a = load_bits(Kernel::detect(), &packed, &elements, &c, start);
        assert_eq!(
            a,
            load_bits(Kernel::Portable, &packed, &elements, &c, start)
        );
        let force = |p: &[u64]| DVec3::from_array([p[0], p[1], p[2]].map(f64::from_bits));
        assert!(a
            .0
            .chunks(3)
            .map(force)
            .all(|f| f.is_finite() && f.length() > 0.0));
    }

    /// Blocks whose rest offsets are all the identity (a hose straight at rest) skip the
    /// end frames' products q · 1 and get the product's bits, on both kernels; blocks with
    /// other offsets take the products.
    #[test]
    fn identity_offsets_skip_the_products_with_the_same_bits() {
        let mut rng = Rng(8);
        let (mut elements, nodes) = seven_elements(&mut rng, |_| 0.6);
        let general = PackedElements::new(&elements, &[nodes.hose()]);
        assert!(general.blocks.iter().all(|b| !b.identity_offsets));
        for e in &mut elements {
            (e.rest_offset_a, e.rest_offset_b) = (DQuat::IDENTITY, DQuat::IDENTITY);
        }
        let skipping = PackedElements::new(&elements, &[nodes.hose()]);
        assert!(skipping.blocks.iter().all(|b| b.identity_offsets));
        let mut multiplying = skipping.clone();
        for b in &mut multiplying.blocks {
            b.identity_offsets = false;
        }
        let c = nodes.view();
        let start = [DVec3::ZERO; 2];
        for kernel in [Kernel::detect(), Kernel::Portable] {
            assert_eq!(
                load_bits(kernel, &skipping, &elements, &c, start),
                load_bits(kernel, &multiplying, &elements, &c, start)
            );
        }
    }

    /// The configuration of a hose's nodes.
    struct NodeArrays {
        x: Vec<DVec3>,
        q: Vec<DQuat>,
        v: Vec<DVec3>,
        w: Vec<DVec3>,
    }

    impl NodeArrays {
        fn view(&self) -> NodeView<'_> {
            NodeView {
                x: &self.x,
                q: &self.q,
                v: &self.v,
                w: &self.w,
                inelastic_history: HistoryView::NONE,
            }
        }

        /// One hose of all the nodes, one element per two nodes.
        fn hose(&self) -> HoseInfo {
            HoseInfo {
                name: "h".into(),
                first_node: 0,
                node_count: self.x.len(),
                first_element: 0,
                element_count: self.x.len() / 2,
            }
        }
    }

    /// Seven random elements, element k between nodes 2k and 2k + 1, and a configuration
    /// of their nodes with element k's ends turned by up to `bend(k)` from its rest.
    fn seven_elements(
        rng: &mut Rng,
        bend: impl Fn(usize) -> f64,
    ) -> (Vec<BeamElement>, NodeArrays) {
        let mut elements = Vec::new();
        let mut rests = Vec::new();
        for k in 0..7 {
            let e = random_element(rng, k);
            let qa = e.rest_offset_a.inverse().normalize();
            let qb = e.rest_offset_b.inverse().normalize();
            rests.push(([DVec3::ZERO, DVec3::X * e.rest_length], [qa, qb]));
            elements.push(e);
        }
        let n = 14;
        let (mut x, mut q) = (vec![DVec3::ZERO; n], vec![DQuat::IDENTITY; n]);
        let (mut v, mut w) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
        for k in 0..7 {
            let ends = random_ends(rng, &elements[k], rests[k], bend(k));
            for j in 0..2 {
                (x[2 * k + j], q[2 * k + j]) = (ends.x[j], ends.q[j]);
                (v[2 * k + j], w[2 * k + j]) = (ends.v[j], ends.w[j]);
            }
        }
        (elements, NodeArrays { x, q, v, w })
    }

    /// The bits of the forces and moments `add_loads` adds to `start` (force, moment) at
    /// every node of `c`, damping 1e-5.
    fn load_bits(
        kernel: Kernel,
        packed: &PackedElements,
        elements: &[BeamElement],
        c: &NodeView,
        start: [DVec3; 2],
    ) -> (Vec<u64>, Vec<u64>) {
        let n = c.x.len();
        let (mut f, mut m) = (vec![start[0]; n], vec![start[1]; n]);
        let none = |_: usize| false;
        add_loads(
            kernel,
            &packed.blocks,
            elements,
            c,
            0,
            1e-5,
            &mut f,
            &mut m,
            &none,
        );
        let bits = |v: &[DVec3]| -> Vec<u64> {
            v.iter()
                .flat_map(|p| p.to_array().map(f64::to_bits))
                .collect()
        };
        (bits(&f), bits(&m))
    }
}
