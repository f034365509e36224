//! Hose–hose and self contact (SPEC L5; dissertation §4.3.4, self contact beyond it):
//! penalty forces between the capsules of beams.
//!
//! **Narrow phase.** For two beams [a, b] (radii r_a, r_b at the nodes) and [c, d], the
//! closest points of the two centre-line segments, clamped to the segments, are
//! p₁ = (1−s) x_a + s x_b and p₂ = (1−t) x_c + t x_d (Ericson, "Real-Time Collision
//! Detection" §5.1.9; for parallel segments the middle of their common stretch). With the
//! radii interpolated there, r₁ = (1−s) r_a + s r_b and r₂ likewise, the penetration is
//! δ = r₁ + r₂ − |p₁ − p₂|. If δ > 0 the force on beam 1 is f n, n = (p₁ − p₂)/|p₁ − p₂|,
//! spread over its nodes as (1−s) f n and s f n; beam 2 gets −(1−t) f n and −t f n. The
//! pair's loads are therefore exactly equal and opposite (no moments: the force acts
//! through the centre lines, as in the thesis).
//!
//! **Stiffness and the stable time step.** Each beam has the contact stiffness
//! k_e = E_c A / (2 l₀) (half its axial stiffness in compression: a hose wall resists being
//! pressed about as the beam resists shortening). A pair uses the mean of its two beams'
//! k_e (SPEC L5), capped by the stability bound below. The contact adds to the stiffness
//! matrix k (w wᵀ) ⊗ (n nᵀ) with w = (1−s, s, −(1−t), −t), whose only frequency is
//! ω_c² = k Σ wᵢ²/mᵢ ≤ 2k/m_min (Σ wᵢ² ≤ 2, m_min the smallest of the four node masses).
//! The cap k ≤ ω_lim² m_min / 8, with ω_lim = 2/min(axial bound, eigen bound) the highest
//! frequency the time step was already built for ([`crate::rod::timestep`]), makes
//! **ω_c ≤ ω_lim / 2**. For two interior nodes of the same hose (m = ρ A l₀) the mean
//! stiffness already satisfies it: 2k/m = E_c/(ρ l₀²) = (ω_axial/2)², ω_axial = 2c/l₀;
//! the cap only acts at end nodes (half mass) and between dissimilar hoses. By Weyl's
//! inequality a node in n simultaneous contact pairs raises the highest frequency to at
//! most ω_lim √(1 + n/4); with the default safety factor 0.5 on the step (ω_lim Δt ≤ 1)
//! the step stays below the central-difference limit 2/ω (less the 5 % high-mode
//! damping reduction) for n ≤ 12 pairs on one node — two hoses crossing at nodes count 4,
//! a hose lying along another about 2 per beam. So the time step is unchanged; a test
//! checks the highest frequency of a pressed pair by power iteration.
//!
//! **Damping.** A normal dashpot, 30 % of critical for the pair (c = 2·0.3·√(k m_eff),
//! 1/m_eff = Σ wᵢ²/mᵢ), acting on the normal approach speed of the two contact points only
//! while they penetrate, keeps a hose dropped onto another from bouncing. The total
//! normal force is clamped at ≥ 0: contact pushes, never pulls. (c Δt / m_eff ≤
//! 0.6 ω_c Δt ≤ 0.3: no effect on stability.)
//!
//! **Which pairs.** All pairs of beams of different hoses, and pairs of beams of one hose
//! whose distance along the hose at rest — the rest arc length between the nearer ends,
//! g — is at least π (r_i + r_j)/2: the length of the half circle of the tightest U a
//! hose can make with its legs touching (centre-line radius (r_i + r_j)/2). Beams closer
//! along the hose (including the neighbours sharing a node, g = 0) cannot touch without
//! the wall folding into itself; their capsules overlap at rest or in any bend, and a
//! force between them would be an artefact of the discretisation. On a hose of uniform
//! radius r and beam length l₀ this excludes beams i, j with |i − j| ≤ ⌈π r / l₀⌉.
//! Pairs of different hoses are excluded only where a junction joins them and the same
//! rule holds along the network (the gap through the junction; `super::network_gaps`);
//! otherwise never — hoses that overlap at rest are pushed apart, unless the model's
//! [`HoseContactRule`] is `ApartAtRest` ([`super::rest_overlap`]).
//!
//! **Broad phase.** [`BroadPhase`]: a uniform grid, O(N), storage allocated once in
//! [`HoseContactScratch::new`] (called by [`State::at_rest`]). A model with one hose too
//! short to touch itself skips all of it. The grid is not rebuilt every step:
//! it files each beam's box grown by a skin s (the smallest beam radius) and keeps
//! the pairs of such boxes that overlap and are not excluded, with the node positions of
//! that moment (a Verlet list). While no node has moved by more than s along any axis
//! since, every beam's true box lies inside its grown one, so every pair whose true boxes
//! overlap — every pair that can touch — is in the list, and the narrow phase over the
//! list finds exactly the contacts a fresh broad phase would. The first node to move
//! farther (or any change of the positions from outside, e.g. a restored snapshot)
//! triggers a rebuild. The pairs are visited in the list's order: deterministic, given
//! the state.
//!
//! **Building the list cheaply.** The grid's 14 bucket look-ups per beam made a
//! rebuild cost about three steps' worth of element work on a long hose (perf, 1 × 1000),
//! whose free end trips the skin every ten steps or so. The pairs are instead found by
//! sort and sweep ([`SweepAndPrune`]; along the axis of the largest spread a hose's beams
//! overlap only their neighbours there) and sorted into the order, and given the
//! orientation (which beam is "beam 1" of the narrow phase), in which the grid reports
//! them: [`BroadPhase::visit_rank`], from the two beams' cells alone (no filing, no
//! counting sort). The list is the grid's list pair for pair, so the forces are bit for
//! bit those of the grid (tests compare lists after random motions and the positions after
//! contact-rich runs). If the sweep exceeds its budget of 16 N + 1024 comparisons (boxes
//! piled up along every axis), the grid builds the list as before.

use super::broad_phase::{BroadPhase, VisitRank};
use super::rest_overlap::HoseContactRule;
use super::sweep::SweepAndPrune;
use crate::{Model, State};
use glam::DVec3;
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// Damping ratio of the contact dashpot, of the pair's critical damping.
pub const CONTACT_DAMPING_RATIO: f64 = 0.3;

/// The explicit time-step safety factor the stiffness cap was made for (module doc: up
/// to 12 pairs on one node at ω_lim Δt ≤ 1). Above it fewer pairs fit: at 0.65 about 4.
/// The engine-bay demo's free hose falling onto its own loop diverged at 0.65–0.8.
pub const SAFETY_FOR_HOSE_CONTACT: f64 = 0.5;

/// Per-beam contact constants, fixed when the model is built (`model.hose_contact`).
#[derive(Clone, Debug, Default)]
pub struct HoseContactModel {
    /// Hose index of each beam.
    element_hose: Vec<u32>,
    /// Rest arc length from the hose's first node to each beam's node a and node b \[m\].
    arc_a: Vec<f64>,
    arc_b: Vec<f64>,
    /// Larger of the two node radii of each beam \[m\].
    element_radius: Vec<f64>,
    /// k_e = E_c A / (2 l₀) of each beam \[N/m\].
    element_stiffness: Vec<f64>,
    /// ω_lim, the highest frequency the time step was built for \[rad/s\].
    pub omega_limit: f64,
    /// Whether any pair of beams may touch at all (false: one short hose; a caller may
    /// also switch hose contact off for a model).
    pub active: bool,
    /// Skin of the pair list: how far a node may move along any axis before the broad
    /// phase is rebuilt \[m\] (the smallest beam radius).
    pub skin: f64,
    /// Rest length of each hose \[m\].
    hose_length: Vec<f64>,
    /// Distances along the network between ends of hoses joined by junctions.
    gaps: super::network_gaps::NetworkGaps,
    /// Which pairs may touch at all.
    pub rule: HoseContactRule,
    /// Under [`HoseContactRule::ApartAtRest`]: the pairs (i < j) overlapping at rest,
    /// sorted; they never touch ([`super::rest_overlap`]).
    overlapping_at_rest: Vec<(u32, u32)>,
    /// Most pairs the pair list may hold ([`crate::SimSettings::max_contact_pairs`]): a
    /// search that finds more stops there and says so ([`HoseContactScratch::overflow`]),
    /// and the health check declares the run diverged.
    pub max_pairs: usize,
}

/// The broad phase and what the last step found, allocated once with the state.
#[derive(Clone, Debug, Default)]
pub struct HoseContactScratch {
    pub broad: BroadPhase,
    /// Beam pairs in contact in the last step.
    pub pairs_in_contact: usize,
    /// Largest penetration in the last step \[m\] (0 when none).
    pub max_penetration: f64,
    /// Elastic energy of the contact springs, Σ ½ k δ², in the last step \[J\].
    pub energy: f64,
    /// Beam pairs (i < j not required) that may touch while no node has moved more than
    /// the skin from `anchor` (see the module doc).
    pub candidates: Vec<(u32, u32)>,
    /// Node positions when the pair list was built (NaN: never).
    pub anchor: Vec<DVec3>,
    /// How often the pair list was built.
    pub rebuilds: u64,
    /// The sweep that finds the pairs, and the pairs it found with their place in the
    /// grid's order.
    sweep: SweepAndPrune,
    ranked: Vec<(VisitRank, u32, u32)>,
    /// Build the list with the grid alone (tests: the sweep's list must equal it).
    pub grid_only: bool,
    /// How often the sweep gave up and the grid built the list.
    pub grid_fallbacks: u64,
    /// The last search found more pairs than the model allows
    /// ([`HoseContactModel::max_pairs`]): the list holds the first `max_pairs`; the count
    /// it stopped at and a beam of the pair that did not fit.
    pub overflow: Option<PairOverflow>,
}

/// A pair search that found more pairs than the model allows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairOverflow {
    /// Pairs found when the search stopped (the limit plus one).
    pub pairs: usize,
    /// The most pairs allowed.
    pub limit: usize,
    /// A beam of the first pair that did not fit.
    pub element: usize,
}

impl HoseContactScratch {
    pub fn new(model: &Model) -> Self {
        HoseContactScratch {
            broad: BroadPhase::new(model.elements.len()),
            pairs_in_contact: 0,
            max_penetration: 0.0,
            energy: 0.0,
            candidates: Vec::with_capacity(4 * model.elements.len()),
            anchor: vec![DVec3::NAN; model.node_count()],
            rebuilds: 0,
            sweep: SweepAndPrune::new(model.elements.len()),
            ranked: Vec::with_capacity(4 * model.elements.len()),
            grid_only: false,
            grid_fallbacks: 0,
            overflow: None,
        }
    }

    /// Whether a node of `x` lies farther than `skin` from where it was when the pair
    /// list was built, along any axis (or the list was never built).
    fn stale(&self, x: &[DVec3], skin: f64) -> bool {
        if self.anchor.len() != x.len() {
            return true;
        }
        // a NaN anywhere (never built, or a diverged state) fails the comparison
        let mut near = true;
        for (p, a) in x.iter().zip(&self.anchor) {
            let d = (*p - *a).abs();
            // `&`, not `&&`: no branch per axis, the loop runs in vector registers
            near &= (d.x <= skin) & (d.y <= skin) & (d.z <= skin);
        }
        !near
    }

    /// Files the beams' boxes grown by the skin and lists the pairs that may touch, in the
    /// order and orientation the grid reports them ([`BroadPhase::for_each_pair`]): found
    /// by the sweep ([`SweepAndPrune`]) and sorted by [`BroadPhase::visit_rank`], or by the
    /// grid itself if the sweep gives up (see the module doc).
    fn rebuild(&mut self, model: &Model, x: &[DVec3]) {
        self.rebuild_with(model, &model.hose_contact, x);
    }

    /// [`Self::rebuild`] with the given contact constants (while the model's own are
    /// being built).
    pub(super) fn rebuild_with(
        &mut self,
        model: &Model,
        constants: &HoseContactModel,
        x: &[DVec3],
    ) {
        for (e, el) in model.elements.iter().enumerate() {
            let (xa, xb) = (x[el.node_a], x[el.node_b]);
            let r = DVec3::splat(constants.element_radius[e] + constants.skin);
            self.broad.lo[e] = xa.min(xb) - r;
            self.broad.hi[e] = xa.max(xb) + r;
        }
        self.candidates.clear();
        let swept = !self.grid_only && {
            self.broad.set_cell_size();
            let (broad, ranked) = (&self.broad, &mut self.ranked);
            ranked.clear();
            let budget = 16 * broad.len() + 1024;
            let swept = self
                .sweep
                .for_each_pair(&broad.lo, &broad.hi, budget, |i, j| {
                    if !constants.excluded(i, j) {
                        if let Some((rank, a, b)) = broad.visit_rank(i, j) {
                            ranked.push((rank, a as u32, b as u32));
                        }
                    }
                });
            swept.is_ok()
        };
        self.overflow = None;
        let limit = constants.max_pairs;
        if swept {
            self.ranked.sort_unstable_by_key(|r| r.0);
            if let Some(&(_, a, _)) = self.ranked.get(limit) {
                self.overflow = Some(PairOverflow {
                    pairs: limit + 1,
                    limit,
                    element: a as usize,
                });
            }
            let pairs = self.ranked.iter().take(limit).map(|&(_, a, b)| (a, b));
            self.candidates.extend(pairs);
        } else {
            self.grid_fallbacks += !self.grid_only as u64;
            self.broad.rebuild();
            let (broad, candidates, overflow) =
                (&self.broad, &mut self.candidates, &mut self.overflow);
            let _ = broad.try_for_each_pair(|i, j| {
                if constants.excluded(i, j) {
                    return ControlFlow::Continue(());
                }
                if candidates.len() == limit {
                    *overflow = Some(PairOverflow {
                        pairs: limit + 1,
                        limit,
                        element: i,
                    });
                    return ControlFlow::Break(());
                }
                candidates.push((i as u32, j as u32));
                ControlFlow::Continue(())
            });
        }
        self.anchor.clear();
        self.anchor.extend_from_slice(x);
        self.rebuilds += 1;
    }
}

impl HoseContactModel {
    /// The constants of `model`'s beams (its elements, radii and time step are built),
    /// the pairs that may touch chosen by `rule`.
    pub fn new(model: &Model, rule: HoseContactRule) -> Self {
        let ne = model.elements.len();
        let mut s = HoseContactModel {
            element_hose: vec![0; ne],
            arc_a: vec![0.0; ne],
            arc_b: vec![0.0; ne],
            element_radius: vec![0.0; ne],
            element_stiffness: vec![0.0; ne],
            omega_limit: f64::INFINITY,
            active: model.hoses.len() > 1,
            skin: 0.0,
            hose_length: vec![0.0; model.hoses.len()],
            gaps: Default::default(),
            rule,
            overlapping_at_rest: Vec::new(),
            max_pairs: crate::spec::DEFAULT_MAX_CONTACT_PAIRS,
        };
        for (h, hose) in model.hoses.iter().enumerate() {
            let mut arc = 0.0;
            let mut r_min = f64::INFINITY;
            for e in hose.first_element..hose.first_element + hose.element_count {
                let el = &model.elements[e];
                s.element_hose[e] = h as u32;
                s.arc_a[e] = arc;
                arc += el.rest_length;
                s.arc_b[e] = arc;
                let (ra, rb) = (model.radius[el.node_a], model.radius[el.node_b]);
                s.element_radius[e] = ra.max(rb);
                r_min = r_min.min(ra.min(rb));
                s.element_stiffness[e] = 0.5 * el.axial_stiffness_compression / el.rest_length;
            }
            s.hose_length[h] = arc;
            // Conservative: the longest gap on this hose against the smallest threshold.
            if hose.element_count >= 2 {
                let first = hose.first_element;
                let last = first + hose.element_count - 1;
                if s.arc_a[last] - s.arc_b[first] >= PI * r_min {
                    s.active = true;
                }
            }
        }
        let r_min = s
            .element_radius
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        s.skin = if r_min.is_finite() { r_min } else { 0.0 };
        let r_max = s.element_radius.iter().copied().fold(0.0, f64::max);
        s.gaps = super::network_gaps::NetworkGaps::new(model, PI * r_max);
        let r = &model.time_step_report;
        let bound = r.axial_bound.min(r.eigen_bound);
        if bound > 0.0 && bound.is_finite() {
            s.omega_limit = 2.0 / bound;
        }
        match rule {
            HoseContactRule::All => {}
            HoseContactRule::Off => s.active = false,
            HoseContactRule::ApartAtRest if s.active => {
                s.overlapping_at_rest = super::rest_overlap::overlapping_at_rest(model, &s);
            }
            HoseContactRule::ApartAtRest => {}
        }
        s
    }

    /// How many pairs of beams overlap at rest and are left out
    /// ([`HoseContactRule::ApartAtRest`]).
    pub fn overlapping_at_rest(&self) -> usize {
        self.overlapping_at_rest.len()
    }

    /// Whether beams `i` and `j` are excluded from contact (same hose and closer along it
    /// than π (r_i + r_j)/2 at rest; see the module doc; or overlapping at rest under
    /// [`HoseContactRule::ApartAtRest`]).
    #[inline]
    pub fn excluded(&self, i: usize, j: usize) -> bool {
        if i == j {
            return true;
        }
        if !self.overlapping_at_rest.is_empty() {
            let pair = (i.min(j) as u32, i.max(j) as u32);
            if self.overlapping_at_rest.binary_search(&pair).is_ok() {
                return true;
            }
        }
        let (hi, hj) = (self.element_hose[i], self.element_hose[j]);
        if hi != hj {
            if self.gaps.is_empty() {
                return false;
            }
            let along =
                |e: usize, h: u32| (self.arc_a[e], self.hose_length[h as usize] - self.arc_b[e]);
            let limit = 0.5 * PI * (self.element_radius[i] + self.element_radius[j]);
            return self
                .gaps
                .shorter_than((hi, along(i, hi)), (hj, along(j, hj)), limit);
        }
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        let gap = self.arc_a[j] - self.arc_b[i];
        gap < 0.5 * PI * (self.element_radius[i] + self.element_radius[j])
    }

    /// Contact stiffness of the pair of beams `i`, `j` \[N/m\]: the mean of their
    /// E_c A/(2 l₀), capped at ω_lim² m_min/8 (see the module doc).
    pub fn stiffness(&self, model: &Model, i: usize, j: usize) -> f64 {
        let (ei, ej) = (&model.elements[i], &model.elements[j]);
        let m_min = model.mass[ei.node_a]
            .min(model.mass[ei.node_b])
            .min(model.mass[ej.node_a])
            .min(model.mass[ej.node_b]);
        let mean = 0.5 * (self.element_stiffness[i] + self.element_stiffness[j]);
        mean.min(self.omega_limit * self.omega_limit * m_min / 8.0)
    }
}

/// Closest points of segments [p1, q1] and [p2, q2]: parameters (s, t) in [0, 1]
/// (Ericson §5.1.9; parallel segments: the middle of their common stretch).
pub fn closest_segment_segment(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (f64, f64) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    let tiny = 1e-30;
    if a <= tiny && e <= tiny {
        return (0.0, 0.0);
    }
    if a <= tiny {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= tiny {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let s = if denom > 1e-12 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        // parallel: segment 2's ends projected on segment 1, middle of the overlap
        let (s0, s1) = (-c / a, (b - c) / a);
        let lo = s0.min(s1).max(0.0);
        let hi = s0.max(s1).min(1.0);
        if lo <= hi {
            0.5 * (lo + hi)
        } else {
            lo.min(1.0) // no overlap: the nearer end (lo > hi means both on one side)
        }
    };
    let t = (b * s + f) / e;
    if t < 0.0 {
        ((-c / a).clamp(0.0, 1.0), 0.0)
    } else if t > 1.0 {
        (((b - c) / a).clamp(0.0, 1.0), 1.0)
    } else {
        (s, t)
    }
}

/// Contact normal from segment 2 towards segment 1 when the centre lines meet (distance
/// ≈ 0): normal to both segments, pointing from 2's middle towards 1's.
fn fallback_normal(d1: DVec3, d2: DVec3, mid_gap: DVec3) -> DVec3 {
    let n = d1.cross(d2);
    let n = if n.length_squared() > 1e-24 * d1.length_squared() * d2.length_squared() {
        n.normalize()
    } else {
        d1.any_orthonormal_vector()
    };
    if n.dot(mid_gap) < 0.0 {
        -n
    } else {
        n
    }
}

/// Hose–hose and self contact forces of the configuration (`x`, `v`), written into
/// `out` (overwritten; one entry per node). No allocation.
pub fn hose_contact_forces(
    model: &Model,
    x: &[DVec3],
    v: &[DVec3],
    scratch: &mut HoseContactScratch,
    out: &mut [DVec3],
) {
    hose_contact_forces_with(model, x, v, scratch, out, |_| {});
}

/// One pair of beams in contact: the force k·pen·n acts on beam i's nodes with weights
/// w\[0\], w\[1\] and against beam j's nodes with w\[2\], w\[3\] (the Newton solvers build their
/// contact tangent k wₐ w_b n nᵀ from it).
#[derive(Clone, Copy, Debug)]
pub struct ContactPair {
    pub nodes: [usize; 4],
    pub weights: [f64; 4],
    pub normal: DVec3,
    pub stiffness: f64,
    /// Coefficient of the normal damper on the approach speed [N·s/m].
    pub damping: f64,
}

/// [`hose_contact_forces`], also reporting each pair in contact to `on_pair`.
pub fn hose_contact_forces_with(
    model: &Model,
    x: &[DVec3],
    v: &[DVec3],
    scratch: &mut HoseContactScratch,
    out: &mut [DVec3],
    mut on_pair: impl FnMut(ContactPair),
) {
    out.fill(DVec3::ZERO);
    scratch.pairs_in_contact = 0;
    scratch.max_penetration = 0.0;
    scratch.energy = 0.0;
    let constants = &model.hose_contact;
    if !constants.active {
        return;
    }
    if scratch.stale(x, constants.skin) {
        scratch.rebuild(model, x);
    }
    let mut pairs = 0;
    let mut max_pen: f64 = 0.0;
    let mut energy = 0.0;
    for &(i, j) in &scratch.candidates {
        let (i, j) = (i as usize, j as usize);
        let (ei, ej) = (&model.elements[i], &model.elements[j]);
        let (a, b, c, d) = (ei.node_a, ei.node_b, ej.node_a, ej.node_b);
        let (s, t) = closest_segment_segment(x[a], x[b], x[c], x[d]);
        let p1 = x[a].lerp(x[b], s);
        let p2 = x[c].lerp(x[d], t);
        let r1 = model.radius[a] + s * (model.radius[b] - model.radius[a]);
        let r2 = model.radius[c] + t * (model.radius[d] - model.radius[c]);
        let gap = p1 - p2;
        let dist = gap.length();
        let pen = r1 + r2 - dist;
        if pen <= 0.0 {
            continue;
        }
        let n = if dist > 1e-9 * (r1 + r2) {
            gap / dist
        } else {
            let mid = 0.5 * (x[a] + x[b]) - 0.5 * (x[c] + x[d]);
            fallback_normal(x[b] - x[a], x[d] - x[c], mid)
        };
        let w = [1.0 - s, s, 1.0 - t, t];
        let inv_m_eff = w[0] * w[0] / model.mass[a]
            + w[1] * w[1] / model.mass[b]
            + w[2] * w[2] / model.mass[c]
            + w[3] * w[3] / model.mass[d];
        let k = constants.stiffness(model, i, j);
        let damping = 2.0 * CONTACT_DAMPING_RATIO * (k / inv_m_eff).sqrt();
        let v_rel = v[a].lerp(v[b], s) - v[c].lerp(v[d], t);
        let f = (k * pen - damping * v_rel.dot(n)).max(0.0);
        let fv = f * n;
        out[a] += w[0] * fv;
        out[b] += w[1] * fv;
        out[c] -= w[2] * fv;
        out[d] -= w[3] * fv;
        if f > 0.0 {
            on_pair(ContactPair {
                nodes: [a, b, c, d],
                weights: w,
                normal: n,
                stiffness: k,
                damping,
            });
        }
        pairs += 1;
        max_pen = max_pen.max(pen);
        energy += 0.5 * k * pen * pen;
    }
    scratch.pairs_in_contact = pairs;
    scratch.max_penetration = max_pen;
    scratch.energy = energy;
}

/// Computes the hose–hose and self contact forces of the state's configuration into
/// `state.hose_contact_force` and adds them to `state.force`. Called by
/// [`crate::integrators::explicit::step`] after the body loads. No allocation.
pub fn add_hose_contact_forces(model: &Model, state: &mut State) {
    if !model.hose_contact.active {
        return;
    }
    hose_contact_forces(
        model,
        &state.x,
        &state.v,
        &mut state.hose_contact,
        &mut state.hose_contact_force,
    );
    if state.hose_contact.pairs_in_contact == 0 {
        return; // no pair in contact: the forces are the zeros filled in
    }
    for (f, c) in state.force.iter_mut().zip(&state.hose_contact_force) {
        *f += *c;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        let n = 400;
        for i in 0..=n {
            let a = p1.lerp(q1, i as f64 / n as f64);
            for j in 0..=n {
                let b = p2.lerp(q2, j as f64 / n as f64);
                best = best.min((a - b).length());
            }
        }
        best
    }

    #[test]
    fn closest_points_match_sampling() {
        let cases = [
            // crossing
            (
                DVec3::new(-1.0, 0.0, 0.0),
                DVec3::X,
                DVec3::new(0.2, -1.0, 0.5),
                DVec3::new(0.2, 1.0, 0.5),
            ),
            // clamped at ends
            (
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(2.0, 1.0, 0.0),
                DVec3::new(3.0, 2.0, 0.3),
            ),
            // parallel, overlapping
            (
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(0.5, 0.3, 0.0),
                DVec3::new(1.5, 0.3, 0.0),
            ),
            // parallel, reversed, disjoint
            (
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(3.0, 0.3, 0.0),
                DVec3::new(2.0, 0.3, 0.0),
            ),
            // skew
            (
                DVec3::new(0.1, 0.2, 0.3),
                DVec3::new(0.9, -0.4, 0.2),
                DVec3::new(-0.3, 0.5, 0.9),
                DVec3::new(0.4, 0.1, -0.6),
            ),
        ];
        for (p1, q1, p2, q2) in cases {
            let (s, t) = closest_segment_segment(p1, q1, p2, q2);
            assert!((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
            let d = (p1.lerp(q1, s) - p2.lerp(q2, t)).length();
            let b = brute(p1, q1, p2, q2);
            assert!(d <= b + 1e-9, "{d} vs sampled {b}");
            assert!(d >= b - 5e-3, "{d} vs sampled {b}");
        }
        // parallel overlap picks the middle of the common stretch [0.5, 1]
        let (s, _) = closest_segment_segment(
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.5, 0.3, 0.0),
            DVec3::new(1.5, 0.3, 0.0),
        );
        assert!((s - 0.75).abs() < 1e-12);
    }
}
